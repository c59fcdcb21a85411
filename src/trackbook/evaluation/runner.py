"""Run a tracker over a clip and score it: ``trackbook.evaluate`` (one target, or one tracker
per target with ``targets=``), all through one loop, :class:`Run`, which the Jupyter
playground steps a few frames at a time."""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from .. import clips as _clips
from .. import trackers as _trackers
from .._checks import as_box, check_max_frames, clip_box
from .._memory import keep_freed_memory
from ..trackers.multi import target_seed
from . import metrics


@dataclasses.dataclass
class Result:
    """One run of one tracker over one clip.

    Attributes
    ----------
    tracker, clip : names
    boxes : (N, 4) array, frame 0 is the initial box
    ok : (N,) bool, the tracker's own ``ok`` per frame (frame 0 True)
    ms : (N,) milliseconds per frame (frame 0 is ``init``); decoding excluded
    scores : dict of the OTB scores over frames 1..N-1 (see :func:`metrics.summary`),
        plus ``ms_median`` and ``ms_mean`` over the ``update`` calls
    params : dict of the tracker's params (empty for foreign trackers)
    extras : per-frame values a tracker chose to report (e.g. ``search_rate``)
    """

    tracker: str
    clip: str
    boxes: np.ndarray
    ok: np.ndarray
    ms: np.ndarray
    scores: dict
    params: dict = dataclasses.field(default_factory=dict)
    extras: dict = dataclasses.field(default_factory=dict)

    def curves(self, gt):
        """``(success_thresholds, success, precision_thresholds, precision)`` over frames 1..N-1."""
        ts, s = metrics.success_curve(self.boxes[1:], gt[1:])
        tp, p = metrics.precision_curve(self.boxes[1:], gt[1:])
        return ts, s, tp, p


@dataclasses.dataclass
class MultiResult:
    """One tracker per target over one clip, as Cho & Kang 2005 §5.3 track two faces:
    ``trackbook.evaluate(name, clip, targets="all")``.

    Attributes
    ----------
    tracker, clip : names
    results : dict target -> :class:`Result` of that target's tracker (its boxes, ``ok``
        flags, milliseconds, and scores against that target's own ground truth)
    ms : (N,) milliseconds per frame of all the targets' updates together (frame 0: ``init``)
    scores : ``ms_median`` and ``ms_mean`` of ``ms`` over the ``update`` calls
    """

    tracker: str
    clip: str
    results: dict
    ms: np.ndarray
    scores: dict

    @property
    def boxes(self) -> dict:
        """target -> (N, 4) boxes (frame 0 is the target's first ground-truth box)."""
        return {k: r.boxes for k, r in self.results.items()}

    @property
    def ok(self) -> dict:
        """target -> (N,) the tracker's own ``ok`` flags."""
        return {k: r.ok for k, r in self.results.items()}


def _make(name_or_tracker, seed, params, preset="book"):
    if isinstance(name_or_tracker, str):
        return (_trackers.create(name_or_tracker, seed=seed, preset=preset, **params),
                name_or_tracker)
    if params or preset != "book":
        raise ValueError("params can only be given with a tracker name, not a tracker object "
                         "(and so can preset).")
    t = name_or_tracker
    if not (hasattr(t, "init") and hasattr(t, "update")):
        raise ValueError(
            f"{t!r} is not a tracker: pass a registered name ({', '.join(_trackers.available())}) "
            "or an object with OpenCV's init(frame, bbox) / update(frame) methods."
        )
    return t, getattr(t, "name", type(t).__name__)


def _init_foreign(t, frame, box):
    # OpenCV's trackers take integer boxes; ours take floats.
    if type(t).__module__.startswith("cv2"):
        x, y, w, h = (int(round(v)) for v in box)
        return t.init(frame, (x, y, max(w, 1), max(h, 1)))
    return t.init(frame, tuple(float(v) for v in box))


def evaluate(name_or_tracker, clip, seed: int | None = 0, max_frames: int | None = None,
             init_box=None, on_frame=None, preset: str = "book", targets=None,
             **params) -> Result | MultiResult:
    """Track a clip from its first ground-truth box and score it (frame 0 excluded).

    Parameters
    ----------
    name_or_tracker : str or tracker object
        A registered name (``trackers.available(reference=True)``) or any object with
        OpenCV's ``init``/``update``, e.g. ``cv2.TrackerMIL_create()``.
    clip : Clip or str or path
        Anything :func:`trackbook.clips.load` accepts.
    seed : int, the tracker's seed (names only).
    max_frames : int, optional; track only the first frames.
    init_box : (x, y, w, h), optional; default the first ground-truth box (clipped to the frame).
    on_frame : callable(i, tracker, frame, box), optional; called after every frame, e.g. to
        record particles for a drawing.
    preset : ``"book"`` (the book's defaults) or ``"paper"`` (the printed method; see
        :func:`trackbook.trackers.departures`), names only; ``params`` override either.
    targets : ``"all"`` or a list of target names of ``clip.targets``, optional: track several
        targets at once, one tracker of this name per target (seeded
        :func:`~trackbook.trackers.multi.target_seed` ``(seed, k)``, as
        :class:`~trackbook.trackers.MultiTracker` does), each from its first ground-truth box,
        and return a :class:`MultiResult` (names only; not with ``init_box``).
    **params : the tracker's params (names only).
    """
    if targets is not None:
        return _evaluate_targets(name_or_tracker, clip, seed, max_frames, init_box, on_frame,
                                 preset, targets, params)
    return evaluate_many([(name_or_tracker, seed, params)], clip, max_frames=max_frames,
                         init_box=init_box, on_frame=on_frame, preset=preset)[0]


def evaluate_many(runs, clip, max_frames: int | None = None, init_box=None, on_frame=None,
                  preset: str = "book") -> list[Result]:
    """Several trackers over one clip in lockstep: each frame is decoded once and given to
    every tracker, so a benchmark decodes a clip once for all its trackers while holding only
    the current frame (memory stays bounded however long the clip).

    ``runs`` is a list of ``(name_or_tracker, seed, params)``; the results, in that order, are
    exactly what :func:`evaluate` gives for each run alone (the trackers share nothing but the
    read-only frame). ``on_frame`` is called as ``on_frame(i, tracker, frame, box)`` for each.
    """
    run = Run(runs, clip, max_frames=max_frames, init_box=init_box, on_frame=on_frame,
              preset=preset)
    run.advance()
    return run.results()


def _n_frames(clip, max_frames) -> int:
    """The number of frames to track (``max_frames`` checked by the one check)."""
    max_frames = check_max_frames(max_frames)
    n = len(clip) if max_frames is None else min(int(max_frames), len(clip))
    if n < 2:
        raise ValueError(f"clip {clip.name!r} needs at least 2 frames to evaluate.")
    return n


def advance(run, until: int | None = None, seconds: float | None = None) -> None:
    """Step ``run`` (anything with ``step()``, ``done``, ``n_done`` and ``n_total``: a
    :class:`Run`, or the playground's live run around one) until ``until`` frames are done
    (all if None) or ``seconds`` have passed; at least one frame is tracked either way,
    unless the run is done."""
    stop = run.n_total if until is None else min(int(until), run.n_total)
    t_end = None if seconds is None else time.perf_counter() + seconds
    while not run.done:
        run.step()
        if run.n_done >= stop or (t_end is not None and time.perf_counter() >= t_end):
            break


class Run:
    """The one run loop: trackers over one clip in lockstep, one frame at a time.

    :func:`evaluate` and :func:`evaluate_many` step a run to its end at once; the Jupyter
    playground steps one a few frames at a time between knob changes. Either way each tracker
    gets ``init`` on the first frame and ``update`` on each next one, so the boxes are the same.

    Parameters
    ----------
    runs : list of ``(name_or_tracker, seed, params)``
    clip : Clip or str or path, anything :func:`trackbook.clips.load` accepts
    max_frames : int, optional; track only the first frames
    init_box : (x, y, w, h), optional; every run's first box (default the first ground-truth
        box, clipped to the frame)
    on_frame : callable(i, tracker, frame, box), optional; called after every frame
    preset : ``"book"`` or ``"paper"`` (trackers made by name)
    targets : list of target names of ``clip.targets``, optional, one per run: run ``j``
        starts from the first box of target ``j`` and is scored against that target
        (not with ``init_box``)

    Attributes
    ----------
    trackers : the trackers, in the order of ``runs``
    n_total : frames to track; ``n_done`` : frames tracked so far
    boxes : (k, n_total, 4), ``ok`` : (k, n_total), ``ms`` : (k, n_total) milliseconds of
        ``init``/``update`` alone (decoding excluded), filled up to ``n_done``
    """

    def __init__(self, runs, clip, max_frames: int | None = None, init_box=None,
                 on_frame=None, preset: str = "book", targets=None):
        # glibc's thresholds raised once per process before the trackers allocate, so their
        # per-frame temporaries reuse memory (``TRACKBOOK_KEEP_MEMORY=0``: off); see _memory
        keep_freed_memory()
        self.clip = clip = _clips.load(clip)
        made = [_make(t, seed, dict(params or {}), preset) for t, seed, params in runs]
        self.trackers = [t for t, _ in made]
        self._names = [name for _, name in made]
        self._ours = [isinstance(r[0], str) for r in runs]
        self.n_total = n = _n_frames(clip, max_frames)
        self._frames = iter(clip.frames)
        self._frame = next(self._frames)
        if targets is None:
            box0 = clip.groundtruth[0] if init_box is None else as_box(init_box,
                                                                        name="init_box")
            if not np.all(np.isfinite(box0)):
                raise ValueError(
                    f"clip {clip.name!r} has no ground-truth box on frame 0; give the "
                    "target's first box: init_box=(x, y, w, h) in Python, --box x,y,w,h on the "
                    "command line (or a <video stem>.groundtruth.txt file beside the video)."
                )
            self._starts = [clip_box(box0, self._frame.shape)] * len(made)
            self._gts = [clip.groundtruth[:n]] * len(made)
        else:
            self._starts = []
            for t in targets:
                b = np.asarray(clip.targets[t][0], dtype=float)
                if not np.all(np.isfinite(b)):
                    raise ValueError(f"target {t!r} of clip {clip.name!r} has no box on "
                                     "frame 0.")
                self._starts.append(clip_box(b, self._frame.shape))
            self._gts = [np.asarray(clip.targets[t][:n], dtype=float) for t in targets]
        k = len(made)
        self.boxes = np.full((k, n, 4), np.nan)
        self.ok = np.zeros((k, n), dtype=bool)
        self.ms = np.zeros((k, n))
        self._extras: list[dict[str, list]] = [{} for _ in made]
        self._on_frame = on_frame
        self.n_done = 0
        self._closed = False

    @property
    def done(self) -> bool:
        """Every frame is tracked."""
        return self.n_done >= self.n_total

    def step(self) -> int:
        """Track the next frame with every tracker (``init`` on frame 0, ``update`` after);
        return its index. The run frees its trackers after the last frame."""
        if self.done:
            raise ValueError(f"the run has tracked all its {self.n_total} frames.")
        i = self.n_done
        frame = self._frame if i == 0 else next(self._frames)
        self._frame = None              # hold only the current frame
        for j, tracker in enumerate(self.trackers):
            t0 = time.perf_counter()
            if i == 0:
                _init_foreign(tracker, frame, self._starts[j])
                self.ms[j, 0] = (time.perf_counter() - t0) * 1e3
                self.boxes[j, 0], self.ok[j, 0] = self._starts[j], True
            else:
                good, box = tracker.update(frame)
                self.ms[j, i] = (time.perf_counter() - t0) * 1e3
                self.boxes[j, i], self.ok[j, i] = np.asarray(box, dtype=float), bool(good)
                report = getattr(tracker, "frame_report", None)
                if callable(report):
                    for key, v in report().items():
                        self._extras[j].setdefault(key, [np.nan] * self.n_total)[i] = v
            if self._on_frame is not None:
                self._on_frame(i, tracker, frame, self.boxes[j, i])
        self.n_done = i + 1
        if self.done:
            self.close()
        return i

    def advance(self, until: int | None = None, seconds: float | None = None) -> None:
        """Step until ``until`` frames are done (all if None) or ``seconds`` have passed
        (at least one frame is tracked either way, unless the run is done)."""
        advance(self, until, seconds)

    def close(self) -> None:
        """Free what the trackers made by name hold (e.g. opencv-mil's child process); done
        after the last frame, and by whoever stops a run midway."""
        if self._closed:
            return
        self._closed = True
        for tracker, ours in zip(self.trackers, self._ours):
            close = getattr(tracker, "close", None)
            if ours and callable(close):
                close()

    def results(self) -> list[Result]:
        """The finished run: one :class:`Result` per tracker, in the order of ``runs``."""
        if not self.done:
            raise ValueError(f"the run has {self.n_done} of {self.n_total} frames; finish it "
                             "(advance()) before asking for its result.")
        results = []
        for j, tracker in enumerate(self.trackers):
            try:
                scores = metrics.summary(self.boxes[j, 1:], self._gts[j][1:])
            except ValueError:  # no ground truth (a user's video without annotation)
                scores = {}
            scores["ms_median"] = float(np.median(self.ms[j, 1:]))
            scores["ms_mean"] = float(np.mean(self.ms[j, 1:]))
            p = getattr(tracker, "params", None)
            results.append(Result(
                self._names[j], self.clip.name, self.boxes[j].copy(), self.ok[j].copy(),
                self.ms[j].copy(), scores,
                params=dataclasses.asdict(p) if dataclasses.is_dataclass(p) else {},
                extras={key: np.asarray(v) for key, v in self._extras[j].items()}))
        return results


def _evaluate_targets(name, clip, seed, max_frames, init_box, on_frame, preset, targets,
                      params) -> MultiResult:
    """``evaluate(..., targets=...)``: one tracker per target through the one loop."""
    if not isinstance(name, str):
        raise ValueError("targets= tracks several targets with trackers made by name; pass a "
                         "registered tracker name, not a tracker object.")
    if init_box is not None:
        raise ValueError("init_box starts one target; with targets= every target starts from "
                         "its first ground-truth box (leave init_box out).")
    clip = _clips.load(clip)
    names = list(clip.targets) if isinstance(targets, str) and targets == "all" else targets
    if isinstance(names, str) or not names:
        raise ValueError(f"targets = {targets!r}: pass 'all' or a list of target names of clip "
                         f"{clip.name!r} ({', '.join(clip.targets) or 'it has none'}).")
    names = list(names)
    unknown = [t for t in names if t not in clip.targets]
    if unknown:
        raise ValueError(f"clip {clip.name!r} has no target(s) {unknown}; "
                         f"its targets are {list(clip.targets)}.")
    runs = [(name, target_seed(seed, k), dict(params)) for k in range(len(names))]
    run = Run(runs, clip, max_frames=max_frames, on_frame=on_frame, preset=preset,
              targets=names)
    run.advance()
    results = run.results()
    ms = np.sum([r.ms for r in results], axis=0)
    return MultiResult(name, clip.name, dict(zip(names, results)), ms,
                       {"ms_median": float(np.median(ms[1:])), "ms_mean": float(np.mean(ms[1:]))})
