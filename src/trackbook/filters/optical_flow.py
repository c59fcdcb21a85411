"""The least-squares motion vector of a target region (eq. 5-8 of Cho & Kang 2005).

The case study ``case_study_cho2005`` of the book. Brightness constancy ``I(x + p, y + q, t + 1) = I(x, y, t)`` (eq. 5),
linearised by Taylor (eq. 6), gives one constraint ``p Ix + q Iy + It = 0`` per pixel (eq. 7).
One (p, q) for the whole region R minimises ``Err(p, q) = sum_R (p Ix + q Iy + It)^2`` (eq. 8),
whose normal equations are the 2x2 system

    [sum Ix^2   sum Ix Iy] [p]      [sum Ix It]
    [sum Ix Iy  sum Iy^2 ] [q]  = - [sum Iy It]

(Horn & Schunck's constraint solved over a region, i.e. one Lucas-Kanade step). The Taylor
expansion only holds for motions of about a pixel, so :func:`motion_vector` can also iterate
the solve (re-warping frame t+1 by the current estimate) and run it coarse to fine on an image
pyramid; ``levels=1, iterations=1`` is the paper's single solve.
"""

from __future__ import annotations

import math

import cv2
import numpy as np


def to_gray(frame: np.ndarray) -> np.ndarray:
    """Float32 grey levels I(x, y) of a BGR (or already grey) image."""
    if frame.ndim == 3:
        frame = cv2.cvtColor(np.ascontiguousarray(frame), cv2.COLOR_BGR2GRAY)
    return frame.astype(np.float32)


def structure_tensor(Ix, Iy) -> np.ndarray:
    """The 2x2 matrix of eq. 8's normal equations: [[sum Ix^2, sum IxIy], [sum IxIy, sum Iy^2]]."""
    return np.array([[np.sum(Ix * Ix), np.sum(Ix * Iy)],
                     [np.sum(Ix * Iy), np.sum(Iy * Iy)]], dtype=float)


def solve_motion(Ix, Iy, It, min_eigenvalue: float = 1.0) -> tuple[float, float, bool]:
    """One least-squares solve of eq. 8: (p, q) minimising sum (p Ix + q Iy + It)^2.

    Returns ``(p, q, ok)``. A flat or edge-only region (the smaller eigenvalue of the structure
    tensor, per pixel, below ``min_eigenvalue`` grey-level^2) has no unique answer (the aperture
    problem): the result is ``(0, 0, False)``.
    """
    G = structure_tensor(Ix, Iy)
    b = -np.array([np.sum(Ix * It), np.sum(Iy * It)], dtype=float)
    n = max(Ix.size, 1)
    lam_min = 0.5 * (G[0, 0] + G[1, 1] - np.hypot(G[0, 0] - G[1, 1], 2 * G[0, 1]))
    if not np.isfinite(lam_min) or lam_min / n < min_eigenvalue:
        return 0.0, 0.0, False
    p, q = np.linalg.solve(G, b)
    if not (np.isfinite(p) and np.isfinite(q)):
        return 0.0, 0.0, False
    return float(p), float(q), True


def pyramid(image, levels: int) -> list:
    """``[I, pyrDown(I), ...]``: up to ``levels`` float32 grey levels of an image (BGR or grey),
    stopping before a level would be smaller than 16 pixels."""
    pyr = [to_gray(image)]
    for _ in range(max(1, int(levels)) - 1):
        if min(pyr[-1].shape) < 16:
            break
        pyr.append(cv2.pyrDown(pyr[-1]))
    return pyr


def _gradients(I):
    # central differences (Ix = dI/dx); np.gradient is the textbook choice and an oracle for cv2
    Iy, Ix = np.gradient(I)
    return Ix, Iy


def motion_vector(prev, curr, box, levels: int = 1, iterations: int = 1,
                  min_eigenvalue: float = 1.0, max_motion: float | None = None):
    """Motion (p, q) of the region ``box = (x, y, w, h)`` from ``prev`` (t) to ``curr`` (t+1).

    Eq. 5-8 of Cho & Kang 2005. ``levels=1, iterations=1`` is the paper's single solve of the
    2x2 normal equations; more ``iterations`` re-sample ``curr`` at (x + p, y + q) and solve
    for the remainder (Lucas-Kanade), more ``levels`` start on a coarser pyramid level so a
    motion of several pixels becomes one of about a pixel there.

    Parameters
    ----------
    prev, curr : BGR or grey images of the same size, or their :func:`pyramid` (a tracker
        computes each frame's pyramid once and uses it as ``curr`` now and ``prev`` next frame)
    box : the region R in ``prev``
    min_eigenvalue : flat-region guard of :func:`solve_motion` (grey-level^2 per pixel)
    max_motion : optional bound on |p|, |q| in pixels; larger answers are taken as failures

    Returns
    -------
    (p, q, ok) : the displacement in pixels and whether it was determined; ``(0, 0, False)``
    for a flat region or a box outside the frame.
    """
    levels = max(1, int(levels))
    pyr0 = prev if isinstance(prev, list) else pyramid(prev, levels)
    pyr1 = curr if isinstance(curr, list) else pyramid(curr, levels)
    pyr0, pyr1 = pyr0[:levels], pyr1[:levels]
    I0, I1 = pyr0[0], pyr1[0]
    if I0.shape != I1.shape or len(pyr0) != len(pyr1):
        raise ValueError(f"prev and curr differ in size ({I0.shape} vs {I1.shape}); "
                         "pass two frames of the same clip.")
    x, y, w, h = (float(v) for v in box)
    H, W = I0.shape
    x0, y0 = max(math.floor(x), 0), max(math.floor(y), 0)
    x1, y1 = min(math.ceil(x + w), W), min(math.ceil(y + h), H)
    if x1 - x0 < 3 or y1 - y0 < 3:
        return 0.0, 0.0, False
    p = q = 0.0               # plain floats: this runs every frame, on small images
    ok_any = False
    for lev in range(len(pyr0) - 1, -1, -1):
        f = 2.0 ** lev
        a0, b0 = math.floor(x0 / f), math.floor(y0 / f)
        a1, b1 = max(math.ceil(x1 / f), a0 + 3), max(math.ceil(y1 / f), b0 + 3)
        P0, P1 = pyr0[lev], pyr1[lev]
        a1, b1 = min(a1, P0.shape[1]), min(b1, P0.shape[0])
        if a1 - a0 < 3 or b1 - b0 < 3:
            if lev > 0:
                p, q = 2.0 * p, 2.0 * q
            continue
        T = P0[b0:b1, a0:a1]
        # the 2x2 matrix of eq. 8 depends on the template only: built once per level, and the
        # re-warped solves below only need the right-hand side (central differences, as
        # np.gradient, on the template's interior pixels)
        gx = ((T[1:-1, 2:] - T[1:-1, :-2]) * 0.5).ravel()
        gy = ((T[2:, 1:-1] - T[:-2, 1:-1]) * 0.5).ravel()
        gxx, gxy, gyy = float(gx @ gx), float(gx @ gy), float(gy @ gy)
        lam_min = 0.5 * (gxx + gyy - math.hypot(gxx - gyy, 2 * gxy))
        det = gxx * gyy - gxy * gxy
        if not (math.isfinite(lam_min) and lam_min / gx.size >= min_eigenvalue and det > 0):
            if lev > 0:
                p, q = 2.0 * p, 2.0 * q
            continue
        inner = T[1:-1, 1:-1].ravel()
        size = (a1 - a0 - 2, b1 - b0 - 2)
        cx, cy = (a0 + a1 - 1) / 2.0, (b0 + b1 - 1) / 2.0
        for _ in range(max(1, int(iterations))):
            # I(x + p, y + q, t + 1) sampled bilinearly (eq. 5's left-hand side)
            Wp = cv2.getRectSubPix(P1, size, (cx + p, cy + q))
            It = Wp.ravel() - inner
            bx, by = -float(gx @ It), -float(gy @ It)
            dp = (gyy * bx - gxy * by) / det            # the 2x2 normal equations of eq. 8
            dq = (gxx * by - gxy * bx) / det
            ok_any = True
            p, q = p + dp, q + dq
            if dp * dp + dq * dq < 1e-4:
                break
        if lev > 0:
            p, q = 2.0 * p, 2.0 * q
    if not ok_any or not (math.isfinite(p) and math.isfinite(q)):
        return 0.0, 0.0, False
    if max_motion is not None and max(abs(p), abs(q)) > max_motion:
        return 0.0, 0.0, False
    return float(p), float(q), True
