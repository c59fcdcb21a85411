"""Is a filter consistent? The NEES and NIS χ² tests of Bar-Shalom, Li and Kirubarajan (2001).

A filter is *consistent* when its errors are as large as its covariances say: the estimation
error x − x̂ has zero mean and covariance P, and the residual y = z − H x̂⁻ has zero mean and
covariance S. Normalising each by its covariance gives a quantity whose distribution is known
when the filter is consistent and the errors Gaussian:

* NEES, the normalised estimation error squared, εₖ = (xₖ − x̂ₖ)ᵀ Pₖ⁻¹ (xₖ − x̂ₖ) ~ χ²(n_x)
  (:func:`nees`; needs the truth, so a simulation);
* NIS, the normalised innovation squared, ε_νₖ = yₖᵀ Sₖ⁻¹ yₖ ~ χ²(n_z) (:func:`nis`; needs
  only the filter's own outputs, so it also works on real data).

Averaged over N independent samples — M Monte-Carlo runs at one step, or, for the NIS, the
steps of a run too, since a consistent filter's residuals are white — N ε̄ ~ χ²(N n), so ε̄
falls inside the two-sided interval [χ²_{Nn}(α/2)/N, χ²_{Nn}(1 − α/2)/N] with probability
1 − α (:func:`chi2_acceptance_interval`). Above the interval the filter is *overconfident*
(its P or S too small: Q or R set too low); below it, *underconfident*.
:func:`consistency_test` and :func:`is_consistent` apply the test;
:func:`average_over_runs` gives the per-step average over M runs that Bar-Shalom plots
against time.

>>> import numpy as np
>>> float(nees(np.array([1.0, 2.0]), np.zeros(2), np.diag([1.0, 4.0])))
2.0
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["ConsistencyTest", "average_over_runs", "chi2_acceptance_interval",
           "consistency_test", "is_consistent", "nees", "nis", "normalized_squared"]


def normalized_squared(e, C) -> np.ndarray:
    """eᵀ C⁻¹ e for one vector or a stack of them.

    Parameters
    ----------
    e : (..., n) array_like
        Errors; any leading shape (runs, steps, ...).
    C : (..., n, n) array_like
        Their covariances, with the same leading shape (or broadcastable to it).

    Returns
    -------
    ndarray of shape e.shape[:-1]
    """
    e = np.asarray(e, dtype=float)
    C = np.asarray(C, dtype=float)
    if e.ndim == 0 or C.shape[-2:] != (e.shape[-1], e.shape[-1]):
        raise ValueError(f"errors of shape {e.shape} need covariances of shape "
                         f"(..., {e.shape[-1] if e.ndim else 'n'}, same), got {C.shape}.")
    # solve rather than invert C: C⁻¹e without forming C⁻¹
    sol = np.linalg.solve(C, e[..., None])[..., 0]
    return np.einsum("...i,...i->...", e, sol)


def nees(x, x_hat, P) -> np.ndarray:
    """The normalised estimation error squared εₖ = (xₖ − x̂ₖ)ᵀ Pₖ⁻¹ (xₖ − x̂ₖ).

    Parameters
    ----------
    x : (..., n_x) array_like
        True states.
    x_hat : (..., n_x) array_like
        The filter's estimates.
    P : (..., n_x, n_x) array_like
        The filter's covariances of those estimates.

    Returns
    -------
    ndarray of shape x.shape[:-1]
        χ²(n_x)-distributed, mean n_x, when the filter is consistent.
    """
    return normalized_squared(np.asarray(x, dtype=float) - np.asarray(x_hat, dtype=float), P)


def nis(y, S) -> np.ndarray:
    """The normalised innovation squared ε_νₖ = yₖᵀ Sₖ⁻¹ yₖ.

    Parameters
    ----------
    y : (..., n_z) array_like
        Residuals y = z − H x̂⁻ (``KalmanFilter.y``).
    S : (..., n_z, n_z) array_like
        Their covariances S = H P⁻ Hᵀ + R (``KalmanFilter.S``).

    Returns
    -------
    ndarray of shape y.shape[:-1]
        χ²(n_z)-distributed, mean n_z, when the filter is consistent.
    """
    return normalized_squared(y, S)


def average_over_runs(eps) -> np.ndarray:
    """The Monte-Carlo average ε̄ₖ = (1/M) Σᵢ εₖⁱ of a NEES or NIS over M runs.

    Parameters
    ----------
    eps : (M, K) array_like
        εₖⁱ for run i and step k.

    Returns
    -------
    (K,) ndarray
        Each entry, times M, is χ²(M n) when the filter is consistent: test it with
        :func:`chi2_acceptance_interval` (dim=n, n_samples=M).
    """
    eps = np.asarray(eps, dtype=float)
    if eps.ndim != 2 or eps.shape[0] < 1:
        raise ValueError(f"eps must be (runs, steps), got shape {eps.shape}.")
    return eps.mean(axis=0)


def chi2_acceptance_interval(dim: int, n_samples: int, confidence: float = 0.95):
    """The two-sided acceptance interval [r₁, r₂] of an average of n_samples χ²(dim) values.

    Under the hypothesis that the filter is consistent, N ε̄ ~ χ²(N·dim), so

        r₁ = χ²⁻¹_{N·dim}(α/2) / N,   r₂ = χ²⁻¹_{N·dim}(1 − α/2) / N,   α = 1 − confidence,

    and P(r₁ ≤ ε̄ ≤ r₂) = confidence.

    Parameters
    ----------
    dim : int
        Degrees of freedom of one value: n_x for the NEES, n_z for the NIS.
    n_samples : int
        N, the number of independent values averaged (M runs; for the NIS, runs × steps).
    confidence : float
        1 − α, in (0, 1).

    Returns
    -------
    (r1, r2) : tuple of float
    """
    from scipy.stats import chi2

    dim, n_samples = int(dim), int(n_samples)
    if dim < 1 or n_samples < 1:
        raise ValueError(f"dim and n_samples must be at least 1, got {dim} and {n_samples}.")
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must lie in (0, 1), e.g. 0.95; got {confidence}.")
    alpha = 1.0 - confidence
    dof = n_samples * dim
    return (float(chi2.ppf(alpha / 2, dof)) / n_samples,
            float(chi2.ppf(1 - alpha / 2, dof)) / n_samples)


@dataclass(frozen=True)
class ConsistencyTest:
    """The outcome of a χ² consistency test.

    Attributes
    ----------
    average : float
        ε̄, the mean of the samples tested.
    lower, upper : float
        The acceptance interval [r₁, r₂].
    dim, n_samples : int
        Degrees of freedom per sample, and how many samples were averaged.
    confidence : float
        The interval's probability under the hypothesis of consistency.
    verdict : str
        ``"consistent"`` (inside), ``"overconfident"`` (above: the covariances are too small)
        or ``"underconfident"`` (below: too large).
    """

    average: float
    lower: float
    upper: float
    dim: int
    n_samples: int
    confidence: float
    verdict: str


def consistency_test(eps, dim: int, confidence: float = 0.95) -> ConsistencyTest:
    """Bar-Shalom's χ² test of the average of independent NEES or NIS values.

    Parameters
    ----------
    eps : array_like
        Independent NEES values (one per Monte-Carlo run, at one step) or NIS values (any
        runs and steps: a consistent filter's residuals are white). The NEES of successive
        steps of one run are correlated; test them step by step, on
        ``average_over_runs(eps)[k]`` with ``n_samples=M``, or pass ``eps[:, k]`` here.
    dim : int
        n_x for the NEES, n_z for the NIS.
    confidence : float
        Probability of the acceptance interval, 0.95 by default.

    Returns
    -------
    ConsistencyTest
    """
    eps = np.asarray(eps, dtype=float).ravel()
    if eps.size == 0 or not np.all(np.isfinite(eps)):
        raise ValueError("eps must hold at least one finite NEES or NIS value.")
    lower, upper = chi2_acceptance_interval(dim, eps.size, confidence)
    average = float(eps.mean())
    verdict = ("overconfident" if average > upper
               else "underconfident" if average < lower else "consistent")
    return ConsistencyTest(average, lower, upper, int(dim), eps.size, float(confidence), verdict)


def is_consistent(eps, dim: int, confidence: float = 0.95) -> bool:
    """True when the average of ``eps`` lies inside the χ² acceptance interval.

    See :func:`consistency_test` for the arguments and which samples may be pooled.
    """
    return consistency_test(eps, dim, confidence).verdict == "consistent"
