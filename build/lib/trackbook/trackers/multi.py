"""Several targets at once, each with its own tracker and model (Cho & Kang 2005 §5.3).

>>> from trackbook import clips
>>> from trackbook.trackers import MultiTracker
>>> clip = clips.load("two-faces")                                       # doctest: +SKIP
>>> mt = MultiTracker("condensation-mean-shift", seed=0)                 # doctest: +SKIP
>>> mt.init(clip.frames[0], [clip.targets["face1"][0], clip.targets["face2"][0]])  # doctest: +SKIP
>>> oks, boxes = mt.update(clip.frames[1])                               # doctest: +SKIP

The paper tracks the two crossing faces with independent trackers (one colour model each, no
joint reasoning about occlusion), which is what :class:`MultiTracker` does: target ``k`` gets a
tracker of the same name and params, seeded with a seed derived deterministically from
``(seed, k)`` so that two targets never share a random stream and a re-run repeats exactly.
"""

from __future__ import annotations

import time

import numpy as np

from .._checks import check_frame, clip_box


def target_seed(seed, k: int):
    """The seed of target ``k`` of a multi-tracker seeded ``seed`` (``None`` stays ``None``)."""
    if seed is None:
        return None
    return int(np.random.SeedSequence([int(seed), int(k)]).generate_state(1)[0])


class MultiTracker:
    """One tracker per target, all of one registered name, updated frame by frame.

    Parameters
    ----------
    name : a registered tracker name (``trackers.available(reference=True)``)
    seed : int or None; target ``k`` uses :func:`target_seed` ``(seed, k)``
    **params : the trackers' params (the same for every target)

    Attributes
    ----------
    trackers : list of the per-target trackers (read their ``particles``, ``ellipse``, ...)
    boxes : list of the last boxes; oks : list of the last ``ok`` flags
    """

    def __init__(self, name: str, seed: int | None = 0, **params):
        from . import create, get

        get(name)  # fail early, with the list of names, on a typo
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


def track_clip(name: str, clip, seed: int | None = 0, max_frames: int | None = None,
               targets=None, **params) -> dict:
    """Track every annotated target of ``clip`` at once; ``{target: (N, 4) boxes}``.

    This is what ``trackbook track NAME CLIP --all-targets`` runs. Each target starts from its
    first ground-truth box; frame 0 of every array is that box.

    Parameters
    ----------
    name : registered tracker name; clip : anything ``trackbook.clips.load`` accepts
    seed : the multi-tracker's seed; max_frames : track only the first frames
    targets : optional list of target names (default: all of ``clip.targets``)
    **params : the trackers' params

    Returns
    -------
    dict target -> (N, 4) float array of boxes; the per-frame milliseconds of the whole
    multi-target update are under the key ``"_ms"`` (an (N,) array, frame 0 = init) and each
    target's ``ok`` flags under ``"_ok"`` (a dict target -> (N,) bool array).
    """
    from .. import clips as _clips

    clip = _clips.load(clip)
    names = list(clip.targets) if targets is None else list(targets)
    unknown = [t for t in names if t not in clip.targets]
    if unknown:
        raise ValueError(f"clip {clip.name!r} has no target(s) {unknown}; "
                         f"its targets are {list(clip.targets)}.")
    if max_frames is not None and (isinstance(max_frames, bool) or not isinstance(
            max_frames, (int, np.integer)) or max_frames < 1):
        raise ValueError(f"max_frames = {max_frames!r}: pass an integer of at least 1 (frame 0 "
                         "is the one the trackers start from), or None for the whole clip.")
    n = len(clip) if max_frames is None else min(int(max_frames), len(clip))
    first = clip.frames[0]
    starts = []
    for t in names:
        b = np.asarray(clip.targets[t][0], dtype=float)
        if not np.all(np.isfinite(b)):
            raise ValueError(f"target {t!r} of clip {clip.name!r} has no box on frame 0.")
        starts.append(clip_box(b, first.shape))
    mt = MultiTracker(name, seed=seed, **params)
    out = {t: np.full((n, 4), np.nan) for t in names}
    oks = {t: np.ones(n, dtype=bool) for t in names}
    ms = np.zeros(n)
    t0 = time.perf_counter()
    mt.init(first, starts)
    ms[0] = (time.perf_counter() - t0) * 1e3
    for t, b in zip(names, starts):
        out[t][0] = b
    for i, frame in enumerate(clip.frames):
        if i == 0:
            continue
        if i >= n:
            break
        t0 = time.perf_counter()
        flags, boxes = mt.update(frame)
        ms[i] = (time.perf_counter() - t0) * 1e3
        for t, b, ok in zip(names, boxes, flags):
            out[t][i] = b
            oks[t][i] = ok
    out["_ms"] = ms
    out["_ok"] = oks
    return out
