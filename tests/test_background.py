"""Background subtraction by a per-pixel mixture of Gaussians (``trackbook.filters.background``).

Oracle: ``cv2.createBackgroundSubtractorMOG2(detectShadows=False)`` with the same parameters,
on a generated clip (a static textured background, a moving sprite, Gaussian noise). Measured:
the masks are identical on every frame of that clip (IoU 1.0). They may differ where float32
sums are taken in another order (a distance exactly at a threshold), where two components
tie in weight and are ordered differently, and where OpenCV prunes a component (it drops the
last slot, assuming the pruned one is the last); the threshold below, mean IoU >= 0.99 after
a 20-frame warm-up, leaves room for those and nothing else.

From the definition: a static background converges to no foreground; a new object is
foreground; it is absorbed into the background at the first frame where the old background's
weight, decayed by ``(1 - α)`` a frame, falls below ``background_ratio`` (computed below by
the scalar recurrence of the update rule: about ``ln(1 / 0.9) / α`` frames, a tenth of 1/α,
because the new component joins the background as soon as the components before it weigh
less than the ratio, long before it is the heaviest).
"""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from trackbook.filters.background import MixtureOfGaussians, detections
from trackbook.mot import Sort

H, W = 90, 120


def _background(seed=0):
    rng = np.random.default_rng(seed)
    tiles = rng.integers(40, 200, (H // 6, W // 6, 3)).astype(np.uint8)
    return cv2.resize(tiles, (W, H), interpolation=cv2.INTER_NEAREST).astype(np.float32)


def _clip(n, sprites, noise=6.0, seed=0, enter=0):
    """Frames of the textured background with ``sprites``: (row, start col, speed, colour),
    drawn from frame ``enter`` on."""
    rng = np.random.default_rng(seed)
    bg = _background(seed)
    frames, truth = [], []
    for t in range(n):
        f = bg.copy()
        boxes = []
        for row, col, speed, colour in (sprites if t >= enter else []):
            x = int(col + speed * t)
            f[row:row + 16, x:x + 14] = colour
            boxes.append((x, row, 14, 16))
        frames.append(np.clip(f + rng.normal(0, noise, f.shape), 0, 255).astype(np.uint8))
        truth.append(boxes)
    return frames, truth


def _iou(a, b):
    a, b = a > 0, b > 0
    union = (a | b).sum()
    return 1.0 if union == 0 else float((a & b).sum() / union)


@pytest.mark.parametrize("rate", [None, 0.01])
def test_masks_agree_with_opencv_mog2(rate):
    frames, _ = _clip(80, [(30, 5, 1.5, (30, 30, 220))])
    ours = MixtureOfGaussians(learning_rate=rate, history=500, var_threshold=16,
                              background_ratio=0.9, n_components=5)
    ocv = cv2.createBackgroundSubtractorMOG2(history=500, varThreshold=16, detectShadows=False)
    ocv.setBackgroundRatio(0.9)
    ocv.setNMixtures(5)
    ious = []
    for f in frames:
        a = ours.apply(f)
        b = ocv.apply(f, learningRate=-1 if rate is None else rate)
        ious.append(_iou(a, b))
    assert np.mean(ious[20:]) >= 0.99 and min(ious[20:]) >= 0.95


def test_a_static_noisy_background_converges_to_no_foreground():
    bg = _background()
    rng = np.random.default_rng(3)
    mog = MixtureOfGaussians(learning_rate=0.02)
    for _ in range(60):
        m = mog.apply(np.clip(bg + rng.normal(0, 3, bg.shape), 0, 255).astype(np.uint8))
    # noise of sigma 3 per channel: the background keeps it within var_threshold 16 sigma^2
    # but for the rare chi-square tail
    assert (m > 0).mean() < 0.005
    clean = MixtureOfGaussians(learning_rate=0.02)
    assert np.all(clean.apply(bg.astype(np.uint8)) == 255)       # nothing known yet
    assert np.all(clean.apply(bg.astype(np.uint8)) == 0)         # the same frame again


def _absorbed_after(alpha, ratio, c_t):
    """Frames after the object appears until it is background, from the update rule for one
    pixel with the old background (weight a) and the object's component (weight b): each frame
    a' = (1 - α) a - α c_T, b' = (1 - α) b - α c_T + α (b owns the value), renormalised; the
    object is background once the weight checked before it, a', is below the ratio."""
    a, b = 1.0 - alpha, alpha          # the frame it appears: b created, a scaled by (1 - α)
    n = 0
    while True:
        n += 1
        a1 = (1 - alpha) * a - alpha * c_t
        b1 = (1 - alpha) * b - alpha * c_t + alpha
        if a1 < ratio or b1 >= a1:
            return n
        a, b = a1 / (a1 + b1), b1 / (a1 + b1)


def test_a_new_object_is_foreground_then_absorbed_on_the_computed_frame():
    alpha = 0.01
    bg = _background().astype(np.uint8)
    mog = MixtureOfGaussians(learning_rate=alpha)
    for _ in range(30):
        mog.apply(bg)
    obj = bg.copy()
    obj[20:40, 30:60] = (250, 10, 10)                  # far from every background tile
    expected = _absorbed_after(alpha, 0.9, 0.05)
    assert 10 <= expected <= 11                        # ln(1 / 0.9) / 0.01 = 10.5
    masks = [mog.apply(obj) for _ in range(expected + 3)]
    for k, m in enumerate(masks):
        inside = m[20:40, 30:60]
        assert np.all(inside == (255 if k < expected else 0)), k
        assert not m[45:, :].any()                     # the rest stays background


def test_detections_are_the_components_boxes():
    m = np.zeros((40, 50), np.uint8)
    m[5:15, 10:18] = 255                               # 80 px
    m[20:30, 30:45] = 255                              # 150 px, with a hole
    m[24, 35] = 0
    m[35, 5] = 255                                     # a speck
    np.testing.assert_array_equal(detections(m, min_area=20), [[10, 5, 8, 10], [30, 20, 15, 10]])
    assert detections(m, min_area=1).shape == (3, 4)
    assert detections(np.zeros((4, 4)), 1).shape == (0, 4)
    with pytest.raises(ValueError, match="H x W"):
        detections(np.zeros((4, 4, 3)))


def test_detections_of_two_moving_sprites_give_sort_two_tracks():
    # the sprites enter after 10 frames of background; at α = 0.005 a pixel of one colour is
    # absorbed after about ln(1 / 0.9) / α = 21 frames, and a sprite 14 px wide moving 1.5 px
    # a frame covers a pixel for at most 10
    frames, truth = _clip(60, [(15, 5, 1.5, (30, 30, 220)), (60, 100, -1.5, (220, 60, 20))],
                          enter=10, noise=2.0)
    mog = MixtureOfGaussians(learning_rate=0.005)
    sort = Sort(max_age=1, min_hits=3, iou_threshold=0.3)
    ids, n_det = set(), []
    for t, f in enumerate(frames):
        mask = mog.apply(f)
        if t < 10:                                     # warm-up: the first frames are all new
            continue
        det = detections(mask, min_area=40)
        n_det.append(len(det))
        out = sort.update(det)
        ids.update(int(r[4]) for r in out)
        if t >= 14:
            assert len(out) == 2
            for x, y, w, h, _ in out:                  # each track on one sprite
                best = max(_box_iou((x, y, w, h), b) for b in truth[t])
                assert best > 0.5
    assert np.mean(n_det) == pytest.approx(2.0, abs=0.1)
    assert len(ids) == 2


def _box_iou(a, b):
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    iw = max(0.0, min(ax + aw, bx + bw) - max(ax, bx))
    ih = max(0.0, min(ay + ah, by + bh) - max(ay, by))
    return iw * ih / (aw * ah + bw * bh - iw * ih)


def test_bad_input_names_the_fix():
    with pytest.raises(ValueError, match="learning_rate"):
        MixtureOfGaussians(learning_rate=2.0)
    with pytest.raises(ValueError, match="background_ratio"):
        MixtureOfGaussians(background_ratio=0.0)
    mog = MixtureOfGaussians()
    mog.apply(np.zeros((10, 12, 3), np.uint8))
    with pytest.raises(ValueError, match="reset"):
        mog.apply(np.zeros((10, 13, 3), np.uint8))
    mog.reset()
    assert mog.apply(np.zeros((10, 13), np.uint8)).shape == (10, 13)
