"""The HTML book's playgrounds: every clip x tracker's runs, computed when the book is built,
over several seeds, written as small script files that the page loads when the reader picks
them.

A playground's page holds only its configuration; each run (one clip, one tracker, one set of
knob values: seed ``s0``'s boxes and state, and the spread over the seeds) and each chunk of a
clip's frames is one file ``tbpg-<hash>.js`` that calls ``window.tbPlaygroundRegister(name,
data)``. A ``<script>`` tag loads it, which works from ``file://`` and over http alike (a
``fetch`` of a local file does not). The files are written to :func:`store` (``files/``), and
the book's ``sphinx_playground`` extension copies those a page names into the book's
``_static``.

The runs go to worker processes (two, spawned) and are kept on disk under :func:`store`
(``runs/``), keyed by the tracker's code (:func:`trackbook.evaluation.runs.code_fingerprint`),
the clip's bytes (:func:`trackbook.evaluation.runs.fingerprint`), the values, seed and number
of frames, so a rebuild reuses every run whose inputs did not change.
"""

from __future__ import annotations

import concurrent.futures as cf
import functools
import hashlib
import importlib.util
import json
import math
import multiprocessing
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

from trackbook import clips as _clips
from trackbook import trackers as _trackers
from trackbook.evaluation import runs as _runs
from trackbook.evaluation.runner import evaluate_many
from trackbook.playground import data as D

#: the environment variable naming the directory of run files and cached runs (the Sphinx
#: extension sets it under the build output before the chapters execute)
OUT_ENV = "TRACKBOOK_PLAYGROUND_DIR"
#: every file the page loads on demand is named ``PREFIX + hash + ".js"``
PREFIX = "tbpg-"
#: most bytes of one run file (or one chunk of frames)
MAX_RUN_BYTES = 300_000
#: frames per file of a clip's frames
CHUNK_FRAMES = 15
#: frames wider than this are shrunk before they are written (the viewer draws them at most
#: this wide; boxes stay in the clip's pixels)
MAX_FRAME_WIDTH = 480
#: seeds per run (from the playground's seed on); a pair whose boxes are the same for the
#: first two is run with one seed only
N_SEEDS = 3
#: worker processes of the precompute
WORKERS = 2


def store() -> Path:
    """Where run files (``files/``) and cached runs (``runs/``) go: ``$TRACKBOOK_PLAYGROUND_DIR``
    (the book build's), or a folder in the temporary directory."""
    d = os.environ.get(OUT_ENV)
    return Path(d) if d else Path(tempfile.gettempdir()) / "trackbook-playground"


def _digest(text: str, n: int = 20) -> str:
    return hashlib.blake2b(text.encode("utf-8"), digest_size=16).hexdigest()[:n]


def script_text(name: str, data) -> str:
    """The text of one run file: a call of the page's registration function with ``data``."""
    js = json.dumps(data, separators=(",", ":")).replace("</", "<\\/")
    return f'(window.tbPlaygroundRegister||function(){{}})("{name}",{js});\n'


def write_script(data, cap: int = MAX_RUN_BYTES, folder=None, name: str | None = None) -> str:
    """Write ``data`` as a run file named by the hash of its content (or ``name``, a name
    :func:`plan_names` gave beforehand); return the file name.

    Raises ``ValueError`` when the file would exceed ``cap`` bytes (the caller thins it)."""
    js = json.dumps(data, separators=(",", ":"), sort_keys=True)
    name = name or f"{PREFIX}{_digest(js)}.js"
    text = script_text(name, data)
    size = len(text.encode("utf-8"))
    if size > cap:
        raise ValueError(f"run file {name} would be {size} bytes, over the {cap}-byte cap; "
                         "send fewer particles or frames per file.")
    path = Path(folder or store() / "files") / name
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        _runs.write_atomic(path, text)
    return name


def write_run(payload: dict, cap: int = MAX_RUN_BYTES, folder=None,
              name: str | None = None) -> str:
    """:func:`write_script` for a run payload; over ``cap`` its drawn state is left out
    (boxes, IoU and scores stay)."""
    try:
        return write_script(payload, cap, folder, name)
    except ValueError:
        return write_script({**payload, "state": {}}, cap, folder, name)


def write_frames(clip, n: int, per: int = CHUNK_FRAMES, cap: int = MAX_RUN_BYTES,
                 folder=None) -> list:
    """The first ``n`` frames of ``clip`` as files of ``per`` JPEG frames each (at most
    ``MAX_FRAME_WIDTH`` px wide, quality lowered until a file fits ``cap``); returns the file
    names in order."""
    import cv2

    w = clip.size[0]
    shrink = min(1.0, MAX_FRAME_WIDTH / w) if w else 1.0

    def img(i):       # the viewer draws a frame at most MAX_FRAME_WIDTH px wide
        f = clip.frames[i]
        if shrink < 1.0:
            f = cv2.resize(f, None, fx=shrink, fy=shrink, interpolation=cv2.INTER_AREA)
        return f

    names = []
    for start in range(0, n, per):
        stop = min(n, start + per)
        for q in (D.JPEG_QUALITY, 60, 50, 40, 30, 20):
            frames = [D.jpeg(img(i), q) for i in range(start, stop)]
            try:
                names.append(write_script({"frames": frames, "start": start}, cap, folder))
                break
            except ValueError:
                if q == 20:
                    raise
    return names


def write_png(png: bytes, folder=None) -> str:
    """A picture (the no-JavaScript fallback) as a file named by its content."""
    name = f"{PREFIX}{hashlib.blake2b(png, digest_size=10).hexdigest()}.png"
    path = Path(folder or store() / "files") / name
    if not path.exists():
        _runs.write_atomic(path, png)
    return name


def to_files(payload: dict, per: int = CHUNK_FRAMES, folder=None) -> dict:
    """A page payload whose runs and frames sit inline (the animations') with them moved to
    files: ``runs`` becomes ``files`` (run key -> file name) and each clip's ``frames`` become
    ``chunks`` of ``per`` frames (fewer when a file would pass the cap)."""
    if "runs" not in payload:
        return payload
    clips = {}
    for key, c in payload["clips"].items():
        c = dict(c)
        frames = c.pop("frames", None)
        if frames is not None:
            step = per
            while True:
                try:
                    c["chunks"] = [write_script({"frames": frames[i:i + step], "start": i},
                                                folder=folder)
                                   for i in range(0, len(frames), step)]
                    break
                except ValueError:
                    if step == 1:
                        raise
                    step = max(1, step // 2)
            c.update(n=len(frames), per=step)
        clips[key] = c
    files = {k: write_run(r, folder=folder) for k, r in payload["runs"].items()}
    return {**{k: v for k, v in payload.items() if k != "runs"}, "clips": clips,
            "files": files}


# ----------------------------------------------------------------------------- the runs
@functools.lru_cache(maxsize=4)
def _clip(key):
    # a worker runs many knob values of the same few clips: load each once, and keep only
    # the last few (a process that precomputes many pages does not hold every clip)
    return _clips.load(key)


def run_seeds(tracker: str, clip, values: dict, n: int, seeds, init_box=None,
              state_seed=None) -> list:
    """Track ``clip`` with one tracker per seed in lockstep; one dict per seed: ``seed``,
    ``boxes`` (0.1 px), ``iou``, ``auc`` and, for ``state_seed``, ``payload`` (what the viewer
    draws). A combination the tracker refuses gives ``[{"error": why}]``."""
    clip = _clip(clip) if isinstance(clip, str) else clip
    params = {k: tuple(v) if isinstance(v, list) else v for k, v in values.items()}
    states, first = [], []

    def on_frame(i, t, f, b):
        if not first:
            first.append(id(t))
        if id(t) == first[0] and state_seed is not None:
            states.append(D.snapshot(t.state()))

    seeds = list(seeds)
    if state_seed is not None and seeds[0] != state_seed:
        raise ValueError("state_seed must be the first of seeds.")
    try:
        rs = evaluate_many([(tracker, s, params) for s in seeds], clip, max_frames=n,
                           init_box=init_box, on_frame=on_frame)
    except ValueError as e:
        return [{"error": str(e)}]
    out = []
    for s, r in zip(seeds, rs):
        p = D.result_payload(r, clip, values, states if s == state_seed else [], n, tracker)
        one = {"seed": s, "boxes": p["boxes"], "iou": p["iou"],
               "auc": float(r.scores.get("auc", float("nan")))}
        if s == state_seed:
            one["payload"] = p
        out.append(one)
    return out


def _job(args):
    return run_seeds(*args)


def _worker_init(path):
    sys.path[:0] = [p for p in path if p not in sys.path]
    from trackbook.evaluation.parallel import one_thread_per_worker

    one_thread_per_worker()


def _importable(tracker: str) -> bool:
    """Whether a fresh process finds ``tracker`` by importing its module (a tracker a
    notebook cell defines is not: it runs in this process)."""
    mod = getattr(_trackers.get(tracker), "__module__", "__main__")
    if mod == "__main__":
        return False
    try:
        return importlib.util.find_spec(mod) is not None
    except (ImportError, ValueError):
        return False


class Runner:
    """Runs jobs ``(tracker, clip_key, values, n, seeds, init_box, state_seed)`` and keeps each
    seed's result on disk; ``known(job, seed)`` may give a result already computed (e.g. the
    run the Jupyter half made)."""

    def __init__(self, clip_objs: dict, workers: int = WORKERS, known=None):
        self.clip_objs = clip_objs
        self.workers = workers
        self.known = dict(known or {})
        self._fp: dict = {}

    @staticmethod
    def known_key(tracker, clip_key, values, n, seed):
        """The key of :attr:`known`: a run given rather than computed."""
        return json.dumps([tracker, clip_key, values, n, seed], sort_keys=True, default=str)

    def _key(self, tracker, clip_key, values, n, seed, init_box, state):
        if clip_key not in self._fp:
            self._fp[clip_key] = _runs.fingerprint(self.clip_objs[clip_key])
        try:
            code = _runs.code_fingerprint(tracker)
        except Exception:     # noqa: BLE001  a tracker without readable code is not cached
            return None
        return _digest(json.dumps([tracker, code, self._fp[clip_key], values, n, seed,
                                   None if init_box is None else [float(v) for v in init_box],
                                   state], sort_keys=True, default=str), 32)

    def _path(self, key):
        return store() / "runs" / f"{key}.json"

    def run(self, jobs: list) -> list:
        """One list of per-seed dicts per job, in order (cached seeds read back)."""
        out = [dict() for _ in jobs]
        todo = []
        for j, (t, c, values, n, seeds, box, state_seed) in enumerate(jobs):
            missing = []
            for s in seeds:
                given = self.known.get(self.known_key(t, c, values, n, s))
                if given is not None and (s != state_seed or "payload" in given):
                    out[j][s] = given
                    continue
                key = self._key(t, c, values, n, s, box, s == state_seed)
                p = self._path(key) if key else None
                if p is not None and p.exists():
                    out[j][s] = json.loads(p.read_text())
                else:
                    missing.append(s)
            if missing:
                ss = state_seed if state_seed in missing else None
                missing.sort(key=lambda s: s != ss)
                todo.append((j, (t, c, values, n, missing, box, ss)))
        remote = [(j, a) for j, a in todo if _importable(a[0])]
        local = [(j, a) for j, a in todo if not _importable(a[0])]
        done = []
        if len(remote) > 1 and self.workers > 1:
            ctx = multiprocessing.get_context("spawn")
            with cf.ProcessPoolExecutor(self.workers, mp_context=ctx, initializer=_worker_init,
                                        initargs=(list(sys.path),)) as pool:
                # the longest runs first, so that the two workers finish together
                order = sorted(remote, key=lambda ja: -len(ja[1][4]) * self._cost(ja[1]))
                futs = {pool.submit(_job, a): (j, a) for j, a in order}
                for f in cf.as_completed(futs):
                    j, a = futs[f]
                    res = f.result()
                    if res and "unknown tracker" in res[0].get("error", ""):
                        local.append((j, a))   # registered here only (e.g. by a test)
                    else:
                        done.append((j, a, res))
        else:
            local = remote + local
        for j, a in local:
            c = self.clip_objs[a[1]]
            done.append((j, a, run_seeds(a[0], c, *a[2:])))
        for j, a, res in done:
            t, c, values, n, seeds, box, ss = a
            if res and "error" in res[0]:
                out[j] = {"error": res[0]["error"]}
                continue
            for one in res:
                out[j][one["seed"]] = one
                key = self._key(t, c, values, n, one["seed"], box, one["seed"] == ss)
                if key:
                    _runs.write_atomic(self._path(key), json.dumps(one))
        return [o if "error" in o else [o[s] for s in jobs[j][4]] for j, o in enumerate(out)]

    @staticmethod
    def _cost(a):
        values = a[2]
        return max(1.0, float(values.get("n_particles", 100)) / 100.0) * (a[3] or 100)


def book_runs(clip_objs: dict, trackers: list, knobs: dict, defaults: dict, n_of: dict,
              boxes: dict, seed: int = 0, known=None, workers: int = WORKERS,
              names: dict | None = None) -> dict:
    """Every run a playground's page offers, written as run files: ``{run key: file name}``
    (``clip|tracker|`` at defaults, ``clip|tracker|knob#i`` with the knob at its i-th sample
    of ``knobs[tracker]`` and the others at ``defaults[tracker]``), plus ``"deterministic"``,
    the pairs ``clip|tracker`` whose boxes did not depend on the seed.

    Each pair first runs at its defaults with two seeds; if their boxes are the same the pair
    is deterministic and each knob value runs once, otherwise every run has ``N_SEEDS``
    seeds. A pair whose clip has no first box (``boxes[c] is False``) is left out. ``names``
    (``{run key: file name}``, :func:`plan_names`) names the files instead of their content."""
    runner = Runner(clip_objs, workers, known)
    names = names or {}
    seeds = [seed + i for i in range(N_SEEDS)]
    pairs = [(c, t) for t in trackers for c in clip_objs if boxes.get(c) is not False]
    first = runner.run([(t, c, defaults[t], n_of[c], seeds[:2], boxes.get(c), seed)
                        for c, t in pairs])
    det, jobs, keys = {}, [], []
    for (c, t), r in zip(pairs, first):
        box, n = boxes.get(c), n_of[c]
        if isinstance(r, dict):
            continue
        det[(c, t)] = r[0]["boxes"] == r[1]["boxes"]
        if not det[(c, t)]:
            jobs.append((t, c, defaults[t], n, seeds[2:], box, None))
            keys.append((c, t, f"{c}|{t}|", r))
        for k in knobs[t]:
            for i, v in enumerate(k["samples"]):
                if v != k["default"]:
                    jobs.append((t, c, {**defaults[t], k["name"]: v}, n,
                                 seeds[:1] if det[(c, t)] else seeds, box, seed))
                    keys.append((c, t, f"{c}|{t}|{k['name']}#{i}", None))
    out = {"runs": {}, "deterministic": sorted(f"{c}|{t}" for (c, t), d in det.items() if d)}
    for (c, t), r in zip(pairs, first):
        key = f"{c}|{t}|"
        if isinstance(r, dict):
            out["runs"][key] = write_script({"error": r["error"]}, name=names.get(key))
            for k in knobs[t]:       # the pair's knob runs share the refusal
                for i, v in enumerate(k["samples"]):
                    kk = f"{c}|{t}|{k['name']}#{i}"
                    if v != k["default"]:
                        out["runs"][kk] = write_script({"error": r["error"]}, name=names.get(kk))
        elif det[(c, t)]:
            out["runs"][key] = _finish(r, True, names.get(key))
    for (c, t, key, head), r in zip(keys, runner.run(jobs)):
        if isinstance(r, dict):
            out["runs"][key] = write_script({"error": r["error"]}, name=names.get(key))
        else:
            out["runs"][key] = _finish((head or []) + r, det[(c, t)], names.get(key))
    return out


def _finish(results: list, deterministic: bool, name=None) -> str:
    payload = dict(results[0]["payload"])
    payload["seeds"] = seeds_entry(results, deterministic)
    payload["spread"] = spread_text(payload["seeds"])
    return write_run(payload, name=name)


# ------------------------------------------------- the book build: runs in the background
#: set (by the Sphinx extension) to run a playground's precompute in a background process
#: while the next chapters execute; the extension waits for it before copying the files
BACKGROUND_ENV = "TRACKBOOK_PLAYGROUND_BACKGROUND"


def _format() -> str:
    """A hash of the code that writes run files: a change renames every planned file."""
    return _digest("".join(Path(m.__file__).read_text(encoding="utf-8") for m in (D, sys.modules[
        __name__])))


def run_keys(clip_objs: dict, trackers: list, knobs: dict, boxes: dict) -> list:
    """``(run key, clip, tracker, knob name or None, value)`` of every run of a page."""
    out = []
    for t in trackers:
        for c in clip_objs:
            if boxes.get(c) is False:
                continue
            out.append((f"{c}|{t}|", c, t, None, None))
            for k in knobs[t]:
                for i, v in enumerate(k["samples"]):
                    if v != k["default"]:
                        out.append((f"{c}|{t}|{k['name']}#{i}", c, t, k["name"], v))
    return out


def plan_names(clip_objs: dict, trackers: list, knobs: dict, defaults: dict, n_of: dict,
               boxes: dict, seed: int = 0) -> dict:
    """``{run key: file name}`` before any run: each name hashes what the run depends on (the
    tracker's code, the clip's bytes, the values, frames, seeds, first box and the writer's
    code), so a page can name files that are still being computed."""
    fmt, fps = _format(), {}
    out = {}
    for key, c, t, name, v in run_keys(clip_objs, trackers, knobs, boxes):
        if c not in fps:
            fps[c] = _runs.fingerprint(clip_objs[c])
        values = dict(defaults[t]) if name is None else {**defaults[t], name: v}
        b = boxes.get(c)
        out[key] = PREFIX + _digest(json.dumps(
            [t, _runs.code_fingerprint(t), fps[c], values, n_of[c], seed, N_SEEDS,
             None if b is None else [float(x) for x in b], fmt], sort_keys=True,
            default=str)) + ".js"
    return out


def background_ok(trackers) -> bool:
    """Whether this playground's runs may go to a background process: asked for by the book
    build, on a system with ``fcntl`` (the processes take turns), for trackers a fresh
    process can import."""
    if os.environ.get(BACKGROUND_ENV) != "1":
        return False
    try:
        import fcntl  # noqa: F401
    except ImportError:
        return False
    return all(_importable(t) for t in trackers)


def book_files(clip_objs: dict, trackers: list, knobs: dict, defaults: dict, n_of: dict,
               boxes: dict, seed: int = 0, known=None, workers: int = WORKERS) -> dict:
    """``{run key: file name}`` of a page: computed now (:func:`book_runs`), or, during the
    book build (:func:`background_ok`), by a background process started here, whose files
    the Sphinx extension waits for (:func:`wait_background`)."""
    if not background_ok(trackers):
        return book_runs(clip_objs, trackers, knobs, defaults, n_of, boxes, seed, known,
                         workers)["runs"]
    names = plan_names(clip_objs, trackers, knobs, defaults, n_of, boxes, seed)
    if all((store() / "files" / n).exists() for n in names.values()):
        return names
    import pickle
    import subprocess

    pending = store() / "pending"
    pending.mkdir(parents=True, exist_ok=True)
    job = pending / f"{_digest(json.dumps(sorted(names.values())))}.pkl"
    plan = {"clips": list(clip_objs), "trackers": trackers, "knobs": knobs,
            "defaults": defaults, "n_of": n_of, "boxes": boxes, "seed": seed,
            "known": known or {}, "workers": workers, "names": names}
    _runs.write_atomic(job, pickle.dumps(plan))
    log = open(job.with_suffix(".log"), "w")   # noqa: SIM115  the child writes it
    p = subprocess.Popen([sys.executable, "-m", __name__, str(job)], stdout=log,
                         stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                         start_new_session=True, env={**os.environ, "PYTHONPATH": os.pathsep.join(
                             [p for p in sys.path if p])})
    log.close()
    _runs.write_atomic(job.with_suffix(".pid"), str(p.pid))
    return names


def _background(job: Path) -> None:
    """The background process: wait for the store's lock (one precompute at a time), run the
    plan, and remove the job file (its ``.log`` stays on failure)."""
    import fcntl
    import pickle

    plan = pickle.loads(job.read_bytes())
    os.nice(5)       # the pages still executing go first: this only fills the idle core
    with open(store() / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        objs = {c: _clips.load(c) for c in plan["clips"] if plan["boxes"].get(c) is not False}
        book_runs(objs, plan["trackers"], plan["knobs"], plan["defaults"], plan["n_of"],
                  plan["boxes"], plan["seed"], plan["known"], plan["workers"], plan["names"])
    job.unlink()
    for ext in (".log", ".pid"):
        job.with_suffix(ext).unlink(missing_ok=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:       # a finished child of this process that nobody waited for is a zombie
        return Path(f"/proc/{pid}/stat").read_text().split()[2] != "Z"
    except OSError:
        return True


def wait_background(folder=None, poll: float = 0.5) -> None:
    """Wait until every background precompute under ``folder`` (the store) has finished;
    raises ``RuntimeError`` with its log when one stopped without finishing."""
    import time

    pending = Path(folder or store()) / "pending"
    while True:
        jobs = sorted(pending.glob("*.pkl")) if pending.is_dir() else []
        if not jobs:
            return
        for job in jobs:
            pid_file = job.with_suffix(".pid")
            if not pid_file.exists():
                continue
            if not _alive(int(pid_file.read_text() or 0)) and job.exists():
                log = job.with_suffix(".log")
                text = log.read_text(errors="replace")[-3000:] if log.exists() else ""
                job.unlink()
                pid_file.unlink(missing_ok=True)
                raise RuntimeError(f"a playground's background precompute stopped without "
                                   f"finishing ({job.name}); its output:\n{text}")
        time.sleep(poll)


def seed_summary(seeds, ious, aucs, deterministic: bool) -> dict:
    """The ``seeds`` entry of a run payload: per frame the least and the greatest IoU over
    the seeds' runs (``None`` where no seed has one), and each seed's AUC.

    ``ious`` holds one IoU list per seed (``None`` entries for frames without ground truth);
    ``deterministic`` says the boxes were found identical for two seeds, so one run stands
    for every seed."""
    seeds, aucs = [int(s) for s in seeds], [float(a) for a in aucs]
    if not (len(seeds) == len(ious) == len(aucs)) or not seeds:
        raise ValueError(f"seed_summary needs one IoU list and one AUC per seed; got "
                         f"{len(seeds)} seeds, {len(ious)} IoU lists, {len(aucs)} AUCs.")
    n = max(len(i) for i in ious)
    a = np.full((len(ious), n), np.nan)
    for k, v in enumerate(ious):
        a[k, :len(v)] = [np.nan if x is None else x for x in v]
    seen = np.isfinite(a).any(axis=0)
    lo = np.where(seen, np.nanmin(np.where(np.isfinite(a), a, np.inf), axis=0), np.nan)
    hi = np.where(seen, np.nanmax(np.where(np.isfinite(a), a, -np.inf), axis=0), np.nan)
    band = lambda b: [None if not math.isfinite(x) else round(float(x), 3) for x in b]  # noqa: E731
    return {"seeds": seeds, "iou_lo": band(lo), "iou_hi": band(hi),
            "auc": [round(x, 4) for x in aucs], "deterministic": bool(deterministic)}


def seeds_entry(results: list, deterministic: bool) -> dict:
    """The run payload's ``seeds`` entry from :meth:`Runner.run`'s per-seed dicts."""
    return seed_summary([r["seed"] for r in results],
                          [r["iou"] or [] for r in results],
                          [r["auc"] for r in results], deterministic)


def spread_text(seeds: dict) -> str:
    """``"AUC 0.52 (0.47–0.58 over 3 seeds)"``, or the deterministic case's words."""
    a = [x for x in seeds["auc"] if x == x]
    if not a:
        return ""
    if seeds["deterministic"]:
        return f"AUC {a[0]:.2f} (same boxes for every seed)"
    mean = sum(a) / len(a)
    return f"AUC {mean:.2f} ({min(a):.2f}\u2013{max(a):.2f} over {len(a)} seeds)"


__all__ = ["BACKGROUND_ENV", "CHUNK_FRAMES", "MAX_RUN_BYTES", "N_SEEDS", "OUT_ENV", "PREFIX",
           "Runner", "book_files", "book_runs", "plan_names", "run_seeds", "to_files",
           "wait_background", "write_png", "script_text", "seed_summary", "seeds_entry",
           "spread_text", "store", "write_frames", "write_run", "write_script"]


if __name__ == "__main__":
    _background(Path(sys.argv[1]))
