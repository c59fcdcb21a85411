"""Mean-shift (Comaniciu et al. 2003), the motion vector (eq. 5-8) and the cho2005 trackers."""

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from skimage import data

import trackbook
from trackbook import clips, trackers
from trackbook.features.color import hsv_bin_index
from trackbook.filters.mean_shift import (bin_image, ellipse_histograms, ellipse_labels,
                                          ellipse_rho, ellipse_window, lattice_pixel, mean_shift,
                                          mean_shift_weights, mean_shift_with_scale)
from trackbook.filters.optical_flow import motion_vector, solve_motion
from trackbook.trackers.multi import MultiTracker, target_seed

H, W = 160, 200
MODE = np.array([100.5, 80.5])


def blob_frame():
    """A red disc with a green core on a blue background: rho has one mode, at the disc centre."""
    f = np.zeros((H, W, 3), np.uint8)
    f[:] = (200, 60, 40)
    cv2.circle(f, (100, 80), 24, (0, 0, 230), -1)
    cv2.circle(f, (100, 80), 10, (0, 220, 0), -1)
    return f


@pytest.fixture(scope="module")
def blob():
    f = blob_frame()
    img = bin_image(f, (0, 0, W, H))
    _, p, _ = ellipse_rho(img, np.zeros(img.n_bins), MODE[None], [[24.0, 24.0]])
    return img, p[0]


def _loop_histogram(frame, centre, axes, stride=1):
    """Oracle: eq. 3 by a plain loop over every stride-th pixel of the frame."""
    labels = hsv_bin_index(frame)
    hist = np.zeros(256)
    for i in range(0, frame.shape[0], stride):
        for j in range(0, frame.shape[1], stride):
            r2 = ((j + 0.5 - centre[0]) / axes[0]) ** 2 + ((i + 0.5 - centre[1]) / axes[1]) ** 2
            if r2 < 1:
                hist[labels[i, j]] += 1 - r2
    return hist / hist.sum()


@pytest.mark.parametrize("stride", [1, 3])
def test_histogram_matches_a_slow_loop(stride):
    # the ellipse is centred on the lattice pixel nearest to its centre (module docstring)
    f = blob_frame()
    img = bin_image(f, (0, 0, W, H), stride=stride)
    c, axes = np.array([95.3, 77.9]), (20.0, 14.0)
    snapped = img.origin + stride * lattice_pixel(img, c[None])[0]
    assert np.all(np.abs(snapped - c) <= stride / 2)
    got = ellipse_rho(img, np.zeros(img.n_bins), c[None], [axes])[1][0]
    np.testing.assert_allclose(got, _loop_histogram(f, snapped, axes, stride), atol=1e-12)


def test_histograms_of_different_sizes_in_one_batch(blob):
    img, _ = blob
    centres = np.array([[95.5, 77.5], [60.5, 50.5]])
    axes = np.array([[20.0, 14.0], [9.0, 25.0]])
    win = ellipse_window(img, axes)
    hist = ellipse_histograms(ellipse_labels(img, lattice_pixel(img, centres), win), win.k,
                              img.n_bins)
    for k in range(2):
        np.testing.assert_allclose(hist[k], _loop_histogram(blob_frame(), centres[k], axes[k]),
                                   atol=1e-12)


def test_weights_are_sqrt_q_over_p_and_zero_outside_the_frame(blob):
    img, q = blob
    c = np.array([[10.5, 10.5]])                 # partly outside the frame
    rho, p, labels = ellipse_rho(img, q, c, [[20.0, 20.0]])
    w = mean_shift_weights(labels, p, q)
    m = img.n_bins
    inside = labels < m
    assert (~inside).any() and inside.any()
    np.testing.assert_allclose(w[inside], np.sqrt(q[labels[inside]] / p[0, labels[inside]]))
    assert np.all(w[~inside] == 0)


@pytest.mark.parametrize("bins", [(8, 8, 4), (6, 5, 3), (16, 16, 16)])
def test_fast_bin_image_equals_hsv_bin_index(bins):
    from trackbook.filters.mean_shift import hsv_bin_image
    img = cv2.resize(data.astronaut()[..., ::-1], (97, 61))        # BGR, odd sizes
    np.testing.assert_array_equal(hsv_bin_image(img, bins), hsv_bin_index(img, bins))
    strided = img[3:50:3, 5:90:2]                                   # a non-contiguous view
    np.testing.assert_array_equal(hsv_bin_image(strided, bins), hsv_bin_index(strided, bins))


def test_ellipse_outside_the_frame_has_rho_zero(blob):
    img, q = blob
    rho, p, _ = ellipse_rho(img, q, [[-500.0, -500.0]], [[10.0, 10.0]])
    assert rho[0] == 0 and p.sum() == 0


@pytest.mark.parametrize("start", [(92, 74), (110, 88), (86, 80), (100, 95), (112, 70)])
def test_mean_shift_converges_to_the_mode(blob, start):
    img, q = blob
    res = mean_shift(img, q, [start], [[24.0, 24.0]], max_iter=50, eps=0.1)
    assert np.linalg.norm(res.centres[0] - MODE) < 1.5
    assert res.rho[0] > 0.99 > res.rho_start[0]


@settings(max_examples=30, deadline=None)
@given(st.floats(-20, 20), st.floats(-20, 20), st.floats(12, 30), st.floats(12, 30))
def test_rho_never_decreases_across_an_accepted_step(dx, dy, hx, hy):
    img, q = _BLOB
    res = mean_shift(img, q, [MODE + (dx, dy)], [[hx, hy]], max_iter=15, eps=0.05)
    steps = np.diff(res.rho_trajectory[:, 0])
    assert np.all(steps >= 0)
    assert res.rho[0] >= res.rho_start[0]


_f = blob_frame()
_img = bin_image(_f, (0, 0, W, H))
_BLOB = (_img, ellipse_rho(_img, np.zeros(_img.n_bins), MODE[None], [[24.0, 24.0]])[1][0])


def test_batched_mean_shift_equals_one_at_a_time(blob):
    img, q = blob
    starts = np.array([[90.0, 70.0], [115.0, 90.0], [100.0, 60.0]])
    axes = np.array([[24.0, 24.0], [20.0, 26.0], [18.0, 18.0]])
    both = mean_shift(img, q, starts, axes)
    for k in range(3):
        one = mean_shift(img, q, starts[k:k + 1], axes[k:k + 1])
        np.testing.assert_allclose(both.centres[k], one.centres[0])
        np.testing.assert_allclose(both.rho[k], one.rho[0])
        assert both.iterations[k] == one.iterations[0]


def test_scale_adaptation_keeps_the_better_size(blob):
    img, q = blob
    res, axes = mean_shift_with_scale(img, q, MODE, (24.0, 24.0), gamma=1.0)
    # at the mode, the model's own size is best: the ±10 % trials lose
    np.testing.assert_allclose(axes, (24.0, 24.0))


def test_strided_lattice_still_finds_the_mode():
    f = blob_frame()
    img = bin_image(f, (0, 0, W, H), stride=3)
    _, p, _ = ellipse_rho(img, np.zeros(img.n_bins), MODE[None], [[24.0, 24.0]])
    res = mean_shift(img, p[0], [MODE + (8, -6)], [[24.0, 24.0]], max_iter=50, eps=0.1)
    assert np.linalg.norm(res.centres[0] - MODE) < 3


# -- motion vector (eq. 5-8) -------------------------------------------------------------
def _texture():
    g = cv2.cvtColor(data.astronaut(), cv2.COLOR_RGB2GRAY)
    return cv2.GaussianBlur(cv2.resize(g, (256, 256)), (5, 5), 1.0)


@pytest.mark.parametrize("shift", [(0.4, -0.3), (-0.25, 0.6), (0.8, 0.5)])
def test_single_solve_recovers_a_subpixel_translation(shift):
    img = _texture()
    moved = cv2.warpAffine(img, np.float32([[1, 0, shift[0]], [0, 1, shift[1]]]), (256, 256))
    p, q, ok = motion_vector(img, moved, (90, 90, 70, 70), levels=1, iterations=1)
    assert ok
    assert abs(p - shift[0]) < 0.1 and abs(q - shift[1]) < 0.1


def test_pyramid_recovers_a_larger_translation():
    img = _texture()
    moved = cv2.warpAffine(img, np.float32([[1, 0, 5.3], [0, 1, -3.6]]), (256, 256))
    p, q, ok = motion_vector(img, moved, (90, 90, 70, 70), levels=3, iterations=5)
    assert ok and abs(p - 5.3) < 0.1 and abs(q + 3.6) < 0.1


def test_flat_region_gives_zero_motion():
    flat = np.full((64, 64), 90, np.uint8)
    assert motion_vector(flat, flat + 1, (10, 10, 40, 40)) == (0.0, 0.0, False)
    # an edge only (aperture problem): also refused
    Ix, Iy = np.ones((10, 10)), np.zeros((10, 10))
    assert solve_motion(Ix, Iy, np.ones((10, 10)))[2] is False


def test_solve_motion_matches_lstsq():
    rng = np.random.default_rng(1)
    Ix, Iy, It = rng.normal(size=(3, 20, 20)) * 10
    p, q, ok = solve_motion(Ix, Iy, It)
    A = np.stack([Ix.ravel(), Iy.ravel()], axis=1)
    ref = np.linalg.lstsq(A, -It.ravel(), rcond=None)[0]
    assert ok
    np.testing.assert_allclose((p, q), ref, rtol=1e-9)


# -- trackers ------------------------------------------------------------------------------
def moving_blob_clip(n=12):
    frames = []
    for t in range(n):
        f = np.zeros((H, W, 3), np.uint8)
        f[:] = (200, 60, 40)
        c = (70 + 4 * t, 80 + t)
        cv2.circle(f, c, 18, (0, 0, 230), -1)
        cv2.circle(f, c, 7, (0, 220, 0), -1)
        frames.append(f)
    gt = np.array([[70 + 4 * t - 18 + 0.5, 80 + t - 18 + 0.5, 36, 36] for t in range(n)])
    return clips.Clip("moving-blob", clips.ArrayFrames(np.stack(frames)), gt)


NAMES = ["condensation", "mean-shift", "condensation-mean-shift"]


@pytest.mark.parametrize("name", NAMES)
def test_registered_and_tracks_a_moving_blob(name):
    assert name in trackers.available()
    r = trackbook.evaluate(name, moving_blob_clip(), seed=0)
    assert r.scores["auc"] > 0.6
    assert np.all(np.isfinite(r.extras["mean_likelihood"][1:]))


@pytest.mark.parametrize("name", NAMES)
def test_deterministic_under_a_seed(name):
    clip = moving_blob_clip()
    a = trackbook.evaluate(name, clip, seed=3).boxes
    b = trackbook.evaluate(name, clip, seed=3).boxes
    np.testing.assert_array_equal(a, b)


def test_target_leaving_the_frame_never_raises_or_nans():
    # tracked on 7 frames first: the failure layer judges a frame only once its reference
    # holds its warm-up of confidences (5)
    clip = moving_blob_clip(9)
    t = trackers.create("condensation-mean-shift", seed=0)
    t.init(clip.frames[0], clip.groundtruth[0])
    for f in clip.frames[1:8]:
        assert t.update(f)[0]
    kept = t.bbox
    empty = np.zeros((H, W, 3), np.uint8)
    empty[:] = (200, 60, 40)
    for _ in range(3):
        ok, box = t.update(empty)
        assert not ok and box == kept
    ok, box = t.update(clip.frames[8])
    assert np.all(np.isfinite(box))


def test_bad_params_are_refused():
    with pytest.raises(ValueError, match="n_particles"):
        trackers.create("condensation-mean-shift", n_particles=0)
    with pytest.raises(ValueError, match="unknown parameter"):
        trackers.create("mean-shift", n_particles=5)


def test_mean_shift_raises_candidate_likelihood_on_a_clip():
    """Eq. 13: the candidates after mean-shift have at least the rho they had before."""
    clip = clips.load("occluder") if "occluder" in clips.available() else moving_blob_clip()
    t = trackers.create("condensation-mean-shift", seed=0)
    t.init(clip.frames[0], clip.groundtruth[0])
    before, after = [], []
    for f in list(clip.frames)[1:30]:
        t.update(f)
        before.append(t.rho_before.mean())
        after.append(t.rho.mean())
        assert np.all(t.rho >= t.rho_before)
    assert np.mean(after) >= np.mean(before)


# -- several targets -----------------------------------------------------------------------
def test_multitracker_seeds_targets_apart_and_repeats():
    assert target_seed(0, 0) != target_seed(0, 1)
    assert target_seed(None, 1) is None
    clip = moving_blob_clip(6)
    boxes = [clip.groundtruth[0], (5.0, 5.0, 30.0, 30.0)]
    runs = []
    for _ in range(2):
        mt = MultiTracker("condensation", seed=0, n_particles=20)
        mt.init(clip.frames[0], boxes)
        runs.append([mt.update(f)[1] for f in list(clip.frames)[1:]])
    assert runs[0] == runs[1]
    with pytest.raises(ValueError, match="unknown tracker"):
        MultiTracker("no-such-tracker")
    # params are checked when the multi-tracker is made, not when init starts the trackers
    with pytest.raises(ValueError, match="bogus"):
        MultiTracker("mean-shift", bogus=1)
    with pytest.raises(ValueError, match="n_particles"):
        MultiTracker("condensation", n_particles=0)


@pytest.mark.slow
@pytest.mark.skipif("two-faces" not in clips.available(), reason="sample clip two-faces not built")
def test_two_faces_keep_their_identities_through_the_crossing():
    from trackbook.metrics import iou

    clip = clips.load("two-faces")
    out = trackbook.evaluate("condensation-mean-shift", clip, seed=0, targets="all").boxes
    names = list(clip.targets)[:2]
    a, b = names
    n = len(clip)
    after = slice(int(0.75 * n), n)
    for me, other in ((a, b), (b, a)):
        own = np.nanmean(iou(out[me][after], clip.targets[me][after]))
        swapped = np.nanmean(iou(out[me][after], clip.targets[other][after]))
        assert own > swapped


def test_cost_counts_histograms_and_pixels(blob):
    """The paper's cost: colour histograms computed (and pixels read) per frame."""
    img, q = blob
    starts = np.array([[90.0, 70.0], [100.5, 80.5], [115.0, 90.0]])
    res = mean_shift(img, q, starts, [[24.0, 24.0]], max_iter=30, eps=0.1)
    n = len(starts)
    # every evaluation computes the candidates still moving: at least one, at most all
    assert n + (res.evaluations - 1) <= res.histograms <= n * res.evaluations
    pixels_per_ellipse = ellipse_window(img, [[24.0, 24.0]]).flat.size
    assert res.pixels == res.histograms * pixels_per_ellipse
    # the start at the mode stops at once: fewer histograms than lock-step would compute
    assert res.iterations[1] < res.iterations.max() and res.histograms < n * res.evaluations
    clip = moving_blob_clip(4)
    r = trackbook.evaluate("condensation", clip, seed=0, n_particles=40)
    np.testing.assert_array_equal(r.extras["histograms"][1:], 40)


def test_prediction_moves_the_position_by_the_new_noised_velocity():
    """The module docstring's dynamics: x_t = x + x_dot_t + w_x, with x_dot_t the
    velocity AFTER its noise, not x + x_dot_{t-1}. With no position noise the displacement of
    every candidate equals its new velocity exactly."""
    import numpy as np
    from trackbook import trackers
    t = trackers.create("condensation", seed=3, noise_position=0.0, noise_velocity=0.2)
    frame = np.full((80, 100, 3), 90, np.uint8)
    frame[30:50, 40:60] = (40, 60, 200)
    t.init(frame, (40, 30, 20, 20))
    s0 = np.array(t.initial_particles(frame, (40, 30, 20, 20)), dtype=float)
    s0[:, 2:4] = [1.5, -0.5]                      # a known previous velocity
    s1 = t.predict(s0.copy())
    np.testing.assert_allclose(s1[:, 0:2] - s0[:, 0:2], s1[:, 2:4], atol=1e-9)
    assert not np.allclose(s1[:, 2:4], s0[:, 2:4])  # the velocity did receive noise
