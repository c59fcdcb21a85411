"""Point tracking: Shi-Tomasi corners, pyramidal Lucas-Kanade and the forward-backward error.

Shi-Tomasi (Shi & Tomasi 1994)
    The structure tensor of a block B around each pixel,
    ``M = sum_B [[Ix^2, Ix Iy], [Ix Iy, Iy^2]]``, has two eigenvalues; a corner is where the
    smaller one, ``lambda_min = (a + c - sqrt((a - c)^2 + 4 b^2)) / 2``, is large (both
    directions textured). :func:`good_features` keeps the pixels with lambda_min above
    ``quality`` x its maximum that are local maxima of their 3 x 3 neighbourhood, strongest
    first, dropping any closer than ``min_distance`` to a stronger one kept.
Pyramidal Lucas-Kanade (Lucas & Kanade 1981; Bouguet's pyramidal form)
    A window of ``win`` x ``win`` pixels around a point u in I is sought in J at u + d,
    minimising ``sum_W (J(x + d) - I(x))^2``. Linearised, each iteration solves
    ``G delta = -b`` with ``G = sum_W [[Ix^2, Ix Iy], [Ix Iy, Iy^2]]`` (the template's
    structure tensor, as eq. 8 of Cho & Kang 2005 in :mod:`~trackbook.filters.optical_flow`)
    and ``b = sum_W (J(x + d) - I(x)) [Ix, Iy]``, then ``d += delta`` until
    ``|delta| < eps`` or ``iterations`` are spent. It starts on the coarsest pyramid level
    (where a motion of many pixels is a small one) and doubles d down to full resolution.
    Points are solved together (arrays of N windows), the loop runs over levels and
    iterations only. The gradients are 0 outside the image, so the part of a window beyond
    the border adds nothing to G or b. A point is lost (``status=False``) when its window's smaller
    eigenvalue per pixel, ``lambda_min(G) / win^2`` with gradients in grey levels per pixel,
    is below ``min_eigenvalue`` at full resolution (the aperture problem), or when its window
    no longer overlaps the image. Gradients are Scharr's, interpolation bilinear, the
    image's border reflected, as OpenCV's ``calcOpticalFlowPyrLK``.
Forward-backward error (Kalal, Mikolajczyk & Matas 2010)
    Track a point forward from frame t to t+1, then the result backward to t; in a reliable
    track the back-tracked point lands where it started. ``FB = ||x_t - x_t^back||``.
"""

from __future__ import annotations

import cv2
import numpy as np

from .optical_flow import to_gray

__all__ = ["forward_backward", "good_features", "min_eigenvalue_map", "patches_at", "pyramid",
           "track_points"]


def min_eigenvalue_map(image, block: int = 3) -> np.ndarray:
    """lambda_min of the structure tensor summed over a ``block`` x ``block`` block at every pixel.

    Gradients are 3 x 3 Sobel derivatives divided by 8 (grey levels per pixel), the block sum
    a box filter; the image border is reflected (OpenCV's default). Returns an (H, W) float64
    array, >= 0 up to rounding.
    """
    g = to_gray(image).astype(np.float64)
    ix = cv2.Sobel(g, cv2.CV_64F, 1, 0, ksize=3) / 8.0
    iy = cv2.Sobel(g, cv2.CV_64F, 0, 1, ksize=3) / 8.0
    box = dict(ddepth=-1, ksize=(block, block), normalize=False)
    a = cv2.boxFilter(ix * ix, **box)
    b = cv2.boxFilter(ix * iy, **box)
    c = cv2.boxFilter(iy * iy, **box)
    return 0.5 * (a + c - np.sqrt((a - c) ** 2 + 4.0 * b * b))


def good_features(image, max_corners: int = 100, quality: float = 0.01,
                  min_distance: float = 10.0, block: int = 3, mask=None) -> np.ndarray:
    """Shi-Tomasi corners: (n, 2) float array of (x, y), strongest first.

    Parameters
    ----------
    image : BGR or grey image
    max_corners : at most this many (<= 0: no limit)
    quality : keep lambda_min >= quality x max lambda_min
    min_distance : no two corners closer than this (pixels, Euclidean)
    block : side of the block the structure tensor sums over
    mask : optional (H, W) array; corners only where it is non-zero
    """
    lam = min_eigenvalue_map(image, block)
    if not 0 < quality < 1:
        raise ValueError(f"quality={quality!r} must lie in (0, 1): a fraction of the "
                         "strongest corner's eigenvalue.")
    peak = float(lam.max())
    if peak <= 0:
        return np.zeros((0, 2))
    # a local maximum of its 3 x 3 neighbourhood (a grey dilation leaves it unchanged)
    keep = (lam >= quality * peak) & (lam >= cv2.dilate(lam, np.ones((3, 3), np.uint8)))
    if mask is not None:
        keep &= np.asarray(mask) != 0
    ys, xs = np.nonzero(keep)
    order = np.argsort(-lam[ys, xs], kind="stable")
    pts = np.stack([xs[order], ys[order]], 1).astype(float)
    if min_distance > 0:
        chosen = np.zeros(len(pts), bool)
        taken = np.zeros((0, 2))
        r2 = float(min_distance) ** 2
        # a loop over candidate corners (not pixels), each checked against all kept at once
        for i, p in enumerate(pts):
            if len(taken) and np.min(np.sum((taken - p) ** 2, 1)) < r2:
                continue
            chosen[i] = True
            taken = np.vstack([taken, p])
            if 0 < max_corners <= len(taken):
                break
        pts = pts[chosen]
    return pts[:max_corners] if max_corners > 0 else pts


def pyramid(image, levels: int) -> list:
    """``[I, pyrDown(I), ...]``: ``levels`` float32 grey levels (fewer when a level would be
    narrower than the next step can halve)."""
    pyr = [to_gray(image)]
    for _ in range(max(1, int(levels)) - 1):
        if min(pyr[-1].shape) < 8:
            break
        pyr.append(cv2.pyrDown(pyr[-1]))
    return pyr


def _scharr(I):
    # Scharr's 3 x 3 derivative divided by 32: grey levels per pixel, as OpenCV's LK uses
    return (cv2.Scharr(I, cv2.CV_32F, 1, 0) / 32.0, cv2.Scharr(I, cv2.CV_32F, 0, 1) / 32.0)


def _reflect(i, n):
    """Indices reflected about the border without repeating it (OpenCV's BORDER_REFLECT_101)."""
    if n == 1:
        return np.zeros_like(i)
    if i.size and i.min() >= 0 and i.max() < n:
        return i                       # the usual case, every index inside: nothing to do
    period = 2 * (n - 1)
    i = np.abs(i) % period
    return np.where(i >= n, period - i, i)


def _reflect_pair(i0, n):
    """``_reflect(i0, n), _reflect(i0 + 1, n)``: the two neighbours bilinear sampling reads,
    with one range test for both in the usual case (every index and its right neighbour
    inside)."""
    if n > 1 and i0.size and i0.min() >= 0 and i0.max() < n - 1:
        return i0, i0 + 1
    return _reflect(i0, n), _reflect(i0 + 1, n)


def _sample(img, x, y, zero_outside=False):
    """Bilinear samples of ``img`` at float arrays x, y (any shape), border reflected, or 0
    outside the image with ``zero_outside``.

    Exact float64 weights: ``cv2.remap`` rounds positions to 1/32 pixel, coarser than the
    sub-pixel steps Lucas-Kanade converges by."""
    H, W = img.shape
    x0, y0 = np.floor(x), np.floor(y)
    fx, fy = x - x0, y - y0
    x0, y0 = x0.astype(np.intp), y0.astype(np.intp)
    if zero_outside:
        # one row and column of zeros around the image, indices clipped onto it
        f = np.zeros((H + 2, W + 2))
        f[1:-1, 1:-1] = img
        xa, xb = np.clip(x0 + 1, 0, W + 1), np.clip(x0 + 2, 0, W + 1)
        ya, yb = np.clip(y0 + 1, 0, H + 1), np.clip(y0 + 2, 0, H + 1)
    else:
        xa, xb = _reflect_pair(x0, W)
        ya, yb = _reflect_pair(y0, H)
        f = img                        # float32 values promote to float64 with the weights
    # gathers from the flattened image by one flat index each (the same values as f[ya, xa],
    # about 1.5 x faster: this sampling is most of a Lucas-Kanade iteration's cost)
    stride = f.shape[1]
    flat = f.ravel()
    ra, rb = ya * stride, yb * stride
    w1x = 1 - fx
    top = flat[ra + xa] * w1x + flat[ra + xb] * fx
    bottom = flat[rb + xa] * w1x + flat[rb + xb] * fx
    return top * (1 - fy) + bottom * fy


def patches_at(image, points, size: int) -> np.ndarray:
    """(N, size, size) bilinear patches of a grey image centred on each of ``points`` (x, y),
    the border reflected: the patches Median Flow compares by NCC, all sampled at once."""
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    off = np.arange(int(size), dtype=np.float64) - (int(size) - 1) / 2.0
    xs = pts[:, 0, None, None] + off[None, None, :]
    ys = pts[:, 1, None, None] + off[None, :, None]
    xs, ys = np.broadcast_arrays(xs, ys)
    return _sample(np.asarray(image, np.float32), xs, ys)


def track_points(prev, curr, points, win: int = 21, levels: int = 4, iterations: int = 30,
                 eps: float = 0.01, min_eigenvalue: float = 1e-4):
    """Pyramidal Lucas-Kanade of a set of points from ``prev`` to ``curr`` (module docstring).

    Parameters
    ----------
    prev, curr : BGR or grey images of one size, or their :func:`pyramid` lists
    points : (N, 2) array of (x, y) in ``prev``
    win : odd window side in pixels (a window of win x win around each point)
    levels : pyramid levels (1: full resolution only; OpenCV's ``maxLevel`` is levels - 1)
    iterations, eps : at most this many updates per level; stop when |delta| < eps pixels
    min_eigenvalue : the aperture-problem guard: lambda_min(G) / win^2 (grey level^2) below it
        at full resolution marks the point lost

    Returns
    -------
    new_points : (N, 2) float array (a lost point's last estimate)
    status : (N,) bool, whether the point was tracked
    """
    if int(win) < 3 or int(win) % 2 == 0:
        raise ValueError(f"win={win!r} must be an odd number >= 3 (the window is centred "
                         "on the point).")
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    levels = max(1, int(levels))
    p0 = prev[:levels] if isinstance(prev, list) else pyramid(prev, levels)
    p1 = curr[:levels] if isinstance(curr, list) else pyramid(curr, levels)
    if p0[0].shape != p1[0].shape:
        raise ValueError(f"prev and curr differ in size ({p0[0].shape} vs {p1[0].shape}); "
                         "pass two frames of the same clip.")
    levels = min(len(p0), len(p1))
    n = len(pts)
    status = np.ones(n, bool)
    if n == 0:
        return pts.copy(), status
    half = (int(win) - 1) / 2.0
    off = np.arange(int(win), dtype=np.float64) - half
    ox, oy = np.meshgrid(off, off)
    ox, oy = ox.ravel()[None], oy.ravel()[None]                # (1, win^2)
    guess = np.zeros_like(pts)                                 # d at the current level
    for lev in range(levels - 1, -1, -1):
        I, J = p0[lev], p1[lev]
        H, W = I.shape
        u = pts / 2.0 ** lev
        d = guess
        gx, gy = _scharr(I)
        xs, ys = u[:, :1] + ox, u[:, 1:] + oy                  # (N, win^2) template pixels
        # outside the image the gradients are 0 (OpenCV pads them with zeros): pixels of a window
        # that the image does not cover add nothing to G or b, so a window at the border is
        # solved on the part of it that is seen
        T = _sample(I, xs, ys)
        Ix, Iy = _sample(gx, xs, ys, zero_outside=True), _sample(gy, xs, ys, zero_outside=True)
        a, b, c = np.sum(Ix * Ix, 1), np.sum(Ix * Iy, 1), np.sum(Iy * Iy, 1)
        det = a * c - b * b
        lam = 0.5 * (a + c - np.sqrt((a - c) ** 2 + 4 * b * b)) / Ix.shape[1]
        # a window still overlapping the image (its top-left corner, as OpenCV tests it)
        tl = u - half
        inside = (tl[:, 0] >= -win) & (tl[:, 0] < W) & (tl[:, 1] >= -win) & (tl[:, 1] < H)
        solvable = inside & (lam >= min_eigenvalue) & (det > np.finfo(np.float32).eps)
        if lev == 0:
            status &= solvable
        active = solvable.copy()
        safe = np.where(solvable, det, 1.0)
        for _ in range(max(1, int(iterations))):
            if not active.any():
                break
            k = np.flatnonzero(active)
            q = u[k] + d[k]
            tl = q - half
            out = (tl[:, 0] < -win) | (tl[:, 0] >= W) | (tl[:, 1] < -win) | (tl[:, 1] >= H)
            if out.any():                                      # the window left the image
                if lev == 0:
                    status[k[out]] = False
                active[k[out]] = False
                k, q = k[~out], q[~out]
            diff = _sample(J, q[:, :1] + ox, q[:, 1:] + oy) - T[k]
            bx, by = np.sum(diff * Ix[k], 1), np.sum(diff * Iy[k], 1)
            dx = (b[k] * by - c[k] * bx) / safe[k]             # G delta = -b, by Cramer's rule
            dy = (b[k] * bx - a[k] * by) / safe[k]
            d[k, 0] += dx
            d[k, 1] += dy
            active[k[dx * dx + dy * dy < eps * eps]] = False
        guess = 2.0 * d if lev > 0 else d
    new = pts + guess
    status &= np.all(np.isfinite(new), 1)
    return new, status


def forward_backward(prev, curr, points, **lk):
    """Forward-backward error of Kalal, Mikolajczyk & Matas 2010 for each point.

    Tracks ``points`` from ``prev`` to ``curr`` with :func:`track_points`, then the results
    back from ``curr`` to ``prev``; FB = distance between each start and its back-tracked
    point.

    Parameters
    ----------
    prev, curr : images or :func:`pyramid` lists, as :func:`track_points`
    points : (N, 2) array of (x, y) in ``prev``
    **lk : ``win``, ``levels``, ``iterations``, ``eps``, ``min_eigenvalue`` of
        :func:`track_points`

    Returns
    -------
    forward : (N, 2) points in ``curr``
    fb_error : (N,) float, ``inf`` where either direction lost the point
    status : (N,) bool, both directions tracked
    """
    fwd, s1 = track_points(prev, curr, points, **lk)
    back, s2 = track_points(curr, prev, fwd, **lk)
    status = s1 & s2
    fb = np.linalg.norm(back - np.asarray(points, float).reshape(-1, 2), axis=1)
    fb[~status] = np.inf
    return fwd, fb, status
