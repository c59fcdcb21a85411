"""The command line against a hostile user: every refusal is one line on stderr with exit
code 2 (never a traceback, never silence), outputs are never replaced unless asked, and errors
of the user's own code are reported as theirs."""
import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from trackbook import cli, clips
from trackbook.evaluation import bench, runs

from .conftest import write_sequence

pytestmark = pytest.mark.usefixtures("clean_registry")


def _folder(root, name, n=6):
    return write_sequence(root, name, n, seed=5, size=(96, 72), side=20, x0=10, y0=20, dx=3)


def _one_line_error(capsys, *words):
    """stderr is one 'trackbook: ...' line holding ``words``; no traceback."""
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("trackbook: ") and "Traceback" not in err
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


def _files(folder):
    """Every path below ``folder`` but Python's own byte-code cache (importing a user's
    tracker file may write one beside it: that is Python, not a trackbook output)."""
    return sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*")
                  if "__pycache__" not in p.parts) if folder.exists() else []


def _env():
    return {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}


TRACKER = '''
import sys
import numpy as np
from trackbook import trackers
from trackbook.trackers import Tracker

{top}

@trackers.register
class Mine(Tracker):
    """A tracker a student wrote."""

    name = {name!r}

    def _init(self, frame, box):
        self.box0 = np.asarray(box, dtype=float)

    def _update(self, frame):
        {update}
        return True, self.box0
'''


def _tracker(folder, stem, name, top="", update="pass"):
    path = folder / f"{stem}.py"
    path.write_text(TRACKER.format(name=name, top=top, update=update))
    line = TRACKER.format(name=name, top=top, update=update).splitlines()
    return path, line


def _line_of(path, text):
    return next(i for i, s in enumerate(path.read_text().splitlines(), 1) if text in s)


# --- 1. a Dask cluster that dies ----------------------------------------------------------------

def _cluster(distributed):
    # in-process workers on loopback TCP, so the address goes through the tcp:// checks
    return distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                    protocol="tcp", host="127.0.0.1", scheduler_port=0,
                                    dashboard_address=":0")


def test_dask_bench_with_every_worker_gone_stops_in_bounded_time(tmp_path, capsys):
    distributed = pytest.importorskip("distributed")
    a = _folder(tmp_path / "d", "a")
    out = tmp_path / "o"
    with _cluster(distributed) as cluster:
        cluster.scale(0)                        # every worker stopped: nothing can run
        cluster.sync(cluster._correct_state)
        code = cli.main(["bench", "--trackers", "mean-shift", "--clips", str(a), "--quiet",
                         "--scheduler", cluster.scheduler_address,
                         "--scheduler-timeout", "1", "--out", str(out)])
    assert code == 2
    _one_line_error(capsys, "no worker left", "--scheduler")


def test_dask_bench_whose_scheduler_dies_says_so_and_a_local_rerun_resumes(tmp_path, capsys,
                                                                           monkeypatch):
    distributed = pytest.importorskip("distributed")
    a, b = _folder(tmp_path / "d", "a"), _folder(tmp_path / "d", "b")
    out = tmp_path / "o"
    save = runs.save_run
    with _cluster(distributed) as cluster:
        def save_then_close(task, record, where):
            save(task, record, where)
            cluster.close()                     # the scheduler dies after the first run
        monkeypatch.setattr(runs, "save_run", save_then_close)
        code = cli.main(["bench", "--trackers", "mean-shift", "--clips", f"{a},{b}",
                         "--quiet", "--scheduler", cluster.scheduler_address,
                         "--scheduler-timeout", "2", "--out", str(out)])
    monkeypatch.setattr(runs, "save_run", save)
    assert code == 2
    _one_line_error(capsys, "went away", "resume")
    saved = len(list((out / "runs").glob("*.json")))
    assert saved >= 1                           # what came back before is on disk
    assert cli.main(["bench", "--trackers", "mean-shift", "--clips", f"{a},{b}", "--quiet",
                     "--workers", "1", "--out", str(out)]) == 0
    # 2 clips x (mean-shift + the reference MIL) = 4 runs, the saved ones read back
    assert f"{saved} read back, {4 - saved} run" in capsys.readouterr().out


# --- 2. an --out the OS refuses -----------------------------------------------------------------

@pytest.mark.parametrize("command", [
    ["track", "mean-shift", "red-cube", "--max-frames", "3"],
    ["bench", "--trackers", "mean-shift", "--clips", "red-cube", "--max-frames", "3", "--quiet"],
    ["notebooks"],
])
def test_an_out_name_too_long_is_one_line_naming_it(tmp_path, capsys, monkeypatch, command):
    monkeypatch.chdir(tmp_path)
    long = "x" * 300
    assert cli.main(command + ["--out", long]) == 2
    _one_line_error(capsys, long, "shorter")
    assert _files(tmp_path) == []


def _refused(folder):
    """True when even this user (root included) cannot create a file in ``folder``."""
    try:
        (Path(folder) / "trackbook-probe").touch()
    except OSError:
        return True
    (Path(folder) / "trackbook-probe").unlink()
    return False


# /sys refuses new files and folders to root too: a folder the OS will not write to
@pytest.mark.skipif(not (sys.platform.startswith("linux") and os.path.isdir("/sys/kernel")
                         and _refused("/sys/kernel")), reason="needs Linux's /sys")
@pytest.mark.parametrize("out", ["/sys/kernel", "/sys/kernel/trackbook-out"])
@pytest.mark.parametrize("command", [
    ["track", "mean-shift", "red-cube", "--max-frames", "3"],
    ["bench", "--trackers", "mean-shift", "--clips", "red-cube", "--max-frames", "3", "--quiet",
     "--workers", "1"],
    ["notebooks"],
])
def test_an_unwritable_out_is_one_line_naming_the_path_and_the_fix(capsys, out, command):
    assert cli.main(command + ["--out", out]) == 2
    msg = _one_line_error(capsys, out, "--out", "permi")
    assert "bug" not in msg and "your code" not in msg


def test_a_file_where_the_out_folder_should_be_is_one_line(tmp_path, capsys):
    (tmp_path / "f").write_text("mine")
    for cmd in (["track", "mean-shift", "red-cube", "--max-frames", "3"], ["notebooks"]):
        assert cli.main(cmd + ["--out", str(tmp_path / "f" / "o")]) == 2
        _one_line_error(capsys, str(tmp_path / "f"), "not a folder")
    assert (tmp_path / "f").read_text() == "mine"


# --- 3. a tracker name that is a path -----------------------------------------------------------

@pytest.mark.parametrize("name", ["../../escaped", "..", "a/b", ".hidden"])
def test_a_tracker_name_that_cannot_be_a_file_name_is_refused(tmp_path, capsys, name):
    f, _ = _tracker(tmp_path, "evil", name)
    out = tmp_path / "deep" / "o"
    before = _files(tmp_path)
    for cmd in (["track", name, "red-cube", "--max-frames", "3"],
                ["bench", "--trackers", name, "--clips", "red-cube", "--max-frames", "3",
                 "--quiet", "--workers", "1"]):
        assert cli.main(cmd + ["--import", str(f), "--out", str(out)]) == 2
        _one_line_error(capsys, repr(name), "rename")
        assert _files(tmp_path) == before          # nothing written, inside or outside


def test_clip_names_become_file_names_without_leaving_the_folder():
    assert runs.safe_name("..") == "_."
    assert runs.safe_name("../../x") == "_._.._x"     # one name: "/" -> "_", no leading dot
    assert runs.safe_name("a/clip") == "a_clip"
    assert runs.safe_name("") == "_"


# --- 4. OTB result files never collide ----------------------------------------------------------

def _record(tracker, clip, boxes, ms=(1.0, 2.0)):
    return {"row": {"tracker": tracker, "clip": clip}, "settings": {"seed": 0},
            "boxes": boxes, "ms": list(ms)}


def test_otb_files_of_clips_with_equal_file_names_are_refused_not_overwritten(tmp_path):
    recs = [_record("t", "my clip", [[1, 2, 3, 4]]), _record("t", "my_clip", [[5, 6, 7, 8]])]
    with pytest.raises(ValueError, match="'my clip' and 'my_clip'.*rename one"):
        bench.write_otb(recs, tmp_path)
    assert _files(tmp_path) == []                  # refused before any file is written
    with pytest.raises(ValueError, match="rename one"):    # case only: one file on macOS
        bench.write_otb([_record("t", "Deer", [[1, 2, 3, 4]]),
                         _record("t", "deer", [[1, 2, 3, 4]])], tmp_path)


def test_a_clip_named_like_a_timing_file_keeps_both(tmp_path):
    recs = [_record("t", "Deer", [[1, 2, 3, 4]], ms=(10.0,)),
            _record("t", "Deer_time", [[5, 6, 7, 8]], ms=(20.0,))]
    bench.write_otb(recs, tmp_path)
    otb = tmp_path / "otb" / "t"
    assert (otb / "Deer.txt").read_text() == "1.0,2.0,3.0,4.0\n"
    assert (otb / "Deer_time.txt").read_text() == "5.0,6.0,7.0,8.0\n"   # a sequence's boxes
    assert (otb / "times" / "Deer_time.txt").read_text() == "0.01\n"     # Deer's timing
    assert (otb / "times" / "Deer_time_time.txt").read_text() == "0.02\n"


def test_bench_refuses_two_clips_whose_otb_files_collide(tmp_path, capsys):
    a, b = _folder(tmp_path / "d", "my clip"), _folder(tmp_path / "e", "my_clip")
    code = cli.main(["bench", "--trackers", "mean-shift", "--clips", f"{a},{b}", "--quiet",
                     "--workers", "1", "--out", str(tmp_path / "o")])
    assert code == 2
    _one_line_error(capsys, "'my clip' and 'my_clip'")
    assert not (tmp_path / "o").exists()          # refused before the first run: no file


# --- 5. never overwritten without --force; atomic writes ----------------------------------------

def test_track_refuses_to_replace_a_run_without_force(tmp_path, capsys):
    out = tmp_path / "o"
    base = ["track", "mean-shift", "red-cube", "--out", str(out), "--param", "max_iter=5"]
    assert cli.main(base) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    stems = {p.stem for p in out.iterdir()}
    assert len(stems) == 1 and stems.pop().startswith("mean-shift_red-cube_")
    assert sorted(p.suffix for p in out.iterdir()) == [".csv", ".json", ".mp4"]
    capsys.readouterr()
    assert cli.main(base) == 2                                    # the same run again
    _one_line_error(capsys, "mean-shift_red-cube", "--force")
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    csv = next(p for p in out.iterdir() if p.suffix == ".csv")
    csv.write_text("edited\n")
    assert cli.main(base + ["--force"]) == 0

    def boxes(text):                  # frame and box columns (the timings differ run to run)
        return [line.split(",")[:5] for line in text.decode().splitlines()]
    assert boxes(csv.read_bytes()) == boxes(before[csv.name])    # replaced: same seed, boxes
    assert sorted(p.name for p in out.iterdir()) == sorted(before)   # no temporary left


def test_track_runs_with_another_box_or_length_get_their_own_files(tmp_path, capsys):
    """README: track a video, then the same video with --box: the second is a new run."""
    from trackbook.clips.loaders import write_video
    clip = clips.load("red-cube")
    video = tmp_path / "my_video.mp4"
    write_video(video, list(clip.frames)[:5], 10, clip.size)
    gt = tmp_path / "my_boxes.txt"
    gt.write_text("".join(",".join(f"{v:g}" for v in b) + "\n" for b in clip.groundtruth[:5]))
    (tmp_path / "my_video.groundtruth.txt").write_text(gt.read_text())   # as clips export
    out = tmp_path / "o"
    base = ["track", "mean-shift", str(video), "--out", str(out)]
    x, y, w, h = (int(v) for v in clip.groundtruth[0])
    for i, extra in enumerate([[], ["--box", f"{x},{y},{w},{h}"],
                               ["--box", f"{x + 1},{y},{w},{h}"],
                               ["--box", f"{x},{y},{w},{h}", "--max-frames", "3"],
                               ["--groundtruth", str(gt)]]):
        assert cli.main(base + extra) == 0, capsys.readouterr().err
        assert len(list(out.glob("*.json"))) == i + 1          # a new run, new files
    records = [json.loads(p.read_text()) for p in out.glob("*.json")]
    assert sorted(map(str, (r["box"] for r in records))) == sorted(
        map(str, [None, None, *[[float(v) for v in b] for b in
                                 ((x, y, w, h), (x + 1, y, w, h), (x, y, w, h))]]))
    assert sorted(str(r["max_frames"]) for r in records) == ["3"] + ["None"] * 4
    assert [r["groundtruth"] for r in records if r["groundtruth"]] == [str(gt.resolve())]


def test_clips_export_never_replaces_a_file_without_force(tmp_path, capsys):
    video = tmp_path / "v.mp4"
    gt = tmp_path / "v.groundtruth.txt"
    gt.write_text("my own boxes\n")
    assert cli.main(["clips", "export", "red-cube", str(video)]) == 2
    _one_line_error(capsys, str(gt), "--force")
    assert gt.read_text() == "my own boxes\n" and not video.exists()
    assert cli.main(["clips", "export", "red-cube", str(video), "--force"]) == 0
    assert video.stat().st_size > 0 and gt.read_text() != "my own boxes\n"


def test_notebooks_never_replace_an_edited_notebook_without_force(tmp_path, capsys):
    pytest.importorskip("jupytext")
    book = tmp_path / "book"
    book.mkdir()
    (book / "01_intro.md").write_text("# Intro\n\nsome text\n")
    out = tmp_path / "nb"
    assert cli.main(["notebooks", "--book", str(book), "--out", str(out)]) == 0
    nb = out / "01_intro.ipynb"
    assert json.loads(nb.read_text())["cells"]
    nb.write_text("my answers")                                  # a student's edits
    capsys.readouterr()
    assert cli.main(["notebooks", "--book", str(book), "--out", str(out)]) == 2
    _one_line_error(capsys, str(nb), "--force")
    assert nb.read_text() == "my answers"
    assert cli.main(["notebooks", "--book", str(book), "--out", str(out), "--force"]) == 0
    assert json.loads(nb.read_text())["cells"]
    assert [p.name for p in out.iterdir()] == ["01_intro.ipynb"]


# --- 6. SIGTERM while the video is written ------------------------------------------------------

def test_sigterm_while_writing_the_video_removes_it_and_exits_143(tmp_path, capsys,
                                                                  monkeypatch):
    from trackbook.clips import loaders

    real = loaders.write_video

    def write_then_terminated(path, frames, *a, **k):
        def frames_then_signal():
            for i, f in enumerate(frames):
                if i == 2:                       # a real SIGTERM, mid-video
                    os.kill(os.getpid(), signal.SIGTERM)
                yield f
        return real(path, frames_then_signal(), *a, **k)
    monkeypatch.setattr(loaders, "write_video", write_then_terminated)
    out = tmp_path / "o"
    code = cli.main(["track", "mean-shift", "red-cube", "--max-frames", "6", "--out", str(out)])
    assert code == 128 + signal.SIGTERM
    _one_line_error(capsys, "stopped by a signal", "removed")
    assert list(out.glob("*")) == []                 # no unplayable .mp4, no half CSV
    assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL or callable(
        signal.getsignal(signal.SIGTERM))


# --- 7. a reader that goes away -----------------------------------------------------------------

def _run_without_a_reader(command, closed, timeout=300):
    """Run the command with a stdout whose reader is gone (``closed="reader"``: a pipe whose
    read end is closed, as after ``| head`` ended) or with no stdout at all (``">&-"``)."""
    argv = [sys.executable, "-m", "trackbook", *command]
    if closed == "reader":
        r, w = os.pipe()
        os.close(r)
        try:
            return subprocess.run(argv, check=False, stdout=w, stderr=subprocess.PIPE, text=True,
                                  env=_env(), timeout=timeout)
        finally:
            os.close(w)
    return subprocess.run(argv, check=False, stderr=subprocess.PIPE, text=True, env=_env(),
                          timeout=timeout, preexec_fn=lambda: os.close(1))


@pytest.mark.parametrize("closed", ["reader", ">&-"])
@pytest.mark.parametrize("command", [["trackers"], ["clips"]])
def test_stdout_gone_is_no_traceback(command, closed):
    p = _run_without_a_reader(command, closed)
    assert "Traceback" not in p.stderr and "Error" not in p.stderr, p.stderr
    assert p.returncode == 0


@pytest.mark.parametrize("closed", ["reader", ">&-"])
def test_bench_with_stdout_gone_is_no_traceback_and_still_writes(tmp_path, closed):
    a = _folder(tmp_path / "d", "a")
    p = _run_without_a_reader(["bench", "--trackers", "mean-shift", "--clips", str(a),
                               "--quiet", "--workers", "1", "--out", str(tmp_path / "o")],
                              closed)
    assert "Traceback" not in p.stderr and "Error" not in p.stderr, p.stderr
    assert p.returncode == 0
    assert (tmp_path / "o" / "results.csv").is_file()


# --- 8. errors of the user's own code -----------------------------------------------------------

def test_an_error_in_a_users_tracker_names_their_file_and_line(tmp_path, capsys):
    f, _ = _tracker(tmp_path, "my_tracker", "mine-keyerror", update="{}['x']")
    line = _line_of(f, "{}['x']")
    cmd = ["track", "mine-keyerror", "red-cube", "--max-frames", "3", "--import", str(f),
           "--out", str(tmp_path / "o")]
    assert cli.main(cmd) == 2
    msg = _one_line_error(capsys, f"error in your code (my_tracker.py:{line}, in _update): "
                                  "KeyError: 'x'", "--traceback")
    assert "bug" not in msg
    assert not (tmp_path / "o").exists()
    assert cli.main(["--traceback"] + cmd) == 2
    err = capsys.readouterr().err
    assert "Traceback (most recent call last)" in err and f'my_tracker.py", line {line}' in err
    assert err.strip().splitlines()[-1].startswith("trackbook: error in your code")


def test_a_value_error_at_import_is_the_users_not_a_usage_error(tmp_path, capsys):
    f, _ = _tracker(tmp_path, "bad_import", "mine-import", top="int('twelve')")
    line = _line_of(f, "int('twelve')")
    assert cli.main(["trackers", "--import", str(f)]) == 2
    _one_line_error(capsys, f"error in your code (bad_import.py:{line}, in <module>): "
                            "ValueError: invalid literal")


def test_an_error_in_a_bench_worker_process_comes_back_with_file_and_line(tmp_path, capsys):
    f, _ = _tracker(tmp_path, "worker_tracker", "mine-worker", update="1 / 0")
    line = _line_of(f, "1 / 0")
    a, b = _folder(tmp_path / "d", "a"), _folder(tmp_path / "d", "b")
    code = cli.main(["bench", "--import", str(f), "--trackers", "mine-worker", "--clips",
                     f"{a},{b}", "--workers", "2", "--quiet", "--out", str(tmp_path / "o")])
    assert code == 2
    _one_line_error(capsys, f"error in your code (worker_tracker.py:{line}, in _update): "
                            "ZeroDivisionError: division by zero")


def test_a_genuine_internal_error_is_still_reported_as_a_bug(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(cli, "_load_clip", None)       # calling it fails inside cmd_track
    assert cli.main(["track", "mean-shift", "red-cube", "--out", str(tmp_path / "o")]) == 1
    _one_line_error(capsys, "TypeError", "this is a bug", "--traceback")


# --- 9. sys.exit in the user's code -------------------------------------------------------------

@pytest.mark.parametrize("where", ["top", "update"])
def test_sys_exit_in_a_users_file_is_an_error_naming_it(tmp_path, capsys, where):
    kw = {"top": "sys.exit(0)"} if where == "top" else {"update": "sys.exit(0)"}
    f, _ = _tracker(tmp_path, "quitter", "mine-exit", **kw)
    line = _line_of(f, "sys.exit(0)")
    code = cli.main(["track", "mine-exit", "red-cube", "--max-frames", "3", "--import", str(f),
                     "--out", str(tmp_path / "o")])
    assert code == 2
    _one_line_error(capsys, f"error in your code (quitter.py:{line}", "SystemExit", "sys.exit(0)")
    assert not (tmp_path / "o").exists()


def test_sys_exit_in_a_bench_worker_is_an_error_naming_it(tmp_path, capsys):
    f, _ = _tracker(tmp_path, "quitter2", "mine-exit2", update="sys.exit(0)")
    line = _line_of(f, "sys.exit(0)")
    a, b = _folder(tmp_path / "d", "a"), _folder(tmp_path / "d", "b")
    code = cli.main(["bench", "--import", str(f), "--trackers", "mine-exit2", "--clips",
                     f"{a},{b}", "--workers", "2", "--quiet", "--out", str(tmp_path / "o")])
    assert code == 2
    _one_line_error(capsys, f"error in your code (quitter2.py:{line}, in _update): SystemExit")


# --- 10. --box never scores silently ------------------------------------------------------------

def test_box_does_not_score_against_a_ground_truth_found_beside_the_video(tmp_path, capsys):
    video, gt = clips.export("red-cube", tmp_path / "v.mp4")
    assert gt.is_file()                                   # the file --box must not use
    box = ",".join(str(int(v)) for v in np.loadtxt(gt, delimiter=",")[0])
    assert cli.main(["track", "mean-shift", str(video), "--box", box, "--max-frames", "4",
                     "--out", str(tmp_path / "o")]) == 0
    out = capsys.readouterr().out
    assert "not scored" in out and "--groundtruth" in out and "AUC" not in out
    assert cli.main(["track", "mean-shift", str(video), "--box", box, "--max-frames", "4",
                     "--groundtruth", str(gt), "--out", str(tmp_path / "o2")]) == 0
    out = capsys.readouterr().out
    assert "AUC" in out and f"against {gt}" in out


# --- 11. the bench says what was read back ------------------------------------------------------

def test_bench_summary_says_how_many_runs_were_read_back(tmp_path, capsys):
    a = _folder(tmp_path / "d", "a")
    cmd = ["bench", "--trackers", "mean-shift", "--clips", str(a), "--quiet", "--workers", "1",
           "--out", str(tmp_path / "o")]
    assert cli.main(cmd) == 0
    assert "0 read back, 2 run" in capsys.readouterr().out        # mean-shift + MIL
    assert cli.main(cmd) == 0
    out = capsys.readouterr().out
    assert "2 read back, 0 run" in out and "timings" in out


# --- 12. odd digits on the command line ---------------------------------------------------------

@pytest.mark.parametrize("box", ["1e400,0,10,10", "١٢,3,4,5", "nan,0,10,10", "inf,0,1,1",
                                 "1_0,0,10,10", "10,10,10", "-1,0,10,10", "0x10,0,10,10"])
def test_odd_box_digits_are_one_line(tmp_path, capsys, box):
    out = tmp_path / "o"
    assert cli.main(["track", "mean-shift", "red-cube", f"--box={box}", "--out", str(out)]) == 2
    _one_line_error(capsys, "--box")
    assert not out.exists()


def test_sys_exit_in_an_entry_point_plugin_is_a_warning_naming_it(tmp_path, capsys,
                                                                  monkeypatch):
    """An installed package that exits while loading neither ends the command with exit 0
    and nothing done nor stops it: the command does its work and a warning names the file
    and line (one broken package does not hide the others; see plugins.load_entry_points)."""
    from trackbook.trackers import plugins

    # a package 'installed' into tmp_path: its module and a .dist-info with the entry point
    f, _ = _tracker(tmp_path, "fake_exit_mod", "mine-plugin", top="sys.exit(0)")
    info = tmp_path / "fake_exit_dist-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: fake_exit_dist\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text("[trackbook.trackers]\nmine-plugin = fake_exit_mod\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(plugins, "_entry_points_done", False)
    try:
        with pytest.warns(UserWarning) as caught:
            assert cli.main(["trackers"]) == 0
    finally:
        sys.modules.pop("fake_exit_mod", None)
    out = capsys.readouterr().out
    assert "kcf" in out and "mine-plugin" not in out        # the work done, the plugin not
    line = _line_of(f, "sys.exit(0)")
    said = " ".join(str(w.message) for w in caught)
    assert "sys.exit(0)" in said and f"fake_exit_mod.py, line {line}" in said, said


def test_an_error_in_a_users_tracker_on_a_dask_worker_names_their_file(tmp_path, capsys):
    distributed = pytest.importorskip("distributed")
    f, _ = _tracker(tmp_path, "dask_tracker", "mine-dask", update="[][3]")
    line = _line_of(f, "[][3]")
    a = _folder(tmp_path / "d", "a")
    with _cluster(distributed) as cluster:
        code = cli.main(["bench", "--import", str(f), "--trackers", "mine-dask", "--clips",
                         str(a), "--quiet", "--scheduler", cluster.scheduler_address,
                         "--out", str(tmp_path / "o")])
    assert code == 2
    _one_line_error(capsys, f"error in your code (dask_tracker.py:{line}, in _update): "
                            "IndexError: list index out of range")


# --- 6. one bench per --out ---------------------------------------------------------------------

def _bench(clip, out, *extra):
    return cli.main(["bench", "--trackers", "mean-shift", "--clips", str(clip), "--quiet",
                     "--workers", "1", "--out", str(out), *extra])


def test_bench_refuses_an_out_holding_another_benchs_tables_and_force_replaces_them(
        tmp_path, capsys):
    a, b = _folder(tmp_path / "d", "Alpha"), _folder(tmp_path / "d", "Beta")
    out = tmp_path / "o"
    assert _bench(a, out, "--max-frames", "4") == 0
    tables = {p: (out / p).read_bytes() for p in _files(out) if (out / p).is_file()}
    capsys.readouterr()
    for other in ([b, "--max-frames", "4"], [a, "--max-frames", "5"],
                  [a, "--max-frames", "4", "--seeds", "0-1"]):
        assert _bench(other[0], out, *other[1:]) == 2           # refused before any run
        _one_line_error(capsys, f"--out {out}", "another bench", "Alpha", "--force")
        assert {p: (out / p).read_bytes() for p in tables} == tables
        assert not any("Beta" in p or "s1" in p for p in _files(out))
    assert _bench(a, out, "--max-frames", "4") == 0              # the same bench: resumed
    assert "2 read back, 0 run" in capsys.readouterr().out
    assert _bench(b, out, "--max-frames", "4", "--force") == 0   # replaced, Alpha's files gone
    otb = [p for p in _files(out) if p.startswith("otb/") and p.endswith(".txt")]
    assert otb == ["otb/mean-shift/Beta.txt", "otb/mean-shift/times/Beta_time.txt",
                   "otb/opencv-mil/Beta.txt", "otb/opencv-mil/times/Beta_time.txt"]
    assert {r["clip"] for r in bench.load(out)} == {"Beta"}


def test_bench_refuses_an_out_whose_tables_predate_the_plan_record(tmp_path, capsys):
    a, b = _folder(tmp_path / "d", "Alpha"), _folder(tmp_path / "d", "Beta")
    out = tmp_path / "o"
    assert _bench(a, out, "--max-frames", "4") == 0
    (out / "plan.json").unlink()                 # tables written by an older trackbook
    assert _bench(a, out, "--max-frames", "4") == 0              # the rows match: resumed
    (out / "plan.json").unlink()
    capsys.readouterr()
    assert _bench(b, out, "--max-frames", "4") == 2
    _one_line_error(capsys, "another bench", "Alpha", "--force")


def test_a_bench_leaves_no_result_file_of_another_bench_in_its_out(tmp_path, capsys):
    a = _folder(tmp_path / "d", "Alpha")
    out = tmp_path / "o"
    assert _bench(a, out, "--max-frames", "4") == 0
    written = _files(out)
    stale = ["otb/kcf/Old.txt", "otb/kcf/times/Old_time.txt", "success_IV.png",
             "precision_IV.png", "attributes.md", "attributes.csv"]
    for p in stale:                     # what a bench over OTB's attributes would have left
        (out / p).parent.mkdir(parents=True, exist_ok=True)
        (out / p).write_text("an earlier bench's\n")
    assert _bench(a, out, "--max-frames", "4", "--force") == 0
    assert _files(out) == written


def test_a_dataset_folder_linked_twice_is_listed_as_skipped_not_dropped(tmp_path, capsys):
    ds = tmp_path / "ds2"
    real = _folder(tmp_path / "data", "seq")
    ds.mkdir()
    (ds / "Alpha").symlink_to(real, target_is_directory=True)
    (ds / "Beta").symlink_to(real, target_is_directory=True)
    with pytest.warns(clips.datasets.DatasetWarning, match="Beta"):
        found = clips.load_dataset(ds)
    assert [q.name for q in found] == ["Alpha"]
    assert [s.name for s in found.skipped] == ["Beta"]
    assert "the same sequence as Alpha" in found.skipped[0].reason
    assert _bench(ds, tmp_path / "o", "--max-frames", "3") == 0
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert len(err) == 1 and err[0].startswith("trackbook: warning:") and "Beta" in err[0]
    assert {r["clip"] for r in bench.load(tmp_path / "o")} == {"Alpha"}


# --- 7. small things a user sees ----------------------------------------------------------------

@pytest.mark.parametrize("command", [
    ["track", "mean-shift", "red-cube", "--max-frames", "3"],
    ["bench", "--trackers", "mean-shift", "--clips", "red-cube", "--max-frames", "3", "--quiet",
     "--workers", "1"],
])
def test_an_out_too_long_under_a_new_folder_leaves_no_folder(tmp_path, capsys, monkeypatch,
                                                             command):
    monkeypatch.chdir(tmp_path)
    assert cli.main(command + ["--out", "c3/" + "x" * 300]) == 2
    _one_line_error(capsys, "shorter")
    assert _files(tmp_path) == []                  # not even the empty c3/


def test_bench_prints_paths_without_a_doubled_slash(tmp_path, capsys):
    a = _folder(tmp_path / "d", "Alpha")
    assert _bench(a, str(tmp_path / "o") + "/", "--max-frames", "3") == 0
    assert _bench(a, str(tmp_path / "o") + "/", "--max-frames", "3") == 0   # read back
    out = capsys.readouterr().out
    assert f"wrote {tmp_path / 'o' / 'results.csv'}," in out
    assert f"read back from {tmp_path / 'o' / 'runs'} keep" in out
    assert "//" not in out


def test_bench_on_a_folder_of_sequences_without_ground_truth_says_what_is_missing(tmp_path,
                                                                                   capsys):
    ds = tmp_path / "ds"
    for name in ("A", "B"):
        _folder(ds, name)
        (ds / name / "groundtruth_rect.txt").unlink()
    assert _bench(ds, tmp_path / "o", "--max-frames", "3") == 2
    line = _one_line_error(capsys, str(ds), "A: no ground truth", "B: no ground truth")
    assert "no images" not in line
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("command", [["track", "mean-shift", "red-cube"],
                                     ["bench", "--trackers", "mean-shift"]])
@pytest.mark.parametrize("seed", ["-1", "x", "1.5", "١"])
def test_a_bad_seed_is_one_line_offering_only_what_can_be_typed(tmp_path, capsys, command,
                                                                seed):
    with pytest.raises(SystemExit) as e:
        cli.main(command + [f"--seed={seed}", "--out", str(tmp_path / "o")])
    assert e.value.code == 2
    line = _one_line_error(capsys, "--seed", "0 or a positive whole number")
    assert "None" not in line
    assert not (tmp_path / "o").exists()


def test_a_bad_tracker_name_is_plain_text_not_markdown(tmp_path, capsys):
    f, _ = _tracker(tmp_path, "evil", "../x")
    assert cli.main(["track", "../x", "red-cube", "--import", str(f),
                     "--out", str(tmp_path / "o")]) == 2
    line = _one_line_error(capsys, "'../x'", "rename")
    assert "`" not in line
