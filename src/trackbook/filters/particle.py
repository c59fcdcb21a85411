"""The particle filter core: resamplers, weights, estimate, and an SIR tracker base.

Chapter 06 of the book. Resamplers are pure functions that take normalised weights and a
``numpy.random.Generator`` and return the indices of the particles to keep (as filterpy's
``monte_carlo`` module does, but without the global RNG).
"""

from __future__ import annotations

import numpy as np

from ..trackers.base import Tracker, readonly


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
    """N_eff = 1 / sum w_i^2 of normalised weights: N when uniform, 1 when one particle has all."""
    w = np.asarray(weights, dtype=float)
    return float(1.0 / np.sum(w**2))


def _cumsum(weights):
    c = np.cumsum(weights)
    c[-1] = 1.0  # guard against round-off leaving c_N a hair below 1
    return c


def multinomial_resample(weights, rng: np.random.Generator) -> np.ndarray:
    """SIR selection of Lee et al. 2012's pseudocode: for each i draw r ~ U[0, 1] and keep
    the smallest index j with c_j >= r, c the cumulative weights."""
    c = _cumsum(weights)
    return np.searchsorted(c, rng.random(len(c)), side="left")


def systematic_resample(weights, rng: np.random.Generator) -> np.ndarray:
    """One uniform offset u ~ U[0, 1/N), then the N evenly spaced points u + i/N."""
    n = len(weights)
    positions = (rng.random() + np.arange(n)) / n
    return np.searchsorted(_cumsum(weights), positions, side="left")


def stratified_resample(weights, rng: np.random.Generator) -> np.ndarray:
    """One uniform draw in each of the N strata [i/N, (i+1)/N)."""
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


RESAMPLERS = {
    "multinomial": multinomial_resample,
    "systematic": systematic_resample,
    "stratified": stratified_resample,
    "residual": residual_resample,
}


def weighted_mean(states, weights) -> np.ndarray:
    """The estimate sum_i w_i x_i of normalised weights (the pseudocode's expectation)."""
    return np.asarray(weights, dtype=float) @ np.asarray(states, dtype=float)


class ParticleFilterTracker(Tracker):
    """Sequential importance resampling as in Lee et al. 2012's pseudocode, for subclasses.

    Each ``update``: select (resample by the previous weights) -> predict -> [refine] ->
    weight -> normalise -> estimate. Subclasses implement

    - ``_initial_particles(frame, box) -> (N, d) states`` and ``_model(frame, box)`` (reference),
    - ``_predict(particles) -> particles`` (the motion model, using ``self.rng``),
    - ``_likelihood(frame, particles) -> (N,)`` unnormalised, >= 0,
    - ``_state_to_box(state) -> (x, y, w, h)``,

    and may override ``_on_lost()`` (e.g. widen the spread) and ``_refine(frame, particles) ->
    particles`` (move the predicted particles before weighting, e.g. uphill by mean-shift as
    Cho & Kang 2005 do; the default leaves them where the motion model put them). The params dataclass must have
    ``n_particles`` and ``resampler``.

    Attributes
    ----------
    particles : (N, d) array, the particles after the last update (read-only view).
    weights : (N,) normalised weights of the last update.
    likelihoods : (N,) the unnormalised likelihoods of the last update.
    estimate : (d,) the weighted-mean state.
    lost : bool, whether the last frame's weights were all zero.
    """

    #: Below this the weights are treated as carrying no information (frame "lost").
    min_total_likelihood = 0.0

    def _init(self, frame, box):
        self._model(frame, box)
        self._particles = np.asarray(self._initial_particles(frame, box), dtype=float)
        n = self._particles.shape[0]
        self._weights = np.full(n, 1.0 / n)
        self._likelihoods = np.ones(n)
        self.estimate = self._box_to_state(box)
        self.lost = False

    def _update(self, frame):
        resample = RESAMPLERS[self.params.resampler]
        idx = resample(self._weights, self.rng)
        particles = self._predict(self._particles[idx])
        particles = np.asarray(self._refine(frame, particles), dtype=float)
        lik = np.asarray(self._likelihood(frame, particles), dtype=float)
        w, informative = normalize_weights(lik)
        if informative and lik.sum() <= self.min_total_likelihood:
            informative = False
        self._particles, self._likelihoods = particles, lik
        if not informative:
            # Nothing in this frame looks like the target: keep the last estimate, spread the
            # particles evenly (uniform weights) and let the subclass widen its search.
            self._weights = w
            self.lost = True
            self._on_lost()
            return False, self._state_to_box(self.estimate)
        self._weights = w
        self.lost = False
        self.estimate = weighted_mean(particles, w)
        return True, self._state_to_box(self.estimate)

    # read-only views for the book's drawings -------------------------------------------
    @property
    def particles(self) -> np.ndarray:
        return readonly(self._particles)

    @property
    def weights(self) -> np.ndarray:
        return readonly(self._weights)

    @property
    def likelihoods(self) -> np.ndarray:
        return readonly(self._likelihoods)

    def _on_lost(self):
        """Hook: called on a frame where every particle scored zero."""

    def _refine(self, frame, particles):
        """Hook: move the predicted particles before they are weighted (default: don't)."""
        return particles

    # subclass interface ----------------------------------------------------------------
    def _model(self, frame, box):  # pragma: no cover
        raise NotImplementedError

    def _initial_particles(self, frame, box):  # pragma: no cover
        raise NotImplementedError

    def _predict(self, particles):  # pragma: no cover
        raise NotImplementedError

    def _likelihood(self, frame, particles):  # pragma: no cover
        raise NotImplementedError

    def _box_to_state(self, box):  # pragma: no cover
        raise NotImplementedError

    def _state_to_box(self, state):  # pragma: no cover
        raise NotImplementedError
