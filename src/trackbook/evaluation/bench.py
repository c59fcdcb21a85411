"""The benchmark: trackers x clips x seeds -> tables and plots, resumable and parallel.

Each (tracker, clip, seed) run is written to ``OUT/runs/<tracker>__<clip>__s<seed>__<key>.json``
atomically as soon as it finishes. ``<key>`` hashes everything the result depends on (see
:mod:`trackbook.evaluation.runs`): the tracker, its preset, params and seed, ``max_frames``,
the clip's identity and a fingerprint of its ground truth and frames' bytes, and a fingerprint
of the tracker's code and the library version. A re-run reads a run back only when its key
matches, so renamed, duplicate or edited clips and edited trackers never reuse a stale result.
The summary files (``results.csv``, ``results.json``, ``curves.json``, ``table.md``,
``success.png``, ``precision.png`` and, when the clips carry attributes,
``attributes.md``/``attributes.csv``/``success_<ATTR>.png``/``precision_<ATTR>.png``) are rebuilt
from the runs at the end, also atomically, with mode 0644, and so are the results in the
format other toolkits read: ``otb/<tracker>/<clip>.txt`` (one ``x,y,w,h`` line per frame,
frame 1 the initial box) and ``otb/<tracker>/times/<clip>_time.txt`` (seconds per frame).
``plan.json`` records the bench the tables came from: an ``out`` holding another bench's
tables is refused unless ``force`` (which re-runs, replaces the tables and removes the other
bench's ``otb/`` files), so one folder never mixes two benches.

Runs go to worker processes (``workers``, default the number of cores) or to a Dask
distributed cluster (``scheduler``): see :mod:`trackbook.evaluation.parallel`. Scores do not
depend on the number of workers: every tracker is seeded per run and OpenCV's MIL runs each run
in a fresh child process (:class:`trackbook.trackers.reference.OpenCVMIL`).
"""

from __future__ import annotations

import csv
import dataclasses
import io
import json
import os
import re
from pathlib import Path

import numpy as np

from .. import clips as _clips
from .._checks import check_max_frames
from . import metrics, parallel, protocol_bench
from .runs import (PLAN_FILE, ClipRef, Task, _jsonable, check_same_plan,  # noqa: F401
                   check_tracker_name, code_fingerprint, fingerprint, load_imports, load_run,
                   plan_record, run_group, safe_name, write_atomic)

REFERENCE = "opencv-mil"
COLUMNS = ["tracker", "clip", "frames", "auc", "precision20", "tracking_rate",
           "mean_center_error", "ms_median", "ms_mean"]
#: The most runs a bench does unless ``max_runs`` (``--max-runs``) raises it.
MAX_RUNS = 5000
PRESETS = ("book", "paper")


def _ref(spec) -> list[ClipRef]:
    if hasattr(spec, "load"):                      # a dataset sequence
        return [ClipRef(spec, spec.name, spec.identity)]
    s = str(spec)
    if s in _clips.available():
        return [ClipRef(s, s, f"sample:{s}")]
    p = Path(s).expanduser()
    # a folder of folders none of which loads still goes to load_dataset: its error says
    # what each sub-folder lacks, where loading it as one sequence would say "no images"
    if p.is_dir() and (_clips.datasets.is_dataset(p) or _clips.datasets.holds_folders(p)):
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


def parse_seeds(spec, limit: int | None = None) -> list[int]:
    """``0``, ``"0-9"``, ``"0,3,7"``, ``"0-2,5"`` or a list -> sorted unique non-negative ints.

    With ``limit``, more than ``limit`` seeds is a ``ValueError`` (checked before a range is
    expanded, so ``0-10**12`` is refused at once).
    """

    def too_many(n):
        if limit is not None and n > limit:
            raise ValueError(f"seeds {spec!r} asks for {n} seeds, more than the {limit} runs "
                             "this bench may do; give fewer seeds or raise the cap with "
                             "--max-runs N (max_runs=N in Python).")

    if isinstance(spec, (int, np.integer)) and not isinstance(spec, bool):
        items = [int(spec)]
    elif isinstance(spec, str):
        items, count = [], 0
        for part in (p.strip() for p in spec.split(",")):
            m = re.fullmatch(r"(\d+)(?:\s*-\s*(\d+))?", part)
            if not m:
                raise ValueError(f"seeds {spec!r}: write a number, a range like 0-9 or a "
                                 "comma-separated list like 0,3,7.")
            a, b = int(m.group(1)), int(m.group(2) or m.group(1))
            if b < a:
                raise ValueError(f"seeds {part!r}: the range ends before it starts; write {b}-{a}.")
            count += b - a + 1
            too_many(count)
            items.extend(range(a, b + 1))
    else:
        items = list(spec)
        for s in items:
            if isinstance(s, bool) or not isinstance(s, (int, np.integer)) or s < 0:
                raise ValueError(f"seed {s!r} is not a non-negative integer.")
        items = [int(s) for s in items]
    if not items:
        raise ValueError("no seeds given; pass e.g. --seeds 0 or --seeds 0-9.")
    items = sorted(set(items))
    too_many(len(items))
    return items


def _check_trackers_and_params(trackers, params):
    from .. import trackers as _trackers

    if not trackers:
        raise ValueError("no trackers given; pass e.g. --trackers color-pf,covariance "
                         f"(available: {', '.join(_trackers.available())}).")
    for t in trackers:
        _trackers.get(t)  # unknown name -> ValueError listing the registered ones
        check_tracker_name(t)
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


def _check_max_runs(max_runs) -> int:
    if max_runs is None:
        return MAX_RUNS
    if isinstance(max_runs, bool) or not isinstance(max_runs, (int, np.integer)) or max_runs < 1:
        raise ValueError(f"max_runs = {max_runs!r}: give the most runs this bench may do, a "
                         "whole number of at least 1 (e.g. --max-runs 20000).")
    return int(max_runs)


def plan(trackers, clips, seed=0, max_frames=None, params=None, reference=True,
         seeds=None, preset: str = "book", max_runs: int | None = None,
         imports=(), protocol: str = "ope") -> list[Task]:
    """The runs a bench would do, in order (clips, then seeds, then trackers); MIL, which
    ignores the seed, runs with the first seed only. More than ``max_runs`` runs (default
    :data:`MAX_RUNS`) is a ``ValueError`` naming the count and the flag that raises the cap.
    ``imports`` are loaded first (user trackers; see :func:`run`). ``protocol`` (see
    :func:`trackbook.evaluation.protocol_bench.parse`) makes each task a protocol's runs."""
    protocol = protocol_bench.canonical(protocol)
    load_imports(imports)
    max_runs = _check_max_runs(max_runs)
    if preset not in PRESETS:
        raise ValueError(f"unknown preset {preset!r}; use one of {', '.join(PRESETS)} "
                         "(--preset paper runs the printed methods).")
    if isinstance(trackers, str):
        trackers = [t.strip() for t in trackers.split(",") if t.strip()]
    trackers = list(dict.fromkeys(trackers))
    params = {k: dict(v) for k, v in (params or {}).items()}
    _check_trackers_and_params(trackers, params)
    if reference and REFERENCE not in trackers:
        trackers.append(REFERENCE)
    seeds = parse_seeds(seed if seeds is None else seeds, limit=max_runs)
    max_frames = check_max_frames(max_frames)
    refs = resolve_clips(clips)
    per_clip = len([t for t in trackers if t != REFERENCE]) * len(seeds) + (REFERENCE in trackers)
    total = per_clip * len(refs)
    if total > max_runs:
        raise ValueError(f"this bench would do {total} runs ({len(trackers)} trackers x "
                         f"{len(refs)} clips x {len(seeds)} seeds), more than the cap of "
                         f"{max_runs}; narrow --trackers/--clips/--seeds or raise the cap with "
                         f"--max-runs {total} (max_runs={total} in Python).")
    code = {t: code_fingerprint(t) for t in trackers}
    tasks = []
    for ref in refs:
        clip = ref.load()
        fp = fingerprint(clip)
        n = len(clip) if max_frames is None else min(int(max_frames), len(clip))
        if protocol.startswith("tre") and n < 21:     # TRE: every segment 20 frames or more
            raise ValueError(f"clip {ref.name!r} has {n} frames to track; --protocol tre needs "
                             "at least 21 (each start leaves 20 frames), so give a longer "
                             "clip or a larger --max-frames.")
        for s in seeds:
            for t in trackers:
                if t == REFERENCE and s != seeds[0]:
                    continue
                tasks.append(Task(t, ref, s, max_frames, _frozen(params.get(t, {})), fp, n,
                                  preset=preset, code=code[t], protocol=protocol))
    return tasks


def _check_out(out) -> Path:
    if out is None or not str(out).strip():
        raise ValueError("out is empty; name the output folder, e.g. --out bench-results "
                         "(an empty name would write into the current folder).")
    return Path(out)


def run(trackers, clips, out, seed=0, max_frames=None, params=None, progress=True,
        force=False, reference=True, seeds=None, workers: int = 1,
        scheduler: str | None = None, imports=(), preset: str = "book",
        max_runs: int | None = None, scheduler_timeout: float | None = None,
        protocol: str = "ope") -> list[dict]:
    """Run every tracker on every clip (and seed); write the tables and plots; return the rows.

    Parameters
    ----------
    trackers : list of names (or comma-separated string); must not be empty
    clips : clip specs (see :func:`resolve_clips`); must not be empty
    out : output folder (not empty)
    seed : int, the seed of every run (``seeds`` sweeps several)
    max_frames : int, optional; track only the first frames
    params : dict tracker name -> dict of params (only for trackers in the run)
    progress : show a progress bar (runs, and frames in its postfix)
    force : replace outputs that exist: re-run runs already saved, and replace the tables
        of ``out`` also when they are another bench's (without it such an ``out`` is a
        ``ValueError``, see :func:`check_same_plan`; the same bench is resumed)
    reference : also run OpenCV's MIL (the reference row of every table)
    seeds : ``"0-9"``, ``"0,3"`` or a list; rows then carry a ``seed`` column
    workers : worker processes on this machine (1: in this process; at least 1)
    scheduler : address of a Dask distributed scheduler (``tcp://HOST:8786``); overrides
        ``workers``. The runs go to the cluster and come back to ``out``.
    imports : modules or ``.py`` files of user trackers (``--import``), loaded here, in every
        local worker and on Dask workers through :func:`trackbook.trackers.plugins.load`
    preset : ``"book"`` or ``"paper"`` (every tracker starts from the values its paper prints;
        ``params`` override either); part of each run's key
    max_runs : the most runs this bench may do (default :data:`MAX_RUNS`)
    scheduler_timeout : seconds a Dask scheduler has to connect and answer (default
        ``$TRACKBOOK_DASK_TIMEOUT`` or 5)
    protocol : ``"ope"`` (one pass from the first frame), ``"tre"`` (``"tre:N"``), ``"sre"``
        or ``"reset"`` (see :mod:`trackbook.evaluation.protocol_bench`): each (tracker, clip,
        seed) is then that protocol's runs, saved as one record; part of each run's key and
        of ``plan.json``

    Returns
    -------
    Rows
        A list of row dicts, with ``read_back`` and ``ran`` (runs read back from ``out`` and
        runs done now) and ``table`` (the text of ``table.md``).
    """
    out = _check_out(out)
    workers = parallel.check_workers(workers)
    imports = [str(i) for i in ([imports] if isinstance(imports, (str, os.PathLike))
                                else (imports or ()))]
    tasks = plan(trackers, clips, seed, max_frames, params, reference, seeds, preset=preset,
                 max_runs=max_runs, imports=imports, protocol=protocol)
    scheduler = scheduler or os.environ.get(parallel.ENV_SCHEDULER) or None
    if isinstance(scheduler, (str, os.PathLike)):  # fail in seconds, before any run
        parallel.check_scheduler(scheduler, parallel.check_timeout(scheduler_timeout))
    check_otb_names({(t.tracker, t.clip.name) for t in tasks}, out)   # before any run
    multi_seed = len({t.seed for t in tasks}) > 1
    if not force:
        check_same_plan(tasks, out)
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
                         multi_seed=multi_seed, imports=imports, timeout=scheduler_timeout)
    finally:
        if bar is not None:
            bar.close()
    records = [done[t] for t in tasks]
    write_summary(records, out)
    write_atomic(out / PLAN_FILE, json.dumps(plan_record(tasks), indent=1))
    return Rows((r["row"] for r in records), read_back=len(tasks) - len(todo), ran=len(todo),
                table=(out / "table.md").read_text())


class Rows(list):
    """The rows :func:`run` returns (a list), with how many runs were read back from
    ``OUT/runs`` (``read_back``: their ``ms_*`` are the timings of the bench that saved them)
    and how many ran now (``ran``), and the text of ``table.md`` (``table``)."""

    def __init__(self, rows=(), read_back: int = 0, ran: int = 0, table: str = ""):
        super().__init__(rows)
        self.read_back, self.ran, self.table = read_back, ran, table


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
            v = [x[k] for x in rs if x.get(k) is not None]  # noqa: B023 (called at once)
            return float(np.mean(v)) if v else float("nan")
        out.append({"tracker": t, "clips": len({x["clip"] for x in rs}), "auc": mean("auc"),
                    "precision20": mean("precision20"), "tracking_rate": mean("tracking_rate"),
                    "ms_median": float(np.median([x["ms_median"] for x in rs]))})
    return out


def markdown_table(rows) -> str:
    """Per-tracker summary, then AUC per clip (mean over seeds), as markdown."""
    from .._markdown import table

    summ = summarize(rows)
    cols = ["tracker", "clips", "auc", "precision20", "tracking_rate", "ms_median"]
    lines = [table(summ, cols, labels={"auc": "mean AUC", "precision20": "mean precision@20",
                                       "tracking_rate": "mean tracking rate",
                                       "ms_median": "median ms/frame"},
                   formats={"auc": ".3f", "precision20": ".3f", "tracking_rate": ".1%",
                            "ms_median": ".2f"}, align={c: "right" for c in cols[1:]})]
    clip_names = list(dict.fromkeys(r["clip"] for r in rows))
    cell: dict = {}
    for r in rows:
        if r.get("auc") is not None:
            cell.setdefault((r["tracker"], r["clip"]), []).append(r["auc"])
    per_clip = [{"tracker": s["tracker"], **{c: float(np.mean(cell[(s["tracker"], c)]))
                                             for c in clip_names if cell.get((s["tracker"], c))}}
                for s in summ]
    lines += ["", "AUC per clip:", "",
              table(per_clip, ["tracker", *clip_names], number=".3f",
                    align={c: "right" for c in clip_names})]
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
    the runs; with attributes also attributes.csv / attributes.md and per-attribute plots.
    Records of a protocol other than OPE: see :func:`write_protocol_summary`."""
    out = Path(out)
    if records and records[0]["row"].get("protocol", "ope") != "ope":
        return write_protocol_summary(records, out)
    (out / "eao.png").unlink(missing_ok=True)                    # a reset bench's
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
    write_otb(records, out)
    _plot(records, out)
    attrs = attribute_rows(records)
    names = {f"{k}_{re.sub(r'[^A-Za-z0-9_-]+', '_', a)}.png" for a in {x["attribute"] for x in attrs}
             for k in ("success", "precision")}
    for p in [*out.glob("success_*.png"), *out.glob("precision_*.png"),     # another bench's
              *([] if attrs else [out / "attributes.csv", out / "attributes.md"])]:
        if p.name not in names:
            p.unlink(missing_ok=True)
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


def write_protocol_summary(records, out) -> None:
    """The tables of a TRE, SRE or reset bench: results.csv / results.json (a row per
    tracker, clip and seed), table.md (:func:`protocol_bench.markdown_table`), curves.json
    (:func:`protocol_bench.curves`) and the plots (TRE/SRE: success.png and precision.png of
    the pooled curves; reset: eao.png). Files of a one-pass bench it does not write (the
    ``otb/`` results, per-attribute tables and plots) are removed."""
    out = Path(out)
    rows = [r["row"] for r in records]
    cols = list(dict.fromkeys(k for r in rows for k in r))
    write_atomic(out / "results.csv", _csv(rows, cols))
    write_atomic(out / "results.json", json.dumps(_jsonable(rows), indent=1))
    write_atomic(out / "curves.json", json.dumps(_jsonable(protocol_bench.curves(records))))
    write_atomic(out / "table.md", protocol_bench.markdown_table(records))
    _remove_stale(out / "otb", keep=())
    reset = rows[0]["protocol"] == "reset"
    for p in [*out.glob("success_*.png"), *out.glob("precision_*.png"), out / "attributes.csv",
              out / "attributes.md",
              *([out / "success.png", out / "precision.png"] if reset else [out / "eao.png"])]:
        p.unlink(missing_ok=True)
    if reset:
        write_atomic(out / "eao.png", protocol_bench.eao_plot(records))
    else:
        _plot(records, out)


def otb_paths(tracker: str, clip: str, out) -> tuple[Path, Path]:
    """Where :func:`write_otb` puts one run: ``OUT/otb/<tracker>/<clip>.txt`` and
    ``OUT/otb/<tracker>/times/<clip>_time.txt`` (got10k's layout: timings in a folder of
    their own, so a clip called ``Deer_time`` cannot replace ``Deer``'s timing file)."""
    folder = Path(out) / "otb" / check_tracker_name(tracker)
    return folder / f"{safe_name(clip)}.txt", folder / "times" / f"{safe_name(clip)}_time.txt"


def check_otb_names(pairs, out) -> None:
    """A ``ValueError`` naming two clips whose OTB result files (:func:`otb_paths`) would be
    one file: ``pairs`` of ``(tracker, clip)``. :func:`run` checks its plan before the first
    run, so such a bench writes nothing."""
    owner: dict = {}
    for tracker, clip in sorted(pairs):
        box_file, _ = otb_paths(tracker, clip, out)
        other = owner.setdefault(str(box_file).casefold(), clip)
        if other != clip:
            raise ValueError(f"clips {other!r} and {clip!r} would both be written to "
                             f"{box_file}; rename one of them (e.g. its folder) so their names "
                             "differ in more than spaces, punctuation or case.")


def _remove_stale(folder: Path, keep) -> None:
    """Remove the result files under ``OUT/otb`` that this bench does not write (an earlier
    bench's trackers or clips, replaced with ``force``), so the folder holds one bench."""
    if not folder.is_dir():
        return
    keep = {Path(p) for p in keep}
    for p in sorted(folder.rglob("*.txt")):
        if p not in keep:
            p.unlink()
    for d in [*sorted((d for d in folder.rglob("*") if d.is_dir()), reverse=True), folder]:
        if not any(d.iterdir()):
            d.rmdir()


def write_otb(records, out) -> None:
    """The results in the layout the OTB toolkit, got10k, pysot and pytracking read:
    ``OUT/otb/<tracker>/<clip>.txt``, one comma-separated ``x,y,w,h`` line per frame (frame 1
    the initial box; 1-based frame numbers, 0-based pixel coordinates as in trackbook's
    boxes), and ``OUT/otb/<tracker>/times/<clip>_time.txt``, the seconds each frame took
    (frame 1: ``init``). With several seeds these are the first seed's runs. Values are written
    with ``repr``, so a reader gets the very floats the bench scored.

    Two clips whose names give the same file name (``my clip`` and ``my_clip``; names that
    differ only in case, which some file systems do not tell apart) are a ``ValueError``
    naming both, raised before any file is written: a result file is never renamed, and never
    overwritten by another clip's.
    """
    chosen: dict = {}
    for r in records:
        k = (r["row"]["tracker"], r["row"]["clip"])
        if k not in chosen or r["settings"]["seed"] < chosen[k]["settings"]["seed"]:
            chosen[k] = r
    check_otb_names(chosen, out)
    keep = {p for tracker, clip in chosen for p in otb_paths(tracker, clip, out)}
    _remove_stale(Path(out) / "otb", keep)
    for (tracker, clip), r in chosen.items():
        box_file, time_file = otb_paths(tracker, clip, out)
        boxes = "".join(",".join(repr(float(v)) for v in b) + "\n" for b in r["boxes"])
        times = "".join(f"{float(ms) / 1e3!r}\n" for ms in r["ms"])
        write_atomic(box_file, boxes)
        write_atomic(time_file, times)


def _plot(records, out, suffix="", title=""):
    # A bare Figure (no pyplot): drawing the plots must not touch the global backend, or a
    # benchmark run inside a notebook would switch the kernel away from inline figures.
    from matplotlib.figure import Figure

    from ..style import label_colors

    by = {}
    for r in records:
        if "success" in r:
            by.setdefault(r["row"]["tracker"], []).append(r)
    n_clips = len({r["row"]["clip"] for rs in by.values() for r in rs})
    for kind, xs, xlabel in (("success", metrics.SUCCESS_THRESHOLDS, "overlap threshold"),
                             ("precision", metrics.PRECISION_THRESHOLDS, "centre error (px)")):
        fig = Figure(figsize=(5, 3.6))
        ax = fig.subplots()
        colours = label_colors(by)
        for i, (t, rs) in enumerate(by.items()):
            curve = np.mean([r[kind] for r in rs], axis=0)
            score = curve.mean() if kind == "success" else curve[20]
            ax.plot(xs, curve, color=colours[i], label=f"{t} [{score:.3f}]")
        ax.set(xlabel=xlabel, ylabel="fraction of frames", ylim=(0, 1.02),
               title=f"{kind} plot{title}, mean over {n_clips} clips")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=110)
        write_atomic(out / f"{kind}{suffix}.png", buf.getvalue())
