"""Staple (Bertinetto et al. 2016): its two learners, their merge and the tracker.

Expected values come from the spatial-domain ridge regressions solved with
``numpy.linalg.solve`` over all cyclic shifts built explicitly, from slow loops, from closed
forms or by hand -- never from the code under test.
"""
from __future__ import annotations

import numpy as np
import pytest

from trackbook import clips, trackers
from trackbook.clips import rendering as R
from trackbook.filters import staple as st
from trackbook.filters.correlation import gaussian_labels


@pytest.fixture
def rng():
    return np.random.default_rng(11)


def _shifted_rows(x):
    """Row t of the design matrix: every channel of x shifted by t (x_c[y + t]), flattened."""
    C, rows, cols = x.shape
    return np.array([np.roll(x, (-a, -b), axis=(1, 2)).ravel()
                     for a in range(rows) for b in range(cols)])


# -- the template: the Fourier-domain filter is the spatial ridge regression ----------------
@pytest.mark.parametrize("channels", [1, 3])
def test_template_filter_equals_spatial_ridge_regression(rng, channels):
    """One training image: ĥ = ŷ* x̂ / (Σ|x̂|² + λ) (terms / n) is the exact minimiser of
    (1/n) Σ_t (Σ_c <h_c, x_c shifted by t> − y[t])² + λ ||h||², and its response on z is
    Σ_c <h_c, z_c shifted by t>."""
    rows, cols, lam = 5, 6, 0.05
    x = rng.normal(size=(channels, rows, cols))
    z = rng.normal(size=(channels, rows, cols))
    y = gaussian_labels(rows, cols, 1.2)
    n = rows * cols
    X = _shifted_rows(x)
    h = np.linalg.solve(X.T @ X / n + lam * np.eye(X.shape[1]), X.T @ y.ravel() / n)
    expected = (_shifted_rows(z) @ h).reshape(rows, cols)
    num, den = st.dcf_terms(x, y)
    got = st.dcf_response(num, den, z, lam)
    np.testing.assert_allclose(got, expected, rtol=1e-9, atol=1e-12)
    # the filter itself (its spatial form) is the solution h
    h_got = np.fft.irfft2(st.dcf_filter(num, den, lam), s=(rows, cols))
    np.testing.assert_allclose(h_got.ravel(), h, rtol=1e-9, atol=1e-12)


def test_template_response_of_a_stack_is_each_response(rng):
    x = rng.normal(size=(2, 4, 5))
    z = rng.normal(size=(3, 2, 4, 5))
    num, den = st.dcf_terms(x, gaussian_labels(4, 5, 1.0))
    stack = st.dcf_response(num, den, z, 1e-2)
    for i in range(3):
        np.testing.assert_allclose(stack[i], st.dcf_response(num, den, z[i], 1e-2), atol=1e-12)


def test_scale_filter_equals_ridge_regression_over_scale_shifts(rng):
    """The 1-D scale filter (DSST code's convention, terms not divided by S) minimises
    Σ_t (Σ_d <h_d, x_d shifted by t> − y[t])² + λ ||h||² over cyclic shifts along scales."""
    D, S, lam = 4, 9, 0.3
    xs = rng.normal(size=(D, S))
    zs = rng.normal(size=(D, S))
    ys = st.scale_labels(S, 0.25)
    X = np.array([np.roll(xs, -t, axis=1).ravel() for t in range(S)])
    Z = np.array([np.roll(zs, -t, axis=1).ravel() for t in range(S)])
    h = np.linalg.solve(X.T @ X + lam * np.eye(D * S), X.T @ ys)
    num, den = st.scale_terms(xs, ys)
    np.testing.assert_allclose(st.scale_response(num, den, zs, lam), Z @ h, rtol=1e-9,
                               atol=1e-12)


def test_scale_factors_and_labels_by_hand():
    # S = 5, a = 2: a^(3 - s) for s = 1..5; the labels peak at the middle scale (index 2)
    np.testing.assert_allclose(st.scale_factors(5, 2.0), [4, 2, 1, 0.5, 0.25])
    sigma = np.sqrt(5) * 0.5
    np.testing.assert_allclose(st.scale_labels(5, 0.5),
                               np.exp(-0.5 * np.array([4, 1, 0, 1, 4]) / sigma ** 2))
    assert st.scale_window(4).shape == (4,) and st.scale_window(5)[2] == 1.0


# -- the colour model: per-pixel likelihood by hand ------------------------------------------
def test_colour_bins_by_hand():
    # 32 bins: width 8, so 7 -> 0, 8 -> 1, 255 -> 31; joined as (b0 * 32 + b1) * 32 + b2
    p = np.array([[[7, 8, 255]]], np.uint8)
    assert st.colour_bins(p, 32)[0, 0] == (0 * 32 + 1) * 32 + 31
    assert st.colour_bins(np.array([[7, 8, 255]], np.uint8), 32, colour=False).tolist() == \
        [[0, 1, 31]]


def test_object_likelihood_is_the_histogram_ratio_by_hand():
    """A 2 x 3 image, 2 bins per channel (< 128 -> 0): black -> bin 0, (255,0,0) -> bin 4,
    white -> bin 7. Foreground = the first two pixels of row 0: ρ(O) = {0: 1/2, 4: 1/2};
    background = the other four: ρ(B) = {0: 2/4, 4: 1/4, 7: 1/4}. β = ρ(O) / (ρ(O) + ρ(B)):
    bin 0 -> 1/2, bin 4 -> (1/2) / (3/4) = 2/3, bin 7 -> 0."""
    k, b, w = (0, 0, 0), (255, 0, 0), (255, 255, 255)
    img = np.array([[k, b, k], [w, k, b]], np.uint8)
    bins = st.colour_bins(img, 2)
    assert bins.tolist() == [[0, 4, 0], [7, 0, 4]]
    fg_mask = np.array([[1, 1, 0], [0, 0, 0]], float)
    fg = st.colour_histogram(bins, fg_mask, 8)
    bg = st.colour_histogram(bins, 1 - fg_mask, 8)
    np.testing.assert_allclose(fg, [0.5, 0, 0, 0, 0.5, 0, 0, 0])
    np.testing.assert_allclose(bg, [0.5, 0, 0, 0, 0.25, 0, 0, 0.25])
    beta = st.object_likelihood(bins, fg, bg)
    np.testing.assert_allclose(beta, [[0.5, 2 / 3, 0.5], [0.0, 0.5, 2 / 3]])
    # a colour seen in neither region (bin 1) scores 0, as the authors' code sets it
    assert st.object_likelihood(np.array([[1]]), fg, bg)[0, 0] == 0.0


def test_empty_region_histogram_is_zero():
    assert not st.colour_histogram(np.zeros((2, 2), int), np.zeros((2, 2)), 4).any()


# -- the integral image against a slow loop ------------------------------------------------
@pytest.mark.parametrize("box", [(1, 1), (3, 4), (7, 9), (2, 9)])
def test_box_means_equal_a_slow_loop(rng, box):
    img = rng.random((2, 7, 9))
    got = st.box_means(img, box)
    h, w = box
    for n in range(2):
        for i in range(7 - h + 1):
            for j in range(9 - w + 1):
                assert got[n, i, j] == pytest.approx(img[n, i:i + h, j:j + w].mean(), abs=1e-12)
    assert got.shape == (2, 7 - h + 1, 9 - w + 1)
    with pytest.raises(ValueError):
        st.box_means(img, (8, 1))


# -- the merge, on the common grid the authors' code uses ------------------------------------
def test_crop_is_the_square_of_shifts_around_zero_by_hand():
    r = np.arange(25.0).reshape(5, 5)
    # shifts -1, 0, 1 are rows/columns 4, 0, 1 of the cyclic map
    np.testing.assert_array_equal(st.crop_response(r, 3), [[24, 20, 21], [4, 0, 1], [9, 5, 6]])
    with pytest.raises(ValueError):
        st.crop_response(r, 4)
    assert st.odd_floor(18.75) == 17 and st.odd_floor(4) == 3 and st.odd_floor(0.5) == 1


def test_merge_on_the_common_grid_equals_its_formula():
    """A template response that is a plane in the cell shifts, f = 1 + 0.5 dy − 0.25 dx, is
    cut to 5 x 5 cells and resized bilinearly to 11 x 11 px (pixel centres aligned: pixel k
    samples cell (k + 0.5) 5/11 − 0.5, clamped to the crop at the border); a bilinear resize
    of a plane is the plane there. Merged with a hand-made colour response by
    (1 − γ) f_tmpl + γ f_hist."""
    rows, cols, cells, side, gamma = 9, 8, 5, 11, 0.3
    dy = np.where(np.arange(rows) > rows // 2, np.arange(rows) - rows, np.arange(rows))
    dx = np.where(np.arange(cols) > cols // 2, np.arange(cols) - cols, np.arange(cols))
    resp = 1 + 0.5 * dy[:, None] - 0.25 * dx[None, :]
    src = np.clip((np.arange(side) + 0.5) * cells / side - 0.5, 0, cells - 1) - cells // 2
    expected_t = 1 + 0.5 * src[:, None] - 0.25 * src[None, :]
    tmpl = st.response_on_grid(resp, cells, side)
    np.testing.assert_allclose(tmpl, expected_t, atol=1e-5)
    assert tmpl[side // 2, side // 2] == pytest.approx(1.0)      # the centres coincide
    hist = np.add.outer(np.linspace(0, 1, side), np.linspace(1, 0, side)) / 2
    merged = st.merge_responses(tmpl, hist, gamma)
    np.testing.assert_allclose(merged, 0.7 * expected_t + 0.3 * hist, atol=1e-5)
    # a stack of responses is resized response by response
    stack = st.response_on_grid(np.stack([resp, 2 * resp]), cells, side)
    np.testing.assert_allclose(stack[1], 2 * tmpl, atol=1e-5)
    with pytest.raises(ValueError):
        st.merge_responses(tmpl, hist[:-1], gamma)


# -- the tracker ----------------------------------------------------------------------------
def _iou(a, b):
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    ix = max(0.0, min(ax + aw, bx + bw) - max(ax, bx))
    iy = max(0.0, min(ay + ah, by + bh) - max(ay, by))
    return ix * iy / (aw * ah + bw * bh - ix * iy)


def test_staple_follows_the_red_cube():
    clip = clips.load("red-cube")
    frames, gt = list(clip.frames)[:60], clip.groundtruth[:60]
    t = trackers.create("staple", seed=0)
    t.init(frames[0], gt[0])
    ious = [_iou(t.update(f)[1], g) for f, g in zip(frames[1:], gt[1:])]
    assert np.mean(ious) > 0.6 and min(ious[-10:]) > 0.4
    s = t.state()
    assert s.search_window is not None and np.isfinite(s.confidence)
    assert t.response.shape == t.response_template.shape == t.response_histogram.shape
    assert t.scale_response.shape == (t.params.n_scales,)


def _growing_clip(n=40, grow=1.012):
    """A textured sprite growing by ``grow`` a frame over a gravel background, drifting
    right; its boxes are the renderer's exact ones."""
    bg = R.tile(R.crop("gravel", 0, 0, 200, 200), R.W, R.H)
    tex = R.crop("chelsea", 80, 40, 320, 240, size=(40, 34))
    sprite = R.Sprite(tex, np.ones(tex.shape[:2], np.float32))
    frames, boxes = [], []
    for i in range(n):
        c = R.Canvas(bg)
        p = c.paste(sprite, (140 + 0.8 * i, 120), scale=grow ** i)
        frames.append(np.clip(c.img, 0, 255).astype(np.uint8))
        boxes.append(p.box)
    return frames, np.array(boxes)


def test_staple_scale_follows_a_growing_target():
    # the algorithm alone (failure=False): what is checked is the scale filter, not the
    # failure layer's thresholds
    frames, boxes = _growing_clip()
    t = trackers.create("staple", seed=0, failure=False)
    t.init(frames[0], boxes[0])
    for f in frames[1:]:
        t.update(f)
    true = boxes[-1][2] / boxes[0][2]                      # 1.012^39 = 1.59
    assert true > 1.5
    # the estimate follows the growth (the scale filter moves in steps of 1.02)
    assert abs(t.scale / true - 1) < 0.1
    assert _iou(t.bbox, boxes[-1]) > 0.7


def test_staple_reinit_repeats_exactly():
    frames, boxes = _growing_clip(n=8)
    t = trackers.create("staple", seed=0)
    runs = []
    for _ in range(2):
        t.init(frames[0], boxes[0])
        runs.append([t.update(f)[1] for f in frames[1:]])
    assert runs[0] == runs[1]


def test_staple_on_a_grey_sequence_uses_the_grey_histogram():
    frames, boxes = _growing_clip(n=6)
    grey = [np.repeat(f.mean(axis=2, keepdims=True).astype(np.uint8), 3, axis=2) for f in frames]
    t = trackers.create("staple", seed=0)
    t.init(grey[0], boxes[0])
    assert t._grey_sequence and t._fg_hist.shape == (t.params.n_bins,)
    for f in grey[1:]:
        ok, box = t.update(f)
    assert _iou(box, boxes[-1]) > 0.5
