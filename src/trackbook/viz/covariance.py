"""Drawings for ``07_region_covariance`` (region covariance) and ``case_study_lee2015`` (the
Kalman search window)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import patches as mpatches

from .._markdown import table
from .core import draw_box, draw_ellipse, draw_search_window, show_frame


def draw_integral_image(ax=None, values=None):
    """A 5x5 image, its summed-area table, and the four look-ups that give a rectangle's sum."""
    if values is None:
        values = np.arange(1, 26).reshape(5, 5) % 7
    S = np.zeros((6, 6), int)
    S[1:, 1:] = values.cumsum(0).cumsum(1)
    if ax is None:
        _, ax = plt.subplots(1, 2, figsize=(8, 3.6))
    for a, M, title in [(ax[0], values, "image I"), (ax[1], S, "integral S (zero-padded)")]:
        a.imshow(np.zeros_like(M), cmap="Greys", vmin=0, vmax=1)
        for (r, c), v in np.ndenumerate(M):
            a.text(c, r, str(v), ha="center", va="center", fontsize=9)
        a.set_xticks(range(M.shape[1]))
        a.set_yticks(range(M.shape[0]))
        a.set_title(title, fontsize=10)
    # the rectangle rows 1..3, cols 2..4 of I
    ax[0].add_patch(mpatches.Rectangle((1.5, 0.5), 3, 3, fill=False, ec="#d62728", lw=2))
    for (r, c), sign in {(4, 5): "+", (1, 5): "−", (4, 2): "−", (1, 2): "+"}.items():
        ax[1].add_patch(mpatches.Circle((c, r), 0.42, fill=False, ec="#d62728", lw=1.8))
        ax[1].text(c + 0.38, r - 0.3, sign, color="#d62728", fontsize=12, weight="bold")
    total = values[1:4, 2:5].sum()
    ax[1].set_xlabel(f"S[4,5] − S[1,5] − S[4,2] + S[1,2] = {S[4,5]} − {S[1,5]} − {S[4,2]} + "
                     f"{S[1,2]} = {S[4,5] - S[1,5] - S[4,2] + S[1,2]}  (direct sum {total})",
                     fontsize=8)
    return ax


def rho_map(frame, tracker, ax=None, title=None):
    """The last frame's candidates coloured by their Förstner distance d_F (eq. 5 of Lee 2015)."""
    ax = show_frame(frame, ax=ax, title=title)
    b = np.asarray(tracker.candidates, dtype=float)
    if len(b):
        cx, cy = b[:, 0] + b[:, 2] / 2, b[:, 1] + b[:, 3] / 2
        sc = ax.scatter(cx, cy, c=tracker.distances, s=6, cmap="viridis_r")
        plt.colorbar(sc, ax=ax, fraction=0.035, label="$d_F$")
    draw_search_window(ax, tracker.search_window)
    draw_box(ax, tracker.bbox, label="best window")
    return ax


def kalman_frames(clip, states, boxes, frames, size=2.6, gt=True, zoom=None):
    """Frames with the tracker's box, the Kalman search window and the 3σ ellipse (``case_study_lee2015``).

    ``states`` is a list (per frame) of dicts with ``search_window``, ``ellipse`` and
    ``center`` (the posterior centre), as recorded by ``evaluate(..., on_frame=...)``.
    ``zoom`` (px): crop each frame to ±zoom around the ground-truth centre, so a window of a
    few pixels stays visible in a column-wide strip (use at most three frames).
    """
    frames = list(frames)
    fig, axes = plt.subplots(1, len(frames), figsize=(size * len(frames), size * 0.85),
                             squeeze=False)
    for ax, i in zip(axes[0], frames):
        show_frame(clip.frames[i], ax=ax, title=f"frame {i}",
                   gt=clip.groundtruth[i] if gt else None)
        s = states[i]
        if s.get("search_window") is not None:
            draw_search_window(ax, s["search_window"], label=None)
        if s.get("ellipse") is not None:
            draw_ellipse(ax, *s["ellipse"], color="#ffffff", lw=1.0)
        if s.get("center") is not None:
            ax.plot(*s["center"], "w.", ms=5)
        draw_box(ax, boxes[i], color="#D55E00")      # Okabe-Ito vermillion
        if zoom:
            g = np.asarray(clip.groundtruth[i], dtype=float)
            cx, cy = g[0] + g[2] / 2, g[1] + g[3] / 2
            ax.set_xlim(cx - zoom, cx + zoom)
            ax.set_ylim(cy + zoom, cy - zoom)
    fig.tight_layout()
    return fig


def recorder(states: list):
    """An ``on_frame`` callback that appends what ``case_study_lee2015`` draws to ``states``."""
    def record(i, tracker, frame, box):
        st = tracker.state()          # the search window; the Kalman gate (kalman-covariance)
        sw, el = st.search_window, st.ellipse
        kf = getattr(tracker, "kalman", None)
        states.append({
            "search_window": None if sw is None else tuple(map(float, sw)),
            "ellipse": None if el is None else tuple(map(float, el)),
            "center": None if kf is None else (float(kf.x[0]), float(kf.x[1])),
            "candidates": int(tracker.frame_report()["candidates"]) if i else 0,
            "manoeuvre": bool(getattr(tracker, "manoeuvre", False)),
            "typical_rho": tracker.typical_rho() if hasattr(tracker, "typical_rho") else None,
        })
    return record


__all__ = ["draw_integral_image", "rho_map", "kalman_frames", "recorder", "markdown_table"]


def markdown_table(rows, columns, formats=None, labels=None):
    """Rows (dicts) as an IPython Markdown table; ``formats`` maps column -> format spec and
    ``labels`` column -> header (short headers keep the table inside the page's column)."""
    from IPython.display import Markdown

    return Markdown(table(rows, columns, formats=formats, labels=labels))
