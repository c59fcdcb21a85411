"""The bench never hangs, orphans or runs absurd work: a scheduler that answers in seconds,
workers that end with the bench, caps on runs, refused empty --out and --workers 0."""
import os
import signal
import socket
import subprocess
import sys
import threading
import time
import types

import numpy as np
import pytest

from .conftest import write_sequence
from trackbook import cli
from trackbook.evaluation import bench, parallel, runs


def _folder(root, name, n=12):
    return write_sequence(root, name, n, seed=11, dx=2)


# ----------------------------------------------------------------------- loopback servers
def _server(behaviour, lifetime=8.0):
    """A TCP server on 127.0.0.1 that serves one connection as ``behaviour`` says and stops
    by itself after ``lifetime`` seconds."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(4)
    srv.settimeout(lifetime)
    t_end = time.monotonic() + lifetime

    def serve():
        try:
            conn, _ = srv.accept()
        except OSError:
            srv.close()
            return
        with conn:
            conn.settimeout(max(0.1, t_end - time.monotonic()))
            try:
                if behaviour == "banner":        # speaks first, like many services
                    conn.sendall(b"HTTP/1.1 200 OK\r\nContent-Length: 0\r\n\r\n")
                elif behaviour == "http":        # answers what it is sent, like a web server
                    conn.recv(65536)
                    conn.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
                while time.monotonic() < t_end:  # then holds the line open, silent
                    if not conn.recv(65536):
                        break
            except OSError:
                pass
        srv.close()

    threading.Thread(target=serve, daemon=True).start()
    return f"tcp://127.0.0.1:{srv.getsockname()[1]}"


def _free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


@pytest.mark.parametrize("behaviour", ["silent", "banner", "http"])
def test_a_scheduler_that_is_not_dask_is_one_line_and_exit_2(tmp_path, capsys, behaviour):
    addr = _server(behaviour)
    code = cli.main(["bench", "--trackers", "mean-shift", "--clips", "red-cube", "--quiet",
                     "--max-frames", "3", "--scheduler", addr, "--scheduler-timeout", "1",
                     "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    assert "bug" not in err[0] and addr in err[0]
    # the 1-second limit decided, not the server hanging up (it holds the line for 8 s)
    assert "within 1 s" in err[0] or "does not speak Dask" in err[0]
    assert not (tmp_path / "o" / "runs").exists()


def test_refused_unresolvable_and_invalid_addresses_are_one_line_and_exit_2(tmp_path, capsys,
                                                                          monkeypatch):
    monkeypatch.setenv(parallel.ENV_TIMEOUT, "1")
    for addr, words in ((f"tcp://127.0.0.1:{_free_port()}", "cannot connect"),
                        ("tcp://no-such-host.invalid:8786", "cannot resolve"),
                        ("tcp://127.0.0.1:notaport", "not an address"),
                        ("tcp://", "not an address")):
        code = cli.main(["bench", "--trackers", "mean-shift", "--clips", "red-cube", "--quiet",
                         "--scheduler", addr, "--out", str(tmp_path / "o")])
        err = capsys.readouterr().err.strip().splitlines()
        assert code == 2 and len(err) == 1 and words in err[0], (addr, err)
    with pytest.raises(ValueError, match="positive"):
        parallel.check_timeout("soon")
    monkeypatch.setenv(parallel.ENV_TIMEOUT, "2.5")
    assert parallel.check_timeout(None) == 2.5 and parallel.check_timeout(7) == 7.0


# ----------------------------------------------------------------------- limits
def test_runs_are_capped_with_the_flag_named(tmp_path):
    clip = str(_folder(tmp_path, "c", n=4))
    with pytest.raises(ValueError, match="--max-runs"):
        bench.plan(["mean-shift"], [clip], seeds="0-100000")
    with pytest.raises(ValueError, match="--max-runs"):
        bench.parse_seeds("0-1000000000000", limit=5000)        # refused before expanding
    with pytest.raises(ValueError, match=r"would do 11 runs.*--max-runs 11"):
        bench.plan(["mean-shift"], [clip], seeds="0-9", max_runs=10)   # 10 seeds + MIL
    assert len(bench.plan(["mean-shift"], [clip], seeds="0-9", max_runs=11)) == 11
    with pytest.raises(ValueError, match="max_runs"):
        bench.plan(["mean-shift"], [clip], max_runs=0)


def test_groups_stay_small_whatever_the_sweep():
    clip = types.SimpleNamespace(identity="x")
    tasks = [types.SimpleNamespace(clip=clip, frames=100) for _ in range(1001)]
    for w in (1, 2, 8):
        gs = parallel.groups(tasks, w)
        assert sum(len(g) for g in gs) == 1001
        assert max(len(g) for g in gs) <= parallel.MAX_GROUP


def test_runs_are_saved_as_each_group_finishes(tmp_path, monkeypatch):
    clip = str(_folder(tmp_path, "c", n=4))
    out = tmp_path / "o"
    seen = []
    real = runs.run_group

    def spy(group, o, *a, **k):
        seen.append((len(list((out / "runs").glob("*.json"))) if (out / "runs").exists()
                     else 0, len(group)))
        return real(group, o, *a, **k)
    monkeypatch.setattr(runs, "run_group", spy)
    bench.run(["mean-shift"], [clip], out, seeds="0-9", progress=False, reference=False)
    assert len(seen) >= 3 and all(n <= parallel.MAX_GROUP for _, n in seen)
    assert [s for s, _ in seen] == list(np.cumsum([0] + [n for _, n in seen[:-1]]))


def test_empty_out_and_zero_workers_are_refused(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for extra, words in ((["--out", ""], "out is empty"), (["--workers", "0"], "workers"),
                         (["--workers", "-3"], "workers")):
        code = cli.main(["bench", "--trackers", "mean-shift", "--clips", "red-cube",
                         "--quiet", *extra])
        err = capsys.readouterr().err.strip().splitlines()
        assert code == 2 and len(err) == 1 and words in err[0], err
    assert list(tmp_path.iterdir()) == []


# ----------------------------------------------------------------------- orphans
def _session(sid):
    """Live (not zombie) processes of session ``sid``."""
    pids = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            stat = open(f"/proc/{d}/stat").read()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2:].split()
        if fields[0] != "Z" and int(fields[3]) == sid:   # state, ppid, pgrp, session
            pids.append(int(d))
    return pids


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL])
def test_a_killed_two_worker_bench_leaves_no_process(tmp_path, sig):
    clips_ = ",".join(str(_folder(tmp_path / "d", n, n=40)) for n in ("a", "b"))
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    p = subprocess.Popen([sys.executable, "-m", "trackbook", "bench", "--trackers",
                          "color-pf,covariance", "--clips", clips_, "--workers", "2", "--quiet",
                          "--seeds", "0-20", "--out", str(tmp_path / "o")],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env,
                         start_new_session=True)
    try:
        t0 = time.monotonic()     # wait until the workers run (bench + 2 workers + tracker)
        while time.monotonic() - t0 < 30 and len(_session(p.pid)) < 4:
            time.sleep(0.1)
        time.sleep(1.0)
        assert len(_session(p.pid)) >= 4, "the workers never started"
        p.send_signal(sig)
        p.wait(timeout=15)
        t0 = time.monotonic()
        while time.monotonic() - t0 < 8 and _session(p.pid):
            time.sleep(0.1)
        assert _session(p.pid) == []
        if sig == signal.SIGTERM:
            err = p.stderr.read()     # every writer is gone: this cannot block
            lines = [x for x in err.splitlines() if x.strip()]
            assert p.returncode == 128 + sig and len(lines) == 1 and "resume" in lines[0], err
    finally:
        for pid in _session(p.pid):      # never leave anything behind, even on failure
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
        p.stderr.close()


def test_bench_parallel_and_runs_do_not_import_each_other():
    import ast
    import importlib

    def imported(mod):
        tree = ast.parse(open(importlib.import_module(mod).__file__).read())
        names = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                names |= {node.module} if node.module else {a.name for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.module:
                names.add(node.module.rsplit(".", 1)[-1])
        return names

    b = imported("trackbook.evaluation.bench")
    p = imported("trackbook.evaluation.parallel")
    r = imported("trackbook.evaluation.runs")
    assert "bench" not in p and "bench" not in r and "parallel" not in r
    assert "runs" in p and ("runs" in b or "parallel" in b)
