"""``trackbook bench --protocol``: TRE, SRE and the reset protocol through the one benchmark.

The bench's numbers are checked against :mod:`trackbook.evaluation.protocols` called directly
on the same clip (its first ``max_frames`` frames), whose functions are tested from their
definitions in tests/test_protocols.py; the bench's promises (one-line errors with exit code
2, resumable runs, no mixing of two benches in one ``--out``) are checked as for OPE.
"""
import dataclasses
import json

import pytest

from trackbook import cli, clips
from trackbook.evaluation import bench, protocol_bench, protocols, runs

N = 30          # frames: TRE needs 21 (each start leaves 20 frames)


def first(name, n=N):
    """The clip's first n frames, made here (not by the bench's helper)."""
    c = clips.load(name)
    return dataclasses.replace(c, frames=c.frames[:n], groundtruth=c.groundtruth[:n],
                               targets={})


def rows_of(out):
    return {(r["tracker"], r["clip"]): r for r in json.loads((out / "results.json").read_text())}


def test_tre_and_sre_rows_are_the_protocols_pooled_scores(tmp_path):
    for proto, direct in (("tre:4", lambda c: protocols.evaluate_tre("kcf", c, n_segments=4)),
                          ("sre", lambda c: protocols.evaluate_sre("kcf", c))):
        out = tmp_path / proto.replace(":", "_")
        got = bench.run(["kcf"], ["red-cube"], out, max_frames=N, protocol=proto,
                        reference=False, progress=False, workers=1)
        want = direct(first("red-cube"))
        row = rows_of(out)[("kcf", "red-cube")]
        assert row["protocol"] == proto and row["runs"] == len(want.results)
        for k in ("auc", "precision20", "tracking_rate"):
            assert row[k] == pytest.approx(want.scores[k], abs=1e-12), (proto, k)
        # the table prints the same number, under a header in words
        table = (out / "table.md").read_text()
        assert f"mean AUC ({proto.split(':')[0].upper()})" in table
        assert f"{want.scores['auc']:.3f}" in table and got.table == table
        # the pooled success curve's mean is the pooled AUC
        curve = bench.load_curves(out)["kcf"]["red-cube"]["success"]
        assert sum(curve) / 21 == pytest.approx(want.scores["auc"], abs=1e-12)
        assert (out / "success.png").is_file() and not (out / "otb").exists()


def test_reset_rows_and_the_pooled_eao_are_the_protocols(tmp_path):
    out = tmp_path / "reset"
    bench.run(["mosse"], ["red-cube", "occluder"], out, max_frames=40, protocol="reset",
              reference=False, progress=False, workers=1)
    got = rows_of(out)
    direct = [protocols.evaluate_reset("mosse", first(c, 40)) for c in ("red-cube", "occluder")]
    for run in direct:
        row = got[("mosse", run.clip)]
        assert row["failures"] == run.n_failures
        assert row["accuracy"] == pytest.approx(run.accuracy, abs=1e-12)
        assert row["eao"] == pytest.approx(protocols.eao([run]), abs=1e-12)
    table = (out / "table.md").read_text()
    pooled = protocols.eao(direct)                       # one curve over both clips' runs
    assert "| expected average overlap |" in table and f"{pooled:.3f}" in table
    mean_acc = sum(r.accuracy for r in direct) / 2
    assert f"{mean_acc:.3f}" in table
    curve = json.loads((out / "curves.json").read_text())["mosse"]["eao_curve"]
    assert curve[1:] == pytest.approx(protocols.eao_curve(direct)[1:].tolist(), abs=1e-12)
    assert (out / "eao.png").is_file() and not (out / "success.png").exists()


def test_the_command_line_runs_a_protocol_and_resumes(tmp_path, capsys, monkeypatch):
    out = tmp_path / "cli"
    args = ["bench", "--trackers", "kcf", "--clips", "red-cube", "--max-frames", "25",
            "--protocol", "reset", "--out", str(out), "--quiet", "--workers", "1"]
    assert cli.main(args) == 0
    printed = capsys.readouterr().out
    assert "expected average overlap" in printed and "eao.png" in printed
    assert json.loads((out / "plan.json").read_text())["protocol"] == "reset"
    assert {r["tracker"] for r in rows_of(out).values()} == {"kcf", "opencv-mil"}

    def tracked_again(*a, **k):
        raise RuntimeError("tracked again")
    monkeypatch.setattr(protocol_bench, "record", tracked_again)
    assert cli.main(args) == 0                               # resumed: nothing runs
    assert "2 read back, 0 run" in capsys.readouterr().out


def test_another_protocol_in_the_same_out_is_refused(tmp_path, capsys):
    out = tmp_path / "mixed"
    common = ["--trackers", "kcf", "--clips", "red-cube", "--max-frames", "25", "--out",
              str(out), "--quiet", "--workers", "1"]
    bench.run(["kcf"], ["red-cube"], out, max_frames=25, progress=False, workers=1)  # OPE
    assert (out / "otb").is_dir()
    assert cli.main(["bench", *common, "--protocol", "sre"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "protocol" in err and "--force" in err
    # --force replaces the one-pass bench: its OTB files and its other plots go
    with pytest.raises(ValueError, match="protocol"):
        bench.run(["kcf"], ["red-cube"], out, max_frames=25, protocol="reset",
                  progress=False, workers=1, reference=False)
    bench.run(["kcf"], ["red-cube"], out, max_frames=25, protocol="reset", force=True,
              progress=False, workers=1, reference=False)
    assert not (out / "otb").exists() and not (out / "success.png").exists()
    assert (out / "eao.png").is_file()


@pytest.mark.parametrize("value", ["tri", "tre:1", "tre:x", "vot", ""])
def test_a_bad_protocol_is_one_line_and_exit_code_2(tmp_path, capsys, value):
    rc = cli.main(["bench", "--trackers", "kcf", "--clips", "red-cube", "--protocol", value,
                   "--out", str(tmp_path / "o"), "--quiet"])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1 and "protocol" in err
    assert not (tmp_path / "o").exists()


def test_tre_on_too_short_a_clip_is_refused_before_any_run(tmp_path, capsys):
    rc = cli.main(["bench", "--trackers", "kcf", "--clips", "red-cube", "--protocol", "tre",
                   "--max-frames", "12", "--out", str(tmp_path / "o"), "--quiet"])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1 and "at least 21" in err


def test_a_one_pass_run_keeps_its_key_and_a_protocol_changes_it():
    ref = bench.resolve_clips(["red-cube"])[0]
    ope = runs.Task("kcf", ref, 0, 5, (), "fp", 5)
    assert "protocol" not in ope.settings                # saved OPE runs stay valid
    keys = {runs.Task("kcf", ref, 0, 5, (), "fp", 5, protocol=p).key
            for p in ("ope", "tre", "tre:5", "sre", "reset")}
    assert len(keys) == 5 and ope.key in keys
    assert protocol_bench.canonical("TRE:20") == "tre"
    assert protocol_bench.parse("tre:7") == ("tre", 7)
