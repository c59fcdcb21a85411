"""Students' trackers in the bench (--import, local workers and Dask), saved runs keyed by
content and code, --preset paper, and results other toolkits read (OTB layout)."""
import json
import os
import subprocess
import sys

import cv2
import numpy as np
import pytest

from .conftest import write_sequence
from trackbook import params as _params
from trackbook import trackers
from trackbook.evaluation import bench, runs

#: the benches load user trackers into this process too: leave the registry as it was
pytestmark = pytest.mark.usefixtures("clean_registry")

TRACKER_FILE = '''
import numpy as np
from trackbook import trackers
from trackbook.trackers import Tracker

SHIFT = {shift}


@trackers.register
class Still(Tracker):
    """Stays where it started (plus SHIFT pixels): a tracker a student might write first."""

    name = "{name}"

    def _init(self, frame, box):
        self.box0 = np.asarray(box, dtype=float)

    def _update(self, frame):
        return True, self.box0 + np.array([SHIFT, 0.0, 0.0, 0.0])
'''


def _tracker_file(folder, name, shift=0):
    path = folder / f"{name.replace('-', '_')}.py"
    path.write_text(TRACKER_FILE.format(name=name, shift=shift))
    return path


def _folder(root, name, n=8, ext="png"):
    return write_sequence(root, name, n, seed=5, size=(120, 90), side=20, x0=10, y0=30, dx=4,
                          ext=ext)


def _env():
    return {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}


def test_a_tracker_in_a_file_runs_in_two_local_workers(tmp_path, capsys):
    from trackbook import cli

    f = _tracker_file(tmp_path, "user-still-workers")
    a, b = _folder(tmp_path / "d", "a"), _folder(tmp_path / "d", "b")
    code = cli.main(["bench", "--import", str(f), "--trackers", "user-still-workers",
                     "--clips", f"{a},{b}", "--workers", "2", "--quiet",
                     "--out", str(tmp_path / "o")])
    assert code == 0, capsys.readouterr().err
    rows = bench.load(tmp_path / "o")
    assert {(r["tracker"], r["clip"]) for r in rows} >= {("user-still-workers", "a"),
                                                         ("user-still-workers", "b")}
    mine = [r for r in rows if r["tracker"] == "user-still-workers"]
    assert all(0.0 <= r["auc"] < 1.0 for r in mine)     # it stays put while the target moves


def test_a_tracker_in_a_file_runs_on_a_dask_local_cluster(tmp_path):
    distributed = pytest.importorskip("distributed")
    f = _tracker_file(tmp_path, "user-still-dask")
    a = _folder(tmp_path / "d", "a")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster:
        # the worker is a fresh process: it knows the tracker only by loading the file
        with distributed.Client(cluster) as client:
            assert "user-still-dask" not in client.run(
                lambda: trackers.available(reference=False))[next(iter(client.scheduler_info()["workers"]))]
        rows = bench.run(["user-still-dask"], [str(a)], tmp_path / "o", progress=False,
                         reference=False, imports=[str(f)],
                         scheduler=cluster.scheduler_address)
    assert [r["tracker"] for r in rows] == ["user-still-dask"]
    assert len(list((tmp_path / "o/runs").glob("user-still-dask__*.json"))) == 1


def test_an_edited_tracker_reruns_and_an_unchanged_one_is_reused(tmp_path):
    f = _tracker_file(tmp_path, "user-still-edit", shift=0)
    a = _folder(tmp_path / "d", "a")
    out = tmp_path / "o"
    cmd = [sys.executable, "-m", "trackbook", "bench", "--import", str(f), "--trackers",
           "user-still-edit", "--clips", str(a), "--workers", "1", "--quiet", "--out", str(out)]

    def bench_once():
        subprocess.run(cmd, check=True, capture_output=True, env=_env())
        row = next(r for r in bench.load(out) if r["tracker"] == "user-still-edit")
        files = sorted(out.glob("runs/user-still-edit__*.json"))
        return row, files, [p.stat().st_mtime_ns for p in files]

    row0, files0, mtimes0 = bench_once()
    row1, files1, mtimes1 = bench_once()              # unchanged: read back, not re-run
    assert files1 == files0 and mtimes1 == mtimes0 and row1 == row0
    _tracker_file(tmp_path, "user-still-edit", shift=6)   # the student edits the tracker
    row2, files2, _ = bench_once()
    assert len(files2) == 2                           # a new run under a new key
    assert row2["mean_center_error"] != row0["mean_center_error"]


def test_code_fingerprint_covers_the_tracker_and_what_it_builds_on():
    from trackbook.evaluation import runs

    names = [m.__name__ for m in runs.code_modules(trackers.get("color-hog-ipca"))]
    assert "trackbook.trackers.base" in names                 # base class
    assert "trackbook.trackers.particle_filter" in names      # the particle filter frame
    assert any(n.startswith("trackbook.features") for n in names)   # its features
    assert "trackbook.cli" not in names and "trackbook.viz.core" not in names
    assert runs.code_fingerprint("covariance") != runs.code_fingerprint("mean-shift")


def test_a_same_size_rewrite_of_a_bmp_frame_reruns(tmp_path):
    a = _folder(tmp_path / "d", "a", ext="bmp")
    out = tmp_path / "o"
    bench.run(["mean-shift"], [str(a)], out, progress=False, reference=False)
    frame = a / "img" / "0004.bmp"
    size = frame.stat().st_size
    img = cv2.imread(str(frame))
    cv2.imwrite(str(frame), 255 - img)                    # other pixels, same size
    assert frame.stat().st_size == size
    bench.run(["mean-shift"], [str(a)], out, progress=False, reference=False)
    assert len(list(out.glob("runs/mean-shift__*.json"))) == 2


def test_preset_paper_runs_the_printed_values_under_its_own_key(tmp_path):
    name = next(n for n in trackers.available(reference=False)
                if _params.paper_values(trackers.get(n).Params))
    paper = _params.paper_values(trackers.get(name).Params)
    book = bench.plan([name], "red-cube", max_frames=3, reference=False)
    pap = bench.plan([name], "red-cube", max_frames=3, reference=False, preset="paper")
    assert book[0].key != pap[0].key and pap[0].preset == "paper"
    bench.run([name], "red-cube", tmp_path, max_frames=3, progress=False, reference=False,
              preset="paper")
    rec = json.loads(next(tmp_path.glob("runs/*.json")).read_text())
    for k, v in paper.items():
        got = rec["params"][k]
        assert (list(got) if isinstance(got, (list, tuple)) else got) == \
            (list(v) if isinstance(v, (list, tuple)) else v), k
    with pytest.raises(ValueError, match="preset"):
        bench.plan([name], "red-cube", preset="papr")


def _iou(a, b):
    """Intersection over union of two (x, y, w, h) boxes, written out by hand."""
    ax2, ay2, bx2, by2 = a[0] + a[2], a[1] + a[3], b[0] + b[2], b[1] + b[3]
    iw = max(0.0, min(ax2, bx2) - max(a[0], b[0]))
    ih = max(0.0, min(ay2, by2) - max(a[1], b[1]))
    inter = iw * ih
    return inter / (a[2] * a[3] + b[2] * b[3] - inter)


def test_otb_layout_files_score_what_the_bench_scored(tmp_path):
    a = _folder(tmp_path / "d", "a", n=10)
    rows = bench.run(["mean-shift"], [str(a)], tmp_path / "o", progress=False)
    gt = np.loadtxt(a / "groundtruth_rect.txt", delimiter=",")
    for r in rows:
        boxes = np.loadtxt(tmp_path / "o/otb" / r["tracker"] / "a.txt", delimiter=",")
        times = np.loadtxt(tmp_path / "o/otb" / r["tracker"] / "times" / "a_time.txt")
        assert boxes.shape == (10, 4) and times.shape == (10,) and np.all(times >= 0)
        assert np.allclose(boxes[0], gt[0])                    # frame 1: the initial box
        ious = [_iou(p, g) for p, g in zip(boxes[1:], gt[1:])]  # OTB scores frames 2..N
        auc = np.mean([np.mean([v > t for v in ious]) for t in np.linspace(0, 1, 21)])
        assert abs(auc - r["auc"]) < 1e-12, r["tracker"]


def test_a_worker_that_dies_is_one_line_not_a_hang(tmp_path, capsys):
    from trackbook import cli

    f = tmp_path / "crasher.py"
    f.write_text(TRACKER_FILE.format(name="user-crasher", shift=0).replace(
        "    def _update(self, frame):\n",
        "    def _update(self, frame):\n        import os\n        os._exit(3)\n"))
    a, b = _folder(tmp_path / "d", "a"), _folder(tmp_path / "d", "b")
    code = cli.main(["bench", "--import", str(f), "--trackers", "user-crasher", "--clips",
                     f"{a},{b}", "--workers", "2", "--quiet", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "exit code 3" in err[0], err


def test_code_text_ignores_docstrings_and_comments_not_code(tmp_path):
    base = 'def f(x):\n    """Twice x."""\n    return 2 * x  # double\n'
    reworded = 'def f(x):\n    """Two times x, reworded."""\n\n    return 2 * x  # doubled\n'
    changed = 'def f(x):\n    """Twice x."""\n    return 3 * x  # double\n'
    paths = []
    for i, text in enumerate((base, reworded, changed)):
        p = tmp_path / f"m{i}.py"
        p.write_text(text)
        paths.append(p)
    a, b, c = (runs.code_text(p) for p in paths)
    assert a == b            # a docstring, a comment and a blank line: the same computation
    assert a != c            # 2 * x -> 3 * x: another computation, the runs are stale
    bad = tmp_path / "bad.py"
    bad.write_text("def (:\n")
    assert runs.code_text(bad) == b"def (:\n"      # does not parse: its bytes
