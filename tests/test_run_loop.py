"""One run loop: ``trackbook.evaluate`` and the Jupyter playground's live run both step
:class:`trackbook.evaluation.runner.Run`, so a run stepped frame by frame gives evaluate's boxes."""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

import trackbook
from trackbook.evaluation.runner import Run
from trackbook.playground import live

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "trackbook"


def test_a_run_stepped_frame_by_frame_gives_evaluates_boxes():
    run = Run([("color-pf", 3, {"n_particles": 40})], "red-cube", max_frames=9)
    seen = []
    while not run.done:
        seen.append(run.step())
    assert seen == list(range(9))
    ref = trackbook.evaluate("color-pf", "red-cube", seed=3, max_frames=9, n_particles=40)
    got = run.results()[0]
    np.testing.assert_array_equal(got.boxes, ref.boxes)
    np.testing.assert_array_equal(got.ok, ref.ok)
    assert got.scores["auc"] == ref.scores["auc"] and got.params == ref.params


def test_a_run_refuses_an_extra_frame_and_an_early_result():
    run = Run([("mean-shift", 0, {})], "red-cube", max_frames=3)
    run.step()
    with pytest.raises(ValueError, match="1 of 3"):
        run.results()
    run.advance()
    with pytest.raises(ValueError, match="all its 3 frames"):
        run.step()


def test_the_live_run_is_the_same_loop():
    clip = trackbook.clips.load("red-cube")
    lr = live.LiveRun("mean-shift", clip, {"max_iter": 4}, 8)
    lr.advance(until=3)
    assert lr.n_done == 3 and len(lr.states) == 3
    lr.advance()
    assert len(lr.states) == 8
    ref = trackbook.evaluate("mean-shift", "red-cube", max_frames=8, max_iter=4)
    np.testing.assert_array_equal(lr.result().boxes, ref.boxes)


def test_no_module_imports_a_private_name_of_another_module():
    """A name with a leading underscore stays in its module: a second caller gets a public one."""
    bad = []
    for path in [PACKAGE / "playground" / "live.py", PACKAGE / "evaluation" / "runner.py"]:
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                bad += [f"{path.name}: {node.module}.{a.name}" for a in node.names
                        if a.name.startswith("_")]
    assert not bad, bad
