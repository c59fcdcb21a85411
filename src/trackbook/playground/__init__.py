"""The playground viewer drawn in the browser: one JS module, precomputed runs as page data.

:func:`page_html` turns runs of trackers on clips into the HTML of one playground: the viewer
module (``viewer.js``, the same file wherever a playground is shown) inline, the frames as
JPEG data URLs encoded once per clip, and per run the boxes, ``ok``, IoU, a few particles and
the scores line. Nothing is fetched, so the book works opened from disk and offline; moving the
frame slider costs no Python. :class:`trackbook.widgets.Playground` decides which runs to
precompute (each knob at a few values, one at a time around the defaults).
"""

from __future__ import annotations

import base64
import html
import itertools
import json
from importlib import resources

import cv2
import numpy as np

from .. import clips as _clips

_ids = itertools.count()


def viewer_js() -> str:
    """The viewer module's source (shipped as package data)."""
    return resources.files(__package__).joinpath("viewer.js").read_text(encoding="utf-8")


def encode_frames(frames, width: int = 320, quality: int = 70) -> tuple[list[str], float]:
    """Frames as JPEG data URLs at most ``width`` px wide; returns them and the scale used."""
    frames = list(frames)
    h, w = frames[0].shape[:2]
    s = min(1.0, width / w)
    out = []
    for f in frames:
        if s < 1.0:
            f = cv2.resize(f, (round(w * s), round(h * s)), interpolation=cv2.INTER_AREA)
        ok, buf = cv2.imencode(".jpg", f, [cv2.IMWRITE_JPEG_QUALITY, quality])
        out.append("data:image/jpeg;base64," + base64.b64encode(buf.tobytes()).decode())
    return out, s


def _box(b, nd=1):
    b = np.asarray(b, dtype=float)
    return None if not np.all(np.isfinite(b)) else [round(float(v), nd) for v in b]


def run_record(result, states, groundtruth, max_particles: int = 100) -> dict:
    """One run as the viewer reads it (coordinates in the clip's own pixels)."""
    from ..evaluation import metrics

    n = len(result.boxes)
    rec = {"boxes": [_box(b) for b in result.boxes], "ok": [bool(v) for v in result.ok]}
    gt = np.asarray(groundtruth, dtype=float)[:n]
    known = np.all(np.isfinite(gt), axis=1)
    if known.any():
        iou = metrics.iou(result.boxes, gt)
        rec["iou"] = [round(float(v), 3) if k else None for v, k in zip(iou, known)]
    s = result.scores
    if "auc" in s:
        rec["scores"] = (f"{result.tracker} on {result.clip}, frames 1–{n - 1}: AUC {s['auc']:.3f} · "
                         f"precision@20px {s['precision20']:.3f} · tracking rate "
                         f"{s['tracking_rate']:.1%}")
    else:
        rec["scores"] = f"{result.tracker} on {result.clip}: no ground truth"
    parts, wins = [], []
    for st in states[:n]:
        p = st.get("particles")
        if p is None or max_particles <= 0:
            parts.append(None)
        else:
            p = np.asarray(p, dtype=float)[:, :2]
            w = st.get("weights")
            w = np.ones(len(p)) if w is None else np.asarray(w, dtype=float)
            keep = np.argsort(-w)[:max_particles]
            wn = w[keep] / (w[keep].max() or 1.0)
            parts.append([[round(float(a), 1), round(float(b), 1), round(float(c), 2)]
                          for (a, b), c in zip(p[keep], wn)])
        sw = st.get("search_window")
        wins.append(_box(sw) if sw is not None and len(sw) == 4 else None)
    if any(p is not None for p in parts):
        rec["particles"] = parts
    if any(w is not None for w in wins):
        rec["windows"] = wins
    return rec


def page_html(clips: dict, runs: dict, trackers: list, knobs: dict, fallback_png: bytes | None,
              note: str) -> str:
    """The HTML of one playground: root ``.tb-playground``, data as inline JSON, viewer inline.

    ``clips[name] = {"frames": [...data URLs], "gt": [...], "w": W, "h": H}``;
    ``runs["tracker|clip|knob=value"]`` (``"tracker|clip|"`` at the defaults) from
    :func:`run_record`; ``knobs[name] = {"values": [str], "default": str}``.
    """
    uid = f"tb-playground-{next(_ids)}-{np.random.default_rng().integers(1 << 30)}"
    data = {"clips": clips, "clips_order": list(clips), "runs": runs, "trackers": trackers,
            "knobs": knobs, "note": note}
    payload = json.dumps(data, separators=(",", ":")).replace("</", "<\\/")
    fallback = ""
    if fallback_png:
        b64 = base64.b64encode(fallback_png).decode()
        fallback = (f'<noscript><img alt="static picture of the playground" '
                    f'src="data:image/png;base64,{b64}" style="max-width:100%"></noscript>')
    style = ("<style>.tb-playground{font:13px sans-serif;margin:.5em 0}.tb-playground canvas"
             "{max-width:100%;border:1px solid #ddd}.tb-controls label{margin-right:.8em;"
             "display:inline-block}.tb-bar input[type=range]{width:50%;vertical-align:middle}"
             ".tb-note{color:#555;font-size:12px}</style>")
    return (f'{style}<div class="tb-playground" data-tb-data="{uid}-data"></div>'
            f'<script type="application/json" id="{uid}-data">{payload}</script>{fallback}'
            f"<script>{viewer_js()}</script>")


def clip_entry(clip, n: int) -> dict:
    """A clip's first ``n`` frames and ground truth for :func:`page_html`."""
    frames = [clip.frames[i] for i in range(n)]
    urls, _ = encode_frames(frames)
    h, w = frames[0].shape[:2]
    return {"frames": urls, "gt": [_box(b) for b in np.asarray(clip.groundtruth)[:n]],
            "w": int(w), "h": int(h), "name": html.escape(clip.name)}


__all__ = ["clip_entry", "encode_frames", "page_html", "run_record", "viewer_js"]
