"""Precomputed step-by-step views (animations) drawn by the playground's viewer module.

An :class:`Animation` holds everything in its data (frames as JPEG, boxes, state, captions, a
per-step curve); in Jupyter it is the same anywidget as the playground with no kernel work
after display, and in the HTML book it is embedded in the page like a playground.
"""

from __future__ import annotations

import base64

import anywidget
import cv2
import numpy as np
import traitlets as T

from ..style import EST_COLOR, GT_COLOR, bgr
from ..style import VIEWER as VIEWER_COLORS
from . import data as D
from .data import VIEWER_CSS, VIEWER_JS

GT_BGR = bgr(GT_COLOR)
EST_BGR = bgr(EST_COLOR)
PARTICLE_BGR = bgr(VIEWER_COLORS["particle"])


def _particles_of_step(state: dict, i: int) -> np.ndarray:
    """Step ``i``'s particles from an encoded state (:func:`trackbook.playground.data.
    _encode_state`): rows (x, y, weight relative to the step's largest), empty if none."""
    counts = state.get("pcount")
    if not counts or i >= len(counts) or not counts[i]:
        return np.zeros((0, 3))
    q = np.frombuffer(base64.b64decode(state["particles"]), dtype="<i2").reshape(-1, 3)
    start = int(np.sum(counts[:i]))
    q = q[start:start + counts[i]].astype(float)
    return np.column_stack([q[:, :2] / 2, q[:, 2] / 1000])


def _r(a, nd=1):
    return None if a is None else np.round(np.asarray(a, dtype=float), nd).tolist()


def run_entry(label, boxes, *, captions=None, curve=None, curve_label="", curve_x="step",
              scores="", states=None, extra_boxes=(), est_label="estimate"):
    """One run of an animation: a box per step (None: no box), captions, a curve in 0..1,
    the tracker state per step (as :func:`trackbook.playground.data.snapshot` makes it) and
    extra labelled boxes ``(label, colour, boxes)``."""
    return {"clip": "", "tracker": label, "animation": True, "values": {},
            "boxes": [None if b is None or not np.isfinite(b).all() else _r(b) for b in boxes],
            "ok": [1] * len(boxes), "iou": None, "scores": scores, "est_label": est_label,
            "captions": list(captions) if captions is not None else None,
            "curve": None if curve is None else {
                "label": curve_label, "x": curve_x,
                "values": [None if v is None or not np.isfinite(v) else round(float(v), 4)
                           for v in curve]},
            "extra_boxes": [{"label": lab, "color": col, "dash": [5, 3],
                             "boxes": [None if b is None else _r(b) for b in bs]}
                            for lab, col, bs in extra_boxes],
            "state": D._encode_state(states) if states else {}}


class Animation(anywidget.AnyWidget):
    """A step-by-step view: ``images`` (BGR arrays), ``index`` (step -> image), ``runs``
    (``{label: run_entry(...)}``, a choice when several), ``gt`` per step (optional);
    ``still`` is the step drawn as the still picture (:meth:`still_png`) for print and pages
    without JavaScript (default: the middle)."""

    _esm = T.Unicode(VIEWER_JS.read_text(encoding="utf-8")).tag(sync=True)
    _css = T.Unicode(VIEWER_CSS.read_text(encoding="utf-8")).tag(sync=True)
    static_data = T.Dict().tag(sync=True)

    def __init__(self, name, images, runs: dict, index=None, gt=None, note="",
                 still: int | None = None, **kwargs):
        super().__init__(**kwargs)
        self._still = None if still is None else int(still)   # the step of the still picture
        h, w = np.asarray(images[0]).shape[:2]
        n = len(next(iter(runs.values()))["boxes"])
        clip = {"name": name, "w": int(w), "h": int(h), "frames": [D.jpeg(i) for i in images],
                "index": None if index is None else [int(i) for i in index],
                "gt": None if gt is None else [None if b is None or not np.isfinite(b).all()
                                               else _r(b) for b in gt]}
        if index is None and len(images) != n:
            raise ValueError(f"{len(images)} images for {n} steps: pass index= (step -> image).")
        labels = list(runs)
        self._png_src = (images, index, gt, runs[labels[0]])
        self.static_data = {
            "config": {"clips": [{"key": name, "name": name}], "trackers": labels,
                       "knobs": {k: [] for k in labels}, "n_frames": n,
                       "colors": VIEWER_COLORS},
            "clips": {name: clip},
            "runs": {f"{name}|{k}|": {**v, "clip": name} for k, v in runs.items()},
            "initial": {"clip": name, "tracker": labels[0]}, "note": note}

    def still_png(self) -> bytes:
        """Step ``still`` (default: the middle one) as a PNG picture for print and pages
        without JavaScript, its particles drawn as the viewer draws them (a dot per
        particle, larger the heavier)."""
        images, index, gt, run = self._png_src
        i = len(run["boxes"]) // 2 if self._still is None else self._still
        img = np.array(images[index[i] if index is not None else i])
        dots = _particles_of_step(run.get("state") or {}, i)
        if len(dots):
            layer = img.copy()
            for x, y, w in dots:
                # the viewer's radius 1.5 + 4 sqrt(w), w relative to the step's largest weight
                r = max(1, int(round(1.5 + 4 * np.sqrt(max(w, 0.0)))))
                cv2.circle(layer, (int(round(x)), int(round(y))), r, PARTICLE_BGR, -1,
                           cv2.LINE_AA)
            img = cv2.addWeighted(layer, 0.8, img, 0.2, 0)   # overlapping dots stay apart
        for b, col in ((gt[i] if gt is not None else None, GT_BGR), (run["boxes"][i], EST_BGR)):
            if b is not None and np.isfinite(b).all():
                x, y, w, h = (int(round(v)) for v in b)
                cv2.rectangle(img, (x, y), (x + w, y + h), col, 2)
        return cv2.imencode(".png", img)[1].tobytes()

    def show(self):
        from IPython.display import display
        display(self)
