"""Frames that carry no information are reported lost.

Every tracker is started on a textured frame (the ``red-cube`` sample) and then shown an
all-black, an all-white and a constant grey frame: each must answer ``ok=False`` with a finite,
non-empty box. Identical black frames must not make the covariance trackers walk with
``ok=True`` (a singular covariance carries no information).
"""

from __future__ import annotations

import numpy as np
import pytest

from trackbook import clips, trackers

NAMES = trackers.available(reference=False)


@pytest.fixture(scope="module")
def start():
    c = clips.load("red-cube")
    frames = [f for _, f in zip(range(4), c.frames)]
    return frames, c.groundtruth[0]


def test_every_registered_tracker():
    # the four papers' eleven, the book's kalman-covariance-manoeuvre, the correlation filters
    # mosse and kcf, dsst, staple, bacf, camshift and median-flow (and the -redetect variant
    # of each)
    assert len([n for n in NAMES if not n.endswith("-redetect")]) == 19


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


LIGHT_FAILING = {(True, 0.4): "the layer (ratio_lost = 0.5) calls the darkened cube lost: its "
                             "HSI match falls from about 0.99 to 0.36"}


@pytest.mark.parametrize("gain,present", [
    pytest.param(g, p, marks=[pytest.mark.xfail(strict=True, reason=LIGHT_FAILING[p, g])]
                 if (p, g) in LIGHT_FAILING else [], id=f"{'present' if p else 'covered'}-{g}")
    for p in (True, False) for g in (0.4, 2.2)])
def test_hsi_colour_keeps_a_target_under_a_change_of_light(gain, present):
    """hsi-color-pf under the failure-detection layer: a light change multiplies every pixel
    by ``gain`` (the HSI intensity bins move, hue and saturation do not), so the cube, still
    there, matches its first-frame histogram poorly, yet it is the target (ok=True). With the
    cube covered by the gravel three box widths to its right, the same change of light is lost
    (ok=False): gravel is not a red cube."""
    from trackbook.features.color import bhattacharyya_coefficient
    from trackbook.features.hsi import hsi_histograms

    c = clips.load("red-cube")
    frames = [f for _, f in zip(range(11), c.frames)]
    gt = c.groundtruth
    frame = frames[10].copy()
    if not present:
        x, y, w, h = (int(round(v)) for v in gt[10])
        frame[y - 8:y + h + 8, x - 8:x + w + 8] = \
            frames[10][y - 8:y + h + 8, x - 8 + 3 * w:x + w + 8 + 3 * w]
    changed = np.clip(np.rint(frame * float(gain)), 0, 255).astype(np.uint8)
    # the premise, from the histograms alone: under the new light the cube's own box matches
    # below 0.7
    ref = hsi_histograms(frames[0], gt[0][None])
    assert bhattacharyya_coefficient(hsi_histograms(changed, gt[10][None]), ref)[0] < 0.7
    t = trackers.create("hsi-color-pf", seed=0)
    t.init(frames[0], gt[0])
    assert all(t.update(f)[0] for f in frames[1:10])
    ok, box = t.update(changed)
    assert ok is present
    assert np.all(np.isfinite(box))
