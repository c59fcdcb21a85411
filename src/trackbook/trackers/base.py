"""The contract every tracker keeps: OpenCV's ``init(frame, bbox)`` / ``update(frame)``.

Subclasses implement ``_init(frame, box)`` and ``_update(frame) -> (ok, box)`` only. This class
owns everything that must be the same for all eleven trackers: the params dataclass, the seeded
``numpy.random.Generator`` (re-created on every ``init`` so a re-run repeats exactly), the input
checks that refuse bad input naming a fix, and the last line of defence against a NaN or empty box.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np

from .._checks import check_box_in_frame, check_frame, check_seed
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
    """

    box: tuple | None = None
    ok: bool = False
    particles: np.ndarray | None = None
    weights: np.ndarray | None = None
    search_window: tuple | None = None
    ellipse: tuple | None = None
    candidates: np.ndarray | None = None
    rays: np.ndarray | None = None

    def __post_init__(self):
        for name in ("particles", "weights", "candidates", "rays"):
            object.__setattr__(self, name, _frozen(getattr(self, name)))
        for name in ("box", "search_window", "ellipse"):
            v = getattr(self, name)
            if v is not None:
                object.__setattr__(self, name, tuple(float(x) for x in np.ravel(v)))


@dataclasses.dataclass(frozen=True)
class NoParams:
    """A tracker without tunables."""


class Tracker:
    """Base class of all trackbook trackers.

    Parameters
    ----------
    seed : int or None
        Seed of the tracker's own ``numpy.random.Generator``. Same seed and same frames give
        the same boxes.
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

    def __init__(self, seed: int | None = 0, **params):
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
        or rays extend.
        """
        st = TrackerState(box=self.bbox, ok=bool(self.ok))
        return st if self._shape is None else dataclasses.replace(st, **self._drawn())

    def _drawn(self) -> dict:
        """The :class:`TrackerState` fields this tracker has once started, by name; a subclass
        returns ``{**super()._drawn(), ...}``."""
        return {}

    def _is_flat(self, frame: np.ndarray) -> bool:
        """Whether ``frame`` is constant up to ``flat_range`` grey levels (nothing to match)."""
        return int(frame.max()) - int(frame.min()) <= self.flat_range

    # -- what subclasses implement ---------------------------------------------------------
    def _init(self, frame: np.ndarray, box: np.ndarray) -> None:  # pragma: no cover
        raise NotImplementedError

    def _update(self, frame: np.ndarray):  # pragma: no cover
        raise NotImplementedError

    def __repr__(self) -> str:
        return f"{type(self).__name__}(seed={self.seed!r}, params={self.params!r})"
