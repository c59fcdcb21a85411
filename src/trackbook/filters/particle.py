"""The particle filter's pure steps: normalised weights, effective sample size, resamplers, estimate.

Chapter ``02_particle_filters`` (the Bayes filter of ``21_bayes_filter`` with samples: factored
sampling, SIR/Condensation, degeneracy and resampling). The SIR tracker built from these steps is
:class:`trackbook.trackers.particle_filter.ParticleFilterTracker`. Resamplers are pure
functions that take normalised weights and a ``numpy.random.Generator`` and return the indices
of the particles to keep (as filterpy's ``monte_carlo`` module does, but without the global
RNG). All four place *pointers* on the cumulative weights c_i and keep, for each pointer r, the
smallest i with c_i >= r; they differ only in where the pointers go.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np



def normalize_weights(w) -> tuple[np.ndarray, bool]:
    """Weights divided by their sum; ``(uniform, False)`` when they are all zero or not finite.

    The second value says whether the weights carried information: a frame in which every
    particle scored zero is a real event (target occluded or lost) that trackers must survive.
    """
    w = np.asarray(w, dtype=float)
    w = np.where(np.isfinite(w) & (w > 0), w, 0.0)
    s = w.sum()
    if not np.isfinite(s) or s <= 0:
        return np.full(w.shape, 1.0 / w.size), False
    return w / s, True


def effective_sample_size(weights) -> float:
    """N_eff = 1 / sum w_i^2 of normalised weights: N when uniform, 1 when one particle has all.

    The usual measure of weight degeneracy (Arulampalam et al. 2002), plotted with and without
    resampling in ``02_particle_filters``.
    """
    w = np.asarray(weights, dtype=float)
    return float(1.0 / np.sum(w**2))


def _cumsum(weights):
    c = np.cumsum(weights)
    c[-1] = 1.0  # guard against round-off leaving c_N a hair below 1
    return c


def multinomial_resample(weights, rng: np.random.Generator) -> np.ndarray:
    """SIR selection of Lee et al. 2012's pseudocode (section V): for each i draw r ~ U[0, 1]
    and keep the smallest index j with c_j >= r, c the cumulative weights.

    N independent pointers, so particle i gets Binomial(N, w_i) copies: mean N w_i, variance
    N w_i (1 - w_i).
    """
    c = _cumsum(weights)
    return np.searchsorted(c, rng.random(len(c)), side="left")


def systematic_resample(weights, rng: np.random.Generator) -> np.ndarray:
    """One uniform offset u ~ U[0, 1/N), then the N evenly spaced pointers u + i/N.

    Particle i gets floor(N w_i) or ceil(N w_i) copies, whatever the offset: the least copying
    noise of the four resamplers.
    """
    n = len(weights)
    positions = (rng.random() + np.arange(n)) / n
    return np.searchsorted(_cumsum(weights), positions, side="left")


def stratified_resample(weights, rng: np.random.Generator) -> np.ndarray:
    """One pointer (i + u_i)/N in each of the N strata [i/N, (i+1)/N), the u_i ~ U[0, 1)
    drawn by one ``rng.random(N)`` call."""
    n = len(weights)
    positions = (rng.random(n) + np.arange(n)) / n
    return np.searchsorted(_cumsum(weights), positions, side="left")


def residual_resample(weights, rng: np.random.Generator) -> np.ndarray:
    """floor(N w_i) copies of each particle, the remainder drawn multinomially on the residuals."""
    w = np.asarray(weights, dtype=float)
    n = len(w)
    counts = np.floor(n * w).astype(int)
    idx = np.repeat(np.arange(n), counts)
    rest = n - counts.sum()
    if rest > 0:
        resid = n * w - counts
        resid /= resid.sum()
        idx = np.concatenate([idx, np.searchsorted(_cumsum(resid), rng.random(rest), side="left")])
    return idx


#: The resampler registry: name -> ``fn(weights, rng) -> (N,) indices``. Extend it with
#: :func:`register_resampler` (never by editing this module); the ``resampler`` param of every
#: particle tracker accepts any name registered when the tracker is made.
RESAMPLERS: dict = {
    "multinomial": multinomial_resample,
    "systematic": systematic_resample,
    "stratified": stratified_resample,
    "residual": residual_resample,
}


def register_resampler(name: str, fn, *, replace: bool = False):
    """Make ``fn(weights, rng) -> indices`` available as the resampler called ``name``.

    Parameters
    ----------
    name : the name the ``resampler`` param will accept (e.g. ``trackers.create("color-pf",
        resampler=name)``).
    fn : a function of the normalised weights (N,) and a ``numpy.random.Generator`` returning
        N integer indices in 0..N-1 of the particles to keep -- on *every* call: the particle
        filter resamples every frame and then rebuilds the weights from the likelihood alone,
        so a scheme that skips resampling (e.g. only when the effective sample size is low)
        must return the identity ``np.arange(N)`` on the frames it skips.
    replace : allow replacing a resampler already registered under ``name`` by another
        function (re-registering the same function is always allowed).

    Returns ``fn``, so it can be used as a decorator's body.

    Examples
    --------
    >>> import numpy as np
    >>> from trackbook.filters import particle
    >>> particle.register_resampler("keep-all", lambda w, rng: np.arange(len(w)))  # doctest: +ELLIPSIS
    <function <lambda> at ...>
    """
    if not isinstance(name, str) or not name.strip():
        raise TypeError(f"register_resampler: the name must be a non-empty string, not {name!r}.")
    if not callable(fn):
        raise TypeError(f"register_resampler({name!r}, ...): {fn!r} is not callable; pass a "
                        "function fn(weights, rng) -> indices.")
    if name in RESAMPLERS and RESAMPLERS[name] is not fn and not replace:
        raise ValueError(f"a resampler named {name!r} is already registered; choose another "
                         "name or pass replace=True.")
    RESAMPLERS[name] = fn
    return fn


def resampler_names() -> tuple:
    """The names of the registered resamplers, in the order they were registered."""
    return tuple(RESAMPLERS)


class RegisteredNames(Sequence):
    """A live, read-only view of the registered resampler names: a sequence that is read
    each time it is used, so the ``choices`` of a ``resampler`` param made with it accept a
    resampler registered after the params class was defined."""

    def __getitem__(self, i):
        return tuple(RESAMPLERS)[i]

    def __len__(self) -> int:
        return len(RESAMPLERS)

    def __contains__(self, name) -> bool:
        return isinstance(name, str) and name in RESAMPLERS

    def __repr__(self) -> str:
        return repr(tuple(RESAMPLERS))


#: The ``choices`` of every ``resampler`` param: the names registered at the time of asking.
RESAMPLER_NAMES = RegisteredNames()


def get_resampler(name: str):
    """The resampler registered as ``name``; ``ValueError`` naming the registered ones."""
    try:
        return RESAMPLERS[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown resampler {name!r}; registered: {', '.join(RESAMPLERS)} "
                         "(add one with trackbook.filters.particle.register_resampler).") from None


def check_indices(idx, n: int, name: str = "resampler") -> np.ndarray:
    """``idx`` as N integer indices in 0..N-1, or a ``ValueError`` saying what a resampler must
    return (see :func:`register_resampler`)."""
    a = np.asarray(idx)
    what = f"resampler {name!r} returned"
    if a.ndim != 1 or a.shape[0] != n:
        raise ValueError(f"{what} an array of shape {a.shape}; it must return {n} indices, one "
                         "per particle, on every call (to skip resampling return "
                         "np.arange(N)).")
    if a.dtype.kind not in "iu":
        if a.dtype.kind == "b" or not np.all(np.isfinite(a)) or np.any(a != np.round(a)):
            raise ValueError(f"{what} values of type {a.dtype}; it must return integer "
                             "indices of the particles to keep.")
        a = a.astype(np.intp)
    if n and (a.min() < 0 or a.max() >= n):
        raise ValueError(f"{what} indices outside 0..{n - 1} (min {a.min()}, max {a.max()}); "
                         "it must return indices of existing particles.")
    return a


def weighted_mean(states, weights) -> np.ndarray:
    """The estimate sum_i w_i x_i of normalised weights (the expectation that closes Lee et
    al. 2012's pseudocode)."""
    return np.asarray(weights, dtype=float) @ np.asarray(states, dtype=float)
