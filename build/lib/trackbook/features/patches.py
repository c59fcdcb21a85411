"""Cutting many boxes out of a frame at once, resized to one patch size.

Every particle tracker needs the same thing per frame: the image under each of N candidate
boxes, resized to a fixed patch (16 x 24 in Lee et al. 2012). Doing that with one
``cv2.remap`` over a stacked coordinate map is one C call for all particles instead of N
Python-level crops and resizes.
"""

from __future__ import annotations

import cv2
import numpy as np


#: cv2.remap accepts maps with fewer than SHRT_MAX rows.
_REMAP_MAX_ROWS = 32766


def patch_grid(boxes, size) -> tuple[np.ndarray, np.ndarray]:
    """Sampling coordinates of every patch pixel.

    Parameters
    ----------
    boxes : (N, 4) array of ``(x, y, w, h)``
    size : ``(width, height)`` of the output patch

    Returns
    -------
    map_x, map_y : (N, height, width) float32 arrays
        Pixel-centre coordinates in the frame: patch pixel (i, j) samples the frame at
        ``x + (j + 0.5) * w / width - 0.5`` (and likewise in y), so a box that is exactly the
        patch size samples the frame pixels themselves.
    """
    b = np.asarray(boxes, dtype=np.float64).reshape(-1, 4)
    pw, ph = size
    u = (np.arange(pw) + 0.5) / pw
    v = (np.arange(ph) + 0.5) / ph
    map_x = b[:, 0, None, None] + u[None, None, :] * b[:, 2, None, None] - 0.5
    map_y = b[:, 1, None, None] + v[None, :, None] * b[:, 3, None, None] - 0.5
    map_x = np.broadcast_to(map_x, (b.shape[0], ph, pw))
    map_y = np.broadcast_to(map_y, (b.shape[0], ph, pw))
    return map_x.astype(np.float32), map_y.astype(np.float32)


def sample_patches(image: np.ndarray, boxes, size, interpolation=cv2.INTER_LINEAR) -> np.ndarray:
    """Resample the region under each box to a ``size = (width, height)`` patch.

    Parameters
    ----------
    image : (H, W) or (H, W, C) array
    boxes : (N, 4) array of ``(x, y, w, h)``; parts outside the frame repeat the border.
    size : ``(width, height)``
    interpolation : OpenCV flag; ``cv2.INTER_NEAREST`` for label images such as bin indices.

    Returns
    -------
    (N, height, width[, C]) array of ``image.dtype``
    """
    map_x, map_y = patch_grid(boxes, size)
    n, ph, pw = map_x.shape
    if n == 0:
        return np.zeros((0, ph, pw) + image.shape[2:], dtype=image.dtype)
    # Stack the patches vertically into one map so OpenCV does many of them in a single call.
    # cv2.remap refuses maps of SHRT_MAX rows or more, so very large batches go in chunks.
    per_call = max(1, _REMAP_MAX_ROWS // ph)
    out = np.empty((n, ph, pw) + image.shape[2:], dtype=image.dtype)
    for a in range(0, n, per_call):
        b = min(n, a + per_call)
        mx = map_x[a:b].reshape((b - a) * ph, pw)
        my = map_y[a:b].reshape((b - a) * ph, pw)
        out[a:b] = cv2.remap(image, mx, my, interpolation,
                             borderMode=cv2.BORDER_REPLICATE).reshape((b - a, ph, pw) + image.shape[2:])
    return out
