"""The playground refuses a bad knob name or value through the one params parser, keeps the
run it shows and never stores the bad value; any param of a tracker is a knob."""
import math

import pytest

from trackbook.widgets import Playground

from .test_bench_cli import tiny_folder  # noqa: F401  (fixture)
from .test_widgets import registered  # noqa: F401  (fixture)


@pytest.fixture
def pg(registered, tiny_folder):  # noqa: F811
    return Playground(clips=[str(tiny_folder)], trackers=["test-slider", "opencv-mil"],
                      params=["speed", "n_particles"])


@pytest.mark.parametrize("knob, bad, words", [
    ("n_particles", -5, "n_particles"), ("n_particles", "abc", "n_particles"),
    ("n_particles", 1.5, "whole number"), ("n_particles", None, "n_particles = None"),
    ("speed", math.nan, "not finite"), ("speed", 9.0, "maximum"),
    ("mode", "c", "not one of"), ("window", (0.8,), "needs 2"),
    ("n_particles", True, "True/False"),
])
def test_bad_value_raises_and_keeps_the_run(pg, knob, bad, words):
    before_values, before_run, runs = dict(pg.values), pg.run_data, pg.runs
    with pytest.raises((ValueError, TypeError), match=words):
        pg.set(**{knob: bad})
    assert pg.values == before_values and pg.run_data is before_run and pg.runs == runs


def test_direct_trait_assignment_is_refused(pg):
    before = dict(pg.values)
    with pytest.raises(ValueError, match="n_particles"):
        pg.values = {**before, "n_particles": -5}
    with pytest.raises(ValueError, match="did you mean 'speed'"):
        pg.values = {"sped": 1.0}
    assert pg.values == before


def test_front_end_path_says_why_and_keeps_values(pg):
    before, runs = dict(pg.values), pg.runs
    pg.set_state({"values": {**before, "n_particles": "abc"}})
    assert "n_particles" in pg.error and pg.values == before and pg.runs == runs


def test_unknown_names_get_a_near_miss(registered, tiny_folder, pg):  # noqa: F811
    with pytest.raises(ValueError, match="did you mean 'n_particles'"):
        Playground(clips=[str(tiny_folder)], trackers=["test-slider"], params=["n_particle"])
    with pytest.raises(ValueError, match="'bogus'"):
        Playground(clips=[str(tiny_folder)], trackers=["test-slider"], values={"bogus": 1})
    with pytest.raises(ValueError, match="speed"):
        Playground(clips=[str(tiny_folder)], trackers=["test-slider"], values={"speed": -1})
    with pytest.raises(ValueError, match="did you mean 'test-slider'"):
        pg.tracker = "test-slidr"
    with pytest.raises(ValueError, match="clip 'tiy'"):
        pg.clip = "tiy"
    with pytest.raises(ValueError, match="did you mean 'speed'"):
        pg.set(sped=1.0)
    assert pg.tracker == "test-slider"


def test_any_knob_without_declaring_it(registered, tiny_folder):  # noqa: F811
    pg = Playground(clips=[str(tiny_folder)], trackers=["test-slider"])
    r = pg.set(n_particles=30, window=(0.7, 1.4))
    assert r.params["n_particles"] == 30 and tuple(r.params["window"]) == (0.7, 1.4)
    assert {k["name"] for k in pg.config["knobs"]["test-slider"]} == {"n_particles", "window"}


def test_a_real_tracker_with_an_unknown_resampler():
    pg = Playground(clips=["red-cube"], trackers=["color-pf"], n_frames=4)
    assert pg.set(n_particles=40).params["n_particles"] == 40
    before, runs = dict(pg.values), pg.runs
    with pytest.raises(ValueError, match="resampler"):
        pg.set(resampler="nope")
    assert pg.values == before and pg.runs == runs


def test_a_combination_the_tracker_refuses_is_raised_and_rolled_back(pg, monkeypatch):
    from trackbook.playground import core

    class Refusing(core.LiveRun):   # a rule between knobs, as trackers have
        def __init__(self, tracker, clip, params, *a, **k):
            if params.get("speed", 0) > 6:
                raise ValueError("speed above 6 needs n_particles >= 50")
            super().__init__(tracker, clip, params, *a, **k)
    monkeypatch.setattr(core, "LiveRun", Refusing)
    before, run, runs = dict(pg.values), pg.run_data, pg.runs
    with pytest.raises(ValueError, match="needs n_particles"):
        pg.set(speed=7.0)
    assert pg.values == before and pg.run_data is run and pg.runs == runs
    assert pg.set(speed=5.0).params["speed"] == 5.0 and pg.runs == runs + 1
