"""Drawing trackers on frames: boxes, particles, ellipses, search windows, curves, animations.

Everything draws on a matplotlib ``Axes`` and returns it, so chapters compose figures freely.
Frames are BGR (as OpenCV reads them); ``show_frame`` converts to RGB for display.
"""

from __future__ import annotations

import matplotlib

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import patches as mpatches

from ..evaluation import metrics
from ..style import (CYCLE, EST_COLOR, GREY, GT_COLOR, OKABE_ITO, Palette,  # noqa: F401
                     label_colors, tracker_color)
from ..trackers.base import Tracker



def bgr2rgb(frame: np.ndarray) -> np.ndarray:
    """BGR (OpenCV) to RGB (matplotlib)."""
    return np.ascontiguousarray(frame[..., ::-1])


def _axes(ax, figsize=(4.8, 3.6)):
    if ax is None:
        _, ax = plt.subplots(figsize=figsize)
    return ax


def draw_box(ax, box, color=EST_COLOR, label=None, lw=1.8, ls="-"):
    """Draw a box ``(x, y, w, h)`` (continuous coordinates) on ``ax``.

    ``None`` or a box with a NaN coordinate (a tracker's answer while the target is lost) draws
    nothing; anything that is not four numbers raises ``ValueError``, so a figure never silently
    misses a box its caption names.
    """
    if box is None:
        return ax
    arr = np.asarray(box, dtype=float)
    if arr.size != 4:
        raise ValueError(f"draw_box draws one box (x, y, w, h); got an array of shape {arr.shape}"
                         " - pass several boxes to show_frame, or draw them one by one")
    arr = arr.reshape(4)
    if not np.all(np.isfinite(arr)):
        return ax
    x, y, w, h = arr
    # Continuous box [x, x+w) drawn on pixel centres: shift by half a pixel.
    ax.add_patch(mpatches.Rectangle((x - 0.5, y - 0.5), w, h, fill=False, ec=color, lw=lw,
                                    ls=ls, label=label))
    return ax


def show_frame(frame, ax=None, boxes=None, title=None, gt=None):
    """Show a BGR frame with optional boxes.

    Parameters
    ----------
    boxes : dict label -> box, a single box ``(x, y, w, h)`` (drawn as the estimate), or a
        sequence / ``(n, 4)`` array of boxes. A box labelled with a tracker's name is drawn
        in that tracker's colour (``style.tracker_color``), the others in the colours of
        ``CYCLE`` (the first vermillion, the second blue, ...). Every box given is drawn; a malformed one raises
        ``ValueError`` (see ``draw_box``).
    gt : box, drawn dashed in green as the ground truth
    """
    ax = _axes(ax)
    ax.imshow(bgr2rgb(frame))
    ax.set_xticks([])
    ax.set_yticks([])
    if gt is not None:
        draw_box(ax, gt, GT_COLOR, "ground truth", ls="--")
    if boxes is not None:
        if not isinstance(boxes, dict):
            arr = np.asarray(boxes, dtype=float)
            if arr.ndim == 1:
                boxes = {"estimate": arr}
            elif arr.ndim == 2 and arr.shape[1] == 4:
                boxes = {("estimate" if i == 0 else f"box {i}"): b for i, b in enumerate(arr)}
            else:
                raise ValueError("show_frame: boxes must be one box (x, y, w, h), an (n, 4) "
                                 f"array or a dict label -> box; got shape {arr.shape}")
        for (label, b), colour in zip(boxes.items(), label_colors(boxes)):
            draw_box(ax, b, colour, label)
    if title:
        ax.set_title(title, fontsize=9)
    return ax


def draw_particles(ax, xy, weights=None, color="#ffdd00", max_size=40.0):
    """Particles as dots whose area grows with their weight."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    if weights is None:
        s = np.full(len(xy), 6.0)
    else:
        w = np.asarray(weights, dtype=float)
        s = 2.0 + max_size * w / (w.max() if w.max() > 0 else 1.0)
    ax.scatter(xy[:, 0], xy[:, 1], s=s, c=color, edgecolors="k", linewidths=0.3, alpha=0.85)
    return ax


def draw_ellipse(ax, cx, cy, hx, hy, angle=0.0, color=EST_COLOR, lw=1.5, ls="-"):
    """An ellipse with centre (cx, cy), half-axes (hx, hy) and rotation ``angle`` in degrees."""
    ax.add_patch(mpatches.Ellipse((cx, cy), 2 * hx, 2 * hy, angle=angle, fill=False, ec=color,
                                  lw=lw, ls=ls))
    return ax


def draw_search_window(ax, box, color="#17becf", label="search window"):
    """A search window as a dotted box."""
    return draw_box(ax, box, color, label, lw=1.2, ls=":")


def filmstrip(clip, boxes=None, frames=None, n=6, ncols=None, size=2.4, title=None):
    """A row of frames of ``clip`` with ground truth and tracker boxes.

    Parameters
    ----------
    boxes : dict name -> (N, 4) boxes or ``Result`` (anything with ``.boxes``)
    frames : frame indices; default ``n`` evenly spaced
    """
    if frames is None:
        frames = np.linspace(0, len(clip) - 1, n).round().astype(int)
    frames = list(frames)
    ncols = ncols or len(frames)
    nrows = int(np.ceil(len(frames) / ncols))
    w, h = clip.size
    fig, axes = plt.subplots(nrows, ncols, figsize=(size * ncols, size * ncols * h / w / ncols * nrows + 0.3),
                             squeeze=False)
    boxes = {k: getattr(v, "boxes", v) for k, v in (boxes or {}).items()}
    for ax, i in zip(axes.ravel(), frames):
        show_frame(clip.frames[i], ax=ax, gt=clip.groundtruth[i],
                   boxes={k: b[i] for k, b in boxes.items()} or None, title=f"frame {i}")
    for ax in axes.ravel()[len(frames):]:
        ax.axis("off")
    handles, labels = axes.ravel()[0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=8,
                   frameon=False, bbox_to_anchor=(0.5, -0.02))
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def plot_curves(results, gt=None, axes=None):
    """Success and precision plots (OTB) for several runs.

    Parameters
    ----------
    results : dict label -> Result, or list of Result; scores over frames 1..N-1
    gt : (N, 4) ground truth; default: each result's clip loaded by name
    """
    from .. import clips as _clips

    if not isinstance(results, dict):
        results = {r.tracker: r for r in results}
    if axes is None:
        _, axes = plt.subplots(1, 2, figsize=(9, 3.4))
    ax_s, ax_p = axes
    colours = label_colors(results)
    for i, (label, r) in enumerate(results.items()):
        g = gt if gt is not None else _clips.load(r.clip).groundtruth
        g = g[: len(r.boxes)]
        ts, s = metrics.success_curve(r.boxes[1:], g[1:])
        tp, p = metrics.precision_curve(r.boxes[1:], g[1:])
        c = colours[i]
        ax_s.plot(ts, s, color=c, label=f"{label} [{s.mean():.3f}]")
        ax_p.plot(tp, p, color=c, label=f"{label} [{p[20]:.3f}]")
    ax_s.set(xlabel="overlap threshold", ylabel="success rate", title="Success plot (AUC)",
             xlim=(0, 1), ylim=(0, 1.02))
    ax_p.set(xlabel="centre error threshold (px)", ylabel="precision",
             title="Precision plot (at 20 px)", xlim=(0, 50), ylim=(0, 1.02))
    for ax in axes:
        ax.grid(alpha=0.3)
        # under the axes: inside, a curve of some tracker always passes behind it
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.22),
                  ncols=2 if len(results) > 3 else 1, frameon=False)
    ax_s.figure.tight_layout()
    return axes


def animate(clip, boxes=None, frames=None, step=None, max_frames=40, width=3.6, interval=120):
    """A compact animation (JS/HTML with embedded frames) for the HTML book.

    Returns an ``IPython.display.HTML`` object; frames are subsampled to at most
    ``max_frames`` so a page stays light.
    """
    from IPython.display import HTML
    from matplotlib import animation

    n = len(clip)
    if frames is None:
        step = step or max(1, int(np.ceil(n / max_frames)))
        frames = list(range(0, n, step))
    boxes = {k: getattr(v, "boxes", v) for k, v in (boxes or {}).items()}
    w, h = clip.size
    fig, ax = plt.subplots(figsize=(width, width * h / w))
    fig.subplots_adjust(0, 0, 1, 1)

    def draw(i):
        ax.clear()
        show_frame(clip.frames[i], ax=ax, gt=clip.groundtruth[i],
                   boxes={k: b[i] for k, b in boxes.items()} or None)
        ax.text(4, 12, f"{i}", color="w", fontsize=8,
                bbox=dict(facecolor="k", alpha=0.5, pad=1, lw=0))
        return []

    anim = animation.FuncAnimation(fig, draw, frames=frames, interval=interval, blit=False)
    with matplotlib.rc_context({"animation.embed_limit": 30}):
        html = anim.to_jshtml(default_mode="loop")
    plt.close(fig)
    return HTML(html)


def draw_tracker_state(ax, state):
    """Draw a :class:`~trackbook.trackers.TrackerState` (``tracker.state()``; a tracker is
    also accepted and asked for its state): particles sized by weight, the search window, the
    ellipse."""
    if isinstance(state, Tracker):
        state = state.state()
    if state.particles is not None and len(state.particles):
        draw_particles(ax, np.asarray(state.particles)[:, :2], state.weights)
    if state.search_window is not None:
        draw_search_window(ax, state.search_window)
    if state.ellipse is not None:
        draw_ellipse(ax, *state.ellipse)
    return ax


def draw_state_cv(img, state, color=(178, 114, 0)):
    """Draw a :class:`~trackbook.trackers.TrackerState` on a BGR image in place, with OpenCV
    (for videos): particles as dots (the 200 heaviest at most), the search window dotted-thin,
    and the ellipse. Returns ``img``."""
    import cv2

    if state.particles is not None and len(state.particles):
        p = np.asarray(state.particles, dtype=float)[:, :2]
        w = state.weights if state.weights is not None else np.ones(len(p))
        keep = np.argsort(-np.asarray(w))[:200]
        for x, y in p[keep]:
            if np.isfinite(x) and np.isfinite(y):
                cv2.circle(img, (int(round(x)), int(round(y))), 1, color, -1, cv2.LINE_AA)
    if state.search_window is not None:
        x, y, w, h = (int(round(v)) for v in state.search_window)
        cv2.rectangle(img, (x, y), (x + w, y + h), color, 1, cv2.LINE_4)
    if state.ellipse is not None:
        cx, cy, hx, hy = state.ellipse[:4]
        angle = state.ellipse[4] if len(state.ellipse) > 4 else 0.0
        if all(np.isfinite(v) for v in (cx, cy, hx, hy)):
            cv2.ellipse(img, (int(round(cx)), int(round(cy))),
                        (max(int(round(hx)), 1), max(int(round(hy)), 1)), angle, 0, 360, color,
                        1, cv2.LINE_AA)
    return img
