"""Batched patch sampling equals per-box crops, for any batch size."""
import cv2
import numpy as np

from trackbook.features.patches import sample_patches


def test_patch_of_an_exact_box_is_the_crop(textured_frame):
    boxes = np.array([[10, 20, 16, 24], [100, 50, 16, 24]], dtype=float)
    out = sample_patches(textured_frame, boxes, (16, 24))
    np.testing.assert_array_equal(out[0], textured_frame[20:44, 10:26])
    np.testing.assert_array_equal(out[1], textured_frame[50:74, 100:116])


def test_matches_cv2_resize_of_the_crop(textured_frame):
    # a 32 x 48 box halved to 16 x 24: bilinear sampling at pixel-centre coordinates is
    # what cv2.resize(INTER_LINEAR) does
    crop = textured_frame[30:78, 40:72]
    want = cv2.resize(crop, (16, 24), interpolation=cv2.INTER_LINEAR).astype(int)
    got = sample_patches(textured_frame, [[40, 30, 32, 48]], (16, 24))[0].astype(int)
    assert np.abs(got - want).max() <= 1


def test_large_batches_are_chunked_and_equal_small_ones(textured_frame, rng):
    n = 3000                                   # 3000 x 24 rows > cv2.remap's SHRT_MAX limit
    boxes = np.column_stack([rng.uniform(0, 280, n), rng.uniform(0, 200, n),
                             rng.uniform(8, 40, n), rng.uniform(8, 40, n)])
    big = sample_patches(textured_frame, boxes, (16, 24))
    assert big.shape == (n, 24, 16, 3)
    for i in (0, 1364, 1365, 2999):
        np.testing.assert_array_equal(big[i], sample_patches(textured_frame, boxes[i:i + 1], (16, 24))[0])
