"""The tracker contract, the registry and bad input."""
import dataclasses

import numpy as np
import pytest

import trackbook
from trackbook import trackers
from trackbook.params import param
from trackbook.trackers.base import Tracker


@dataclasses.dataclass(frozen=True)
class _P:
    step: float = param(2.0, 0.0, 10.0, 0.5, "pixels per frame")
    mode: str = param("a", choices=("a", "b"))


class Drifter(Tracker):
    """Moves the box right by ``step`` px per frame plus seeded jitter; for testing the base."""
    name = "test-drifter"
    Params = _P

    def _init(self, frame, box):
        self.box = box.copy()

    def _update(self, frame):
        self.box[0] += self.params.step + self.rng.normal()
        return True, self.box


class Broken(Drifter):
    name = "test-broken"

    def _update(self, frame):
        return True, (np.nan, 0, 10, 10)


def test_registry_lists_only_real_trackers_and_names_them_on_error():
    names = trackers.available(reference=False)
    assert "opencv-mil" not in names
    assert "opencv-mil" in trackers.available()
    with pytest.raises(ValueError, match="registered trackers"):
        trackers.create("no-such-tracker")


def test_params_defaults_overrides_and_errors():
    t = Drifter(seed=1)
    assert t.params.step == 2.0
    assert Drifter(step=3.5).params.step == 3.5
    with pytest.raises(ValueError, match="unknown parameter"):
        Drifter(stpe=1)
    with pytest.raises(ValueError, match="not finite"):
        Drifter(step=float("nan"))
    with pytest.raises(ValueError, match="above its maximum"):
        Drifter(step=99.0)
    with pytest.raises(ValueError, match="not one of"):
        Drifter(mode="c")
    with pytest.raises(dataclasses.FrozenInstanceError):
        t.params.step = 1.0


def test_same_seed_same_boxes_and_reinit_repeats(textured_frame):
    def run(t):
        t.init(textured_frame, (10, 10, 20, 20))
        return [t.update(textured_frame)[1] for _ in range(5)]
    a, b, c = Drifter(seed=7), Drifter(seed=7), Drifter(seed=8)
    ra = run(a)
    assert ra == run(b)
    assert ra != run(c)
    assert run(a) == ra  # init re-seeds: a teacher re-running a cell sees the same boxes


@pytest.mark.parametrize("frame, msg", [
    (np.zeros((240, 320), np.uint8), "COLOR_GRAY2BGR"),
    (np.zeros((240, 320, 4), np.uint8), "BGRA2BGR"),
    (np.zeros((240, 320, 3), np.float32), "uint8"),
    ([[1, 2, 3]], "numpy array"),
    (np.zeros((0, 0, 3), np.uint8), "empty"),
])
def test_bad_frames(frame, msg):
    with pytest.raises(ValueError, match=msg):
        Drifter().init(frame, (1, 1, 1, 1))


@pytest.mark.parametrize("box, msg", [
    ((0, 0, 0, 10), "zero or negative size"),
    ((0, 0, 10, -3), "zero or negative size"),
    ((np.nan, 0, 10, 10), "NaN"),
    ((0, 0, 10), "four numbers"),
    ((500, 500, 10, 10), "wholly outside"),
    ((-20, 5, 40, 40), "partly outside"),
    ("box", "four numbers"),
])
def test_bad_boxes(textured_frame, box, msg):
    with pytest.raises(ValueError, match=msg):
        Drifter().init(textured_frame, box)


def test_clip_box_fixes_partly_outside(textured_frame):
    box = trackers.clip_box((-20, 5, 40, 40), textured_frame.shape)
    np.testing.assert_array_equal(box, [0, 5, 20, 40])
    Drifter().init(textured_frame, box)


def test_update_before_init_and_size_change(textured_frame):
    t = Drifter()
    with pytest.raises(ValueError, match="call init"):
        t.update(textured_frame)
    t.init(textured_frame, (10, 10, 20, 20))
    with pytest.raises(ValueError, match="same size"):
        t.update(textured_frame[:100])


def test_base_never_returns_a_nan_box(textured_frame):
    t = Broken()
    t.init(textured_frame, (10, 10, 20, 20))
    ok, box = t.update(textured_frame)
    assert ok is False and box == (10.0, 10.0, 20.0, 20.0)


def test_evaluate_with_foreign_opencv_tracker_and_names(textured_frame):
    import cv2
    from trackbook.clips import ArrayFrames, Clip
    frames = np.stack([np.roll(textured_frame, 2 * i, axis=1) for i in range(8)])
    gt = np.array([[100 + 2 * i, 80, 40, 40] for i in range(8)], dtype=float)
    clip = Clip("shift", ArrayFrames(frames), gt)
    r = trackbook.evaluate(cv2.TrackerMIL_create(), clip)
    assert r.boxes.shape == (8, 4) and r.ms.shape == (8,)
    assert r.scores["auc"] > 0.5          # a textured shift is easy for MIL
    r2 = trackbook.evaluate("opencv-mil", clip)
    # MIL is not repeatable within one process (see trackers.reference.OpenCVMIL), so the
    # wrapper is checked for what it does promise, not for equal boxes
    assert r2.tracker == "opencv-mil" and r2.scores["auc"] > 0.5
    np.testing.assert_array_equal(r2.boxes[0], r.boxes[0])
    with pytest.raises(ValueError, match="not a tracker"):
        trackbook.evaluate(object(), clip)
    with pytest.raises(ValueError, match="params can only be given"):
        trackbook.evaluate(cv2.TrackerMIL_create(), clip, n_particles=3)
