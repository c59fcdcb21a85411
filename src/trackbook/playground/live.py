"""The Jupyter playground's run, frame by frame: a knob change answers with the frames up to
the one on screen, then the rest of the clip streams in chunks while the kernel stays free.

A :class:`LiveRun` is the evaluation's own run loop (:class:`trackbook.evaluation.runner.Run`)
over one tracker, stepped a few frames at a time, so its finished boxes are
:func:`~trackbook.evaluation.evaluate`'s boxes; it adds what the viewer draws of the tracker's
state after each frame. :func:`stream` drives one on the kernel's event loop.
"""

from __future__ import annotations

import asyncio
import time

from ..evaluation import runner
from ..evaluation.runner import Result, Run
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
        self.states: list[dict] = []
        self._run = Run([(tracker, seed, dict(values))], clip, max_frames=n, init_box=init_box,
                        on_frame=self._keep_state)
        self.tracker = self._run.trackers[0]
        self.n_total = self._run.n_total

    def _keep_state(self, i, tracker, frame, box) -> None:
        # inside the loop's step, before the run frees the tracker after its last frame
        self.states.append(D.snapshot(tracker.state()))

    @property
    def n_done(self) -> int:
        return self._run.n_done

    @property
    def done(self) -> bool:
        return self._run.done

    def step(self) -> None:
        """Track one more frame through the run loop, keeping what the viewer draws of the
        tracker's state."""
        self._run.step()

    def advance(self, until: int | None = None, seconds: float | None = None) -> None:
        """Step until ``until`` frames are done (all if None) or ``seconds`` have passed
        (at least one frame is tracked either way, unless the run is done)."""
        runner.advance(self, until, seconds)    # through this run's own step()

    def close(self) -> None:
        """Free what the tracker holds (e.g. opencv-mil's child process); the run does it
        after its last frame, and a stale run cancelled midway is closed here."""
        self._run.close()

    def result(self) -> Result:
        """The finished run as :func:`trackbook.evaluation.evaluate` returns it (same boxes,
        ``ok`` flags and scores; the milliseconds are this run's own)."""
        return self._run.results()[0]

    def payload(self) -> dict:
        """What the viewer draws: the run payload of :mod:`trackbook.playground.data` for the
        frames done so far, with ``n_done`` and ``n_total`` (``n_done < n_total``: partial)."""
        k = self.n_done
        if self.done:
            scores = D.scores_text(self.result())
        else:
            scores = f"{self.name} on {self.clip.name}: running\u2026 {k}/{self.n_total} frames"
        return D.payload(self.clip, self.name, self.values, self._run.boxes[0, :k],
                         self._run.ok[0, :k], scores, self.states[:k], self.n_total)


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
