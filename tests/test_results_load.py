"""Committed results load by name from anywhere, through one loader, ``trackbook.results.load``."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from trackbook import results

ROOT = Path(__file__).resolve().parents[1]
#: The results the chapters and lab notes read (and ``failure_samples``, the failure
#: contract's tests).
NAMES = ["claims", "cho2005_real", "failure_samples", "kim2016_edges", "kim2016_real",
         "lee2012_learning", "lee2012_learning_samples", "lee2012_real", "lee2015_real",
         "protocols", "real", "samples"]


@pytest.mark.parametrize("cwd", [ROOT / "book", ROOT, ROOT / "tests"])
def test_found_from_any_working_folder(cwd, monkeypatch, tmp_path):
    for where in (cwd, tmp_path):          # a student's session: any folder at all
        monkeypatch.chdir(where)
        t = results.load("real")
        assert len(t) > 0 and {"tracker", "clip", "auc", "seed", "preset"} <= set(t[0])


def test_every_result_the_book_reads_is_committed_with_one_format():
    assert results.available() == sorted(NAMES)
    for name in NAMES:
        t = results.load(name)
        assert t.meta["name"] == name and "experiments run" in t.meta["command"]
        for r in t:
            assert {"label", "tracker", "preset", "params", "clip", "seed", "auc"} <= set(r)
            assert isinstance(json.loads(r["params"]), dict) and isinstance(r["seed"], int)
            if r.get("protocol") == "reset":     # VOT's scores, no OTB AUC
                assert 0.0 <= r["accuracy"] <= 1.0 and 0.0 <= r["eao"] <= 1.0
            else:
                assert 0.0 <= r["auc"] <= 1.0


def test_missing_or_bad_names_say_what_exists_and_how_to_make_it():
    with pytest.raises(FileNotFoundError, match="experiments run no-such"):
        results.load("no-such")
    with pytest.raises(ValueError, match="claims"):
        results.load("../claims")


def test_table_helpers_against_a_hand_made_table(tmp_path):
    rows = [{"label": "a", "clip": "x", "auc": 0.2}, {"label": "a", "clip": "y", "auc": 0.4},
            {"label": "b", "clip": "x", "auc": None}]
    f = tmp_path / "t.json"
    f.write_text(json.dumps({"name": "t", "rows": rows}))
    t = results.read(f)
    assert len(t) == 3 and t.meta == {"name": "t"}
    assert math.isnan(t[2]["auc"])                       # missing numbers read as nan
    rows.append({"label": "c", "clip": "x", "auc": 0.5, "learning": 1.0})
    f.write_text(json.dumps({"name": "t", "rows": rows}))
    t2 = results.read(f)                                 # a column only some rows have
    assert all(set(r) == {"label", "clip", "auc", "learning"} for r in t2)
    assert math.isnan(t2[0]["learning"]) and t2[3]["learning"] == 1.0
    assert len(t.where(label="a")) == 2 and len(t.where(clip=("x", "z"))) == 2
    np.testing.assert_array_equal(t.where(label="a").column("auc"), [0.2, 0.4])
    assert t.unique("label") == ["a", "b"]
    m = t.where(label="a").mean("auc")
    assert m == {"a": pytest.approx(0.3)}
    assert t.mean("auc", by=("label", "clip"))[("a", "y")] == pytest.approx(0.4)
