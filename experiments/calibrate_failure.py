"""Calibrate the failure rule for every tracker on the calibration scenes.

Every tracker of ``trackbook.trackers.available()`` (and OpenCV's ``opencv-mil`` unless
``--no-mil``: about 100 ms a frame; not the ``-redetect`` variants, which share their
algorithm's thresholds), with its failure layer off (``failure=False``), runs over
``trackbook.clips.calibration_set`` (seven kinds
of disappearance: leaving the frame, an occluder, a camera cut, a fade to black, shrinking
away, heavy blur, a look-alike while the target is covered). For every frame after the first
the script records the tracker's own confidence (``tracker.state().confidence``), the IoU
with the ground truth and whether the target is absent; then
``trackbook.evaluation.failure.calibrate`` chooses each tracker's thresholds of the rule
(``trackbook.trackers.failure.FailureDetector``): flag at least 95 % of the absent frames
while flagging at most 1 % of the frames on target (IoU > 0.5, at least half of the target
in view and lit by at least half of the light, not the first 3 frames after a return: the
rule needs 3 frames to trust it) lost. A frame of a fade lit by less than half of the light
but more than a tenth (under a tenth the target is absent) is neither: a rule may call the
target lost in a picture that dark, and need not.

That first pass replays the rule on runs without the layer, where the tracker kept learning
after it would have been lost; it cannot see what the layer does (a lost tracker stops
learning, a background it stares at may pass a loose found threshold, and blank frames and an
algorithm's own rule count as lost). So a second pass runs each tracker with its layer on over the same
scenes, with the found thresholds chosen and, where it changes them, with ``floor_found``'s
(``ratio_found`` at least 0.8, ``k_found`` at most 4, for the tests in use), and keeps the better by the same objective, the
first on a tie (``found_floored`` and ``with_layer`` in each row: both candidates' rates, on
target judged with the box the tracker reports).

With the real sequences present (``../shared/data/sequences``; ``--no-sequences`` skips
them), each tracker also runs over them and the confidence's ROC is taken for "on target"
(IoU > 0.5) against "off target" (IoU = 0: the box has left the target), the only negatives
sequences without absent frames have.

It writes ``src/trackbook/data/failure_calibration.json`` (tracker -> thresholds,
achieved rates, ROC AUC and thinned ROC curve of the confidence, the same on the real
sequences; the set's seed and size; the library version and
``git describe``) and prints a table tracker x kind: share of absent frames flagged / share
of on-target frames flagged (false losses) / ROC AUC of the confidence.

    PYTHONPATH=src python experiments/calibrate_failure.py [--quick] [--no-mil]
        [--per-kind N] [--seed S] [--trackers a,b] [--out FILE] [--force]

``--quick`` uses 2 scenes per kind (a smoke test); the default is 6. The default took about
16 minutes on two cores for the twenty trackers: 3 recording the runs, 3 the grid, 8 the
second pass (``opencv-mil`` 2 of them), 2 the real sequences.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import trackbook
from trackbook import trackers
from trackbook.clips.failure_scenes import KINDS, calibration_set
from trackbook.evaluation.runner import evaluate_many
from trackbook.evaluation.failure import (calibrate, detection_rates, floor_found, judged_rates,
                                          objective, roc_auc, roc_curve)
from trackbook.evaluation.metrics import iou as box_iou
from trackbook.trackers.failure import FailureParams

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "src" / "trackbook" / "data" / "failure_calibration.json"
ON_TARGET_IOU = 0.5
MIN_VISIBLE = 0.5
MIN_LIGHT = 0.5


class NoConfidence(RuntimeError):
    """A tracker's state has no ``confidence``."""


@dataclasses.dataclass
class Run:
    """One tracker on one scene, frames 1..N-1 (frame 0 is the given box)."""

    kind: str
    confidence: np.ndarray
    iou: np.ndarray
    absent: np.ndarray
    visible: np.ndarray
    light: np.ndarray

    @property
    def on_target(self) -> np.ndarray:
        """Frames the rule should call ok: the box on the target (IoU > 0.5), at least half
        of the target in view and at least half of the light (a target mostly out of the
        frame, behind a panel or in the dark may well be called lost)."""
        return on_target(self.iou, self.absent, self.visible, self.light)


def on_target(iou, absent, visible, light) -> np.ndarray:
    """See :attr:`Run.on_target`."""
    return ~absent & (iou > ON_TARGET_IOU) & (visible >= MIN_VISIBLE) & (light >= MIN_LIGHT)


def confidence_of(tracker) -> float:
    """``tracker.state().confidence`` as a float (NaN on the first frame, which is given, not
    tracked), or :class:`NoConfidence` when a tracked frame has none."""
    st = tracker.state()
    c = getattr(st, "confidence", None)
    if c is None and getattr(tracker, "frame_index", 0) > 0:
        name = getattr(tracker, "name", type(tracker).__name__)
        hint = " (or leave it out with --no-mil)" if name == "opencv-mil" else ""
        raise NoConfidence(
            f"tracker {name!r} reports no confidence: its state() has 'confidence' None; "
            f"the failure rule is calibrated on TrackerState.confidence, so give the tracker "
            f"a _last_confidence() first{hint}.")
    return math.nan if c is None else float(c)


def run_with_confidence(names, clip, seed: int = 0):
    """Every tracker of ``names`` over ``clip`` in lockstep, the failure layer off: their
    results and an ``(n_trackers, n_frames)`` array of ``state().confidence`` (NaN on frame
    0, which is given, not tracked)."""
    made = [trackers.create(n, seed=seed, failure=False) for n in names]
    conf = np.full((len(made), len(clip)), np.nan)
    index = {id(t): j for j, t in enumerate(made)}

    def hook(i, tracker, frame, box):
        if i > 0:
            conf[index[id(tracker)], i] = confidence_of(tracker)

    return in_lockstep(made, clip, on_frame=hook), conf


def in_lockstep(made, clip, on_frame=None):
    """The results of the trackers ``made`` over ``clip`` in lockstep; each is closed after
    (``opencv-mil`` runs in a child process)."""
    try:
        return evaluate_many([(t, None, {}) for t in made], clip, on_frame=on_frame)
    finally:
        for t in made:
            close = getattr(t, "close", None)
            if callable(close):
                close()


def record(names, scenes, seed: int = 0, log=None) -> dict:
    """``{tracker: [Run per scene]}``: every tracker over every scene, in lockstep per scene."""
    out = {n: [] for n in names}
    for k, sc in enumerate(scenes):
        t0 = time.perf_counter()
        # the algorithm alone (failure=False): the layer's thresholds are what is being chosen
        results, conf = run_with_confidence(names, sc.clip, seed)
        for j, (n, r) in enumerate(zip(names, results)):
            iou = np.nan_to_num(box_iou(r.boxes, sc.clip.groundtruth), nan=0.0)
            out[n].append(Run(sc.kind, conf[j, 1:], iou[1:], np.asarray(sc.absent)[1:],
                              np.asarray(sc.visible)[1:], np.asarray(sc.light)[1:]))
        if log:
            log(f"scene {k + 1}/{len(scenes)} ({sc.kind}, {len(sc.clip)} frames): "
                f"{time.perf_counter() - t0:.1f} s")
    return out


def _classes(runs):
    on = [r.confidence[r.on_target] for r in runs]
    off = [r.confidence[r.absent] for r in runs]
    return np.concatenate(on or [[]]), np.concatenate(off or [[]])


def _auc(runs) -> float:
    on, off = _classes(runs)
    return roc_auc(on, off) if on.size and off.size else math.nan


#: Points kept of each ROC curve in the JSON (enough to draw it).
ROC_POINTS = 60


def thin_roc(on, off) -> dict:
    """The ROC curve of confidences ``on`` (positives) against ``off``, thinned to at most
    ``ROC_POINTS`` points spread evenly along its false-positive axis (ends kept)."""
    if not (np.size(on) and np.size(off)):
        return {"fpr": [], "tpr": []}
    fpr, tpr, _ = roc_curve(on, off)
    keep = np.unique(np.r_[0, np.searchsorted(fpr, np.linspace(0, 1, ROC_POINTS)).clip(
        0, fpr.size - 1), fpr.size - 1])
    return {"fpr": [round(float(v), 5) for v in fpr[keep]],
            "tpr": [round(float(v), 5) for v in tpr[keep]]}


def record_sequences(names, seqs, seed: int = 0, log=None) -> dict:
    """On real sequences (no absent frames): ``{tracker: (conf on target, conf off target)}``
    where on target is IoU > 0.5 and off target IoU = 0 (the box has left the target)."""
    out = {n: ([], []) for n in names}
    for name, path in seqs.items():
        t0 = time.perf_counter()
        clip = trackbook.clips.load(str(path))
        results, conf = run_with_confidence(names, clip, seed)
        for j, (n, r) in enumerate(zip(names, results)):
            iou = np.nan_to_num(box_iou(r.boxes, clip.groundtruth), nan=0.0)[1:]
            c = conf[j, 1:]
            out[n][0].append(c[iou > ON_TARGET_IOU])
            out[n][1].append(c[iou == 0.0])
        if log:
            log(f"sequence {name} ({len(clip)} frames): {time.perf_counter() - t0:.1f} s")
    return {n: (np.concatenate(a), np.concatenate(b)) for n, (a, b) in out.items()}


def _rates(runs, params) -> dict:
    return detection_rates([r.confidence for r in runs], [r.absent for r in runs],
                           [r.on_target for r in runs], params)


def with_layer(name: str, candidates, scenes, seed: int = 0) -> list[dict]:
    """The second pass: tracker ``name`` run with its layer on, once per
    :class:`~trackbook.trackers.failure.FailureParams` of ``candidates`` (in lockstep per
    scene), over ``scenes``; the rates of
    :func:`~trackbook.evaluation.failure.judged_rates` per candidate. On target is as in
    :attr:`Run.on_target`, with the box the tracker reports: a run that stops learning when
    lost is judged on what it does, not on what the algorithm alone would have done."""
    ok, on = [[] for _ in candidates], [[] for _ in candidates]
    absent = []                                   # the scene's, the same for every candidate
    for sc in scenes:
        results = in_lockstep([trackers.create(name, seed=seed, failure=p)
                               for p in candidates], sc.clip)
        absent.append(np.asarray(sc.absent, bool)[1:])
        for j, r in enumerate(results):
            iou = np.nan_to_num(box_iou(r.boxes, sc.clip.groundtruth), nan=0.0)[1:]
            ok[j].append(np.asarray(r.ok, bool)[1:])
            on[j].append(on_target(iou, absent[-1], np.asarray(sc.visible)[1:],
                                   np.asarray(sc.light)[1:]))
    return [judged_rates(ok[j], absent, on[j], p.m) for j, p in enumerate(candidates)]


def choose_found(name: str, row: dict, scenes, seed: int = 0, target: float = 0.95,
                 max_false: float = 0.01, log=None) -> dict:
    """Keep the first pass's found thresholds or :func:`floor_found`'s, whichever does better
    by the calibration's objective with the layer on (a tie keeps the first pass's); the row
    gets the chosen thresholds, ``found_floored`` and ``with_layer`` (both candidates'
    thresholds and rates)."""
    # the row as summarise made it: its thresholds are floats (inf, not yet JSON's null)
    first = FailureParams(**{f.name: row[f.name] for f in dataclasses.fields(FailureParams)})
    floored = floor_found(first)
    cands = [first] if floored == first else [first, floored]
    t0 = time.perf_counter()
    rates = with_layer(name, cands, scenes, seed)
    keys = [objective(r["absent_lost"], r["false_lost"], target, max_false) + (j == 0,)
            for j, r in enumerate(rates)]
    best = max(range(len(cands)), key=keys.__getitem__)
    if log:
        log(f"{name} with the layer on: {time.perf_counter() - t0:.1f} s")
    chosen = cands[best]
    out = {**row, "k_found": chosen.k_found, "ratio_found": chosen.ratio_found,
           "found_floored": best == 1}
    out["with_layer"] = {
        label: {"k_found": p.k_found, "ratio_found": p.ratio_found,
                "absent_lost": r["absent_lost"], "false_lost": r["false_lost"],
                "n_absent": r["n_absent"], "n_on": r["n_on"]}
        for label, p, r in zip(("first_pass", "floored"), cands, rates)}
    if floored == first:
        out["with_layer"]["floored"] = out["with_layer"]["first_pass"]
    return out


def summarise(name: str, runs, **options) -> dict:
    """The JSON row of one tracker: chosen thresholds, achieved rates, ROC AUC, per kind."""
    cal = calibrate([r.confidence for r in runs], [r.absent for r in runs],
                    [r.on_target for r in runs], **options)
    per_kind = {}
    for kind in dict.fromkeys(r.kind for r in runs):
        sub = [r for r in runs if r.kind == kind]
        rates = _rates(sub, cal.params)
        per_kind[kind] = {"absent_lost": rates["absent_lost"], "false_lost": rates["false_lost"],
                          "n_absent": rates["n_absent"], "n_on": rates["n_on"],
                          "roc_auc": _auc(sub)}
    return {"tracker": name, **dataclasses.asdict(cal.params),
            "absent_lost": cal.absent_lost, "false_lost": cal.false_lost,
            "feasible": cal.feasible, "meets_target": cal.meets_target,
            "n_absent": cal.n_absent, "n_on": cal.n_on, "roc_auc": _auc(runs),
            "roc": thin_roc(*_classes(runs)), "per_kind": per_kind}


def summarise_real(row: dict, on, off) -> dict:
    """Add the real sequences' ROC (on target against off target) to a tracker's row."""
    auc = roc_auc(on, off) if on.size and off.size else math.nan
    return {**row, "real_roc_auc": auc, "real_n_on": int(on.size), "real_n_off": int(off.size),
            "real_roc": thin_roc(on, off)}


def _cell(v, fmt="{:.2f}") -> str:
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else fmt.format(v)


def table(rows, kinds) -> str:
    """Markdown: tracker x kind, each cell ``absent flagged / false losses / ROC AUC``."""
    head = ["tracker", "k_lost / k_found", "ratio_lost / ratio_found"] + list(kinds) + ["all"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        cells = [r["tracker"], f"{_cell(r['k_lost'], '{:g}')} / {_cell(r['k_found'], '{:g}')}",
                 f"{r['ratio_lost']:g} / {r['ratio_found']:.2f}"]
        for k in kinds:
            p = r["per_kind"].get(k, {})
            cells.append(f"{_cell(p.get('absent_lost'))} / {_cell(p.get('false_lost'), '{:.3f}')}"
                         f" / {_cell(p.get('roc_auc'))}")
        cells.append(f"{_cell(r['absent_lost'])} / {_cell(r['false_lost'], '{:.3f}')} / "
                     f"{_cell(r['roc_auc'])}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def git_describe() -> str:
    try:
        return subprocess.run(["git", "describe", "--always", "--dirty", "--tags"], cwd=ROOT,
                              capture_output=True, text=True, check=True,
                              timeout=30).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def _json_safe(x):
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {k: _json_safe(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_json_safe(v) for v in x]
    if isinstance(x, (np.floating, np.integer, np.bool_)):
        return _json_safe(x.item())
    return x


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="2 scenes per kind (a smoke test)")
    ap.add_argument("--per-kind", type=int, default=None, help="scenes per kind (default 6)")
    ap.add_argument("--seed", type=int, default=0, help="the calibration set's seed")
    ap.add_argument("--trackers", default=None, help="comma-separated names (default: all)")
    ap.add_argument("--no-mil", action="store_true", help="leave out opencv-mil (slow)")
    ap.add_argument("--out", default=str(OUT), help="the JSON file to write")
    ap.add_argument("--force", action="store_true", help="overwrite --out if it exists")
    ap.add_argument("--no-sequences", action="store_true",
                    help="skip the real sequences' ROC (on target against off target)")
    return ap.parse_args(argv)


def main(argv=None) -> int:
    a = parse(sys.argv[1:] if argv is None else argv)
    per_kind = a.per_kind if a.per_kind is not None else (2 if a.quick else 6)
    if per_kind < 1 or a.seed < 0:
        print("error: --per-kind must be >= 1 and --seed >= 0.", file=sys.stderr)
        return 2
    if a.trackers:
        names = [n.strip() for n in a.trackers.split(",") if n.strip()]
        known = trackers.available(reference=True)
        unknown = [n for n in names if n not in known]
        if unknown:
            print(f"error: unknown tracker(s) {', '.join(unknown)}; known: {', '.join(known)}.",
                  file=sys.stderr)
            return 2
    else:
        # a -redetect variant judges the same confidence with the same thresholds
        names = [n for n in trackers.available(reference=not a.no_mil)
                 if not n.endswith("-redetect")]
    if a.no_mil:
        names = [n for n in names if n != "opencv-mil"]
    out = Path(a.out)
    if out.exists() and not a.force:
        print(f"error: {out} exists; pass --force to overwrite it.", file=sys.stderr)
        return 2
    scenes = calibration_set(seed=a.seed, per_kind=per_kind)

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    try:
        runs = record(names, scenes, log=log)
    except NoConfidence as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    options = {"m": 3, "window": 30, "warmup": 5, "target": 0.95, "max_false": 0.01}
    rows = [summarise(n, runs[n], **options) for n in names]
    rows = [choose_found(r["tracker"], r, scenes, a.seed, options["target"],
                         options["max_false"], log) for r in rows]
    seqs = trackbook.clips.find_sequences() if not a.no_sequences else {}
    if seqs:
        real = record_sequences(names, seqs, log=log)
        rows = [summarise_real(r, *real[r["tracker"]]) for r in rows]
    doc = {"name": "failure_calibration",
           "description": "thresholds of the failure rule per tracker, calibrated on the "
                          "calibration scenes (trackbook.clips.calibration_set)",
           "command": "python experiments/calibrate_failure.py"
                      + (" --quick" if a.quick else "") + (" --no-mil" if a.no_mil else ""),
           "seed": a.seed, "per_kind": per_kind, "scenes": len(scenes), "kinds": list(KINDS),
           "frames": int(sum(len(r.confidence) for r in runs[names[0]])) if names else 0,
           "on_target_iou": ON_TARGET_IOU, "on_target_min_visible": MIN_VISIBLE,
           "on_target_min_light": MIN_LIGHT, **options,
           "sequences": sorted(seqs),
           "version": trackbook.__version__, "git": git_describe(), "rows": rows}
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(_json_safe(doc), indent=1) + "\n")
    print(table(rows, KINDS))
    log(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
