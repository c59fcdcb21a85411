"""The playground driven as a student would: set a value, check what is shown changed."""
import dataclasses

import ipywidgets as W
import numpy as np
import pytest

from trackbook.params import param
from trackbook.trackers import registry
from trackbook.trackers.base import Tracker
from trackbook.widgets import Playground, slider_for

from .test_bench_cli import tiny_folder  # noqa: F401  (fixture)


@dataclasses.dataclass(frozen=True)
class _P:
    speed: float = param(4.0, 0.0, 8.0, 0.5, "px per frame")
    n_particles: int = param(20, 5, 100, 5, "particles")
    window: tuple = param((0.8, 1.2), 0.5, 1.5, 0.05, "ratio window")


class _Slider(Tracker):
    name = "test-slider"
    Params = _P

    def _init(self, frame, box):
        self.box = box.copy()
        self.particles = np.zeros((self.params.n_particles, 2))

    def _update(self, frame):
        self.box[0] += self.params.speed
        self.particles = self.box[:2] + self.rng.normal(size=(self.params.n_particles, 2))
        return True, self.box


@pytest.fixture
def registered():
    registry.register(_Slider)
    yield
    del registry._REGISTRY[_Slider.name]


def test_sliders_come_from_params_metadata():
    f = {x.name: x for x in dataclasses.fields(_P)}
    s = slider_for(f["speed"])
    assert isinstance(s, W.FloatSlider) and (s.min, s.max, s.value) == (0.0, 8.0, 4.0)
    assert s.continuous_update is False
    assert isinstance(slider_for(f["n_particles"]), W.IntSlider)
    assert isinstance(slider_for(f["window"]), W.FloatRangeSlider)


def test_playground_reacts_to_frame_and_param_changes(registered, tiny_folder):  # noqa: F811
    pg = Playground(clips=[str(tiny_folder)], trackers=["test-slider", "opencv-mil"],
                    params=["speed", "n_particles"])
    assert set(pg.param_ws) == {"speed", "n_particles"}
    renders, first, png = pg.renders, pg.result.boxes.copy(), pg.image_w.value
    pg.frame_w.value = 5
    assert pg.frame == 5 and pg.renders == renders + 1
    assert pg.image_w.value[:4] == b"\x89PNG" and pg.image_w.value != png
    pg.param_ws["speed"].value = 0.0              # the student drags the slider
    assert pg.result.params["speed"] == 0.0
    assert not np.allclose(pg.result.boxes, first)
    np.testing.assert_allclose(pg.result.boxes[5], pg.result.boxes[0])  # box no longer moves
    assert "AUC" in pg.scores_w.value
    assert len(pg.states[5]["particles"]) == 20
    pg.tracker_w.value = "opencv-mil"             # MIL has no such params: sliders go away
    assert pg.param_ws == {} and pg.result.tracker == "opencv-mil"
    fig = pg.static_figure()
    assert len(fig.axes) == 4


def test_playground_rejects_unknown_tracker(tiny_folder):  # noqa: F811
    with pytest.raises(ValueError, match="unknown tracker"):
        Playground(clips=[str(tiny_folder)], trackers=["nope"])
