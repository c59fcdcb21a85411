"""The benchmark's unit of work, shared by the local and the Dask paths.

A :class:`Task` is one (tracker, clip, seed) run; :func:`run_group` runs tasks that share a
clip and writes each record with :func:`write_atomic`; :func:`load_run` reads a saved record
back when its key still matches. The key hashes everything a run's result depends on:

- the tracker's name, preset, params and seed, and ``max_frames``;
- the clip's identity (resolved path, or ``sample:<name>``) and :func:`fingerprint`, a hash of
  its ground truth and of the *bytes* of every image or video file it reads, so any rewrite of
  a frame (even one that keeps the file's size) re-runs it;
- :func:`code_fingerprint`, a hash of the tracker's code and of the library version, so an
  edited tracker re-runs and an unchanged one is reused.

:mod:`trackbook.evaluation.parallel` decides where groups run; :mod:`trackbook.evaluation.bench`
plans them and writes the tables. Neither imports the other's internals: both use this module.
"""

from __future__ import annotations

import ast
import dataclasses
import hashlib
import importlib.metadata
import json
import os
import re
import sys
import tempfile
import types
from pathlib import Path

import numpy as np

from .. import clips as _clips
from ..clips import samples as _samples
from . import metrics, protocol_bench
from .runner import evaluate, evaluate_many


def _umask() -> int:
    m = os.umask(0)
    os.umask(m)
    return m


def write_atomic(path, data: bytes | str) -> None:
    """Write ``data`` to ``path`` so that readers see the old file or the new one, never half.

    The file gets the mode an ordinary ``open`` would give (0644 under the usual umask 022),
    not ``mkstemp``'s 0600.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    mode = "wb" if isinstance(data, bytes) else "w"
    try:
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    except OSError as e:        # name the file being written, not a temporary name
        raise OSError(e.errno, e.strerror, str(path)) from None
    try:
        with os.fdopen(fd, mode) as f:
            f.write(data)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def load_imports(imports) -> None:
    """Import user tracker modules or ``.py`` files (each registers its trackers), through
    :func:`trackbook.trackers.plugins.load`; idempotent, so every worker may call it."""
    if not imports:
        return
    from ..trackers import plugins

    for spec in imports:
        plugins.load(spec)


# --------------------------------------------------------------------------- clip references
@dataclasses.dataclass(frozen=True)
class ClipRef:
    """What a worker needs to load one clip, and how the bench names and keys it.

    ``spec`` is what :func:`trackbook.clips.load` accepts (a sample name or a path) or a
    :class:`trackbook.clips.datasets.Sequence`; ``name`` is the clip's column in the tables
    (unique within one bench); ``identity`` is ``sample:<name>`` or the resolved path (with
    ``#<target>`` for one target of a multi-target sequence).
    """

    spec: object
    name: str
    identity: str
    target: str | None = None

    def load(self):
        """The :class:`~trackbook.clips.Clip` (for one target when ``target`` is set)."""
        if hasattr(self.spec, "load"):
            clip = self.spec.load()
        else:
            clip = _clips.load(self.spec)
        if self.target is not None and self.target in clip.targets and len(clip.targets) > 1:
            clip = dataclasses.replace(clip, groundtruth=clip.targets[self.target],
                                       targets={self.target: clip.targets[self.target]})
        if clip.name != self.name:
            clip = dataclasses.replace(clip, name=self.name)
        return clip


def _hash_file(h, path) -> None:
    with open(path, "rb") as f:
        while chunk := f.read(1 << 20):
            h.update(chunk)


def fingerprint(clip) -> str:
    """A hash of the clip's ground truth (every target) and of its frames' content: the bytes
    of every image file (with its name) or of the video file, or a generated clip's pixels.

    Hashing bytes (BLAKE2b) rather than names and sizes makes any rewrite of a frame re-run,
    including a same-size one (BMP and other uncompressed formats keep their size). The cost
    is one read of the clip's files per bench, usually from the page cache; the README's bench
    section gives a measured figure and the command that measures it.
    """
    h = hashlib.blake2b(digest_size=20)
    for k in sorted(clip.targets):
        h.update(k.encode())
        h.update(np.ascontiguousarray(np.asarray(clip.targets[k], dtype=np.float64)).tobytes())
    h.update(np.asarray(clip.groundtruth, dtype=np.float64).tobytes())
    fr = clip.frames
    h.update(str(len(fr)).encode())
    paths = getattr(fr, "paths", None)
    if paths is not None:
        for p in paths:
            h.update(f"{Path(p).name};".encode())
            _hash_file(h, p)
    elif getattr(fr, "path", None) is not None:
        _hash_file(h, fr.path)
    elif getattr(fr, "array", None) is not None:
        h.update(np.ascontiguousarray(fr.array).tobytes())
    else:
        for f in fr:
            h.update(np.ascontiguousarray(f).tobytes())
    return h.hexdigest()


# --------------------------------------------------------------------------- code fingerprint
_CODE: dict = {}


def _module_of(v):
    if isinstance(v, types.ModuleType):
        return v
    try:
        name = getattr(v, "__module__", None)
    except Exception:  # noqa: BLE001  an object whose attribute access fails
        return None
    return sys.modules.get(name) if isinstance(name, str) else None


def code_modules(cls) -> list:
    """The modules whose source decides what tracker class ``cls`` computes.

    The modules that define ``cls`` and each of its base classes (the tracker, the particle
    filter frame, ``Tracker``), and, one level down, the modules those reference by name:
    trackbook's own modules (the features, filters and learning code a tracker calls) and
    modules beside a user's tracker file (its helpers). Third-party and standard-library
    modules are left out (their versions, not their files, matter; OpenCV's is keyed apart).
    One level, not the whole library: an edit of an unrelated module (a figure, the CLI)
    does not throw away every saved run.
    """
    core = {}
    for k in cls.__mro__:
        m = sys.modules.get(k.__module__)
        if m is not None and getattr(m, "__file__", None) and k is not object:
            core[m.__name__] = m
    folders = {str(Path(m.__file__).resolve().parent) for m in core.values()
               if not (m.__name__ == "trackbook" or m.__name__.startswith("trackbook."))}
    found = dict(core)
    for m in core.values():
        for v in list(vars(m).values()):
            vm = _module_of(v)
            f = getattr(vm, "__file__", None) if vm is not None else None
            if not f or vm.__name__ in found:
                continue
            if (vm.__name__ == "trackbook" or vm.__name__.startswith("trackbook.")
                    or str(Path(f).resolve().parent) in folders):
                found[vm.__name__] = vm
    return [found[k] for k in sorted(found)]


def code_fingerprint(name: str, versions: bool = True) -> str:
    """A hash of the code behind tracker ``name``: the source of :func:`code_modules` (and of
    any ``.py`` script such a module names, e.g. the MIL child), the failure layer's
    calibrated thresholds for it, and (``versions``) the installed trackbook version and
    OpenCV's version (cached per process). Without the versions it names the code alone, as
    the committed results' rows that carry it do (a release does not make them stale)."""
    if (name, versions) in _CODE:
        return _CODE[name, versions]
    import cv2

    from .. import trackers as _trackers

    try:
        version = importlib.metadata.version("trackbook")
    except importlib.metadata.PackageNotFoundError:  # a source tree without install
        version = "unknown"
    from ..trackers.failure import calibrated_params

    cls = _trackers.get(name)
    h = hashlib.blake2b(digest_size=16)
    if versions:
        h.update(f"{version};{cv2.__version__};".encode())
    h.update(f"{cls.__module__}.{cls.__qualname__};".encode())
    # the failure layer's thresholds are data, not code, and decide ok and learning too
    h.update(repr(calibrated_params(name)).encode())
    for m in code_modules(cls):
        files = [m.__file__]
        # a script the module runs in a child process (opencv-mil's _mil_child.py) is its code
        files += sorted({v for v in vars(m).values() if isinstance(v, str)
                         and v.endswith(".py") and os.path.isfile(v)})
        for f in files:
            h.update(f"{m.__name__}:{Path(f).name};".encode())
            try:
                h.update(code_text(f))
            except OSError:  # a module without a readable file (zip import): key by name only
                pass
    _CODE[name, versions] = h.hexdigest()
    return _CODE[name, versions]


def code_text(path) -> bytes:
    """What of a ``.py`` file decides what it computes: its syntax tree without docstrings,
    comments or line numbers (``ast.dump``), so rewording a docstring or a comment keeps the
    saved runs while any change to the code re-runs them; the raw bytes for a file that does
    not parse."""
    raw = Path(path).read_bytes()
    try:
        tree = ast.parse(raw)
    except (SyntaxError, ValueError):
        return raw
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
                and body and isinstance(body[0], ast.Expr)
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str)):
            node.body = body[1:] or [ast.Pass()]
    return ast.dump(tree).encode()


def _jsonable(v):
    if isinstance(v, dict):
        return {k: _jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_jsonable(x) for x in v]
    if isinstance(v, np.ndarray):
        return _jsonable(v.tolist())
    if isinstance(v, (np.floating, float)):
        return None if not np.isfinite(v) else float(v)
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.bool_):
        return bool(v)
    return v


# --------------------------------------------------------------------------- tasks
@dataclasses.dataclass(frozen=True)
class Task:
    """One run: tracker, clip, seed; ``key`` decides whether a saved run can be reused.

    ``preset`` (``"book"`` or ``"paper"``) and ``code`` (:func:`code_fingerprint`) are part of
    the key like the params, and so is ``protocol`` when it is not ``"ope"`` (see
    :mod:`trackbook.evaluation.protocol_bench`; a one-pass run keeps the key it always had).
    """

    tracker: str
    clip: ClipRef
    seed: int
    max_frames: int | None
    params: tuple  # sorted (name, value) pairs
    fingerprint: str
    frames: int  # frames this run tracks (for the progress bar)
    preset: str = "book"
    code: str = ""
    protocol: str = "ope"

    @property
    def settings(self) -> dict:
        extra = {} if self.protocol == "ope" else {"protocol": self.protocol}
        return _jsonable({"tracker": self.tracker, "seed": self.seed,
                          "max_frames": self.max_frames, "params": dict(self.params),
                          "clip": self.clip.identity, "fingerprint": self.fingerprint,
                          "preset": self.preset, "code": self.code, **extra})

    @property
    def key(self) -> str:
        return hashlib.sha1(json.dumps(self.settings, sort_keys=True).encode()).hexdigest()

    def path(self, out) -> Path:
        name = f"{check_tracker_name(self.tracker)}__{safe_name(self.clip.name)}__s{self.seed}__{self.key[:12]}"
        return Path(out) / "runs" / f"{name}.json"


def safe_name(name: str) -> str:
    """A clip name as one file name (``a/clip`` -> ``a_clip``): characters other than
    letters, digits, ``.``, ``_`` and ``-`` become ``_``, and so does a leading dot, so the
    result never names a parent folder (``..``) or a hidden file."""
    s = re.sub(r"[^A-Za-z0-9._-]+", "_", str(name))
    return re.sub(r"^\.", "_", s) or "_"


#: What a tracker name may be, since it names files and folders of the outputs.
TRACKER_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9._+-]{0,99}")


def check_tracker_name(name) -> str:
    """``name`` when it can be a file name as it is; else a ``ValueError``.

    A tracker's name names its output files (``OUT/runs/<tracker>__...``,
    ``OUT/otb/<tracker>/``, ``TRACKER_CLIP.csv``). A name such as ``../../x`` would write
    outside the output folder, and rewriting it would let two trackers share files, so such a
    name is refused rather than changed.
    """
    if not isinstance(name, str) or not TRACKER_NAME.fullmatch(name):
        # plain text, no Markdown: the command line prints it on a terminal
        raise ValueError(f"tracker name {name!r} cannot name an output file; rename the tracker "
                         "(the name = ... line of its class) to letters, digits, '.', '_', '+' "
                         "and '-', starting with a letter or digit, at most 100 characters.")
    return name


def load_run(task: Task, out) -> dict | None:
    """The saved record of ``task`` when its key matches, else None (damaged files re-run)."""
    path = task.path(out)
    if not path.is_file():
        return None
    try:
        saved = json.loads(path.read_text())
    except (json.JSONDecodeError, OSError, UnicodeDecodeError):
        return None
    return saved if saved.get("key") == task.key else None


def save_run(task: Task, record: dict, out) -> None:
    """Write ``record`` as ``task``'s saved run (atomically)."""
    write_atomic(task.path(out), json.dumps(record))


def _record(task: Task, r, clip, multi_seed: bool) -> dict:
    gt = clip.groundtruth[: len(r.boxes)]
    row = {"tracker": task.tracker, "clip": clip.name, "frames": int(len(r.boxes)), **r.scores}
    if multi_seed:
        row["seed"] = task.seed
    for k, v in r.extras.items():
        row[k] = float(np.nanmean(v))
    rec = {"key": task.key, "settings": task.settings, "row": row, "boxes": r.boxes,
           "ms": r.ms, "params": r.params, "attributes": list(clip.attributes)}
    try:
        rec["success"] = metrics.success_curve(r.boxes[1:], gt[1:])[1]
        rec["precision"] = metrics.precision_curve(r.boxes[1:], gt[1:])[1]
    except ValueError:
        pass
    # the failure contract's count (frames reported lost with the box on the target); on a
    # sample clip only where its target is at least half in view (the clip's own name: a bench
    # may show it under another)
    ident = task.clip.identity
    in_view = _samples.in_view(ident.split(":", 1)[1]) if ident.startswith("sample:") else None
    rec["false_losses"] = list(metrics.false_losses(r.ok, r.boxes, gt, in_view))
    return _jsonable(rec)


def run_group(tasks, out=None, multi_seed=False, on_frames=None) -> list[dict]:
    """Run tasks that share one clip, decoding each frame once for all of them (lockstep, see
    :func:`trackbook.evaluation.runner.evaluate_many`); save each record to ``out`` (when
    given) and return the records. This is what a worker process or a Dask worker executes;
    :func:`trackbook.evaluation.parallel.groups` keeps groups small, so runs are saved often.
    """
    tasks = list(tasks)
    clip = tasks[0].clip.load()
    by: dict = {}
    recs = {}
    for t in tasks:
        if t.protocol != "ope":     # several runs of its own (TRE, SRE, resets): one by one
            recs[t] = _jsonable(protocol_bench.record(t, clip))
            if multi_seed:
                recs[t]["row"]["seed"] = t.seed
            if out is not None:
                save_run(t, recs[t], out)
            if on_frames is not None:
                on_frames(t.frames)
        else:
            by.setdefault((t.max_frames, t.preset), []).append(t)
    for (max_frames, preset), ts in by.items():
        if len(ts) == 1:  # kept separate so tests can patch evaluate()
            t = ts[0]
            results = [evaluate(t.tracker, clip, seed=t.seed, max_frames=max_frames,
                                preset=preset, **dict(t.params))]
        else:
            results = evaluate_many([(t.tracker, t.seed, dict(t.params)) for t in ts], clip,
                                    max_frames=max_frames, preset=preset)
        for t, r in zip(ts, results):
            rec = _record(t, r, clip, multi_seed)
            if out is not None:
                save_run(t, rec, out)
            recs[t] = rec
            if on_frames is not None:
                on_frames(t.frames)
    return [recs[t] for t in tasks]


# --------------------------------------------------------------------------- the plan of OUT
#: The file beside the tables that records the bench they were made from (see
#: :func:`check_same_plan`).
PLAN_FILE = "plan.json"


def plan_record(tasks) -> dict:
    """What decides a bench's tables: its trackers, clips (name and identity), seeds, params,
    preset, ``max_frames`` and protocol; written to ``OUT/plan.json`` with the tables."""
    t0 = tasks[0] if tasks else None
    return _jsonable({
        "trackers": list(dict.fromkeys(t.tracker for t in tasks)),
        "clips": list(dict.fromkeys(t.clip.name for t in tasks)),
        "clip_identities": list(dict.fromkeys(t.clip.identity for t in tasks)),
        "seeds": sorted({t.seed for t in tasks}),
        "params": {t.tracker: dict(t.params) for t in tasks if t.params},
        "preset": t0.preset if t0 else None, "max_frames": t0.max_frames if t0 else None,
        "protocol": t0.protocol if t0 else "ope"})


def _plan_text(p: dict) -> str:
    def few(xs):
        xs = [str(x) for x in xs]
        return ", ".join(xs[:4]) + (f" and {len(xs) - 4} more" if len(xs) > 4 else "")
    text = f"trackers {few(p.get('trackers', []))} on clips {few(p.get('clips', []))}"
    if "seeds" in p:
        text += f", seeds {few(p['seeds'])}"
    if p.get("max_frames") is not None:
        text += f", max-frames {p['max_frames']}"
    if p.get("protocol", "ope") != "ope":
        text += f", protocol {p['protocol']}"
    if p.get("preset") not in (None, "book"):
        text += f", preset {p['preset']}"
    if p.get("params"):
        text += f", params {json.dumps(p['params'], sort_keys=True)}"
    return text


def _saved_plan(out: Path):
    """The plan of the tables in ``out``: ``OUT/plan.json``, or what the rows of an
    ``OUT/results.json`` written without one tell (trackers, clips, seeds, frames); None when
    ``out`` holds no tables."""
    if (out / PLAN_FILE).is_file():
        try:
            return json.loads((out / PLAN_FILE).read_text())
        except (ValueError, OSError, UnicodeDecodeError):
            return {"unreadable": PLAN_FILE}
    if not (out / "results.json").is_file():
        return None
    try:
        rows = json.loads((out / "results.json").read_text())
        return {"trackers": list(dict.fromkeys(r["tracker"] for r in rows)),
                "clips": list(dict.fromkeys(r["clip"] for r in rows)),
                "rows": sorted([r["tracker"], r["clip"], r.get("seed"), r["frames"]]
                               for r in rows)}
    except (ValueError, OSError, UnicodeDecodeError, KeyError, TypeError):
        return {"unreadable": "results.json"}


_LABEL = {"clip_identities": "clip folders", "max_frames": "max-frames"}


def check_same_plan(tasks, out) -> None:
    """A ``ValueError`` when ``out`` holds the tables of another bench (other trackers, clips,
    seeds, params, preset, ``max_frames`` or protocol): its results would be replaced and its
    ``otb/`` files mixed with this bench's. The same bench is resumed; ``force`` replaces."""
    out = Path(out)
    saved = _saved_plan(out)
    if saved is None:
        return
    new = json.loads(json.dumps(plan_record(tasks)))
    if "rows" in saved:              # tables written before plan.json: compare the rows
        multi = len(new["seeds"]) > 1
        new = {**new, "rows": sorted([t.tracker, t.clip.name, t.seed if multi else None,
                                      t.frames] for t in tasks)}
        differs = [] if saved["rows"] == new["rows"] else ["rows"]
    else:
        saved = {"protocol": "ope", **saved}   # a plan.json from before protocols: one pass
        differs = [k for k in ("trackers", "clips", "clip_identities", "seeds", "params",
                               "preset", "max_frames", "protocol") if saved.get(k) != new.get(k)]
    if not differs:
        return
    if "clips" in differs:               # the same names from other folders: say so only then
        differs.remove("clip_identities")
    what = (f"tables whose {saved['unreadable']} cannot be read" if "unreadable" in saved
            else f"the tables of another bench ({_plan_text(saved)})")
    diff = "" if "unreadable" in saved or differs == ["rows"] else \
        f"; this one differs in its {', '.join(_LABEL.get(d, d) for d in differs)}"
    raise ValueError(f"--out {out} holds {what}{diff}; pass a new --out for this bench, or "
                     "--force to replace them (force=True in Python; saved runs are re-run).")
