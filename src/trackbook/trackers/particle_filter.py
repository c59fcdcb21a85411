"""The SIR particle-filter tracker (chapter 2): the frame every particle tracker fills in.

The estimation steps it calls (weights, resamplers, estimate) are pure functions in
:mod:`trackbook.filters.particle`; this class only strings them together behind the
``init``/``update`` contract of :class:`trackbook.trackers.base.Tracker`.
"""

from __future__ import annotations

import numpy as np

from ..filters.particle import RESAMPLERS, normalize_weights, weighted_mean
from .base import Tracker, readonly


class ParticleFilterTracker(Tracker):
    """Sequential importance resampling (SIR, Condensation) as in Lee et al. 2012's
    pseudocode, for subclasses.

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
    lost : bool, whether the last frame was lost (all weights zero, a constant frame, or --
        when enabled -- a best particle below ``lost_fraction`` of ``L_self``).

    Lost rule
    ---------
    A frame whose grey levels span at most ``flat_range`` (a constant frame: all black, all
    white, one grey) carries no information at all -- no colour to compare, no gradient for a
    HOG or an edge -- so it is not scored: ``update`` returns ``ok=False``, keeps the last
    estimate and calls ``_on_lost()`` (which widens the search), instead of following the
    least-bad particle. (The likelihood alone cannot tell: the HOG of a gradient-free patch is
    a flat histogram that scores above a real but hard frame.)

    Optional second rule, off by default (``lost_fraction = 0``): at ``init`` the reference is
    scored against itself, ``L_self`` (1 for the Gaussian-of-Bhattacharyya likelihoods); a
    frame whose best particle scores below ``lost_fraction * L_self`` is lost. It is off
    because a fraction of a likelihood depends on the likelihood's sigma: at sigma = 0.1,
    hard but correct frames of Crossing score below 1e-8 of ``L_self`` and a gate there
    changed committed scores; a sigma-free gate is still to be designed.
    """

    #: Below this the weights are treated as carrying no information (frame "lost").
    min_total_likelihood = 0.0
    #: A frame is lost when its best particle scores below this fraction of ``L_self`` (0: off).
    lost_fraction = 0.0
    #: A frame whose values span at most this many grey levels carries no information.
    flat_range = 2

    def _init(self, frame, box):
        self._model(frame, box)
        self._particles = np.asarray(self._initial_particles(frame, box), dtype=float)
        n = self._particles.shape[0]
        self._weights = np.full(n, 1.0 / n)
        self._likelihoods = np.ones(n)
        self.estimate = self._box_to_state(box)
        self.lost = False
        # L_self: the reference scored against itself (the initial state on the initial frame)
        self._self_likelihood = 0.0
        if self.lost_fraction > 0:
            own = np.asarray(self._likelihood(frame, self.estimate[None, :]), dtype=float)
            if own.size and np.isfinite(own).all():
                self._self_likelihood = float(own.max())

    def _update(self, frame):
        resample = RESAMPLERS[self.params.resampler]
        idx = resample(self._weights, self.rng)
        particles = self._predict(self._particles[idx])
        particles = np.asarray(self._refine(frame, particles), dtype=float)
        if int(frame.max()) - int(frame.min()) <= self.flat_range:
            lik = np.zeros(particles.shape[0])      # a constant frame: nothing to score
        else:
            lik = np.asarray(self._likelihood(frame, particles), dtype=float)
        w, informative = normalize_weights(lik)
        if informative and lik.sum() <= self.min_total_likelihood:
            informative = False
        best = float(lik.max()) if lik.size else 0.0
        self.best_ratio = best / self._self_likelihood if self._self_likelihood > 0 else 1.0
        if informative and self.best_ratio < self.lost_fraction:
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
