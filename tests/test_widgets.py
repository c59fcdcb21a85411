"""The playground driven as the front-end drives it: a trait changes, the kernel re-runs, and
what it sends to the viewer changes."""
import base64
import dataclasses
import json
import shutil

import numpy as np
import pytest
from playground_export import export, page_bundle, static  # book/_ext (tests/conftest.py)
from playground_export.static import OUT_ENV

from trackbook.params import param
from trackbook.playground import VIEWER_JS
from trackbook.playground.data import MAX_PARTICLES, knob_spec, sample_values
from trackbook.trackers import registry
from trackbook.trackers.base import Tracker
from trackbook.widgets import Playground

from .test_bench_cli import tiny_folder  # noqa: F401  (fixture)


@dataclasses.dataclass(frozen=True)
class _P:
    speed: float = param(4.0, 0.0, 8.0, 0.5, "px per frame")
    n_particles: int = param(20, 5, 100, 5, "particles")
    window: tuple = param((0.8, 1.2), 0.5, 2.0, 0.05, "ratio window")
    mode: str = param("a", doc="a choice", choices=("a", "b"))


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

    def state(self):      # what the viewer draws comes from here (Tracker.state contract)
        return dataclasses.replace(super().state(), particles=self.particles)


@pytest.fixture
def registered():
    registry.register(_Slider)
    yield
    del registry._REGISTRY[_Slider.name]


def _particles(run, i):
    """Frame i's particles as the viewer decodes them (x, y in pixels)."""
    st = run["state"]
    a = np.frombuffer(base64.b64decode(st["particles"]), dtype="<i2").reshape(-1, 3)
    start = sum(st["pcount"][:i])
    return a[start:start + st["pcount"][i], :2] / 2


def test_knobs_come_from_params_metadata():
    f = knob_spec(_Slider, "speed")
    assert (f["kind"], f["lo"], f["hi"], f["default"]) == ("float", 0.0, 8.0, 4.0)
    assert knob_spec(_Slider, "n_particles")["kind"] == "int"
    assert knob_spec(_Slider, "window")["kind"] == "pair"
    assert knob_spec(_Slider, "mode")["choices"] == ["a", "b"]
    assert knob_spec(_Slider, "nope") is None
    s = sample_values(f)
    assert min(s) == 0.0 and max(s) == 8.0 and 4.0 in s and s == sorted(s)
    n = sample_values(knob_spec(_Slider, "n_particles"))
    assert n == [10, 20, 30, 100]            # the book's 10/30/100/300/1000 within 5..100
    w = sample_values(knob_spec(_Slider, "window"))
    assert [0.95, 1.05] in w and [0.5, 2.0] in w and [0.8, 1.2] in w


def test_set_reruns_and_the_state_sent_changes(registered, tiny_folder):  # noqa: F811
    pg = Playground(clips=[str(tiny_folder)], trackers=["test-slider", "opencv-mil"],
                    params=["speed", "n_particles"])
    assert [k["name"] for k in pg.config["knobs"]["test-slider"]] == ["speed", "n_particles"]
    assert len(pg.clip_data["frames"]) == 12 and pg.clip_data["gt"] is not None
    first = dict(pg.run_data)
    r = pg.set(speed=0.0)
    assert r is pg.result and r.params["speed"] == 0.0 and pg.runs == 2
    boxes = np.array(pg.run_data["boxes"])
    np.testing.assert_allclose(boxes[5], boxes[0])              # the box no longer moves
    assert pg.run_data["boxes"] != first["boxes"] and pg.run_data["iou"] != first["iou"]
    assert pg.run_data["scores"].startswith("test-slider on tiny: AUC")
    # the front-end's path: a knob input sends {"values": ...} over the comm
    pg.set_state({"values": {"speed": 0.0, "n_particles": 60}})
    assert pg.result.params["n_particles"] == 60 and pg.runs == 3
    assert pg.run_data["state"]["pcount"][3] == min(60, MAX_PARTICLES)
    p = _particles(pg.run_data, 3)               # quantised to half pixels, near the box corner
    assert np.abs(p - boxes[3][:2]).max() < 6
    with pytest.raises(ValueError, match="unknown parameter .alpha."):
        pg.set(alpha=0.5)


def test_tracker_and_clip_choice(registered, tiny_folder):  # noqa: F811
    pg = Playground(clips=[str(tiny_folder), "red-cube"], trackers=["test-slider", "opencv-mil"],
                    params=["speed"], n_frames=10, values={"speed": 2.0})
    assert pg.values == {"speed": 2.0}
    pg.set_state({"tracker": "opencv-mil"})       # MIL has none of these knobs
    assert pg.values == {} and pg.result.tracker == "opencv-mil"
    assert "state" in pg.run_data and "particles" not in pg.run_data["state"]
    pg.set_state({"clip": "red-cube"})
    assert pg.clip_data["name"] == "red-cube" and len(pg.clip_data["frames"]) == 10
    assert pg.run_data["clip"] == "red-cube"


def test_your_own_video_waits_for_the_dragged_box(registered, tiny_folder, tmp_path):  # noqa: F811
    own = tmp_path / "own"
    shutil.copytree(tiny_folder / "img", own / "img")    # frames, no ground truth
    pg = Playground(clips=[str(own)], trackers=["test-slider"], params=["speed"])
    assert pg.run_data.get("waiting") and pg.result is None and pg.clip_data["gt"] is None
    pg.set_state({"init_box": [20, 40, 30, 30]})          # the student's drag on frame 0
    assert pg.result is not None and pg.run_data["iou"] is None
    assert "no ground truth" in pg.run_data["scores"]
    np.testing.assert_allclose(pg.run_data["boxes"][0], [20, 40, 30, 30])


def _page_data(html):
    return json.loads(html.split('class="tb-data">')[1].split("</script>")[0]
                      .replace("<\\/", "</"))


def _file(store, name):
    """A run file's data, read back from its text (the call of the registration function)."""
    text = (store / "files" / name).read_text(encoding="utf-8")
    head = f'(window.tbPlaygroundRegister||function(){{}})("{name}",'
    assert text.startswith(head) and text.endswith(");\n")
    return json.loads(text[len(head):-3].replace("<\\/", "</"))


def test_widget_module_is_the_file_the_book_ships(registered, tiny_folder, monkeypatch,  # noqa: F811
                                                  tmp_path):
    monkeypatch.setenv(OUT_ENV, str(tmp_path))
    pg = Playground(clips=[str(tiny_folder)], trackers=["test-slider"],
                    params=["speed", "n_particles", "window"], n_frames=8,
                    samples={"speed": [0.0, 8.0]})
    assert pg._esm == VIEWER_JS.read_text(encoding="utf-8")
    assert "application/vnd.jupyter.widget-view+json" in pg._repr_mimebundle_()[0]
    monkeypatch.setattr(static, "WORKERS", 1)
    bundle, _ = page_bundle(pg)         # as a chapter's kernel in the book's build shows it
    html = bundle["text/html"]
    assert html.startswith('<div class="tb-playground"') and "<noscript><img" in html
    assert pg._esm.replace("</script", "<\\/script") in html
    data = _page_data(html)
    assert "runs" not in data            # the runs are files, loaded on demand
    keys = set(data["files"])
    tiny = str(tiny_folder)
    # defaults, then each knob's other samples one at a time (speed: the samples given)
    assert f"{tiny}|test-slider|" in keys
    assert {f"{tiny}|test-slider|speed#0", f"{tiny}|test-slider|speed#1"} <= keys
    assert data["config"]["knobs"]["test-slider"][0]["samples"] == [0.0, 8.0, 4.0]
    assert _file(tmp_path, data["files"][f"{tiny}|test-slider|speed#0"])["values"]["speed"] == 0.0
    for k, name in data["files"].items():
        run = _file(tmp_path, name)
        assert len(run["boxes"]) == run["n_total"] == run["n_done"] == 8   # n_frames=8
        # the slider's box moves by `speed` whatever the seed: two seeds, same boxes, so
        # the pair is deterministic and each knob value runs once
        assert run["seeds"]["deterministic"]
        assert run["seeds"]["seeds"] == ([0, 1] if k == f"{tiny}|test-slider|" else [0])
        if "n_particles" not in k:
            assert run["values"]["n_particles"] == 20
    chunks = data["clips"][tiny]["chunks"]
    assert sum(len(_file(tmp_path, c)["frames"]) for c in chunks) == 8


def test_samples_stay_within_the_range():
    """lo 0.01 on a 0.5 grid: the top sample is the maximum 100, not 100.01 (a value the
    params refuse, so the page showed "This setting was refused")."""
    spec = {"name": "q", "kind": "float", "lo": 0.01, "hi": 100.0, "step": 0.5, "default": 1.0}
    s = sample_values(spec)
    assert max(s) == 100.0 and min(s) == 0.01 and 1.0 in s


def test_static_page_has_runs_for_every_knob(registered, tiny_folder, monkeypatch,  # noqa: F811
                                             tmp_path):
    """The HTML book moves EVERY knob of EVERY clip x tracker: each knob keeps its default,
    the paper's value (where printed) and about two others."""
    monkeypatch.setenv(OUT_ENV, str(tmp_path))
    pg = Playground(clips=[str(tiny_folder), "red-cube"], trackers=["test-slider", "mean-shift"],
                    params=["speed", "n_particles", "mode"], n_frames=8)
    data = export.static_payload(pg, workers=1)
    knobs = {k["name"]: k for k in data["config"]["knobs"]["test-slider"]}
    assert knobs["speed"]["samples"] == [2.0, 4.0, 6.0]           # 0..8 by 2, default 4
    assert knobs["n_particles"]["samples"] == [10, 20, 30]
    assert knobs["mode"]["samples"] == ["a", "b"]
    for c in (str(tiny_folder), "red-cube"):
        for t in ("test-slider", "mean-shift"):
            for k in data["config"]["knobs"][t]:
                for i, v in enumerate(k["samples"]):
                    key = f"{c}|{t}|" + ("" if v == k["default"] else f"{k['name']}#{i}")
                    assert key in data["files"], f"{c} {t} {k['name']}={v}: no run file"
                    assert _file(tmp_path, data["files"][key])["values"][k["name"]] == v
    # mean-shift has no knob among these: its run at the defaults, over the first two seeds
    # (the same boxes: it draws nothing at random)
    run = _file(tmp_path, data["files"]["red-cube|mean-shift|"])
    assert run["seeds"]["deterministic"] and run["seeds"]["seeds"] == [0, 1]
    # the live widget keeps the whole range (Jupyter takes any value)
    assert len(pg.config["knobs"]["test-slider"][0]["samples"]) == 5


def test_playground_rejects_unknown_tracker(tiny_folder):  # noqa: F811
    with pytest.raises(ValueError, match="unknown tracker"):
        Playground(clips=[str(tiny_folder)], trackers=["nope"])


@pytest.mark.parametrize("make", ["sir_cycle", "kalman_ball", "mean_shift_climb",
                                  "subspace_drift"])
def test_animations_use_the_viewer(make, monkeypatch, tmp_path):
    from trackbook.playground import animations

    kw = {"kalman_ball": {"n_frames": 8}, "subspace_drift": {"n_frames": 12},
          "sir_cycle": {"frames": [1, 2]}}.get(make, {})
    a = getattr(animations, make)(**kw)
    assert a._esm == VIEWER_JS.read_text(encoding="utf-8")
    d = a.static_data
    run = next(iter(d["runs"].values()))   # kalman_ball offers one run per Q scale
    clip = d["clips"][run["clip"]]
    n = len(run["boxes"])
    assert n >= 2 and len(run["curve"]["values"]) == n and len(run["captions"]) == n
    assert len(clip["index"] or clip["frames"]) == n
    if make == "sir_cycle":     # three steps per frame; resample/predict equal, weigh varies
        assert n == 6 and [c.split(" \u00b7 ")[1].split(":")[0] for c in run["captions"][:3]] \
            == ["resample", "predict", "weigh"]
        ess = run["curve"]["values"]
        assert ess[1] == 1.0 and ess[2] < 1.0
    if make == "mean_shift_climb":   # an accepted mean-shift step never lowers rho (eq. 13)
        rho = run["curve"]["values"]
        assert all(b >= a - 1e-4 for a, b in zip(rho, rho[1:])) and rho[-1] > rho[0]
    monkeypatch.setenv(OUT_ENV, str(tmp_path))
    assert page_bundle(a)[0]["text/html"].startswith('<div class="tb-playground"')


def test_the_viewer_takes_its_colours_from_python(monkeypatch, tmp_path):
    import re

    monkeypatch.setenv(OUT_ENV, str(tmp_path))
    from trackbook import style

    js = VIEWER_JS.read_text(encoding="utf-8")
    assert not re.search(r"#[0-9a-fA-F]{6}\b", js)      # no second list of colours in the JS
    pg = Playground(clips=["red-cube"], trackers=["mean-shift"], params=[], n_frames=3)
    assert pg.config["colors"] == style.VIEWER
    assert export.static_payload(pg, workers=1)["config"]["colors"] == style.VIEWER
    assert style.bgr(style.GT_COLOR) == (0x73, 0x9E, 0x00)   # "#009E73" read back to front


def test_every_knob_sample_of_every_tracker_is_a_value_the_tracker_takes():
    """The HTML book precomputes these samples: each must pass the params parser (1e-8 once
    became 0.0 by rounding to six decimals, below lambda's minimum), and a range over decades
    is sampled in log."""
    import dataclasses

    from trackbook import trackers

    for name in trackers.available(reference=False):
        cls = trackers.get(name)
        for f in dataclasses.fields(cls.Params):
            spec = knob_spec(cls, f.name)
            if spec is None:
                continue          # not a knob: nothing is precomputed for it
            for v in sample_values(spec):
                trackers.create(name, **{f.name: v})     # raises on a refused value
    lam = sample_values(knob_spec(trackers.get("kcf"), "lam"))
    assert min(lam) == 1e-8 and 1e-4 in lam and max(lam) == 1.0
    assert sorted(lam)[1] < 1e-4           # log spacing: a value between 1e-8 and the default
