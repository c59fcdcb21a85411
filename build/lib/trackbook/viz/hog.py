"""Drawings for chapters 02 and 08: HOG cells as star glyphs, learned bases as images."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ..features.hog import HOG_BINS, HOG_CELL


def plot_hog(descriptor, ax=None, shape=(6, 4), color="#1f77b4", title=None):
    """Draw a (rows x cols x 8) HOG descriptor: in each cell, one ray per orientation bin,
    its length the bin's share, pointing along the bin's centre angle (y down, as the image).
    Negative values (basis vectors) are drawn in red."""
    if ax is None:
        _, ax = plt.subplots(figsize=(2.2, 3.2))
    d = np.asarray(descriptor, dtype=float).reshape(shape[0], shape[1], HOG_BINS)
    scale = 0.48 / max(np.abs(d).max(), 1e-12)
    ang = (np.arange(HOG_BINS) + 0.5) * 2 * np.pi / HOG_BINS
    for r in range(shape[0]):
        for c in range(shape[1]):
            for b in range(HOG_BINS):
                v = d[r, c, b] * scale
                ax.plot([c + 0.5, c + 0.5 + abs(v) * np.cos(ang[b])],
                        [r + 0.5, r + 0.5 + abs(v) * np.sin(ang[b])],
                        color=color if v >= 0 else "#d62728", lw=1.4)
    ax.set_xlim(0, shape[1])
    ax.set_ylim(shape[0], 0)
    ax.set_aspect("equal")
    ax.set_xticks(np.arange(shape[1] + 1))
    ax.set_yticks(np.arange(shape[0] + 1))
    ax.set_xticklabels([])
    ax.set_yticklabels([])
    ax.grid(True, lw=0.5, color="0.8")
    if title:
        ax.set_title(title, fontsize=9)
    return ax


def plot_gradients(gray_patch, ax=None, step=1):
    """The patch with its (blurred) gradient vectors as arrows (eq. 2)."""
    from ..features.hog import _blur, gradients
    if ax is None:
        _, ax = plt.subplots(figsize=(2.4, 3.4))
    p = np.asarray(gray_patch, dtype=float)
    gx, gy = gradients(_blur(p[None]))
    ax.imshow(p, cmap="gray", interpolation="nearest")
    yy, xx = np.mgrid[0:p.shape[0]:step, 0:p.shape[1]:step]
    ax.quiver(xx, yy, gx[0, ::step, ::step], gy[0, ::step, ::step], color="#ff7f0e",
              angles="xy", scale_units="xy", scale=None)
    for k in range(0, p.shape[1] + 1, HOG_CELL):
        ax.axvline(k - 0.5, color="c", lw=0.6)
    for k in range(0, p.shape[0] + 1, HOG_CELL):
        ax.axhline(k - 0.5, color="c", lw=0.6)
    ax.set_xticks([])
    ax.set_yticks([])
    return ax


def plot_bases(basis, n=6, axes=None, title=""):
    """The first ``n`` columns of a learned HOG basis (192 x k) as HOG glyphs."""
    k = min(n, basis.shape[1])
    if axes is None:
        _, axes = plt.subplots(1, k, figsize=(1.6 * k, 2.6))
    axes = np.atleast_1d(axes)
    for j in range(k):
        plot_hog(basis[:, j], ax=axes[j], title=f"{title}u{j + 1}")
    return axes
