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

Local workers are processes this module starts and stops itself (``spawn``): each watches its
parent and exits within a second or so when the parent is gone (and, on Linux, the kernel
kills it at once: ``PR_SET_PDEATHSIG``); the bench turns SIGTERM and SIGHUP into an orderly
stop that ends every worker (a worker's MIL child exits when its pipe closes). A Dask
scheduler is checked before use: it must accept a connection and send Dask's handshake within
a few seconds, otherwise the bench stops with one line.
"""

from __future__ import annotations

import contextlib
import math
import os
import pickle
import queue
import signal
import socket
import struct
import sys
import threading
import time

from .._user_code import UserCodeError, describe
from . import runs

ENV_SCHEDULER = "TRACKBOOK_DASK_SCHEDULER"
#: Seconds to wait for a Dask scheduler to connect and answer its handshake.
ENV_TIMEOUT = "TRACKBOOK_DASK_TIMEOUT"
DEFAULT_TIMEOUT = 5.0
#: At most this many runs go to a worker at once (one lockstep group), so runs are saved
#: every few runs whatever the size of the sweep.
MAX_GROUP = 4


def default_workers() -> int:
    """The cores this process may use (``os.sched_getaffinity`` where available)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # macOS, Windows
        return max(1, os.cpu_count() or 1)


def groups(tasks, workers: int = 1) -> list[list]:
    """Tasks -> groups sharing a clip, split so there are at least ``4 x workers`` groups when
    possible and no group has more than :data:`MAX_GROUP` runs, longest (frames x runs)
    first."""
    by: dict = {}
    for t in tasks:
        by.setdefault(t.clip.identity, []).append(t)
    out = []
    want = 4 * workers if workers > 1 else 1
    split = max(1, math.ceil(want / max(1, len(by))))
    for ts in by.values():
        k = min(len(ts), max(split, math.ceil(len(ts) / MAX_GROUP)))
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
    patches and frames, where the thread pool's hand-offs cost more than they save (the
    README's bench section gives measured figures)."""
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



# --------------------------------------------------------------------------- orphans
class Stopped(KeyboardInterrupt):
    """SIGTERM or SIGHUP reached the bench: it stops its workers and exits like on Ctrl-C."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


@contextlib.contextmanager
def stop_on_signals():
    """Turn SIGTERM and SIGHUP into :class:`Stopped` while the block runs (main thread only;
    elsewhere the caller's handlers stay), so the bench's cleanup ends every worker."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def stop(signum, frame):
        raise Stopped(signum)

    wanted = [s for s in ("SIGTERM", "SIGHUP") if hasattr(signal, s)]
    old = {s: signal.signal(getattr(signal, s), stop) for s in wanted}
    try:
        yield
    finally:
        for s, h in old.items():
            signal.signal(getattr(signal, s), h)


class WorkerLost(ChildProcessError):
    """A worker process died (killed, out of memory) before finishing its runs."""


def watch_parent(parent: int, interval: float = 0.5) -> None:
    """End this process when process ``parent`` is gone: on Linux the kernel sends SIGKILL
    (``prctl(PR_SET_PDEATHSIG)``); everywhere a daemon thread polls ``os.getppid()``."""
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, int(signal.SIGKILL), 0, 0, 0)  # 1 = PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent:  # the parent died before the line above
        os._exit(1)

    def poll():
        while os.getppid() == parent:
            time.sleep(interval)
        os._exit(1)

    threading.Thread(target=poll, name="trackbook-watch-parent", daemon=True).start()


def _portable(e: BaseException) -> BaseException:
    """``e`` as an exception that survives pickling to the parent: an error of the user's
    own code is described here (file, line), where its traceback still is."""
    user = describe(e)
    if user is not None:
        return user
    try:
        pickle.loads(pickle.dumps(e))
        return e
    except Exception:  # noqa: BLE001  an exception that does not pickle: keep its words
        return RuntimeError(f"{type(e).__name__}: {e}")


def _worker(inbox, outbox, parent: int, imports) -> None:
    # Ctrl-C is the parent's to handle (one line, then it stops the workers): a worker that
    # also caught it would print its own traceback.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    watch_parent(parent)
    one_thread_per_worker()
    try:
        runs.load_imports(imports)
    except BaseException as e:  # noqa: BLE001  reported to the parent, which stops
        outbox.put((-1, False, _portable(e)))
        return
    while True:
        item = inbox.get()
        if item is None:
            return
        i, group, out, multi_seed = item
        try:
            outbox.put((i, True, runs.run_group(group, out, multi_seed)))
        except BaseException as e:  # noqa: BLE001
            outbox.put((i, False, _portable(e)))


def _stop(procs, timeout: float = 3.0) -> None:
    for p in procs:
        if p.is_alive():
            p.terminate()
    t_end = time.monotonic() + timeout
    for p in procs:
        p.join(timeout=max(0.0, t_end - time.monotonic()))
        if p.is_alive():
            p.kill()
            p.join(timeout=1.0)


@contextlib.contextmanager
def _ctrl_c_as_flag(flag: list):
    """While the block runs, Ctrl-C appends to ``flag`` instead of raising (main thread only).

    The bench then raises KeyboardInterrupt itself, between two reads of its queue: raised
    wherever the signal happened to land, it could interrupt multiprocessing's own code (a
    queue's put, a lock's finaliser half-way between removing its semaphore and telling the
    resource tracker), and the tracker then printed warnings about a leaked semaphore after
    the bench's one line.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = signal.signal(signal.SIGINT, lambda signum, frame: flag.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)
    if flag:
        raise KeyboardInterrupt


def _execute_local(gs, out, finished, workers, multi_seed, imports):
    import multiprocessing as mp

    # spawn: a worker must not inherit this process's threads (a notebook's, tqdm's) or state.
    ctx = mp.get_context("spawn")
    inbox, outbox = ctx.Queue(), ctx.Queue()
    procs = [ctx.Process(target=_worker, args=(inbox, outbox, os.getpid(), list(imports)),
                         name=f"trackbook-bench-{k}", daemon=True)
             for k in range(min(workers, len(gs)))]
    interrupted = []
    try:
        with _ctrl_c_as_flag(interrupted):
            for p in procs:
                p.start()
            for i, g in enumerate(gs):
                inbox.put((i, g, str(out), multi_seed))
            for _ in procs:
                inbox.put(None)
        left = len(gs)
        while left:
            if interrupted:
                raise KeyboardInterrupt
            try:
                with _ctrl_c_as_flag(interrupted):
                    i, ok, payload = outbox.get(timeout=0.5)
            except queue.Empty:
                dead = [p for p in procs if p.exitcode not in (None, 0)]
                if dead or all(p.exitcode is not None for p in procs):
                    code = dead[0].exitcode if dead else 0
                    raise WorkerLost(
                        f"a bench worker process ended unexpectedly (exit code {code}); "
                        "finished runs are saved, run the same command again to resume."
                    ) from None
                continue
            if not ok:
                raise payload
            finished(gs[i], payload)
            left -= 1
    finally:
        # on success the workers are leaving already; on any error, Ctrl-C or SIGTERM they
        # stop now: finished runs are on disk, a running group is re-run on resume
        _stop(procs)
        for q in (inbox, outbox):
            q.cancel_join_thread()
            q.close()


def execute(tasks, out, finished, workers: int = 1, scheduler: str | None = None,
            multi_seed: bool = False, imports=(), timeout: float | None = None) -> None:
    """Run ``tasks``; call ``finished(group, records)`` in this process as each group ends.

    ``imports`` (modules or ``.py`` files of user trackers) are loaded in every worker, local or
    Dask; ``timeout`` is the Dask scheduler's connect-and-handshake limit in seconds
    (default ``$TRACKBOOK_DASK_TIMEOUT`` or 5).
    """
    if not tasks:
        return
    scheduler = scheduler or os.environ.get(ENV_SCHEDULER) or None
    workers = check_workers(workers)
    with stop_on_signals():
        if scheduler:
            return _execute_dask(tasks, out, finished, scheduler, multi_seed, imports, timeout)
        gs = groups(tasks, workers)
        if workers == 1 or len(gs) == 1:
            with one_opencv_thread():
                for g in gs:
                    finished(g, runs.run_group(g, out, multi_seed))
            return
        _execute_local(gs, out, finished, workers, multi_seed, imports)


def check_workers(workers) -> int:
    """``workers`` as a positive int (None: :func:`default_workers`); ``ValueError`` else."""
    if workers is None:
        return default_workers()
    if isinstance(workers, bool) or not hasattr(workers, "__index__") or workers < 1:
        raise ValueError(f"workers = {workers!r}: use a whole number of processes, at least 1 "
                         "(--workers 1 runs in this process).")
    return int(workers)


# --------------------------------------------------------------------------- Dask
def check_timeout(timeout) -> float:
    """The scheduler timeout: ``timeout``, else ``$TRACKBOOK_DASK_TIMEOUT``, else 5 s."""
    src = "scheduler_timeout"
    if timeout is None:
        timeout, src = os.environ.get(ENV_TIMEOUT) or DEFAULT_TIMEOUT, ENV_TIMEOUT
    try:
        t = float(timeout)
    except (TypeError, ValueError):
        t = float("nan")
    if not (t > 0 and math.isfinite(t)):
        raise ValueError(f"{src} = {timeout!r}: give the Dask scheduler timeout in seconds, "
                         "a positive number (e.g. 5).")
    return t


def _recv(sock, n: int, deadline: float) -> bytes:
    buf = b""
    while len(buf) < n:
        left = deadline - time.monotonic()
        if left <= 0:
            raise socket.timeout
        sock.settimeout(left)
        chunk = sock.recv(n - len(buf))
        if not chunk:
            raise ConnectionResetError
        buf += chunk
    return buf


def check_scheduler(address: str, timeout: float = DEFAULT_TIMEOUT) -> None:
    """Check that a Dask scheduler answers at ``address`` before anything large is read.

    A Dask server sends its handshake (a small msgpack message naming ``pickle-protocol``,
    framed by an 8-byte length) as soon as a connection opens. This reads at most that
    message, with a deadline of ``timeout`` seconds over connect and read, so a refused,
    unresolvable, silent or non-Dask peer (an HTTP server, whose words would be read as a
    length of exabytes) is a ``ValueError`` of one line within the timeout. Addresses other
    than ``tcp://`` (``inproc://`` of an in-process cluster, ``tls://``, ``ucx://``) are
    left to Dask.
    """
    addr = str(address).strip()
    proto, sep, rest = addr.partition("://")
    if not sep:
        proto, rest = "tcp", addr
    if proto != "tcp":
        return
    fix = "write tcp://HOST:PORT, e.g. --scheduler tcp://10.0.0.5:8786"
    host, sep, port = rest.rstrip("/").rpartition(":")
    host = host.strip("[]")
    if not sep or not host or not port.isdigit() or not 0 < int(port) < 65536:
        raise ValueError(f"scheduler {address!r} is not an address; {fix}.")
    where = f"scheduler {addr}"
    hint = (f"check that `dask scheduler` runs there and the port is right (or raise the "
            f"limit: --scheduler-timeout / ${ENV_TIMEOUT}).")
    try:
        socket.getaddrinfo(host, int(port), type=socket.SOCK_STREAM)
    except (socket.gaierror, UnicodeError) as e:
        raise ValueError(f"{where}: cannot resolve host {host!r} "
                         f"({getattr(e, 'strerror', None) or e}); {fix}.") from None
    deadline = time.monotonic() + timeout
    try:
        sock = socket.create_connection((host, int(port)), timeout=timeout)
    except socket.timeout:
        raise ValueError(f"{where}: no connection within {timeout:g} s; {hint}") from None
    except OSError as e:
        raise ValueError(f"{where}: cannot connect ({e.strerror or e}); {hint}") from None
    with sock:
        try:
            (n,) = struct.unpack("<Q", _recv(sock, 8, deadline))
            body = _recv(sock, n, deadline) if 0 < n <= 1 << 16 else b""
        except socket.timeout:
            raise ValueError(f"{where}: connected, but no Dask handshake within {timeout:g} s "
                             f"(a silent service, or not a Dask scheduler); {hint}") from None
        except OSError:
            raise ValueError(f"{where}: the peer closed the connection without a Dask "
                             f"handshake; {hint}") from None
    if b"pickle-protocol" not in body:
        raise ValueError(f"{where}: the service there does not speak Dask (its first bytes "
                         f"are not a Dask handshake); {hint}")


def _work_dask(group, multi_seed, imports=()):
    # a Dask worker is a process of its own on a core of its own, like a local worker; user
    # trackers are loaded here, in the worker, before the runs need them (idempotent). An
    # error is described here, where its traceback is (see _portable).
    try:
        runs.load_imports(imports)
        one_thread_per_worker()
        return runs.run_group(group, None, multi_seed)
    except BaseException as e:  # noqa: BLE001  SystemExit of a user file included
        raise _portable(e) from None


class ClusterLost(ConnectionError):
    """The Dask scheduler went away, or no worker was left to run the bench's runs."""


#: Seconds between two looks at the cluster while waiting for results.
POLL = 0.5


def _live_workers(client) -> int:
    """Workers the scheduler knows now (one round trip), or -1 when it does not answer."""
    try:
        return len(client.nthreads())
    except Exception:  # noqa: BLE001  a closed connection, in whatever form Dask raises it
        return -1


def _execute_dask(tasks, out, finished, scheduler, multi_seed, imports=(), timeout=None):
    """Run the groups on a Dask cluster and save their runs here as they come back.

    Waiting is bounded: when the scheduler stops answering, or no worker is left for
    ``timeout`` seconds (every worker died), the bench stops with :class:`ClusterLost`;
    the runs saved so far are read back by the next bench, local or on a cluster.
    """
    import logging

    try:
        from distributed import Client, wait
    except ImportError:
        raise ImportError("--scheduler needs Dask: pip install 'trackbook[dask]' "
                          "(dask[distributed]).") from None
    timeout = check_timeout(timeout)
    resume = (f"finished runs are saved in {out}/runs; run the same command again (without "
              "--scheduler to run here) to resume.")
    # Dask logs a lost connection (with tracebacks) on stderr from several loggers; the bench
    # says it in one line
    logs = [logging.getLogger(n) for n in ["distributed", *logging.root.manager.loggerDict]
            if n == "distributed" or n.startswith("distributed.")]
    levels = [lg.level for lg in logs]
    for lg in logs:
        lg.setLevel(logging.CRITICAL + 1)
    if isinstance(scheduler, Client):
        client = scheduler
    else:
        check_scheduler(scheduler, timeout)
        try:
            client = Client(scheduler, timeout=timeout)
        except (OSError, TimeoutError) as e:
            _restore(logs, levels)
            raise ValueError(f"scheduler {scheduler}: cannot connect a Dask client within "
                             f"{timeout:g} s ({' '.join(str(e).split())}).") from None
    where = f"scheduler {getattr(client, 'scheduler', None) and client.scheduler.address}"
    try:
        n = max(1, _live_workers(client))
        gs = groups(tasks, n)
        imports = list(imports)
        futs = {client.submit(_work_dask, g, multi_seed, imports, pure=False): i
                for i, g in enumerate(gs)}
        pending = set(futs)
        no_worker_since = None
        try:
            while pending:
                gone = client.status not in ("running", "newly-created")
                try:
                    done, pending = wait(pending, timeout=POLL, return_when="FIRST_COMPLETED")
                except TimeoutError:
                    done = set()
                except Exception:  # noqa: BLE001  the futures were cancelled: connection lost
                    done, gone = set(), True
                for f in done:
                    if f.status in ("cancelled", "lost"):
                        gone = True
                        continue
                    try:
                        recs = f.result()
                    except UserCodeError:
                        raise
                    except Exception as e:  # noqa: BLE001
                        if type(e).__name__ == "KilledWorker":
                            raise ClusterLost(f"{where}: a group of runs killed every worker "
                                              f"that took it (out of memory?); {resume}") from None
                        if client.status != "running" or type(e).__name__.endswith(
                                ("CancelledError", "CommClosedError")):
                            gone = True
                            continue
                        raise
                    g = gs[futs[f]]
                    for t, r in zip(g, recs):
                        runs.save_run(t, r, out)
                    finished(g, recs)
                if gone or any(f.status in ("cancelled", "lost") for f in pending):
                    raise ClusterLost(f"{where} went away (stopped, or the connection "
                                      f"broke); {resume}")
                if done:
                    no_worker_since = None
                    continue
                live = _live_workers(client)
                if live < 0:
                    raise ClusterLost(f"{where} stopped answering; {resume}")
                if live > 0:
                    no_worker_since = None
                elif no_worker_since is None:
                    no_worker_since = time.monotonic()
                elif time.monotonic() - no_worker_since > timeout:
                    raise ClusterLost(f"{where} has no worker left (for {timeout:g} s: they "
                                      f"died or were stopped); start workers with `dask "
                                      f"worker {client.scheduler.address}`; {resume}")
        except BaseException:
            with contextlib.suppress(Exception):
                client.cancel(list(futs))
            raise
    finally:
        if client is not scheduler:
            with contextlib.suppress(Exception):
                client.close(timeout=timeout)
        _restore(logs, levels)


def _restore(logs, levels) -> None:
    for lg, level in zip(logs, levels):
        lg.setLevel(level)
