"""Scenario clips for the contract of ``ok`` (``tests/test_failure_contract.py``,
``experiments/failure_contract.py``), built on the public clips API (``clips.Clip``,
``clips.ArrayFrames``) from the photographs bundled in scikit-image.

Every clip is small (160 x 120 by default) and short, so the matrix over twelve trackers stays
fast. Ground truth is NaN on the frames where no part of the target is in view; ``absent``
marks them, ``back`` is the first frame the whole target is in view again after an absence.

- ``edge_exit``: the target drifts right and leaves across the right border, is out of view,
  and re-enters across the left border at another height.
- ``occluder``: a panel of another colour slides over the target, covers it, and slides away.
- ``flat_frames``: the target is in view; then ``n_absent`` all-black (or all-white) frames.
- ``small_long``: a long run on a small frame; the target stays in view, moving in a loop.
"""

from __future__ import annotations

import dataclasses
from functools import lru_cache

import cv2
import numpy as np
import skimage.data

from trackbook import clips

W, H = 160, 120


@dataclasses.dataclass
class Scenario:
    """A clip and which of its frames the target is absent from."""

    name: str
    clip: clips.Clip
    absent: np.ndarray          # (n,) bool: no part of the target in view
    back: int | None            # first frame fully in view after the absence (None: none)


@lru_cache(maxsize=None)
def _background(w: int, h: int) -> np.ndarray:
    """A cluttered background without the target's colours (the grass photograph, tinted
    green): edges everywhere, so a lost tracker always finds texture to score."""
    g = cv2.resize(skimage.data.grass(), (w, h), interpolation=cv2.INTER_AREA).astype(np.float32)
    bgr = np.stack([0.35 * g + 30, 0.6 * g + 50, 0.4 * g + 40], -1)
    return np.clip(bgr, 0, 255).astype(np.uint8)


@lru_cache(maxsize=None)
def _target(w: int = 24, h: int = 30) -> np.ndarray:
    img = skimage.data.astronaut()[20:260, 150:330, ::-1]          # RGB -> BGR
    t = cv2.resize(np.ascontiguousarray(img), (w, h), interpolation=cv2.INTER_AREA)
    t[:2], t[-2:], t[:, :2], t[:, -2:] = (30, 30, 200), (30, 30, 200), (30, 30, 200), \
        (30, 30, 200)                                                 # a red frame around it
    return t


@lru_cache(maxsize=None)
def _panel(w: int, h: int) -> np.ndarray:
    """An occluder of another colour: a blue-grey textured panel."""
    g = cv2.resize(skimage.data.camera(), (w, h), interpolation=cv2.INTER_AREA).astype(np.float32)
    bgr = np.stack([0.3 * g + 120, 0.3 * g + 90, 0.2 * g + 60], -1)
    return np.clip(bgr, 0, 255).astype(np.uint8)


def _paste(frame, sprite, x, y):
    """Paste ``sprite`` with its top-left at integer (x, y), cut at the frame's border; returns
    the visible box (x, y, w, h) or None when nothing is in view."""
    Hf, Wf = frame.shape[:2]
    h, w = sprite.shape[:2]
    x, y = int(round(x)), int(round(y))
    x0, y0, x1, y1 = max(x, 0), max(y, 0), min(x + w, Wf), min(y + h, Hf)
    if x1 <= x0 or y1 <= y0:
        return None
    frame[y0:y1, x0:x1] = sprite[y0 - y:y1 - y, x0 - x:x1 - x]
    return np.array([x0, y0, x1 - x0, y1 - y0], float)


def _finish(name, frames, gt, rng, noise=2.0) -> clips.Clip:
    a = np.asarray(frames, np.float32)
    a += rng.normal(0.0, noise, a.shape).astype(np.float32)
    a = np.clip(a, 0, 255).astype(np.uint8)
    return clips.Clip(name, clips.ArrayFrames(a), np.asarray(gt, float), fps=30.0,
                      description=name, source="generated")


def _absent(gt):
    return ~np.all(np.isfinite(gt), axis=1)


def _back(gt, full_wh, start):
    for i in range(start, len(gt)):
        if np.all(np.isfinite(gt[i])) and np.allclose(gt[i, 2:], full_wh):
            return i
    return None


def edge_exit(n_before=24, n_absent=16, n_after=20, seed=0, size=(W, H), speed=2.0) -> Scenario:
    """Leaves across the right border at ``speed`` px/frame, re-enters across the left one at
    another height at the same speed."""
    rng = np.random.default_rng(seed)
    w, h = size
    bg, t = _background(w, h), _target()
    th, tw = t.shape[:2]
    frames, gt = [], []
    x_leave = w - tw - speed * n_before + 20            # partly out over the last frames
    n_out = None
    i = 0
    while True:
        f = bg.copy()
        if n_out is None:
            b = _paste(f, t, x_leave + speed * i, 30)
            if b is None:
                n_out = i
        if n_out is not None:
            k = i - n_out
            b = None if k < n_absent else _paste(f, t, -tw + speed * (k - n_absent + 1), 70)
        frames.append(f)
        gt.append(b if b is not None else np.full(4, np.nan))
        i += 1
        if n_out is not None and i - n_out >= n_absent + n_after:
            break
    gt = np.array(gt)
    return Scenario("edge-exit", _finish("edge-exit", frames, gt, rng), _absent(gt),
                    _back(gt, (tw, th), n_out + n_absent))


def occluder(n_before=12, n_cover=14, n_after=20, seed=0, size=(W, H)) -> Scenario:
    """A panel of another colour slides in from the left over the target (which drifts
    slowly right), covers it whole for ``n_cover`` frames, and slides away upwards."""
    rng = np.random.default_rng(seed)
    w, h = size
    bg, t = _background(w, h), _target()
    th, tw = t.shape[:2]
    pw, ph = 44, 50
    panel = _panel(pw, ph)
    frames, gt = [], []
    n = n_before + n_cover + n_after
    for i in range(n):
        f = bg.copy()
        tx, ty = 60 + 0.5 * i, 40
        b = _paste(f, t, tx, ty)
        # panel: approaches over n_before frames, covers, then leaves upwards fast
        if i < n_before:
            px, py = tx - 10 - pw - 3 * (n_before - 1 - i), ty - 10
        elif i < n_before + n_cover:
            px, py = tx - 10, ty - 10
        else:
            px, py = tx - 10, ty - 10 - 8 * (i - n_before - n_cover + 1)
        _paste(f, panel, px, py)
        covered = px <= tx and py <= ty and px + pw >= tx + tw and py + ph >= ty + th
        frames.append(f)
        gt.append(np.full(4, np.nan) if covered else b)
    gt = np.array(gt)
    # a partly covered target: keep its box (the tracker is not asked to be lost there)
    return Scenario("occluder", _finish("occluder", frames, gt, rng), _absent(gt),
                    _back_uncovered("occluder", frames, gt, t, n_before + n_cover, panel))


def _back_uncovered(name, frames, gt, t, start, panel):
    # first frame after ``start`` where the panel no longer overlaps the target at all
    th, tw = t.shape[:2]
    for i in range(start, len(frames)):
        b = gt[i]
        if np.all(np.isfinite(b)):
            x, y = int(b[0]), int(b[1])
            if np.array_equal(frames[i][y:y + th, x:x + tw], t):
                return i
    return None


def flat_frames(value=0, n_before=10, n_absent=10, n_after=15, seed=0, size=(W, H)) -> Scenario:
    """The target in view, then ``n_absent`` constant frames of ``value``, then back where it
    was."""
    rng = np.random.default_rng(seed)
    w, h = size
    bg, t = _background(w, h), _target()
    frames, gt = [], []
    for i in range(n_before + n_absent + n_after):
        f = bg.copy()
        b = _paste(f, t, 60 + i, 45)
        if n_before <= i < n_before + n_absent:
            f[:] = value
            b = np.full(4, np.nan)
        frames.append(f)
        gt.append(b)
    gt = np.array(gt)
    clip = _finish("flat", frames, gt, rng)
    arr = np.array(clip.frames.array)
    arr[n_before:n_before + n_absent] = value              # exactly constant, no noise
    clip = clips.Clip(f"flat-{value}", clips.ArrayFrames(arr), gt, fps=30.0,
                      description="flat frames", source="generated")
    return Scenario(f"flat-{value}", clip, _absent(gt), n_before + n_absent)


def small_long(n=300, size=(W, H), clip="red-cube") -> Scenario:
    """A long run on a small frame: a sample clip shrunk to ``size`` and played forwards and
    backwards for ``n`` frames; the target stays in view."""
    c = clips.load(clip)
    sx, sy = size[0] / c.frames[0].shape[1], size[1] / c.frames[0].shape[0]
    small = np.stack([cv2.resize(f, size, interpolation=cv2.INTER_AREA) for f in c.frames])
    gt = c.groundtruth * np.array([sx, sy, sx, sy])
    k = len(small)
    order = np.array([i % (2 * k - 2) for i in range(n)])
    order = np.where(order < k, order, 2 * k - 2 - order)
    clip = clips.Clip("small-long", clips.ArrayFrames(small[order]), gt[order], fps=30.0,
                      description="small-long", source="generated")
    return Scenario("small-long", clip, _absent(gt[order]), None)


SCENARIOS = {
    "edge-exit": edge_exit,
    "occluder": occluder,
    "black": lambda: flat_frames(0),
    "white": lambda: flat_frames(255),
    "small-long": small_long,
}


def measure(result, sc: Scenario) -> dict:
    """The matrix's numbers for one run (``trackbook.evaluate`` result) on a scenario.

    ``lost_absent``: fraction of absent frames reported ``ok=False``; ``recover``: frames from
    ``back`` to the first frame with IoU > 0.5 (None if not within the clip); ``false_lost``:
    fraction of frames with IoU > 0.5 reported ``ok=False``; ``ok_off``: fraction of present
    frames with IoU < 0.1 (the box is not on the target) reported ``ok=True``.
    """
    from trackbook.evaluation import metrics

    ok = np.asarray(result.ok, bool)
    gt = sc.clip.groundtruth
    iou = np.nan_to_num(metrics.iou(result.boxes, gt), nan=0.0)
    idx = np.arange(len(ok)) >= 1                               # frame 0 is the given box
    absent = sc.absent & idx
    on = (iou > 0.5) & idx
    off = (~sc.absent) & (iou < 0.1) & idx
    rec = None
    if sc.back is not None:
        hit = np.flatnonzero(iou[sc.back:] > 0.5)
        rec = int(hit[0]) if hit.size else None
    return {"lost_absent": float((~ok[absent]).mean()) if absent.any() else float("nan"),
            "recover": rec,
            "false_lost": float((~ok[on]).mean()) if on.any() else float("nan"),
            "ok_off": float(ok[off].mean()) if off.any() else float("nan"),
            "n_off": int(off.sum())}


@lru_cache(maxsize=None)
def in_view(name):
    """Frames of sample clip ``name`` whose target shows at least half of itself: a target
    mostly hidden behind something drawn over it (a tree, the other face) is behind an
    occluder, where ``ok=False`` is the right answer, whatever the box's IoU."""
    from trackbook.clips import samples

    support = samples.render_masks(name).sum(axis=(1, 2))
    visible = samples.render_masks(name, visible=True).sum(axis=(1, 2))
    return visible >= 0.5 * np.maximum(support, 1)


def false_losses(result, clip) -> tuple[int, int]:
    """(frames reported lost, frames with IoU > 0.5 and the target at least half in view) of
    a run on a sample clip, the first frame (given) left out."""
    from trackbook.evaluation import metrics

    iou = np.nan_to_num(metrics.iou(result.boxes, clip.groundtruth), nan=0.0)[1:]
    on = (iou > 0.5) & in_view(clip.name)[1:len(iou) + 1]
    return int((~np.asarray(result.ok, bool)[1:][on]).sum()), int(on.sum())


@lru_cache(maxsize=None)
def scenario(key):
    """``SCENARIOS[key]()``, built once per process."""
    return SCENARIOS[key]()


@lru_cache(maxsize=None)
def evaluated(name, key):
    """``trackbook.evaluate(name, scenario(key).clip, seed=0)``, once per process: the failure
    contract and the confidence checks judge the same runs, and a worker that meets both
    cells of one run makes it once (``--dist loadgroup`` could put them on one worker, but
    pytest 9.2 ignores xdist's groups: pytest-dev/pytest-xdist#1386)."""
    import trackbook

    return trackbook.evaluate(name, scenario(key).clip, seed=0)


def growing_target(n: int, grow: float):
    """A textured target that grows from 40 x 32 px by ``grow`` over ``n`` frames while it
    drifts right: ``(frames, boxes)``. Rendered with the sample clips' compositing engine, so
    every box is exact (the scale tests of the correlation filters)."""
    from trackbook.clips.rendering import Canvas, Sprite, crop, tile

    background = tile(crop("grass", 0, 0, 256, 256, (160, 160)), 320, 240) * np.float32(0.8)
    face = crop("astronaut", 150, 40, 330, 200, (40, 32))
    target = Sprite(face, np.ones(face.shape[:2], np.float32))
    scale = np.geomspace(1.0, grow, n)
    frames, boxes = [], []
    for i in range(n):
        canvas = Canvas(background)
        p = canvas.paste(target, (130 + 1.0 * i, 115 + 0.3 * i), scale=scale[i])
        frames.append(np.clip(canvas.img, 0, 255).astype(np.uint8))
        boxes.append(p.box)
    return frames, np.array(boxes)
