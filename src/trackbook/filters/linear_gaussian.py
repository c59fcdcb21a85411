"""The linear-Gaussian state-space model: simulate it, and run the Kalman filter over it.

    x_k = F x_{k-1} + w_k,   w_k ~ N(0, Q)
    z_k = H x_k + v_k,       v_k ~ N(0, R)

:func:`simulate_linear_gaussian` draws a true track and its measurements;
:func:`run_kalman_filter` runs the Kalman filter of :mod:`trackbook.filters.kalman` over the
measurements and keeps what the design tools need: the priors and posteriors (for the
smoother of :mod:`trackbook.filters.smoother`), and the residuals y and their covariances S
(for the consistency tests of :mod:`trackbook.filters.consistency`).
:func:`constant_velocity_model` gives F, Q, H for a target moving at constant velocity in the
plane under white-noise acceleration.

>>> import numpy as np
>>> F, Q, H = constant_velocity_model(q=0.1)
>>> truth, zs = simulate_linear_gaussian(np.random.default_rng(0), F, Q, H, np.eye(2),
...                                      x0=[0.0, 0.0, 1.0, 0.5], n_steps=3)
>>> truth.shape, zs.shape
((3, 4), (3, 2))
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .kalman import KalmanFilter

__all__ = ["KalmanRun", "constant_velocity_model", "run_kalman_filter",
           "simulate_linear_gaussian", "sqrt_psd"]


def constant_velocity_model(q: float, dt: float = 1.0):
    """F, Q and H of the constant-velocity model with white-noise acceleration, in 2-D.

    Parameters
    ----------
    q : float
        Variance of the acceleration, held constant over one step.
    dt : float
        The time step.

    Returns
    -------
    F : (4, 4) ndarray
        Transition of x = [p_x, p_y, v_x, v_y]: p ← p + dt v.
    Q : (4, 4) ndarray
        Q = q G Gᵀ with G = [dt²/2 I₂; dt I₂] (the acceleration moves position and velocity).
    H : (2, 4) ndarray
        Picks the position.
    """
    F = np.eye(4)
    F[0, 2] = F[1, 3] = dt
    G = np.vstack([0.5 * dt ** 2 * np.eye(2), dt * np.eye(2)])
    return F, q * G @ G.T, np.eye(2, 4)


def sqrt_psd(A) -> np.ndarray:
    """L with L Lᵀ = A for a symmetric positive semi-definite A.

    By eigen-decomposition rather than Cholesky because the Q of a white-acceleration model is
    singular (rank 2 in a 4-D state).
    """
    lam, V = np.linalg.eigh(np.asarray(A, dtype=float))
    return V * np.sqrt(np.clip(lam, 0.0, None))


def simulate_linear_gaussian(rng: np.random.Generator, F, Q, H, R, x0, n_steps: int):
    """A true track x_1 … x_n and its measurements z_1 … z_n.

    Parameters
    ----------
    rng : numpy.random.Generator
        The only source of randomness: same generator state, same track and measurements.
    F, Q, H, R : array_like
        The model: x_k = F x_{k-1} + w_k, w_k ~ N(0, Q); z_k = H x_k + v_k, v_k ~ N(0, R).
    x0 : array_like
        The state x_0 before the first step (known exactly).
    n_steps : int
        Number of steps, at least 1.

    Returns
    -------
    truth : (n_steps, dim_x) ndarray
    zs : (n_steps, dim_z) ndarray
    """
    if not isinstance(rng, np.random.Generator):
        raise TypeError("simulate_linear_gaussian needs a numpy.random.Generator, "
                        "e.g. np.random.default_rng(0).")
    n_steps = int(n_steps)
    if n_steps < 1:
        raise ValueError(f"n_steps must be at least 1, got {n_steps}.")
    F, H = np.asarray(F, dtype=float), np.asarray(H, dtype=float)
    Lq, Lr = sqrt_psd(Q), sqrt_psd(R)
    x = np.asarray(x0, dtype=float)
    truth = np.empty((n_steps, x.size))
    for k in range(n_steps):           # each state depends on the last one: a loop over time
        x = F @ x + Lq @ rng.standard_normal(x.size)
        truth[k] = x
    zs = truth @ H.T + rng.standard_normal((n_steps, H.shape[0])) @ Lr.T
    return truth, zs


@dataclass
class KalmanRun:
    """Everything one pass of the Kalman filter produced, one row per measurement.

    Attributes
    ----------
    x_prior, P_prior : (n, dim_x), (n, dim_x, dim_x)
        x̂_k⁻ and P_k⁻ after ``predict``.
    x, P : (n, dim_x), (n, dim_x, dim_x)
        x̂_k⁺ and P_k⁺ after ``update``.
    y, S : (n, dim_z), (n, dim_z, dim_z)
        The residual y_k = z_k − H x̂_k⁻ and its covariance S_k = H P_k⁻ Hᵀ + R.
    """

    x_prior: np.ndarray
    P_prior: np.ndarray
    x: np.ndarray
    P: np.ndarray
    y: np.ndarray
    S: np.ndarray


def run_kalman_filter(kf: KalmanFilter, zs) -> KalmanRun:
    """Run ``kf.predict(); kf.update(z)`` for each z and record every step.

    Parameters
    ----------
    kf : trackbook.filters.kalman.KalmanFilter
        Set up with x, P (the belief before the first step) and F, H, Q, R; it is advanced
        in place.
    zs : (n, dim_z) array_like
        The measurements.

    Returns
    -------
    KalmanRun
    """
    if not isinstance(kf, KalmanFilter):
        raise TypeError("run_kalman_filter needs a trackbook.filters.kalman.KalmanFilter, e.g. "
                        "trackbook.filters.kalman.constant_velocity().")
    zs = np.asarray(zs, dtype=float).reshape(-1, kf.dim_z)
    out = {k: [] for k in ("x_prior", "P_prior", "x", "P", "y", "S")}
    for z in zs:
        kf.predict()
        out["x_prior"].append(kf.x.copy()); out["P_prior"].append(kf.P.copy())
        kf.update(z)
        out["x"].append(kf.x.copy()); out["P"].append(kf.P.copy())
        out["y"].append(kf.y.copy()); out["S"].append(kf.S.copy())
    return KalmanRun(**{k: np.array(v) for k, v in out.items()})
