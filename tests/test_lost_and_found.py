"""A tracker says when the target is gone and finds it again.

On :func:`trackbook.clips.synthetic.leave_and_return` (the target drifts right, is out of view
for 18 frames, and reappears 88 px to the left of where it left) every tracker must answer
``ok=False`` on most of the absent frames, and have IoU > 0.5 with the target again within 10
frames of its return.
"""

from __future__ import annotations

import numpy as np
import pytest

import trackbook
from trackbook import trackers
from trackbook.clips.synthetic import leave_and_return
from trackbook.evaluation import metrics

N_BEFORE, N_ABSENT, N_AFTER = 12, 18, 20

# Trackers that do not pass yet (none since the distance gate and the whole-frame search;
# kept so a regression can be marked while it is being fixed).
PENDING: set = set()


def _names(pending=PENDING):
    return [pytest.param(n, marks=pytest.mark.xfail(reason="not yet met",
                                                    strict=False))
            if n in pending else n for n in trackers.available(reference=False)]


@pytest.fixture(scope="module")
def clip():
    return leave_and_return(N_BEFORE, N_ABSENT, N_AFTER)


def _run(name, clip):
    r = trackbook.evaluate(name, clip, seed=0)
    return r.ok, r.boxes


@pytest.mark.parametrize("name", _names())
def test_lost_while_absent_then_found(name, clip):
    oks, boxes = _run(name, clip)
    assert oks[1:N_BEFORE].mean() > 0.5, f"{name} lost the target before it left"
    absent = oks[N_BEFORE:N_BEFORE + N_ABSENT]
    assert absent.mean() < 0.5, f"{name} says ok=True on {absent.sum()} of {N_ABSENT} " \
        "frames without the target"
    iou = metrics.iou(boxes, clip.groundtruth)[N_BEFORE + N_ABSENT:]
    assert np.any(iou[:10] > 0.5), f"{name} did not find the target within 10 frames of its " \
        f"return (IoU {np.round(iou[:10], 2)})"


@pytest.mark.parametrize("name", _names())
@pytest.mark.parametrize("value", [0, 255], ids=["black", "white"])
def test_black_and_white_frames_are_lost(name, value, clip):
    t = trackers.create(name, seed=0)
    t.init(clip.frames[0], clip.groundtruth[0])
    t.update(clip.frames[1])
    ok, b = t.update(np.full_like(clip.frames[0], value))
    assert ok is False
    assert np.all(np.isfinite(b)) and b[2] > 0 and b[3] > 0
