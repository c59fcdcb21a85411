"""The SIR particle-filter tracker (``02_particle_filters``): the frame particle trackers fill in.

The estimation steps it calls (weights, resamplers, estimate) are pure functions in
:mod:`trackbook.filters.particle`; this class only strings them together behind the
``init``/``update`` contract of :class:`trackbook.trackers.base.Tracker`, as the two halves of
a frame: ``_locate`` (the SIR cycle) and ``_learn`` (accept the estimate).
"""

from __future__ import annotations


import numpy as np

from ..filters.particle import (RESAMPLER_NAMES, check_indices, get_resampler,
                                normalize_weights, weighted_mean)
from ..params import param
from .base import Tracker, readonly_attr


def resampler_param(doc: str, paper="multinomial", default: str = "multinomial", **kw):
    """The ``resampler`` field of a particle tracker's params: any name registered in
    :data:`trackbook.filters.particle.RESAMPLERS` when the params are made (see
    :func:`~trackbook.filters.particle.register_resampler`)."""
    return param(default, doc=doc, choices=RESAMPLER_NAMES, paper=paper, **kw)


class ParticleFilterTracker(Tracker):
    """Sequential importance resampling (SIR, Condensation) as in Lee et al. 2012's
    pseudocode, for subclasses.

    Each frame, :meth:`_locate` runs one cycle: select (resample by the previous weights) ->
    predict -> [refine] -> weigh -> normalise -> estimate (the weighted mean), and returns the
    estimate's box with the tracker's confidence, the best particle's match (see
    "Confidence"). The failure-detection layer of :class:`~trackbook.trackers.base.Tracker`
    judges that confidence; on a frame judged on target :meth:`_learn` accepts the estimate
    (and a learning subclass updates its model there), on a frame judged lost the last box
    stays and nothing is learned. A subclass fills in these public hooks:

    - ``initial_particles(frame, box) -> (N, d) states`` and ``model(frame, box)`` (take the
      reference, e.g. the first frame's histogram; called first by ``init``),
    - ``predict(particles) -> particles`` (the motion model, using ``self.rng``),
    - ``likelihood(frame, particles) -> (N,)`` unnormalised, >= 0, which also sets
      ``self._match``, the (N,) matches ``1 - D^2`` of the particles (the confidence),
    - ``box_to_state(box) -> (d,)`` and ``state_to_box(state) -> (x, y, w, h)``,

    and may override ``refine(frame, particles) -> particles`` (move the predicted particles
    before weighting, e.g. uphill by mean-shift as Cho & Kang 2005 do; the default leaves them
    where the motion model put them) and ``respread(frame, box) -> (N, d)`` (the particles the
    re-detection layer restarts from; default ``initial_particles``). Each hook's docstring
    states what it receives and must return. A subclass that learns overrides ``_learn``
    (calling ``super()._learn(frame, box)`` first); ``_drawn()`` says what ``state()`` shows
    (particles and weights here). The params dataclass must have ``n_particles`` and
    ``resampler`` (made with :func:`resampler_param`). The colour trackers add
    ``features(frame, boxes) -> dict`` (see :class:`trackbook.trackers.color_pf.ColorPF`),
    from which their ``likelihood`` is computed.

    While lost
    ----------
    The filter goes on as it is: every frame the particles are selected by the last weights
    and moved by the motion model from where they are, and weighed; only the reported box (the
    last one kept) and the learning stop. What a velocity does while lost is the motion
    model's (``predict`` reads ``self.ok``, the previous frame's judgement): the colour
    trackers start each lost frame's particles at rest, the centre filters add no measured
    motion (the estimate did not move). That is the filter, not a search: searching the whole frame
    is the re-detection layer of the ``-redetect`` names, which scores boxes with
    :meth:`_score_boxes` (the likelihood's match of a particle placed at each box) and
    restarts the particles around the best with :meth:`_relocate`.

    A frame whose grey levels span at most ``flat_range`` (all black, all white, one grey)
    carries no information (no colour to compare, no gradient for a HOG or an edge): it is
    not scored (every likelihood 0, confidence 0) and the failure layer reports it lost. When
    every likelihood is zero or not finite, the weighted mean is 0 / 0: there is no estimate
    and ``_locate`` returns a NaN box, which the base reports lost with the last box.

    What the frame assumes
    ----------------------
    It resamples on **every** frame and then rebuilds the weights from this frame's likelihood
    alone (w_i proportional to p(z_t | x_t^i), not w_(t-1) p(z_t | x_t^i)). So a resampler,
    ``fn(weights, rng)`` of :data:`trackbook.filters.particle.RESAMPLERS`, must return N
    integer indices in 0..N-1 on every call. An "ESS-triggered" resampler that resamples only
    when the effective sample size is low must return the identity ``np.arange(N)`` on the
    frames it skips. Even then the frame rebuilds the weights from the likelihood alone, so a
    skipped frame forgets the previous weights instead of multiplying them in (the textbook
    w_t proportional to w_(t-1) p(z_t | x_t^i) needs a subclass that overrides ``_locate``).
    A resampler that returns anything else fails with a ``ValueError`` saying so. Register
    your own with :func:`trackbook.filters.particle.register_resampler`; the ``resampler``
    param accepts every name registered when the tracker is made.

    Confidence
    ----------
    The best particle's match of the frame, max_i (1 - D^2_i) (:attr:`best_match`; the
    Bhattacharyya coefficient rho for a histogram model), in [0, 1]; 0 on a constant frame
    (not scored) and for a model that sets no match. The estimate itself is not scored again.

    Attributes
    ----------
    particles : (N, d) array, the particles after the last update (read-only view).
    weights : (N,) normalised weights of the last update.
    likelihoods : (N,) the unnormalised likelihoods of the last update.
    estimate : (d,) the weighted-mean state of the last frame judged on target.
    lost : bool, whether the last frame was judged lost (``not ok``).
    match : (N,) how well each particle of the last frame matches the target, 1 - D^2 in
        [0, 1]; NaN where a tracker's model has no such number.
    """

    def _init(self, frame, box):
        """Start the filter: ``model``, then ``initial_particles`` with uniform weights.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            The first frame, BGR.
        box : (4,) float array
            The target's box ``(x, y, w, h)``, clipped to the frame.

        Returns
        -------
        None
            A subclass that overrides it calls ``super()._init(frame, box)`` and adds its own
            state (``condensation-mean-shift`` remembers the frame for its optical flow).
        """
        self._frame_wh = np.array([frame.shape[1], frame.shape[0]], dtype=float)
        self.model(frame, box)
        self._particles = np.asarray(self.initial_particles(frame, box), dtype=float)
        n = self._particles.shape[0]
        self._weights = np.full(n, 1.0 / n)
        self._likelihoods = np.ones(n)
        self.estimate = self.box_to_state(box)
        self._located = np.array(self.estimate, dtype=float)
        self._match = np.ones(n)

    @property
    def lost(self) -> bool:
        """Whether the last frame was judged lost (``not ok``)."""
        return not self.ok

    def _locate(self, frame):
        """One SIR cycle: select, predict, refine, weigh, normalise, estimate (no learning).

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            This frame, BGR.

        Returns
        -------
        box : (4,) array
            ``state_to_box`` of the weighted-mean estimate; NaN when every likelihood is zero
            or not finite (no estimate: the base reports the frame lost, last box kept).
        confidence : float
            The best particle's match (see "Confidence").

        The particles, weights and likelihoods move (they are the filter's state, lost or
        not); ``estimate`` changes only in :meth:`_learn`.
        """
        name = self.params.resampler
        idx = check_indices(get_resampler(name)(self._weights, self.rng), len(self._weights),
                            name)
        particles = self.predict(np.array(self._particles[idx], dtype=float))
        particles = np.asarray(self.refine(frame, particles), dtype=float)
        self._match = np.full(particles.shape[0], np.nan)   # a subclass's likelihood fills it
        if self._is_flat(frame):
            lik = np.zeros(particles.shape[0])      # a constant frame: nothing to score
        else:
            lik = np.asarray(self.likelihood(frame, particles), dtype=float)
        w, informative = normalize_weights(lik)
        self._particles, self._likelihoods, self._weights = particles, lik, w
        if informative:
            self._located = weighted_mean(particles, w)
            box = np.asarray(self.state_to_box(self._located), dtype=float)
        else:
            # every weight zero: the weighted mean is 0 / 0, there is no estimate this frame
            box = np.full(4, np.nan)
        return box, self._confidence()

    def _confidence(self) -> float:
        """max_i match_i of the frame just weighed (see "Confidence"); 0 when unknown."""
        m = self.best_match
        return m if np.isfinite(m) else 0.0

    def _learn(self, frame, box):
        """Accept the frame's estimate (a frame judged on target): ``estimate`` becomes it.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            The frame ``_locate`` just weighed.
        box : (4,) float array
            The box ``_locate`` returned, ``state_to_box(self._located)``.

        Returns
        -------
        None
            A learning subclass calls ``super()._learn(frame, box)`` and then updates its
            model (``color-hog-ipca`` adds the estimate to its subspaces); the fixed-model
            trackers only record the estimate.
        """
        self.estimate = np.array(self._located, dtype=float)

    def _score_boxes(self, frame, boxes):
        """The likelihood's match (1 - D^2, rho for a histogram) of a particle placed at each
        box, for the re-detection layer; the tracker's state is restored afterwards, so
        scoring changes nothing.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
        boxes : (n, 4) float array

        Returns
        -------
        (n,) float array
        """
        states = np.array([self.box_to_state(b) for b in np.asarray(boxes, dtype=float)])
        saved = dict(self.__dict__)             # the likelihood records per-frame numbers
        try:
            self._match = np.full(len(states), np.nan)
            self.likelihood(frame, states)
            return np.array(self._match, dtype=float)
        finally:
            self.__dict__.clear()
            self.__dict__.update(saved)

    def _relocate(self, frame, box):
        """For the re-detection layer: the particles restart around ``box`` at rest
        (``respread``) with uniform weights; the estimate stays until a frame is accepted."""
        self._particles = np.asarray(self.respread(frame, np.asarray(box, dtype=float)),
                                     dtype=float)
        n = self._particles.shape[0]
        self._weights = np.full(n, 1.0 / n)

    def _follow(self, frame, box):
        """On a lost frame: nothing. The particles already moved in ``_locate`` (they are
        the filter's state), so the next cycle starts from them; restarting them around
        the estimate every lost frame would undo the filter's own spread.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            The lost frame.
        box : (4,) float array
            The box ``_locate`` found on it.

        Returns
        -------
        None
        """

    def respread(self, frame, box):
        """Hook: the particles the re-detection layer restarts from, around ``box`` at rest
        (default ``initial_particles(frame, box)``).

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            This frame.
        box : (4,) float array
            The box the re-detection layer found.

        Returns
        -------
        (N, d) array
            As ``initial_particles``; draw the noise from ``self.rng``.
        """
        return self.initial_particles(frame, box)

    def _update(self, frame):
        """A whole frame for a subclass still written as a wrapper of ``_update`` (``ok,
        box = super()._update(frame)``): ``_locate``, then ``_learn`` on every frame with an
        estimate, without the failure layer. A subclass that does not override ``_update``
        runs in halves (``_locate`` -> failure layer -> ``_learn``) instead.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            This frame, BGR.

        Returns
        -------
        ok : bool
            False on a constant frame or when every likelihood is zero (no estimate).
        box : (4,) array
            The estimate's box, or the last box when ``ok`` is False.
        """
        box, conf = self._locate(frame)[:2]
        self._judged_confidence = float(conf)
        box = np.asarray(box, dtype=float)
        ok = bool(np.all(np.isfinite(box))) and not self._is_flat(frame)
        if ok:
            self._learn(frame, box)
        self.ok = ok                    # ``lost`` reads it; the base sets the same value after
        return ok, (box if ok else np.asarray(self.bbox, dtype=float))

    def _in_halves(self) -> bool:
        """Halves unless a subclass wraps ``_update`` (then that wrapper runs the frame)."""
        return type(self)._update is ParticleFilterTracker._update

    # read-only views for the book's drawings -------------------------------------------
    def _drawn(self) -> dict:
        """The :class:`~trackbook.trackers.base.TrackerState` fields: the base's, plus the
        particles and their normalised weights.

        Returns
        -------
        dict
            ``{**super()._drawn(), "particles": (N, d), "weights": (N,)}``; a subclass adds
            its own fields the same way.
        """
        return {**super()._drawn(), "particles": self._particles, "weights": self._weights}

    particles = readonly_attr("_particles")
    weights = readonly_attr("_weights")
    likelihoods = readonly_attr("_likelihoods")
    match = readonly_attr("_match")

    @property
    def best_match(self) -> float:
        """max over particles of ``match`` (1 - D^2) in the last frame; NaN if unknown."""
        m = self._match
        return float(np.nanmax(m)) if m.size and np.isfinite(m).any() else float("nan")

    def refine(self, frame, particles):
        """Hook: move the predicted particles before they are weighted (default: don't).

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            This frame, BGR.
        particles : (N, d) array
            The particles ``predict`` returned.

        Returns
        -------
        (N, d) array
            The particles to weigh, same shape (``condensation-mean-shift`` climbs each one
            uphill by mean-shift, Cho & Kang 2005).
        """
        return particles

    # subclass interface ----------------------------------------------------------------
    def model(self, frame, box):  # pragma: no cover
        """Take the reference of the target (required); ``_init`` calls it first.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            The first frame, BGR.
        box : (4,) float array
            The target's box ``(x, y, w, h)``, clipped to the frame.

        Returns
        -------
        None
            Store the reference on ``self`` (e.g. the first frame's histogram) and reset any
            per-clip state; ``initial_particles`` is called next.
        """
        raise NotImplementedError

    def initial_particles(self, frame, box):  # pragma: no cover
        """The particles of the first frame (required).

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            The first frame, BGR.
        box : (4,) float array
            The target's box ``(x, y, w, h)``.

        Returns
        -------
        (N, d) array
            N states (N usually ``self.params.n_particles``), columns 0-1 the centre (x, y):
            ``respread`` and the drawings rely on it. Draw any noise from
            ``self.rng``. They start with uniform weights.
        """
        raise NotImplementedError

    def predict(self, particles):  # pragma: no cover
        """The motion model (required): move the selected particles one frame on.

        Parameters
        ----------
        particles : (N, d) array
            The particles the resampler selected (a fresh array; may be edited in place).
            ``self.lost`` says whether the previous frame was lost.

        Returns
        -------
        (N, d) array
            The predicted states, same shape. Draw the noise from ``self.rng`` so the same
            seed gives the same boxes.
        """
        raise NotImplementedError

    def likelihood(self, frame, particles):  # pragma: no cover
        """How well each particle matches the target in this frame (required).

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            This frame, BGR.
        particles : (N, d) array
            The predicted (and refined) particles.

        Returns
        -------
        (N,) array
            Unnormalised weights >= 0 (``update`` normalises them; all zero or not finite
            means no estimate this frame). Also set ``self._match`` to the (N,) matches
            ``1 - D^2`` in [0, 1] (the confidence; left NaN, the confidence is 0). It is also
            called by ``_score_boxes`` on boxes of the re-detection layer, which restores
            every attribute afterwards.
        """
        raise NotImplementedError

    def box_to_state(self, box):  # pragma: no cover
        """The state at rest of a box (required).

        Parameters
        ----------
        box : (4,) array
            ``(x, y, w, h)``.

        Returns
        -------
        (d,) array
            Centre (x, y) in columns 0-1; where the state has them, zero velocity and the
            box's size.
        """
        raise NotImplementedError

    def state_to_box(self, state):  # pragma: no cover
        """The box of one state (required); the inverse of ``box_to_state`` on its image.

        Parameters
        ----------
        state : (d,) array
            One particle state or the weighted-mean estimate.

        Returns
        -------
        (4,) array
            ``(x, y, w, h)`` in pixels, what ``update`` returns.
        """
        raise NotImplementedError
