"""Figures of ``09_trackers_compared``: trackers side by side, claims with their intervals, speed.

Comparison plots highlight the trackers under discussion and draw the rest in grey, keep
legends outside the data, and use the book's one palette (:data:`trackbook.style.OKABE_ITO`).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ..style import GREY, OKABE_ITO

#: Colour per preset in the claims plots.
PRESET_COLORS = {"paper": OKABE_ITO[1], "book": OKABE_ITO[5]}
# the words the book's text uses for the two settings
PRESET_LABELS = {"paper": "paper preset", "book": "book defaults"}
VERDICT_MARKERS = {"holds": "o", "fails": "X", "inconclusive": "o"}


def dot_ranking(means: dict, spread: dict | None = None, highlight=(), xlabel="mean AUC",
                title="", ax=None):
    """Trackers sorted by a score, one dot each (and a bar from min to max when given).

    ``highlight`` names are drawn in colour and labelled in bold; the rest are grey.
    """
    names = sorted(means, key=lambda t: means[t])
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 0.32 * len(names) + 1.0))
    for i, t in enumerate(names):
        on = t in highlight
        c = OKABE_ITO[6] if t == "opencv-mil" else (OKABE_ITO[5] if on else GREY)
        if spread and t in spread:
            lo, hi = spread[t]
            ax.plot([lo, hi], [i, i], color=c, lw=2, alpha=0.6, solid_capstyle="butt")
        ax.plot(means[t], i, "o", color=c if (on or t == "opencv-mil") else "#777777", ms=6)
    ax.set_yticks(range(len(names)), names, fontsize=8)
    for lab in ax.get_yticklabels():
        if lab.get_text() in highlight or lab.get_text() == "opencv-mil":
            lab.set_fontweight("bold")
    ax.set_xlabel(xlabel)
    ax.set_xlim(0, max(1e-9, max(hi for _, hi in spread.values()) if spread else
                       max(means.values())) * 1.08)
    ax.grid(axis="x", alpha=0.3)
    if title:
        ax.set_title(title, fontsize=10)
    return ax


def claims_forest(results: dict, metrics=("auc", "tracking_rate"), labels=None):
    """Mean paired difference with its 95 % interval per comparison, one panel per metric.

    ``results[(preset, metric)]`` is the list :func:`trackbook.evaluation.compare.check_claims`
    returned. Filled markers: the interval excludes 0 (holds or fails); hollow: inconclusive.
    """
    labels = labels or {"auc": "difference in AUC", "tracking_rate": "difference in tracking rate"}
    first = results[next(iter(results))]
    comps = [f"{r['paper']}: {r['comparison']}" for r in first]
    fig, axes = plt.subplots(1, len(metrics), figsize=(9.6, 0.42 * len(comps) + 1.6),
                             sharey=True)
    axes = np.atleast_1d(axes)
    presets = sorted({p for p, _ in results})
    for ax, m in zip(axes, metrics):
        for k, preset in enumerate(presets):
            rows = results.get((preset, m), [])
            for i, r in enumerate(rows):
                y = len(comps) - 1 - i + (0.15 if k == 0 else -0.15)
                c = PRESET_COLORS.get(preset, OKABE_ITO[0])
                # the legend shows the interval's line: a marker there would look like a verdict
                ax.plot([r["ci_low"], r["ci_high"]], [y, y], color=c, lw=2,
                        label=PRESET_LABELS.get(preset, preset) if i == 0 else None)
                filled = r["verdict"] != "inconclusive"
                ax.plot(r["mean_diff"], y, VERDICT_MARKERS[r["verdict"]], ms=7, color=c,
                        mfc=c if filled else "white", mew=1.5)
        ax.axvline(0, color="k", lw=0.8)
        ax.set_xlabel(labels.get(m, m))
        ax.grid(axis="x", alpha=0.3)
    axes[0].set_yticks(range(len(comps)), comps[::-1], fontsize=8)
    axes[-1].legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, frameon=False)
    fig.suptitle("claimed improvement, better minus worse (95 % interval over sequences)",
                 fontsize=10)
    fig.tight_layout()
    return fig


def speed_bars(ms: dict, reference: str = "opencv-mil", highlight=()):
    """Median ms per frame of each tracker as a fraction of the reference's, log scale."""
    ref = ms[reference]
    names = sorted((t for t in ms if t != reference), key=lambda t: ms[t])
    fig, ax = plt.subplots(figsize=(6.4, 0.3 * len(names) + 1.2))
    ratios = [ms[t] / ref for t in names]
    colors = [OKABE_ITO[5] if (t in highlight or not highlight) else GREY for t in names]
    ax.barh(range(len(names)), ratios, color=colors)
    ax.set_yticks(range(len(names)), names, fontsize=8)
    ax.set_xscale("log")
    ax.axvline(1.0, color=OKABE_ITO[6], lw=1.2)
    ax.text(1.0, len(names) - 0.4, f" {reference}", color=OKABE_ITO[6], fontsize=8, va="top")
    ax.set_xlabel(f"time per frame ÷ {reference}'s on the same frames (log scale)")
    ax.grid(axis="x", alpha=0.3, which="both")
    fig.tight_layout()
    return fig


def attribute_heatmap(guide: list[dict], trackers: list[str]):
    """Mean AUC per difficulty (rows) and tracker (columns), colour scale fitted to the data."""
    M = np.array([[r[t] for t in trackers] for r in guide], dtype=float)
    fig, ax = plt.subplots(figsize=(9.6, 0.42 * len(guide) + 2.0))
    lo, hi = float(np.nanmin(M)), float(np.nanmax(M))
    im = ax.imshow(M, cmap="cividis", vmin=lo, vmax=hi, aspect="auto")
    ax.set_xticks(range(len(trackers)), trackers, rotation=35, ha="right", fontsize=8)
    ax.set_yticks(range(len(guide)), [r["difficulty"] for r in guide], fontsize=8)
    mid = (lo + hi) / 2
    for i in range(M.shape[0]):
        for j in range(M.shape[1]):
            ax.text(j, i, f"{M[i, j]:.2f}", ha="center", va="center", fontsize=6.5,
                    color="w" if M[i, j] < mid else "k",
                    fontweight="bold" if trackers[j] == guide[i]["best"] else "normal")
    fig.colorbar(im, ax=ax, label="mean AUC", fraction=0.03)
    fig.tight_layout()
    return fig
