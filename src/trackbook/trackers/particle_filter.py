"""The SIR particle-filter tracker (``02_particle_filters``): the frame particle trackers fill in.

The estimation steps it calls (weights, resamplers, estimate) are pure functions in
:mod:`trackbook.filters.particle`; this class only strings them together behind the
``init``/``update`` contract of :class:`trackbook.trackers.base.Tracker`.
"""

from __future__ import annotations


import numpy as np

from ..filters.particle import (RESAMPLER_NAMES, check_indices, get_resampler,
                                normalize_weights, weighted_mean)
from ..params import NOT_PRINTED, param
from .base import Tracker, readonly_attr


def lost_below_param():
    """The ``lost_below`` field of a particle tracker's params (the distance gate, see
    :class:`ParticleFilterTracker`); a function so every params class gets its own field."""
    return param(0.7, 0.0, 1.0, 0.05, "a frame can be lost only if its best match 1 - D^2 is "
                 "below this (0 = no distance gate)", paper=NOT_PRINTED, paper_value=0.0,
                 why="the papers' trackers have no lost state (Lee et al. 2012's tracking "
                 "'failed for a while' [quote: lee2012.failed_for_a_while] and went on); the "
                 "book's gate: a frame is lost only when its match is poor and also far "
                 "outside the recent frames' range (lost_k), so a slow drift of the look is "
                 "not a loss")


def resampler_param(doc: str, paper="multinomial", default: str = "multinomial", **kw):
    """The ``resampler`` field of a particle tracker's params: any name registered in
    :data:`trackbook.filters.particle.RESAMPLERS` when the params are made (see
    :func:`~trackbook.filters.particle.register_resampler`)."""
    return param(default, doc=doc, choices=RESAMPLER_NAMES, paper=paper, **kw)


def lost_k_param():
    """The ``lost_k`` field: how far above the recent range a lost frame's D^2 lies."""
    return param(3.0, 0.5, 20.0, 0.5, "... and its D^2 above median + k max(1.4826 MAD, "
                 "median / 2) of recent frames", paper=NOT_PRINTED,
                 why="the papers' trackers have no lost state [quote: "
                 "lee2012.failed_for_a_while]; 3 robust standard deviations, the "
                 "book's choice (only used when lost_below > 0)")


def scatter_grid(k: int, frame_wh, rng) -> np.ndarray:
    """``k`` points spread evenly over a frame of size ``frame_wh = (W, H)``: a grid of about
    ``k`` cells of the frame's aspect, ``k`` distinct cells drawn at random, one uniform point
    in each (a jittered grid: no part of the frame is left out, as i.i.d. uniform points may)."""
    W, H = (float(v) for v in frame_wh)
    nx = max(1, int(np.ceil(np.sqrt(k * W / H))))
    ny = max(1, int(np.ceil(k / nx)))
    cells = rng.choice(nx * ny, size=k, replace=False)
    u = rng.uniform(0.0, 1.0, size=(k, 2))
    return np.column_stack([(cells % nx + u[:, 0]) / nx * W, (cells // nx + u[:, 1]) / ny * H])


class ParticleFilterTracker(Tracker):
    """Sequential importance resampling (SIR, Condensation) as in Lee et al. 2012's
    pseudocode, for subclasses.

    Each ``update``: select (resample by the previous weights) -> predict -> [refine] ->
    weight -> normalise -> estimate. A subclass fills in these public hooks:

    - ``initial_particles(frame, box) -> (N, d) states`` and ``model(frame, box)`` (take the
      reference, e.g. the first frame's histogram; called first by ``init``),
    - ``predict(particles) -> particles`` (the motion model, using ``self.rng``),
    - ``likelihood(frame, particles) -> (N,)`` unnormalised, >= 0 (and, for the distance
      gate, ``self._match = 1 - D^2`` of every particle),
    - ``box_to_state(box) -> (d,)`` and ``state_to_box(state) -> (x, y, w, h)``,

    and may override ``on_lost()`` (called at the end of every frame ``update`` reports
    lost, whatever the reason, e.g. to forget velocities or count the lost frames that widen
    the spread) and ``refine(frame, particles) -> particles`` (move the predicted particles
    before weighting, e.g. uphill by mean-shift as Cho & Kang 2005 do; the default leaves them
    where the motion model put them). Each hook's docstring states what it receives and must
    return. The params dataclass must have ``n_particles`` and ``resampler`` (made with
    :func:`resampler_param`); ``lost_below`` and ``lost_k`` (:func:`lost_below_param`,
    :func:`lost_k_param`) switch the distance gate on.

    Further hooks for trackers that need them: ``_scatter_reset(particles, idx)`` (clear what
    scattered particles must not keep), ``_stands_out(frame, particles)`` (the gate's second
    look), ``_drawn()`` (what ``state()`` shows; particles and weights here), and ``_init`` /
    ``_update`` themselves, which a subclass may wrap (call ``super()`` and add to it, e.g. to
    learn from the estimate) but should not replace. The class attributes below tune the lost
    rule. The colour trackers add ``features(frame, boxes) -> dict`` (see
    :class:`trackbook.trackers.color_pf.ColorPF`), from which their ``likelihood`` is computed.

    What the frame assumes
    ----------------------
    It resamples on **every** frame and then rebuilds the weights from this frame's likelihood
    alone (w_i proportional to p(z_t | x_t^i), not w_(t-1) p(z_t | x_t^i)). So a resampler,
    ``fn(weights, rng)`` of :data:`trackbook.filters.particle.RESAMPLERS`, must return N
    integer indices in 0..N-1 on every call. An "ESS-triggered" resampler that resamples only
    when the effective sample size is low must return the identity ``np.arange(N)`` on the
    frames it skips. Even then the frame rebuilds the weights from the likelihood alone, so a
    skipped frame forgets the previous weights instead of multiplying them in (the textbook
    w_t proportional to w_(t-1) p(z_t | x_t^i) needs a subclass that overrides ``_update``).
    A resampler that returns anything else fails with a ``ValueError`` saying so. Register
    your own with :func:`trackbook.filters.particle.register_resampler`; the ``resampler``
    param accepts every name registered when the tracker is made.

    Attributes
    ----------
    particles : (N, d) array, the particles after the last update (read-only view).
    weights : (N,) normalised weights of the last update.
    likelihoods : (N,) the unnormalised likelihoods of the last update.
    estimate : (d,) the weighted-mean state.
    lost : bool, whether the last frame was lost (all weights zero, a constant frame, or the
        distance gate below).
    match : (N,) how well each particle of the last frame matches the target, 1 - D^2 in
        [0, 1] (the Bhattacharyya coefficient rho for a histogram model); NaN where a
        tracker's model has no such number.

    Lost rule
    ---------
    A frame whose grey levels span at most ``flat_range`` (a constant frame: all black, all
    white, one grey) carries no information at all -- no colour to compare, no gradient for a
    HOG or an edge -- so it is not scored: ``update`` returns ``ok=False``, keeps the last
    estimate and calls ``on_lost()``, instead of following the least-bad particle. So does a
    frame whose likelihoods are all zero or not finite (or sum to at most
    ``min_total_likelihood``). (The likelihood alone cannot tell: the HOG of a gradient-free patch is
    a flat histogram that scores above a real but hard frame.)

    Second rule, the distance gate (trackers whose params have ``lost_below`` > 0): a frame is
    lost when its *best* particle both matches poorly, ``1 - D^2 < lost_below``, and is far
    outside the recent range, ``D^2 > med + lost_k * max(1.4826 MAD, med / 2)`` over the
    best ``D^2`` of the last ``gate_window`` frames that were not lost (the first five frames
    always pass). The gate is on the distance, not on the likelihood: ``exp(-D^2 / 2 sigma^2)``
    of a given match changes by orders of magnitude with sigma, ``D^2`` does not. Both tests
    are needed: a box still on a pedestrian can match only moderately (a HOG that swings with
    small misalignments, a colour distance that rises as the light changes). The colour + HOG
    trackers gate on the colour term alone (whether the target is there at all). After
    ``gate_patience`` lost frames in a row the recent range is forgotten and rebuilt, so a
    target whose look changed for good is not reported lost for ever.

    Second look (``gate_contrast`` > 0): before the gate calls a frame lost, the best
    particle's match is compared with the median match of eight boxes of its size around it
    (``probe_offsets``, 1.5 box sizes away; ``_stands_out``). A match of at least
    ``contrast_floor`` that beats its surroundings by ``gate_contrast`` is the target under a
    sudden change of light (every match drops, the target's stays the best around), not a
    target that has gone: the frame is kept. A target that left, or is covered, leaves no
    such peak. Only frames the gate would call lost pay for the look (one more likelihood of
    eight boxes); ``hog-pf`` has none (a textured background's HOG stands out as much).

    Leaving across the border: the boxes are kept inside the frame, so the visible part of a
    leaving target shrinks in them and the match drops with it: the same two rules report it.

    Recovery: while lost, every prediction restarts ``scatter_fraction`` of the particles at
    rest, at the size of the first box, on a jittered grid over the whole frame
    (``scatter_grid``: one particle per cell, so the whole frame is covered at a cost bounded
    by N); of the rest, half keep what the last frame's weights selected (the search closes in
    on a good match over a few frames) and half wait at rest at the last estimate, for a target
    that reappears where it vanished. ``ok=True`` comes back only when the best match passes
    the gate again. On a frame that is never lost nothing is scattered and no random number
    is drawn for it, so trackers that never lose the target run exactly as without the rule.
    """

    #: Below this the weights are treated as carrying no information (frame "lost").
    min_total_likelihood = 0.0
    #: While lost, this fraction of the particles is scattered over the whole frame.
    scatter_fraction = 0.8
    #: The distance gate's memory: best D^2 of this many recent frames that were not lost.
    gate_window = 30
    #: After this many lost frames in a row the gate forgets its range and rebuilds it.
    gate_patience = 30
    #: A frame the gate would call lost is kept when the best particle's match beats the
    #: median of the boxes around it by this much (0 = no second look).
    gate_contrast = 0.12
    #: ... but never when that best match is below this (a sliver at the border, a look-alike).
    contrast_floor = 0.5
    #: Where the second look's boxes are, in box sizes from the best particle's centre.
    probe_offsets = ((-1.5, 0), (1.5, 0), (0, -1.5), (0, 1.5), (-1.5, -1.5), (1.5, -1.5),
                     (-1.5, 1.5), (1.5, 1.5))
    #: Per-frame records a probe's ``_likelihood`` call must not overwrite.
    _probe_keeps = ("_similarities", "_report", "_rho", "_likelihoods")

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
        self.lost = False
        self._match = np.ones(n)
        self._start_state = np.asarray(self.box_to_state(box), dtype=float)
        self._gate_d2 = []          # best D^2 of recent frames that were not lost
        self._lost_in_a_row = 0

    def _update(self, frame):
        """One SIR cycle: select, [scatter while lost], predict, refine, weigh, normalise,
        estimate, and the lost rule.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            This frame, BGR.

        Returns
        -------
        ok : bool
            False on a lost frame (then ``on_lost`` has been called).
        box : (4,) array
            ``state_to_box`` of the weighted-mean estimate, or of the last good estimate on
            a lost frame.

        A subclass may wrap it, ``ok, box = super()._update(frame)`` followed by its own
        bookkeeping (learning from the estimate, a velocity), rather than replace it.
        """
        name = self.params.resampler
        idx = check_indices(get_resampler(name)(self._weights, self.rng), len(self._weights),
                            name)
        particles = self._particles[idx]
        if self.lost and self.scatter_fraction > 0:
            particles = self._scatter(np.array(particles, dtype=float))
        particles = self.predict(particles)
        particles = np.asarray(self.refine(frame, particles), dtype=float)
        self._match = np.full(particles.shape[0], np.nan)   # a subclass's likelihood fills it
        if self._is_flat(frame):
            lik = np.zeros(particles.shape[0])      # a constant frame: nothing to score
        else:
            lik = np.asarray(self.likelihood(frame, particles), dtype=float)
        w, informative = normalize_weights(lik)
        if informative and lik.sum() <= self.min_total_likelihood:
            informative = False
        if informative and self._gated_out() and not self._stands_out(frame, particles):
            informative = False                     # the distance gate (see "Lost rule")
        self._lost_in_a_row = 0 if informative else self._lost_in_a_row + 1
        self._particles, self._likelihoods = particles, lik
        if not informative:
            # Nothing in this frame looks like the target: keep the last estimate and let the
            # subclass react (on_lost). The weights are uniform when the likelihoods said
            # nothing, this frame's own when the gate called it lost; the next update resamples
            # by them and, being lost, scatters part of the particles.
            self._weights = w
            self.lost = True
            self.on_lost()
            return False, self.state_to_box(self.estimate)
        self._weights = w
        self.lost = False
        self.estimate = weighted_mean(particles, w)
        return True, self.state_to_box(self.estimate)

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

    def _last_confidence(self) -> float:
        """The confidence ``state()`` reports: the best particle's match of the last frame.

        Returns
        -------
        float
            max_i (1 - D^2_i) (:attr:`best_match`, the number the distance gate reads), in
            [0, 1]; 0, the lowest match, on a constant frame, which is not scored. Read from
            what the last ``update`` stored, so calling it changes nothing.
        """
        m = self.best_match
        return m if np.isfinite(m) else 0.0

    def on_lost(self):
        """Hook: react to a lost frame (default: nothing).

        ``_update`` calls it at the end of every frame it reports lost (``ok=False``): a flat
        frame (see ``flat_range``), likelihoods that carry no information (all zero or not
        finite, or a sum at most ``min_total_likelihood``), or a frame the distance gate calls
        lost (see "Lost rule" in the class docstring). It is not called on frames that are
        tracked.

        When it is called, ``self.lost`` is True; ``self._particles`` holds this frame's
        predicted (and refined) particles and may be edited in place; ``self._weights`` are
        uniform (no information) or this frame's normalised likelihoods (gated out);
        ``self.estimate`` is still the last good estimate, which ``update`` returns; and
        ``self._lost_in_a_row`` counts this frame. The next ``update`` resamples by
        ``self._weights``, scatters ``scatter_fraction`` of the particles over the frame and
        calls ``predict`` with ``self.lost`` still True. ``ColorPF`` zeroes the particles'
        velocities here; ``CentreParticleFilter`` counts the lost frames that widen its
        spread.

        Returns
        -------
        None
            The return value is ignored.
        """

    def _gated_out(self) -> bool:
        """The distance gate of the class docstring: True if this frame's best match is both
        below ``lost_below`` and far above the recent range of ``D^2``. Records the frame's
        ``D^2`` in the range when it passes."""
        below = float(getattr(self.params, "lost_below", 0.0))
        m = self._match
        if below <= 0 or not (m.size and np.isfinite(m).any()):
            return False
        d2 = 1.0 - float(np.nanmax(m))
        hist = self._gate_d2
        if self._lost_in_a_row >= self.gate_patience:
            hist.clear()                    # the look changed for good: rebuild the range
        if self._outside_range(1.0 - d2):
            return True
        hist.append(d2)
        del hist[:-self.gate_window]
        return False

    def _outside_range(self, match: float) -> bool:
        """The distance gate's test of one match ``1 - D^2``, without recording it: below
        ``lost_below`` and ``D^2`` above ``med + lost_k max(1.4826 MAD, med / 2)`` of the
        recent range (never before five frames have passed)."""
        below = float(getattr(self.params, "lost_below", 0.0))
        hist = self._gate_d2
        if below <= 0 or len(hist) < 5 or not match < below:
            return False
        d2 = 1.0 - float(match)
        v = np.asarray(hist)
        med = float(np.median(v))
        spread = max(1.4826 * float(np.median(np.abs(v - med))), med / 2.0)
        return d2 > med + float(getattr(self.params, "lost_k", 3.0)) * spread

    def _stands_out(self, frame, particles) -> bool:
        """The gate's second look (see "Lost rule"): whether the best particle's match is at
        least ``contrast_floor`` and beats the median match of the ``probe_offsets`` boxes
        around it, of its own size, by at least ``gate_contrast``. Computed only on frames the
        distance gate would call lost.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            This frame.
        particles : (N, d) array
            This frame's weighted particles; ``self._match`` holds their matches.

        Returns
        -------
        bool
            True keeps the frame (not lost). Override to return False for a tracker whose
            features stand out on any textured background; the probes' ``likelihood`` call
            must leave ``self._match`` and the attributes named in ``_probe_keeps`` as
            they were (this method restores them).
        """
        m = self._match
        i = int(np.nanargmax(m))
        best = float(m[i])
        if self.gate_contrast <= 0 or best < self.contrast_floor:
            return False
        box = np.asarray(self.state_to_box(particles[i]), dtype=float)
        centres = box[:2] + box[2:] / 2 + np.asarray(self.probe_offsets) * box[2:]
        inside = np.all((centres >= 0) & (centres < self._frame_wh), axis=1)
        if inside.sum() < 2:
            return False
        probes = np.repeat(particles[i:i + 1], int(inside.sum()), axis=0)
        probes[:, 0:2] += centres[inside] - (box[:2] + box[2:] / 2)
        saved = {k: getattr(self, k) for k in self._probe_keeps if hasattr(self, k)}
        self.likelihood(frame, probes)
        around = float(np.nanmedian(self._match))
        for k, v in saved.items():
            setattr(self, k, v)
        self._match = m
        self._contrast = best - around
        return best - around >= self.gate_contrast

    def _scatter(self, particles):
        """Recovery while lost (see "Lost rule"): a random ``scatter_fraction`` of the
        particles restart at rest at the size of the first box, on a jittered grid over the
        whole frame (one particle per grid cell, so the frame is covered evenly at a cost
        bounded by N); of the others, half keep what the last frame's weights selected (so the
        search closes in on a good match over a few frames) and half restart at rest at the
        last estimate (all of them after a frame with nothing to weigh, uniform weights).
        ``_scatter_reset`` clears what else should not carry over."""
        n = particles.shape[0]
        k = int(round(self.scatter_fraction * n))
        if k <= 0:
            return particles
        # at rest: the state of a box (zero velocity, unit size change); columns 0-1 are the
        # centre in every tracker here
        home = self.box_to_state(self.state_to_box(self.estimate))
        order = self.rng.permutation(n)
        idx = order[:k]
        if np.ptp(self._weights) == 0:
            particles[:] = home
        else:
            particles[order[k:k + (n - k) // 2]] = home  # half of the rest waits where it left
        particles[idx] = self._start_state
        particles[idx, 0:2] = scatter_grid(k, self._frame_wh, self.rng)
        self._scatter_reset(particles, idx)
        return particles

    def _scatter_reset(self, particles, idx):
        """Hook: clear the parts of scattered particles' states that should not carry over
        (default: nothing).

        Parameters
        ----------
        particles : (N, d) array
            The particles being scattered while lost; edit in place.
        idx : (k,) int array
            The rows just restarted on the grid over the frame (at the first box's state,
            centre moved).

        Returns
        -------
        None
        """

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
            the lost rule's scatter and the drawings rely on it. Draw any noise from
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
            means a lost frame). For the distance gate also set ``self._match`` to the
            (N,) matches ``1 - D^2`` in [0, 1]; left NaN, the gate is off. It is also called
            on the eight probe boxes of the gate's second look, so keep per-frame records
            in attributes named in ``_probe_keeps``.
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
