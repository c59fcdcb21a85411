"""Where a benchmark's runs execute: this process, worker processes, or a Dask cluster.

The unit of work is a *group*: runs that share one clip. A worker loads the clip once and
gives each decoded frame to every tracker of its group in turn
(:func:`trackbook.evaluation.runner.evaluate_many`), so a clip is decoded once per group and
only the current frame is held (memory stays bounded by one clip's trackers, not by the dataset).
When there are fewer clips than ``4 x workers`` the trackers of a clip are split into several
groups so that all workers stay busy; groups go out longest first.

Every run's result is the same wherever it runs: trackers are seeded per run and OpenCV's MIL
runs each run in a fresh child process. Local workers write each run's file themselves
(atomically); with Dask the records come back and this process writes them, so a cluster
whose workers do not share the output folder works too (they must see the clips at the same
paths, or use sample clips).
"""

from __future__ import annotations

import contextlib
import math
import os
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

from . import bench as _bench

ENV_SCHEDULER = "TRACKBOOK_DASK_SCHEDULER"


def default_workers() -> int:
    """The cores this process may use (``os.sched_getaffinity`` where available)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # macOS, Windows
        return max(1, os.cpu_count() or 1)


def groups(tasks, workers: int = 1) -> list[list]:
    """Tasks -> groups sharing a clip, split so there are at least ``4 x workers`` groups when
    possible, longest (frames x runs) first."""
    by: dict = {}
    for t in tasks:
        by.setdefault(t.clip.identity, []).append(t)
    out = []
    want = 4 * workers if workers > 1 else 1
    split = max(1, math.ceil(want / max(1, len(by))))
    for ts in by.values():
        k = min(split, len(ts))
        size = math.ceil(len(ts) / k)
        out.extend(ts[i:i + size] for i in range(0, len(ts), size))
    out.sort(key=lambda g: -sum(t.frames for t in g))
    return out


#: Set in a worker's environment so that its OpenCV MIL child runs one thread too.
ENV_CV_THREADS = "TRACKBOOK_CV_THREADS"


def one_thread_per_worker():
    """Make OpenCV in this process (and the MIL children it starts) use one thread.

    With N workers on N cores, OpenCV's own thread pool (one thread per core in every worker)
    oversubscribes the cores: the workers' threads preempt each other. One thread per worker
    is the usual rule for process-parallel OpenCV. The boxes do not change: the trackers'
    OpenCV calls are deterministic whatever the number of threads
    (tests/test_bench_parallel.py compares 1 and 2 workers)."""
    import cv2

    cv2.setNumThreads(1)
    os.environ[ENV_CV_THREADS] = "1"


@contextlib.contextmanager
def one_opencv_thread():
    """One OpenCV thread for a single-process bench, restored afterwards (the caller may be a
    notebook that uses OpenCV for other things). The trackers' OpenCV calls work on small
    patches and frames, where the thread pool's hand-offs cost more than they save: the
    development-set bench (7 sequences, 11 trackers + MIL) took 139 s in one process with
    OpenCV's default threads and 104 s with one, on 2 cores (benchmarks/scaling.py's
    machine)."""
    import cv2

    threads, env = cv2.getNumThreads(), os.environ.get(ENV_CV_THREADS)
    one_thread_per_worker()
    try:
        yield
    finally:
        cv2.setNumThreads(threads)
        if env is None:
            os.environ.pop(ENV_CV_THREADS, None)
        else:
            os.environ[ENV_CV_THREADS] = env


def _worker_init(imports=()):
    # Ctrl-C is the parent's to handle (one line, then it stops the workers): a worker that
    # also caught it would print its own traceback.
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    one_thread_per_worker()
    _bench.load_imports(imports)


def _work(group, out, multi_seed):
    return _bench.run_group(group, out, multi_seed)


def _work_dask(group, multi_seed, imports=()):
    # a Dask worker is a process of its own on a core of its own, like a local worker; user
    # trackers are loaded here, in the worker, before the runs need them (idempotent)
    _bench.load_imports(imports)
    one_thread_per_worker()
    return _bench.run_group(group, None, multi_seed)


def execute(tasks, out, finished, workers: int = 1, scheduler: str | None = None,
            multi_seed: bool = False, imports=()) -> None:
    """Run ``tasks``; call ``finished(group, records)`` in this process as each group ends.

    ``imports`` (modules or ``.py`` files of user trackers) are loaded in every worker, local or
    Dask, and in this process when it runs the tasks itself."""
    if not tasks:
        return
    scheduler = scheduler or os.environ.get(ENV_SCHEDULER) or None
    if workers is None:
        workers = default_workers()
    if isinstance(workers, bool) or int(workers) < 1:
        raise ValueError(f"workers = {workers!r}: use a whole number of processes, at least 1.")
    workers = int(workers)
    if scheduler:
        return _execute_dask(tasks, out, finished, scheduler, multi_seed, imports)
    gs = groups(tasks, workers)
    if workers == 1 or len(gs) == 1:
        _bench.load_imports(imports)
        with one_opencv_thread():
            for g in gs:
                finished(g, _bench.run_group(g, out, multi_seed))
        return
    import multiprocessing as mp

    # spawn: a worker must not inherit this process's threads (a notebook's, tqdm's) or state.
    pool = ProcessPoolExecutor(max_workers=min(workers, len(gs)),
                               mp_context=mp.get_context("spawn"), initializer=_worker_init,
                               initargs=(tuple(imports),))
    try:
        pending = {pool.submit(_work, g, str(out), multi_seed): g for g in gs}
        while pending:
            done, _ = wait(pending, return_when=FIRST_COMPLETED)
            for f in done:
                g = pending.pop(f)
                finished(g, f.result())
    except BaseException:
        # stop now: finished runs are on disk, a running group is re-run on resume
        procs = list((getattr(pool, "_processes", None) or {}).values())
        pool.shutdown(wait=False, cancel_futures=True)
        for p in procs:
            p.terminate()
        for p in procs:
            p.join(timeout=5)
        raise
    pool.shutdown()


def _execute_dask(tasks, out, finished, scheduler, multi_seed, imports=()):
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise ImportError("--scheduler needs Dask: pip install 'trackbook[dask]' "
                          "(dask[distributed]).") from None
    client = scheduler if isinstance(scheduler, Client) else Client(scheduler)
    try:
        n = max(1, len(client.scheduler_info().get("workers", {})))
        gs = groups(tasks, n)
        futs = {client.submit(_work_dask, g, multi_seed, tuple(imports), pure=False): i
                for i, g in enumerate(gs)}
        try:
            for f in as_completed(list(futs)):
                g = gs[futs[f]]
                recs = f.result()
                for t, r in zip(g, recs):
                    _bench.write_atomic(t.path(out), _bench.json.dumps(r))
                finished(g, recs)
        except BaseException:
            client.cancel(list(futs))
            raise
    finally:
        if client is not scheduler:
            client.close()
