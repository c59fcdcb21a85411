"""The Rauch–Tung–Striebel (RTS) smoother over the Kalman filter's outputs.

The Kalman filter's x̂ₖ uses the measurements up to step k; once the whole sequence is in,
each estimate can also use the ones after it. The RTS smoother (Rauch, Tung and Striebel 1965)
runs backwards over the filter's posteriors x̂ₖ, Pₖ, from the last step (where filter and
smoother agree) to the first:

    Pₖ₊₁⁻ = Fₖ₊₁ Pₖ Fₖ₊₁ᵀ + Qₖ₊₁              (the filter's prediction, recomputed)
    Kₖ    = Pₖ Fₖ₊₁ᵀ (Pₖ₊₁⁻)⁻¹                 (the smoother gain)
    x̂ₖˢ   = x̂ₖ + Kₖ (x̂ₖ₊₁ˢ − Fₖ₊₁ x̂ₖ)
    Pₖˢ   = Pₖ + Kₖ (Pₖ₊₁ˢ − Pₖ₊₁⁻) Kₖᵀ

Symbols as in filterpy's ``KalmanFilter.rts_smoother`` (Labbe's book), where Fₖ₊₁ and Qₖ₊₁
are the transition and process noise that took step k to step k + 1.

>>> import numpy as np
>>> from trackbook.filters.kalman import constant_velocity
>>> from trackbook.filters.linear_gaussian import run_kalman_filter
>>> kf = constant_velocity()
>>> run = run_kalman_filter(kf, [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
>>> xs, Ps, K, P_prior = rts_smoother(run.x, run.P, kf.F, kf.Q)
>>> bool(np.allclose(xs[-1], run.x[-1]))
True
"""

from __future__ import annotations

import numpy as np

__all__ = ["rts_smoother"]


def _per_step(A, n: int, dim_x: int, name: str) -> np.ndarray:
    """A constant (dim_x, dim_x) matrix repeated n times, or a checked (n, dim_x, dim_x) stack."""
    A = np.asarray(A, dtype=float)
    if A.shape == (dim_x, dim_x):
        return np.broadcast_to(A, (n, dim_x, dim_x))
    if A.shape == (n, dim_x, dim_x):
        return A
    raise ValueError(f"{name} must be ({dim_x}, {dim_x}) or ({n}, {dim_x}, {dim_x}) for {n} "
                     f"steps of a {dim_x}-state filter, got {A.shape}.")


def rts_smoother(x, P, F, Q):
    """Smooth the Kalman filter's posteriors backwards in time (Rauch–Tung–Striebel).

    Parameters
    ----------
    x : (n, dim_x) array_like
        The filter's posterior means x̂ₖ⁺ (``KalmanRun.x`` of
        :func:`trackbook.filters.linear_gaussian.run_kalman_filter`).
    P : (n, dim_x, dim_x) array_like
        Their covariances Pₖ⁺.
    F, Q : (dim_x, dim_x) or (n, dim_x, dim_x) array_like
        The transition and process noise; per step, ``F[k]`` and ``Q[k]`` are those that
        predicted step k from step k − 1 (``F[0]`` and ``Q[0]`` are not used), as in
        filterpy's ``KalmanFilter.rts_smoother``.

    Returns
    -------
    x : (n, dim_x) ndarray
        The smoothed means x̂ₖˢ.
    P : (n, dim_x, dim_x) ndarray
        Their covariances Pₖˢ.
    K : (n, dim_x, dim_x) ndarray
        The smoother gains Kₖ (zero at the last step).
    P_prior : (n, dim_x, dim_x) ndarray
        The predicted covariances Pₖ₊₁⁻ used at step k (Pₙ at the last step).
    """
    xs = np.array(x, dtype=float)
    Ps = np.array(P, dtype=float)
    if xs.ndim != 2 or Ps.shape != (xs.shape[0], xs.shape[1], xs.shape[1]):
        raise ValueError(f"x must be (n, dim_x) and P (n, dim_x, dim_x); got {xs.shape} and "
                         f"{Ps.shape}.")
    n, dim_x = xs.shape
    Fs = _per_step(F, n, dim_x, "F")
    Qs = _per_step(Q, n, dim_x, "Q")
    K = np.zeros((n, dim_x, dim_x))
    P_prior = Ps.copy()
    # backwards: step k needs the smoothed step k + 1
    for k in range(n - 2, -1, -1):
        P_prior[k] = Fs[k + 1] @ Ps[k] @ Fs[k + 1].T + Qs[k + 1]
        # Kₖ = Pₖ Fᵀ (Pₖ₊₁⁻)⁻¹, by solving with the symmetric Pₖ₊₁⁻ instead of inverting it
        K[k] = np.linalg.solve(P_prior[k], Fs[k + 1] @ Ps[k]).T
        xs[k] = xs[k] + K[k] @ (xs[k + 1] - Fs[k + 1] @ xs[k])
        Ps[k] = Ps[k] + K[k] @ (Ps[k + 1] - P_prior[k]) @ K[k].T
    return xs, Ps, K, P_prior
