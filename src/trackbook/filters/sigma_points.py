"""Van der Merwe's scaled sigma points and weights, the ones the unscented Kalman filter uses.

For a Gaussian N(x, P) in n dimensions, 2n + 1 points and two sets of weights are chosen so
that the weighted mean and covariance of the points are x and P (Van der Merwe 2004):

    λ   = α² (n + κ) − n
    χ₀  = x,    χᵢ = x + [√((n + λ) P)]ᵢ,    χₙ₊ᵢ = x − [√((n + λ) P)]ᵢ,    i = 1 … n
    Wm₀ = λ / (n + λ)
    Wc₀ = Wm₀ + 1 − α² + β
    Wmᵢ = Wcᵢ = 1 / (2 (n + λ)),    i = 1 … 2n

[√A]ᵢ is the i-th row of the upper Cholesky factor U of A (A = UᵀU), as in filterpy's
``MerweScaledSigmaPoints``. α sets the spread (small α: points close to x), β folds in prior
knowledge of the distribution (β = 2 is optimal for a Gaussian), κ is a secondary scaling
(often 0 or 3 − n).

>>> import numpy as np
>>> Wm, Wc = merwe_scaled_weights(1, alpha=1.0, beta=0.0, kappa=2.0)
>>> (6 * Wm).round(12).tolist(), bool(np.allclose(Wc, Wm))   # λ = 2: Wm = [2/3, 1/6, 1/6]
([4.0, 1.0, 1.0], True)
"""

from __future__ import annotations

import numpy as np

__all__ = ["merwe_scaled_lambda", "merwe_scaled_sigma_points", "merwe_scaled_weights"]


def _check(n: int, alpha: float, kappa: float) -> int:
    n = int(n)
    if n < 1:
        raise ValueError(f"n, the state dimension, must be at least 1, got {n}.")
    if not alpha > 0:
        raise ValueError(f"alpha must be positive (typically 1e-3 to 1), got {alpha}.")
    if not n + merwe_scaled_lambda(n, alpha, kappa) > 0:
        raise ValueError(f"n + λ = α²(n + κ) must be positive; raise kappa above {-n}.")
    return n


def merwe_scaled_lambda(n: int, alpha: float, kappa: float) -> float:
    """The scaling parameter λ = α² (n + κ) − n.

    Parameters
    ----------
    n : int
        State dimension.
    alpha, kappa : float
        Spread and secondary scaling.

    Returns
    -------
    float
    """
    return alpha ** 2 * (n + kappa) - n


def merwe_scaled_weights(n: int, alpha: float, beta: float, kappa: float):
    """The mean weights Wm and covariance weights Wc of the 2n + 1 scaled sigma points.

    Wm₀ = λ / (n + λ),  Wc₀ = Wm₀ + 1 − α² + β,  Wmᵢ = Wcᵢ = 1 / (2 (n + λ)) for i ≥ 1,
    with λ = α² (n + κ) − n. Wm sums to 1; Wc sums to 2 − α² + β.

    Parameters
    ----------
    n : int
        State dimension.
    alpha, beta, kappa : float
        The scaling parameters (α > 0; β = 2 for a Gaussian).

    Returns
    -------
    Wm, Wc : (2n + 1,) ndarray
    """
    n = _check(n, alpha, kappa)
    lam = merwe_scaled_lambda(n, alpha, kappa)
    Wm = np.full(2 * n + 1, 0.5 / (n + lam))
    Wc = Wm.copy()
    Wm[0] = lam / (n + lam)
    Wc[0] = Wm[0] + 1.0 - alpha ** 2 + beta
    return Wm, Wc


def merwe_scaled_sigma_points(x, P, alpha: float, beta: float, kappa: float):
    """The 2n + 1 scaled sigma points of N(x, P) and their weights.

    χ₀ = x; χᵢ = x + Uᵢ and χₙ₊ᵢ = x − Uᵢ (i = 1 … n), Uᵢ the i-th row of the upper
    Cholesky factor of (n + λ) P; weights from :func:`merwe_scaled_weights`.

    Parameters
    ----------
    x : (n,) array_like or float
        The mean.
    P : (n, n) array_like or float
        The covariance, symmetric positive definite (a scalar means P·I).
    alpha, beta, kappa : float
        The scaling parameters (filterpy's ``MerweScaledSigmaPoints(n, alpha, beta, kappa)``).

    Returns
    -------
    sigmas : (2n + 1, n) ndarray
        One sigma point per row, in the order χ₀, χ₁ … χₙ, χₙ₊₁ … χ₂ₙ.
    Wm, Wc : (2n + 1,) ndarray
        Weights for the mean and for the covariance.
    """
    from scipy.linalg import cholesky

    x = np.atleast_1d(np.asarray(x, dtype=float)).ravel()
    n = _check(x.size, alpha, kappa)
    P = np.asarray(P, dtype=float)
    P = P * np.eye(n) if P.ndim == 0 else np.atleast_2d(P)
    if P.shape != (n, n):
        raise ValueError(f"P must be ({n}, {n}) for a mean of size {n}, got {P.shape}.")
    lam = merwe_scaled_lambda(n, alpha, kappa)
    try:
        U = cholesky((n + lam) * P)             # upper: (n + λ) P = UᵀU
    except np.linalg.LinAlgError:
        raise ValueError("P must be symmetric positive definite (its Cholesky factor failed); "
                         "symmetrise it with (P + P.T) / 2 or add a small multiple of I.") from None
    sigmas = np.vstack([x, x + U, x - U])
    Wm, Wc = merwe_scaled_weights(n, alpha, beta, kappa)
    return sigmas, Wm, Wc
