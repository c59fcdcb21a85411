"""Drawings of ``08_mean_shift``, ``case_study_cho2005`` and ``lab_notes_cho2005`` (Cho & Kang 2005 Fig. 1-6).

Coordinates: trackers use continuous image coordinates (pixel i covers [i, i+1)); matplotlib's
``imshow`` puts pixel i at i, so everything drawn here is shifted by half a pixel.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ..filters.mean_shift import bin_image, ellipse_rho
from ..style import CYCLE, GT_COLOR, OKABE_ITO, label_colors
from .core import bgr2rgb, draw_box, draw_ellipse


def rho_map(frame, q, axes, region, step: int = 2, stride: int = 1, bins=(8, 8, 4)):
    """rho[p(y), q] for every centre y on a grid over ``region = (x0, y0, x1, y1)``.

    Returns ``(xs, ys, rho)`` with rho of shape ``(len(ys), len(xs))``: the surface mean-shift
    climbs (the density picture of ``08_mean_shift``).
    """
    x0, y0, x1, y1 = region
    xs = np.arange(x0, x1, step) + 0.5
    ys = np.arange(y0, y1, step) + 0.5
    gx, gy = np.meshgrid(xs, ys)
    centres = np.stack([gx.ravel(), gy.ravel()], axis=1)
    ax_ = np.asarray(axes, dtype=float).reshape(1, 2)
    img = bin_image(frame, (x0 - 2 * ax_[0, 0], y0 - 2 * ax_[0, 1], x1 + 2 * ax_[0, 0],
                            y1 + 2 * ax_[0, 1]), stride, bins)
    rho = np.concatenate([ellipse_rho(img, q, c, np.repeat(ax_, len(c), 0))[0]
                          for c in np.array_split(centres, max(1, len(centres) // 400))])
    return xs, ys, rho.reshape(gy.shape)


def show_rho_map(frame, xs, ys, rho, ax=None, trajectories=None, title=None, alpha=0.55):
    """The frame with the rho surface over it and optional mean-shift paths ``(T, N, 2)``."""
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 3.8))
    ax.imshow(bgr2rgb(frame))
    ext = (xs[0] - 0.5 - 1, xs[-1] - 0.5 + 1, ys[-1] - 0.5 + 1, ys[0] - 0.5 - 1)
    im = ax.imshow(rho, extent=ext, cmap="magma", alpha=alpha, vmin=0, vmax=1)
    if trajectories is not None:
        tr = np.asarray(trajectories)
        for k in range(tr.shape[1]):
            ax.plot(tr[:, k, 0] - 0.5, tr[:, k, 1] - 0.5, "-o", ms=3, lw=1.2,
                    color=CYCLE[k % len(CYCLE)])
            ax.plot(tr[-1, k, 0] - 0.5, tr[-1, k, 1] - 0.5, "*", ms=10, color=CYCLE[k % len(CYCLE)],
                    mec="k")
    ax.set_xticks([])
    ax.set_yticks([])
    plt.colorbar(im, ax=ax, fraction=0.035, label="rho")
    if title:
        ax.set_title(title, fontsize=9)
    return ax


def show_candidates(frame, states, values, ax=None, estimate=None, gt=None, title=None,
                    label="likelihood", vmin=None, vmax=None):
    """Fig. 1 / Fig. 2 of Cho & Kang: candidate centres coloured by their likelihood.

    The colour scale is fitted to the values (``vmin``/``vmax`` default to their range) so that
    differences of a few hundredths stay visible; pass both to share a scale between panels.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 3.8))
    ax.imshow(bgr2rgb(frame))
    s = np.asarray(states)
    sc = ax.scatter(s[:, 0] - 0.5, s[:, 1] - 0.5, c=values, cmap="viridis", s=22,
                    vmin=np.nanmin(values) if vmin is None else vmin,
                    vmax=np.nanmax(values) if vmax is None else vmax, edgecolors="k", linewidths=0.3)
    plt.colorbar(sc, ax=ax, fraction=0.035, label=label)
    if estimate is not None:
        draw_ellipse(ax, estimate[0] - 0.5, estimate[1] - 0.5, estimate[2], estimate[3],
                     color="w", lw=1.5)
    if gt is not None:
        draw_box(ax, gt, GT_COLOR, "ground truth", ls="--")
    ax.set_xticks([])
    ax.set_yticks([])
    if title:
        ax.set_title(title, fontsize=9)
    return ax


def plot_per_frame(series: dict, ylabel: str, ax=None, title=None, logy=False):
    """One line per tracker of a per-frame number (Fig. 5: mean likelihood; Fig. 6: error)."""
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 2.8))
    colours = label_colors(series)
    for i, (name, v) in enumerate(series.items()):
        v = np.asarray(v, dtype=float)
        ax.plot(np.arange(len(v)), v, lw=1.3, color=colours[i], label=name)
    ax.set_xlabel("frame")
    ax.set_ylabel(ylabel)
    if logy:
        ax.set_yscale("log")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    if title:
        ax.set_title(title, fontsize=9)
    return ax


def weight_histogram(weights, ax=None, title=None):
    """How many candidates carry how much of the normalised weight (the cost of Condensation)."""
    if ax is None:
        _, ax = plt.subplots(figsize=(4.5, 2.8))
    w = np.sort(np.asarray(weights, dtype=float))[::-1]
    ax.bar(np.arange(len(w)), w, color=OKABE_ITO["blue"])
    ax.set_xlabel("candidates, heaviest first")
    ax.set_ylabel("normalised weight")
    if title:
        ax.set_title(title, fontsize=9)
    return ax
