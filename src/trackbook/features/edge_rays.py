"""The 8-ray edge observation model of Kim, Kim & Choi 2016 (chapter ``05_edge_rays`` of the book).

From a point, walk along 8 rays at 45 degree steps and note how far the nearest edge pixel is
on each ray (eq. 1 for the target model M, eq. 4 for a particle's model p). Two sets of rays
are compared through the mean of their two middle distances (eq. 5) and the relative sum of
absolute differences (eq. 6).

Conventions fixed by this module (none is printed)
--------------------------------------------------
- Ray order ``j = 0..7`` is E, NE, N, NW, W, SW, S, SE, i.e. theta_j = 45 * j degrees
  counter-clockwise as seen on the screen (image rows grow downwards, so N is "up").
  ``DIRECTIONS[j]`` is the pixel step ``(dx, dy)`` of ray j.
- A ray starts at the neighbouring pixel: the point itself is never its own nearest edge, so
  every distance is >= 1 and mAvg of eq. 5 can never be 0.
- Distances are Euclidean lengths: ``k`` steps along a diagonal ray measure ``k * sqrt(2)``
  pixels, so a circle of edges gives 8 (nearly) equal distances.
- The frame border acts as an edge just outside the image: a ray that meets no edge gets the
  length of the first step that leaves the frame.
- ``max_length`` (optional) caps every distance: ``d = min(d, max_length)``.

Fast path
---------
:func:`ray_distance_maps` computes, for every pixel at once, the distance along each of the 8
directions: one reverse cumulative-minimum scan per direction (rows for E/W, columns for N/S,
sheared diagonals for the rest). A particle then costs 8 look-ups (:func:`rays_at`). The book
uses these maps for its pictures (:func:`weight_map`).

The tracker uses :func:`rays_at_points` (:func:`ray_steps_at`): a ray never leaves its image
line, so only the rows, columns and diagonals through the particles are gathered, and each
particle finds the next and previous edge on its lines by a binary search. Same numbers, a cost
that grows with the number of distinct lines instead of the frame area.
"""

from __future__ import annotations

import cv2
import numpy as np

#: Ray names in the order of the maps' first axis.
DIRECTION_NAMES = ("E", "NE", "N", "NW", "W", "SW", "S", "SE")
#: Pixel step (dx, dy) of each ray; dy < 0 is up.
DIRECTIONS = np.array([(1, 0), (1, -1), (0, -1), (-1, -1), (-1, 0), (-1, 1), (0, 1), (1, 1)])
#: theta_j of eq. 1, degrees counter-clockwise on screen.
THETAS = np.arange(8) * 45.0
#: Length of one step along ray j (1 or sqrt 2).
STEP_LENGTHS = np.hypot(DIRECTIONS[:, 0], DIRECTIONS[:, 1])

#: The Ratio window of eq. 5-6 (Kim et al. 2016 section 3.2).
RATIO_WINDOW = (0.8, 1.2)


def edge_image(frame: np.ndarray, low: float = 50.0, high: float = 150.0,
               blur: int = 0) -> np.ndarray:
    """Canny (1986) edge map of a BGR (or grey) frame as an (H, W) bool array.

    No edge detector, thresholds or smoothing is printed in Kim et al. (2016); Canny with
    50/150 and no blur are the book's choices (the ``canny_low``, ``canny_high``, ``blur`` params of
    ``edge-ray-pf`` record them as not printed).

    Parameters
    ----------
    frame : (H, W, 3) BGR or (H, W) uint8
    low, high : Canny hysteresis thresholds on the gradient magnitude.
    blur : odd Gaussian kernel size applied first (0 = none); fewer, steadier edges on noisy
        or JPEG-compressed video.
    """
    if low < 0 or high < 0:
        raise ValueError(f"Canny thresholds must be >= 0, got low={low}, high={high}.")
    grey = frame if frame.ndim == 2 else cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)
    if blur and blur > 1:
        k = int(blur) | 1
        grey = cv2.GaussianBlur(grey, (k, k), 0)
    return cv2.Canny(grey, float(low), float(high)) > 0


def _scan_next(A: np.ndarray, out: np.ndarray) -> None:
    """``out[r] = min(A[r+1:], R)`` down the columns of an (R, C) array of hit positions.

    One ``np.minimum`` per row over all columns at once: numpy runs it as a vectorised loop,
    several times faster than ``np.minimum.accumulate`` along the columns.
    """
    R = A.shape[0]
    out[-1] = R  # below the last row lies the frame border, which counts as an edge
    for r in range(R - 2, -1, -1):
        np.minimum(out[r + 1], A[r + 1], out=out[r])


def _shear_view(block: np.ndarray, H: int, W: int) -> np.ndarray:
    """(H, W) view of an (H, W + H - 1) block such that pixel (y, x) sits in column x - y + H - 1.

    Each diagonal x - y = const of the image becomes one column of ``block``, so a scan down the
    columns of ``block`` walks the image along (dx, dy) = (1, 1). The view is strided, not
    copied: writing to it fills the block.
    """
    isz = block.itemsize
    return np.lib.stride_tricks.as_strided(
        block[:, H - 1:], shape=(H, W), strides=(block.strides[0] - isz, isz))


class _Workspace:
    """Scratch arrays of one frame size, reused from frame to frame.

    Fresh multi-megabyte arrays cost page faults on every frame; reusing them halves the time
    of :func:`ray_steps` on a 640x360 frame.
    """

    def __init__(self, H: int, W: int):
        self.dt = dt = np.int16 if max(H, W) < 32000 else np.int32
        Wd = W + H - 1
        self.A = np.empty((H, 2 * W + 4 * Wd), dtype=dt)
        self.nA = np.empty_like(self.A)
        self.X = np.empty((W, 2 * H), dtype=dt)
        self.nX = np.empty_like(self.X)
        self.y = np.arange(H, dtype=dt)[:, None]
        self.x = np.arange(W, dtype=dt)[:, None]
        self.big = dt(max(H, W) + 1)


_WORKSPACES: dict[tuple[int, int], _Workspace] = {}


def _workspace(H: int, W: int) -> _Workspace:
    ws = _WORKSPACES.get((H, W))
    if ws is None:
        if len(_WORKSPACES) >= 4:  # a few sizes (frame, ROI crops) are enough to keep
            _WORKSPACES.pop(next(iter(_WORKSPACES)))
        ws = _WORKSPACES[(H, W)] = _Workspace(H, W)
    return ws


def ray_steps(edges: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
    """Number of steps from every pixel to the nearest edge along each of the 8 rays.

    The per-pixel form of eq. 1 / eq. 4 of Kim et al. 2016 (before step lengths).

    Parameters
    ----------
    edges : (H, W) bool edge map
    out : optional (8, H, W) integer array to write into.

    Returns
    -------
    (8, H, W) int16 (int32 for frames over 32000 px) array, rays in the order of
    :data:`DIRECTION_NAMES`; a ray without an edge gets the number of the first step that
    leaves the frame.

    Notes
    -----
    All rays are reduced to one scan "down the rows": N, S and the four diagonals share one
    (H, 2W + 4(W + H - 1)) array (a flip turns N into S; a shear turns each diagonal into a
    column), E and W share one transposed (W, 2H) array. A cell holds its row index if it is an
    edge (or lies outside the frame, in the sheared blocks) and a large number otherwise; the
    running minimum from below is the row of the nearest edge, and subtracting the cell's own
    row gives the number of steps.
    """
    e = np.asarray(edges, dtype=bool)
    if e.ndim != 2 or e.shape[0] < 1 or e.shape[1] < 1:
        raise ValueError(f"edges must be a non-empty (H, W) bool map, got shape {e.shape}.")
    H, W = e.shape
    ws = _workspace(H, W)
    A, nA, X, nX, y, x, big = ws.A, ws.nA, ws.X, ws.nX, ws.y, ws.x, ws.big
    if out is None:
        out = np.empty((8, H, W), dtype=ws.dt)
    elif out.shape != (8, H, W):
        raise ValueError(f"out must have shape {(8, H, W)}, got {out.shape}.")

    Wd = W + H - 1
    down, up = A[:, :W], A[:, W:2 * W]
    down[...] = big
    np.copyto(down, y, where=e)          # scans of e itself: S, SE, (flipped in x) SW
    up[...] = big
    np.copyto(up, y, where=e[::-1])      # scans of e upside down: N, NE, (flipped in x) NW
    blocks = [(2 * W + k * Wd, 2 * W + (k + 1) * Wd) for k in range(4)]
    for (a, b), src in zip(blocks, (down, up, down[:, ::-1], up[:, ::-1])):
        A[:, a:b] = y                    # cells outside the frame = a hit at that row
        _shear_view(A[:, a:b], H, W)[...] = src
    _scan_next(A, nA)
    np.subtract(nA, y, out=nA)

    eT = np.ascontiguousarray(e.T)
    X[...] = big
    np.copyto(X[:, :H], x, where=eT)
    np.copyto(X[:, H:], x, where=eT[::-1])
    _scan_next(X, nX)
    np.subtract(nX, x, out=nX)

    out[0] = nX[:, :H].T                                          # E
    out[4] = nX[:, H:].T[:, ::-1]                                 # W
    out[6] = nA[:, :W]                                            # S
    out[2] = nA[:, W:2 * W][::-1]                                 # N
    out[7] = _shear_view(nA[:, blocks[0][0]:blocks[0][1]], H, W)                  # SE
    out[1] = _shear_view(nA[:, blocks[1][0]:blocks[1][1]], H, W)[::-1]            # NE
    out[5] = _shear_view(nA[:, blocks[2][0]:blocks[2][1]], H, W)[:, ::-1]         # SW
    out[3] = _shear_view(nA[:, blocks[3][0]:blocks[3][1]], H, W)[::-1, ::-1]      # NW
    return out


def steps_to_lengths(steps, max_length: float | None = None, axis: int = 0) -> np.ndarray:
    """Step counts -> Euclidean lengths (x sqrt 2 on the diagonal rays), capped at ``max_length``.

    ``axis`` is the axis of ``steps`` that runs over the 8 rays.
    """
    shape = [1] * np.ndim(steps)
    shape[axis] = 8
    d = np.asarray(steps, dtype=np.float32) * STEP_LENGTHS.astype(np.float32).reshape(shape)
    if max_length:
        if max_length < 1:
            raise ValueError(f"max_length must be >= 1 pixel (or None), got {max_length}.")
        np.minimum(d, np.float32(max_length), out=d)
    return d


def ray_distance_maps(edges: np.ndarray, max_length: float | None = None) -> np.ndarray:
    """Per-pixel nearest-edge distance along the 8 rays (the fast path of eq. 1 and 4).

    Parameters
    ----------
    edges : (H, W) bool edge map (e.g. :func:`edge_image`)
    max_length : optional cap in pixels; ``None`` or 0 = the frame border is the only limit.

    Returns
    -------
    (8, H, W) float32 array D with ``D[j, y, x]`` = Euclidean distance from pixel (x, y) to
    the nearest edge along ray j (see the module conventions).
    """
    return steps_to_lengths(ray_steps(edges), max_length)


def rays_at(maps: np.ndarray, xy, offset=(0, 0), max_length: float | None = None) -> np.ndarray:
    """The 8 distances at points ``xy`` (N, 2) of ``(x, y)``: eq. 4 for N particles at once.

    Parameters
    ----------
    maps : (8, h, w) distance maps (float) or step counts (int, from :func:`ray_steps`, turned
        into lengths here).
    xy : (N, 2) points in frame coordinates; rounded to the nearest pixel and clipped to the
        maps.
    offset : frame coordinates ``(x0, y0)`` of the maps' pixel (0, 0) (for maps of a crop).
    max_length : optional cap in pixels.

    Returns
    -------
    (N, 8) distances.
    """
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    h, w = maps.shape[1:]
    x = np.clip(np.rint(xy[:, 0] - offset[0]), 0, w - 1).astype(np.intp)
    y = np.clip(np.rint(xy[:, 1] - offset[1]), 0, h - 1).astype(np.intp)
    v = maps[:, y, x].T
    if np.issubdtype(maps.dtype, np.integer):
        return steps_to_lengths(v, max_length, axis=1)
    v = np.asarray(v, dtype=np.float32)
    return np.minimum(v, np.float32(max_length)) if max_length else v


def _steps_to_hits(lines: np.ndarray, r: np.ndarray, t: np.ndarray):
    """Steps from position ``t`` of line ``r`` to the next and to the previous hit.

    ``lines`` is an (R, L + 2) bool array: R lines whose positions 0..L-1 are stored in
    columns 1..L, and whose columns 0 and L + 1 are True (the border just outside the line
    stops every ray). The hits are listed once, in order, as flat indices; each point then
    finds its neighbours by a binary search, so the cost is one pass over the lines plus
    O(N log hits). The sentinels guarantee that both neighbours lie on the point's own line.

    Returns two (N,) int arrays of step counts >= 1: forward (towards larger t) and backward.
    """
    flat = np.flatnonzero(lines)
    q = r * lines.shape[1] + (t + 1)
    i = np.searchsorted(flat, q, side="right")     # flat[i] is the first hit after q
    before = flat[i - 1]                           # the last hit at or before q ...
    before = np.where(before == q, flat[i - 2], before)  # ... unless it is q itself
    return flat[i] - q, q - before


def _line_index(key: np.ndarray, lo: int, n: int):
    """The distinct values of integer ``key`` (all in ``lo .. lo + n - 1``) and each point's
    position among them: ``np.unique(key, return_inverse=True)`` by counting instead of
    sorting (the keys are line numbers of a small range)."""
    present = np.zeros(n, dtype=bool)
    present[key - lo] = True
    inverse = (np.cumsum(present) - 1)[key - lo]
    return np.flatnonzero(present) + lo, inverse


#: Reused (H + 2, W + 2) buffers of :func:`ray_steps_at`, border cells set once.
_FRAMED: dict[tuple[int, int], np.ndarray] = {}


def ray_steps_at(edges: np.ndarray, x, y) -> np.ndarray:
    """Steps to the nearest edge along the 8 rays from pixels ``(x, y)``: eq. 1 / eq. 4 of
    Kim et al. 2016 for N points, exact, without the per-pixel maps.

    Only the image lines that pass through the points matter: the rows for E/W, the columns
    for N/S, the diagonals x - y = const for SE/NW and x + y = const for NE/SW. Those lines are
    gathered from the edge map with a border of "edges" around it (a few hundred lines for a
    particle cloud instead of 8 whole-frame scans), and the next / previous edge of each point
    on its line is found by a binary search in the list of the lines' edge pixels. Gives the
    same numbers as ``ray_steps(edges)[:, y, x]`` (tested), at a cost that grows with the
    number of distinct lines, not with the frame.

    Parameters
    ----------
    edges : (H, W) bool edge map
    x, y : (N,) integer pixel coordinates inside the frame.

    Returns
    -------
    (N, 8) step counts in the order of :data:`DIRECTION_NAMES` (multiply by
    :data:`STEP_LENGTHS`, or use :func:`steps_to_lengths` with ``axis=1``, for distances).
    """
    e = np.asarray(edges, dtype=bool)
    if e.ndim != 2 or e.shape[0] < 1 or e.shape[1] < 1:
        raise ValueError(f"edges must be a non-empty (H, W) bool map, got shape {e.shape}.")
    H, W = e.shape
    x = np.asarray(x, dtype=np.intp).ravel()
    y = np.asarray(y, dtype=np.intp).ravel()
    if x.shape != y.shape:
        raise ValueError(f"x and y must have the same length, got {x.size} and {y.size}.")
    out = np.empty((x.size, 8), dtype=np.intp)
    if x.size == 0:
        return out
    if x.min() < 0 or x.max() >= W or y.min() < 0 or y.max() >= H:
        raise ValueError(f"points must lie inside the {W}x{H} frame; clip them first.")
    # the edge map inside a one-pixel frame of "edges": the border that stops every ray
    framed = _FRAMED.get((H, W))
    if framed is None:
        if len(_FRAMED) >= 4:
            _FRAMED.pop(next(iter(_FRAMED)))
        framed = _FRAMED[(H, W)] = np.ones((H + 2, W + 2), dtype=bool)
    framed[1:-1, 1:-1] = e

    rows, r = _line_index(y, 0, H)                         # E (forward in x), W
    out[:, 0], out[:, 4] = _steps_to_hits(framed[rows + 1], r, x)
    cols, c = _line_index(x, 0, W)                         # S (forward in y), N
    out[:, 6], out[:, 2] = _steps_to_hits(framed[:, cols + 1].T, c, y)
    flat = framed.ravel()
    ty = np.arange(-1, H + 1)
    for key, lo, sign, fwd, bwd in ((x - y, 1 - H, 1, 7, 3), (x + y, 0, -1, 5, 1)):
        # diagonal x - y = d holds pixels (d + y, y): SE forward in y, NW backward;
        # anti-diagonal x + y = s holds (s - y, y): SW forward in y, NE backward.
        # Cells left or right of the frame are clipped onto the border column (an "edge").
        lines, k = _line_index(key, lo, H + W - 1)
        xx = np.clip(lines[:, None] + sign * ty[None, :], -1, W)
        out[:, fwd], out[:, bwd] = _steps_to_hits(flat[(ty + 1) * (W + 2) + (xx + 1)], k, y)
    return out


def rays_at_points(edges: np.ndarray, xy, max_length: float | None = None) -> np.ndarray:
    """The 8 distances at points ``xy`` (N, 2) of ``(x, y)``: eq. 4 of Kim et al. 2016 for N
    particles, computed along the particles' lines only (:func:`ray_steps_at`).

    Points are rounded to the nearest pixel and clipped to the frame, as in :func:`rays_at`;
    the result equals ``rays_at(ray_distance_maps(edges, max_length), xy)``.

    Returns
    -------
    (N, 8) float32 distances.
    """
    e = np.asarray(edges, dtype=bool)
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    H, W = e.shape
    x = np.clip(np.rint(xy[:, 0]), 0, W - 1).astype(np.intp)
    y = np.clip(np.rint(xy[:, 1]), 0, H - 1).astype(np.intp)
    return steps_to_lengths(ray_steps_at(e, x, y), max_length, axis=1)


def median_pair_mean(dis) -> np.ndarray:
    """mAvg / pAvg of eq. 5 (Kim et al. 2016): sort the 8 distances, average the 4th and 5th.

    ``dis`` is (..., 8); returns (...).
    """
    s = np.sort(np.asarray(dis, dtype=float), axis=-1)
    return 0.5 * (s[..., 3] + s[..., 4])


def ratio(p_dis, m_dis) -> np.ndarray:
    """Ratio = pAvg / mAvg of eq. 5 (Kim et al. 2016); 1 means the same median scale."""
    return median_pair_mean(p_dis) / median_pair_mean(m_dis)


def edge_weight(p_dis, m_dis, window=RATIO_WINDOW) -> np.ndarray:
    """Particle weight of eq. 6 (Kim et al. 2016) with the Ratio window of section 3.2.

    w = 1 - sum_j |pDis_j - mDis_j| / sum_j mDis_j, clipped at 0, and w = 0 when the Ratio of
    eq. 5 lies outside ``window = (low, high)`` (the paper's [0.8, 1.2]). The rays are compared
    direction by direction (j is the same theta_j in both sets); the sorting of eq. 5 is used
    only for the Ratio test.

    Parameters
    ----------
    p_dis : (..., 8) distances of the particles (eq. 4)
    m_dis : (8,) distances of the model M (eq. 1)
    window : (low, high) Ratio bounds, low <= high.

    Returns
    -------
    (...) weights in [0, 1].
    """
    low, high = window
    if not low <= high:
        raise ValueError(f"ratio window must have low <= high, got {window}.")
    p = np.asarray(p_dis, dtype=float)
    m = np.asarray(m_dis, dtype=float)
    w = 1.0 - np.abs(p - m).sum(axis=-1) / m.sum(axis=-1)
    r = ratio(p, m)
    inside = (r >= low) & (r <= high)
    return np.where(inside, np.clip(w, 0.0, None), 0.0)


def weight_map(maps: np.ndarray, m_dis, window=RATIO_WINDOW) -> np.ndarray:
    """Eq. 6 for every pixel of the frame at once: the weight surface a particle would see.

    Returns (H, W).
    """
    return edge_weight(np.moveaxis(maps, 0, -1), m_dis, window)
