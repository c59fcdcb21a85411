"""What the viewer draws, as compact JSON: frames once as JPEG, and per run only boxes and state.

A *clip payload* holds the frames (base64 JPEG) and the ground truth; a *run payload* holds a
tracker's boxes, ``ok`` flags, IoU per frame, the scores line and the state the chapter draws
(particles subsampled and quantised, search window, ellipse, candidates, rays, the tracker's
confidence per frame and a correlation filter's response map, shrunk and quantised). The same
payloads feed the Jupyter widget (sent over the comm) and the static HTML book (embedded in the
page), so one JavaScript module draws both.
"""

from __future__ import annotations

import base64
import dataclasses
import math
from pathlib import Path

import cv2
import numpy as np

from .. import params as _params
from .. import trackers as _trackers
from ..evaluation import metrics
from ..evaluation.runner import evaluate

#: the viewer module (and its style sheet) that draws every panel, in Jupyter and in the book
VIEWER_JS = Path(__file__).parent / "viewer.js"
VIEWER_CSS = Path(__file__).parent / "viewer.css"

#: most particles sent per frame: enough to see the cloud, small enough to ship many runs
MAX_PARTICLES = 40
#: most candidate boxes sent per frame
MAX_CANDIDATES = 12
#: most cells a side of a response map sent per frame (the inset is ~100 px: more is not seen)
MAX_RESPONSE_SIDE = 32
#: most bytes of response maps per run (uint8 cells, before base64; a 120-frame run: 14 x 14
#: cells a map, some 31 KB of base64 beside its 7 KB of boxes): a long clip's maps are
#: shrunk below ``MAX_RESPONSE_SIDE`` so a run file keeps its state under the file cap
RESPONSE_BYTES = 24_000
#: fewest cells a side of a shrunk response map (the peak and its side lobes still show)
MIN_RESPONSE_SIDE = 8
JPEG_QUALITY = 72


def _b64(a: np.ndarray) -> str:
    return base64.b64encode(np.ascontiguousarray(a).tobytes()).decode("ascii")


def jpeg(img, quality: int = JPEG_QUALITY) -> str:
    """A BGR image (as OpenCV and the clips hold it) as base64 JPEG text for the viewer."""
    ok, buf = cv2.imencode(".jpg", np.asarray(img), [cv2.IMWRITE_JPEG_QUALITY, int(quality)])
    if not ok:
        raise ValueError(f"cannot encode an image of shape {np.shape(img)} as JPEG.")
    return base64.b64encode(buf.tobytes()).decode("ascii")


def clip_payload(clip, n: int, quality: int = JPEG_QUALITY) -> dict:
    """The first ``n`` frames of ``clip`` as JPEG (encoded once) and their ground truth."""
    frames = []
    for i, f in enumerate(clip.frames):
        if i >= n:
            break
        frames.append(jpeg(f, quality))
    gt = np.asarray(clip.groundtruth[:len(frames)], dtype=float)
    has_gt = bool(np.isfinite(gt).all(axis=1).any())
    w, h = clip.size
    return {"name": clip.name, "w": int(w), "h": int(h), "frames": frames,
            "gt": [[round(float(v), 1) for v in b] if np.isfinite(b).all() else None
                   for b in gt] if has_gt else None}


def downsample_response(r, side: int = MAX_RESPONSE_SIDE) -> np.ndarray:
    """A response map shrunk to at most ``side`` cells a side, its aspect kept, each new cell
    the mean of the cells it covers (OpenCV's area interpolation: a block mean when the sizes
    divide); a map already that small is returned as it is (as float)."""
    r = np.asarray(r, dtype=float)
    R, C = r.shape
    if max(R, C) <= side:
        return r
    f = side / max(R, C)
    nr, nc = max(1, min(side, round(R * f))), max(1, min(side, round(C * f)))
    # float32 is what cv2.resize averages in; a response has no use for more digits
    return cv2.resize(r.astype(np.float32), (nc, nr), interpolation=cv2.INTER_AREA).astype(float)


def snapshot(state) -> dict:
    """What to draw for one frame, from a tracker's :class:`~trackbook.trackers.TrackerState`
    (``tracker.state()``), subsampled for the viewer."""
    snap = {}
    p = state.particles
    if p is not None and len(p):
        p = np.asarray(p, dtype=float)
        w = state.weights
        w = np.full(len(p), 1.0 / len(p)) if w is None else np.asarray(w, dtype=float)
        full_w = w
        if len(p) > MAX_PARTICLES:     # an even subsample keeps the cloud's shape
            idx = np.linspace(0, len(p) - 1, MAX_PARTICLES).round().astype(int)
            p, w = p[idx], w[idx]
        snap["particles"] = p[:, :2].copy()
        snap["weights"] = w.copy()
        pr = state.rays
        if pr is not None and len(pr) and state.weights is not None and len(full_w) == len(pr):
            best = int(np.argmax(full_w))
            snap["rays"] = [*np.asarray(state.particles)[best, :2], *np.asarray(pr)[best]]
    for key in ("search_window", "ellipse"):
        v = getattr(state, key)
        if v is not None:
            snap[key] = [float(x) for x in np.asarray(v, dtype=float).ravel()[:4]]
    c = state.candidates
    if c is not None and len(c):
        c = np.asarray(c, dtype=float)[:, :4]
        if len(c) > MAX_CANDIDATES:
            c = c[np.linspace(0, len(c) - 1, MAX_CANDIDATES).round().astype(int)]
        snap["candidates"] = c.copy()
    conf = getattr(state, "confidence", None)
    if conf is not None:
        snap["confidence"] = float(conf)
    resp, rbox = getattr(state, "response", None), getattr(state, "response_box", None)
    if resp is not None and rbox is not None and np.ndim(resp) == 2 and np.size(resp):
        snap["response"] = downsample_response(resp)
        snap["response_box"] = [float(v) for v in rbox]
    return snap


def _sig(x: float, digits: int = 4):
    """``x`` to ``digits`` significant digits (None for NaN or infinity: JSON has neither)."""
    x = float(x)
    return None if not math.isfinite(x) else float(f"{x:.{digits}g}")


def encode_responses(maps: list, max_bytes: int = RESPONSE_BYTES) -> dict:
    """Per-frame response maps (None where a frame has none) as the run payload's entries:
    ``rshape`` ([rows, cols] per frame), ``rrange`` ([lo, hi] per frame, 6 significant
    digits) and ``response``, base64 of every map's cells as uint8, row by row, frame after
    frame: cell = lo + q / 255 (hi - lo). Maps are shrunk (:func:`downsample_response`) until
    all of them fit ``max_bytes`` bytes, but never below ``MIN_RESPONSE_SIDE`` cells a side."""
    have = [m for m in maps if m is not None]
    side = MAX_RESPONSE_SIDE
    if have:
        cells = max(np.shape(m)[0] * np.shape(m)[1] for m in have)
        while side > MIN_RESPONSE_SIDE and min(cells, side * side) * len(have) > max_bytes:
            side -= 1
    shapes, ranges, flat = [], [], []
    for m in maps:
        if m is None:
            shapes.append(None)
            ranges.append(None)
            continue
        m = downsample_response(m, side)
        finite = np.isfinite(m)
        lo = _sig(m[finite].min(), 6) if finite.any() else 0.0
        hi = _sig(m[finite].max(), 6) if finite.any() else 0.0
        span = hi - lo
        q = (np.zeros(m.shape) if span <= 0 else
             np.round((np.where(finite, m, lo) - lo) / span * 255))
        flat.append(np.clip(q, 0, 255).astype(np.uint8).ravel())
        shapes.append([int(m.shape[0]), int(m.shape[1])])
        ranges.append([lo, hi])
    return {"rshape": shapes, "rrange": ranges,
            "response": _b64(np.concatenate(flat)) if flat else ""}


def decode_responses(state: dict) -> list:
    """The maps of :func:`encode_responses`'s entries (None where a frame has none), as the
    viewer reads them."""
    raw = np.frombuffer(base64.b64decode(state.get("response", "")), dtype=np.uint8)
    out, o = [], 0
    for shape, rng in zip(state["rshape"], state["rrange"]):
        if shape is None:
            out.append(None)
            continue
        n = shape[0] * shape[1]
        q = raw[o:o + n].reshape(shape).astype(float)
        o += n
        out.append(rng[0] + q / 255.0 * (rng[1] - rng[0]))
    return out


def _encode_state(states: list[dict]) -> dict:
    """Per-frame snapshots -> compact arrays: particles as base64 int16 (x, y in half pixels;
    weight relative to the frame's largest, 0..1000), response maps as base64 uint8
    (:func:`encode_responses`), the confidence to four significant digits, the rest rounded
    to 0.1 px."""
    out: dict = {}
    if any("particles" in s for s in states):
        counts, flat = [], []
        for s in states:
            p = s.get("particles")
            if p is None:
                counts.append(0)
                continue
            w = s["weights"]
            w = w / w.max() if w.max() > 0 else np.ones_like(w)
            q = np.column_stack([np.round(p * 2), np.round(w * 1000)])
            flat.append(np.clip(q, -32768, 32767).astype("<i2").ravel())
            counts.append(len(p))
        out["pcount"] = counts
        out["particles"] = _b64(np.concatenate(flat)) if flat else ""

    def tidy(x):    # 33.0 -> 33: whole-pixel boxes (a stride's grid) cost a third less JSON
        if isinstance(x, list):
            return [tidy(v) for v in x]
        return int(x) if float(x).is_integer() else x

    def rounded(key, reshape=False):
        if any(key in s for s in states):
            out[key] = [None if key not in s else
                        tidy(np.round(np.asarray(s[key], dtype=float), 1).tolist())
                        for s in states]

    for key in ("search_window", "ellipse", "candidates", "rays", "response_box"):
        rounded(key)
    if any("confidence" in s for s in states):
        # four significant digits: a curve 100-odd px high shows no more
        out["confidence"] = [_sig(s["confidence"]) if "confidence" in s else None
                             for s in states]
    if any("response" in s for s in states):
        out.update(encode_responses([s.get("response") for s in states]))
    return out


def scores_text(result) -> str:
    return f"{result.tracker} on {result.clip}: {metrics.scores_line(result.scores)}"


def run_payload(tracker: str, clip, values: dict, n: int | None, seed: int = 0,
                init_box=None) -> tuple[dict, object, list]:
    """Track ``clip`` with ``tracker`` and ``values``; return (payload, result, snapshots)."""
    states: list[dict] = []
    r = evaluate(tracker, clip, seed=seed, max_frames=n, init_box=init_box,
                 on_frame=lambda i, t, f, b: states.append(snapshot(t.state())), **values)
    return result_payload(r, clip, values, states, n, tracker), r, states


def payload(clip, tracker: str, values: dict, boxes, ok, scores: str, states: list,
            n_total: int) -> dict:
    """The run payload of the frames done so far: ``boxes``/``ok`` of the first
    ``n_done = len(boxes)`` frames, their snapshots ``states`` and the ``scores`` line;
    ``n_total`` the frames the run will have (``n_done < n_total``: partial)."""
    boxes = np.asarray(boxes, dtype=float)
    nb = len(boxes)
    gt = np.asarray(clip.groundtruth[:max(n_total, nb)], dtype=float)
    has_gt = bool(np.isfinite(gt).all(axis=1)[1:].any())
    iou = metrics.iou(boxes, gt[:nb]) if has_gt and nb else None
    return {
        "clip": clip.name, "tracker": tracker,
        "values": {k: list(v) if isinstance(v, tuple) else v for k, v in values.items()},
        "boxes": np.round(boxes, 1).tolist(),
        "ok": np.asarray(ok, dtype=bool).astype(int).tolist(),
        "iou": None if iou is None else [None if not math.isfinite(v) else round(float(v), 3)
                                          for v in iou],
        "scores": scores,
        "state": _encode_state(states),
        "n_done": nb, "n_total": max(n_total, nb),
    }


def result_payload(r, clip, values: dict, states: list, n: int | None = None,
                   tracker: str | None = None) -> dict:
    """The run payload of a finished :class:`~trackbook.evaluation.runner.Result` and its
    per-frame snapshots (``[]`` when the tracker draws no state): ``n_done`` frames computed,
    ``n_total`` the frames the run has (the clip, or ``n``)."""
    nb = len(r.boxes)
    n_total = len(clip) if n is None else min(int(n), len(clip))
    if not states:
        states = [{}] * nb
    return payload(clip, tracker or str(r.tracker), values, r.boxes, r.ok, scores_text(r),
                   states[:nb] if len(states) >= nb else [{}] + states, n_total)


def knob_spec(cls, name: str, value=None) -> dict | None:
    """The viewer's description of one knob, from the params field's metadata."""
    fields = {f.name: f for f in dataclasses.fields(cls.Params)}
    if name not in fields:
        return None
    f = fields[name]
    m = f.metadata
    v = f.default if value is None else value
    spec = {"name": name, "doc": m.get("doc", ""), "default": list(v) if isinstance(v, tuple) else v}
    choices = _params.choices_of(f)
    lo, hi = _params.slider_of(f)       # the slider's range, not the (wider) allowed one
    if choices:
        spec.update(kind="choice", choices=list(choices))
    elif isinstance(v, bool):
        spec.update(kind="bool")
    elif isinstance(v, tuple):
        lo = lo if lo is not None else 0.0
        hi = hi if hi is not None else 2 * max(v)
        spec.update(kind="pair", lo=lo, hi=hi, step=m.get("step") or (hi - lo) / 100)
    elif isinstance(v, (int, float)):
        is_int = isinstance(v, int)
        lo = lo if lo is not None else 0
        hi = hi if hi is not None else max(2 * v, 1)
        step = m.get("step") or (1 if is_int else (hi - lo) / 100)
        spec.update(kind="int" if is_int else "float", lo=lo, hi=hi, step=step)
    else:
        spec.update(kind="text")
    return spec


_SAMPLES = {
    "n_particles": [10, 30, 100, 300, 1000],
    "alpha": [0.0, 0.1, 0.3, 0.5, 0.9, 1.0],
}
_PAIR_SAMPLES = [(0.95, 1.05), (0.9, 1.1), (0.8, 1.2), (0.7, 1.4), (0.5, 2.0)]


def sample_values(spec: dict, k: int = 5) -> list:
    """A few values of a knob around its default, within the field's range: the stops the
    knob offers (the HTML book's pages precompute a few of them; Jupyter takes any value)."""
    d = spec["default"]
    kind = spec["kind"]
    if kind == "choice":
        return list(spec["choices"])
    if kind == "bool":
        return [d, not d]
    if kind == "pair":
        vals = [list(p) for p in _PAIR_SAMPLES if spec["lo"] <= p[0] and p[1] <= spec["hi"]]
    elif kind in ("int", "float"):
        lo, hi = spec["lo"], spec["hi"]
        if spec["name"] in _SAMPLES:
            vals = [v for v in _SAMPLES[spec["name"]] if lo <= v <= hi]
        elif kind == "float" and lo > 0 and hi / lo >= 1e3:
            # a range over decades (a regulariser such as lambda): evenly spaced in log
            vals = list(np.geomspace(lo, hi, k))
        else:
            vals = list(np.linspace(lo, hi, k))
            step = spec["step"]
            # on the step grid, but never past the field's range (0.01 + 200 * 0.5 = 100.01
            # would be refused by a q whose maximum is 100)
            vals = [min(hi, max(lo, lo + round((v - lo) / step) * step)) for v in vals]
        # six significant digits (not decimals: 1e-8 must not become 0), never past the range
        vals = [int(round(v)) if kind == "int" else min(hi, max(lo, float(f"{v:.6g}")))
                for v in vals]
    else:
        return [d]
    if d not in vals:
        vals.append(d)
    out = []
    for v in sorted(vals):
        if v not in out:
            out.append(v)
    return out


def params_class(name):
    """The tracker class of ``name`` when its params are a dataclass (knobs), else None."""
    cls = _trackers.get(name)
    return cls if dataclasses.is_dataclass(getattr(cls, "Params", None)) else None


def field_names(tracker) -> list:
    """The names of ``tracker``'s params (its knobs), in declaration order."""
    cls = params_class(tracker)
    return [f.name for f in dataclasses.fields(cls.Params)] if cls else []


def _jsonable(v):
    return list(v) if isinstance(v, tuple) else v


def parse_values(tracker, values: dict) -> dict:
    """``values`` for ``tracker``'s params through the one parser
    (:func:`trackbook.params.parse`, then the params' own checks of combinations), as the
    ``values`` trait stores them (tuples as lists); raises ``ValueError`` naming the knob."""
    cls = params_class(tracker)
    if cls is None:
        if values:
            raise ValueError(f"tracker {tracker!r} has no params; it takes no knob "
                             f"(got {sorted(values)}).")
        return {}
    if not isinstance(values, dict):
        raise TypeError(f"values must be a dict {{knob: value}}, got {type(values).__name__}.")
    # make_params parses each value once and checks the combinations (e.g. low < high)
    p = _params.make_params(cls.Params, values)
    return {k: _jsonable(getattr(p, k)) for k in values}
