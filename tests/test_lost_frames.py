"""Frames that carry no information are reported lost, and so are boxes mostly out of view.

Every tracker is started on a textured frame (the ``red-cube`` sample) and then shown an
all-black, an all-white and a constant grey frame: each must answer ``ok=False`` with a finite,
non-empty box. Identical black frames must not make the covariance trackers walk with
``ok=True`` (a singular covariance carries no information).
"""

from __future__ import annotations

import numpy as np
import pytest

from trackbook import clips, trackers
from trackbook.evaluation import metrics
from trackbook.trackers.failure import MIN_IN_VIEW, FailureParams, in_view

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


def _in_view_by_pixels(box, shape):
    """The share of an integer box's pixels inside the frame, counted one by one."""
    x, y, w, h = (int(v) for v in box)
    inside = sum(0 <= i < shape[1] and 0 <= j < shape[0]
                 for i in range(x, x + w) for j in range(y, y + h))
    return inside / (w * h)


@pytest.mark.parametrize("box,share", [((0, 0, 10, 10), 1.0), ((-10, 0, 20, 10), 0.5),
                                       ((95, 95, 10, 10), 0.25), ((100, 0, 5, 5), 0.0),
                                       ((-3, -4, 10, 8), 0.35)])
def test_in_view_by_hand(box, share):
    assert in_view(box, (100, 100, 3)) == pytest.approx(share)
    assert in_view(box, (100, 100, 3)) == pytest.approx(_in_view_by_pixels(box, (100, 100)))


def test_a_box_less_than_half_in_view_never_overlaps_a_target_in_view_by_more_than_half():
    """The bound behind the out-of-view rule: for a target box inside the frame, IoU <= the
    share of the tracker's box in view, so a box found less than half in view is never on
    target."""
    rng = np.random.default_rng(0)
    shape = (120, 160, 3)
    b = np.column_stack([rng.uniform(-60, 180, 2000), rng.uniform(-60, 140, 2000),
                         rng.uniform(2, 80, 2000), rng.uniform(2, 80, 2000)])
    g = np.column_stack([rng.uniform(0, 100, 2000), rng.uniform(0, 70, 2000),
                         rng.uniform(2, 60, 2000), rng.uniform(2, 50, 2000)])
    g[:, 2] = np.minimum(g[:, 2], shape[1] - g[:, 0])
    g[:, 3] = np.minimum(g[:, 3], shape[0] - g[:, 1])
    v = np.array([in_view(x, shape) for x in b])
    iou = metrics.iou(b, g)
    assert np.all(iou <= v + 1e-12)
    assert (v < MIN_IN_VIEW).sum() > 100 and (v >= MIN_IN_VIEW).sum() > 100


class _Leaving(trackers.Tracker):
    """A tracker written in halves whose box walks 8 px right each frame, always sure of it."""

    name = "test-leaving"

    def _init(self, frame, box):
        self._box = np.asarray(box, float)

    def _locate(self, frame):
        return self._box + (8, 0, 0, 0), 1.0

    def _learn(self, frame, box):
        self._box = np.asarray(box, float)

    def _relocate(self, frame, box):
        self._box = np.asarray(box, float)


def test_a_box_that_leaves_during_the_warm_up_is_lost_too_and_not_learned():
    """The detector calls the first ``warmup`` frames ok whatever they score; a box that is
    out of view by then is still lost, and the tracker does not move to it."""
    frame = np.random.default_rng(1).integers(0, 256, (60, 80, 3), dtype=np.uint8)
    t = _Leaving(failure=FailureParams(warmup=5))
    t.init(frame, (50, 20, 20, 20))
    oks, reported = [], []
    for _ in range(6):
        ok, box = t.update(frame)
        oks.append(ok)
        reported.append(box[0])
    # found at x = 58 (all in view), 66 (0.7 of it), then 74 (0.3), 82, ...: out of view
    # on the third frame, two frames before the reference holds five values
    assert oks == [True, True] + [False] * 4
    assert reported == [58.0, 66.0] + [66.0] * 4   # the last box judged on target


@pytest.mark.parametrize("failure", [True, False], ids=["layer", "no-layer"])
def test_a_box_that_leaves_the_frame_is_lost_once_less_than_half_is_in_view(failure):
    frame = np.random.default_rng(1).integers(0, 256, (60, 80, 3), dtype=np.uint8)
    t = _Leaving(failure=FailureParams() if failure else False)
    t.init(frame, (22, 20, 20, 20))
    shares, oks = [], []
    for _ in range(12):
        ok, _ = t.update(frame)
        shares.append(in_view(t._box, frame.shape))
        oks.append(ok)
    shares, oks = np.array(shares), np.array(oks)
    # after update k the box is at x = 30 + 8 k: in view up to k = 3, half out at k = 5
    assert shares[3] == 1.0 and shares[5] == 0.5 and shares[6] < 0.5
    if failure:
        assert oks[:6].all() and not oks[6:].any()
    else:
        assert oks.all()                    # the algorithm alone: the rule belongs to the layer


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
