"""CamShift (Bradski 1998): mean-shift on a colour probability image whose window adapts.

Bradski, "Computer vision face tracking for use in a perceptual user interface", Intel
Technology Journal, 1998 (bradski1998). The target is a hue histogram; every frame is turned
into a *back-projection* ``P(x, y)``, the histogram's value at each pixel's hue (pixels too
grey or too dark to have a reliable hue count nothing, as Bradski masks them). Then:

1. **Mean-shift** at a fixed window size: the window's centre moves to the centroid of ``P``
   inside it, ``x_c = M10 / M00, y_c = M01 / M00``, with the moments
   ``M00 = Σ P, M10 = Σ x P, M01 = Σ y P`` over the window; repeated until the move is under
   ``eps`` pixels or ``max_iter`` moves.
2. **Size and orientation** from the converged window's moments. The central second moments
   ``a = μ20 / M00, b = μ11 / M00, c = μ02 / M00`` are the covariance of ``P``; its
   eigen-axes give the orientation ``θ = ½ atan2(2 b, a − c)`` and the standard deviations
   ``σ_l, σ_w`` along and across them; the ellipse has half-axes ``2 σ_l, 2 σ_w``
   (OpenCV's rotated rect has the full sides ``4 σ_l, 4 σ_w``).
3. The next frame's **search window**: Bradski's rule, a side ``s = 2 sqrt(M00 / 256)`` (M00
   of an 8-bit probability image over 256 is the number of "full" pixels, so the window is
   twice the side of the blob), or OpenCV's rule (``window_rule="opencv"``): per axis the
   larger of the rotated rect's two sides projected on it, plus 2 px (narrower than the
   rect's bounding box, which adds the two projections), after the moments were taken over
   the converged window grown by 10 px on every side (``TOLERANCE`` in OpenCV's
   ``camshift.cpp``).

Windows are integer pixel rectangles and pixel ``(i, j)`` sits at ``x = j, y = i``, as in
OpenCV's ``cv::meanShift`` and ``cv::moments``, so that :func:`camshift` with
``window_rule="opencv"`` is the same computation as ``cv2.CamShift`` (``tests/test_camshift.py``
compares them); the moments and iterations here are numpy's own.
"""

from __future__ import annotations

import dataclasses

import cv2
import numpy as np

#: Pixels OpenCV's CamShift grows the converged window by on every side before the final
#: moments (``TOLERANCE`` in ``camshift.cpp``).
OPENCV_TOLERANCE = 10
WINDOW_RULES = ("bradski", "opencv")


@dataclasses.dataclass(frozen=True)
class Moments:
    """Raw and central moments of a probability image over a window (window coordinates)."""

    m00: float
    m10: float
    m01: float
    mu20: float
    mu11: float
    mu02: float


@dataclasses.dataclass(frozen=True)
class CamShiftResult:
    """What one CamShift call found.

    Attributes
    ----------
    center : (cx, cy), the centroid of the probability in the final window, in image pixels
        (pixel ``(i, j)`` at ``x = j, y = i``). ``cv2.CamShift`` returns the centre of its
        next window instead (the centroid rounded to a pixel).
    size : (width, length) of the rotated rect, ``4 σ_w`` and ``4 σ_l`` (OpenCV's order: the
        rect's height is the long side).
    angle : degrees in [0, 180), ``90° + θ`` with θ the long axis's angle from the x axis
        (OpenCV's convention).
    window : (x, y, w, h) integer search window for the next frame.
    m00 : zeroth moment of the probability image over the final window (0: nothing found).
    iterations : mean-shift iterations run.
    """

    center: tuple
    size: tuple
    angle: float
    window: tuple
    m00: float
    iterations: int

    @property
    def ellipse(self) -> tuple:
        """(cx, cy, hx, hy, angle): half-axes along the rect's width and length, in degrees."""
        return (*self.center, self.size[0] / 2.0, self.size[1] / 2.0, self.angle)


def moments(prob: np.ndarray, window) -> Moments:
    """Moments of ``prob`` over the integer window ``(x, y, w, h)`` (clipped to the image).

    Coordinates are relative to the window's top-left pixel, as ``cv2.moments(prob[y:y+h,
    x:x+w])`` gives them.
    """
    x, y, w, h = (int(v) for v in window)
    p = np.asarray(prob, dtype=np.float64)[max(y, 0):y + h, max(x, 0):x + w]
    if p.size == 0:
        return Moments(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    col = p.sum(axis=0)                       # mass per column (x)
    row = p.sum(axis=1)                       # mass per row (y)
    xs = np.arange(p.shape[1], dtype=np.float64)
    ys = np.arange(p.shape[0], dtype=np.float64)
    m00 = float(col.sum())
    m10, m01 = float(col @ xs), float(row @ ys)
    m20, m02 = float(col @ xs**2), float(row @ ys**2)
    m11 = float(ys @ p @ xs)
    if m00 <= 0:
        return Moments(m00, m10, m01, 0.0, 0.0, 0.0)
    xc, yc = m10 / m00, m01 / m00
    return Moments(m00, m10, m01, m20 - xc * m10, m11 - xc * m01, m02 - yc * m01)


def _intersect(rect, width, height):
    """``rect & Rect(0, 0, width, height)`` as OpenCV computes it (empty -> zeros)."""
    x, y, w, h = rect
    x0, y0 = max(x, 0), max(y, 0)
    x1, y1 = min(x + w, width), min(y + h, height)
    if x1 <= x0 or y1 <= y0:
        return (0, 0, 0, 0)
    return (x0, y0, x1 - x0, y1 - y0)


def _round(v: float) -> int:
    """OpenCV's cvRound: to nearest, ties to even."""
    return int(np.rint(v))


def mean_shift(prob: np.ndarray, window, max_iter: int = 10, eps: float = 1.0):
    """Move an integer window to the centroid of ``prob`` inside it until it stops.

    The iteration of ``cv::meanShift``: the window keeps its size and stays inside the image;
    it moves by the rounded offset of the centroid from its centre; it stops when the squared
    move is below ``round(eps^2)`` or after ``max_iter`` moves, or where ``prob`` is all zero.

    Returns
    -------
    window : (x, y, w, h) ints
    iterations : int
    """
    prob = np.asarray(prob)
    H, W = prob.shape[:2]
    x, y, w, h = (int(v) for v in window)
    if w <= 0 or h <= 0:
        raise ValueError(f"mean_shift: window {tuple(window)} has a side <= 0; pass w, h >= 1.")
    clipped = _intersect((x, y, w, h), W, H)
    eps2 = _round(max(float(eps), 0.0) ** 2)
    cur = (x, y, w, h)
    i = 0
    for i in range(max(int(max_iter), 1)):  # noqa: B007 (i is returned)
        cur = _intersect(cur, W, H)
        if cur == (0, 0, 0, 0):
            cur = (W // 2, H // 2, 0, 0)
        cur = (cur[0], cur[1], max(cur[2], 1), max(cur[3], 1))
        m = moments(prob, cur)
        if abs(m.m00) < np.finfo(float).eps:
            break
        dx = _round(m.m10 / m.m00 - clipped[2] * 0.5)
        dy = _round(m.m01 / m.m00 - clipped[3] * 0.5)
        nx = min(max(cur[0] + dx, 0), W - cur[2])
        ny = min(max(cur[1] + dy, 0), H - cur[3])
        dx, dy = nx - cur[0], ny - cur[1]
        cur = (nx, ny, cur[2], cur[3])
        if dx * dx + dy * dy < eps2:
            break
    return cur, i


def orientation(m: Moments):
    """Angle and standard deviations of the probability mass from its central moments.

    Returns
    -------
    theta : radians, the angle of the long axis from the x axis, ``½ atan2(2b, a − c)``
        written as OpenCV does, ``atan2(2b, a − c + sqrt(4b² + (a − c)²))``, and 90° where
        that form gives the short axis (``b = 0, a < c``: OpenCV swaps the axes there too).
    sigma_l, sigma_w : standard deviations along the long and the short axis.
    """
    if m.m00 <= 0:
        return 0.0, 0.0, 0.0
    a, b, c = m.mu20 / m.m00, m.mu11 / m.m00, m.mu02 / m.m00
    root = np.sqrt(4 * b * b + (a - c) ** 2)
    theta = float(np.arctan2(2 * b, a - c + root))
    cs, sn = np.cos(theta), np.sin(theta)
    var_l = max(0.0, cs * cs * a + 2 * cs * sn * b + sn * sn * c)
    var_w = max(0.0, sn * sn * a - 2 * cs * sn * b + cs * cs * c)
    if var_l < var_w:
        # b = 0 and a < c (a blob longer in y than in x): the half-angle form gives
        # atan2(0, 0) = 0, the short axis; the long one is at 90 degrees
        var_l, var_w, theta = var_w, var_l, np.pi / 2 - theta
    return theta, float(np.sqrt(var_l)), float(np.sqrt(var_w))


def camshift(prob: np.ndarray, window, max_iter: int = 10, eps: float = 1.0,
             window_rule: str = "bradski", aspect: float = 1.0) -> CamShiftResult:
    """One frame of CamShift on the probability image ``prob`` (H x W, values 0..255).

    Parameters
    ----------
    prob : (H, W) array, the back-projection (see :func:`back_projection`).
    window : (x, y, w, h) integer start window (the last frame's ``result.window``).
    max_iter, eps : mean-shift termination, as ``cv2.TermCriteria`` (COUNT | EPS).
    window_rule : ``"bradski"`` (the next window has side ``s = 2 sqrt(M00 / 256)``, height
        ``aspect * s``, centred on the centroid; moments over the converged window) or
        ``"opencv"`` (``cv2.CamShift``'s: moments over the window grown by 10 px a side, next
        window per axis the larger projection of the rect's sides + 2 px).
    aspect : height / width of Bradski's window (1.2 for his faces).

    Returns
    -------
    CamShiftResult
        ``size = (4 σ_w, 4 σ_l)`` and ``angle = 90° + θ`` folded into [0, 180), as OpenCV's
        ``RotatedRect`` (whose ``height`` is the long side). With nothing under the window
        (M00 = 0) the centre is NaN, the size 0 and the window the converged one.
    """
    if window_rule not in WINDOW_RULES:
        raise ValueError(f"camshift: window_rule={window_rule!r}; pass one of {WINDOW_RULES}.")
    prob = np.asarray(prob)
    if prob.ndim != 2:
        raise ValueError(f"camshift: prob has shape {prob.shape}; pass a 2-D image.")
    H, W = prob.shape
    win, iters = mean_shift(prob, window, max_iter, eps)
    if window_rule == "opencv":
        x, y, w, h = win
        x, y = max(x - OPENCV_TOLERANCE, 0), max(y - OPENCV_TOLERANCE, 0)
        w, h = min(w + 2 * OPENCV_TOLERANCE, W - x), min(h + 2 * OPENCV_TOLERANCE, H - y)
        win = (x, y, w, h)
    m = moments(prob, win)
    if abs(m.m00) < np.finfo(float).eps:
        nan = float("nan")
        return CamShiftResult((nan, nan), (0.0, 0.0), 0.0, tuple(win), 0.0, iters)
    theta, s_l, s_w = orientation(m)
    length, width = 4 * s_l, 4 * s_w
    cs, sn = np.cos(theta), np.sin(theta)
    if length < width:                        # theta at 0 or 90 degrees: axes swapped
        length, width, cs, sn = width, length, sn, cs
        theta = np.pi / 2 - theta
    cx_win, cy_win = m.m10 / m.m00 + win[0], m.m01 / m.m00 + win[1]
    if window_rule == "opencv":
        xc, yc = _round(cx_win), _round(cy_win)
        ww = min(max(_round(abs(length * cs)), _round(abs(width * sn))) + 2, (W - xc) * 2)
        wh = min(max(_round(abs(length * sn)), _round(abs(width * cs))) + 2, (H - yc) * 2)
        nx, ny = max(0, xc - ww // 2), max(0, yc - wh // 2)
        new = (nx, ny, min(W - nx, ww), min(H - ny, wh))
    else:
        s = 2.0 * np.sqrt(m.m00 / 256.0)
        ww, wh = max(_round(s), 1), max(_round(aspect * s), 1)
        nx = min(max(_round(cx_win - ww / 2.0), 0), max(W - ww, 0))
        ny = min(max(_round(cy_win - wh / 2.0), 0), max(H - wh, 0))
        new = (nx, ny, min(ww, W), min(wh, H))
    angle = float(np.degrees(np.pi / 2 + theta)) % 360.0
    if angle >= 180.0:
        angle -= 180.0
    return CamShiftResult((float(cx_win), float(cy_win)), (float(width), float(length)), angle,
                          tuple(int(v) for v in new), float(m.m00), iters)


# -- the hue histogram and its back-projection -------------------------------------------------
def hue_mask(hsv: np.ndarray, s_min: int, v_min: int, v_max: int) -> np.ndarray:
    """Pixels whose hue is trusted: saturation >= ``s_min`` and ``v_min`` <= value <= ``v_max``
    (OpenCV 8-bit HSV). Bradski ignores pixels too grey or too dark for their hue to mean
    anything."""
    s, v = hsv[..., 1], hsv[..., 2]
    return (s >= s_min) & (v >= v_min) & (v <= v_max)


def _hsv(bgr: np.ndarray) -> np.ndarray:
    return cv2.cvtColor(np.ascontiguousarray(bgr), cv2.COLOR_BGR2HSV)


def hue_bins(hsv: np.ndarray, bins: int) -> np.ndarray:
    """Bin of every pixel's hue (0..179 in OpenCV) among ``bins`` equal intervals."""
    return (hsv[..., 0].astype(np.int32) * bins) // 180


def hue_histogram(bgr: np.ndarray, box, bins: int = 16, s_min: int = 60, v_min: int = 32,
                  v_max: int = 255) -> np.ndarray:
    """The target's hue histogram over the integer ``box`` (x, y, w, h), scaled so its largest
    bin is 255 (a back-projection is then an 8-bit probability image); all zeros when no
    pixel of the box has a trusted hue."""
    x, y, w, h = (int(round(v)) for v in box)
    hsv = _hsv(bgr[max(y, 0):y + h, max(x, 0):x + w])
    keep = hue_mask(hsv, s_min, v_min, v_max)
    hist = np.bincount(hue_bins(hsv, bins)[keep], minlength=bins).astype(np.float64)
    top = hist.max() if hist.size else 0.0
    return hist * (255.0 / top) if top > 0 else hist


def background_weights(bgr: np.ndarray, box, bins: int = 16, s_min: int = 60, v_min: int = 32,
                       v_max: int = 255, margin: float = 1.0) -> np.ndarray:
    """Comaniciu, Ramesh & Meer 2003's background weights ``v_u = min(o* / o_u, 1)`` of the hue
    bins, ``o`` the hue histogram of the ring around ``box`` (the box grown by ``margin`` times
    its side on every side, the box left out) and ``o*`` its smallest non-zero bin: a hue
    common around the target counts less in the target's histogram. Bins absent from the
    ring weigh 1."""
    H, W = bgr.shape[:2]
    x, y, w, h = (int(round(v)) for v in box)
    mx, my = int(round(margin * w)), int(round(margin * h))
    x0, y0, x1, y1 = max(x - mx, 0), max(y - my, 0), min(x + w + mx, W), min(y + h + my, H)
    hsv = _hsv(bgr[y0:y1, x0:x1])
    keep = hue_mask(hsv, s_min, v_min, v_max)
    yy, xx = np.mgrid[y0:y1, x0:x1]
    keep &= ~((xx >= x) & (xx < x + w) & (yy >= y) & (yy < y + h))
    o = np.bincount(hue_bins(hsv, bins)[keep], minlength=bins).astype(np.float64)
    if not np.any(o > 0):
        return np.ones(bins)
    o_star = o[o > 0].min()
    return np.where(o > 0, np.minimum(o_star / np.where(o > 0, o, 1.0), 1.0), 1.0)


def back_projection(bgr: np.ndarray, hist: np.ndarray, s_min: int = 60, v_min: int = 32,
                    v_max: int = 255) -> np.ndarray:
    """The 8-bit probability image: each trusted pixel gets its hue bin's histogram value
    (rounded), every other pixel 0."""
    hsv = _hsv(bgr)
    lut = np.rint(np.clip(np.asarray(hist, float), 0, 255)).astype(np.uint8)
    p = lut[hue_bins(hsv, len(lut))]
    p[~hue_mask(hsv, s_min, v_min, v_max)] = 0
    return p


__all__ = ["CamShiftResult", "Moments", "OPENCV_TOLERANCE", "back_projection", "camshift",
           "background_weights", "hue_bins", "hue_histogram", "hue_mask", "mean_shift", "moments", "orientation"]
