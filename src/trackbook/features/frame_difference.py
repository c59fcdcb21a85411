"""Where is something moving? Frame differencing, the start of Lee 2015's tracker (Fig. 1).

The paper avoids asking the user for a first box: the region that changes between two
frames is the moving object, and its centre seeds the Kalman filter.
"""

from __future__ import annotations

import cv2
import numpy as np

from .._checks import check_frame


def motion_mask(frame0: np.ndarray, frame1: np.ndarray, threshold: float = 25.0,
                open_size: int = 3) -> np.ndarray:
    """Boolean mask of the pixels whose grey level changed by more than ``threshold``.

    A morphological opening with an ``open_size`` square removes isolated noisy pixels.
    """
    g0 = cv2.cvtColor(check_frame(frame0, name="frame0"), cv2.COLOR_BGR2GRAY)
    g1 = cv2.cvtColor(check_frame(frame1, name="frame1"), cv2.COLOR_BGR2GRAY)
    if g0.shape != g1.shape:
        raise ValueError(f"frame0 {g0.shape} and frame1 {g1.shape} must have the same size.")
    mask = (cv2.absdiff(g0, g1) > threshold).astype(np.uint8)
    if open_size > 1:
        mask = cv2.morphologyEx(mask, cv2.MORPH_OPEN, np.ones((open_size, open_size), np.uint8))
    return mask.astype(bool)


def find_moving_region(frame0: np.ndarray, frame1: np.ndarray, threshold: float = 25.0,
                       open_size: int = 3, close_size: int = 15, min_area: int = 16):
    """The bounding box ``(x, y, w, h)`` of the largest moving region between two frames.

    Frame differencing |I₁ − I₀| > threshold, an opening against noise, a closing that joins
    the two halves a moving object leaves in a difference image (its leading and trailing
    edges), then the largest connected component. Returns ``None`` when nothing of at least
    ``min_area`` pixels moved.

    Notes
    -----
    The difference image covers both where the object was and where it is, so the box is the
    union of the two positions: larger than the object by the displacement between the frames.
    A flat (untextured) object changes only at its leading and trailing edges; the closing
    (``close_size`` px square) joins those strips as long as the object is narrower than
    ``close_size`` plus the displacement.
    """
    mask = motion_mask(frame0, frame1, threshold, open_size).astype(np.uint8)
    if close_size > 1:
        mask = cv2.morphologyEx(mask, cv2.MORPH_CLOSE,
                                np.ones((close_size, close_size), np.uint8))
    n, _, stats, _ = cv2.connectedComponentsWithStats(mask, connectivity=8)
    if n <= 1:
        return None
    areas = stats[1:, cv2.CC_STAT_AREA]
    best = 1 + int(np.argmax(areas))
    if areas[best - 1] < min_area:
        return None
    x, y, w, h = stats[best, :4]
    return (float(x), float(y), float(w), float(h))


__all__ = ["motion_mask", "find_moving_region"]
