"""Correlation filters (``10_correlation_filters``): the Fourier solutions against closed forms.

Expected values come from the spatial-domain problems solved with ``numpy.linalg`` over all
cyclic shifts built explicitly, from slow loops, or by hand -- never from the FFT code.
"""
from __future__ import annotations

import copy

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import trackbook
from trackbook import clips, trackers
from trackbook.features.gradient_cells import orientation_cells
from trackbook.filters import correlation as cf

ROWS, COLS = 6, 5


def _shifts(rows, cols):
    return [(a, b) for a in range(rows) for b in range(cols)]


def _kappa(u, v, sigma):
    """The Gaussian kernel with the distance per feature value (as gaussian_correlation)."""
    return np.exp(-np.sum((u - v) ** 2) / u.size / sigma ** 2)


@pytest.fixture
def rng():
    return np.random.default_rng(7)


# (a) KCF's dual solution is kernel ridge regression over all cyclic shifts -----------------
@pytest.mark.parametrize("channels", [1, 3])
def test_kcf_dual_solution_equals_kernel_ridge_regression(rng, channels):
    sigma, lam = 0.7, 1e-2
    x = rng.normal(size=(channels, ROWS, COLS))
    z = x + 0.3 * rng.normal(size=x.shape)
    y = cf.gaussian_labels(ROWS, COLS, 1.0)
    S = _shifts(ROWS, COLS)
    # sample i is x shifted by -s_i (the convention of the module docstring), label y[s_i]
    X = [np.roll(x, (-a, -b), axis=(1, 2)) for a, b in S]
    K = np.array([[_kappa(Xi, Xj, sigma) for Xj in X] for Xi in X])
    labels = np.array([y[a, b] for a, b in S])
    alpha = np.linalg.solve(K + lam * np.eye(len(S)), labels)

    xf = np.fft.fft2(x)
    alphaf, _ = cf.kcf_train(xf, np.fft.fft2(y), sigma, lam)
    np.testing.assert_allclose(np.fft.ifft2(alphaf).real.ravel(), alpha, atol=1e-9)

    # the response at shift t is the regression evaluated on z shifted by -t
    expected = np.array([sum(al * _kappa(np.roll(z, (-a, -b), axis=(1, 2)), Xs, sigma)
                             for al, Xs in zip(alpha, X)) for a, b in S])
    got = cf.kcf_response(alphaf, xf, np.fft.fft2(z), sigma)
    np.testing.assert_allclose(got.ravel(), expected, atol=1e-9)


# (b) MOSSE is the spatial least-squares filter -------------------------------------------
def test_mosse_equals_spatial_least_squares(rng):
    lam = 0.05
    f = rng.normal(size=(3, ROWS, COLS))          # three training images
    g = np.stack([cf.gaussian_labels(ROWS, COLS, 1.2)] * 3)
    S = _shifts(ROWS, COLS)
    # row t of X_i: the image shifted so that <h, row> is g_i[t] = sum_y f[y] h[y - t]
    rows = [np.roll(fi, (-a, -b), axis=(0, 1)).ravel() for fi in f for a, b in S]
    X = np.array(rows)
    target = g.reshape(-1)
    n = ROWS * COLS
    h = np.linalg.solve(X.T @ X + lam * np.eye(n), X.T @ target)
    F = np.fft.fft2(f)
    A, B = cf.mosse_terms(F, np.fft.fft2(g))
    H_conj = cf.mosse_filter(A, B, lam)
    np.testing.assert_allclose(np.fft.ifft2(np.conj(H_conj)).real.ravel(), h, atol=1e-10)
    test = rng.normal(size=(ROWS, COLS))
    expected = np.array([np.dot(np.roll(test, (-a, -b), axis=(0, 1)).ravel(), h) for a, b in S])
    got = cf.linear_response(H_conj, np.fft.fft2(test))
    np.testing.assert_allclose(got.ravel(), expected, atol=1e-10)


def test_mosse_without_regularisation_matches_lstsq(rng):
    f = rng.normal(size=(4, ROWS, COLS))
    g = np.stack([cf.gaussian_labels(ROWS, COLS, 1.0)] * 4)
    S = _shifts(ROWS, COLS)
    X = np.array([np.roll(fi, (-a, -b), axis=(0, 1)).ravel() for fi in f for a, b in S])
    h, *_ = np.linalg.lstsq(X, g.reshape(-1), rcond=None)
    A, B = cf.mosse_terms(np.fft.fft2(f), np.fft.fft2(g))
    h_fft = np.fft.ifft2(np.conj(cf.mosse_filter(A, B, 0.0))).real
    np.testing.assert_allclose(h_fft.ravel(), h, atol=1e-8)


# (c) the Gaussian kernel correlation via FFT equals a loop over shifts --------------------
def test_gaussian_correlation_equals_a_loop(rng):
    sigma = 0.5
    x = rng.normal(size=(4, ROWS, COLS))
    z = rng.normal(size=(2, 4, ROWS, COLS))        # a stack of two test images
    got = cf.gaussian_correlation(np.fft.fft2(x), np.fft.fft2(z), sigma)
    assert got.shape == (2, ROWS, COLS)
    for k in range(2):
        for a, b in _shifts(ROWS, COLS):
            want = _kappa(z[k], np.roll(x, (a, b), axis=(1, 2)), sigma)
            assert got[k, a, b] == pytest.approx(want, abs=1e-12)


# (d) PSR by hand ---------------------------------------------------------------------------
def test_psr_of_a_hand_built_response():
    r = np.zeros((15, 15))
    r[7, 7] = 10.0
    r[0, 0] = 2.0          # outside the 11 x 11 window around (7, 7): in the sidelobe
    r[3, 3] = 50.0 - 45.0  # inside the window: excluded
    # sidelobe: 225 - 121 = 104 values, one 2 and 103 zeros
    mu = 2.0 / 104
    sd = np.sqrt((2.0 - mu) ** 2 / 104 + 103 * mu ** 2 / 104)
    assert cf.psr(r) == pytest.approx((10.0 - mu) / sd, rel=1e-12)


def test_psr_window_wraps_and_flat_is_zero():
    r = np.zeros((15, 15))
    r[0, 0] = 4.0
    r[14, 14] = 1.0        # cyclically next to the peak: excluded
    r[7, 7] = 1.0          # 7 away on both axes: in the sidelobe
    n = 225 - 121
    mu = 1.0 / n
    sd = np.sqrt(((1 - mu) ** 2 + (n - 1) * mu ** 2) / n)
    assert cf.psr(r) == pytest.approx((4.0 - mu) / sd)
    assert cf.psr(np.zeros((15, 15))) == 0.0
    stack = cf.psr(np.stack([r, np.zeros((15, 15))]))
    assert stack.shape == (2,) and stack[1] == 0.0


def test_peak_offset_is_signed_and_refined():
    r = np.zeros((8, 8))
    r[7, 2] = 1.0          # row 7 of 8 is a move of -1
    r[7, 1] = 0.5
    r[7, 3] = 0.5
    assert cf.peak_offset(r) == (-1.0, 2.0)
    r[7, 3] = 0.75         # parabola through 0.5, 1, 0.75: vertex at +0.1667
    assert cf.peak_offset(r)[1] == pytest.approx(2 + 0.25 / 1.5)


# the invariant: a shifted patch gives the shifted response --------------------------------
@settings(max_examples=25, deadline=None)
@given(dy=st.integers(-7, 7), dx=st.integers(-7, 7), seed=st.integers(0, 2 ** 16))
def test_response_of_shifted_patch_is_shifted_response(dy, dx, seed):
    rng = np.random.default_rng(seed)
    x = rng.normal(size=(2, 8, 9))
    z = rng.normal(size=(2, 8, 9))
    xf = np.fft.fft2(x)
    alphaf, _ = cf.kcf_train(xf, np.fft.fft2(cf.gaussian_labels(8, 9, 1.0)), 0.5, 1e-4)
    r = cf.kcf_response(alphaf, xf, np.fft.fft2(z), 0.5)
    rs = cf.kcf_response(alphaf, xf, np.fft.fft2(np.roll(z, (dy, dx), axis=(1, 2))), 0.5)
    np.testing.assert_allclose(rs, np.roll(r, (dy, dx), axis=(0, 1)), atol=1e-9)
    # and the trained patch moved by (dy, dx) puts the peak at (dy, dx)
    peak = cf.kcf_response(alphaf, xf, np.fft.fft2(np.roll(x, (dy, dx), axis=(1, 2))), 0.5)
    py, px = np.unravel_index(np.argmax(peak), peak.shape)
    assert (py, px) == (dy % 8, dx % 9)


def test_labels_and_window_by_hand():
    y = cf.gaussian_labels(5, 4, 1.0)
    assert y[0, 0] == 1.0
    assert y[4, 0] == pytest.approx(np.exp(-0.5))          # row 4 of 5 is offset -1
    assert y[0, 2] == pytest.approx(np.exp(-2.0))          # col 2 of 4 is offset +2
    w = cf.hann_window(5, 4)
    assert w[0, 0] == 0.0 and w[2, 0] == 0.0 and w.max() <= 1.0


def test_orientation_cells_vote_into_one_bin():
    # a vertical step (dark left, bright right): g_x > 0, g_y = 0 -> bin 0 only
    p = np.zeros((1, 8, 12))
    p[:, :, 6:] = 100.0
    c = orientation_cells(p, cell=4, bins=8)
    assert c.shape == (1, 8, 2, 3)
    assert np.all(c[0, 1:] == 0.0)
    assert np.all(c[0, 0][:, 1] > 0) and np.all(c[0, 0][:, 0] == 0)
    assert np.all(orientation_cells(np.full((2, 8, 8), 5.0)) == 0.0)
    with pytest.raises(ValueError, match="stack of grey patches"):
        orientation_cells(np.zeros((8, 8)))
    with pytest.raises(ValueError, match="no 4x4 px cell"):
        orientation_cells(np.zeros((1, 3, 8)))


# (e) tracking ------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def red_cube():
    return clips.load("red-cube")


@pytest.mark.parametrize("name", ["mosse", "kcf"])
def test_tracks_the_red_cube(name, red_cube):
    r = trackbook.evaluate(name, red_cube, seed=0)
    assert r.scores["auc"] > 0.6
    assert r.ok[1:].mean() > 0.9


@pytest.mark.parametrize("name", ["mosse", "kcf"])
def test_same_seed_same_boxes(name, red_cube):
    a = trackbook.evaluate(name, red_cube, seed=3, max_frames=15)
    b = trackbook.evaluate(name, red_cube, seed=3, max_frames=15)
    np.testing.assert_array_equal(a.boxes, b.boxes)


@pytest.mark.parametrize("name", ["mosse", "kcf"])
@pytest.mark.parametrize("value", [0, 128, 255])
def test_flat_frames_are_lost_and_the_box_kept(name, value, red_cube):
    t = trackers.create(name, seed=0)
    t.init(red_cube.frames[0], red_cube.groundtruth[0])
    ok1, box1 = t.update(red_cube.frames[1])
    ok, box = t.update(np.full_like(red_cube.frames[0], value))
    assert ok1 is True and ok is False
    assert box == box1


@pytest.mark.parametrize("name", ["mosse", "kcf"])
def test_tiny_box_and_paper_preset_run(name, red_cube):
    for preset in ("book", "paper"):
        t = trackers.create(name, seed=0, preset=preset)
        t.init(red_cube.frames[0], (100, 100, 3, 2))
        for f in red_cube.frames[1:4]:
            ok, box = t.update(f)
            assert np.all(np.isfinite(box)) and box[2] == 3 and box[3] == 2


def test_paper_values_recorded():
    mosse = trackers.create("mosse", preset="paper").params
    assert (mosse.eta, mosse.psr_threshold, mosse.n_perturbations) == (0.125, 7.0, 8)
    kcf = trackers.create("kcf", preset="paper").params
    assert (kcf.padding, kcf.lam, kcf.kernel_sigma, kcf.eta, kcf.output_sigma_factor) == \
        (1.5, 1e-4, 0.5, 0.02, 0.1)
    assert "bins" in {r["param"] for r in trackers.departures("kcf")}


def test_mosse_reports_a_psr_below_7_lost_without_learning(red_cube):
    """Bolme et al. 2010: a PSR below 7 is a failure and the filter is not updated, whatever
    the failure layer says (here switched off: ``failure=False``)."""
    t = trackers.create("mosse", seed=0, failure=False)
    t.init(red_cube.frames[0], red_cube.groundtruth[0])
    # the target's box filled with uniform noise: the filter finds no peak in it
    f = red_cube.frames[1].copy()
    x, y, w, h = (int(round(v)) for v in red_cube.groundtruth[0])
    f[y:y + h, x:x + w] = np.random.default_rng(0).integers(0, 256, (h, w, 3))
    H = t._H.copy()
    box, conf, own_ok = t._locate(f)
    assert conf < 7 and own_ok is False
    ok, _ = t.update(f)
    assert ok is False and np.array_equal(t._H, H)


def _model(t):
    return [t._H.copy()] if t.name.startswith("mosse") else [t._alphaf.copy(), t._xf.copy()]


@pytest.mark.parametrize("name", ["mosse", "kcf"])
def test_locate_has_no_side_effect_on_the_model(name, red_cube):
    t = trackers.create(name, seed=0)
    t.init(red_cube.frames[0], red_cube.groundtruth[0])
    t.update(red_cube.frames[1])
    before, centre = _model(t), t._centre
    u = copy.deepcopy(t)
    a = u._locate(red_cube.frames[2])
    b = u._locate(red_cube.frames[2])
    np.testing.assert_array_equal(a[0], b[0])
    assert a[1] == b[1] and np.isfinite(a[1])
    assert u._centre == centre
    for m0, m1 in zip(before, _model(u)):
        np.testing.assert_array_equal(m0, m1)


@pytest.mark.parametrize("name", ["mosse", "kcf"])
def test_a_flat_frame_does_not_change_the_model(name, red_cube):
    t = trackers.create(name, seed=0)
    t.init(red_cube.frames[0], red_cube.groundtruth[0])
    t.update(red_cube.frames[1])
    before = _model(t)
    ok, _ = t.update(np.full_like(red_cube.frames[0], 128))
    assert ok is False and np.isfinite(t.state().confidence)
    for m0, m1 in zip(before, _model(t)):
        np.testing.assert_array_equal(m0, m1)


@pytest.mark.parametrize("name", ["mosse", "kcf"])
def test_redetect_finds_a_target_that_jumped_across_the_frame(name):
    """tests/_jump.py: the target still at A, then still at B far away. The canonical name
    loses it and stays lost at A; ``<name>-redetect`` searches the whole frame and ends on B's
    box, on target."""
    from ._jump import A, iou, jump
    clip, box_b = jump()
    for variant in (name, f"{name}-redetect"):
        t = trackers.create(variant, seed=0)
        t.init(clip.frames[0], clip.groundtruth[0])
        oks = [t.update(f)[0] for f in clip.frames[1:]]
        box = np.asarray(t.bbox)
        if variant == name:
            assert not any(oks[15:]) and np.allclose(box[:2], A, atol=1.0)
        else:
            assert all(oks[-5:]) and iou(box, box_b) > 0.9, (oks, box)


# (f) the lost rule on the scenario clips of the lost matrix ----------------------------------
def _run(name, key, **params):
    from . import _scenarios as S
    sc = S.SCENARIOS[key]()
    t = trackers.create(name, seed=0, **params)
    t.init(sc.clip.frames[0], sc.clip.groundtruth[0])
    out = []
    for i in range(1, len(sc.clip)):
        model = np.copy(t._H if name == "mosse" else t._alphaf)
        ok, box = t.update(sc.clip.frames[i])
        after = t._H if name == "mosse" else t._alphaf
        out.append((i, ok, np.asarray(box, float), np.array_equal(model, after)))
    return sc, out


@pytest.mark.parametrize("name", ["mosse", "kcf"])
def test_a_lost_frame_leaves_the_model_unchanged(name):
    # blank frames are lost whatever the thresholds (whether an occluder is judged lost is
    # the contract test's question, tests/test_failure_contract.py)
    _, out = _run(name, "black")
    lost = [same for _, ok, _, same in out if not ok]
    assert lost and all(lost)
