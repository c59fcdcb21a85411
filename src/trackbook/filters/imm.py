"""The interacting multiple model (IMM) estimator of Blom and Bar-Shalom (1988).

A target that flies straight and then turns is not described by one motion model: a
constant-velocity filter tuned for the straight part (small Q) lags in the turn, one tuned
for the turn (large Q) is noisy on the straight. The IMM runs r Kalman filters, one per mode
(motion model), side by side, and keeps the probability μⱼ that mode j is in force. The modes
switch as a Markov chain with transition matrix M, M[i, j] = P(mode j at k | mode i at k − 1).
One cycle, for a measurement z:

1. **mixing probabilities** (:func:`mixing_probabilities`): c̄ⱼ = Σᵢ M[i, j] μᵢ, the predicted
   probability of mode j, and ω[i, j] = M[i, j] μᵢ / c̄ⱼ, the probability that the target was
   in mode i given that it is now in mode j;
2. **mixing** (:func:`mix_estimates`): each filter j restarts from
   x̂⁰ⱼ = Σᵢ ω[i, j] x̂ᵢ, P⁰ⱼ = Σᵢ ω[i, j] (Pᵢ + (x̂ᵢ − x̂⁰ⱼ)(x̂ᵢ − x̂⁰ⱼ)ᵀ);
3. **per-model filtering**: each filter predicts and updates with z as the book's Kalman filter
   does, and reports the likelihood Λⱼ = N(yⱼ; 0, Sⱼ) of its residual
   (:func:`gaussian_likelihood`);
4. **mode probability update** (:func:`mode_probability_update`): μⱼ = c̄ⱼ Λⱼ / Σₗ c̄ₗ Λₗ;
5. **combination** (:func:`combine_estimates`): x̂ = Σⱼ μⱼ x̂ⱼ,
   P = Σⱼ μⱼ (Pⱼ + (x̂ⱼ − x̂)(x̂ⱼ − x̂)ᵀ) — the output; the filters keep their own x̂ⱼ, Pⱼ.

:class:`InteractingMultipleModel` holds the cycle with filterpy's ``IMMEstimator`` interface
(``predict()``, ``update(z)``, ``x``, ``P``, ``mu``, ``M``, ``omega``, ``cbar``,
``likelihood``). :func:`simulate_turning_target` and :func:`imm_versus_constant_velocity`
show the point of it: a target that goes straight, turns sharply and goes straight again.

>>> import numpy as np
>>> cbar, omega = mixing_probabilities([0.5, 0.5], [[0.9, 0.1], [0.2, 0.8]])
>>> cbar.tolist(), omega[:, 0].round(4).tolist()
([0.55, 0.45], [0.8182, 0.1818])
"""

from __future__ import annotations

import sys
from dataclasses import dataclass

import numpy as np

from .kalman import KalmanFilter
from .linear_gaussian import constant_velocity_model

__all__ = ["ImmRun", "InteractingMultipleModel", "combine_estimates", "gaussian_likelihood",
           "imm_versus_constant_velocity", "mix_estimates", "mixing_probabilities",
           "mode_probability_update", "run_imm", "simulate_turning_target"]


def _check_probabilities(mu, M):
    mu = np.asarray(mu, dtype=float).ravel()
    M = np.asarray(M, dtype=float)
    r = mu.size
    if M.shape != (r, r):
        raise ValueError(f"the transition matrix M must be ({r}, {r}) for {r} modes, "
                         f"got {M.shape}.")
    if np.any(mu < 0) or not mu.sum() > 0:
        raise ValueError(f"mode probabilities mu must be non-negative with a positive sum, got "
                         f"{mu.tolist()}.")
    if np.any(M < 0) or not np.allclose(M.sum(axis=1), 1.0):
        raise ValueError("each row i of the transition matrix M must hold the probabilities "
                         "P(mode j | mode i) and sum to 1; got row sums "
                         f"{M.sum(axis=1).round(6).tolist()}.")
    return mu, M


def mixing_probabilities(mu, M):
    """The predicted mode probabilities c̄ and the mixing probabilities ω.

    c̄ⱼ = Σᵢ M[i, j] μᵢ  and  ω[i, j] = M[i, j] μᵢ / c̄ⱼ.

    Parameters
    ----------
    mu : (r,) array_like
        Mode probabilities μ after the last update.
    M : (r, r) array_like
        Mode transition matrix, M[i, j] = P(mode j now | mode i before); rows sum to 1.

    Returns
    -------
    cbar : (r,) ndarray
    omega : (r, r) ndarray
        Each column j sums to 1: where the target in mode j came from.
    """
    mu, M = _check_probabilities(mu, M)
    cbar = mu @ M
    omega = M * mu[:, None] / cbar[None, :]
    return cbar, omega


def mix_estimates(xs, Ps, omega):
    """The mixed initial conditions x̂⁰ⱼ, P⁰ⱼ of every filter j.

    x̂⁰ⱼ = Σᵢ ω[i, j] x̂ᵢ,  P⁰ⱼ = Σᵢ ω[i, j] (Pᵢ + (x̂ᵢ − x̂⁰ⱼ)(x̂ᵢ − x̂⁰ⱼ)ᵀ).

    Parameters
    ----------
    xs : (r, n) array_like
        Each filter's posterior mean.
    Ps : (r, n, n) array_like
        Each filter's posterior covariance.
    omega : (r, r) array_like
        Mixing probabilities from :func:`mixing_probabilities`.

    Returns
    -------
    x0 : (r, n) ndarray
    P0 : (r, n, n) ndarray
    """
    xs, Ps, omega = (np.asarray(a, dtype=float) for a in (xs, Ps, omega))
    x0 = omega.T @ xs
    d = xs[None, :, :] - x0[:, None, :]               # d[j, i] = x̂ᵢ − x̂⁰ⱼ
    P0 = np.einsum("ij,ikl->jkl", omega, Ps) + np.einsum("ij,jik,jil->jkl", omega, d, d)
    return x0, P0


def gaussian_likelihood(y, S) -> float:
    """The likelihood Λ = N(y; 0, S) of a residual y with covariance S.

    Λ = exp(−yᵀS⁻¹y / 2) / √det(2πS). Like filterpy's ``KalmanFilter.likelihood``, a value that
    underflows to 0 is replaced by the smallest positive float, so that one far-off
    measurement cannot zero every mode probability at once.

    Parameters
    ----------
    y : (m,) array_like
    S : (m, m) array_like

    Returns
    -------
    float
    """
    y = np.atleast_1d(np.asarray(y, dtype=float))
    S = np.atleast_2d(np.asarray(S, dtype=float))
    _, logdet = np.linalg.slogdet(2 * np.pi * S)
    value = float(np.exp(-0.5 * (y @ np.linalg.solve(S, y)) - 0.5 * logdet))
    return value if value > 0 else sys.float_info.min


def mode_probability_update(cbar, likelihood) -> np.ndarray:
    """The posterior mode probabilities μⱼ = c̄ⱼ Λⱼ / Σₗ c̄ₗ Λₗ.

    Parameters
    ----------
    cbar : (r,) array_like
        Predicted mode probabilities.
    likelihood : (r,) array_like
        Each filter's likelihood Λⱼ of the measurement.

    Returns
    -------
    mu : (r,) ndarray
    """
    mu = np.asarray(cbar, dtype=float) * np.asarray(likelihood, dtype=float)
    return mu / mu.sum()


def combine_estimates(xs, Ps, mu):
    """The IMM's output: the mixture's mean and covariance.

    x̂ = Σⱼ μⱼ x̂ⱼ,  P = Σⱼ μⱼ (Pⱼ + (x̂ⱼ − x̂)(x̂ⱼ − x̂)ᵀ).

    Parameters
    ----------
    xs : (r, n) array_like
    Ps : (r, n, n) array_like
    mu : (r,) array_like

    Returns
    -------
    x : (n,) ndarray
    P : (n, n) ndarray
    """
    xs, Ps, mu = (np.asarray(a, dtype=float) for a in (xs, Ps, mu))
    x = mu @ xs
    d = xs - x
    return x, np.einsum("j,jkl->kl", mu, Ps) + np.einsum("j,jk,jl->kl", mu, d, d)


class InteractingMultipleModel:
    """The IMM estimator over the book's Kalman filters (filterpy's ``IMMEstimator`` interface).

    Parameters
    ----------
    filters : sequence of trackbook.filters.kalman.KalmanFilter
        One per mode, at least two, all with the same state size; set up with their x, P,
        F, H, Q, R. They are used (and changed) in place.
    mu : (r,) array_like
        Initial mode probabilities (normalised here).
    M : (r, r) array_like
        Mode transition matrix, M[i, j] = P(mode j at k | mode i at k − 1).

    Attributes
    ----------
    x, P : the combined estimate (after ``predict``: the prior; after ``update``: the posterior)
    mu : mode probabilities; cbar, omega : see :func:`mixing_probabilities`
    likelihood : each filter's likelihood of the last measurement
    """

    def __init__(self, filters, mu, M):
        filters = list(filters)
        if len(filters) < 2 or not all(isinstance(f, KalmanFilter) for f in filters):
            raise TypeError("InteractingMultipleModel needs two or more "
                            "trackbook.filters.kalman.KalmanFilter objects, one per mode.")
        if len({f.x.shape for f in filters}) != 1:
            raise ValueError("every filter of the IMM must have the same state size, so their "
                             "estimates can be mixed.")
        mu, M = _check_probabilities(mu, M)
        if mu.size != len(filters):
            raise ValueError(f"mu has {mu.size} entries for {len(filters)} filters.")
        self.filters, self.M = filters, M
        self.mu = mu / mu.sum()
        self.likelihood = np.zeros(len(filters))
        self.cbar, self.omega = mixing_probabilities(self.mu, self.M)
        self.x, self.P = combine_estimates(*self._stack(), self.mu)

    def _stack(self):
        return (np.array([f.x for f in self.filters]), np.array([f.P for f in self.filters]))

    def predict(self) -> None:
        """Mix the filters' estimates (:func:`mix_estimates`), then predict each filter."""
        x0, P0 = mix_estimates(*self._stack(), self.omega)
        for f, x, P in zip(self.filters, x0, P0):
            f.x, f.P = x.copy(), P.copy()
            f.predict()
        self.x, self.P = combine_estimates(*self._stack(), self.mu)

    def update(self, z) -> None:
        """Update each filter with z, then the mode probabilities, then the combination."""
        for j, f in enumerate(self.filters):
            f.update(z)
            self.likelihood[j] = gaussian_likelihood(f.y, f.S)
        self.mu = mode_probability_update(self.cbar, self.likelihood)
        self.cbar, self.omega = mixing_probabilities(self.mu, self.M)
        self.x, self.P = combine_estimates(*self._stack(), self.mu)


@dataclass
class ImmRun:
    """The IMM's posterior after each measurement.

    Attributes
    ----------
    x : (n, dim_x) ndarray
    P : (n, dim_x, dim_x) ndarray
    mu : (n, r) ndarray
        Mode probabilities.
    """

    x: np.ndarray
    P: np.ndarray
    mu: np.ndarray


def run_imm(imm: InteractingMultipleModel, zs) -> ImmRun:
    """``imm.predict(); imm.update(z)`` for each measurement z, recording x, P and μ.

    Parameters
    ----------
    imm : InteractingMultipleModel
    zs : (n, dim_z) array_like

    Returns
    -------
    ImmRun
    """
    xs, Ps, mus = [], [], []
    for z in np.asarray(zs, dtype=float):
        imm.predict()
        imm.update(z)
        xs.append(imm.x.copy()); Ps.append(imm.P.copy()); mus.append(imm.mu.copy())
    return ImmRun(np.array(xs), np.array(Ps), np.array(mus))


# --------------------------------------------------------------------------- demonstration

def simulate_turning_target(rng: np.random.Generator, n_straight: int = 40, n_turn: int = 10,
                            n_after: int = 30, speed: float = 5.0, turn_rate: float = 0.3,
                            sigma_z: float = 2.0):
    """A target that goes straight, turns sharply, and goes straight again; noisy positions.

    The velocity keeps its length ``speed`` and turns by ``turn_rate`` radians per step during
    the ``n_turn`` middle steps (0.3 rad for 10 steps: a near U-turn, an acceleration of
    speed · turn_rate per step); the position advances by the velocity. Measurements are the
    positions plus N(0, sigma_z² I).

    Parameters
    ----------
    rng : numpy.random.Generator
        The measurement noise's only source.
    n_straight, n_turn, n_after : int
        Steps before, during and after the turn.
    speed : float
        Length of the velocity, per step.
    turn_rate : float
        Radians the velocity turns per step during the turn.
    sigma_z : float
        Standard deviation of the measurement noise on each coordinate.

    Returns
    -------
    truth : (n, 4) ndarray
        [p_x, p_y, v_x, v_y] per step, n = n_straight + n_turn + n_after.
    zs : (n, 2) ndarray
    """
    if not isinstance(rng, np.random.Generator):
        raise TypeError("simulate_turning_target needs a numpy.random.Generator.")
    rates = np.r_[np.zeros(int(n_straight)), np.full(int(n_turn), turn_rate),
                  np.zeros(int(n_after))]
    heading = np.cumsum(rates)                           # velocity direction after each step
    v = speed * np.stack([np.cos(heading), np.sin(heading)], axis=1)
    v_before = np.vstack([[speed, 0.0], v[:-1]])         # the position moves by the old velocity
    p = np.cumsum(v_before, axis=0)
    truth = np.hstack([p, v])
    zs = p + sigma_z * rng.standard_normal(p.shape)
    return truth, zs


def _cv_filter(q: float, sigma_z: float, x0) -> KalmanFilter:
    kf = KalmanFilter(4, 2)
    kf.F, kf.Q, kf.H = constant_velocity_model(q)
    kf.R = sigma_z ** 2 * np.eye(2)
    kf.x = np.asarray(x0, dtype=float).copy()
    kf.P = np.diag([sigma_z ** 2, sigma_z ** 2, 4.0, 4.0])
    return kf


def imm_versus_constant_velocity(truth, zs, sigma_z: float = 2.0, q_straight: float = 0.01,
                                 q_turn: float = 2.0, M=((0.95, 0.05), (0.10, 0.90))):
    """A single constant-velocity filter against a two-mode IMM on the same measurements.

    The single filter is tuned for the straight part (q = ``q_straight``). The IMM holds that
    filter and a second constant-velocity filter with q = ``q_turn`` (about the squared
    acceleration of the turn), mixed by the transition matrix ``M``. Both start from the true
    state one step before the first measurement (the track must begin straight), the IMM with
    μ = (0.9, 0.1).

    Parameters
    ----------
    truth : (n, 4) array_like
        The true states, from :func:`simulate_turning_target`.
    zs : (n, 2) array_like
        The measured positions.
    sigma_z : float
        Standard deviation of the measurement noise (R = sigma_z² I).
    q_straight, q_turn : float
        Acceleration variances of the quiet and the manoeuvring constant-velocity models.
    M : (2, 2) array_like
        Mode transition matrix, M[i, j] = P(mode j | mode i).

    Returns
    -------
    dict
        ``{"cv": (n, 4) estimates, "imm": ImmRun, "rmse_cv": float, "rmse_imm": float}``;
        the RMSEs are of the position over all steps.
    """
    truth = np.asarray(truth, dtype=float)
    x0 = truth[0] - np.r_[truth[0, 2:], 0.0, 0.0]        # one step before the first state
    cv = _cv_filter(q_straight, sigma_z, x0)
    xs = []
    for z in np.asarray(zs, dtype=float):
        cv.predict(); cv.update(z)
        xs.append(cv.x.copy())
    xs = np.array(xs)
    imm = InteractingMultipleModel([_cv_filter(q_straight, sigma_z, x0),
                                    _cv_filter(q_turn, sigma_z, x0)], [0.9, 0.1], np.array(M))
    run = run_imm(imm, zs)

    def rmse(est):
        return float(np.sqrt(np.mean(np.sum((est[:, :2] - truth[:, :2]) ** 2, axis=1))))

    return {"cv": xs, "imm": run, "rmse_cv": rmse(xs), "rmse_imm": rmse(run.x)}
