"""HOG of Lee et al. 2012 (eq. 2-5) against a direct per-pixel loop and hand cases."""

import math

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbook.features.hog import HOG_DIM, hog_descriptors, hog_of_patch, hog_of_patches, to_gray
from trackbook.features.patches import sample_patches


def slow_hog(patch, cell=4, bins=8):
    """The paper's five steps written as plain loops over pixels (the oracle)."""
    P = np.asarray(patch, dtype=float)
    h, w = P.shape
    k = [1 / 16, 4 / 16, 6 / 16, 4 / 16, 1 / 16]

    def at(img, y, x):  # replicated border
        return img[min(max(y, 0), h - 1), min(max(x, 0), w - 1)]

    B = np.zeros_like(P)  # step 1: 5x5 Gaussian = outer product of the 5-tap kernel
    for y in range(h):
        for x in range(w):
            B[y, x] = sum(k[i] * k[j] * at(P, y + i - 2, x + j - 2)
                          for i in range(5) for j in range(5))
    D = np.zeros((h // cell, w // cell, bins))
    for y in range(h):
        for x in range(w):
            gx = at(B, y, x + 1) - at(B, y, x - 1)            # eq. 2
            gy = at(B, y + 1, x) - at(B, y - 1, x)
            m = math.sqrt(gx * gx + gy * gy)                   # eq. 3
            t = math.atan2(gy, gx)
            if t < 0:                                          # eq. 4
                t += 2 * math.pi
            u = min(int(t // (math.pi / 4)), bins - 1)
            D[y // cell, x // cell, u] += m                    # eq. 5
    D = D.ravel()
    return D / D.sum() if D.sum() > 1e-9 else np.full(D.size, 1 / D.size)


def test_dim_is_192():
    assert HOG_DIM == 192 == 6 * 4 * 8


@pytest.mark.parametrize("seed", range(5))
def test_equals_slow_loop_on_random_patches(seed):
    rng = np.random.default_rng(seed)
    patch = rng.integers(0, 256, size=(24, 16)).astype(float)
    np.testing.assert_allclose(hog_of_patch(patch), slow_hog(patch), rtol=1e-9, atol=1e-12)


def test_equals_slow_loop_on_smooth_patch_and_other_size():
    yy, xx = np.mgrid[0:12, 0:8]
    patch = 100 + 50 * np.sin(xx / 3.0) * np.cos(yy / 5.0)
    np.testing.assert_allclose(hog_of_patch(patch), slow_hog(patch), rtol=1e-9, atol=1e-12)


def test_blur_matches_opencv_gaussian():
    """The 5-tap kernel is OpenCV's GaussianBlur(5, sigma=0) with replicated borders."""
    from trackbook.features.hog import _blur
    rng = np.random.default_rng(3)
    p = rng.random((24, 16)).astype(np.float64) * 255
    ref = cv2.GaussianBlur(p, (5, 5), 0, borderType=cv2.BORDER_REPLICATE)
    np.testing.assert_allclose(_blur(p[None])[0], ref, atol=1e-9)


def test_batched_equals_per_box():
    rng = np.random.default_rng(1)
    frame = rng.integers(0, 256, size=(60, 80, 3), dtype=np.uint8)
    boxes = np.array([[3, 4, 16, 24], [10.5, 7.25, 30, 41], [-5, -5, 20, 20], [70, 50, 20, 20]])
    d = hog_descriptors(frame, boxes)
    assert d.shape == (4, HOG_DIM)
    gray = to_gray(frame)          # a grey frame is resampled directly
    np.testing.assert_allclose(hog_descriptors(gray, boxes[:1])[0],
                               slow_hog(sample_patches(gray, boxes[:1], (16, 24))[0]), rtol=1e-6)
    for i, b in enumerate(boxes):
        bgr = sample_patches(frame, b[None], (16, 24))[0]
        patch = cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY)        # resize first, then grey
        np.testing.assert_allclose(d[i], slow_hog(patch), rtol=1e-6, atol=1e-9)


def test_flat_patch_is_uniform_not_nan():
    d = hog_of_patch(np.full((24, 16), 77.0))
    assert np.all(np.isfinite(d))
    np.testing.assert_allclose(d, 1 / 192)
    frame = np.full((50, 50, 3), 128, np.uint8)
    np.testing.assert_allclose(hog_descriptors(frame, [[5, 5, 10, 10]]), 1 / 192)


def test_signed_orientation_hand_cases():
    """A ramp brightening to the right votes only bin 0 (theta = 0); to the left only bin 4
    (theta = pi); downwards only bin 2 (theta = pi/2) -- the sign the unsigned HOG loses."""
    yy, xx = np.mgrid[0:24, 0:16].astype(float)
    for img, b in [(xx * 5, 0), (-xx * 5 + 200, 4), (yy * 5, 2), (-yy * 5 + 200, 6)]:
        d = hog_of_patch(img).reshape(6, 4, 8)
        assert np.allclose(d.sum(axis=(0, 1))[b], 1.0), b


def test_layout_cell_row_major():
    """A single step edge in the top-left cell's area votes in cell (0, 0) and its neighbours
    but never in the bottom row of cells."""
    img = np.zeros((24, 16))
    img[:4, 2:] = 100
    d = hog_of_patch(img).reshape(6, 4, 8)
    assert d[0].sum() > 0.5
    assert d[5].sum() == 0


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**31 - 1), st.integers(1, 6))
def test_rows_sum_to_one(seed, n):
    rng = np.random.default_rng(seed)
    patches = rng.random((n, 24, 16)) * rng.choice([0.0, 1e-3, 255.0])
    d = hog_of_patches(patches)
    assert np.all(np.isfinite(d)) and np.all(d >= 0)
    np.testing.assert_allclose(d.sum(axis=1), 1.0)


def test_bad_input():
    with pytest.raises(ValueError, match="multiple"):
        hog_of_patch(np.zeros((10, 10)))
    with pytest.raises(ValueError, match="2-D"):
        hog_of_patch(np.zeros((24, 16, 3)))


def test_bin_edges_are_half_open():
    """Angles exactly on a bin edge k*45 deg belong to bin k (bins are [k, k+1) * 45 deg)."""
    from trackbook.features.hog import orientation_bin
    k = np.arange(8)
    gx = np.round(np.cos(k * np.pi / 4), 12) * 3
    gy = np.round(np.sin(k * np.pi / 4), 12) * 3
    np.testing.assert_array_equal(orientation_bin(gx, gy), k)


def test_many_boxes_beyond_remap_limit():
    """More boxes than one cv2.remap call can take (N * 24 rows >= 32767) are chunked."""
    rng = np.random.default_rng(2)
    frame = rng.integers(0, 256, size=(40, 40, 3), dtype=np.uint8)
    boxes = np.tile([[5.0, 5.0, 16.0, 24.0]], (1500, 1)) + rng.random((1500, 4))
    d = hog_descriptors(frame, boxes)
    assert d.shape == (1500, HOG_DIM)
    np.testing.assert_allclose(d[1400], hog_descriptors(frame, boxes[1400:1401])[0])



def test_bins_on_axes_and_diagonals():
    """Half-open bins [k 45, (k+1) 45): an angle on an axis or a diagonal starts its bin."""
    from trackbook.features.hog import orientation_bin
    for a in (1e-3, 1.0, 37.5):
        gx = np.array([a, -a, -a, a, a, 0.0, -a, 0.0, 0.0])
        gy = np.array([a, a, -a, -a, 0.0, a, 0.0, -a, 0.0])
        np.testing.assert_array_equal(orientation_bin(gx, gy), [1, 3, 5, 7, 0, 2, 4, 6, 0])
    assert orientation_bin(np.array(0.0), np.array(-1.0)) == 6      # 0-d input (03_hog)



def test_orientation_bin_other_bin_counts_and_tiny_negative_angles():
    """The cast-and-mask floor equals floor(theta * bins / 2 pi) mod bins for any bin count,
    and an angle just below 0 is in the last bin, never a bin ``bins``."""
    from trackbook.features.hog import orientation_bin
    rng = np.random.default_rng(5)
    gx, gy = rng.normal(size=(2, 5000))
    theta = np.mod(np.arctan2(gy, gx), 2 * np.pi)
    for bins in (6, 8, 9):
        expected = np.minimum(np.floor(theta * bins / (2 * np.pi)).astype(int), bins - 1)
        np.testing.assert_array_equal(orientation_bin(gx, gy, bins), expected)
    assert orientation_bin(np.array([1.0]), np.array([-1e-9]))[0] == 7


def test_octant_bins_match_a_slow_arctangent_loop_on_an_integer_grid():
    """The 8-bin octant rule (signs and the diagonal) against math.atan2 pixel by pixel on
    every integer gradient in [-20, 20]^2: axes, diagonals and all angles between. An integer
    angle off an edge is at least 1 / (2 * 20^2) rad from it, so the slow loop's 1e-9 nudge
    only moves angles that lie on an edge (which atan2 may round just below it)."""
    import math

    from trackbook.features.hog import orientation_bin
    v = np.arange(-20, 21, dtype=float)
    gx, gy = np.meshgrid(v, v)
    slow = np.empty(gx.shape, dtype=int)
    for i in range(gx.shape[0]):
        for j in range(gx.shape[1]):
            theta = math.atan2(gy[i, j], gx[i, j]) % (2 * math.pi)
            slow[i, j] = int(math.floor(theta * 8 / (2 * math.pi) + 1e-9)) % 8
    np.testing.assert_array_equal(orientation_bin(gx, gy), slow)
    np.testing.assert_array_equal(orientation_bin(gx / 256, gy / 256), slow)   # blurred scale
