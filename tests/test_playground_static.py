"""The HTML book's playgrounds: which knob values are precomputed, the spread over seeds, the
run files the page loads on demand (``book/_ext/playground_export``)."""
import dataclasses
import json
import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from playground_export import export as E  # from book/_ext (tests/conftest.py)
from playground_export import static as S

from trackbook import params as P
from trackbook import trackers
from trackbook.playground import data as D

#: every playground of the book: tracker -> the knobs its chapter declares
BOOK_KNOBS = {
    "color-pf": ["n_particles", "sigma_color", "resampler", "init"],
    "color-hog-pf": ["n_particles", "alpha", "sigma_hog", "sigma_color"],
    "color-hog-ipca": ["n_particles", "alpha", "forgetting", "K", "T", "anchor"],
    "edge-ray-pf": ["ratio_low", "ratio_high", "n_particles", "canny_low", "canny_high",
                    "sigma", "velocity_gain"],
    "hsi-color-pf": ["n_particles", "sigma", "velocity_gain"],
    "hog-pf": ["n_particles", "sigma", "velocity_gain"],
    "covariance": ["features", "stride", "threshold", "search_radius"],
    "kalman-covariance-manoeuvre": ["features", "stride", "threshold", "search_radius", "q", "r",
                                    "gate", "manoeuvre_gate"],
    "condensation": ["n_particles", "noise_position"],
    "mean-shift": ["max_iter"],
    "condensation-mean-shift": ["n_particles", "max_iter", "noise_position", "use_motion"],
    "kcf": ["eta", "lam", "kernel_sigma", "padding"],
    "mosse": ["eta", "lam"],
}


def _printed(cls, name):
    """The printed value of a field, read from the field's own record (an independent path
    to the one paper_sample takes through the preset)."""
    f = {f.name: f for f in dataclasses.fields(cls.Params)}[name]
    paper = f.metadata.get("paper")
    return None if paper is P.NOT_PRINTED or paper is None else paper


@pytest.mark.parametrize("tracker", sorted(BOOK_KNOBS))
def test_samples_hold_the_default_and_the_paper_value(tracker):
    cls = trackers.get(tracker)
    preset = trackers.create(tracker, preset="paper").params
    for name in BOOK_KNOBS[tracker]:
        spec = D.knob_spec(cls, name)
        paper = E.paper_sample(cls, name)
        s = E.static_samples(spec, paper)
        assert spec["default"] in s, f"{tracker}.{name}: default {spec['default']} not in {s}"
        printed = _printed(cls, name)
        if printed is not None:       # what the paper prints is what its preset runs
            assert paper == getattr(preset, name) == printed
            assert paper in s, f"{tracker}.{name}: paper's {paper} not in {s}"
        assert len(s) <= max(4, len(spec.get("choices") or [])), s     # few: build time
        assert len(s) == len({json.dumps(v) for v in s})                 # no value twice
        for v in s:                   # every stop is a value the tracker takes
            trackers.create(tracker, **{name: tuple(v) if isinstance(v, list) else v})


def test_the_chapters_central_values_are_stops():
    """By hand: sigma_color, the book 0.2 against Lee et al.'s 0.4; the manoeuvre gate's
    'off' (0: kalman-covariance, the paper's method) that the case study of Lee (2015) asks the
    reader to set on the book's variant."""
    pf = trackers.get("color-pf")
    assert {0.2, 0.4} <= set(E.static_samples(D.knob_spec(pf, "sigma_color"),
                                              E.paper_sample(pf, "sigma_color")))
    kc = trackers.get("kalman-covariance-manoeuvre")
    assert E.paper_sample(kc, "manoeuvre_gate") == 0.0
    assert 0.0 in E.static_samples(D.knob_spec(kc, "manoeuvre_gate"), 0.0)
    # a particle count the paper does not print (a reading) is not "the paper's value"
    assert E.paper_sample(trackers.get("hsi-color-pf"), "n_particles") is None


def test_static_samples_by_hand():
    spec = {"name": "q", "kind": "float", "lo": 0.0, "hi": 8.0, "step": 0.5, "default": 4.0}
    assert E.static_samples(spec) == [2.0, 4.0, 6.0]          # nearest below and above
    assert E.static_samples(spec, paper=8.0) == [2.0, 4.0, 8.0]   # paper + one other
    assert E.static_samples(spec, paper=4.0) == [2.0, 4.0, 6.0]
    edge = {**spec, "default": 0.0}
    assert E.static_samples(edge) == [0.0, 2.0, 4.0]          # nothing below: two above
    choice = {"name": "m", "kind": "choice", "choices": ["a", "b", "c"], "default": "b"}
    assert E.static_samples(choice, "c") == ["a", "b", "c"]


def _slow_band(ious):
    n = max(len(i) for i in ious)
    lo, hi = [], []
    for k in range(n):
        vals = [i[k] for i in ious if k < len(i) and i[k] is not None]
        lo.append(min(vals) if vals else None)
        hi.append(max(vals) if vals else None)
    return lo, hi


@settings(max_examples=60, deadline=None)
@given(st.lists(st.lists(st.one_of(st.none(), st.floats(0, 1)), min_size=1, max_size=30),
                min_size=1, max_size=5),
       st.booleans())
def test_seed_band_is_min_and_max_over_seeds(ious, det):
    aucs = [float(np.mean([v for v in i if v is not None] or [0])) for i in ious]
    s = S.seed_summary(list(range(len(ious))), ious, aucs, det)
    lo, hi = _slow_band(ious)
    r = lambda v: None if v is None else round(v, 3)   # noqa: E731  the payload's rounding
    assert s["iou_lo"] == [r(v) for v in lo] and s["iou_hi"] == [r(v) for v in hi]
    assert s["seeds"] == list(range(len(ious))) and s["deterministic"] is det
    assert s["auc"] == [round(a, 4) for a in aucs]


def test_seed_summary_refuses_mismatched_lists():
    with pytest.raises(ValueError, match="one IoU list and one AUC per seed"):
        S.seed_summary([0, 1], [[0.5]], [0.5, 0.4], False)


def test_spread_line():
    sd = {"seeds": [0, 1, 2], "auc": [0.47, 0.52, 0.58], "deterministic": False}
    mean = (0.47 + 0.52 + 0.58) / 3
    assert S.spread_text(sd) == f"AUC {mean:.2f} (0.47\u20130.58 over 3 seeds)"
    assert S.spread_text({"seeds": [0, 1], "auc": [0.61, 0.61], "deterministic": True}) \
        == "AUC 0.61 (same boxes for every seed)"


def _read(path):
    text = path.read_text(encoding="utf-8")
    m = re.fullmatch(r'\(window\.tbPlaygroundRegister\|\|function\(\)\{\}\)\("([^"]+)",(.*)\);\n',
                     text, re.S)
    assert m, text[:120]
    return m.group(1), json.loads(m.group(2).replace("<\\/", "</"))


def test_run_files_are_named_by_content_and_capped(tmp_path):
    a = {"boxes": [[1, 2, 3, 4]], "scores": "</script> in a string"}
    name = S.write_script(a, folder=tmp_path)
    assert re.fullmatch(re.escape(S.PREFIX) + r"[0-9a-f]{20}\.js", name)
    assert _read(tmp_path / name) == (name, a)                # the file says its own name
    assert "</script" not in (tmp_path / name).read_text()    # safe inside a page too
    assert S.write_script(dict(a), folder=tmp_path) == name   # same data, same file
    assert S.write_script({**a, "boxes": [[1, 2, 3, 5]]}, folder=tmp_path) != name
    big = {"state": {"particles": "x" * 400}, "boxes": [[0, 0, 1, 1]] * 3}
    with pytest.raises(ValueError, match="over the 300-byte cap"):
        S.write_script(big, cap=300, folder=tmp_path)
    thin = S.write_run(big, cap=300, folder=tmp_path)         # the state is left out
    assert _read(tmp_path / thin)[1] == {**big, "state": {}}
    assert (tmp_path / thin).stat().st_size <= 300


def test_frame_files_hold_every_frame_in_order(tmp_path):
    from trackbook import clips

    clip = clips.load("red-cube")
    names = S.write_frames(clip, 23, per=10, folder=tmp_path)
    assert len(names) == 3
    got = [_read(tmp_path / n)[1] for n in names]
    assert [g["start"] for g in got] == [0, 10, 20]
    assert [len(g["frames"]) for g in got] == [10, 10, 3]
    assert got[2]["frames"][0] == D.jpeg(clip.frames[20])     # frame 20, at full quality


def test_a_deterministic_pair_runs_once_per_value(tmp_path, monkeypatch):
    """mean-shift gives the same boxes for two seeds (no random draw), condensation does not:
    the first's knob runs have one seed, the second's three."""
    from trackbook import clips

    monkeypatch.setenv(S.OUT_ENV, str(tmp_path))
    c = {"red-cube": clips.load("red-cube")}
    knobs = {"mean-shift": [], "condensation": []}
    for t in knobs:
        spec = D.knob_spec(trackers.get(t), "max_iter" if t == "mean-shift" else "n_particles")
        knobs[t] = [{**spec, "samples": [spec["default"], 3 if t == "mean-shift" else 30]}]
    defaults = {t: {k["name"]: k["default"] for k in ks} for t, ks in knobs.items()}
    out = S.book_runs(c, list(knobs), knobs, defaults, {"red-cube": 12}, {"red-cube": None},
                      seed=0, workers=1)
    assert out["deterministic"] == ["red-cube|mean-shift"]
    runs = {k: _read(tmp_path / "files" / v)[1] for k, v in out["runs"].items()}
    assert runs["red-cube|mean-shift|max_iter#1"]["seeds"]["seeds"] == [0]
    assert runs["red-cube|condensation|"]["seeds"]["seeds"] == [0, 1, 2]
    band = runs["red-cube|condensation|n_particles#1"]["seeds"]
    assert band["seeds"] == [0, 1, 2] and not band["deterministic"]
    assert all(lo <= hi for lo, hi in zip(band["iou_lo"], band["iou_hi"]) if lo is not None)
    for r in runs.values():
        assert r["n_done"] == r["n_total"] == len(r["boxes"]) == 12
    # a rebuild reads every run back from the disk instead of tracking again
    monkeypatch.setattr(S, "evaluate_many", lambda *a, **k: pytest.fail("ran again"))
    again = S.book_runs(c, list(knobs), knobs, defaults, {"red-cube": 12}, {"red-cube": None},
                        seed=0, workers=1)
    assert again == out
    assert not math.isnan(runs["red-cube|condensation|"]["seeds"]["auc"][0])


def test_background_precompute_writes_the_planned_files(tmp_path, monkeypatch):
    """During the book build a page names its run files before they exist; a background
    process writes them under those names, and the same runs computed in this process give
    the same data."""
    from trackbook import clips

    monkeypatch.setenv(S.OUT_ENV, str(tmp_path / "bg"))
    monkeypatch.setenv(S.BACKGROUND_ENV, "1")
    c = {"red-cube": clips.load("red-cube")}
    spec = D.knob_spec(trackers.get("condensation"), "n_particles")
    knobs = {"condensation": [{**spec, "samples": [spec["default"], 30]}]}
    defaults = {"condensation": {"n_particles": spec["default"]}}
    args = (c, ["condensation"], knobs, defaults, {"red-cube": 10}, {"red-cube": None})
    names = S.book_files(*args, seed=0, workers=1)
    assert set(names) == {"red-cube|condensation|", "red-cube|condensation|n_particles#1"}
    assert names == S.plan_names(*args, seed=0)
    S.wait_background(tmp_path / "bg", poll=0.1)
    assert not list((tmp_path / "bg" / "pending").glob("*.pkl"))
    monkeypatch.setenv(S.BACKGROUND_ENV, "0")
    monkeypatch.setenv(S.OUT_ENV, str(tmp_path / "here"))
    here = S.book_files(*args, seed=0, workers=1)
    for key, name in names.items():
        got = _read(tmp_path / "bg" / "files" / name)[1]
        want = _read(tmp_path / "here" / "files" / here[key])[1]
        for k in ("boxes", "iou", "seeds", "values", "n_total"):
            assert got[k] == want[k], (key, k)


def test_a_background_precompute_that_dies_fails_the_wait(tmp_path):
    pending = tmp_path / "pending"
    pending.mkdir()
    (pending / "x.pkl").write_bytes(b"not a plan")
    (pending / "x.log").write_text("Traceback: the run crashed")
    (pending / "x.pid").write_text("999999999")          # no such process
    with pytest.raises(RuntimeError, match="(?s)stopped without finishing.*the run crashed"):
        S.wait_background(tmp_path, poll=0.01)
