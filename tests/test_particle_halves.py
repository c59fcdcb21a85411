"""The particle trackers written in halves: ``_locate`` (the SIR cycle) learns nothing, a frame
judged lost teaches nothing, and the ``-redetect`` variants find a target that jumped away."""

from __future__ import annotations

import copy

import cv2
import numpy as np
import pytest

from trackbook import trackers

NAMES = ("color-pf", "color-hog-pf", "color-hog-ipca", "hsi-color-pf", "hog-pf", "edge-ray-pf",
         "condensation", "condensation-mean-shift")

H, W, S = 240, 320, 40          # frame and target size (px)
A, B = (30, 30), (250, 170)     # the target's top-left corner before and after the jump


def _background(seed=0):
    """A textured background: smoothed noise, green-grey, the same every frame."""
    rng = np.random.default_rng(seed)
    noise = cv2.GaussianBlur(rng.uniform(0, 255, (H, W)).astype(np.float32), (0, 0), 3)
    noise = cv2.normalize(noise, None, 60, 160, cv2.NORM_MINMAX)
    return np.dstack([0.6 * noise, noise, 0.7 * noise]).astype(np.uint8)


def _target():
    """A 40 x 40 target of colours the background does not have (red and blue halves) with
    a white ring: edges and gradients around its centre for the edge and HOG models."""
    t = np.zeros((S, S, 3), np.uint8)
    t[:, :S // 2] = (30, 30, 220)
    t[:, S // 2:] = (220, 60, 30)
    cv2.rectangle(t, (10, 10), (29, 29), (255, 255, 255), 3)
    return t


def _frame(corner, rng=None):
    """The background with the target at ``corner``; with ``rng``, light sensor noise
    (+-3 grey levels per pixel and channel) on top."""
    f = _background()
    x, y = corner
    f[y:y + S, x:x + S] = _target()
    if rng is not None:
        f = np.clip(f.astype(np.int16) + rng.integers(-3, 4, f.shape), 0, 255).astype(np.uint8)
    return f


def _model_arrays(t) -> dict:
    """Copies of the arrays that make a tracker's model of the target."""
    out = {}
    for k in ("_reference", "_root_reference"):
        for kk, v in getattr(t, k, {}).items() if isinstance(getattr(t, k, None), dict) else ():
            out[f"{k}.{kk}"] = np.array(v)
    for k in ("reference", "model_rays", "_m0", "q"):
        v = t.__dict__.get(k)
        if isinstance(v, np.ndarray):
            out[k] = v.copy()
    if getattr(t, "_subspaces", None):
        for kk, s in t._subspaces.items():
            out[f"U.{kk}"], out[f"S.{kk}"] = s.U.copy(), s.S.copy()
    if hasattr(t, "_colour"):
        out["colour"] = t._colour.reference.copy()
    out["estimate"] = np.array(t.estimate, dtype=float)
    return out


def _assert_same(a: dict, b: dict):
    assert a.keys() == b.keys()
    for k in a:
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)


@pytest.mark.parametrize("name", NAMES)
def test_locate_learns_nothing_and_repeats(name):
    """Two copies of a tracker run ``_locate`` on the same frame: the same box and confidence,
    and neither the model nor the accepted estimate moved (the particles may: they are the
    filter's state)."""
    kw = {"T": 3} if name == "color-hog-ipca" else {}
    t = trackers.create(name, seed=0, **kw)
    t.init(_frame(A), (*A, S, S))
    for i in range(5):                              # past T: the subspaces exist
        t.update(_frame((A[0] + i, A[1])))
    before = _model_arrays(t)
    t1, t2 = copy.deepcopy(t), copy.deepcopy(t)
    f = _frame((A[0] + 6, A[1] + 2))
    box1, c1 = t1._locate(f)[:2]
    box2, c2 = t2._locate(f)[:2]
    np.testing.assert_array_equal(box1, box2)
    assert c1 == c2 and np.isfinite(c1)
    _assert_same(before, _model_arrays(t1))
    if name == "color-hog-ipca":
        assert t1.n_learned == t.n_learned


@pytest.mark.parametrize("name", NAMES)
def test_a_lost_frame_teaches_nothing(name):
    """A flat frame is judged lost: the box stays, the model and the estimate do not change
    (``color-hog-ipca`` learns no frame)."""
    kw = {"T": 3} if name == "color-hog-ipca" else {}
    t = trackers.create(name, seed=0, **kw)
    t.init(_frame(A), (*A, S, S))
    for i in range(5):
        t.update(_frame((A[0] + i, A[1])))
    before, box, learned = _model_arrays(t), t.bbox, getattr(t, "n_learned", None)
    for _ in range(3):
        ok, b = t.update(np.full((H, W, 3), 90, np.uint8))
        assert not ok and b == box
        assert np.isfinite(t.state().confidence)
    _assert_same(before, _model_arrays(t))
    assert getattr(t, "n_learned", None) == learned


def _iou(a, b):
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    iw = max(0.0, min(ax + aw, bx + bw) - max(ax, bx))
    ih = max(0.0, min(ay + ah, by + bh) - max(ay, by))
    return iw * ih / (aw * ah + bw * bh - iw * ih)


# hog-pf-redetect misses it: the HOG match is sharply peaked (rho 1.0 at B, 0.39 at the
# nearest box of the re-detection grid, 6 px off in x and y; 0.52 at a background box), and
# the base's grid over this 320 x 240 frame has a 16 px step, so the restart lands 40 px away.
REDETECT_CASES = [pytest.param(n, marks=pytest.mark.xfail(
    strict=True, reason="the re-detection grid (16 px step) is coarser than the HOG match's "
    "peak")) if n == "hog-pf" else n for n in NAMES]


@pytest.mark.parametrize("name", REDETECT_CASES)
def test_redetect_finds_a_target_that_jumped_across_the_frame(name):
    """The target sits at A for 10 frames, then at B, across the frame, for 15. The
    canonical name loses it (ok=False) and its box stays near A; the ``-redetect`` variant
    searches the whole frame and ends on B (IoU >= 0.5), on target."""
    if name.startswith("condensation"):
        # Without noise the ellipse trackers' best candidate sits on the same pixels every
        # frame and scores the same rho to the last digit: the failure layer's reference has
        # no spread, and any lower value would be a loss. Sensor noise gives it one.
        rng = np.random.default_rng(5)
        frames = [_frame(A, rng) for _ in range(11)] + [_frame(B, rng) for _ in range(15)]
    else:
        frames = [_frame(A)] * 11 + [_frame(B)] * 15
    gt_b = (*B, S, S)
    runs = {}
    for n in (name, f"{name}-redetect"):
        t = trackers.create(n, seed=0)
        t.init(frames[0], (*A, S, S))
        runs[n] = [t.update(f) for f in frames[1:]]
    canon, redet = runs[name], runs[f"{name}-redetect"]
    assert all(ok for ok, _ in canon[:10]) and all(ok for ok, _ in redet[:10])
    assert not canon[10][0]                                   # the jump is a loss
    assert _iou(canon[-1][1], gt_b) < 0.1
    assert redet[-1][0] and _iou(redet[-1][1], gt_b) >= 0.5
