"""Input checks shared by every public entry point (SPEC section 7).

Each check either returns a clean value or raises a ``ValueError`` whose message names the
problem *and* the fix, because the people calling these are students in the middle of an
assignment.
"""

from __future__ import annotations

import math
from numbers import Real

import numpy as np


def check_frame(frame, *, name: str = "frame") -> np.ndarray:
    """Return ``frame`` if it is an H x W x 3 ``uint8`` BGR image, else raise ``ValueError``."""
    if not isinstance(frame, np.ndarray):
        raise ValueError(
            f"{name} must be a numpy array (H x W x 3, uint8, BGR as cv2.imread returns), "
            f"got {type(frame).__name__}. Read frames with cv2.imread or trackbook.clips.load."
        )
    if frame.ndim == 2:
        raise ValueError(
            f"{name} is a grey image of shape {frame.shape}; trackers expect H x W x 3 BGR. "
            "Convert it with cv2.cvtColor(frame, cv2.COLOR_GRAY2BGR)."
        )
    if frame.ndim != 3 or frame.shape[2] not in (3,):
        if frame.ndim == 3 and frame.shape[2] == 4:
            raise ValueError(
                f"{name} has 4 channels (BGRA); trackers expect 3. "
                "Drop alpha with cv2.cvtColor(frame, cv2.COLOR_BGRA2BGR)."
            )
        raise ValueError(
            f"{name} has shape {frame.shape}; trackers expect H x W x 3 (BGR). "
            "Pass one video frame as cv2.imread returns it."
        )
    if frame.dtype != np.uint8:
        raise ValueError(
            f"{name} has dtype {frame.dtype}; trackers expect uint8 in 0..255. "
            "Convert with np.clip(frame * 255, 0, 255).astype(np.uint8) for images in [0, 1]."
        )
    if frame.shape[0] < 2 or frame.shape[1] < 2:
        raise ValueError(f"{name} has shape {frame.shape}: it is empty; pass a real image.")
    return frame


def _fmt(box) -> str:
    """``(10, 20, 30, 0.5)``: a box in plain numbers (no ``np.float64(...)`` in messages)."""
    return "(" + ", ".join(f"{float(v):g}" for v in box) + ")"


def as_box(bbox, *, name: str = "bbox") -> np.ndarray:
    """Return ``bbox`` as a float array ``(x, y, w, h)`` with w, h > 0, else raise."""
    try:
        box = np.asarray(bbox, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ValueError(
            f"{name} must be four numbers (x, y, w, h), got {bbox!r}."
        ) from None
    if box.shape != (4,):
        raise ValueError(
            f"{name} must be four numbers (x, y, w, h): top-left corner, width, height; "
            f"got {box.size} values."
        )
    if not np.all(np.isfinite(box)):
        raise ValueError(f"{name} {_fmt(box)} contains NaN or infinity; pass finite numbers.")
    if box[2] <= 0 or box[3] <= 0:
        raise ValueError(
            f"{name} {_fmt(box)} has zero or negative size; width and height must be > 0 "
            "(the box is (x, y, w, h), not (x1, y1, x2, y2))."
        )
    return box


def clip_box(bbox, frame_shape) -> np.ndarray:
    """Intersect a box ``(x, y, w, h)`` with the frame; raise if nothing is left."""
    box = as_box(bbox)
    H, W = frame_shape[:2]
    if box[2] < 1 or box[3] < 1:
        raise ValueError(
            f"bbox {_fmt(box)} has a side under 1 px ({box[2]:g} x {box[3]:g}); a target box "
            "must be at least 1 x 1 pixel (x, y, w, h in pixels)."
        )
    x0, y0 = max(box[0], 0.0), max(box[1], 0.0)
    x1, y1 = min(box[0] + box[2], float(W)), min(box[1] + box[3], float(H))
    if x1 - x0 < 1 or y1 - y0 < 1:
        raise ValueError(
            f"bbox {_fmt(box)} lies outside the {W}x{H} frame; "
            "give a box inside the image (x, y are the top-left corner in pixels)."
        )
    return np.array([x0, y0, x1 - x0, y1 - y0])


def check_box_in_frame(bbox, frame_shape, *, name: str = "bbox", tol: float = 1.0) -> np.ndarray:
    """Return ``bbox`` if it lies inside the frame (within ``tol`` px), else raise."""
    box = as_box(bbox, name=name)
    H, W = frame_shape[:2]
    x, y, w, h = box
    if x + w <= 0 or y + h <= 0 or x >= W or y >= H:
        raise ValueError(
            f"{name} {_fmt(box)} lies wholly outside the {W}x{H} frame; "
            "give the target's box in pixel coordinates of this frame."
        )
    if x < -tol or y < -tol or x + w > W + tol or y + h > H + tol:
        raise ValueError(
            f"{name} {_fmt(box)} lies partly outside the {W}x{H} frame; "
            "clip it first with trackbook.trackers.clip_box(bbox, frame.shape)."
        )
    return clip_box(box, frame_shape)


def check_seed(seed) -> None:
    """Raise ``ValueError`` unless ``seed`` is None or a non-negative integer (not a bool)."""
    if seed is None:
        return
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)):
        raise ValueError(f"seed must be a non-negative int or None, got {seed!r}.")
    if seed < 0:
        raise ValueError(f"seed = {seed} is negative; pass 0 or a positive integer "
                         "(or None for a fresh random run).")


def check_finite_number(value, *, name: str) -> None:
    """Raise ``ValueError`` if ``value`` is a number that is NaN or infinite."""
    if isinstance(value, bool):
        return
    if isinstance(value, Real) and not math.isfinite(float(value)):
        raise ValueError(f"parameter {name} = {value!r} is not finite; pass a real number.")
    if isinstance(value, (tuple, list)):
        for v in value:
            check_finite_number(v, name=name)


def check_boxes(arr, *, name: str) -> np.ndarray:
    """Return ``arr`` as an N x 4 float array, else raise ``ValueError``."""
    a = np.asarray(arr, dtype=float)
    if a.ndim == 1 and a.shape[0] == 4:
        a = a[None, :]
    if a.ndim != 2 or a.shape[1] != 4:
        raise ValueError(
            f"{name} must be an N x 4 array of boxes (x, y, w, h), got shape {a.shape}."
        )
    return a
