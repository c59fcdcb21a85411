"""Region covariance (eq. 4), the Förstner metric (eq. 5–6) and the lee2015 trackers."""

import cv2
import numpy as np
import pytest
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbook import clips, evaluate, metrics, trackers
from trackbook.features.covariance import (FEATURE_SETS, IntegralCovariance, feature_image,
                                           forstner_distance, generalized_eigenvalues,
                                           radial_template, region_covariance)
from trackbook.features.frame_difference import find_moving_region
from trackbook.trackers.covariance import grid_boxes, n_windows

FRAME = cv2.resize(np.random.default_rng(7).integers(0, 256, (24, 32, 3), dtype=np.uint8),
                   (160, 120), interpolation=cv2.INTER_CUBIC)


def _spd(rng, d=5, cond=10.0):
    A = rng.normal(size=(d, d))
    Q, _ = np.linalg.qr(A)
    return Q @ np.diag(np.geomspace(1.0, cond, d)) @ Q.T


# -- eq. 4 from integral images --------------------------------------------------------------
@settings(max_examples=60, deadline=None)
@given(x=st.integers(0, 150), y=st.integers(0, 110), w=st.integers(1, 160),
       h=st.integers(1, 120), features=st.sampled_from(FEATURE_SETS))
def test_integral_covariance_equals_np_cov(x, y, w, h, features):
    w, h = min(w, 160 - x), min(h, 120 - y)
    F = feature_image(FRAME, features)
    radial = features == "rI|Ix||Iy|"
    C = IntegralCovariance(F, radial=radial).covariances([[x, y, w, h]])[0]
    patch = F[y:y + h, x:x + w]
    if radial:  # eq. 3: prepend the distance from the window's centre
        patch = np.concatenate([radial_template(w, h)[..., None], patch], -1)
    oracle = np.cov(patch.reshape(-1, patch.shape[-1]), rowvar=False, bias=True)
    np.testing.assert_allclose(C, np.atleast_2d(oracle), atol=1e-6 * max(1.0, np.abs(oracle).max()))


def test_integral_covariance_of_a_crop_uses_frame_coordinates():
    F = feature_image(FRAME)
    boxes = np.array([[40, 30, 24, 24], [52, 41, 24, 24], [40, 30, 30, 20]])
    crop = IntegralCovariance(F[25:80, 35:100], origin=(35, 25)).covariances(boxes)
    whole = IntegralCovariance(F).covariances(boxes)
    np.testing.assert_allclose(crop, whole, atol=1e-8)
    with pytest.raises(ValueError, match="outside"):
        IntegralCovariance(F[25:80, 35:100], origin=(35, 25)).covariances([[0, 0, 10, 10]])


@pytest.mark.parametrize("features", FEATURE_SETS)
def test_feature_planes_are_the_feature_image_channels_first(features):
    from trackbook.features.covariance import feature_planes
    F = feature_image(FRAME, features)
    G = feature_planes(FRAME, features)
    np.testing.assert_array_equal(G, np.moveaxis(F, -1, 0))
    boxes = np.array([[5, 5, 20, 30], [40, 20, 25, 25]])
    radial = features == "rI|Ix||Iy|"
    np.testing.assert_array_equal(
        IntegralCovariance(G, radial=radial, channels_first=True).covariances(boxes),
        IntegralCovariance(F, radial=radial).covariances(boxes))


@pytest.mark.parametrize("features", FEATURE_SETS)
def test_workspace_reuse_gives_the_same_covariances(features):
    from trackbook.features.covariance import Workspace
    ws = Workspace()
    F = feature_image(FRAME, features)
    radial = features == "rI|Ix||Iy|"
    boxes = np.array([[5, 5, 20, 30], [40, 20, 25, 25]])
    # A large table, then a smaller one in the same buffers, then the large one again.
    for crop in (F, F[10:70, 0:90], F):
        ic_ws = IntegralCovariance(crop, radial=radial, workspace=ws)
        ic = IntegralCovariance(crop, radial=radial)
        np.testing.assert_array_equal(ic_ws.covariances(boxes), ic.covariances(boxes))


def test_region_covariance_is_population_form():
    f = np.arange(12.0).reshape(2, 2, 3)
    np.testing.assert_allclose(region_covariance(f), np.cov(f.reshape(-1, 3).T, bias=True))


def test_integral_images_keep_precision_on_bright_frames():
    # A nearly flat bright frame: the mean offset keeps Q − PPᵀ/n from cancelling to noise.
    rng = np.random.default_rng(1)
    frame = np.full((240, 320, 3), 250, np.uint8)
    frame += rng.integers(0, 3, frame.shape, dtype=np.uint8)
    F = feature_image(frame)
    C = IntegralCovariance(F).covariances([[200, 150, 100, 80]])[0]
    oracle = np.cov(F[150:230, 200:300].reshape(-1, 5).T, bias=True)
    np.testing.assert_allclose(C, oracle, rtol=1e-9, atol=1e-9)


# -- eq. 5–6 ---------------------------------------------------------------------------------
def test_forstner_by_hand_2x2():
    # λ(C_i, C_j) of diagonal matrices are the ratios of the diagonals: 2 and 1/2.
    rho = forstner_distance(np.diag([1.0, 2.0]), np.diag([2.0, 1.0]), eps=0)
    assert rho == pytest.approx(np.sqrt(2) * np.log(2), rel=1e-12)


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10_000), d=st.integers(2, 7))
def test_forstner_metric_properties(seed, d):
    rng = np.random.default_rng(seed)
    A, B = _spd(rng, d), _spd(rng, d)
    assert forstner_distance(A, A, eps=0) == pytest.approx(0, abs=1e-6)
    assert forstner_distance(A, B, eps=0) == pytest.approx(forstner_distance(B, A, eps=0),
                                                           rel=1e-9)
    # A random invertible M with condition number <= 4: congruence invariance is exact in
    # exact arithmetic, and a well-conditioned M keeps floating point from hiding it
    # (normal(d, d) + 3I can be nearly singular: seed 7529, d = 7 lost 5 digits).
    Q1, _ = np.linalg.qr(rng.normal(size=(d, d)))
    Q2, _ = np.linalg.qr(rng.normal(size=(d, d)))
    M = Q1 @ np.diag(rng.uniform(0.5, 2.0, d)) @ Q2
    assert forstner_distance(M @ A @ M.T, M @ B @ M.T, eps=0) == pytest.approx(
        forstner_distance(A, B, eps=0), rel=1e-7)
    lam = generalized_eigenvalues(A, B, eps=0)
    np.testing.assert_allclose(lam, scipy.linalg.eigh(B, A, eigvals_only=True), rtol=1e-9)


def test_forstner_is_batched():
    rng = np.random.default_rng(3)
    A = _spd(rng)
    Bs = np.stack([_spd(rng) for _ in range(6)])
    batched = forstner_distance(A, Bs)
    one_by_one = [forstner_distance(A, B) for B in Bs]
    np.testing.assert_allclose(batched, one_by_one, rtol=1e-12)
    assert batched.shape == (6,)


def test_singular_covariances_do_not_raise():
    flat = np.full((30, 30, 3), 128, np.uint8)
    C_flat = IntegralCovariance(feature_image(flat)).covariances([[0, 0, 30, 30]])[0]
    C_tex = IntegralCovariance(feature_image(FRAME)).covariances([[0, 0, 30, 30]])[0]
    for a, b in [(C_flat, C_tex), (C_tex, C_flat), (C_flat, C_flat), (np.zeros((5, 5)),) * 2]:
        rho = forstner_distance(a, b)
        assert np.isfinite(rho)
    assert forstner_distance(C_flat, C_flat) == pytest.approx(0, abs=1e-6)


# -- Kalman filter (eq. 7–13) against filterpy -------------------------------------------------
def test_kalman_matches_filterpy_step_by_step():
    from filterpy.kalman import KalmanFilter as FP

    from trackbook.filters.kalman import constant_velocity
    rng = np.random.default_rng(11)
    ours = constant_velocity((5.0, 7.0), q=0.7, r=2.5, p0=3.0)
    ref = FP(dim_x=4, dim_z=2)
    ref.x, ref.P, ref.F, ref.H, ref.Q, ref.R = (ours.x.copy(), ours.P.copy(), ours.F.copy(),
                                                ours.H.copy(), ours.Q.copy(), ours.R.copy())
    for z in rng.normal(scale=5.0, size=(60, 2)).cumsum(axis=0):
        ours.predict()
        ref.predict()
        np.testing.assert_allclose(ours.x, ref.x.ravel(), atol=1e-9)
        np.testing.assert_allclose(ours.P, ref.P, atol=1e-9)
        ours.update(z)
        ref.update(z)
        np.testing.assert_allclose(ours.x, ref.x.ravel(), atol=1e-9)
        np.testing.assert_allclose(ours.P, ref.P, atol=1e-9)
        np.testing.assert_allclose(ours.K, ref.K, atol=1e-9)


def test_constant_velocity_model_is_the_printed_one():
    from trackbook.filters.kalman import constant_velocity
    kf = constant_velocity()
    np.testing.assert_array_equal(kf.F, [[1, 0, 1, 0], [0, 1, 0, 1], [0, 0, 1, 0], [0, 0, 0, 1]])
    np.testing.assert_array_equal(kf.H, [[1, 0, 0, 0], [0, 1, 0, 0]])
    np.testing.assert_array_equal(kf.Q, np.eye(4))
    np.testing.assert_array_equal(kf.R, np.eye(2))


# -- frame differencing ------------------------------------------------------------------------
def test_frame_differencing_finds_a_moving_square():
    f0 = np.full((120, 160, 3), 40, np.uint8)
    f1 = f0.copy()
    f0[50:70, 30:50] = 220
    f1[50:70, 36:56] = 220     # moved 6 px right
    x, y, w, h = find_moving_region(f0, f1)
    # The difference covers where it was and where it is: x 30..56, y 50..70.
    assert (x, y, w, h) == (30.0, 50.0, 26.0, 20.0)
    assert find_moving_region(f0, f0) is None


def test_init_from_motion_seeds_the_kalman_filter():
    f0 = np.full((120, 160, 3), 40, np.uint8)
    f1 = f0.copy()
    f0[50:70, 30:50] = 220
    f1[50:70, 36:56] = 220
    f1[52:68, 40:52] = 90   # some texture so the covariance is not flat
    t = trackers.create("kalman-covariance")
    box = t.init_from_motion(f0, f1)
    assert t.kalman.x[:2] == pytest.approx((box[0] + box[2] / 2, box[1] + box[3] / 2))


# -- search-rate counting --------------------------------------------------------------------
def test_search_rate_is_counted_exactly():
    # 100x80 frame, 20x20 target, stride 2: (80/2+1)*(60/2+1) = 41*31 = 1271 windows.
    assert n_windows((80, 100), (20, 20), 2) == 1271
    # radius 4 at stride 2 -> offsets -4..4 step 2 -> 5 x 5 = 25 candidates.
    b = grid_boxes((80, 100), (20, 20), (50, 40), (4, 4), 2)
    assert len(b) == 25 and len({tuple(r) for r in b.tolist()}) == 25
    # Near the border the windows leaving the frame are not candidates: x0 clamps to 0.
    assert len(grid_boxes((80, 100), (20, 20), (0, 40), (4, 4), 2)) == 3 * 5

    rng = np.random.default_rng(0)
    frame = cv2.resize(rng.integers(0, 256, (10, 13, 3), dtype=np.uint8), (100, 80))
    t = trackers.create("covariance", stride=2, search_radius=4, threshold=20.0)
    t.init(frame, (40, 30, 20, 20))
    t.update(frame)
    rep = t.frame_report()
    assert rep["candidates"] == 25
    assert rep["search_rate"] == pytest.approx(25 / 1271)
    assert t.bbox == (40.0, 30.0, 20.0, 20.0) and rep["rho"] == pytest.approx(0, abs=1e-6)


def test_whole_frame_search_when_lost_is_counted():
    rng = np.random.default_rng(0)
    frame = cv2.resize(rng.integers(0, 256, (10, 13, 3), dtype=np.uint8), (100, 80))
    # threshold below any achievable ρ: local 25 + coarse (81/4 -> 21 * 61/4 -> 16) 336
    # + refinement 7 x 7 = 49 at stride 1 around the coarse best.
    t = trackers.create("covariance", stride=1, search_radius=2, threshold=0.1,
                        global_stride=4)
    t.init(frame, (41, 30, 20, 20))
    ok, _ = t.update(np.ascontiguousarray(frame[:, ::-1]))
    assert ok is False
    assert t.frame_report()["candidates"] == 25 + 21 * 16 + 7 * 7


# -- the trackers ------------------------------------------------------------------------------
def _moving_square_clip(n=30, v=(4, 2)):
    """A textured 24x24 patch gliding over a smoothly textured background."""
    rng = np.random.default_rng(5)
    bg = cv2.resize(rng.integers(60, 120, (12, 16, 3), dtype=np.uint8), (160, 120))
    patch = cv2.resize(rng.integers(0, 256, (4, 4, 3), dtype=np.uint8), (24, 24),
                       interpolation=cv2.INTER_NEAREST)
    frames, gt = [], []
    for k in range(n):
        x, y = 10 + v[0] * k, 20 + v[1] * k
        f = bg.copy()
        w = min(24, 160 - x)          # the square may slide out of the frame on the right
        if w > 0:
            f[y:y + 24, x:x + w] = patch[:, :w]
        frames.append(f)
        gt.append((x, y, w, 24) if w > 0 else (np.nan,) * 4)
    return clips.Clip("square", clips.ArrayFrames(np.stack(frames)), np.array(gt, float))


@pytest.mark.parametrize("name", ["covariance", "kalman-covariance"])
def test_trackers_follow_a_moving_square(name):
    clip = _moving_square_clip()
    r = evaluate(name, clip)
    assert r.scores["tracking_rate"] == 1.0
    assert np.nanmax(metrics.center_error(r.boxes, clip.groundtruth)) < 1.0


def test_kalman_window_follows_velocity_the_baseline_lags():
    # 9 px/frame: beyond the baseline's ±8 px reach, inside the Kalman window once the
    # filter has learnt the velocity (the mechanism of Lee 2015, Fig. 3 vs Fig. 4).
    clip = _moving_square_clip(n=14, v=(9, 0))
    base = evaluate("covariance", clip)
    kal = evaluate("kalman-covariance", clip)
    e_base = metrics.center_error(base.boxes, clip.groundtruth)
    e_kal = metrics.center_error(kal.boxes, clip.groundtruth)
    assert np.all(e_kal[6:] < 1.0)
    assert e_base[-1] > 10.0                      # the baseline falls behind, frame by frame
    assert np.all(np.diff(e_base[1:]) > 0)


def test_determinism_under_a_seed():
    clip = _moving_square_clip(n=12)
    a = evaluate("kalman-covariance", clip, seed=3)
    b = evaluate("kalman-covariance", clip, seed=3)
    np.testing.assert_array_equal(a.boxes, b.boxes)


def test_target_leaving_the_frame_does_not_raise():
    clip = _moving_square_clip(n=40, v=(5, 0))   # the square reaches the right edge and stops
    for name in ("covariance", "kalman-covariance"):
        r = evaluate(name, clip)
        assert np.all(np.isfinite(r.boxes))


def test_bad_params_are_rejected():
    with pytest.raises(ValueError, match="features"):
        trackers.create("covariance", features="HOG")
    with pytest.raises(ValueError, match="stride"):
        trackers.create("kalman-covariance", stride=0)


def _reversing_square_clip(n=20, turn=12, v=6):
    """A textured square falling at ``v`` px/frame that bounces up at frame ``turn``."""
    rng = np.random.default_rng(5)
    bg = cv2.resize(rng.integers(60, 120, (12, 16, 3), dtype=np.uint8), (160, 160))
    patch = cv2.resize(rng.integers(0, 256, (4, 4, 3), dtype=np.uint8), (24, 24),
                       interpolation=cv2.INTER_NEAREST)
    ys = [20 + v * k if k < turn else 20 + v * (2 * (turn - 1) - k) for k in range(n)]
    frames, gt = [], []
    for y in ys:
        f = bg.copy()
        f[y:y + 24, 60:84] = patch
        frames.append(f)
        gt.append((60, y, 24, 24))
    return clips.Clip("bounce", clips.ArrayFrames(np.stack(frames)), np.array(gt, float))


def test_manoeuvre_window_is_the_inflated_prediction():
    # At the bounce the 3σ window of S (±7 px) misses the square (12 px off); the tracker must
    # redo the prediction with σ_v² added to P⁺'s velocity block — checked against filterpy.
    from filterpy.kalman import KalmanFilter as FP
    clip = _reversing_square_clip()
    t = trackers.create("kalman-covariance-manoeuvre", manoeuvre_sigma=8.0)
    t.init(clip.frames[0], clip.groundtruth[0])
    for k in range(1, 13):
        x_post, P_post = t.kalman.x.copy(), t.kalman.P.copy()
        ok, box = t.update(clip.frames[k])
    assert t.manoeuvre and ok
    assert metrics.center_error(np.array([box]), clip.groundtruth[12:13])[0] < 1.0
    ref = FP(dim_x=4, dim_z=2)
    ref.x, ref.F, ref.H, ref.Q, ref.R = x_post, t.kalman.F, t.kalman.H, np.eye(4), np.eye(2)
    ref.P = P_post + np.diag([0.0, 0.0, 64.0, 64.0])
    ref.predict()
    half_h = 3 * np.sqrt(ref.P[1, 1] + 1.0)
    assert t.search_window[3] == pytest.approx(24 + 2 * half_h)
    ref.update(np.array([box[0] + 12, box[1] + 12]))
    np.testing.assert_allclose(t.kalman.x, ref.x.ravel(), atol=1e-9)
    assert t.kalman.x[3] < -3.0                   # the velocity estimate turned upwards at once


def test_manoeuvre_gate_zero_is_the_paper_tracker():
    clip = _reversing_square_clip()
    used = []
    # under the paper tracker's failure thresholds (each name has its own calibrated pair)
    from trackbook.trackers.failure import calibrated_params
    t = trackers.create("kalman-covariance-manoeuvre", manoeuvre_gate=0,
                        failure=calibrated_params("kalman-covariance"))
    off = evaluate(t, clip, on_frame=lambda i, t, f, b: used.append(t.manoeuvre))
    assert not any(used)
    np.testing.assert_array_equal(off.boxes, evaluate("kalman-covariance", clip).boxes)


@pytest.mark.slow
@pytest.mark.skipif("red-cube" not in clips.available(), reason="red-cube sample not available")
def test_red_cube_table1_claims():
    # Measured on red-cube (book/case_study_lee2015.md): both trackers 183/183 frames with IoU > 0.5
    # (tracking rate 1.000); search rate covariance 0.448 %, kalman-covariance 0.348 %; at most
    # 289 resp. 225 candidates per frame. The paper's detection rates are 87.1 % / 96.3 %: we
    # assert at least the paper's proposed rate for both. Its search-rate claim (proposed
    # evaluates fewer windows) holds; its explanation (fewer whole-frame searches) cannot
    # show, because neither tracker searches the whole frame on this clip.
    base, kal = evaluate("covariance", "red-cube"), evaluate("kalman-covariance", "red-cube")
    for r in (base, kal):
        assert r.scores["tracking_rate"] >= 0.963
    assert np.nanmean(kal.extras["search_rate"][1:]) < np.nanmean(base.extras["search_rate"][1:])
    assert np.nanmax(base.extras["candidates"][1:]) == 17 * 17
    assert np.nanmax(kal.extras["candidates"][1:]) < 17 * 17


@pytest.mark.slow
@pytest.mark.skipif("yellow-ball" not in clips.available(), reason="yellow-ball not available")
def test_yellow_ball_needs_the_manoeuvre_window():
    # Measured (book/case_study_lee2015.md): tracking rate covariance 0.916, kalman-covariance
    # (the paper's tracker) 0.496 — it loses the ball at the bounces — and with
    # the book's manoeuvre re-search (kalman-covariance-manoeuvre) 0.992, at a lower search rate than the baseline
    # (0.402 % vs 0.427 %).
    base = evaluate("covariance", "yellow-ball")
    paper = evaluate("kalman-covariance", "yellow-ball")
    book = evaluate("kalman-covariance-manoeuvre", "yellow-ball")
    assert paper.scores["tracking_rate"] < base.scores["tracking_rate"]
    assert book.scores["tracking_rate"] > base.scores["tracking_rate"]
    assert book.scores["tracking_rate"] >= 0.95
    assert np.nanmean(book.extras["search_rate"][1:]) < np.nanmean(base.extras["search_rate"][1:])


# -- regression: initialisation from frame differencing (Lee 2015 §2.3) ------------------------
@pytest.mark.parametrize("k", [1, 2, 3, 5])
def test_init_from_motion_tracks_red_cube_from_any_early_pair(k):
    """The moving region's centre seeds the filter; the model is a 24×24 window there.

    Taking the region's *box* as the model gave a 19×3 strip and 0 % tracking for frames
    0→1 (and 9 % for 0→5 on 60 frames). Measured with the fix on the whole clip: 0.962 (0→1),
    1.0 (0→2, 0→3, 0→5); the assertion leaves the 0→1 case a little room, no more.
    """
    clip = clips.load("red-cube")
    t = trackers.create("kalman-covariance")
    box = t.init_from_motion(clip.frames[0], clip.frames[k])
    region = t.motion_region
    centre = (region[0] + region[2] / 2, region[1] + region[3] / 2)
    assert t.kalman.x[:2] == pytest.approx(centre)          # the paper: the region's centre
    assert box[2:] == (24.0, 24.0) and t.model.shape == (5, 5)
    preds = [t.bbox]
    for frame in clip.frames[k + 1:]:
        preds.append(t.update(frame)[1])
    rate = metrics.tracking_rate(np.array(preds), clip.groundtruth[k:])
    assert rate >= 0.9, f"frames 0→{k}: tracking rate {rate:.3f}"
