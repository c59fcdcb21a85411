"""DSST (Danelljan et al. 2014): the filters against their spatial definitions, the tracker.

Expected values come from the ridge regressions over all cyclic shifts written out as dense
matrices and solved with ``numpy.linalg.solve``, from closed forms worked by hand, or from
rendered clips whose boxes are known exactly -- never from the FFT code under test.
"""
from __future__ import annotations

import numpy as np
import pytest

import trackbook
from trackbook import clips, trackers
from trackbook.features.gradient_cells import CLIP, orientation_cells
from trackbook.filters import scale_filter as sf

from . import _scenarios as S


@pytest.fixture
def rng():
    return np.random.default_rng(11)


def _shift_matrix(f):
    """Rows t: the sample cyclically shifted by t, flattened over (channels, *signal).

    With ``(h ⋆ f)[t] = Σ_y f[y] h[y − t] = Σ_y f[y + t] h[y]``, row t holds f[· + t], so
    the response of h is ``M @ h.ravel()``.
    """
    d, *signal = f.shape
    axes = tuple(range(1, f.ndim))
    rows = []
    for t in np.ndindex(*signal):
        rows.append(np.roll(f, tuple(-s for s in t), axis=axes).ravel())
    return np.array(rows)


def _ridge(f, g, lam):
    """argmin_h ‖M h − g‖² + λ ‖h‖², solved densely: (MᵀM + λI) h = Mᵀ g."""
    M = _shift_matrix(f)
    h = np.linalg.solve(M.T @ M + lam * np.eye(M.shape[1]), M.T @ g.ravel())
    return h.reshape(f.shape)


# (a) the multi-channel translation filter is its spatial ridge regression ---------------------
@pytest.mark.parametrize("channels", [1, 3])
def test_translation_filter_equals_spatial_ridge_regression(rng, channels):
    rows, cols, lam = 5, 6, 0.05
    f = rng.normal(size=(channels, rows, cols))
    g = np.exp(-0.5 * ((np.arange(rows)[:, None] - 2) ** 2 + (np.arange(cols) - 3) ** 2))
    h = _ridge(f, g, lam)

    A, B = sf.multichannel_terms(np.fft.fft2(f), np.fft.fft2(g), 2)
    H = sf.multichannel_filter(A, B, lam, 2)
    np.testing.assert_allclose(np.fft.ifft2(H).real, h, atol=1e-10)
    np.testing.assert_allclose(np.fft.ifft2(H).imag, 0.0, atol=1e-10)

    # the response on another sample is the dense filter applied to all its shifts
    z = f + 0.5 * rng.normal(size=f.shape)
    got = sf.multichannel_response(A, B, np.fft.fft2(z), lam, 2)
    np.testing.assert_allclose(got, (_shift_matrix(z) @ h.ravel()).reshape(rows, cols),
                               atol=1e-10)


def test_translation_response_stack_matches_one_by_one(rng):
    f = rng.normal(size=(2, 4, 4))
    A, B = sf.multichannel_terms(np.fft.fft2(f), np.fft.fft2(rng.normal(size=(4, 4))), 2)
    Z = np.fft.fft2(rng.normal(size=(3, 2, 4, 4)))
    stack = sf.multichannel_response(A, B, Z, 0.1, 2)
    for i in range(3):
        np.testing.assert_allclose(stack[i], sf.multichannel_response(A, B, Z[i], 0.1, 2))


@pytest.mark.parametrize("ndim,shape", [(2, (5, 6)), (2, (4, 7)), (1, (33,)), (1, (8,))])
def test_real_dft_path_equals_the_full_one(rng, ndim, shape):
    # the tracker keeps half spectra (the features are real): same terms, same responses
    f, z = rng.normal(size=(2, 3) + shape)
    g = rng.normal(size=shape)
    A, B = sf.multichannel_terms(sf.spectra(f, ndim), sf.spectra(g, ndim), ndim)
    Ah, Bh = sf.multichannel_terms(sf.spectra(f, ndim, half=True),
                                   sf.spectra(g, ndim, half=True), ndim)
    full = sf.multichannel_response(A, B, sf.spectra(z, ndim), 0.1, ndim)
    half = sf.multichannel_response(Ah, Bh, sf.spectra(z, ndim, half=True), 0.1, ndim, shape)
    np.testing.assert_allclose(half, full, atol=1e-12)


def test_response_peaks_at_the_shift(rng):
    # a sample moved by (1, 2) puts the peak of a filter trained on g peaked at 0 at (1, 2)
    f = rng.normal(size=(3, 8, 8))
    g = np.zeros((8, 8))
    g[0, 0] = 1.0
    A, B = sf.multichannel_terms(np.fft.fft2(f), np.fft.fft2(g), 2)
    r = sf.multichannel_response(A, B, np.fft.fft2(np.roll(f, (1, 2), axis=(1, 2))), 1e-6, 2)
    assert np.unravel_index(np.argmax(r), r.shape) == (1, 2)


# (b) the scale filter is ridge regression over the scale samples -----------------------------
@pytest.mark.parametrize("n_scales,dims", [(7, 5), (33, 4)])
def test_scale_filter_equals_ridge_regression_over_scales(rng, n_scales, dims):
    lam = 0.01
    # d-dimensional samples at each of the S scales, windowed over the scales as in DSST
    x = rng.normal(size=(dims, n_scales)) * sf.scale_window(n_scales)[None, :]
    y = sf.scale_labels(n_scales, sf.scale_sigma(n_scales, 0.25))
    h = _ridge(x, y, lam)

    A, B = sf.multichannel_terms(np.fft.fft(x, axis=-1), np.fft.fft(y), 1)
    H = sf.multichannel_filter(A, B, lam, 1)
    np.testing.assert_allclose(np.fft.ifft(H, axis=-1).real, h, atol=1e-10)
    z = x + 0.3 * rng.normal(size=x.shape)
    np.testing.assert_allclose(sf.multichannel_response(A, B, np.fft.fft(z, axis=-1), lam, 1),
                               _shift_matrix(z) @ h.ravel(), atol=1e-10)


def test_scale_response_on_the_training_sample_is_its_label_shrunk(rng):
    # with one sample, y = Σ_l Ā^l F^l / (B + λ) = G B / (B + λ): for λ → 0 the label itself,
    # so the argmax is the middle scale (n = 0)
    S = 33
    x = rng.normal(size=(6, S)) * sf.scale_window(S)
    y = sf.scale_labels(S, 1.4)
    X = np.fft.fft(x, axis=-1)
    A, B = sf.multichannel_terms(X, np.fft.fft(y), 1)
    r = sf.multichannel_response(A, B, X, 1e-9, 1)
    np.testing.assert_allclose(r, y, atol=1e-6)
    assert sf.scale_exponents(S)[np.argmax(r)] == 0


def test_running_average_of_terms():
    A, B = sf.update_terms(np.array([2.0]), np.array([4.0]), np.array([6.0]), np.array([0.0]),
                           0.25)
    np.testing.assert_allclose([A[0], B[0]], [0.75 * 2 + 0.25 * 6, 3.0])


# (c) the scale search's geometry, by hand --------------------------------------------------
def test_scale_geometry_by_hand():
    np.testing.assert_array_equal(sf.scale_exponents(5), [-2, -1, 0, 1, 2])
    np.testing.assert_array_equal(sf.scale_exponents(4), [-1, 0, 1, 2])
    np.testing.assert_allclose(sf.scale_factors(3, 1.02), [1 / 1.02, 1.0, 1.02])
    assert sf.scale_sigma(33, 0.25) == pytest.approx(np.sqrt(33) / 4)
    np.testing.assert_allclose(sf.scale_labels(3, 1.0), [np.exp(-0.5), 1.0, np.exp(-0.5)])
    # MATLAB's hann(5) = [0, .5, 1, .5, 0]; an even S takes hann(S + 1) without its first value
    np.testing.assert_allclose(sf.scale_window(5), [0, 0.5, 1, 0.5, 0], atol=1e-15)
    np.testing.assert_allclose(sf.scale_window(4), [0.5, 1, 0.5, 0], atol=1e-15)
    # 48 x 24 px = 1152 > 512: shrunk by sqrt(512 / 1152) = 2/3 -> 32 x 16
    assert sf.scale_model_size((48, 24), 512) == (32, 16)
    assert sf.scale_model_size((20, 10), 512) == (20, 10)
    # window 40 x 20: 5 / 20 = 0.25 -> 1.02^ceil(ln 0.25 / ln 1.02) = 1.02^-70;
    # target 20 x 10 in 320 x 240: min(16, 24) = 16 -> 1.02^floor(ln 16 / ln 1.02) = 1.02^140
    lo, hi = sf.scale_limits((40, 20), (20, 10), (320, 240), 1.02)
    assert lo == pytest.approx(1.02 ** -70) and hi == pytest.approx(1.02 ** 140)


def test_pixel_orientation_cells_by_their_definition(rng):
    # 1-px cells (DSST's translation features): pixel (r, c) puts m / sqrt(Σ_{3x3} m²), clipped
    # at CLIP, into the bin of its gradient's angle; loops over the pixels, borders replicated
    g = rng.random((2, 7, 9)) * 255
    g[1, :, :4] = 40.0                                      # a flat part: zero channels there
    bins = 8
    got = orientation_cells(g, cell=1, bins=bins)
    assert got.shape == (2, bins, 7, 9)
    for n in range(2):
        p = np.pad(g[n], 1, mode="edge")
        gx = p[1:-1, 2:] - p[1:-1, :-2]
        gy = p[2:, 1:-1] - p[:-2, 1:-1]
        m = np.hypot(gx, gy)
        mp = np.pad(m, 1, mode="edge")
        expected = np.zeros((bins, 7, 9))
        for r in range(7):
            for c in range(9):
                e = np.sum(mp[r:r + 3, c:c + 3] ** 2)
                b = int(np.floor(np.arctan2(gy[r, c], gx[r, c]) % (2 * np.pi) / (2 * np.pi)
                                 * bins)) % bins
                expected[b, r, c] = min(m[r, c] / np.sqrt(e + 1e-12), CLIP)
        np.testing.assert_allclose(got[n], expected, atol=1e-12)


# (d) the tracker --------------------------------------------------------------------------
@pytest.fixture(scope="module")
def red_cube():
    return clips.load("red-cube")


def test_tracks_the_red_cube(red_cube):
    r = trackbook.evaluate("dsst", red_cube, seed=0)
    assert r.scores["auc"] > 0.6
    assert r.ok[1:].mean() > 0.9


def _growing_clip(n=45, grow=1.6):
    return S.growing_target(n, grow)


def test_scale_follows_a_growing_target():
    frames, boxes = _growing_clip()
    t = trackers.create("dsst", seed=0, failure=False)
    t.init(frames[0], boxes[0])
    widths = [t.update(f)[1][2] for f in frames[1:]]
    # the truth grows by 1.6; the estimate within 6 % at the end, and growing throughout
    ratio = widths[-1] / boxes[-1][2]
    assert 0.94 < ratio < 1.06, ratio
    assert t.scale == pytest.approx(widths[-1] / boxes[0][2])
    assert widths[-1] > 1.4 * boxes[0][2]
    centre = np.asarray(t.bbox[:2]) + np.asarray(t.bbox[2:]) / 2
    assert np.linalg.norm(centre - (boxes[-1][:2] + boxes[-1][2:] / 2)) < 3.0


def test_state_and_drawing_attributes(red_cube):
    t = trackers.create("dsst", seed=0)
    t.init(red_cube.frames[0], red_cube.groundtruth[0])
    t.update(red_cube.frames[1])
    st = t.state()
    assert st.search_window is not None and np.isfinite(st.confidence)
    assert t.scale_response.shape == (t.params.n_scales,)
    assert t.response.shape == t.filter.shape[1:]


@pytest.mark.parametrize("value", [0, 255])
def test_flat_frames_are_lost_and_the_box_kept(value, red_cube):
    t = trackers.create("dsst", seed=0)
    t.init(red_cube.frames[0], red_cube.groundtruth[0])
    ok1, box1 = t.update(red_cube.frames[1])
    ok, box = t.update(np.full_like(red_cube.frames[0], value))
    assert ok1 is True and ok is False
    assert box == box1
