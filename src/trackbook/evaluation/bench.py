"""The benchmark: trackers x clips -> tables and plots, resumable (``trackbook bench``).

Each (tracker, clip) run is written to ``OUT/runs/<tracker>__<clip>.json`` atomically (write a
temporary file, then rename) as soon as it finishes; a re-run with the same settings reads it
back instead of tracking again, so an interrupted benchmark loses no finished result. The
summary files (``results.csv``, ``results.json``, ``curves.json``, ``table.md``,
``success.png``, ``precision.png``) are rebuilt from the runs at the end, also atomically.
"""

from __future__ import annotations

import csv
import io
import json
import os
import tempfile
from pathlib import Path

import numpy as np

from .. import clips as _clips
from . import metrics
from .runner import evaluate

REFERENCE = "opencv-mil"
COLUMNS = ["tracker", "clip", "frames", "auc", "precision20", "tracking_rate",
           "mean_center_error", "ms_median", "ms_mean"]


def write_atomic(path, data: bytes | str) -> None:
    """Write ``data`` to ``path`` so that readers see the old file or the new one, never half."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    mode = "wb" if isinstance(data, bytes) else "w"
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, mode) as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def resolve_clips(specs) -> list:
    """Clip specs -> list of names/paths: ``samples`` (all sample clips), ``shared`` (every
    sequence found by :func:`trackbook.clips.find_sequences`), names, folders or videos."""
    if isinstance(specs, str):
        specs = [s for s in specs.split(",") if s]
    out = []
    for s in specs:
        if s == "samples":
            out.extend(_clips.available())
        elif s == "shared":
            found = _clips.find_sequences()
            if not found:
                raise FileNotFoundError(
                    "--clips shared: no sequence folder found; put the data at "
                    "../shared/data/sequences or set TRACKBOOK_SEQUENCES=/path/to/sequences."
                )
            out.extend(str(p) for p in found.values())
        else:
            out.append(s)
    return out


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
    return v


def _settings(tracker, seed, max_frames, params):
    return {"tracker": tracker, "seed": seed, "max_frames": max_frames, "params": params or {}}


def run_one(tracker: str, clip, out, seed=0, max_frames=None, params=None, force=False) -> dict:
    """One (tracker, clip) run, read back from ``OUT/runs`` when it already exists."""
    clip = _clips.load(clip)
    path = Path(out) / "runs" / f"{tracker}__{clip.name}.json"
    settings = _settings(tracker, seed, max_frames, params)
    if path.is_file() and not force:
        try:
            saved = json.loads(path.read_text())
            if saved.get("settings") == _jsonable(settings):
                return saved
        except (json.JSONDecodeError, OSError):
            pass  # a damaged file is simply re-run
    r = evaluate(tracker, clip, seed=seed, max_frames=max_frames, **(params or {}))
    gt = clip.groundtruth[: len(r.boxes)]
    row = {"tracker": tracker, "clip": clip.name, "frames": int(len(r.boxes)), **r.scores}
    for k, v in r.extras.items():
        row[k] = float(np.nanmean(v))
    rec = {"settings": settings, "row": row, "boxes": r.boxes, "ms": r.ms,
           "params": r.params, "attributes": list(clip.attributes)}
    try:
        rec["success"] = metrics.success_curve(r.boxes[1:], gt[1:])[1]
        rec["precision"] = metrics.precision_curve(r.boxes[1:], gt[1:])[1]
    except ValueError:
        pass
    rec = _jsonable(rec)
    write_atomic(path, json.dumps(rec))
    return rec


def run(trackers, clips, out, seed=0, max_frames=None, params=None, progress=True,
        force=False, reference=True) -> list[dict]:
    """Run every tracker on every clip; write the tables and plots; return the rows.

    Parameters
    ----------
    trackers : list of names (or comma-separated string)
    clips : clip specs (see :func:`resolve_clips`)
    out : output folder
    params : dict tracker name -> dict of params
    reference : also run OpenCV's MIL (the reference row of every table)
    """
    if isinstance(trackers, str):
        trackers = [t for t in trackers.split(",") if t]
    trackers = list(dict.fromkeys(trackers + ([REFERENCE] if reference else [])))
    clip_specs = resolve_clips(clips)
    params = params or {}
    tasks = [(t, c) for c in clip_specs for t in trackers]
    records = []
    bar = None
    if progress:
        from tqdm.auto import tqdm
        bar = tqdm(total=len(tasks), desc="bench", unit="run")
    for t, c in tasks:
        if bar is not None:
            bar.set_postfix_str(f"{t} on {Path(str(c)).name}")
        records.append(run_one(t, c, out, seed, max_frames, params.get(t), force))
        if bar is not None:
            bar.update(1)
    if bar is not None:
        bar.close()
    rows = [r["row"] for r in records]
    write_summary(records, out)
    return rows


def load(out) -> list[dict]:
    """The rows of ``OUT/results.json`` (what a chapter reads back)."""
    return json.loads((Path(out) / "results.json").read_text())


def load_curves(out) -> dict:
    """``{tracker: {clip: {"success": [21], "precision": [51]}}}`` from ``OUT/curves.json``."""
    return json.loads((Path(out) / "curves.json").read_text())


def summarize(rows) -> list[dict]:
    """Per-tracker means over clips: AUC, precision, tracking rate; median of ms/frame."""
    by = {}
    for r in rows:
        by.setdefault(r["tracker"], []).append(r)
    out = []
    for t, rs in by.items():
        def mean(k):
            v = [x[k] for x in rs if x.get(k) is not None]
            return float(np.mean(v)) if v else float("nan")
        out.append({"tracker": t, "clips": len(rs), "auc": mean("auc"),
                    "precision20": mean("precision20"), "tracking_rate": mean("tracking_rate"),
                    "ms_median": float(np.median([x["ms_median"] for x in rs]))})
    return out


def markdown_table(rows) -> str:
    """Per-tracker summary, then AUC per clip, as markdown."""
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
    cell = {(r["tracker"], r["clip"]): r for r in rows}
    for s in summ:
        vals = []
        for c in clip_names:
            r = cell.get((s["tracker"], c))
            vals.append("" if r is None or r.get("auc") is None else f"{r['auc']:.3f}")
        lines.append(f"| {s['tracker']} | " + " | ".join(vals) + " |")
    return "\n".join(lines) + "\n"


def write_summary(records, out) -> None:
    """results.csv / results.json / table.md / success.png / precision.png from the runs."""
    out = Path(out)
    rows = [r["row"] for r in records]
    extra_cols = sorted({k for r in rows for k in r} - set(COLUMNS))
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=COLUMNS + extra_cols, extrasaction="ignore")
    w.writeheader()
    for r in rows:
        w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in COLUMNS + extra_cols})
    write_atomic(out / "results.csv", buf.getvalue())
    write_atomic(out / "results.json", json.dumps(rows, indent=1))
    curves = {}
    for r in records:
        if "success" in r:
            curves.setdefault(r["row"]["tracker"], {})[r["row"]["clip"]] = {
                "success": r["success"], "precision": r["precision"]}
    write_atomic(out / "curves.json", json.dumps(curves))
    write_atomic(out / "table.md", markdown_table(rows))
    _plot(records, out)


def _plot(records, out):
    # A bare Figure (no pyplot): drawing the plots must not touch the global backend, or a
    # benchmark run inside a notebook would switch the kernel away from inline figures.
    from matplotlib.figure import Figure

    from ..viz.core import CYCLE

    by = {}
    for r in records:
        if "success" in r:
            by.setdefault(r["row"]["tracker"], []).append(r)
    for kind, xs, xlabel in (("success", metrics.SUCCESS_THRESHOLDS, "overlap threshold"),
                             ("precision", metrics.PRECISION_THRESHOLDS, "centre error (px)")):
        fig = Figure(figsize=(5, 3.6))
        ax = fig.subplots()
        for i, (t, rs) in enumerate(by.items()):
            curve = np.mean([r[kind] for r in rs], axis=0)
            score = curve.mean() if kind == "success" else curve[20]
            ax.plot(xs, curve, color=CYCLE[i % len(CYCLE)], label=f"{t} [{score:.3f}]")
        ax.set(xlabel=xlabel, ylabel="fraction of frames", ylim=(0, 1.02),
               title=f"{kind} plot, mean over clips")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=110)
        write_atomic(out / f"{kind}.png", buf.getvalue())
