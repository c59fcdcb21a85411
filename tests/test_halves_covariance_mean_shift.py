"""The covariance trackers (Lee 2015), mean-shift and OpenCV's MIL written in halves:
``_locate`` learns nothing, a lost frame teaches nothing, and the ``-redetect`` names find a
target that jumped across the frame."""
import copy

import cv2
import numpy as np
import pytest

from trackbook import trackers
from trackbook.trackers.failure import FailureParams

HALVES = ["covariance", "kalman-covariance", "kalman-covariance-manoeuvre", "mean-shift"]
A, B, SIZE = (20, 20), (112, 80), 24


def _background(rng):
    return cv2.resize(rng.integers(40, 140, (12, 16, 3), dtype=np.uint8), (160, 120))


def _target(rng):
    # red, textured: distinct from the green-grey background in colour and in covariance
    t = cv2.resize(rng.integers(0, 256, (4, 4, 3), dtype=np.uint8), (SIZE, SIZE),
                   interpolation=cv2.INTER_NEAREST)
    t[..., 2] = 200 + t[..., 2] // 5
    t[..., 1] //= 4
    return t


def _jump_clip(n_before=10, n_after=20):
    """Frames with the target at A, then at B (far away) for good; light sensor noise. The
    target sits on a plain grey card 4 px wider on each side, so the pixels just outside its
    box (the gradients at a window's edge) are the same at A and at B."""
    rng = np.random.default_rng(3)
    bg, patch = _background(rng), _target(rng)
    frames = []
    for k in range(n_before + n_after):
        x, y = A if k < n_before else B
        f = bg.astype(np.int16) + rng.integers(-3, 4, bg.shape)
        f[y - 4:y + SIZE + 4, x - 4:x + SIZE + 4] = 128
        f[y:y + SIZE, x:x + SIZE] = patch
        frames.append(np.clip(f, 0, 255).astype(np.uint8))
    return frames


def _model_arrays(t):
    out = {}
    for k in ("_model", "q", "_center", "_centre", "_axes"):
        if hasattr(t, k):
            out[k] = np.array(getattr(t, k), dtype=float, copy=True)
    if hasattr(t, "_kf"):
        out["kf.x"], out["kf.P"] = t._kf.x.copy(), t._kf.P.copy()
    return out


@pytest.mark.parametrize("name", HALVES)
def test_locate_has_no_side_effect_on_the_model(name):
    frames = _jump_clip()
    t = trackers.create(name)
    t.init(frames[0], (*A, SIZE, SIZE))
    for f in frames[1:4]:
        t.update(f)
    before = _model_arrays(t)
    a, b = copy.deepcopy(t), copy.deepcopy(t)
    out_a, out_b = a._locate(frames[4]), b._locate(frames[4])
    np.testing.assert_array_equal(np.asarray(out_a[0], float), np.asarray(out_b[0], float))
    assert out_a[1] == out_b[1] and np.isfinite(out_a[1])
    after = _model_arrays(a)
    for k in ("_model", "q", "_center", "_centre", "_axes"):
        if k in before:
            np.testing.assert_array_equal(after[k], before[k], err_msg=k)


@pytest.mark.parametrize("name", HALVES)
def test_a_lost_frame_does_not_change_the_model(name):
    frames = _jump_clip()
    t = trackers.create(name, model_update=0.5) if "covariance" in name else \
        trackers.create(name)
    t.init(frames[0], (*A, SIZE, SIZE))
    for f in frames[1:5]:
        assert t.update(f)[0]
    before = _model_arrays(t)
    flat = np.full_like(frames[0], 128)
    ok, box = t.update(flat)
    assert not ok and box == t.bbox
    after = _model_arrays(t)
    for k in ("_model", "q", "_center", "_centre", "_axes"):
        if k in before:
            np.testing.assert_array_equal(after[k], before[k], err_msg=k)
    assert np.isfinite(t.state().confidence)


@pytest.mark.parametrize("name", ["kalman-covariance", "mean-shift"])
def test_redetect_finds_a_target_that_jumped(name):
    frames = _jump_clip()
    boxes = {}
    for n in (name, f"{name}-redetect"):
        t = trackers.create(n)
        t.init(frames[0], (*A, SIZE, SIZE))
        boxes[n] = [t.update(f) for f in frames[1:]]
    # the canonical name stays lost where the target was: nothing near A matches any more
    oks = [ok for ok, _ in boxes[name][9:]]   # boxes[i] is frame i + 1
    assert not any(oks[:5])
    # the re-detecting one ends on B (the construction of the frames) and reports ok
    ok, box = boxes[f"{name}-redetect"][-1]
    assert ok
    assert abs(box[0] + box[2] / 2 - (B[0] + SIZE / 2)) <= 3
    assert abs(box[1] + box[3] / 2 - (B[1] + SIZE / 2)) <= 3


def test_failure_params_can_force_the_layer():
    # k_lost = k_found = 0 with a reference of identical frames: any worse frame is lost
    frames = _jump_clip()
    t = trackers.create("covariance", failure=FailureParams(k_lost=0, k_found=0, warmup=1))
    t.init(frames[0], (*A, SIZE, SIZE))
    assert t.failure_params.k_lost == 0
