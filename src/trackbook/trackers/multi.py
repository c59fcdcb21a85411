"""Several targets at once, each with its own tracker and model (Cho & Kang 2005 §5.3).

>>> from trackbook import clips
>>> from trackbook.trackers import MultiTracker
>>> clip = clips.load("two-faces")                                       # doctest: +SKIP
>>> mt = MultiTracker("condensation-mean-shift", seed=0)                 # doctest: +SKIP
>>> mt.init(clip.frames[0], [clip.targets["face1"][0], clip.targets["face2"][0]])  # doctest: +SKIP
>>> oks, boxes = mt.update(clip.frames[1])                               # doctest: +SKIP

The paper tracks several targets [quote: cho2005.multi_tracking] but does not say how it ran
its trackers on them. :class:`MultiTracker` runs independent trackers (one colour model each,
no joint reasoning about occlusion), the book's choice: target ``k`` gets a
tracker of the same name and params, seeded with a seed derived deterministically from
``(seed, k)`` so that two targets never share a random stream and a re-run repeats exactly.
To run it over a clip and score every target, use
``trackbook.evaluate(name, clip, targets="all")`` (the same trackers, the same seeds).
"""

from __future__ import annotations

import numpy as np

from .._checks import check_frame, clip_box, positional_seed_error
from ..params import make_params
from .registry import create, get


def target_seed(seed, k: int):
    """The seed of target ``k`` of a multi-tracker seeded ``seed`` (``None`` stays ``None``)."""
    if seed is None:
        return None
    return int(np.random.SeedSequence([int(seed), int(k)]).generate_state(1)[0])


class MultiTracker:
    """One tracker per target, all of one registered name, updated frame by frame.

    Parameters
    ----------
    name : a tracker name (``trackers.available()``)
    seed : int or None, keyword only; target ``k`` uses :func:`target_seed` ``(seed, k)``
    **params : the trackers' params (the same for every target), checked here: a typo or a
        value out of range raises ``ValueError`` when the multi-tracker is made

    Attributes
    ----------
    trackers : list of the per-target trackers (read their ``particles``, ``ellipse``, ...)
    boxes : list of the last boxes; oks : list of the last ``ok`` flags
    """

    def __init__(self, name: str, *args, seed: int | None = 0, **params):
        if args:
            raise positional_seed_error(f"MultiTracker({name!r}, seed={args[0]!r})",
                                        "MultiTracker()")
        # fail early, with the list of names or the valid params, on a typo
        make_params(get(name).Params, dict(params))
        self.name, self.seed, self._params = name, seed, dict(params)
        self._create = create
        self.trackers: list = []
        self.boxes: list = []
        self.oks: list = []

    def init(self, frame, boxes) -> None:
        """Start one tracker per box of ``boxes`` (a list of ``(x, y, w, h)``) on ``frame``."""
        frame = check_frame(frame)
        boxes = list(boxes)
        if not boxes:
            raise ValueError("MultiTracker.init needs at least one box; pass [box1, box2, ...].")
        self.trackers = [self._create(self.name, seed=target_seed(self.seed, k), **self._params)
                         for k in range(len(boxes))]
        for t, b in zip(self.trackers, boxes):
            t.init(frame, b)
        self.boxes = [tuple(float(v) for v in clip_box(b, frame.shape)) for b in boxes]
        self.oks = [True] * len(boxes)

    def update(self, frame):
        """Track every target into ``frame``; returns ``(oks, boxes)``, lists in target order."""
        if not self.trackers:
            raise ValueError("MultiTracker: call init(frame, [box1, box2, ...]) before update.")
        out = [t.update(frame) for t in self.trackers]
        self.oks = [bool(ok) for ok, _ in out]
        self.boxes = [tuple(float(v) for v in b) for _, b in out]
        return self.oks, self.boxes

    def frame_report(self) -> dict:
        """The mean over targets of each number the per-target trackers report."""
        reports = [t.frame_report() for t in self.trackers if hasattr(t, "frame_report")]
        keys = set().union(*reports) if reports else set()
        return {k: float(np.mean([r[k] for r in reports if k in r])) for k in keys}

    def __len__(self) -> int:
        return len(self.trackers)
