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
from trackbook.trackers.failure import (MIN_IN_VIEW, FailureDetector, FailureParams, in_view,
                                        reaches_out)

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


def test_a_frame_stepped_without_learning_is_judged_but_kept_out_of_the_reference():
    """By hand: after 10, 11, 10, 11, 10 (median 10, MAD 0, so the spread is
    1.2533 x mean|c - 10| = 1.2533 x 0.4 = 0.5013) the lost level is 10 - 4 x 0.5013 = 7.995.
    A 9 is on target either way; learned, it enters the reference, whose spread becomes
    1.4826 x median(0, 1, 0, 1, 0, 1) = 1.4826 x 0.5 = 0.7413 and the lost level
    10 - 4 x 0.7413 = 7.035; not learned, the reference is as it was. A 7.5 is then lost only
    if the 9 was not learned."""
    p = FailureParams(k_lost=4, k_found=1, m=2, window=10, warmup=3)
    for learn, expected in [(True, (10.0, 0.7413)), (False, (10.0, 0.5013))]:
        d = FailureDetector(p)
        assert all(d.step(v) for v in [10, 11, 10, 11, 10])
        assert d.step(9, learn=learn) is True
        assert d.reference == pytest.approx(expected, abs=1e-4), learn
        assert d.step(7.5) is learn


def test_frames_of_the_warm_up_enter_the_reference_even_unlearned():
    """A reference must exist before it can be kept clean: a target that starts across the
    border would otherwise never warm the layer up, and no frame of it could be lost."""
    d = FailureDetector(FailureParams(k_lost=4, k_found=1, m=2, window=10, warmup=3))
    assert all(d.step(v, learn=False) for v in [10, 11, 10])
    assert len(d._ref) == 3
    assert d.step(10, learn=False) and len(d._ref) == 3
    assert d.step(2, learn=False) is False


def test_a_frame_that_ends_a_loss_unlearned_stays_out_of_the_reference():
    """A target coming back across the edge: the frame that ends the loss is stepped with
    ``learn=False`` and must not enter the reference either (m = 1: one frame ends it)."""
    d = FailureDetector(FailureParams(k_lost=4, k_found=1, m=1, window=10, warmup=3))
    assert all(d.step(v) for v in [10, 11, 10, 11, 10])
    assert d.step(2) is False
    assert d.step(10.5, learn=False) is True
    assert list(d._ref) == [10, 11, 10, 11, 10]
    assert d.step(10.5) is True and list(d._ref) == [10, 11, 10, 11, 10, 10.5]


def test_a_box_flush_with_the_edge_by_arithmetic_does_not_reach_out():
    """x = cx - w/2 with cx = W - w/2 lands a rounding error past the edge for many widths;
    a millionth of a pixel is rounding, a thousandth is reaching out."""
    W, H = 320, 240
    widths = np.random.default_rng(0).uniform(1, 100, 2000)
    xs = (W - widths / 2) - widths / 2
    assert np.any(xs + widths > W)                       # the rounding does happen
    assert not any(reaches_out((x, 100, w, 40), (H, W, 3)) for x, w in zip(xs, widths))
    assert all(reaches_out((x + 1e-3, 100, w, 40), (H, W, 3)) for x, w in zip(xs, widths))
    assert reaches_out((-1e-3, 0, 10, 10), (H, W, 3)) and reaches_out((0, -1e-3, 10, 10), (H, W, 3))


@pytest.mark.parametrize("box,out", [
    ((64.05920704482398, 27.70888466262316, 3.0077026728735397, 1.8098541408979256), False),
    ((0.0, 0.0, 200.0, 200.0), False), ((-0.5, 10, 20, 20), True), ((10, -0.5, 20, 20), True),
    ((180.5, 10, 20, 20), True), ((10, 180.5, 20, 20), True)])
def test_reaches_out_compares_edges_not_a_share_in_view(box, out):
    """The first box lies well inside a 200 x 200 frame, yet its share in view, computed in
    floating point, is a rounding error short of 1: "reaches out" must not be ``in_view < 1``."""
    assert reaches_out(box, (200, 200, 3)) is out
    if box[0] > 60:
        assert in_view(box, (200, 200, 3)) < 1


class _Scripted(trackers.Tracker):
    """A tracker written in halves that finds the boxes and confidences it is given."""

    name = "test-scripted"

    def _init(self, frame, box):
        self._script = iter(self.script)

    def _locate(self, frame):
        return next(self._script)

    def _learn(self, frame, box):
        pass


@pytest.mark.parametrize("x", [40.0, 62.0], ids=["inside", "past-the-right-edge"])
def test_a_slow_fall_across_the_edge_does_not_lower_the_reference(x):
    """Five frames at 10 and 11, then the confidence falls by 0.1 a frame from 10 to 5 with
    the box inside the frame or reaching 2 px past its right edge (0.9 of it in view); lost
    below 0.7 of the reference's median. Inside, each value enters the reference and the lost
    level sinks with it (the median is 6.45 at the end): no frame is lost. Past the edge the
    median stays 10, and the first value under 7 (6.9) is lost."""
    frame = np.random.default_rng(2).integers(0, 256, (60, 80, 3), dtype=np.uint8)
    t = _Scripted(failure=FailureParams(k_lost=np.inf, k_found=np.inf, ratio_lost=0.7,
                                        ratio_found=0.8, m=2, window=30, warmup=5))
    inside = np.array([40.0, 20.0, 20.0, 20.0])
    fall = np.round(10 - 0.1 * np.arange(51), 1)                       # 10, 9.9, ..., 5
    t.script = [(inside, c) for c in (10, 11, 10, 11, 10)] + [
        (np.array([x, 20, 20, 20]), c) for c in fall]
    t.init(frame, inside)
    oks = np.array([t.update(frame)[0] for _ in range(len(t.script))])
    median = t._detector.reference[0]
    if x == 40.0:
        assert oks.all() and median == pytest.approx(6.45)
    else:
        assert in_view((x, 20, 20, 20), frame.shape) == pytest.approx(0.9)
        assert oks[:5].all() and fall[np.flatnonzero(~oks[5:])[0]] == 6.9
        assert median == 10.0


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
