"""Frames that carry no information are reported lost (issue 13).

Every tracker is started on a textured frame (the ``red-cube`` sample) and then shown an
all-black, an all-white and a constant grey frame: each must answer ``ok=False`` with a finite,
non-empty box. Identical black frames must not make the covariance trackers walk with
``ok=True`` (a singular covariance carries no information).
"""

from __future__ import annotations

import numpy as np
import pytest

from trackbook import clips, trackers

NAMES = trackers.available()


@pytest.fixture(scope="module")
def start():
    c = clips.load("red-cube")
    frames = [f for _, f in zip(range(4), c.frames)]
    return frames, c.groundtruth[0]


def test_eleven_trackers():
    assert len(NAMES) == 11


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("value", [0, 255, 128], ids=["black", "white", "grey"])
def test_blank_frame_is_lost(name, value, start):
    frames, box = start
    t = trackers.create(name)
    t.init(frames[0], box)
    for f in frames[1:]:
        t.update(f)                         # a few normal frames first
    blank = np.full_like(frames[0], value)
    for _ in range(3):
        ok, b = t.update(blank)
        assert ok is False, f"{name} says ok=True on a constant frame of {value}"
        assert np.all(np.isfinite(b)) and b[2] > 0 and b[3] > 0


@pytest.mark.parametrize("name", ["covariance", "kalman-covariance"])
def test_identical_black_frames_do_not_walk_with_ok(name):
    frame = np.zeros((120, 160, 3), np.uint8)
    first = frame.copy()
    first[40:70, 60:90] = (30, 180, 220)       # a textured target on the first frame only
    first[50:60, 70:80] = (200, 20, 20)
    t = trackers.create(name)
    t.init(first, (60, 40, 30, 30))
    for _ in range(10):
        ok, b = t.update(frame)
        assert ok is False
        assert np.all(np.isfinite(b)) and b[2] > 0 and b[3] > 0


def test_optional_self_likelihood_rule(start):
    """With ``lost_fraction`` set, a frame whose best particle scores below that fraction of
    the reference's score against itself is lost; a normal next frame is not."""
    frames, box = start
    t = trackers.create("color-pf")
    t.lost_fraction = 1e-3
    t.init(frames[0], box)
    ok, _ = t.update(frames[1])
    assert ok and t.best_ratio > t.lost_fraction
    t.lost_fraction = 1.01            # nothing can beat the reference by 1 %
    ok, _ = t.update(frames[2])
    assert not ok and t.best_ratio < 1.01
