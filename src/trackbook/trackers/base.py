"""The contract every tracker keeps: OpenCV's ``init(frame, bbox)`` / ``update(frame)``.

A tracker implements ``_init(frame, box)`` and either the two halves of a frame,
``_locate(frame) -> (box, confidence)`` and ``_learn(frame, box)``, or the whole frame,
``_update(frame) -> (ok, box)``. This class owns everything that must be the same for every
tracker: the params dataclass, the seeded ``numpy.random.Generator`` (re-created on every
``init`` so a re-run repeats exactly), the input checks that refuse bad input naming a fix, the
last line of defence against a NaN or empty box and, for a tracker written in halves, the two
layers that stand between locating and learning:

- the **failure-detection layer** (on unless ``failure=False``): the frame's confidence is
  judged by :class:`~trackbook.trackers.failure.FailureDetector` with the tracker's calibrated
  thresholds (a located box less than half in view, or no box at all, is lost whatever the
  confidence says; one past the frame's edge is kept out of the reference after the warm-up);
  a frame judged lost keeps the last box and teaches the model nothing;
- the **re-detection layer** (opt-in, the ``-redetect`` names): while lost, the tracker's own
  appearance model scores boxes over the whole frame and the search restarts from the best.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np

from .._checks import check_box_in_frame, check_frame, check_seed, positional_seed_error
from ..params import make_params
from .failure import (MIN_IN_VIEW, FailureDetector, FailureParams, calibrated_params,
                      in_view, reaches_out)


def readonly_attr(name: str, doc: str | None = None) -> property:
    """A property giving a read-only view of ``self.<name>`` (see :func:`readonly`)."""
    return property(lambda self: readonly(getattr(self, name)), doc=doc)


def readonly(a) -> np.ndarray:
    """A read-only view of ``a``: trackers expose their state for drawings, never for editing."""
    v = np.asarray(a).view()
    v.flags.writeable = False
    return v


def centred_response(response, centre, step, cyclic: bool = True) -> dict:
    """The ``response`` and ``response_box`` fields of :class:`TrackerState` from a score map
    over shifts of the target.

    Parameters
    ----------
    response : (R, C) array
        The map; ``cyclic``: index (0, 0) is "no move" and the last rows and columns are the
        negative shifts (a correlation filter's FFT layout), else the middle cell
        (R // 2, C // 2) is "no move" already.
    centre : (x, y)
        The target's centre the search started from, in frame pixels.
    step : (sx, sy)
        Frame pixels per cell across and down.

    Returns
    -------
    dict
        ``{"response": the map with "no move" in its middle cell, "response_box": (x, y, w,
        h)}``, the box's cell (i, j) centred on ``centre + ((j - C // 2) sx, (i - R // 2)
        sy)``.
    """
    r = np.asarray(response, dtype=float)
    R, C = r.shape
    if cyclic:     # shift (0, 0) to the middle cell, as np.fft.fftshift does for any size
        r = np.roll(r, (R // 2, C // 2), axis=(0, 1))
    sx, sy = (float(v) for v in step)
    x0 = centre[0] - (C // 2 + 0.5) * sx
    y0 = centre[1] - (R // 2 + 0.5) * sy
    return {"response": r, "response_box": (x0, y0, C * sx, R * sy)}


def _frozen(a, dtype=float):
    """A read-only copy of ``a`` (None stays None): a state outlives the tracker's next frame."""
    return None if a is None else readonly(np.array(a, dtype=dtype, copy=True))


@dataclasses.dataclass(frozen=True)
class TrackerState:
    """What a tracker shows of itself after a frame: the one interface drawings read.

    ``Tracker.state()`` returns it; the book's figures, the playground and the command line's
    video draw from it. A field is None when the tracker has no such thing (a Kalman window
    has no particles, a particle filter no search window). Arrays are read-only copies, so a
    state kept for later is not changed by the next ``update``.

    Attributes
    ----------
    box : (x, y, w, h) of the last estimate, or None before ``init``.
    ok : whether the last frame was tracked (False while the target is lost).
    particles : (N, d) particle states; columns 0-1 are the centre (x, y) in every tracker.
    weights : (N,) their normalised weights (sum 1).
    search_window : (x, y, w, h) of the area a local search covered.
    ellipse : (cx, cy, hx, hy) or (cx, cy, hx, hy, angle in degrees): a target ellipse
        (mean-shift) or a gate (the Kalman filter's).
    candidates : (n, 4) boxes ``(x, y, w, h)`` evaluated on the last frame.
    rays : (N, 8) edge distances of every particle along the 8 rays (Kim et al. 2016 eq. 4),
        row i belonging to ``particles[i]``.
    confidence : float, the tracker's own confidence in the last estimate, larger is surer;
        see each tracker's docstring for its definition. A finite number after every
        ``update`` (lost and constant frames included), None before the first one. It is the
        number the tracker computed during that ``update``: reading it changes nothing.
    response : (R, C) the last score map of a tracker that scores every shift of the target
        in a window (a correlation filter's response), laid out as the frame: cell (i, j)
        scores the target's centre at the centre of that cell of ``response_box``, so the
        middle cell (R // 2, C // 2) is "no move" and the brightest cell is where the search
        put the target. None before the first ``update``.
    response_box : (x, y, w, h) of the frame area ``response`` covers, in frame pixels
        (C cells of w / C px across, R cells of h / R px down).
    """

    box: tuple | None = None
    ok: bool = False
    particles: np.ndarray | None = None
    weights: np.ndarray | None = None
    search_window: tuple | None = None
    ellipse: tuple | None = None
    candidates: np.ndarray | None = None
    rays: np.ndarray | None = None
    confidence: float | None = None
    response: np.ndarray | None = None
    response_box: tuple | None = None

    def __post_init__(self):
        for name in ("particles", "weights", "candidates", "rays", "response"):
            object.__setattr__(self, name, _frozen(getattr(self, name)))
        for name in ("box", "search_window", "ellipse", "response_box"):
            v = getattr(self, name)
            if v is not None:
                object.__setattr__(self, name, tuple(float(x) for x in np.ravel(v)))
        if self.confidence is not None:
            object.__setattr__(self, "confidence", float(self.confidence))


@dataclasses.dataclass(frozen=True)
class NoParams:
    """A tracker without tunables."""


class Tracker:
    """Base class of all trackbook trackers.

    A tracker of your own subclasses it, sets ``name`` and ``Params``, implements ``_init``
    and ``_update`` and is decorated with ``@trackbook.trackers.register`` (the appendix
    "Write your own tracker", ``appendix_own_tracker.md``, works one through). The public
    ``init``/``update`` are this class's and are not overridden: they check the input, seed
    the generator and guard the output around the two methods below.

    Writing a subclass
    ------------------
    name : str (class attribute)
        The registry name, unique among the registered trackers (``"lab-color-pf"``):
        ``trackers.create(name)``, ``trackbook bench --trackers name`` and the playground find
        the class by it.
    Params : frozen dataclass (class attribute)
        The tunables, each field made with ``trackbook.params.param(default, lo, hi, step,
        doc, ..., paper=..., why=...)``. ``Tracker(**params)`` checks every value against its
        range and stores the instance as ``self.params`` (read-only); unknown names are
        refused. Without tunables leave the default, an empty dataclass.
    _init(frame, box) -> None
        Called by ``init`` after the checks, once per clip. ``frame`` is an H x W x 3
        ``uint8`` BGR array (as ``cv2.imread`` returns it); ``box`` a float array
        ``(x, y, w, h)`` in pixels, already clipped to the frame, each side >= 1. Build the
        model of the target here and reset every piece of state a previous clip may have
        left: ``init`` can be called again on the same object. ``self.rng`` is a fresh
        ``numpy.random.Generator`` seeded with ``seed`` at every ``init``; draw every random
        number from it, never from ``np.random``, so the same seed and frames give the same
        boxes. The return value is ignored; ``init`` sets ``bbox`` to ``box`` and ``ok`` to
        True afterwards.
    _update(frame) -> (ok, box)
        Called by ``update`` once per frame after the first, with a frame checked to be
        ``uint8`` BGR of the same shape as ``init``'s (``frame_index`` already counts it).
        Return ``ok``, a bool, False while the tracker believes the target is gone (and only
        then), and ``box``, four numbers ``(x, y, w, h)`` in pixels (any sequence or array).
        A box that is NaN, infinite or has a side <= 0 is replaced by the last good box and
        ``ok`` set to False, so return the last box rather than inventing one when lost.
        Treat ``frame`` as read-only: it may be a view of the caller's data.
    _drawn() -> dict
        Optional. The :class:`TrackerState` fields this tracker can draw once started
        (``particles``, ``weights``, ``search_window``, ``ellipse``, ``candidates``,
        ``rays``, ``response`` with ``response_box``), by name; return ``{**super()._drawn(), ...}``. ``state()`` adds them to
        the box and ``ok``; the book's figures, the playground and ``trackbook track``'s
        video draw whatever is there.
    flat_range : int (class attribute, default 2)
        A frame whose values span at most this many grey levels (all black, all white, one
        grey) carries nothing to match; ``self._is_flat(frame)`` tests it, and a tracker
        should report such a frame lost (``ok=False``, last box) rather than score it.

    ``state()`` is public and not meant to be overridden: extend ``_drawn`` instead. For a
    particle filter, subclass
    :class:`trackbook.trackers.particle_filter.ParticleFilterTracker`, whose ``_update`` is
    the whole SIR cycle and which asks for smaller hooks (``model``, ``predict``,
    ``likelihood``, ...).

    Parameters
    ----------
    seed : int or None, keyword only
        Seed of the tracker's own ``numpy.random.Generator``. Same seed and same frames give
        the same boxes. ``Tracker(50)`` raises ``TypeError``: write ``Tracker(seed=50)``.
    **params
        Values for the fields of the tracker's ``Params`` dataclass; the rest keep the
        book's defaults (``trackers.create(name, preset="paper")`` starts from the printed
        values instead).

    Attributes
    ----------
    params : dataclass
        The tunables, as passed or defaulted (read-only).
    bbox : tuple of 4 floats or None
        The last estimate ``(x, y, w, h)``.
    ok : bool
        Whether the last ``update`` believes it is on target.
    frame_index : int
        Number of ``update`` calls since ``init``.
    """

    name: ClassVar[str] = "tracker"
    Params: ClassVar[type] = NoParams
    #: A frame whose values span at most this many grey levels (all black, all white, one
    #: grey) carries no information: trackers report it lost instead of scoring it.
    flat_range: ClassVar[int] = 2
    #: Whether the re-detection layer is on (the ``-redetect`` names, see :func:`redetecting`).
    redetect: ClassVar[bool] = False
    #: Most boxes the re-detection layer scores per lost frame (its cost per frame).
    redetect_boxes: ClassVar[int] = 300

    def __init__(self, *args, seed: int | None = 0, failure: FailureParams | bool = True,
                 **params):
        if args:
            cls = type(self).__name__
            raise positional_seed_error(f"{cls}(seed={args[0]!r})", f"{cls}()")
        check_seed(seed)
        self.seed = seed
        self._params = make_params(self.Params, params)
        if failure is True:
            failure = calibrated_params(self.name)
        elif failure is not False and not isinstance(failure, FailureParams):
            raise TypeError(f"{self.name}: failure={failure!r}; give True (the calibrated "
                            "thresholds), False (no failure layer: the algorithm alone) or a "
                            "trackbook.trackers.failure.FailureParams.")
        #: The failure layer's thresholds, or None when the layer is off (``failure=False``).
        self.failure_params = failure or None
        self.rng = np.random.default_rng(seed)
        self._shape = None
        self.bbox = None
        self.ok = False
        self.frame_index = 0
        self._judged_confidence = None
        self._detector = None

    @property
    def params(self):
        return self._params

    # -- the public contract -------------------------------------------------------------
    def init(self, frame, bbox) -> None:
        """Start tracking the target in ``bbox = (x, y, w, h)`` of ``frame`` (H x W x 3 BGR)."""
        frame = check_frame(frame)
        box = check_box_in_frame(bbox, frame.shape)
        self._shape = frame.shape
        self.rng = np.random.default_rng(self.seed)
        self.frame_index = 0
        self._judged_confidence = None
        self._detector = None if self.failure_params is None else \
            FailureDetector(self.failure_params)
        self._init(frame, box)
        self.bbox = tuple(float(v) for v in box)
        self.ok = True

    def update(self, frame) -> tuple[bool, tuple[float, float, float, float]]:
        """Track into the next frame; return ``(ok, (x, y, w, h))`` as OpenCV does."""
        if self._shape is None:
            raise ValueError(f"{self.name}: call init(frame, bbox) before update(frame).")
        frame = check_frame(frame)
        if frame.shape != self._shape:
            raise ValueError(
                f"{self.name}: frame has shape {frame.shape} but init saw {self._shape}; "
                "all frames of one clip must have the same size (call init again for a new clip)."
            )
        self.frame_index += 1
        if self._in_halves():
            ok, box = self._locate_judge_learn(frame)
        else:
            ok, box = self._update(frame)
        box = np.asarray(box, dtype=float).reshape(4)
        if not np.all(np.isfinite(box)) or box[2] <= 0 or box[3] <= 0:
            # A tracker must never hand a NaN or empty box to the caller: keep the last good one.
            ok, box = False, np.asarray(self.bbox, dtype=float)
        self.bbox = tuple(float(v) for v in box)
        self.ok = bool(ok)
        return self.ok, self.bbox

    # -- the two layers between locating and learning --------------------------------------
    def _in_halves(self) -> bool:
        """Whether this tracker is written as ``_locate`` + ``_learn`` (else ``_update``)."""
        return type(self)._locate is not Tracker._locate

    def _locate_judge_learn(self, frame):
        """One frame of a tracker written in halves: locate -> judge -> learn (or re-detect).

        1. ``_locate`` finds the target near where it was and says how sure it is; a frame
           whose values span at most ``flat_range`` grey levels is lost whatever it says
           (nothing to match), with the layer or without it.
        2. The failure layer judges the confidence against the tracker's own recent ones
           (:class:`~trackbook.trackers.failure.FailureDetector`); a paper's own rule, the
           third value ``_locate`` may return (MOSSE's PSR < 7), can only add a loss, and so
           can a located box less than half inside the frame
           (:func:`~trackbook.trackers.failure.in_view`: the target has left the view) or no
           box at all (NaN or empty: the algorithm found no estimate). The layer judges each
           of these as a frame with no confidence, so, like any loss, it takes ``m`` good
           frames to undo once the layer's reference is warmed up (during its first
           ``warmup`` confident frames such a frame is lost, and the next may be on target).
           A located box past the frame's edge (:func:`~trackbook.trackers.failure.reaches_out`)
           is judged as usual, its confidence kept out of the reference after the warm-up.
        3. On target: ``_learn`` moves the tracker to the box and updates the model. Lost: the
           last box is reported, the model learns nothing, the local search follows its own
           answer (:meth:`_follow`) and, for a ``-redetect`` name only, the whole frame is
           searched with the tracker's own model (:meth:`_redetect`).
        """
        out = self._locate(frame)
        box, conf = out[0], out[1]
        own_ok = bool(out[2]) if len(out) > 2 else True
        conf = float(conf)
        self._judged_confidence = conf
        flat = self._is_flat(frame)
        box = np.asarray(box, dtype=float).reshape(4)
        good = bool(np.all(np.isfinite(box)) and box[2] > 0 and box[3] > 0)
        # A flat frame, no box, a box mostly outside the frame (a target that left across the
        # border cannot be half in a box that is not), or a frame the algorithm's own rule calls
        # lost is judged as one with no confidence (NaN: lost), which never enters the reference.
        seen = good and in_view(box, frame.shape) >= MIN_IN_VIEW
        # Part of what a box past the edge scores is not in the picture; a slow exit would pull
        # the reference toward the background's score. Judged, but kept out of the reference.
        judged = True if self._detector is None else \
            self._detector.step(conf if own_ok and seen and not flat else float("nan"),
                                learn=not (good and reaches_out(box, frame.shape)))
        # The detector calls every frame of its warm-up ok, a NaN one too: the out-of-view
        # rule must still hold there. It is the layer's, so failure=False leaves it out.
        if own_ok and judged and (good if self._detector is None else seen) and not flat:
            self._learn(frame, box)
            return True, box
        if good and not flat:
            self._follow(frame, box)
        if self.redetect:
            self._redetect(frame, box if good and not flat else None)
        return False, np.asarray(self.bbox, dtype=float)

    def _follow(self, frame, box) -> None:
        """Hook: on a lost frame, let the local search start from ``box`` next time, without
        learning (default: :meth:`_relocate` when the tracker has one, else nothing).

        The reported box stays the last one judged on target, but the algorithm keeps
        tracking its best local answer: a target that moved while it was judged lost (a
        false loss, an occluder passing) stays inside the next search window. A tracker
        whose state already moves in ``_locate`` (a particle filter's particles) overrides
        it to do nothing.

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
        if type(self)._relocate is not Tracker._relocate:
            self._relocate(frame, box)

    def _redetect(self, frame, located=None) -> None:
        """The re-detection layer: score boxes of the last size on a grid over the whole frame
        (at most ``redetect_boxes`` of them) and the box the local search just found
        (``located``) with :meth:`_score_boxes`, refine the best on a grid a quarter as fine
        around it (25 boxes), and restart the local search from the best with
        :meth:`_relocate` when it is not the located box. The failure layer still
        decides when the target is found again: the next frames' confidences."""
        if self._is_flat(frame):
            return
        last = np.asarray(self.bbox, dtype=float)
        here = last if located is None else np.asarray(located, dtype=float)
        boxes = np.vstack([here[None], whole_frame_boxes(frame.shape, here[2:],
                                                         self.redetect_boxes)])
        scores = np.asarray(self._score_boxes(frame, boxes), dtype=float)
        if scores.shape != (len(boxes),) or not np.isfinite(scores).any():
            return
        best = int(np.nanargmax(scores))
        if best == 0:
            return
        # a second pass on a grid a quarter as fine around the best: a model with a sharp
        # peak (a HOG match, a correlation response) can score low a few pixels off it
        step = grid_step(frame.shape, self.redetect_boxes) / 4
        d = np.arange(-2, 3) * step
        dx, dy = np.meshgrid(d, d)
        fine = np.tile(boxes[best], (dx.size, 1))
        fine[:, 0] += dx.ravel()
        fine[:, 1] += dy.ravel()
        fine_scores = np.asarray(self._score_boxes(frame, np.vstack([here[None], fine])),
                                 dtype=float)
        if fine_scores.shape == (len(fine) + 1,) and np.isfinite(fine_scores[1:]).any() \
                and np.nanmax(fine_scores[1:]) >= scores[best]:
            self._relocate(frame, fine[int(np.nanargmax(fine_scores[1:]))])
        else:
            self._relocate(frame, boxes[best])

    def state(self) -> TrackerState:
        """What to draw of this tracker after the last frame (see :class:`TrackerState`).

        This base gives the box and ``ok``; after ``init`` it adds the fields of
        :meth:`_drawn`, which trackers with particles, a search window, an ellipse, candidates
        or rays extend, and after the first ``update`` the ``confidence`` of
        :meth:`_last_confidence`.
        """
        st = TrackerState(box=self.bbox, ok=bool(self.ok))
        if self._shape is None:
            return st
        conf = self._last_confidence() if self.frame_index > 0 else None
        return dataclasses.replace(st, confidence=conf, **self._drawn())

    def _last_confidence(self) -> float | None:
        """Hook: the tracker's own confidence in the last estimate.

        Returns
        -------
        float or None
            Larger is surer; None when the tracker has none. A number the last ``update``
            stored, never one computed here, so ``state()`` costs nothing and changes nothing.
            For a tracker written in halves, the confidence ``_locate`` returned.
        """
        return self._judged_confidence

    def _drawn(self) -> dict:
        """The :class:`TrackerState` fields this tracker has once started, by name.

        Returns
        -------
        dict
            Field name -> value, e.g. ``{"particles": ..., "weights": ...}``; only called
            after ``init``. A subclass returns ``{**super()._drawn(), ...}``.
        """
        return {}

    def _is_flat(self, frame: np.ndarray) -> bool:
        """Whether ``frame`` is constant up to ``flat_range`` grey levels (nothing to match).

        Parameters
        ----------
        frame : (H, W, 3) uint8 array

        Returns
        -------
        bool
            True when ``frame.max() - frame.min() <= flat_range``.
        """
        return int(frame.max()) - int(frame.min()) <= self.flat_range

    # -- what subclasses implement ---------------------------------------------------------
    def _locate(self, frame: np.ndarray):  # pragma: no cover
        """Find the target in the next frame, without learning from it (first half of a frame).

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            The next frame, BGR, of the same shape as ``init``'s; read-only by convention.

        Returns
        -------
        box : sequence of 4 floats
            ``(x, y, w, h)`` where the algorithm puts the target.
        confidence : float
            How sure the algorithm is of ``box``, larger is surer, on the algorithm's own
            scale (a peak-to-sidelobe ratio, a Bhattacharyya coefficient, ...); finite on every
            frame. The failure layer judges it.
        own_ok : bool, optional
            A third value, for an algorithm whose paper prints its own failure rule (MOSSE's
            PSR < 7): False reports the frame lost whatever the failure layer says.

        The tracker's state may move (a particle filter's particles), but the model of the
        target and the position the next search starts from change only in :meth:`_learn`
        (on target) or :meth:`_follow` (lost).
        """
        raise NotImplementedError

    def _learn(self, frame: np.ndarray, box: np.ndarray) -> None:  # pragma: no cover
        """Accept ``box`` on a frame judged on target: move there and update the model.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            The frame ``_locate`` just saw.
        box : (4,) float array
            The box ``_locate`` returned.
        """
        raise NotImplementedError

    def _score_boxes(self, frame: np.ndarray, boxes: np.ndarray) -> np.ndarray:  # pragma: no cover
        """For the re-detection layer: how well each box matches the model, larger is better.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
        boxes : (n, 4) float array
            Candidate boxes ``(x, y, w, h)``; the first is the last box.

        Returns
        -------
        (n,) float array
            Only the order matters (the best box is relocated to). Must not change the model.
        """
        raise NotImplementedError(f"{self.name} cannot re-detect: it has no _score_boxes.")

    def _relocate(self, frame: np.ndarray, box: np.ndarray) -> None:  # pragma: no cover
        """For the re-detection layer: restart the local search at ``box`` (no learning)."""
        raise NotImplementedError(f"{self.name} cannot re-detect: it has no _relocate.")

    def _init(self, frame: np.ndarray, box: np.ndarray) -> None:  # pragma: no cover
        """Take the model of the target from the first frame (a subclass implements it).

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            The first frame, BGR, checked by ``init``.
        box : (4,) float array
            The target's box ``(x, y, w, h)`` in pixels, clipped to the frame, sides >= 1.

        Returns
        -------
        None
            ``init`` then sets ``bbox`` to ``box`` and ``ok`` to True. ``self.rng`` has just
            been re-seeded; reset here any state an earlier clip left.
        """
        raise NotImplementedError

    def _update(self, frame: np.ndarray):  # pragma: no cover
        """Track the target into the next frame (a subclass implements it).

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            The next frame, BGR, of the same shape as ``init``'s; read-only by convention.

        Returns
        -------
        ok : bool
            False while the tracker believes the target is gone, True otherwise.
        box : sequence of 4 floats
            ``(x, y, w, h)`` in pixels. A NaN, infinite or empty box is replaced by the last
            good one with ``ok=False`` (see ``update``); while lost, return the last box.
        """
        raise NotImplementedError

    def __repr__(self) -> str:
        return f"{type(self).__name__}(seed={self.seed!r}, params={self.params!r})"


def grid_step(frame_shape, max_boxes: int) -> float:
    """The step, in pixels, of a square grid of at most ``max_boxes`` points over the frame."""
    H, W = frame_shape[:2]
    return max(float(np.sqrt(W * H / max(int(max_boxes), 1))), 1.0)


def whole_frame_boxes(frame_shape, size, max_boxes: int) -> np.ndarray:
    """Boxes of ``size = (w, h)`` centred on a grid over the whole frame, at most ``max_boxes``.

    The grid step is ``sqrt(W H / max_boxes)`` in both directions, so the centres cover the
    frame evenly whatever its shape; a box may stick out of the frame by up to half its size
    (a target at the edge is found too).
    """
    H, W = frame_shape[:2]
    step = grid_step(frame_shape, max_boxes)
    xs = np.arange(step / 2, W, step)
    ys = np.arange(step / 2, H, step)
    X, Y = np.meshgrid(xs, ys)
    w, h = (float(v) for v in size)
    n = X.size
    return np.column_stack([X.ravel() - w / 2, Y.ravel() - h / 2, np.full(n, w),
                            np.full(n, h)])[:max_boxes]


def redetecting(cls: type[Tracker]) -> type[Tracker]:
    """The re-detecting variant of a tracker written in halves: ``<name>-redetect``.

    The same algorithm, the same failure layer and thresholds; while lost, the re-detection
    layer (:meth:`Tracker._redetect`) searches the whole frame with the tracker's own
    appearance model. Register the result to give it its name.
    """
    if not issubclass(cls, Tracker) or type.__getattribute__(cls, "_locate") is Tracker._locate:
        raise TypeError(f"{cls.__name__} is not written as _locate + _learn; only such a "
                        "tracker can take the re-detection layer.")
    doc = (f"{cls.name} with the re-detection layer: while lost, the whole frame is searched "
           f"with its own appearance model (:meth:`Tracker._redetect`).\n\nSee "
           f":class:`{cls.__module__}.{cls.__qualname__}`.")
    return type(f"{cls.__name__}Redetect", (cls,),
                {"name": f"{cls.name}-redetect", "redetect": True, "__doc__": doc,
                 "__module__": cls.__module__})
