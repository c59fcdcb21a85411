"""Importance weights of a particle set drawn from a proposal q (sequential importance sampling).

A particle filter moves each particle xⁱ_{k-1} to a new xⁱ_k drawn from a *proposal*
q(x_k | x_{k-1}, z_k) and corrects for having drawn from q instead of the posterior by the
importance weight (Arulampalam et al. 2002):

    wⁱ_k ∝ wⁱ_{k-1} · p(z_k | xⁱ_k) p(xⁱ_k | xⁱ_{k-1}) / q(xⁱ_k | xⁱ_{k-1}, z_k)

(:func:`importance_weights`). Two proposals matter:

* the **transition** q = p(x_k | x_{k-1}) (the bootstrap filter of Gordon et al. 1993, the
  Condensation of ``02_particle_filters``): transition and proposal cancel, w ∝ w_{k-1} p(z|x)
  (:func:`bootstrap_weights`); it ignores z when it moves the particles;
* the **optimal** q = p(x_k | x_{k-1}, z_k), which minimises the variance of the weights given
  x_{k-1}: then w ∝ w_{k-1} p(z_k | x_{k-1}), independent of where xⁱ_k landed. For a linear-
  Gaussian model it is Gaussian (:func:`optimal_gaussian_proposal`).

Densities are passed as log-densities so that weights of far-off particles do not underflow
before they are normalised.

>>> import numpy as np
>>> bootstrap_weights(np.log([1.0, 3.0])).tolist()
[0.25, 0.75]
"""

from __future__ import annotations

import numpy as np

__all__ = ["bootstrap_weights", "gaussian_log_density", "importance_weights",
           "normalize_log_weights", "optimal_gaussian_proposal"]


def normalize_log_weights(log_w) -> np.ndarray:
    """Weights exp(log wⁱ) / Σⱼ exp(log wʲ), computed without overflow or underflow.

    Parameters
    ----------
    log_w : (N,) array_like
        Unnormalised log-weights; −inf for a particle of zero weight.

    Returns
    -------
    (N,) ndarray
        Non-negative, summing to 1.
    """
    log_w = np.asarray(log_w, dtype=float).ravel()
    if log_w.size == 0 or np.any(np.isnan(log_w)) or np.any(log_w == np.inf):
        raise ValueError("log-weights must be a non-empty array without NaN or +inf; check the "
                         "densities passed in.")
    top = log_w.max()
    if top == -np.inf:
        raise ValueError("every particle has zero weight (all log-weights are -inf): the "
                         "measurement is impossible under every particle; widen R or Q.")
    w = np.exp(log_w - top)            # the largest becomes 1: no overflow, no all-zero sum
    return w / w.sum()


def importance_weights(log_likelihood, log_transition, log_proposal, weights_prev=None):
    """Normalised importance weights w ∝ w_prev · p(z|x) p(x|x_prev) / q(x|x_prev, z).

    Parameters
    ----------
    log_likelihood : (N,) array_like
        log p(z_k | xⁱ_k) for each particle.
    log_transition : (N,) array_like
        log p(xⁱ_k | xⁱ_{k-1}).
    log_proposal : (N,) array_like
        log q(xⁱ_k | xⁱ_{k-1}, z_k), the density the particles were drawn from.
    weights_prev : (N,) array_like, optional
        The weights wⁱ_{k-1} before the move (uniform, e.g. after resampling, if omitted).

    Returns
    -------
    (N,) ndarray
        The weights wⁱ_k, summing to 1.
    """
    parts = [np.asarray(a, dtype=float).ravel()
             for a in (log_likelihood, log_transition, log_proposal)]
    if len({p.size for p in parts}) != 1:
        raise ValueError("log_likelihood, log_transition and log_proposal need one value per "
                         f"particle each; got sizes {[p.size for p in parts]}.")
    log_w = parts[0] + parts[1] - parts[2]
    return normalize_log_weights(log_w + _log_prev(weights_prev, log_w.size))


def bootstrap_weights(log_likelihood, weights_prev=None):
    """The weights when the proposal is the transition: w ∝ w_prev · p(z | x).

    Parameters
    ----------
    log_likelihood : (N,) array_like
        log p(z_k | xⁱ_k) for each particle (drawn from p(x_k | xⁱ_{k-1})).
    weights_prev : (N,) array_like, optional
        The weights before the move (uniform if omitted).

    Returns
    -------
    (N,) ndarray
        The normalised likelihoods (times the previous weights), summing to 1.
    """
    log_l = np.asarray(log_likelihood, dtype=float).ravel()
    return normalize_log_weights(log_l + _log_prev(weights_prev, log_l.size))


def _log_prev(weights_prev, n: int):
    if weights_prev is None:
        return 0.0
    w = np.asarray(weights_prev, dtype=float).ravel()
    if w.size != n or np.any(w < 0) or not np.all(np.isfinite(w)):
        raise ValueError(f"weights_prev must hold {n} finite non-negative weights, one per "
                         "particle.")
    with np.errstate(divide="ignore"):  # a zero weight stays zero: log 0 = −inf
        return np.log(w)


def gaussian_log_density(x, mean, cov) -> np.ndarray:
    """log N(x; mean, cov) for each row of a particle set.

    Parameters
    ----------
    x : (N, n) or (N,) array_like
        Points (a 1-D array is N scalar points).
    mean : (N, n), (n,) or scalar array_like
        One mean per point, or one for all.
    cov : (n, n) array_like or float
        The covariance, positive definite.

    Returns
    -------
    (N,) ndarray
    """
    x = np.asarray(x, dtype=float)
    x = x[:, None] if x.ndim == 1 else x
    n = x.shape[1]
    d = x - np.broadcast_to(np.asarray(mean, dtype=float).reshape(-1, n), x.shape)
    cov = np.asarray(cov, dtype=float).reshape(n, n)
    L = np.linalg.cholesky(cov)
    u = np.linalg.solve(L, d.T)                     # L u = d: uᵀu = dᵀ cov⁻¹ d
    return -0.5 * np.sum(u * u, axis=0) - np.log(np.diag(L)).sum() - 0.5 * n * np.log(2 * np.pi)


def optimal_gaussian_proposal(x_prev, z, F, Q, H, R):
    """The optimal proposal p(x_k | x_{k-1}, z_k) of a linear-Gaussian model.

    For x_k = F x_{k-1} + w, w ~ N(0, Q) and z_k = H x_k + v, v ~ N(0, R), it is the Kalman
    update of the point prediction F x_{k-1} with prior covariance Q:

        S = H Q Hᵀ + R,   K = Q Hᵀ S⁻¹,   mean = F x_{k-1} + K (z − H F x_{k-1}),
        cov = (I − K H) Q,

    and the weight it leaves, p(z_k | x_{k-1}) = N(z; H F x_{k-1}, S).

    Parameters
    ----------
    x_prev : (N, n) array_like
        The particles at k − 1.
    z : (m,) array_like
        The measurement.
    F, Q, H, R : array_like
        The model matrices.

    Returns
    -------
    mean : (N, n) ndarray
        Each particle's proposal mean.
    cov : (n, n) ndarray
        The proposal covariance, the same for every particle.
    S : (m, m) ndarray
        Covariance of z given x_{k-1}, for the weights.
    """
    F, Q, H, R = (np.atleast_2d(np.asarray(a, dtype=float)) for a in (F, Q, H, R))
    x_prev = np.asarray(x_prev, dtype=float).reshape(-1, F.shape[1])
    z = np.atleast_1d(np.asarray(z, dtype=float))
    S = H @ Q @ H.T + R
    K = np.linalg.solve(S, H @ Q).T                 # Q Hᵀ S⁻¹ (Q and S symmetric)
    pred = x_prev @ F.T
    mean = pred + (z - pred @ H.T) @ K.T
    cov = (np.eye(F.shape[0]) - K @ H) @ Q
    return mean, cov, S
