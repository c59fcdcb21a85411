"""Drawings of ``05_edge_rays`` (edge rays, Kim, Kim & Choi 2016)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from .._markdown import table
from ..features import edge_rays as er
from ..style import CYCLE, EST_COLOR, GT_COLOR, label_colors
from .core import bgr2rgb, draw_box

RAY_COLORS = CYCLE              # one colour per ray, the book's palette


def draw_rays(ax, xy, dists, color=None, lw=1.5, labels=False):
    """Draw the 8 rays of eq. 1/4 from point ``xy`` with lengths ``dists`` (order E..SE)."""
    x, y = xy
    for j, ((dx, dy), d) in enumerate(zip(er.DIRECTIONS, dists)):
        u = np.array([dx, dy], float) / np.hypot(dx, dy)
        c = color or RAY_COLORS[j]
        ax.plot([x, x + u[0] * d], [y, y + u[1] * d], color=c, lw=lw)
        ax.plot(x + u[0] * d, y + u[1] * d, "o", color=c, ms=3)
        if labels:
            ax.text(x + u[0] * (d + 6), y + u[1] * (d + 6), er.DIRECTION_NAMES[j], color=c,
                    fontsize=7, ha="center", va="center")


def show_edges(frame, edges, ax=None, title=None, box=None):
    """The frame dimmed, with the Canny edges drawn in white on top."""
    if ax is None:
        _, ax = plt.subplots(figsize=(4.8, 3.6))
    img = bgr2rgb(frame).astype(float) / 255 * 0.45
    img[edges] = 1.0
    ax.imshow(img)
    if box is not None:
        draw_box(ax, box, GT_COLOR)
    ax.set_axis_off()
    if title:
        ax.set_title(title, fontsize=9)
    return ax


def plot_sorted_rays(m_dis, p_dis, ax=None, labels=("model M", "particle p")):
    """Sorted distances of two ray sets with the 4th/5th pair (eq. 5) highlighted."""
    if ax is None:
        _, ax = plt.subplots(figsize=(4.2, 2.6))
    k = np.arange(1, 9)
    for dis, lab, off, c in ((m_dis, labels[0], -0.2, GT_COLOR), (p_dis, labels[1], 0.2, EST_COLOR)):
        s = np.sort(dis)
        ax.bar(k + off, s, width=0.4, color=c, alpha=0.5, label=lab)
        ax.bar([4 + off, 5 + off], s[3:5], width=0.4, color=c)
        ax.axhline(er.median_pair_mean(dis), color=c, ls="--", lw=1)
    ax.set_xlabel("rank after sorting (4th, 5th: the median pair)")
    ax.set_ylabel("distance to edge (px)")
    ax.set_xticks(k)
    ax.legend(fontsize=8)
    return ax


def plot_weight_map(frame, wmap, box=None, ax=None, title=None, *, grow=0, view=None,
                    marks=(), colorbar=True):
    """The eq. 6 weight of every pixel (0 outside the Ratio window) over the darkened frame.

    Parameters
    ----------
    frame : (H, W, 3) BGR frame, drawn in dark grey so that high weights (bright in the
        ``inferno`` map, fixed to 0..1) stand out.
    wmap : (H, W) weights, e.g. :func:`trackbook.features.edge_rays.weight_map`.
    box : a box to outline (x, y, w, h), or None.
    grow : draw each pixel with the largest weight within ``grow`` pixels (a square of side
        2 grow + 1): isolated one-pixel peaks stay visible on a whole frame. 0 draws the
        weights as they are (for a zoomed ``view``).
    view : ``(x0, x1, y0, y1)``, the part of the frame to show, or None for all of it.
    marks : points ``(x, y)`` (pixel centres) to circle, e.g. the highest weight.
    colorbar : add a colour bar labelled w (eq. 6).
    """
    import cv2

    if ax is None:
        _, ax = plt.subplots(figsize=(4.8, 3.6))
    grey = bgr2rgb(frame).astype(float).mean(axis=2) / 255
    ax.imshow(grey * 0.35, cmap="gray", vmin=0, vmax=1, interpolation="nearest")
    shown = np.asarray(wmap, np.float32)
    if grow:
        shown = cv2.dilate(shown, np.ones((2 * grow + 1, 2 * grow + 1), np.uint8))
    m = np.ma.masked_where(shown <= 0, shown)
    im = ax.imshow(m, cmap="inferno", vmin=0, vmax=1, interpolation="nearest")
    if box is not None:
        draw_box(ax, box, GT_COLOR)
    for x, y in marks:
        ax.plot(x, y, "o", ms=12, mfc="none", mec="white", mew=1.5)
    if view is not None:
        x0, x1, y0, y1 = view
        ax.set_xlim(x0 - 0.5, x1 + 0.5)
        ax.set_ylim(y1 + 0.5, y0 - 0.5)
    ax.set_axis_off()
    if title:
        ax.set_title(title, fontsize=9)
    if colorbar:
        plt.colorbar(im, ax=ax, fraction=0.035, label="w (eq. 6)")
    return ax


def plot_center_errors(results: dict, gt, ax=None, title=None):
    """Centre error per frame for several runs (Fig. 5 of Kim et al. 2016)."""
    from ..evaluation import metrics
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 2.8))
    colours = label_colors(results)
    for i, (name, r) in enumerate(results.items()):
        boxes = r.boxes if hasattr(r, "boxes") else np.asarray(r)
        ce = metrics.center_error(boxes, gt)
        ax.plot(np.arange(len(ce)), np.where(np.isfinite(ce), ce, np.nan),
                color=colours[i],
                label=f"{name} (mean {np.nanmean(ce[1:][np.isfinite(ce[1:])]):.0f} px)")
    ax.set_xlabel("frame")
    ax.set_ylabel("centre error (px)")
    # beside the axes: the error curves fill the plot's whole height at one time or another
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1))
    if title:
        ax.set_title(title, fontsize=9)
    return ax


def md_table(rows, digits: int = 3):
    """A list of dicts (or a dict of dicts: row name -> values) as a Markdown table for display."""
    from IPython.display import Markdown
    if isinstance(rows, dict):
        rows = [{"": k, **v} if isinstance(v, dict) else {"": k, "value": v} for k, v in rows.items()]
    rows = [{k: ("yes" if v else "no") if isinstance(v, (bool, np.bool_)) else v
             for k, v in r.items()} for r in rows]
    return Markdown(table(rows, number=f".{digits}f"))
