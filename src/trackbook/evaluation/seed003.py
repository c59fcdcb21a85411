"""Cho & Kang 2005's Tables 1-2 on our data: ms per frame and accuracy of the three trackers.

Regenerate the committed real-sequence table of the Cho & Kang lab notes (chapter 8) with::

    TRACKBOOK_SEQUENCES=/path/to/sequences python -m trackbook.evaluation.seed003 \\
        --out book/results/seed003_real.csv

(the sequences are the OTB/VOT folders of the development set; ``opencv-mil`` is added on
MotorRolling as the speed reference). The sample-clip tables are computed live by the chapter
with :func:`single_target_table` and :func:`two_target_table`.

The speed check of the three trackers next to ``opencv-mil`` (median of 3 runs of
``evaluate(...).scores["ms_median"]``, with the machine's load average) is::

    python -m trackbook.evaluation.seed003 --speed MotorRolling
"""

from __future__ import annotations

import argparse
import csv
import os
from pathlib import Path

import numpy as np

from .. import clips as _clips
from . import metrics
from .runner import evaluate

TRACKERS = ("condensation", "mean-shift", "condensation-mean-shift")
#: Table 1 and Table 2 of the paper, ms per frame (320x240, Pentium 4 1.5 GHz).
PAPER_MS = {"single": {"condensation": 84.0, "mean-shift": 7.0, "condensation-mean-shift": 35.0},
            "two": {"condensation": 248.0, "mean-shift": 17.0, "condensation-mean-shift": 86.0}}


def single_target_table(clip_names, trackers=TRACKERS, seed=0, max_frames=None) -> list[dict]:
    """One row per (tracker, clip): ms_median, auc, precision20, mean candidate likelihood."""
    rows = []
    for c in clip_names:
        clip = _clips.load(c)
        for t in trackers:
            r = evaluate(t, clip, seed=seed, max_frames=max_frames)
            lik = r.extras.get("mean_likelihood")
            rows.append({"tracker": t, "clip": clip.name, "frames": len(r.boxes),
                         "auc": r.scores["auc"], "precision20": r.scores["precision20"],
                         "ms_median": r.scores["ms_median"], "ms_mean": r.scores["ms_mean"],
                         "mean_likelihood": float(np.nanmean(lik[1:])) if lik is not None
                         else float("nan"),
                         "paper_ms": PAPER_MS["single"].get(t, float("nan"))})
    return rows


def two_target_table(clip_name="two-faces", trackers=TRACKERS, seed=0, max_frames=None):
    """One row per tracker: ms per frame for all targets at once and each target's AUC."""
    clip = _clips.load(clip_name)
    rows = []
    for t in trackers:
        res = evaluate(t, clip, seed=seed, max_frames=max_frames, targets="all")
        row = {"tracker": t, "clip": clip.name, "ms_median": res.scores["ms_median"],
               "paper_ms": PAPER_MS["two"][t]}
        for name, r in res.results.items():
            row[f"auc_{name}"] = metrics.auc(r.boxes[1:], clip.targets[name][1:len(r.boxes)])
        rows.append(row)
    return rows


def speed_table(clip_name, trackers=TRACKERS + ("opencv-mil",), runs: int = 3, seed=0):
    """ms per frame of each tracker on one clip: the median over ``runs`` runs of
    ``evaluate(...).scores["ms_median"]``, with the 1-minute load average before and after
    (timings on a shared machine mean little without it)."""
    clip = _clips.load(clip_name)
    rows = []
    for t in trackers:
        load0 = os.getloadavg()[0]
        ms, r = [], None
        for _ in range(runs):
            r = evaluate(t, clip, seed=seed)
            ms.append(r.scores["ms_median"])
        rows.append({"tracker": t, "clip": clip.name, "ms_median": float(np.median(ms)),
                     "ms_runs": " ".join(f"{v:.2f}" for v in ms), "auc": r.scores["auc"],
                     "load_before": load0, "load_after": os.getloadavg()[0]})
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="book/results/seed003_real.csv")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--speed", metavar="CLIP", help="only time the trackers on CLIP (a sample "
                    "name, a sequence name or folder) next to opencv-mil and print the table")
    args = ap.parse_args(argv)
    if args.speed:
        rows = speed_table(args.speed, seed=args.seed)
        from .._markdown import table

        print(table(rows, number=".3f"))
        return 0
    seqs = _clips.find_sequences()
    if not seqs:
        raise SystemExit("no sequences found: set TRACKBOOK_SEQUENCES to the sequences folder")
    rows = single_target_table([str(p) for p in seqs.values()], seed=args.seed)
    if "MotorRolling" in seqs:
        rows += single_target_table([str(seqs["MotorRolling"])], trackers=("opencv-mil",),
                                    seed=args.seed)
    load = os.getloadavg()[0]
    for r in rows:
        r["load_after"] = load     # the 1-minute load average when the table was written
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_suffix(".tmp")
    with open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.4f}" if isinstance(v, float) else v) for k, v in r.items()})
    os.replace(tmp, out)
    print(f"wrote {out} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
