"""The HTML book's playgrounds: every clip x tracker's runs, computed when the book is built,
over several seeds, written as small script files that the page loads when the reader picks
them.

A playground's page holds only its configuration; each run (one clip, one tracker, one set of
knob values: seed ``s0``'s boxes and state, and the spread over the seeds) and each chunk of a
clip's frames is one file ``tbpg-<hash>.js`` that calls ``window.tbPlaygroundRegister(name,
data)``. A ``<script>`` tag loads it, which works from ``file://`` and over http alike (a
``fetch`` of a local file does not). The files are written to :func:`store` (``files/``), and
``trackbook.sphinx_playground`` copies those a page names into the book's ``_static``.

The runs go to worker processes (two, spawned) and are kept on disk under :func:`store`
(``runs/``), keyed by the tracker's code (:func:`trackbook.evaluation.runs.code_fingerprint`),
the clip's bytes (:func:`trackbook.evaluation.runs.fingerprint`), the values, seed and number
of frames, so a rebuild reuses every run whose inputs did not change.
"""

from __future__ import annotations

import concurrent.futures as cf
import hashlib
import importlib.util
import json
import multiprocessing
import os
import sys
import tempfile
from pathlib import Path

from .. import clips as _clips
from .. import trackers as _trackers
from ..evaluation import runs as _runs
from ..evaluation.runner import evaluate_many
from . import data as D

#: the environment variable naming the directory of run files and cached runs (the Sphinx
#: extension sets it under the build output before the chapters execute)
OUT_ENV = "TRACKBOOK_PLAYGROUND_DIR"
#: every file the page loads on demand is named ``PREFIX + hash + ".js"``
PREFIX = "tbpg-"
#: most bytes of one run file (or one chunk of frames)
MAX_RUN_BYTES = 300_000
#: frames per file of a clip's frames
CHUNK_FRAMES = 20
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


def write_script(data, cap: int = MAX_RUN_BYTES, folder=None) -> str:
    """Write ``data`` as a run file named by the hash of its content; return the file name.

    Raises ``ValueError`` when the file would exceed ``cap`` bytes (the caller thins it)."""
    js = json.dumps(data, separators=(",", ":"), sort_keys=True)
    name = f"{PREFIX}{_digest(js)}.js"
    text = script_text(name, data)
    size = len(text.encode("utf-8"))
    if size > cap:
        raise ValueError(f"run file {name} would be {size} bytes, over the {cap}-byte cap; "
                         "send fewer particles or frames per file.")
    path = Path(folder or store() / "files") / name
    if not path.exists():
        _runs.write_atomic(path, text)
    return name


def write_run(payload: dict, cap: int = MAX_RUN_BYTES, folder=None) -> str:
    """:func:`write_script` for a run payload; over ``cap`` its drawn state is left out
    (boxes, IoU and scores stay)."""
    try:
        return write_script(payload, cap, folder)
    except ValueError:
        return write_script({**payload, "state": {}}, cap, folder)


def write_frames(clip, n: int, per: int = CHUNK_FRAMES, cap: int = MAX_RUN_BYTES,
                 folder=None) -> list:
    """The first ``n`` frames of ``clip`` as files of ``per`` JPEG frames each (quality
    lowered until a file fits ``cap``); returns the file names in order."""
    names = []
    for start in range(0, n, per):
        stop = min(n, start + per)
        for q in (D.JPEG_QUALITY, 60, 50, 40, 30, 20):
            frames = [D.jpeg(clip.frames[i], q) for i in range(start, stop)]
            try:
                names.append(write_script({"frames": frames, "start": start}, cap, folder))
                break
            except ValueError:
                if q == 20:
                    raise
    return names


# ----------------------------------------------------------------------------- the runs
_WORKER_CLIPS: dict = {}


def _clip(key):
    if key not in _WORKER_CLIPS:
        _WORKER_CLIPS[key] = _clips.load(key)
    return _WORKER_CLIPS[key]


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
    from ..evaluation.parallel import one_thread_per_worker

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
              boxes: dict, seed: int = 0, known=None, workers: int = WORKERS) -> dict:
    """Every run a playground's page offers, written as run files: ``{run key: file name}``
    (``clip|tracker|`` at defaults, ``clip|tracker|knob#i`` with the knob at its i-th sample
    of ``knobs[tracker]`` and the others at ``defaults[tracker]``), plus ``"deterministic"``,
    the pairs ``clip|tracker`` whose boxes did not depend on the seed.

    Each pair first runs at its defaults with two seeds; if their boxes are the same the pair
    is deterministic and each knob value runs once, otherwise every run has ``N_SEEDS``
    seeds. A pair whose clip has no first box (``boxes[c] is False``) is left out."""
    runner = Runner(clip_objs, workers, known)
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
        if isinstance(r, dict):
            out["runs"][f"{c}|{t}|"] = write_script({"error": r["error"]})
        elif det[(c, t)]:
            out["runs"][f"{c}|{t}|"] = _finish(r, True)
    for (c, t, key, head), r in zip(keys, runner.run(jobs)):
        if isinstance(r, dict):
            out["runs"][key] = write_script({"error": r["error"]})
        else:
            out["runs"][key] = _finish((head or []) + r, det[(c, t)])
    return out


def _finish(results: list, deterministic: bool) -> str:
    payload = dict(results[0]["payload"])
    payload["seeds"] = seeds_entry(results, deterministic)
    payload["spread"] = spread_text(payload["seeds"])
    return write_run(payload)


def seeds_entry(results: list, deterministic: bool) -> dict:
    """The run payload's ``seeds`` entry from :meth:`Runner.run`'s per-seed dicts."""
    return D.seed_summary([r["seed"] for r in results],
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


__all__ = ["CHUNK_FRAMES", "MAX_RUN_BYTES", "N_SEEDS", "OUT_ENV", "PREFIX", "Runner",
           "book_runs", "run_seeds", "script_text", "seeds_entry", "spread_text", "store",
           "write_frames", "write_run", "write_script"]
