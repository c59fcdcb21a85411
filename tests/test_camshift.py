"""CamShift (Bradski 1998): the numpy computation against ``cv2.CamShift`` and against its
definitions, and the ``camshift`` tracker's box, confidence and lost rule.

Oracle: ``cv2.CamShift`` on the same 8-bit probability image, the same start window and the
same termination criteria (COUNT | EPS, 10, 1), with ``window_rule="opencv"``:

- the next window agrees exactly (integer pixels);
- the rotated rect's size agrees to a relative 1e-5 (OpenCV computes in float32 at the end)
  and its angle to 1e-3 degrees, modulo 180;
- OpenCV's returned centre is NOT the centroid: ``camshift.cpp`` sets it to the centre of the
  next window (the centroid rounded to a pixel, the window's side halved in integers, the
  window clipped to the image). Checked as such: OpenCV's centre equals our window's
  ``(x + w / 2, y + h / 2)`` exactly, and our centroid lies within 1 px of it where the
  window is not clipped at the image border.
"""

from __future__ import annotations

import copy

import cv2
import numpy as np
import pytest

from trackbook import clips, trackers
from trackbook.filters import camshift as cs

from .conftest import moving_square_frames

CRIT = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 10, 1)


def _blob(rng, H=120, W=160, noise=10.0):
    """A rotated Gaussian blob of probability (0..255) plus noise, and a start window near it."""
    yy, xx = np.mgrid[0:H, 0:W]
    cx, cy = rng.uniform(10, W - 10), rng.uniform(10, H - 10)
    sa, sb, th = rng.uniform(4, 15), rng.uniform(3, 10), rng.uniform(0, np.pi)
    dx, dy = xx - cx, yy - cy
    u, v = dx * np.cos(th) + dy * np.sin(th), -dx * np.sin(th) + dy * np.cos(th)
    p = 255 * np.exp(-0.5 * ((u / sa) ** 2 + (v / sb) ** 2)) + rng.normal(0, noise, (H, W))
    side = int(rng.integers(12, 40))
    win = (int(cx + rng.uniform(-10, 10) - side / 2), int(cy + rng.uniform(-10, 10) - side / 2),
           side, side)
    return np.clip(p, 0, 255).astype(np.uint8), win


def _agree(prob, win):
    """Assert our opencv-rule CamShift matches cv2.CamShift on ``prob`` from ``win``."""
    (ocx, ocy), (ow, oh), oangle = cv2.CamShift(prob, win, CRIT)[0]
    owin = tuple(cv2.CamShift(prob, win, CRIT)[1])
    r = cs.camshift(prob, win, 10, 1.0, window_rule="opencv")
    assert r.window == owin
    np.testing.assert_allclose(r.size, (ow, oh), rtol=1e-5, atol=1e-4)
    d = abs(r.angle - oangle) % 180.0
    assert min(d, 180.0 - d) < 1e-3
    x, y, w, h = r.window
    assert (ocx, ocy) == (x + w / 2.0, y + h / 2.0)
    H, W = prob.shape
    clipped = x == 0 or y == 0 or x + w == W or y + h == H
    if not clipped:
        assert abs(r.center[0] - ocx) <= 1.0 and abs(r.center[1] - ocy) <= 1.0
    return clipped


def test_agrees_with_opencv_on_generated_blobs():
    rng = np.random.default_rng(0)
    clipped = [_agree(*_blob(rng)) for _ in range(300)]
    assert 0 < sum(clipped) < 300          # both cases were exercised


def test_agrees_with_opencv_on_a_sample_clip_frame():
    clip = clips.load("red-cube")
    f0, box = clip.frames[0], clip.groundtruth[0]
    hist = cs.hue_histogram(f0, box)
    for i in (0, 20, 60):
        prob = cs.back_projection(clip.frames[i], hist)
        x, y, w, h = (int(round(v)) for v in clip.groundtruth[i])
        _agree(prob, (x, y, w, h))
        _agree(prob, (x + 5, y - 4, w, h))


def test_moments_match_opencv():
    rng = np.random.default_rng(1)
    p = rng.integers(0, 256, (50, 70)).astype(np.uint8)
    for x, y, w, h in [(0, 0, 70, 50), (10, 5, 20, 30), (60, 40, 10, 10)]:
        m, o = cs.moments(p, (x, y, w, h)), cv2.moments(p[y:y + h, x:x + w])
        for k in ("m00", "m10", "m01", "mu20", "mu11", "mu02"):
            assert getattr(m, k) == pytest.approx(o[k], rel=1e-9), k


def test_back_projection_matches_calc_back_project():
    """The hue histogram and its back-projection against OpenCV's calcHist/calcBackProject with
    the same saturation/value mask."""
    clip = clips.load("red-cube")
    f, box = clip.frames[0], clip.groundtruth[0]
    bins, s_min, v_min, v_max = 16, 60, 32, 255
    hist = cs.hue_histogram(f, box, bins, s_min, v_min, v_max)
    x, y, w, h = (int(round(v)) for v in box)
    hsv = cv2.cvtColor(f, cv2.COLOR_BGR2HSV)
    mask = cv2.inRange(hsv, (0, s_min, v_min), (180, 255, v_max))
    ref = cv2.calcHist([hsv[y:y + h, x:x + w]], [0], mask[y:y + h, x:x + w], [bins], [0, 180])
    ref = ref.ravel() * 255.0 / ref.max()
    np.testing.assert_allclose(hist, ref, rtol=1e-5)
    bp = cv2.calcBackProject([hsv], [0], np.round(ref).astype(np.float32), [0, 180], 1)
    np.testing.assert_array_equal(cs.back_projection(f, hist, s_min, v_min, v_max), bp & mask)


def test_background_weights_by_hand():
    """A 10 x 10 red box (hue 0) in a ring 10 px wide: 300 of the ring's 800 pixels blue
    (hue 120), 100 green (hue 60), the rest grey (no trusted hue). o* = 100, so blue's bin
    weighs 100 / 300, green's 1, red's (absent from the ring) 1."""
    f = np.full((30, 30, 3), 128, np.uint8)
    f[10:20, 10:20] = (0, 0, 255)
    f[0:10, 0:30] = (255, 0, 0)                        # 300 px of the ring
    f[20:30, 0:10] = (0, 255, 0)                       # 100 px
    v = cs.background_weights(f, (10, 10, 10, 10), bins=6, margin=1.0)
    # 6 bins of 30 hue units (OpenCV's hue is 0..179): red in bin 0, green 2, blue 4
    np.testing.assert_allclose(v, [1, 1, 1, 1, 100 / 300, 1])


def test_orientation_and_axes_of_a_hand_made_ellipse():
    """A filled ellipse of half-axes 20 and 8 at 30 degrees (the pixels whose centre lies
    inside): its standard deviations are a / 2 and b / 2 (a uniform ellipse has variance
    a^2 / 4 along an axis), so the rect's sides 4 sigma are 40 and 16 and the long axis is at
    30 degrees (OpenCV's angle 90 + 30 = 120)."""
    yy, xx = np.mgrid[0:120, 0:160] - np.array([60, 80])[:, None, None]
    th = np.radians(30)
    u, v = xx * np.cos(th) + yy * np.sin(th), -xx * np.sin(th) + yy * np.cos(th)
    p = np.where((u / 20) ** 2 + (v / 8) ** 2 <= 1, 255, 0).astype(np.uint8)
    r = cs.camshift(p, (50, 40, 60, 40), window_rule="bradski")
    assert r.size[1] == pytest.approx(40, rel=0.03) and r.size[0] == pytest.approx(16, rel=0.05)
    assert r.angle == pytest.approx(120, abs=1.0)
    assert r.center == pytest.approx((80, 60), abs=0.1)


def test_orientation_of_a_vertical_bar_names_the_long_axis():
    """A 3 x 16 bar of 255 standing upright: mu11 = 0 and mu20 < mu02, where the half-angle
    form atan2(2b, a - c + root) is atan2(0, 0) = 0. The long axis is the y axis (90 degrees)
    and the deviations are those of 16 rows and 3 columns, sqrt((n^2 - 1) / 12)."""
    p = np.zeros((20, 20), np.uint8)
    p[2:18, 8:11] = 255
    theta, s_l, s_w = cs.orientation(cs.moments(p, (0, 0, 20, 20)))
    assert np.degrees(theta) == pytest.approx(90)
    assert s_l == pytest.approx(np.sqrt((16 ** 2 - 1) / 12))
    assert s_w == pytest.approx(np.sqrt((3 ** 2 - 1) / 12))
    # OpenCV reports the same bar as a rect of sides 4 sigma_w x 4 sigma_l at angle 0
    (_, (w, h), angle), _ = cv2.CamShift(p, (0, 0, 20, 20), (3, 10, 1))
    assert (w, h) == pytest.approx((4 * s_w, 4 * s_l), rel=1e-5) and angle == 0


def test_bradski_window_side_is_two_sqrt_m00_over_256():
    """A uniform 255 square of side 20 inside the window: M00 = 255 * 400, so the next side is
    round(2 sqrt(255 * 400 / 256)) = round(39.92) = 40, centred on the square."""
    p = np.zeros((120, 160), np.uint8)
    p[50:70, 70:90] = 255
    r = cs.camshift(p, (62, 42, 30, 30), window_rule="bradski")
    assert r.m00 == 255 * 400
    assert r.window == (60, 40, 40, 40)
    assert cs.camshift(p, (62, 42, 30, 30), window_rule="bradski", aspect=1.2).window[3] == 48


def test_nothing_under_the_window():
    r = cs.camshift(np.zeros((40, 50), np.uint8), (5, 5, 10, 10))
    assert r.m00 == 0 and np.isnan(r.center[0]) and r.window == (5, 5, 10, 10)
    with pytest.raises(ValueError, match="window_rule"):
        cs.camshift(np.zeros((40, 50), np.uint8), (5, 5, 10, 10), window_rule="intel")


# -- the tracker ------------------------------------------------------------------------------
def _square_frames(n=8):
    # grey levels 90..110 per channel: saturation at most 20 / 110 of 255 = 46, below s_min,
    # so the background puts nothing in the back-projection
    return moving_square_frames(n, size=(160, 120), side=24, grey=(90, 111), top=40, left=20,
                                step=5, colour=(20, 30, 220))


def test_tracker_follows_and_fills_its_state():
    frames, box0 = _square_frames()
    t = trackers.create("camshift")
    t.init(frames[0], box0)
    for k, f in enumerate(frames[1:], 1):
        ok, box = t.update(f)
        assert ok
        # the square moves 5 px a frame; a red square on grey is the only hue there
        assert box[0] + box[2] / 2 == pytest.approx(20 + 5 * k + 12, abs=1.0)
        assert box[2] == pytest.approx(24, rel=0.1)
    st = t.state()
    cx, cy, hx, hy, angle = st.ellipse
    assert (cx, cy) == pytest.approx((box[0] + box[2] / 2, box[1] + box[3] / 2))
    # a uniform 24 x 24 square: sigma = 24 / sqrt(12), half-axes 2 sigma = 13.9
    assert hx == pytest.approx(24 / np.sqrt(12) * 2, rel=0.05)
    x, y, w, h = st.search_window
    assert w == pytest.approx(2 * np.sqrt(255 * 24 * 24 / 256), abs=1.0)


def test_confidence_is_m00_relative_to_the_first_frame():
    """Recomputed with OpenCV: cv2.calcBackProject of the same histogram, cv2.meanShift from the
    window the tracker searched from, cv2.moments over the converged window."""
    clip = clips.load("red-cube")
    t = trackers.create("camshift")
    t.init(clip.frames[0], clip.groundtruth[0])
    hsv0 = cv2.cvtColor(clip.frames[0], cv2.COLOR_BGR2HSV)
    lut = np.round(np.asarray(t.hist)).astype(np.float32)

    def prob(f):
        hsv = cv2.cvtColor(f, cv2.COLOR_BGR2HSV)
        mask = cv2.inRange(hsv, (0, 60, 32), (180, 255, 255))
        return cv2.calcBackProject([hsv], [0], lut, [0, 180], 1) & mask

    def m00(p, win):
        x, y, w, h = cv2.meanShift(p, win, CRIT)[1]
        return cv2.moments(p[y:y + h, x:x + w])["m00"]

    assert hsv0 is not None
    x, y, w, h = (int(round(v)) for v in clip.groundtruth[0])
    first = m00(prob(clip.frames[0]), (x, y, w, h))
    for f in clip.frames[1:10]:
        win = tuple(int(v) for v in t.state().search_window)
        ok, _ = t.update(f)
        assert ok
        assert t.state().confidence == pytest.approx(m00(prob(f), win) / first, rel=1e-9)


def test_lost_keeps_the_last_box_and_finds_it_again():
    frames, box0 = _square_frames(16)
    grey = [f.copy() for f in frames]
    for f in grey[7:11]:                      # the square is painted over with background grey
        f[:] = np.random.default_rng(1).integers(90, 111, f.shape, dtype=np.uint8)
    t = trackers.create("camshift")
    # six frames on the square first: the layer's reference is warmed up before the loss
    assert t.failure_params.warmup <= 6
    t.init(grey[0], box0)
    boxes = [t.update(f) for f in grey[1:]]
    last = boxes[5][1]
    for ok, box in boxes[6:10]:
        assert not ok and box == last
        assert t.state().confidence is not None
    # the square is back from frame 11: the failure layer believes it after m frames in a row
    m = t.failure_params.m
    assert [ok for ok, _ in boxes[10:]] == [False] * (m - 1) + [True] * (len(boxes) - 9 - m)
    ok, box = boxes[13]                       # frame 14, the box on the square
    assert ok and box[0] + box[2] / 2 == pytest.approx(20 + 5 * 14 + 12, abs=1.0)


def test_a_loss_during_the_layers_warm_up_ends_on_the_first_frame_back():
    """The same, with the square gone after three frames: the layer's reference holds fewer
    than ``warmup`` confidences, so the frames without a target are reported lost (no box)
    but the layer has not declared a loss, and the first frame with the square is on
    target at once (README, "What `ok` promises")."""
    frames, box0 = _square_frames(12)
    grey = [f.copy() for f in frames]
    for f in grey[4:8]:
        f[:] = np.random.default_rng(1).integers(90, 111, f.shape, dtype=np.uint8)
    t = trackers.create("camshift")
    assert t.failure_params.warmup > 3
    t.init(grey[0], box0)
    boxes = [t.update(f) for f in grey[1:]]
    last = boxes[2][1]
    assert all(not ok and box == last for ok, box in boxes[3:7])
    assert all(ok for ok, _ in boxes[7:])
    ok, box = boxes[10]                       # frame 11, the box on the square
    assert ok and box[0] + box[2] / 2 == pytest.approx(20 + 5 * 11 + 12, abs=1.0)


def test_scale_follows_the_target():
    """The square doubles its side: M00 quadruples, the box's side doubles."""
    rng = np.random.default_rng(0)
    frames = []
    for side in (20, 24, 28, 32, 36, 40):
        f = rng.integers(90, 111, (120, 160, 3), dtype=np.uint8)
        f[60 - side // 2:60 + side // 2, 80 - side // 2:80 + side // 2] = (20, 30, 220)
        frames.append(f)
    t = trackers.create("camshift")
    t.init(frames[0], (70, 50, 20, 20))
    for f in frames[1:]:
        ok, box = t.update(f)
    assert ok and box[2] == pytest.approx(40, rel=0.05)


def _model(t):
    return [np.array(t.hist, copy=True), np.array(t.window, float)]


def test_locate_has_no_side_effect_on_the_model():
    frames, box0 = _square_frames(4)
    t = trackers.create("camshift")
    t.init(frames[0], box0)
    t.update(frames[1])
    before = _model(t)
    u = copy.deepcopy(t)
    a, b = u._locate(frames[2]), u._locate(frames[2])
    np.testing.assert_array_equal(a[0], b[0])
    assert a[1] == b[1] and np.isfinite(a[1])
    for m0, m1 in zip(before, _model(u)):
        np.testing.assert_array_equal(m0, m1)


def test_a_lost_frame_does_not_change_the_model():
    frames, box0 = _square_frames(8)
    t = trackers.create("camshift")
    t.init(frames[0], box0)
    for f in frames[1:6]:
        t.update(f)
    before, box = _model(t), t.bbox
    ok, _ = t.update(np.full_like(frames[0], 100))
    assert not ok and t.bbox == box and np.isfinite(t.state().confidence)
    for m0, m1 in zip(before, _model(t)):
        np.testing.assert_array_equal(m0, m1)


def test_redetect_finds_a_target_that_jumped_across_the_frame():
    """tests/_jump.py: the canonical name loses the target at A and stays lost there;
    ``camshift-redetect`` restarts the window on the densest box and tracks it at B (the box's
    size follows M00, so only its overlap with B's box is asked)."""
    from ._jump import A, iou, jump
    clip, box_b = jump()
    for name in ("camshift", "camshift-redetect"):
        t = trackers.create(name, seed=0)
        t.init(clip.frames[0], clip.groundtruth[0])
        oks = [t.update(f)[0] for f in clip.frames[1:]]
        box = np.asarray(t.bbox)
        if name == "camshift":
            centre = box[:2] + box[2:] / 2
            assert not any(oks[15:]) and np.allclose(centre, np.add(A, (12, 15)), atol=3)
        else:
            assert all(oks[-5:]) and iou(box, box_b) > 0.5, (oks, box)

