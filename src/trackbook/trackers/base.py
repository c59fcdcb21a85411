"""The contract every tracker keeps: OpenCV's ``init(frame, bbox)`` / ``update(frame)``.

Subclasses implement ``_init(frame, box)`` and ``_update(frame) -> (ok, box)`` only. This class
owns everything that must be the same for every tracker: the params dataclass, the seeded
``numpy.random.Generator`` (re-created on every ``init`` so a re-run repeats exactly), the input
checks that refuse bad input naming a fix, and the last line of defence against a NaN or empty box.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np

from .._checks import check_box_in_frame, check_frame, check_seed, positional_seed_error
from ..params import make_params


def readonly_attr(name: str, doc: str | None = None) -> property:
    """A property giving a read-only view of ``self.<name>`` (see :func:`readonly`)."""
    return property(lambda self: readonly(getattr(self, name)), doc=doc)


def readonly(a) -> np.ndarray:
    """A read-only view of ``a``: trackers expose their state for drawings, never for editing."""
    v = np.asarray(a).view()
    v.flags.writeable = False
    return v


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

    def __post_init__(self):
        for name in ("particles", "weights", "candidates", "rays"):
            object.__setattr__(self, name, _frozen(getattr(self, name)))
        for name in ("box", "search_window", "ellipse"):
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
        ``rays``), by name; return ``{**super()._drawn(), ...}``. ``state()`` adds them to
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

    def __init__(self, *args, seed: int | None = 0, **params):
        if args:
            cls = type(self).__name__
            raise positional_seed_error(f"{cls}(seed={args[0]!r})", f"{cls}()")
        check_seed(seed)
        self.seed = seed
        self._params = make_params(self.Params, params)
        self.rng = np.random.default_rng(seed)
        self._shape = None
        self.bbox = None
        self.ok = False
        self.frame_index = 0

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
        ok, box = self._update(frame)
        box = np.asarray(box, dtype=float).reshape(4)
        if not np.all(np.isfinite(box)) or box[2] <= 0 or box[3] <= 0:
            # A tracker must never hand a NaN or empty box to the caller: keep the last good one.
            ok, box = False, np.asarray(self.bbox, dtype=float)
        self.bbox = tuple(float(v) for v in box)
        self.ok = bool(ok)
        return self.ok, self.bbox

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
        """
        return None

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
