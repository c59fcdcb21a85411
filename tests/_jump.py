"""A target that jumps across the frame, for the re-detection layer's tests.

The target (the lost-matrix scenarios' sprite, 24 x 30 px) stays still at A for ``n_before``
frames, then still at B, far from A (outside any local search around A), for ``n_after``
frames. The background is the scenarios' grass texture tiled with a period of 48 px in both
directions, and B - A is a whole number of periods, so the target has the same surroundings at
B as at A: a tracker whose model includes some background around the target (KCF's padded
window) answers at B as it did at A, and the failure layer can see it found again. B's centre,
(186, 138), lies on the re-detection layer's grid of the 240 x 180 frame (step 12 px, centres
at 6 + 12 k), so the layer's best box can be exactly the target's.
"""

from __future__ import annotations

import numpy as np

from ._scenarios import _background, _finish, _paste, _target

SIZE = (240, 180)
PERIOD = 48
#: Top-left corners of the target before and after the jump: B = A + (3, 2) periods.
A, B = (30, 27), (30 + 3 * PERIOD, 27 + 2 * PERIOD)


def _tiled_background():
    tile = _background(PERIOD, PERIOD)
    w, h = SIZE
    return np.tile(tile, (h // PERIOD + 1, w // PERIOD + 1, 1))[:h, :w].copy()


def jump(n_before=15, n_after=15, seed=0):
    """``(clip, box_b)``: the clip (the target always whole in view) and its box after the
    jump, ``(B[0], B[1], 24, 30)``."""
    rng = np.random.default_rng(seed)
    bg, t = _tiled_background(), _target()
    frames, gt = [], []
    for i in range(n_before + n_after):
        f = bg.copy()
        x, y = A if i < n_before else B
        gt.append(_paste(f, t, x, y))
        frames.append(f)
    clip = _finish("jump", frames, gt, rng)
    return clip, np.array([B[0], B[1], t.shape[1], t.shape[0]], float)


def iou(a, b) -> float:
    """Intersection over union of two boxes (x, y, w, h), by hand."""
    ix = max(0.0, min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0]))
    iy = max(0.0, min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1]))
    inter = ix * iy
    return inter / (a[2] * a[3] + b[2] * b[3] - inter)
