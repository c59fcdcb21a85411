"""The benchmark (atomic, resumable) and the command line."""
import json
import subprocess
import sys

import cv2
import numpy as np
import pytest

from trackbook import cli, clips
from trackbook.evaluation import bench, runs

from .conftest import SEQUENCES, needs_sequences


@pytest.fixture
def tiny_folder(tmp_path):
    """An OTB folder: a textured square sliding over a textured background (12 frames)."""
    rng = np.random.default_rng(3)
    bg = cv2.resize(rng.integers(0, 255, (12, 16, 3), dtype=np.uint8), (160, 120))
    obj = cv2.resize(rng.integers(0, 255, (4, 4, 3), dtype=np.uint8), (30, 30),
                     interpolation=cv2.INTER_NEAREST)
    img = tmp_path / "tiny" / "img"
    img.mkdir(parents=True)
    rows = []
    for i in range(12):
        f = bg.copy()
        x, y = 20 + 4 * i, 40 + i
        f[y:y + 30, x:x + 30] = obj
        cv2.imwrite(str(img / f"{i + 1:04d}.png"), f)
        rows.append(f"{x}\t{y}\t30\t30")
    (tmp_path / "tiny" / "groundtruth_rect.txt").write_text("\n".join(rows))
    return tmp_path / "tiny"


def test_bench_writes_tables_and_resumes(tmp_path, tiny_folder, monkeypatch):
    out = tmp_path / "bench"
    rows = bench.run(["opencv-mil"], [str(tiny_folder)], out, progress=False)
    assert [r["tracker"] for r in rows] == ["opencv-mil"]
    for f in ("results.csv", "results.json", "curves.json", "table.md", "success.png",
              "precision.png"):
        assert (out / f).is_file()
    curves = bench.load_curves(out)["opencv-mil"]["tiny"]
    assert len(curves["success"]) == 21 and len(curves["precision"]) == 51
    assert abs(sum(curves["success"]) / 21 - rows[0]["auc"]) < 1e-12
    assert json.loads((out / "results.json").read_text())[0]["clip"] == "tiny"
    assert "| opencv-mil |" in (out / "table.md").read_text()
    # resume: a second run must not track again
    calls = []

    def tracked_again(*a, **k):
        calls.append(a)
        raise RuntimeError("tracked again")
    monkeypatch.setattr(runs, "evaluate", tracked_again)
    rows2 = bench.run(["opencv-mil"], [str(tiny_folder)], out, progress=False)
    assert calls == [] and rows2 == rows
    # different settings are not confused with the saved run: it tracks again (the tables of
    # the first bench are removed, since an out holding another bench's tables is refused)
    for f in ("plan.json", "results.json"):
        (out / f).unlink()
    with pytest.raises(RuntimeError, match="tracked again"):
        bench.run(["opencv-mil"], [str(tiny_folder)], out, progress=False, max_frames=5)
    assert len(calls) == 1


def test_bench_leaves_the_matplotlib_backend_alone(tmp_path, tiny_folder):
    import matplotlib
    matplotlib.use("svg")                 # stands in for a notebook's inline backend
    try:
        bench.run(["opencv-mil"], [str(tiny_folder)], tmp_path, progress=False)
        assert matplotlib.get_backend() == "svg"   # a notebook keeps its inline figures
    finally:
        matplotlib.use("Agg")


def test_bench_interrupted_loses_nothing_finished(tmp_path, tiny_folder, monkeypatch):
    out = tmp_path / "bench"
    real = runs.evaluate
    second = tmp_path / "tiny2"
    import shutil
    shutil.copytree(tiny_folder, second)

    def flaky(tracker, clip, **kw):
        if clip.name == "tiny2":
            raise KeyboardInterrupt
        return real(tracker, clip, **kw)
    monkeypatch.setattr(runs, "evaluate", flaky)
    with pytest.raises(KeyboardInterrupt):
        bench.run(["opencv-mil"], [str(tiny_folder), str(second)], out, progress=False)
    assert len(list((out / "runs").glob("opencv-mil__tiny__s0__*.json"))) == 1
    assert not list((out / "runs").glob("*.tmp"))
    monkeypatch.setattr(runs, "evaluate", real)
    rows = bench.run(["opencv-mil"], [str(tiny_folder), str(second)], out, progress=False)
    assert {r["clip"] for r in rows} == {"tiny", "tiny2"}


def test_cli_track_writes_video_and_csv(tmp_path, tiny_folder, capsys):
    assert cli.main(["track", "opencv-mil", str(tiny_folder), "--out", str(tmp_path / "o")]) == 0
    csv = (tmp_path / "o" / "opencv-mil_tiny.csv").read_text().splitlines()
    assert csv[0] == "frame,x,y,w,h,ok,ms" and len(csv) == 13
    back = clips.load(tmp_path / "o" / "opencv-mil_tiny.mp4")
    assert len(back) == 12


def test_cli_errors_are_messages_not_tracebacks(capsys):
    assert cli.main(["track", "no-such-tracker", "whatever"]) == 2
    assert "unknown" in capsys.readouterr().err


def test_python_dash_m_runs():
    p = subprocess.run([sys.executable, "-m", "trackbook", "--help"], capture_output=True,
                       text=True, check=True)
    assert "bench" in p.stdout and "track" in p.stdout


@needs_sequences
@pytest.mark.shared
@pytest.mark.slow
def test_bench_on_a_real_sequence(tmp_path):
    name = "Crossing" if "Crossing" in SEQUENCES else next(iter(SEQUENCES))
    rows = bench.run(["opencv-mil"], [str(SEQUENCES[name])], tmp_path, progress=False,
                     max_frames=30)
    assert rows[0]["frames"] == 30 and 0.0 <= rows[0]["auc"] <= 1.0
