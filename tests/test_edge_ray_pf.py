"""edge-ray-pf and its baselines (Kim, Kim & Choi 2016) on small scenes built here."""

import numpy as np
import pytest

from trackbook import clips, metrics, trackers
from trackbook.features.hsi import bgr_to_hsi, hsi_bin_index, hsi_histograms

H, W, S = 120, 160, 32  # frame height, width, target side


def target_patch():
    """A patterned square: dark frame, bright inside, a dark cross and a red disc in the middle,
    so rays from the centre meet edges at distances that differ by direction."""
    p = np.full((S, S, 3), 40, np.uint8)
    p[3:-3, 3:-3] = (200, 220, 230)
    p[S // 2 - 1:S // 2 + 1, 6:-6] = 30
    p[9:-9, S // 2 - 7:S // 2 - 5] = (20, 20, 160)
    yy, xx = np.mgrid[0:S, 0:S]
    p[(yy - 10) ** 2 + (xx - 22) ** 2 < 16] = (40, 40, 220)
    return p


def scene(n=30, step=(2.0, 1.0), blank=()):
    """Frames with the patch moving on a smooth background; frames in ``blank`` are flat grey."""
    rng = np.random.default_rng(7)
    yy, xx = np.mgrid[0:H, 0:W]
    bg = (110 + 20 * np.sin(xx / 17.0) + 15 * np.cos(yy / 13.0)).astype(np.uint8)
    bg = np.repeat(bg[:, :, None], 3, axis=2)
    patch = target_patch()
    frames, boxes = [], []
    for t in range(n):
        x, y = 30 + step[0] * t, 30 + step[1] * t
        f = bg.copy()
        xi, yi = int(round(x)), int(round(y))
        f[yi:yi + S, xi:xi + S] = patch
        f = np.clip(f.astype(int) + rng.integers(-3, 4, f.shape), 0, 255).astype(np.uint8)
        if t in blank:
            f = np.full_like(f, 128)
        frames.append(f)
        boxes.append((xi, yi, S, S))
    return frames, np.array(boxes, float)


def run(name, frames, gt, seed=0, **params):
    t = trackers.create(name, seed=seed, **params)
    t.init(frames[0], gt[0])
    out, oks = [gt[0]], [True]
    for f in frames[1:]:
        ok, box = t.update(f)
        assert np.all(np.isfinite(box)) and box[2] > 0 and box[3] > 0
        out.append(box)
        oks.append(ok)
    return t, np.array(out), np.array(oks)


def test_hsi_of_primaries_and_grey():
    px = np.array([[[0, 0, 255], [0, 255, 0], [255, 0, 0], [128, 128, 128], [0, 0, 0]]], np.uint8)
    hsi = bgr_to_hsi(px)[0]
    # red: theta = arccos(1) = 0; green: 120; blue (B > G): 360 - 120 = 240; S = 1, I = 1/3
    np.testing.assert_allclose(hsi[:3, 0], [0, 120, 240], atol=1e-3)
    np.testing.assert_allclose(hsi[:3, 1], 1.0, atol=1e-6)
    np.testing.assert_allclose(hsi[:3, 2], 1 / 3, atol=1e-6)
    # grey: S = 0, hue undefined -> 0; black: S = 0, I = 0
    np.testing.assert_allclose(hsi[3], [0, 0, 128 / 255], atol=1e-6)
    np.testing.assert_allclose(hsi[4], [0, 0, 0], atol=1e-6)
    # yellow (R = G = 1, B = 0): theta = arccos(0.5 / 1) = 60 degrees
    assert bgr_to_hsi(np.array([[0, 255, 255]], np.uint8))[0, 0] == pytest.approx(60, abs=1e-3)
    # bins: red -> hue bin 0, top saturation bin, intensity bin 1 (1/3 of 4 bins)
    assert hsi_bin_index(px[:, :1])[0, 0] == (0 * 8 + 7) * 4 + 1


def hsi_oracle(b, g, r):
    """Independent HSI of one pixel (0..255 ints): the hue as the angle of the chromaticity
    vector, atan2(sqrt(3) (G - B), 2R - G - B) -- algebraically equal to the arccos form of
    Gonzalez & Woods, numerically a different computation."""
    R, G, B = r / 255.0, g / 255.0, b / 255.0
    total = R + G + B
    i = total / 3.0
    s = 0.0 if total == 0 else 1.0 - 3.0 * min(R, G, B) / total
    h = 0.0 if (R == G == B) else np.degrees(np.arctan2(np.sqrt(3.0) * (G - B), 2 * R - G - B)) % 360.0
    return h, s, i


def test_hsi_matches_an_independent_conversion_and_a_slow_histogram():
    rng = np.random.default_rng(11)
    px = rng.integers(0, 256, size=(500, 3)).astype(np.uint8)
    px[:20] = px[:20, :1]            # some greys
    hsi = bgr_to_hsi(px[None])[0]
    want = np.array([hsi_oracle(*map(int, p)) for p in px])
    dh = (hsi[:, 0] - want[:, 0] + 180.0) % 360.0 - 180.0   # hue is circular
    np.testing.assert_allclose(dh, 0.0, atol=0.05)
    np.testing.assert_allclose(hsi[:, 1:], want[:, 1:], atol=1e-5)
    # a 16 x 24 box on integer pixels samples those pixels themselves: a slow histogram over
    # them, with the kernel written out, must equal the batched one
    frame = rng.integers(0, 256, size=(40, 50, 3)).astype(np.uint8)
    x0, y0 = 7, 5
    slow = np.zeros(256)
    for yy in range(24):
        for xx in range(16):
            h, s_, i = hsi_oracle(*map(int, frame[y0 + yy, x0 + xx]))
            k = (min(int(h * 8 / 360), 7) * 8 + min(int(s_ * 8), 7)) * 4 + min(int(i * 4), 3)
            r2 = (xx + 0.5 - 8) ** 2 + (yy + 0.5 - 12) ** 2
            slow[k] += 1.0 - r2 / (7.5 ** 2 + 11.5 ** 2)
    slow /= slow.sum()
    np.testing.assert_allclose(hsi_histograms(frame, [(x0, y0, 16, 24)])[0], slow, atol=1e-6)


def test_hsi_histograms_batched_rows_sum_to_one():
    frames, gt = scene(2)
    boxes = np.vstack([gt[0], gt[0] + [40, 10, 0, 0], [-5, -5, 20, 20]])
    h = hsi_histograms(frames[0], boxes)
    assert h.shape == (3, 256)
    np.testing.assert_allclose(h.sum(axis=1), 1.0)
    np.testing.assert_allclose(h[0], hsi_histograms(frames[0], boxes[:1])[0])
    assert not np.allclose(h[0], h[1])


# Measured on this scene (seeds 0-2): edge-ray-pf mean IoU 0.60-0.65 (min 0.50), last centre
# error 6-8 px -- its eq. 6 weights are flat near the target, so the eq. 7 mean lags a moving
# target by a few pixels; hsi-color-pf mean IoU 0.94, hog-pf 0.98, last error < 2 px. A
# tracker that stays put ends 65 px away with IoU 0. The bounds sit below each measured range
# and far above "not following".
@pytest.mark.parametrize("name, min_iou, max_err", [
    ("edge-ray-pf", 0.5, 12.0), ("hsi-color-pf", 0.8, 5.0), ("hog-pf", 0.8, 5.0)])
def test_trackers_follow_the_patterned_square(name, min_iou, max_err):
    frames, gt = scene()
    _, boxes, oks = run(name, frames, gt)
    iou = metrics.iou(boxes[1:], gt[1:])
    assert iou.mean() > min_iou
    assert metrics.center_error(boxes[-1:], gt[-1:])[0] < max_err
    assert oks[1:].mean() > 0.9


def test_edge_ray_pf_same_seed_same_boxes_other_seed_differs():
    frames, gt = scene(12)
    _, a, _ = run("edge-ray-pf", frames, gt, seed=3)
    _, b, _ = run("edge-ray-pf", frames, gt, seed=3)
    _, c, _ = run("edge-ray-pf", frames, gt, seed=4)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)


def test_frames_without_edges_are_lost_then_recovered():
    # Frames 10-13 are flat grey: no edge anywhere, every ray runs to the border, which is far
    # from the model's short rays -> every particle is outside the Ratio window.
    blank = range(10, 14)
    frames, gt = scene(30, blank=blank)
    t, boxes, oks = run("edge-ray-pf", frames, gt)
    assert not oks[list(blank)].any()
    # while lost, the box stays where it was last seen
    np.testing.assert_allclose(boxes[10:14], np.repeat(boxes[9:10], 4, axis=0))
    assert oks[-5:].all()
    assert metrics.center_error(boxes[-1:], gt[-1:])[0] < 12


def test_ratio_window_and_options_are_checked():
    frames, gt = scene(3)
    with pytest.raises(ValueError, match="ratio_low"):
        trackers.create("edge-ray-pf", ratio_low=1.1)  # the window must contain Ratio = 1
    with pytest.raises(ValueError, match="n_particles"):
        trackers.create("edge-ray-pf", n_particles=1000)
    # the options beyond the paper run and keep finite boxes
    for kw in ({"adapt_scale": True}, {"model_rate": 0.1}, {"max_ray": 40.0}):
        _, boxes, oks = run("edge-ray-pf", frames, gt, **kw)
        assert oks[1:].all()


@pytest.mark.parametrize("max_ray", [0.0, 25.0])
def test_particle_rays_equal_whole_frame_maps(max_ray):
    # The tracker computes the rays along the particles' lines only; its pDis_j and weights
    # must equal those read from the whole-frame maps (with the same cap).
    from trackbook.features import edge_rays as er
    frames, gt = scene(4)
    t = trackers.create("edge-ray-pf", max_ray=max_ray, seed=1)
    t.init(frames[0], gt[0])
    prev = t.particles.copy()
    t.update(frames[1])
    full = er.ray_distance_maps(t.edges, max_ray or None)
    expect = er.rays_at(full, np.floor(t.particles))
    np.testing.assert_allclose(t.particle_rays, expect, rtol=1e-6)
    np.testing.assert_allclose(t.likelihoods, er.edge_weight(expect, t.model_rays))
    assert not np.array_equal(prev, t.particles)


def test_a_centre_maps_to_the_pixel_that_contains_it():
    # Regression: np.rint(c - 0.5) rounds halves to even, so the centres 20.0 and 21.0 both
    # landed on pixel 20. Pixel i covers [i, i + 1), so c -> floor(c). A vertical edge at
    # column 25: the east ray from pixel 20 is 5 px long, from pixel 21 it is 4 px.
    edges = np.zeros((50, 50), bool)
    edges[:, 25] = True
    t = trackers.create("edge-ray-pf", seed=0)
    t.edges = edges
    xy = np.array([[20.0, 10.0], [21.0, 10.0], [21.99, 10.0], [22.0, 10.0]])
    east = t._rays(xy)[:, 0]
    np.testing.assert_allclose(east, [5.0, 4.0, 4.0, 3.0])


@pytest.mark.slow
@pytest.mark.skipif("patterned-object" not in clips.available(),
                    reason="the patterned-object sample clip is not available")
def test_edge_ray_pf_on_patterned_object():
    import trackbook
    # Measured (seed 0, defaults): AUC 0.49, tracking rate 0.49, mean centre error 18 px
    # (seeds 1-2: AUC 0.39 and 0.51). A box that stays at the first frame's place scores
    # AUC 0.07. The bound sits below the measured seed-0 value and far above "not following".
    r = trackbook.evaluate("edge-ray-pf", "patterned-object", seed=0)
    assert r.scores["auc"] > 0.4
    assert r.scores["mean_center_error"] < 25


@pytest.mark.parametrize("name", ["edge-ray-pf", "hsi-color-pf", "hog-pf"])
def test_velocity_gain_scales_the_motion_added_to_the_prediction(name):
    """v = g (C_t - C_{t-1}): g = 1 is the paper, 0 a pure random walk, 0.5 half the motion."""
    frames, boxes = scene(n=4)
    for g in (1.0, 0.5, 0.0):
        t = trackers.create(name, seed=3, velocity_gain=g)
        t.init(frames[0], boxes[0])
        before = np.array(t.estimate, dtype=float)
        t.update(frames[1])
        assert not t.lost
        np.testing.assert_allclose(t.velocity, g * (np.asarray(t.estimate) - before), atol=1e-12)


def test_confidence_is_the_colour_match_of_the_estimate_against_the_first_box():
    """The edge likelihood cannot say "gone": the confidence is the failure layer's generic
    one, rho between the kernel colour histograms of the estimate's box and of the first box
    (eq. 1 of Lee et al. 2012), computed here from the histograms directly."""
    from trackbook.trackers.generic_confidence import ColourCheck

    clip = clips.load("patterned-object")
    t = trackers.create("edge-ray-pf", seed=0)
    t.init(clip.frames[0], clip.groundtruth[0])
    h0 = ColourCheck.histograms(clip.frames[0], np.asarray(clip.groundtruth[0], float)[None])[0]
    for f in clip.frames[1:6]:
        ok, box = t.update(f)
        h = ColourCheck.histograms(f, np.asarray(box, float)[None])[0]
        assert ok
        assert t.state().confidence == pytest.approx(float(np.sum(np.sqrt(h * h0))), abs=1e-9)


