"""Experiments are declarations run by the one benchmark; papers' figures live in one place."""
import json

import pytest

import trackbook
import trackbook.results
from trackbook.evaluation import bench, experiments
from trackbook.papers import PAPERS

from . import _scenarios


#: experiments load their plugin trackers (edge-ray-x): leave the registry as it was
pytestmark = pytest.mark.usefixtures("clean_registry")


def test_every_experiment_names_registered_trackers_and_valid_params():
    for e in experiments.EXPERIMENTS.values():
        for c in e.grid():
            if c.tracker in ("edge-ray-x", bench.REFERENCE):
                continue                      # a plugin's tracker; MIL has no params
            trackbook.trackers.create(c.tracker, seed=0, preset=c.preset, **c.params)


def test_the_grids_keep_their_sizes():
    # the configurations each experiment runs (rows = configs x clips x seeds)
    sizes = {"lee2012_learning": 31, "kim2016_edges": 26, "lee2012_real": 4, "kim2016_real": 4,
             "lee2015_real": 4, "cho2005_real": 4}
    for name, n in sizes.items():
        assert len(experiments.get(name).grid()) == n, name
    assert experiments.get("kim2016_edges").seeds == (0, 1, 2)
    claims = experiments.get("claims").grid()
    # the four papers' trackers, both presets (the correlation filters come after the claims)
    assert len(claims) == 2 * len(trackbook.papers.TRACKERS) == 22
    with pytest.raises(ValueError, match="known"):
        experiments.get("nope")


def test_the_sample_ranking_is_the_benchmark_the_chapter_ran():
    """09_trackers_compared reads ``samples`` instead of running ``bench.run(PAPER_TRACKERS,
    "samples", seed=0)`` (with MIL, the benchmark's default): the same grid, declared."""
    from pathlib import Path

    e = experiments.get("samples")
    grid = e.grid()
    assert sorted(c.tracker for c in grid[:-1]) == sorted(trackbook.papers.TRACKERS)
    assert grid[-1].tracker == bench.REFERENCE
    assert {c.preset for c in grid} == {"book"} and all(not c.params for c in grid)
    assert e.seeds == (0,) and e.clips == ("samples",)
    chapter = Path(__file__).resolve().parents[1] / "book" / "09_trackers_compared.md"
    assert "bench.run(" not in chapter.read_text(encoding="utf-8")
    assert 'results.load("samples")' in chapter.read_text(encoding="utf-8")


def test_preset_is_part_of_the_saved_runs_key():
    ref = bench.resolve_clips(["red-cube"])[0]
    a = bench.Task("covariance", ref, 0, 5, (), "fp", 5)
    b = bench.Task("covariance", ref, 0, 5, (), "fp", 5, preset="paper")
    assert a.preset == "book" and a.key != b.key and a.path("o") != b.path("o")


def test_an_experiment_row_is_what_evaluate_gives(tmp_path, monkeypatch):
    # a one-clip experiment through the benchmark's tasks and workers against trackbook.evaluate
    e = experiments.Experiment("tiny", "test", (
        experiments.Config("cov", "covariance"),
        experiments.Config("cov paper", "covariance", preset="paper"),
        experiments.Config("cov q", "kalman-covariance", {"q": 5.0})),
        clips=("red-cube",), seeds=(0, 1), false_losses=True)
    monkeypatch.setitem(experiments.EXPERIMENTS, "tiny", e)
    doc = experiments.run("tiny", tmp_path / "runs", progress=False)
    assert len(doc["rows"]) == 6
    clip = trackbook.clips.load("red-cube")
    for r in doc["rows"]:
        run = trackbook.evaluate(r["tracker"], clip, seed=r["seed"], preset=r["preset"],
                                 **json.loads(r["params"]))
        want = run.scores
        assert r["auc"] == want["auc"] and r["tracking_rate"] == want["tracking_rate"]
        # the failure contract's count, against the contract tests' own counting
        assert r["false_losses"] == list(_scenarios.false_losses(run, clip))
    path = experiments.write(doc, tmp_path)
    t = trackbook.results.read(path)
    assert [x["auc"] for x in t] == [x["auc"] for x in doc["rows"]]   # full precision
    # a second run reads every saved run back (resumable), giving the same rows
    assert experiments.run("tiny", tmp_path / "runs", progress=False)["rows"] == doc["rows"]


def test_clip_filter_refuses_clips_the_experiment_does_not_have():
    e = experiments.Experiment("tiny2", "test", (experiments.Config("c", "covariance"),),
                               clips=("red-cube",))
    with pytest.raises(ValueError, match="red-cube"):
        experiments.plan(e, clips=["yellow-ball"])


def test_papers_are_keyed_by_paper_with_their_printed_tables():
    assert list(PAPERS) == ["lee2012", "kim2016", "lee2015", "cho2005"]
    for p in PAPERS.values():
        assert set(p["tracking_rate"]) <= set(p["trackers"]) and set(p["ms"]) <= set(p["trackers"])
    # Table 1 of Lee 2015 and the headline rates are the same figures, typed once
    for t, row in PAPERS["lee2015"]["table1"].items():
        assert row["detection_rate"] == PAPERS["lee2015"]["tracking_rate"][t]
        assert row["search_rate"] == PAPERS["lee2015"]["search_rate"][t]


def test_command_line_errors_are_one_line_with_exit_code_2(capsys):
    assert experiments.main(["run", "nope"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "unknown experiment 'nope'" in err and "claims" in err
