"""Kernel colour histograms (eq. 1 of Lee et al. 2012) and the Bhattacharyya coefficient.

Oracles: a per-pixel loop over the patch with the paper's binning written out, hand-worked
kernels and histograms, and the definition rho = sum sqrt(p q).
"""

import math

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from trackbook.features.color import (HSV_BINS, bhattacharyya_coefficient, bhattacharyya_distance,
                                      color_histograms, ellipse_kernel, hsv_bin_index,
                                      hsv_bin_index_u8, kernel_weights, weighted_histograms)
from trackbook.features.patches import sample_patches

PATCH = (16, 24)            # (width, height) of the paper
N_BINS = 8 * 8 * 4


def slow_histogram(patch_bgr):
    """eq. 1 as plain loops: each pixel's HSV bin gets its kernel weight 1 - r^2 / r_max^2."""
    hsv = cv2.cvtColor(np.ascontiguousarray(patch_bgr), cv2.COLOR_BGR2HSV).astype(int)
    h, w = hsv.shape[:2]
    cy, cx = h / 2, w / 2
    r2max = max((y + 0.5 - cy) ** 2 + (x + 0.5 - cx) ** 2 for y in range(h) for x in range(w))
    q = np.zeros(N_BINS)
    for y in range(h):
        for x in range(w):
            H, S, V = hsv[y, x]
            u = (min(H * 8 // 180, 7) * 8 + S * 8 // 256) * 4 + V * 4 // 256
            q[u] += 1 - ((y + 0.5 - cy) ** 2 + (x + 0.5 - cx) ** 2) / r2max
    return q / q.sum()


def flat_frame(bgr=(40, 120, 200), shape=(60, 80)):
    frame = np.zeros(shape + (3,), np.uint8)
    frame[:] = bgr
    return frame


# -- the kernel ------------------------------------------------------------------------------

def test_kernel_hand_values():
    """A 2 x 2 patch: every pixel is a farthest pixel (r = 1), so all weights are 0; a 3 x 3
    patch has centre weight 1, edge-midpoints 1 - 1/2 and corners 0."""
    np.testing.assert_allclose(kernel_weights(2, 2), np.zeros((2, 2)))
    np.testing.assert_allclose(kernel_weights(3, 3), [[0, .5, 0], [.5, 1, .5], [0, .5, 0]])
    k = kernel_weights(24, 16)
    assert k.shape == (24, 16)
    assert k[0, 0] == k[0, -1] == k[-1, 0] == k[-1, -1] == 0.0      # the corners: r = 1
    assert k.max() == k[11:13, 7:9].max() < 1.0 and k.min() >= 0.0   # even size: no pixel at r = 0


def test_ellipse_kernel_is_zero_outside_the_inscribed_ellipse():
    k = ellipse_kernel(24, 16)
    yy, xx = np.mgrid[0:24, 0:16]
    r2 = ((xx + 0.5 - 8) / 8) ** 2 + ((yy + 0.5 - 12) / 12) ** 2
    assert np.all(k[r2 >= 1] == 0) and np.all(k[r2 < 1] > 0)
    np.testing.assert_allclose(k[r2 < 1], 1 - r2[r2 < 1])


def test_a_pixel_at_the_border_moves_the_histogram_less_than_at_the_centre():
    """The kernel of eq. 1 in action: recolour one pixel of a flat 16 x 24 box."""
    frame = flat_frame()
    box = np.array([[20.0, 10.0, 16.0, 24.0]])      # exactly the patch size: pixels map 1:1
    h0 = color_histograms(frame, box)[0]
    u_new = hsv_bin_index(np.array([[[255, 0, 0]]], np.uint8))[0, 0]   # pure blue

    def recoloured(y, x):
        f = frame.copy()
        f[10 + y, 20 + x] = (255, 0, 0)
        return color_histograms(f, box)[0]

    centre, border, corner = recoloured(12, 8), recoloured(12, 0), recoloured(0, 0)
    assert centre[u_new] > border[u_new] > 0
    assert np.abs(centre - h0).sum() > np.abs(border - h0).sum() > 0
    np.testing.assert_array_equal(corner, h0)                  # corner weight 0: no change
    k = kernel_weights(24, 16)
    np.testing.assert_allclose(centre[u_new], k[12, 8] / k.sum())


# -- histograms --------------------------------------------------------------------------------

boxes_strategy = hnp.arrays(np.float64, (5, 4), elements=st.floats(0, 1))


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), boxes_strategy)
def test_histograms_sum_to_one(seed, unit_boxes):
    """Any boxes, inside the frame or hanging over its edge, give non-negative rows summing to 1."""
    rng = np.random.default_rng(seed)
    frame = rng.integers(0, 256, (50, 70, 3), dtype=np.uint8)
    boxes = unit_boxes * [90, 70, 60, 50] - [10, 10, 0, 0] + [0, 0, 1, 1]   # w, h >= 1
    H = color_histograms(frame, boxes)
    assert H.shape == (5, N_BINS)
    assert np.all(H >= 0) and np.all(np.isfinite(H))
    np.testing.assert_allclose(H.sum(axis=1), 1.0)


def test_flat_colour_is_one_bin():
    frame = flat_frame((40, 120, 200))
    H = color_histograms(frame, [[5, 5, 30, 20]])[0]
    u = hsv_bin_index(frame[:1, :1])[0, 0]
    assert H[u] == pytest.approx(1.0) and np.count_nonzero(H) == 1


def test_batched_equals_per_box_and_the_slow_loop(textured_frame, rng):
    boxes = np.column_stack([rng.uniform(0, 250, 6), rng.uniform(0, 180, 6),
                             rng.uniform(8, 70, 6), rng.uniform(8, 60, 6)])
    H = color_histograms(textured_frame, boxes)
    for i, b in enumerate(boxes):
        np.testing.assert_allclose(H[i], color_histograms(textured_frame, b[None])[0])
        patch = sample_patches(textured_frame, b[None], PATCH)[0]
        np.testing.assert_allclose(H[i], slow_histogram(patch), rtol=1e-12, atol=1e-15)


def test_weighted_histograms_equals_loop(rng):
    idx = rng.integers(0, 5, (3, 4, 6))
    k = rng.random((4, 6))
    H = weighted_histograms(idx, k, 5)
    for i in range(3):
        q = np.zeros(5)
        for y in range(4):
            for x in range(6):
                q[idx[i, y, x]] += k[y, x]
        np.testing.assert_allclose(H[i], q / q.sum())


def test_zero_kernel_gives_uniform_not_nan():
    H = weighted_histograms(np.zeros((2, 2, 2), int), np.zeros((2, 2)), 4)
    np.testing.assert_allclose(H, 0.25)


@settings(max_examples=30, deadline=None)
@given(hnp.arrays(np.uint8, st.tuples(st.integers(1, 5), st.integers(1, 9), st.just(3))))
def test_lut_bins_equal_arithmetic_bins(img):
    """hsv_bin_index_u8 (cv2.LUT) gives exactly hsv_bin_index's bins."""
    np.testing.assert_array_equal(hsv_bin_index_u8(img), hsv_bin_index(img))


def test_bin_index_hand_cases():
    """OpenCV HSV: H 0..179, S and V 0..255; bins 8 x 8 x 4, u = (h * 8 + s) * 4 + v."""
    px = np.array([[[0, 0, 0],           # black: H = S = V = 0 -> bin 0
                    [255, 255, 255],     # white: S = 0, V = 255 -> v bin 3
                    [0, 0, 255],         # red: H = 0, S = V = 255
                    [255, 0, 0]]],       # blue: H = 120 -> 120 * 8 // 180 = 5
                  np.uint8)
    np.testing.assert_array_equal(hsv_bin_index(px)[0], [0, 3, 7 * 4 + 3, (5 * 8 + 7) * 4 + 3])
    assert HSV_BINS == (8, 8, 4)
    with pytest.raises(ValueError, match="256"):
        hsv_bin_index_u8(px, bins=(16, 16, 4))


# -- Bhattacharyya -----------------------------------------------------------------------------

def test_bhattacharyya_identical_and_disjoint():
    p = np.array([0.1, 0.2, 0.3, 0.4])
    assert bhattacharyya_coefficient(p, p) == pytest.approx(1.0)
    assert bhattacharyya_distance(p, p) == pytest.approx(0.0, abs=1e-7)
    q1, q2 = np.array([0.5, 0.5, 0, 0]), np.array([0, 0, 0.25, 0.75])
    assert bhattacharyya_coefficient(q1, q2) == 0.0
    assert bhattacharyya_distance(q1, q2) == 1.0


def test_bhattacharyya_two_bin_worked_case():
    """p = (1/4, 3/4), q = (3/4, 1/4): rho = 2 sqrt(3/16) = sqrt(3)/2, D = sqrt(1 - sqrt(3)/2).
    p = (1, 0), q = (1/2, 1/2): rho = sqrt(1/2), D = sqrt(1 - 1/sqrt(2))."""
    p, q = np.array([0.25, 0.75]), np.array([0.75, 0.25])
    assert bhattacharyya_coefficient(p, q) == pytest.approx(math.sqrt(3) / 2)
    assert bhattacharyya_distance(p, q) == pytest.approx(math.sqrt(1 - math.sqrt(3) / 2))
    assert bhattacharyya_coefficient([1, 0], [0.5, 0.5]) == pytest.approx(math.sqrt(0.5))
    assert bhattacharyya_distance([1, 0], [0.5, 0.5]) == pytest.approx(0.541196100146197)


@settings(max_examples=50, deadline=None)
@given(hnp.arrays(np.float64, (2, 6), elements=st.floats(0, 1)))
def test_bhattacharyya_is_symmetric_and_bounded(raw):
    raw = raw + 1e-3
    p, q = raw / raw.sum(axis=1, keepdims=True)
    rho = bhattacharyya_coefficient(p, q)
    assert rho == pytest.approx(bhattacharyya_coefficient(q, p))
    assert -1e-12 <= rho <= 1 + 1e-12
    assert 0.0 <= bhattacharyya_distance(p, q) <= 1.0


def test_bhattacharyya_broadcasts_over_rows():
    P = np.array([[0.5, 0.5], [1.0, 0.0], [0.0, 1.0]])
    np.testing.assert_allclose(bhattacharyya_coefficient(P, [1.0, 0.0]),
                               [math.sqrt(0.5), 1.0, 0.0])
