"""OpenCV's MIL behind trackbook: repeatable within one process, never hung by a tiny box."""

import numpy as np
import pytest

import trackbook
from trackbook import trackers
from trackbook.clips.clip import ArrayFrames, Clip
from trackbook.trackers.reference import MIN_FRAME, safe_box


def _clip(n=12, size=(120, 160), box=(60, 40, 20, 16)):
    rng = np.random.default_rng(3)
    H, W = size
    frames, gt = [], []
    x, y, w, h = box
    for i in range(n):
        f = rng.integers(0, 60, (H, W, 3), dtype=np.uint8)
        xi = int(x + 2 * i)
        f[y:y + h, xi:xi + w] = (0, 0, 230)
        frames.append(f)
        gt.append((xi, y, w, h))
    return Clip("mil-test", ArrayFrames(np.stack(frames)), np.asarray(gt, float))


def test_two_runs_in_one_process_give_identical_boxes():
    c = _clip()
    a = trackbook.evaluate("opencv-mil", c)
    b = trackbook.evaluate("opencv-mil", c)
    np.testing.assert_array_equal(a.boxes, b.boxes)


def test_frame_by_frame_equals_evaluate():
    c = _clip()
    ref = trackbook.evaluate("opencv-mil", c).boxes
    t = trackers.create("opencv-mil")
    frames = list(c.frames)
    t.init(frames[0], tuple(c.groundtruth[0]))
    boxes = [c.groundtruth[0]] + [t.update(f)[1] for f in frames[1:]]
    np.testing.assert_array_equal(np.asarray(boxes, float), ref)


@pytest.mark.parametrize("box", [(60, 40, 4, 4), (60, 40, 1, 1), (0, 0, 160, 120),
                                 (2, 2, 156, 116)])
def test_boxes_that_hang_or_assert_in_opencv_are_adjusted(box):
    c = _clip(n=4, box=(60, 40, 4, 4))
    r = trackbook.evaluate("opencv-mil", c, init_box=box)
    assert np.all(np.isfinite(r.boxes))


def test_safe_box_limits():
    assert safe_box((10, 10, 4, 4), (100, 100, 3))[2:] == (6, 6)
    x, y, w, h = safe_box((0, 0, 100, 100), (100, 100, 3))
    assert w <= 92 and h <= 92 and x >= 0 and y >= 0
    with pytest.raises(ValueError, match="at least"):
        safe_box((1, 1, 5, 5), (MIN_FRAME - 1, 40, 3))
