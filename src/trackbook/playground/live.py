"""The Jupyter playground's run, frame by frame: a knob change answers with the frames up to
the one on screen, then the rest of the clip streams in chunks while the kernel stays free.

A :class:`LiveRun` steps one tracker through a clip exactly as
:func:`trackbook.evaluation.evaluate` does (``init`` on the first frame, then ``update`` on
each next one, the same tracker made by name with the same seed), so its finished boxes are
``evaluate``'s boxes; it only lets the caller stop between frames and look at what is done.
:func:`stream` drives one on the kernel's event loop.
"""

from __future__ import annotations

import asyncio
import dataclasses
import time

import numpy as np

from .._checks import as_box, clip_box
from ..evaluation import metrics
from ..evaluation.runner import Result, _init_foreign, _make, _n_frames
from . import data as D

#: longest stretch of tracking between two yields to the kernel's loop (seconds): a slider
#: drag or a newer knob change is read within this
CHUNK_S = 0.03
#: the first answer goes out when the frame on screen is tracked or after this long (seconds),
#: whichever comes first, so a reader at the end of a long clip still sees the run start
FIRST_S = 0.12
#: shortest time between two partial payloads (seconds): each carries every frame done so far
SEND_EVERY_S = 0.25


class LiveRun:
    """One tracker over one clip, advanced a few frames at a time.

    Parameters
    ----------
    tracker : registered tracker name
    clip : a loaded :class:`~trackbook.clips.Clip`
    values : the tracker's params (as :func:`trackbook.evaluation.evaluate` takes them)
    n : frames to track (None: the whole clip)
    seed : the tracker's seed
    init_box : (x, y, w, h) on the first frame, or None for the first ground-truth box

    Raises
    ------
    ValueError
        A knob combination the tracker refuses, or a clip without a first box.
    """

    def __init__(self, tracker: str, clip, values: dict, n: int | None, seed: int = 0,
                 init_box=None):
        self.name, self.clip, self.seed = tracker, clip, seed
        self.values = dict(values)
        self.n_total = _n_frames(clip, n)
        self.tracker = _make(tracker, seed, dict(values))[0]
        self._frames = iter(clip.frames)
        self._first = next(self._frames)
        box0 = clip.groundtruth[0] if init_box is None else as_box(init_box, name="init_box")
        if not np.all(np.isfinite(box0)):
            raise ValueError(f"clip {clip.name!r} has no ground-truth box on frame 0; give "
                             "the target's first box (init_box=(x, y, w, h)).")
        self._box0 = clip_box(box0, self._first.shape)
        self.boxes = np.full((self.n_total, 4), np.nan)
        self.ok = np.zeros(self.n_total, dtype=bool)
        self.ms = np.zeros(self.n_total)
        self.states: list[dict] = []
        self.n_done = 0

    @property
    def done(self) -> bool:
        return self.n_done >= self.n_total

    def step(self) -> None:
        """Track one more frame (``init`` on frame 0, ``update`` after), as the evaluation
        loop does, and keep what the viewer draws of the tracker's state."""
        i = self.n_done
        t0 = time.perf_counter()
        if i == 0:
            _init_foreign(self.tracker, self._first, self._box0)
            self.boxes[0], self.ok[0] = self._box0, True
            self._first = None          # hold only the current frame
        else:
            good, box = self.tracker.update(next(self._frames))
            self.boxes[i], self.ok[i] = np.asarray(box, dtype=float), bool(good)
        self.ms[i] = (time.perf_counter() - t0) * 1e3
        self.states.append(D.snapshot(self.tracker.state()))
        self.n_done = i + 1
        if self.done:
            self.close()

    def advance(self, until: int | None = None, seconds: float | None = None) -> None:
        """Step until ``until`` frames are done (all if None) or ``seconds`` have passed
        (at least one frame is tracked either way, unless the run is done)."""
        stop = self.n_total if until is None else min(int(until), self.n_total)
        t_end = None if seconds is None else time.perf_counter() + seconds
        while not self.done:
            self.step()
            if self.n_done >= stop or (t_end is not None and time.perf_counter() >= t_end):
                break

    def close(self) -> None:
        """Free what the tracker holds (e.g. opencv-mil's child process), as ``evaluate``
        does after its loop; a stale run cancelled midway is closed too."""
        close = getattr(self.tracker, "close", None)
        if callable(close):
            close()

    def result(self) -> Result:
        """The finished run as :func:`trackbook.evaluation.evaluate` returns it (same boxes,
        ``ok`` flags and scores; the milliseconds are this run's own)."""
        if not self.done:
            raise ValueError(f"the run has {self.n_done} of {self.n_total} frames; finish it "
                             "(advance()) before asking for its result.")
        gt = self.clip.groundtruth[:self.n_total]
        try:
            scores = metrics.summary(self.boxes[1:], gt[1:])
        except ValueError:      # no ground truth (a user's video without annotation)
            scores = {}
        scores["ms_median"] = float(np.median(self.ms[1:]))
        scores["ms_mean"] = float(np.mean(self.ms[1:]))
        p = getattr(self.tracker, "params", None)
        return Result(self.name, self.clip.name, self.boxes.copy(), self.ok.copy(),
                      self.ms.copy(), scores,
                      params=dataclasses.asdict(p) if dataclasses.is_dataclass(p) else {})

    def payload(self) -> dict:
        """What the viewer draws: the run payload of :mod:`trackbook.playground.data` for the
        frames done so far, with ``n_done`` and ``n_total`` (``n_done < n_total``: partial)."""
        k = self.n_done
        if self.done:
            scores = D.scores_text(self.result())
        else:
            scores = f"{self.name} on {self.clip.name}: running\u2026 {k}/{self.n_total} frames"
        return D.payload(self.clip, self.name, self.values, self.boxes[:k], self.ok[:k],
                         scores, self.states[:k], self.n_total)


def running_loop():
    """The running event loop (the kernel's, in Jupyter), or None (plain Python)."""
    try:
        return asyncio.get_running_loop()
    except RuntimeError:
        return None


async def stream(run: LiveRun, send, frame: int = 0, alive=lambda: True,
                 refused=None) -> None:
    """Drive ``run`` on the running event loop: the frames up to ``frame`` (the one on
    screen) first, or :data:`FIRST_S` of tracking if that comes sooner, then ``send`` a
    partial payload; then chunks of :data:`CHUNK_S`, yielding to the loop between chunks
    (so the kernel reads the next message) and sending a partial payload at most every
    :data:`SEND_EVERY_S`; the complete payload last. Stops, sending nothing more, as soon as
    ``alive()`` is false (a newer knob change) or the task is cancelled. A ``ValueError``
    raised by the tracker while running goes to ``refused(error)`` when given."""
    try:
        await _stream(run, send, frame, alive)
    except ValueError as e:
        if refused is None:
            raise
        if alive():
            refused(e)


async def _stream(run, send, frame, alive):
    try:
        run.advance(until=max(int(frame), 0) + 1, seconds=FIRST_S)
        if not alive():
            return
        if not run.done:
            send(run.payload())
        last = time.perf_counter()
        while not run.done:
            await asyncio.sleep(0)
            if not alive():
                return
            run.advance(seconds=CHUNK_S)
            if not run.done and time.perf_counter() - last >= SEND_EVERY_S:
                send(run.payload())
                last = time.perf_counter()
    finally:
        if not run.done:
            run.close()
    send(run.payload())
