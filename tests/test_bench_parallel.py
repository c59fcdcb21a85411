"""Bench at scale: workers and Dask give the clean single-process scores; keys never stale."""
import json
import os
import shutil
import stat

import cv2
import pytest

from .conftest import write_sequence
from trackbook import cli
from trackbook.evaluation import bench, parallel

TRACKERS = ["mean-shift", "covariance"]


def _folder(root, name, n=10, shift=0):
    return write_sequence(root, name, n, seed=7 + shift, x0=20 + shift)


@pytest.fixture
def two_clips(tmp_path):
    return [str(_folder(tmp_path / "data", "a")), str(_folder(tmp_path / "data", "b", shift=5))]


def _scores(rows):
    return sorted((r["tracker"], r["clip"], r.get("seed"), r["auc"], r["precision20"])
                  for r in rows)


def test_two_workers_give_the_single_process_scores_mil_included(tmp_path, two_clips):
    one = bench.run(TRACKERS, two_clips, tmp_path / "w1", progress=False, workers=1)
    two = bench.run(TRACKERS, two_clips, tmp_path / "w2", progress=False, workers=2)
    assert any(r["tracker"] == "opencv-mil" for r in one)
    assert _scores(one) == _scores(two)
    b1 = {p.name: json.loads(p.read_text())["boxes"] for p in (tmp_path / "w1/runs").iterdir()}
    b2 = {p.name: json.loads(p.read_text())["boxes"] for p in (tmp_path / "w2/runs").iterdir()}
    assert b1 == b2


def _drop_tables(out):
    """Remove a bench's tables, keeping its saved runs: an out holding another bench's tables
    is refused (tests/test_cli_hostile.py), while saved runs are reused by their key."""
    for f in ("plan.json", "results.json"):
        (out / f).unlink()


def test_resumed_bench_equals_a_clean_one(tmp_path, two_clips):
    clean = bench.run(TRACKERS, two_clips, tmp_path / "clean", progress=False)
    out = tmp_path / "resumed"
    bench.run(TRACKERS, two_clips[1:], out, progress=False)    # MIL ran on b first here
    for p in (out / "runs").glob("mean-shift*"):
        p.unlink()                                              # as if interrupted
    _drop_tables(out)
    resumed = bench.run(TRACKERS, two_clips, out, progress=False)
    assert _scores(clean) == _scores(resumed)


def test_dask_local_cluster_gives_the_local_scores(tmp_path, two_clips):
    distributed = pytest.importorskip("distributed")
    local = bench.run(["mean-shift"], two_clips, tmp_path / "local", progress=False,
                      reference=False, workers=1)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=":0") as cluster:
        rows = bench.run(["mean-shift"], two_clips, tmp_path / "dask", progress=False,
                         reference=False, scheduler=cluster.scheduler_address)
    assert _scores(rows) == _scores(local)
    assert len(list((tmp_path / "dask/runs").glob("*.json"))) == 2


def test_seeds_sweep_and_mil_once(tmp_path, two_clips):
    rows = bench.run(["mean-shift"], two_clips[:1], tmp_path, progress=False, seeds="0-2")
    assert sorted(r["seed"] for r in rows if r["tracker"] == "mean-shift") == [0, 1, 2]
    assert sum(r["tracker"] == "opencv-mil" for r in rows) == 1
    assert bench.parse_seeds("0-2,5") == [0, 1, 2, 5]
    for bad in ("3-1", "x", "-1"):
        with pytest.raises(ValueError, match="seed"):
            bench.parse_seeds(bad)


def test_duplicate_names_and_edited_ground_truth_never_share_a_result(tmp_path):
    a = _folder(tmp_path / "x", "clip")
    b = _folder(tmp_path / "y", "clip", shift=9)
    rows = bench.run(["mean-shift"], [str(a), str(b)], tmp_path / "o", progress=False,
                     reference=False)
    assert {r["clip"] for r in rows} == {"x/clip", "y/clip"}
    assert rows[0]["auc"] != rows[1]["auc"] or rows[0]["mean_center_error"] != \
        rows[1]["mean_center_error"]
    before = rows[0]
    gt = a / "groundtruth_rect.txt"
    lines = gt.read_text().splitlines()
    lines[5] = "0,0,10,10"
    gt.write_text("\n".join(lines) + "\n")
    _drop_tables(tmp_path / "o")
    again = bench.run(["mean-shift"], [str(a)], tmp_path / "o", progress=False,
                      reference=False)
    assert again[0]["auc"] != before["auc"] or again[0]["mean_center_error"] != \
        before["mean_center_error"]
    assert len(list((tmp_path / "o/runs").glob("mean-shift__*"))) == 3


def test_hygiene_empty_lists_stray_params_and_file_modes(tmp_path, two_clips):
    with pytest.raises(ValueError, match="no clips"):
        bench.run(["mean-shift"], "", tmp_path, progress=False)
    with pytest.raises(ValueError, match="no trackers"):
        bench.run("", two_clips, tmp_path, progress=False)
    with pytest.raises(ValueError, match="does not run"):
        bench.run(["mean-shift"], two_clips, tmp_path, progress=False,
                  params={"mean-shfit": {"max_iter": 3}})
    old = os.umask(0o022)
    try:
        bench.run(["mean-shift"], two_clips[:1], tmp_path / "m", progress=False,
                  reference=False)
    finally:
        os.umask(old)
    for p in [*(tmp_path / "m").iterdir(), *(tmp_path / "m/runs").iterdir()]:
        if p.is_file():
            assert stat.S_IMODE(p.stat().st_mode) == 0o644, p


def test_cli_refuses_empty_lists_and_stops_on_ctrl_c_with_one_line(tmp_path, two_clips,
                                                                  capsys, monkeypatch):
    assert cli.main(["bench", "--trackers", "", "--clips", two_clips[0], "--quiet"]) == 2
    assert cli.main(["bench", "--trackers", "mean-shift", "--clips", "", "--quiet"]) == 2
    capsys.readouterr()

    def interrupted(*a, **k):
        raise KeyboardInterrupt
    monkeypatch.setattr(bench, "run", interrupted)
    code = cli.main(["bench", "--trackers", "mean-shift", "--clips", two_clips[0],
                     "--out", str(tmp_path / "o"), "--quiet"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 130 and len(err) == 1 and "resume" in err[0]


def test_groups_split_clips_for_idle_workers():
    tasks = bench.plan(["mean-shift", "covariance"], ["red-cube"], max_frames=5)
    assert len(parallel.groups(tasks, 1)) == 1
    assert len(parallel.groups(tasks, 2)) == 3       # 3 runs, 8 wanted -> one per group


def test_tiny_target_bench_finishes(tmp_path):
    root = tmp_path / "tiny"
    _folder(tmp_path, "tiny")
    gt = root / "groundtruth_rect.txt"
    gt.write_text("\n".join(f"{40 + i},{50},3,3" for i in range(10)) + "\n")
    rows = bench.run(["mean-shift"], [str(root)], tmp_path / "o", progress=False)
    assert {r["tracker"] for r in rows} == {"mean-shift", "opencv-mil"}


def test_existing_book_results_still_load():
    from trackbook import results
    rows = results.load("real").rows
    assert rows and {"tracker", "clip", "auc"} <= set(rows[0])
    shutil.rmtree  # noqa: B018  (imported for fixtures above)


def test_ctrl_c_during_a_parallel_bench_prints_one_line(tmp_path, two_clips):
    import signal
    import subprocess
    import sys
    import time

    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    p = subprocess.Popen([sys.executable, "-m", "trackbook", "bench", "--trackers",
                          "color-pf,covariance", "--clips", ",".join(two_clips), "--workers",
                          "2", "--quiet", "--seeds", "0-20", "--out", str(tmp_path / "o")],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    runs = tmp_path / "o" / "runs"
    t0 = time.time()
    while time.time() - t0 < 60 and not (runs.is_dir() and any(runs.glob("*.json"))):
        time.sleep(0.2)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    lines = [x for x in err.splitlines() if x.strip()]
    assert p.returncode == 130, err
    assert len(lines) == 1 and "resume" in lines[0], err


def test_single_process_bench_uses_one_opencv_thread_and_restores_it(tmp_path, two_clips,
                                                                    monkeypatch):
    """A one-worker bench runs with one OpenCV thread (faster on these small images) and
    gives the caller back its own setting and environment afterwards."""
    monkeypatch.delenv(parallel.ENV_CV_THREADS, raising=False)
    before = cv2.getNumThreads()
    seen = []
    real = parallel.runs.run_group

    def spy(*a, **k):
        seen.append((cv2.getNumThreads(), os.environ.get(parallel.ENV_CV_THREADS)))
        return real(*a, **k)

    monkeypatch.setattr(parallel.runs, "run_group", spy)
    bench.run(["mean-shift"], two_clips, str(tmp_path), workers=1, progress=False,
              reference=False)
    assert seen and all(s == (1, "1") for s in seen)
    assert cv2.getNumThreads() == before
    assert parallel.ENV_CV_THREADS not in os.environ
