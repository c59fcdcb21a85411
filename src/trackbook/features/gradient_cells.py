"""Multi-channel gradient-orientation cells: the HOG cells of ``03_hog`` as a feature image.

A correlation filter needs a feature *image*, not one descriptor vector: one channel per
orientation bin, one sample per cell, so that a cyclic shift of the features is a shift of the
image by whole cells. This module builds it from the book's HOG building blocks
(:func:`trackbook.features.hog.gradients` and :func:`~trackbook.features.hog.orientation_bin`:
central differences, signed orientation bins of eq. 2–4 of Lee et al. 2012) on 4 x 4 px
cells, and normalises each cell by the gradient energy of its 3 x 3 cell neighbourhood (the
role of Dalal & Triggs' block normalisation), clipped at 0.2 as they do.

Henriques et al. 2015 use Felzenszwalb's 31-channel FHOG (18 signed and 9 unsigned
orientations, 4 texture energies, four block normalisations). The book keeps the HOG cells
the reader has met in ``03_hog`` instead: 8 signed channels, exact octant binning.
"""

from __future__ import annotations

import numpy as np

from .hog import gradients, orientation_bin

#: Cell side in pixels.
CELL = 4
#: Clip of the normalised cell values (Dalal & Triggs 2005).
CLIP = 0.2


def _box3(E: np.ndarray) -> np.ndarray:
    """Sum over each cell's 3 x 3 neighbourhood, (N, rows, cols), edges replicated."""
    p = np.pad(E, ((0, 0), (1, 1), (1, 1)), mode="edge")
    s = p[:, :-2] + p[:, 1:-1] + p[:, 2:]
    return s[:, :, :-2] + s[:, :, 1:-1] + s[:, :, 2:]


def _pixel_cells(m: np.ndarray, b: np.ndarray, bins: int) -> np.ndarray:
    """:func:`orientation_cells` for 1-px cells, without the histogram: each pixel's only
    vote is its own magnitude in its own bin, so its energy is m² and the channels are that
    one value scattered into its bin (the same numbers, several times faster)."""
    v = m / np.sqrt(_box3(m * m) + 1e-12)
    np.minimum(v, CLIP, out=v)
    out = np.zeros((m.shape[0], bins) + m.shape[1:])
    np.put_along_axis(out, b[:, None].astype(np.intp), v[:, None], axis=1)
    return out


def orientation_cells(gray: np.ndarray, cell: int = CELL, bins: int = 8) -> np.ndarray:
    """Gradient-orientation feature images of a stack of grey patches.

    Parameters
    ----------
    gray : (N, h, w) grey patches (any real dtype); h and w are cut down to multiples of
        ``cell``.
    cell : cell side in pixels.
    bins : signed orientation bins over [0, 2π).

    Returns
    -------
    (N, bins, h // cell, w // cell) float array: channel b of cell (r, c) is the gradient
    magnitude voting into bin b inside the cell, divided by the root of the gradient energy
    of the 3 x 3 cells around it and clipped at ``CLIP``. A flat patch gives zeros.
    """
    g = np.asarray(gray, dtype=np.float64)
    if g.ndim != 3:
        raise ValueError(f"gray must be an (N, h, w) stack of grey patches, got shape {g.shape}.")
    n, h, w = g.shape
    rows, cols = h // cell, w // cell
    if rows < 1 or cols < 1:
        raise ValueError(f"patches of {w}x{h} px hold no {cell}x{cell} px cell; pass larger "
                         "patches or a smaller cell.")
    g = g[:, :rows * cell, :cols * cell]
    gx, gy = gradients(g)                                 # eq. 2 of Lee et al. 2012
    b = orientation_bin(gx, gy, bins)                     # eq. 3-4
    m = np.sqrt(gx * gx + gy * gy)
    if cell == 1:
        return _pixel_cells(m, b, bins)
    cell_of = ((np.arange(rows * cell)[:, None] // cell) * cols
               + np.arange(cols * cell)[None, :] // cell)
    index = (np.arange(n)[:, None, None] * (rows * cols) + cell_of[None]) * bins + b
    hist = np.bincount(index.ravel(), weights=m.ravel(), minlength=n * rows * cols * bins)
    hist = hist.reshape(n, rows, cols, bins)
    energy = _box3(np.einsum("nrcb,nrcb->nrc", hist, hist))
    hist /= np.sqrt(energy + 1e-12)[..., None]
    np.minimum(hist, CLIP, out=hist)
    return np.ascontiguousarray(hist.transpose(0, 3, 1, 2))


__all__ = ["CELL", "CLIP", "orientation_cells"]
