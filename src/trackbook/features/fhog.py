"""Felzenszwalb's 31-channel HOG (FHOG), as the correlation-filter trackers compute it.

Felzenszwalb, Girshick, McAllester & Ramanan, "Object detection with discriminatively trained
part-based models", TPAMI 2010, section 6: per cell, 18 contrast-sensitive and 9
contrast-insensitive orientation channels, each normalised by the energies of the four 2 x 2
cell blocks that contain the cell and truncated at 0.2, plus 4 texture (gradient energy)
channels. KCF, DSST, Staple and BACF all call Piotr Dollár's toolbox implementation
(``channels/fhog.m`` and ``channels/private/gradientMex.cpp`` of github.com/pdollar/toolbox,
``fhog(I, binSize, nOrients, clip)``, which the toolbox says gives "nearly identical results to
features.cc in code release version 5"); this module follows that code's conventions, listed
in :func:`fhog`, so a tracker fed with it sees the features its authors' code saw.

Departures from the reference code, all at the level of its floating-point shortcuts: the
gradient magnitude is the exact square root (the reference uses SSE's approximate reciprocal
square root, relative error ~4e-4), the orientation bin is the exact nearest centre (found
by comparing a pseudo-angle with the bin edges, which needs no ``atan2``; the reference looks
``arccos`` up in a table of 10^4 steps, so gradients within 1e-4 of vertical count as
vertical) and a pixel with no gradient votes nothing (the reference floors the magnitude at
1e-10, which leaves values ~1e-7 on a flat image).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

#: Cell side in pixels used by KCF, DSST, Staple and BACF (the toolbox's own default is 8).
CELL = 4
#: Contrast-insensitive orientations; the sensitive ones are twice as many (section 6.1).
N_ORIENT = 9
#: Truncation of the normalised histogram values, alpha = 0.2 (section 6.1).
CLIP = 0.2
#: Weight of the texture channels, ~ 1/sqrt(18): the constant in ``hogChannels`` of the
#: reference code and in ``features.cc`` of the DPM release.
TEXTURE_SCALE = 0.2357
#: Factor applied once per image side a boundary cell lies on: with the bilinear spatial votes
#: a boundary cell receives 7/8 of an interior cell's weight (``gradHist`` of the reference).
BOUNDARY_GAIN = 8.0 / 7.0


def _gradients(imgs: np.ndarray, order: tuple[int, ...]
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per-pixel gradient (gx, gy) of the colour channel with the largest gradient norm.

    Central differences (I(x+1) - I(x-1)) / 2, one-sided I(1) - I(0) and I(w-1) - I(w-2) on
    the first and last column (and likewise for rows), as ``grad1`` of the reference computes
    them. ``imgs`` is (n, h, w, c) float32; ``order`` lists the channels in the reference's
    order (R, G, B), which decides ties. Returns gx, gy and gx^2 + gy^2, (n, h, w) float32.
    """
    gx = np.empty_like(imgs); gy = np.empty_like(imgs)
    np.subtract(imgs[:, :, 2:], imgs[:, :, :-2], out=gx[:, :, 1:-1]); gx[:, :, 1:-1] *= 0.5
    np.subtract(imgs[:, :, 1], imgs[:, :, 0], out=gx[:, :, 0])
    np.subtract(imgs[:, :, -1], imgs[:, :, -2], out=gx[:, :, -1])
    np.subtract(imgs[:, 2:], imgs[:, :-2], out=gy[:, 1:-1]); gy[:, 1:-1] *= 0.5
    np.subtract(imgs[:, 1], imgs[:, 0], out=gy[:, 0])
    np.subtract(imgs[:, -1], imgs[:, -2], out=gy[:, -1])
    first = order[0]
    norm2 = gx * gx + gy * gy
    bx, by, best = gx[..., first], gy[..., first], norm2[..., first]
    # A later channel wins only with a strictly larger squared norm, so a tie keeps the first,
    # as the reference's "greater than" over channels in order does.
    for c in order[1:]:
        wins = norm2[..., c] > best
        best = np.where(wins, norm2[..., c], best)
        bx = np.where(wins, gx[..., c], bx); by = np.where(wins, gy[..., c], by)
    return bx, by, best


@lru_cache(maxsize=16)
def _bin_edges(n_sens: int) -> np.ndarray:
    """Edges between the orientation bins, as values of the pseudo-angle of :func:`_bins`.

    Edge k lies half-way between centres k and k + 1, moved clockwise by 1e-9 of a bin so
    that a gradient exactly on it goes to the counter-clockwise bin (the reference's tie rule).
    """
    theta = (np.arange(n_sens) + 0.5 - 1e-9) * (2.0 * np.pi / n_sens)
    c, s = np.cos(theta), np.sin(theta)
    q = c / (np.abs(c) + np.abs(s))
    return np.where(s >= 0, 1.0 - q, 3.0 + q)


def _bins(gx: np.ndarray, gy: np.ndarray, n_sens: int) -> np.ndarray:
    """Nearest of the ``n_sens`` orientation centres of each gradient, without ``atan2``.

    The pseudo-angle q = 1 - gx / (|gx| + |gy|) for gy >= 0 and 3 + gx / (|gx| + |gy|)
    below grows strictly with the angle atan2(gy, gx) in [0, 2 pi) (from 0 to 4), so the bin
    is the number of bin edges at or below q, taken modulo ``n_sens`` (the last edge is 10 deg
    short of 360 for 18 bins; beyond it is bin 0 again). Computed in float64 so that the
    1e-9-bin tie margin survives rounding.
    """
    x = gx.astype(np.float64); y = gy.astype(np.float64)
    den = np.abs(x) + np.abs(y)
    den[den == 0] = 1.0                  # a zero gradient votes nothing: any bin does
    q = x / den
    q = np.where(y >= 0, 1.0 - q, 3.0 + q)
    b = np.searchsorted(_bin_edges(n_sens), q, side="right")
    b[b == n_sens] = 0
    return b


def _spatial_votes(n: int, cell: int, cells: int) -> tuple[np.ndarray, np.ndarray]:
    """Bilinear votes of pixels 0..n-1 along one axis into ``cells`` cells.

    Pixel p sits at cell coordinate u = (p + 0.5) / cell - 0.5; it votes 1 - (u - floor u) to
    cell floor(u) and u - floor(u) to cell floor(u) + 1; votes to cells outside
    0..cells-1 are dropped. Returns (index, weight), each (n, 2), with dropped votes given
    weight 0 and a clipped index.
    """
    u = (np.arange(n) + 0.5) / cell - 0.5
    lo = np.floor(u).astype(np.intp)
    frac = u - lo
    idx = np.stack([lo, lo + 1], axis=1)
    wgt = np.stack([1.0 - frac, frac], axis=1)
    inside = (idx >= 0) & (idx < cells)
    return np.clip(idx, 0, cells - 1), np.where(inside, wgt, 0.0)


@lru_cache(maxsize=16)
def _vote_layout(h0: int, w0: int, cell: int, n_sens: int) -> tuple[np.ndarray, np.ndarray]:
    """The four (cell, weight) spatial votes of every pixel, (h0, w0, 4) each.

    They depend on the image size only, so they are built once per size (a tracker extracts
    patches of a handful of sizes); the index is the flat offset of bin 0 of the cell in the
    (rows, cols, bins) histogram, the weight includes the 1/k^2.
    """
    rows, cols = h0 // cell, w0 // cell
    iy, wy = _spatial_votes(h0, cell, rows)
    ix, wx = _spatial_votes(w0, cell, cols)
    index = (iy[:, None, :, None] * cols + ix[None, :, None, :]) * n_sens
    weight = wy[:, None, :, None] * wx[None, :, None, :] / (cell * cell)
    return index.reshape(h0, w0, 4), weight.reshape(h0, w0, 4)


def _histograms(mag: np.ndarray, obin: np.ndarray, cell: int, n_sens: int) -> np.ndarray:
    """Contrast-sensitive cell histograms C, (n, rows, cols, n_sens) float32, boundary gain
    included.

    One ``bincount`` over the four spatial votes of every pixel. (Separable filtering of an
    (h, w, bins) stack, or matrix products over it, touch 2p times more memory than the
    pixels' votes, and a BLAS call's threads cost more than they save on a shared machine.)
    """
    n, h0, w0 = mag.shape
    rows, cols = h0 // cell, w0 // cell
    index, weight = _vote_layout(h0, w0, cell, n_sens)
    size = rows * cols * n_sens
    flat = index + (obin + (np.arange(n) * size)[:, None, None])[..., None]
    votes = weight * mag[..., None]
    C = np.bincount(flat.ravel(), weights=votes.ravel(), minlength=n * size)
    C = C.astype(np.float32).reshape(n, rows, cols, n_sens)
    C[:, [0, -1]] *= BOUNDARY_GAIN
    C[:, :, [0, -1]] *= BOUNDARY_GAIN
    return C


def _normalise(C: np.ndarray, n_orient: int, clip: float, cell: int,
               zero_channel: bool) -> np.ndarray:
    """Block normalisation, truncation and the analytic projection (steps 4-6 of :func:`fhog`).
    """
    n, rows, cols, n_sens = C.shape
    D = C[..., :n_orient] + C[..., n_orient:]
    E = np.einsum("...b,...b->...", D, D)
    eps = np.float32(1e-4 / (4.0 * cell ** 4))
    N = 1.0 / np.sqrt(E[:, :-1, :-1] + E[:, 1:, :-1] + E[:, :-1, 1:] + E[:, 1:, 1:] + eps)
    P = np.pad(N, ((0, 0), (1, 1), (1, 1)), mode="edge")     # P[:, i + 1, j + 1] = N(i, j)
    # (n, rows, cols, 4): below-right, above-right, below-left, above-left (reference order)
    Nl = np.stack([P[:, 1:, 1:], P[:, :-1, 1:], P[:, 1:, :-1], P[:, :-1, :-1]], axis=-1)
    TC = np.minimum(C[..., None, :] * Nl[..., None], clip)    # (n, rows, cols, 4, 2p)
    TD = np.minimum(D[..., None, :] * Nl[..., None], clip)    # (n, rows, cols, 4, p)
    out = np.zeros((n, rows, cols, 3 * n_orient + 4 + int(zero_channel)), np.float32)
    np.multiply(TC.sum(axis=3), 0.5, out=out[..., :n_sens])
    np.multiply(TD.sum(axis=3), 0.5, out=out[..., n_sens:3 * n_orient])
    np.multiply(TC.sum(axis=4), TEXTURE_SCALE, out=out[..., 3 * n_orient:3 * n_orient + 4])
    return out


def fhog(image: np.ndarray, cell: int = CELL, n_orient: int = N_ORIENT, clip: float = CLIP,
         *, zero_channel: bool = False) -> np.ndarray:
    r"""Felzenszwalb's HOG of an image, one (3·n_orient + 4)-vector per cell.

    Parameters
    ----------
    image : (h, w) grey or (h, w, 3) BGR (OpenCV's order) or (h, w, 1) array, uint8 or float.
        Values are used in the image's own units; the trackers' reference code passes 0..255
        (DSST, Staple, BACF; KCF divides by 255 first), which only matters through the small
        :math:`\varepsilon` below. Needs at least 2 x 2 cells (``h, w >= 2 * cell``).
    cell : int
        Cell side :math:`k` in pixels (4 in the trackers' code).
    n_orient : int
        Number :math:`p` of contrast-insensitive orientations (9); :math:`2p` sensitive ones.
    clip : float
        Truncation :math:`\alpha` of the normalised values (0.2).
    zero_channel : bool
        Append the all-zero last channel of the toolbox's 32-channel output (the
        "truncation" feature of the DPM code); the trackers drop it, hence off by default.

    Returns
    -------
    (h // k, w // k, 3p + 4) float32 array (``+ 1`` channel with ``zero_channel``); with
    ``p = 9``: channels 0-17 contrast-sensitive, 18-26 contrast-insensitive, 27-30 texture.
    An image whose side is not a multiple of :math:`k` keeps ``floor(h / k)`` rows of cells:
    the pixels beyond row :math:`k\lfloor h/k\rfloor` (column :math:`k\lfloor w/k\rfloor`)
    cast no votes, though they still enter the central differences of the pixels before
    them. Cell (0, 0) is the top-left one; the grid is not shifted or cropped.

    Notes
    -----
    1. **Gradient** (``gradMag``). On each colour channel, central differences with
       one-sided differences on the image border,

       .. math:: g_x = \tfrac12\,[I(x+1, y) - I(x-1, y)], \qquad
                 g_y = \tfrac12\,[I(x, y+1) - I(x, y-1)],

       (:math:`g_x = I(1, y) - I(0, y)` on the first column, and so on), y pointing *down*;
       per pixel the channel with the largest :math:`g_x^2 + g_y^2` is kept (first of R, G, B
       on a tie). Magnitude :math:`r = \sqrt{g_x^2 + g_y^2}`, orientation
       :math:`\theta = \operatorname{atan2}(g_y, g_x) \in [0, 2\pi)`.
    2. **Orientation bin** (``gradQuantize`` with ``softBin = -1``): hard, to the nearest of
       :math:`2p` centres :math:`2\pi b / (2p)`,
       :math:`b = \lfloor 2p\,\theta / (2\pi) + \tfrac12 \rfloor \bmod 2p`; an exact tie (for
       :math:`p = 9` only an exactly vertical gradient, at 90° or 270°) goes to the
       counter-clockwise bin, as in the reference (a gradient pointing down is bin 5, up bin 14).
    3. **Spatial votes** (``gradHist``, bilinear in space only): pixel (x, y) sits at cell
       coordinates :math:`u = (x + \tfrac12)/k - \tfrac12`, :math:`v = (y + \tfrac12)/k -
       \tfrac12` and adds :math:`r\,(1 - |u - j|)(1 - |v - i|)/k^2` to bin :math:`b` of each of
       the (up to) four cells (i, j) with :math:`|u - j| < 1, |v - i| < 1` inside the grid.
       This gives the contrast-sensitive histogram :math:`C(i, j, b)`, :math:`b < 2p`. Each
       boundary cell is multiplied by :math:`8/7` once per image side it lies on (a corner
       cell by :math:`(8/7)^2`), because it only received 7/8 of an interior cell's votes.
    4. **Contrast-insensitive** histogram :math:`D(i, j, b) = C(i, j, b) + C(i, j, b + p)`,
       :math:`b < p`, and cell energy :math:`E(i, j) = \sum_b D(i, j, b)^2`.
    5. **Block normalisers** (``hogNormMatrix``): for the block of 2 x 2 cells with top-left
       cell (i, j), :math:`0 \le i < H_c - 1`, :math:`0 \le j < W_c - 1`,

       .. math:: N(i, j) = \bigl(E(i, j) + E(i+1, j) + E(i, j+1) + E(i+1, j+1)
                 + \varepsilon\bigr)^{-1/2}, \qquad \varepsilon = 10^{-4} / (4 k^4),

       (the DPM code's :math:`10^{-4}`, rescaled for the reference's halved differences and
       :math:`1/k^2` votes), and :math:`N` is extended by one block on every side by repeating
       its edge (so a boundary cell reuses its nearest block's normaliser). Cell (i, j) then has
       the four normalisers :math:`N_1 = N(i, j)` (block below-right), :math:`N_2 = N(i-1, j)`
       (above-right), :math:`N_3 = N(i, j-1)` (below-left), :math:`N_4 = N(i-1, j-1)`
       (above-left).
    6. **Features** (``hogChannels``), with :math:`T_\alpha(z) = \min(z, \alpha)`:

       .. math::
          F_b &= \tfrac12 \sum_{l=1}^{4} T_\alpha\bigl(C_b N_l\bigr), \quad b < 2p
          \qquad \text{(contrast-sensitive)}\\
          F_{2p + b} &= \tfrac12 \sum_{l=1}^{4} T_\alpha\bigl(D_b N_l\bigr), \quad b < p
          \qquad \text{(contrast-insensitive)}\\
          F_{3p + l - 1} &= 0.2357 \sum_{b < 2p} T_\alpha\bigl(C_b N_l\bigr), \quad
          l = 1..4 \qquad \text{(texture)}.

    The 0.2357 (~ :math:`1/\sqrt{18}`) is the reference's constant, kept for every ``p``.
    The orientation and texture channels are the paper's analytic projection of the
    :math:`4 \times 2p` normalised, truncated values (section 6.2).
    """
    img = np.asarray(image)
    if img.ndim not in (2, 3):
        raise ValueError(f"image has shape {img.shape}; pass an (h, w) grey image or an "
                         "(h, w, 3) BGR image.")
    return _fhog_batch(img[None], cell, n_orient, clip, zero_channel)[0]


def _fhog_batch(stack: np.ndarray, cell, n_orient, clip, zero_channel: bool) -> np.ndarray:
    """FHOG of an (n, h, w) or (n, h, w, c) stack, c = 1 or 3 (BGR)."""
    if stack.ndim == 3:
        stack = stack[..., None]
    if stack.shape[3] == 3:
        order = (2, 1, 0)                    # BGR: the reference's order R, G, B decides ties
    elif stack.shape[3] == 1:
        order = (0,)
    else:
        raise ValueError(f"image has shape {stack.shape[1:]}; pass an (h, w) grey image or an "
                         "(h, w, 3) BGR image.")
    if int(cell) != cell or cell < 1 or int(n_orient) != n_orient or n_orient < 1:
        raise ValueError(f"cell ({cell}) and n_orient ({n_orient}) must be positive integers.")
    cell, n_orient = int(cell), int(n_orient)
    h, w = stack.shape[1:3]
    rows, cols = h // cell, w // cell
    if rows < 2 or cols < 2:
        raise ValueError(f"an image of {w}x{h} px holds {cols}x{rows} cells of {cell} px; "
                         "FHOG's block normalisation needs at least 2x2 cells.")
    n_sens = 2 * n_orient
    # float32 gradients are exact for 8-bit images (multiples of 1/2 below 2^8)
    gx, gy, norm2 = _gradients(stack.astype(np.float32), order)
    # Only the pixels of whole cells vote; the others entered the differences above.
    h0, w0 = rows * cell, cols * cell
    gx, gy, norm2 = gx[:, :h0, :w0], gy[:, :h0, :w0], norm2[:, :h0, :w0]
    C = _histograms(np.sqrt(norm2), _bins(gx, gy, n_sens), cell, n_sens)
    return _normalise(C, n_orient, clip, cell, zero_channel)


__all__ = ["BOUNDARY_GAIN", "CELL", "CLIP", "N_ORIENT", "TEXTURE_SCALE", "fhog"]
