"""The benchmark's evaluation protocols: one (tracker, clip, seed) run of the bench through
OTB's one-pass evaluation (``ope``, the default), temporal or spatial robustness (``tre``,
``sre``) or VOT's reset-based protocol (``reset``), and the tables of such runs.

A protocol is named by a short spec: ``ope``, ``tre`` (OTB's 20 starts), ``tre:N`` (N starts,
at least 2), ``sre`` or ``reset`` (VOT: re-initialise 5 frames after a failure, 10 frames of
burn-in). :func:`record` runs one task through :mod:`trackbook.evaluation.protocols` and
returns what the bench saves; :func:`summary` and :func:`markdown_table` turn saved records
into the tables. Writing files is the bench's (:mod:`trackbook.evaluation.bench`); this module
only computes, so :mod:`trackbook.evaluation.runs` can call it from a worker.
"""

from __future__ import annotations

import dataclasses
import io
import re

import numpy as np

from . import metrics, protocols

#: The protocols ``trackbook bench --protocol`` accepts (``tre:N`` too).
PROTOCOLS = ("ope", "tre", "sre", "reset")
#: OTB's number of TRE starts (Wu et al. 2013).
TRE_STARTS = 20


def parse(spec) -> tuple[str, int | None]:
    """``"ope"``, ``"tre"``, ``"tre:N"``, ``"sre"`` or ``"reset"`` -> ``(name, starts)``;
    ``starts`` is TRE's number of starts (None for the other protocols). Anything else is a
    ``ValueError`` of one line naming the accepted forms."""
    s = str(spec).strip().lower()
    m = re.fullmatch(r"tre(?::(\d{1,4}))?", s)
    if m:
        n = int(m.group(1)) if m.group(1) else TRE_STARTS
        if n >= 2:
            return "tre", n
    elif s in PROTOCOLS:
        return s, None
    raise ValueError(f"protocol {spec!r}: use ope (one pass, the default), tre (OTB's 20 "
                     "starts; tre:N for N >= 2 starts), sre (12 shifted and scaled first "
                     "boxes) or reset (VOT's re-initialisation after each failure).")


def canonical(spec) -> str:
    """The spec as the bench records it: ``tre:20`` is written ``tre``."""
    name, n = parse(spec)
    return name if n in (None, TRE_STARTS) else f"{name}:{n}"


def first_frames(clip, max_frames):
    """The clip's first ``max_frames`` frames (all when None): a protocol runs on that clip,
    so TRE's starts and the reset protocol's lengths are those of the shortened clip."""
    if max_frames is None or int(max_frames) >= len(clip):
        return clip
    n = int(max_frames)
    return dataclasses.replace(clip, frames=clip.frames[:n], groundtruth=clip.groundtruth[:n],
                               targets={k: v[:n] for k, v in clip.targets.items()})


def record(task, clip) -> dict:
    """Run ``task`` (a :class:`~trackbook.evaluation.runs.Task` whose ``protocol`` is not
    ``ope``) on ``clip`` and return its record: ``key``, ``settings``, ``row`` (the scores of
    the results table) and what the pooled tables need (TRE/SRE: the pooled success and
    precision curves and each run's start, first box and AUC; reset: the overlaps, the
    initialisation and failure frames)."""
    name, n = parse(task.protocol)
    clip = first_frames(clip, task.max_frames)
    args = dict(seed=task.seed, preset=task.preset, **dict(task.params))
    row = {"tracker": task.tracker, "clip": clip.name, "frames": len(clip),
           "protocol": canonical(task.protocol)}
    rec = {"key": task.key, "settings": task.settings, "protocol": row["protocol"]}
    if name == "reset":
        run = protocols.evaluate_reset(task.tracker, clip, **args)
        row.update(accuracy=run.accuracy, failures=run.n_failures,
                   failure_rate=run.failure_rate, reliability=run.reliability(),
                   eao=protocols.eao([run]))
        rec.update(overlaps=run.overlaps, inits=list(run.inits), failures=list(run.failures),
                   burnin=run.burnin)
    else:
        res = (protocols.evaluate_tre(task.tracker, clip, n_segments=n, **args)
               if name == "tre" else protocols.evaluate_sre(task.tracker, clip, **args))
        row.update(runs=len(res.results), **res.scores)
        boxes = np.concatenate([r.boxes[1:] for r in res.results])
        gts = np.concatenate([clip.groundtruth[s + 1:s + len(r.boxes)]
                              for s, r in zip(res.starts, res.results)])
        rec.update(starts=res.starts, labels=list(res.labels), init_boxes=res.init_boxes,
                   run_auc=[r.scores["auc"] for r in res.results],
                   success=metrics.success_curve(boxes, gts)[1],
                   precision=metrics.precision_curve(boxes, gts)[1])
    rec["row"] = row
    return rec


def reset_run(rec) -> protocols.ResetRun:
    """A saved reset record back as a :class:`~trackbook.evaluation.protocols.ResetRun`."""
    ov = np.array([np.nan if v is None else v for v in rec["overlaps"]], dtype=float)
    return protocols.ResetRun(np.full((len(ov), 4), np.nan), ov, tuple(rec["inits"]),
                              tuple(rec["failures"]), int(rec["burnin"]),
                              rec["row"]["tracker"], rec["row"]["clip"])


def _by_tracker(records) -> dict:
    by: dict = {}
    for r in records:
        by.setdefault(r["row"]["tracker"], []).append(r)
    return by


def summary(records) -> list[dict]:
    """One row per tracker over its records (all clips and seeds).

    TRE/SRE: ``runs`` (per clip), ``auc`` and ``precision20``, each the mean over clips
    (and seeds) of the clip's pooled score, as OTB's toolkit averages its per-sequence
    curves. Reset: ``accuracy``, the mean over clips of each clip's accuracy; ``failures``,
    the failures on all clips (mean over seeds); ``failure_rate``, failures per 100 frames
    over all clips; ``eao``, :func:`protocols.eao` of all the runs together (one curve over
    every fragment of every clip).
    """
    out = []
    for t, rs in _by_tracker(records).items():
        rows = [r["row"] for r in rs]
        n_seeds = len({r["settings"]["seed"] for r in rs})
        s = {"tracker": t, "clips": len({x["clip"] for x in rows})}
        if rows[0]["protocol"] == "reset":
            acc = [x["accuracy"] for x in rows if x.get("accuracy") is not None]
            fails = sum(x["failures"] for x in rows)
            s.update(accuracy=float(np.mean(acc)) if acc else float("nan"),
                     failures=fails / n_seeds,
                     failure_rate=100.0 * fails / sum(x["frames"] for x in rows),
                     eao=protocols.eao([reset_run(r) for r in rs]))
        else:
            s.update(runs=int(np.median([x["runs"] for x in rows])),
                     auc=float(np.mean([x["auc"] for x in rows])),
                     precision20=float(np.mean([x["precision20"] for x in rows])))
        out.append(s)
    return out


def markdown_table(records) -> str:
    """The protocol's table: per tracker (:func:`summary`), then the main score per clip."""
    from .._markdown import table

    summ = summary(records)
    if not summ:
        return "no runs\n"
    proto = records[0]["row"]["protocol"]
    name = parse(proto)[0].upper()
    if name == "RESET":
        cols = ["tracker", "clips", "accuracy", "failures", "failure_rate", "eao"]
        labels = {"failure_rate": "failures per 100 frames", "eao": "expected average overlap"}
        formats = {"accuracy": ".3f", "failures": ".3g", "failure_rate": ".2f", "eao": ".3f"}
        key, what = "accuracy", "Accuracy per clip (reset protocol):"
    else:
        cols = ["tracker", "clips", "runs", "auc", "precision20"]
        labels = {"runs": "runs per clip", "auc": f"mean AUC ({name})",
                  "precision20": f"mean precision@20 ({name})"}
        formats = {"auc": ".3f", "precision20": ".3f"}
        key, what = "auc", f"AUC per clip ({name}, runs pooled):"
    lines = [table(summ, cols, labels=labels, formats=formats,
                   align={c: "right" for c in cols[1:]})]
    clip_names = list(dict.fromkeys(r["row"]["clip"] for r in records))
    cell: dict = {}
    for r in records:
        if r["row"].get(key) is not None:
            cell.setdefault((r["row"]["tracker"], r["row"]["clip"]), []).append(r["row"][key])
    per_clip = [{"tracker": s["tracker"], **{c: float(np.mean(cell[(s["tracker"], c)]))
                                             for c in clip_names if cell.get((s["tracker"], c))}}
                for s in summ]
    lines += ["", what, "", table(per_clip, ["tracker", *clip_names], number=".3f",
                                  align={c: "right" for c in clip_names})]
    return "\n".join(lines) + "\n"


def curves(records) -> dict:
    """TRE/SRE: ``{tracker: {clip: {"success", "precision"}}}`` (mean over seeds of the
    pooled curves); reset: ``{tracker: {"eao_curve": [...]}}`` over all the runs (entry N is
    the expected average overlap of an N-frame sequence; entry 0 is None)."""
    if records and records[0]["row"]["protocol"] == "reset":
        return {t: {"eao_curve": protocols.eao_curve([reset_run(r) for r in rs])}
                for t, rs in _by_tracker(records).items()}
    out: dict = {}
    for t, rs in _by_tracker(records).items():
        by: dict = {}
        for r in rs:
            by.setdefault(r["row"]["clip"], []).append(r)
        out[t] = {c: {k: np.mean([r[k] for r in v], axis=0) for k in ("success", "precision")}
                  for c, v in by.items()}
    return out


def eao_plot(records) -> bytes:
    """A PNG of each tracker's expected average overlap curve (reset records)."""
    from matplotlib.figure import Figure

    from ..style import label_colors

    fig = Figure(figsize=(5, 3.6))
    ax = fig.subplots()
    by_curve = curves(records)
    colours = label_colors(by_curve)
    for i, (t, c) in enumerate(by_curve.items()):
        y = np.asarray(c["eao_curve"], dtype=float)
        score = protocols.eao([reset_run(r) for r in _by_tracker(records)[t]])
        ax.plot(np.arange(len(y)), y, color=colours[i], label=f"{t} [{score:.3f}]")
    ax.set(xlabel="sequence length N (frames)", ylabel="expected average overlap",
           ylim=(0, 1.02), title="expected average overlap curve (reset protocol)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    return buf.getvalue()
