"""The benchmark: trackers x clips x seeds -> tables and plots, resumable and parallel.

Each (tracker, clip, seed) run is written to ``OUT/runs/<tracker>__<clip>__s<seed>__<key>.json``
atomically (write a temporary file, then rename) as soon as it finishes. ``<key>`` is a hash of
everything the result depends on: the tracker, its preset, params and seed, ``max_frames``,
the clip's *identity* (the resolved path of its folder or video, or ``sample:<name>``, plus the
target) and a *fingerprint* of its ground truth and frame list (file names and sizes). A re-run reads a
run back only when its key matches, so renamed, duplicate or edited clips never share or reuse
a stale result. The summary files (``results.csv``, ``results.json``, ``curves.json``,
``table.md``, ``success.png``, ``precision.png`` and, when the clips carry attributes,
``attributes.md``/``attributes.csv``/``success_<ATTR>.png``/``precision_<ATTR>.png``) are rebuilt
from the runs at the end, also atomically, with mode 0644.

Runs go to worker processes (``workers``, default the number of cores) or to a Dask
distributed cluster (``scheduler``): see :mod:`trackbook.evaluation.parallel`. Scores do not
depend on the number of workers: every tracker is seeded per run and OpenCV's MIL runs each run
in a fresh child process (:class:`trackbook.trackers.reference.OpenCVMIL`).
"""

from __future__ import annotations

import csv
import dataclasses
import hashlib
import io
import json
import os
import re
import tempfile
from pathlib import Path

import numpy as np

from .. import clips as _clips
from . import metrics
from .runner import evaluate, evaluate_many  # noqa: F401  (evaluate: tests patch it)

REFERENCE = "opencv-mil"
COLUMNS = ["tracker", "clip", "frames", "auc", "precision20", "tracking_rate",
           "mean_center_error", "ms_median", "ms_mean"]


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
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, mode) as f:
            f.write(data)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


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


def _ref(spec) -> list[ClipRef]:
    if hasattr(spec, "load"):                      # a dataset sequence
        return [ClipRef(spec, spec.name, spec.identity)]
    s = str(spec)
    if s in _clips.available():
        return [ClipRef(s, s, f"sample:{s}")]
    p = Path(s).expanduser()
    if p.is_dir() and _clips.datasets.is_dataset(p):
        return [ClipRef(q, q.name, q.identity) for q in _clips.load_dataset(p)]
    if p.exists():
        clip = _clips.load(p)
        ident = str(p.resolve())
        if len(clip.targets) > 1:                  # OTB's Jogging: one run per target
            return [ClipRef(str(p), f"{clip.name}.{t}", f"{ident}#{t}", t) for t in clip.targets]
        return [ClipRef(str(p), clip.name, ident)]
    clip = _clips.load(s)                           # a sequence name found on disk
    return [ClipRef(clip.source or s, clip.name, str(Path(clip.source).resolve())
                    if clip.source else s)]


def resolve_clips(specs) -> list[ClipRef]:
    """Clip specs -> :class:`ClipRef` list: ``samples`` (all sample clips), ``shared`` (every
    sequence found by :func:`trackbook.clips.find_sequences`), names, folders, videos, or the
    root of a dataset (OTB-100, UAV123 or a folder of OTB-style sequences; see
    :func:`trackbook.clips.load_dataset`). Duplicate names get their parent folder prepended
    (``a/clip``, ``b/clip``); the same clip given twice is run once.

    Raises ``ValueError`` for an empty list.
    """
    if isinstance(specs, (str, os.PathLike)):
        specs = [s.strip() for s in str(specs).split(",") if s.strip()]
    specs = list(specs)
    if not specs:
        raise ValueError("no clips given; pass --clips samples, a sample name, a sequence "
                         "folder, a video or a dataset root (e.g. --clips /data/OTB100).")
    refs: list[ClipRef] = []
    for s in specs:
        if s == "samples":
            refs.extend(ClipRef(n, n, f"sample:{n}") for n in _clips.available())
        elif s == "shared":
            found = _clips.find_sequences()
            if not found:
                raise FileNotFoundError(
                    "--clips shared: no sequence folder found; put the data at "
                    "../shared/data/sequences or set TRACKBOOK_SEQUENCES=/path/to/sequences."
                )
            for p in found.values():
                refs.extend(_ref(p))
        else:
            refs.extend(_ref(s))
    seen, out = set(), []
    for r in refs:
        if r.identity not in seen:
            seen.add(r.identity)
            out.append(r)
    names = [r.name for r in out]
    for i, r in enumerate(out):
        if names.count(r.name) > 1:
            parent = Path(r.identity.split("#")[0]).parent.name or "clip"
            out[i] = dataclasses.replace(r, name=f"{parent}/{r.name}")
    names = [r.name for r in out]
    for i, r in enumerate(out):                     # still equal (same parent name): number them
        if names.count(r.name) > 1:
            out[i] = dataclasses.replace(r, name=f"{r.name}#{names[:i].count(r.name) + 1}")
    return out


def fingerprint(clip) -> str:
    """A hash of the clip's ground truth (every target) and frame list: image file names and
    sizes, a video's path and size, or a generated clip's pixels."""
    h = hashlib.sha1()
    for k in sorted(clip.targets):
        h.update(k.encode())
        h.update(np.ascontiguousarray(np.asarray(clip.targets[k], dtype=np.float64)).tobytes())
    h.update(np.asarray(clip.groundtruth, dtype=np.float64).tobytes())
    fr = clip.frames
    h.update(str(len(fr)).encode())
    paths = getattr(fr, "paths", None)
    if paths is not None:
        for p in paths:
            p = Path(p)
            h.update(f"{p.name}:{p.stat().st_size};".encode())
    elif getattr(fr, "path", None) is not None:
        p = Path(fr.path)
        h.update(f"{p.resolve()}:{p.stat().st_size}".encode())
    elif getattr(fr, "array", None) is not None:
        h.update(np.ascontiguousarray(fr.array).tobytes())
    else:
        for f in fr:
            h.update(np.ascontiguousarray(f).tobytes())
    return h.hexdigest()


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


def parse_seeds(spec) -> list[int]:
    """``0``, ``"0-9"``, ``"0,3,7"``, ``"0-2,5"`` or a list -> sorted unique non-negative ints."""
    if isinstance(spec, (int, np.integer)) and not isinstance(spec, bool):
        items = [int(spec)]
    elif isinstance(spec, str):
        items = []
        for part in (p.strip() for p in spec.split(",")):
            m = re.fullmatch(r"(\d+)(?:\s*-\s*(\d+))?", part)
            if not m:
                raise ValueError(f"seeds {spec!r}: write a number, a range like 0-9 or a "
                                 "comma-separated list like 0,3,7.")
            a, b = int(m.group(1)), int(m.group(2) or m.group(1))
            if b < a:
                raise ValueError(f"seeds {part!r}: the range ends before it starts; write {b}-{a}.")
            items.extend(range(a, b + 1))
    else:
        items = list(spec)
        for s in items:
            if isinstance(s, bool) or not isinstance(s, (int, np.integer)) or s < 0:
                raise ValueError(f"seed {s!r} is not a non-negative integer.")
        items = [int(s) for s in items]
    if not items:
        raise ValueError("no seeds given; pass e.g. --seeds 0 or --seeds 0-9.")
    return sorted(set(items))


@dataclasses.dataclass(frozen=True)
class Task:
    """One run: tracker, clip, seed; ``key`` decides whether a saved run can be reused."""

    tracker: str
    clip: ClipRef
    seed: int
    max_frames: int | None
    params: tuple  # sorted (name, value) pairs
    fingerprint: str
    frames: int  # frames this run tracks (for the progress bar)
    preset: str = "book"  # the tracker's preset ("book" or "paper"); params override it

    @property
    def settings(self) -> dict:
        return _jsonable({"tracker": self.tracker, "seed": self.seed, "preset": self.preset,
                          "max_frames": self.max_frames, "params": dict(self.params),
                          "clip": self.clip.identity, "fingerprint": self.fingerprint})

    @property
    def key(self) -> str:
        return hashlib.sha1(json.dumps(self.settings, sort_keys=True).encode()).hexdigest()

    def path(self, out) -> Path:
        safe = re.sub(r"[^A-Za-z0-9._-]+", "_", self.clip.name)
        return Path(out) / "runs" / f"{self.tracker}__{safe}__s{self.seed}__{self.key[:12]}.json"


def load_imports(imports) -> None:
    """Import user tracker modules or ``.py`` files (each registers its trackers), through
    :func:`trackbook.trackers.plugins.load`; idempotent, so every worker may call it."""
    if not imports:
        return
    from ..trackers import plugins

    for spec in imports:
        plugins.load(spec)


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
    return _jsonable(rec)


def run_group(tasks, out=None, multi_seed=False, on_frames=None) -> list[dict]:
    """Run tasks that share one clip, decoding each frame once for all of them (lockstep, see
    :func:`trackbook.evaluation.runner.evaluate_many`); write each record to ``out`` (when
    given) and return the records. This is what a worker process or a Dask worker executes.
    """
    tasks = list(tasks)
    clip = tasks[0].clip.load()
    by_frames: dict = {}
    for t in tasks:
        by_frames.setdefault((t.max_frames, t.preset), []).append(t)
    recs = {}
    for (max_frames, preset), ts in by_frames.items():
        if len(ts) == 1:  # kept separate so tests can patch evaluate()
            t = ts[0]
            kw = {"preset": preset} if preset != "book" else {}
            results = [evaluate(t.tracker, clip, seed=t.seed, max_frames=max_frames,
                                **kw, **dict(t.params))]
        else:
            results = evaluate_many([(t.tracker, t.seed, dict(t.params)) for t in ts], clip,
                                    max_frames=max_frames, preset=preset)
        for t, r in zip(ts, results):
            rec = _record(t, r, clip, multi_seed)
            if out is not None:
                write_atomic(t.path(out), json.dumps(rec))
            recs[t] = rec
            if on_frames is not None:
                on_frames(t.frames)
    return [recs[t] for t in tasks]


def _check_trackers_and_params(trackers, params):
    from .. import trackers as _trackers

    if not trackers:
        raise ValueError("no trackers given; pass e.g. --trackers color-pf,covariance "
                         f"(available: {', '.join(_trackers.available())}).")
    for t in trackers:
        _trackers.get(t)  # unknown name -> ValueError listing the registered ones
    stray = sorted(set(params) - set(trackers))
    if stray:
        raise ValueError(f"params given for {', '.join(stray)}, which this bench does not run "
                         f"(it runs {', '.join(trackers)}); fix the name in --param "
                         "TRACKER:NAME=VALUE or add the tracker to --trackers.")
    for t, p in params.items():
        if p:
            _trackers.create(t, seed=0, **p)  # bad names/values -> ValueError naming them


def _frozen(p: dict) -> tuple:
    def f(v):
        return tuple(f(x) for x in v) if isinstance(v, (list, tuple)) else v
    return tuple(sorted((k, f(v)) for k, v in p.items()))


def plan(trackers, clips, seed=0, max_frames=None, params=None, reference=True,
         seeds=None) -> list[Task]:
    """The runs a bench would do, in order (clips, then seeds, then trackers); MIL, which
    ignores the seed, runs with the first seed only."""
    if isinstance(trackers, str):
        trackers = [t.strip() for t in trackers.split(",") if t.strip()]
    trackers = list(dict.fromkeys(trackers))
    params = {k: dict(v) for k, v in (params or {}).items()}
    _check_trackers_and_params(trackers, params)
    if reference and REFERENCE not in trackers:
        trackers.append(REFERENCE)
    seeds = parse_seeds(seed if seeds is None else seeds)
    if max_frames is not None and (isinstance(max_frames, bool) or int(max_frames) < 2):
        raise ValueError(f"max_frames = {max_frames!r}: evaluating needs at least 2 frames.")
    tasks = []
    for ref in resolve_clips(clips):
        clip = ref.load()
        fp = fingerprint(clip)
        n = len(clip) if max_frames is None else min(int(max_frames), len(clip))
        for s in seeds:
            for t in trackers:
                if t == REFERENCE and s != seeds[0]:
                    continue
                tasks.append(Task(t, ref, s, max_frames, _frozen(params.get(t, {})), fp, n))
    return tasks


def run(trackers, clips, out, seed=0, max_frames=None, params=None, progress=True,
        force=False, reference=True, seeds=None, workers: int = 1,
        scheduler: str | None = None) -> list[dict]:
    """Run every tracker on every clip (and seed); write the tables and plots; return the rows.

    Parameters
    ----------
    trackers : list of names (or comma-separated string); must not be empty
    clips : clip specs (see :func:`resolve_clips`); must not be empty
    out : output folder
    seed : int, the seed of every run (``seeds`` sweeps several)
    max_frames : int, optional; track only the first frames
    params : dict tracker name -> dict of params (only for trackers in the run)
    progress : show a progress bar (runs, and frames in its postfix)
    force : re-run runs already saved
    reference : also run OpenCV's MIL (the reference row of every table)
    seeds : ``"0-9"``, ``"0,3"`` or a list; rows then carry a ``seed`` column
    workers : worker processes on this machine (1: in this process)
    scheduler : address of a Dask distributed scheduler (``tcp://HOST:8786``); overrides
        ``workers``. The runs go to the cluster and come back to ``out``.
    """
    from . import parallel

    tasks = plan(trackers, clips, seed, max_frames, params, reference, seeds)
    multi_seed = len({t.seed for t in tasks}) > 1
    done: dict[Task, dict] = {}
    if not force:
        for t in tasks:
            rec = load_run(t, out)
            if rec is not None:
                done[t] = rec
    todo = [t for t in tasks if t not in done]
    bar = None
    frames_total = sum(t.frames for t in tasks)
    frames_done = [sum(t.frames for t in done)]
    if progress:
        from tqdm.auto import tqdm
        bar = tqdm(total=len(tasks), initial=len(done), desc="bench", unit="run")
        bar.set_postfix_str(f"{frames_done[0]}/{frames_total} frames")

    def finished(group, recs):
        for t, r in zip(group, recs):
            done[t] = r
            frames_done[0] += t.frames
        if bar is not None:
            bar.update(len(group))
            bar.set_postfix_str(f"{frames_done[0]}/{frames_total} frames")

    try:
        parallel.execute(todo, out, finished, workers=workers, scheduler=scheduler,
                         multi_seed=multi_seed)
    finally:
        if bar is not None:
            bar.close()
    records = [done[t] for t in tasks]
    write_summary(records, out)
    return [r["row"] for r in records]


def load(out) -> list[dict]:
    """The rows of ``OUT/results.json`` (what a chapter reads back)."""
    return json.loads((Path(out) / "results.json").read_text())


def load_curves(out) -> dict:
    """``{tracker: {clip: {"success": [21], "precision": [51]}}}`` from ``OUT/curves.json``
    (with several seeds, the mean curve over seeds)."""
    return json.loads((Path(out) / "curves.json").read_text())


def summarize(rows) -> list[dict]:
    """Per-tracker means over clips (and seeds): AUC, precision, tracking rate; median of
    ms/frame."""
    by = {}
    for r in rows:
        by.setdefault(r["tracker"], []).append(r)
    out = []
    for t, rs in by.items():
        def mean(k):
            v = [x[k] for x in rs if x.get(k) is not None]
            return float(np.mean(v)) if v else float("nan")
        out.append({"tracker": t, "clips": len({x["clip"] for x in rs}), "auc": mean("auc"),
                    "precision20": mean("precision20"), "tracking_rate": mean("tracking_rate"),
                    "ms_median": float(np.median([x["ms_median"] for x in rs]))})
    return out


def markdown_table(rows) -> str:
    """Per-tracker summary, then AUC per clip (mean over seeds), as markdown."""
    summ = summarize(rows)
    lines = ["| tracker | clips | mean AUC | mean precision@20 | mean tracking rate | median ms/frame |",
             "|---|---:|---:|---:|---:|---:|"]
    for s in summ:
        lines.append(f"| {s['tracker']} | {s['clips']} | {s['auc']:.3f} | {s['precision20']:.3f} "
                     f"| {s['tracking_rate']:.1%} | {s['ms_median']:.2f} |")
    clip_names = list(dict.fromkeys(r["clip"] for r in rows))
    lines += ["", "AUC per clip:", "",
              "| tracker | " + " | ".join(clip_names) + " |",
              "|---|" + "---:|" * len(clip_names)]
    cell: dict = {}
    for r in rows:
        if r.get("auc") is not None:
            cell.setdefault((r["tracker"], r["clip"]), []).append(r["auc"])
    for s in summ:
        vals = []
        for c in clip_names:
            v = cell.get((s["tracker"], c))
            vals.append("" if not v else f"{np.mean(v):.3f}")
        lines.append(f"| {s['tracker']} | " + " | ".join(vals) + " |")
    return "\n".join(lines) + "\n"


def attribute_rows(records) -> list[dict]:
    """Per attribute and tracker, as the OTB toolkit reports them (Wu et al. 2013): the
    number of clips with the attribute, the AUC of the mean success curve and the precision at
    20 px of the mean precision curve over those clips."""
    by: dict = {}
    for r in records:
        if "success" not in r:
            continue
        for a in r.get("attributes") or []:
            by.setdefault(a, {}).setdefault(r["row"]["tracker"], []).append(r)
    out = []
    for a in sorted(by):
        for t, rs in by[a].items():
            s = np.mean([r["success"] for r in rs], axis=0)
            p = np.mean([r["precision"] for r in rs], axis=0)
            out.append({"attribute": a, "tracker": t, "clips": len({r["row"]["clip"] for r in rs}),
                        "auc": float(s.mean()), "precision20": float(p[20])})
    return out


def _csv(rows, cols) -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=cols, extrasaction="ignore")
    w.writeheader()
    for r in rows:
        w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in cols})
    return buf.getvalue()


def write_summary(records, out) -> None:
    """results.csv / results.json / curves.json / table.md / success.png / precision.png from
    the runs; with attributes also attributes.csv / attributes.md and per-attribute plots."""
    out = Path(out)
    rows = [r["row"] for r in records]
    extra_cols = sorted({k for r in rows for k in r} - set(COLUMNS))
    write_atomic(out / "results.csv", _csv(rows, COLUMNS + extra_cols))
    write_atomic(out / "results.json", json.dumps(rows, indent=1))
    curves: dict = {}
    for r in records:
        if "success" in r:
            curves.setdefault(r["row"]["tracker"], {}).setdefault(r["row"]["clip"], []).append(r)
    curves = {t: {c: {"success": np.mean([r["success"] for r in rs], axis=0).tolist(),
                      "precision": np.mean([r["precision"] for r in rs], axis=0).tolist()}
                  for c, rs in cs.items()} for t, cs in curves.items()}
    write_atomic(out / "curves.json", json.dumps(curves))
    write_atomic(out / "table.md", markdown_table(rows))
    _plot(records, out)
    attrs = attribute_rows(records)
    if attrs:
        write_atomic(out / "attributes.csv",
                     _csv(attrs, ["attribute", "tracker", "clips", "auc", "precision20"]))
        lines = ["| attribute | tracker | clips | AUC | precision@20 |", "|---|---|---:|---:|---:|"]
        lines += [f"| {a['attribute']} | {a['tracker']} | {a['clips']} | {a['auc']:.3f} | "
                  f"{a['precision20']:.3f} |" for a in attrs]
        write_atomic(out / "attributes.md", "\n".join(lines) + "\n")
        for a in sorted({x["attribute"] for x in attrs}):
            safe = re.sub(r"[^A-Za-z0-9_-]+", "_", a)
            _plot([r for r in records if a in (r.get("attributes") or [])], out,
                  suffix=f"_{safe}", title=f" ({a})")


def _plot(records, out, suffix="", title=""):
    # A bare Figure (no pyplot): drawing the plots must not touch the global backend, or a
    # benchmark run inside a notebook would switch the kernel away from inline figures.
    from matplotlib.figure import Figure

    from ..viz.core import CYCLE

    by = {}
    for r in records:
        if "success" in r:
            by.setdefault(r["row"]["tracker"], []).append(r)
    n_clips = len({r["row"]["clip"] for rs in by.values() for r in rs})
    for kind, xs, xlabel in (("success", metrics.SUCCESS_THRESHOLDS, "overlap threshold"),
                             ("precision", metrics.PRECISION_THRESHOLDS, "centre error (px)")):
        fig = Figure(figsize=(5, 3.6))
        ax = fig.subplots()
        for i, (t, rs) in enumerate(by.items()):
            curve = np.mean([r[kind] for r in rs], axis=0)
            score = curve.mean() if kind == "success" else curve[20]
            ax.plot(xs, curve, color=CYCLE[i % len(CYCLE)], label=f"{t} [{score:.3f}]")
        ax.set(xlabel=xlabel, ylabel="fraction of frames", ylim=(0, 1.02),
               title=f"{kind} plot{title}, mean over {n_clips} clips")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=110)
        write_atomic(out / f"{kind}{suffix}.png", buf.getvalue())
