"""Table 1 of Lee 2015: misses, detection rate, averaging search rate, ms/frame.

The paper's detection rate (eq. 14) is "frames where the region was detected / all frames";
the book counts a frame as detected when IoU > 0.5 (:func:`trackbook.metrics.tracking_rate`),
and a miss is any other scored frame. The averaging search rate is the mean over frames of
evaluated candidate windows / all windows in the frame (the trackers' ``frame_report``).

Regenerate the committed real-sequence table of chapter 7 and its lab notes with::

    PYTHONPATH=src python -m trackbook.evaluation.table_seed002 book/results/seed002_real.csv

and try other settings of the seed-002 trackers with ``... OUT.csv manoeuvre_gate=0`` (the
paper's behaviour) or any other ``param=value``.
"""

from __future__ import annotations

import ast
import csv
import dataclasses
import os
import sys

import numpy as np

from .. import clips as _clips
from . import metrics
from .runner import evaluate

#: Table 1 of Lee 2015 (RedCube, 164 frames), as printed.
PAPER_TABLE1 = {
    "covariance": {"misses": 21, "frames": 164, "detection_rate": 0.871, "search_rate": 0.00134},
    "kalman-covariance": {"misses": 6, "frames": 164, "detection_rate": 0.963,
                          "search_rate": 0.00043},
}

COLUMNS = ["tracker", "clip", "frames", "misses", "detection_rate", "search_rate", "auc",
           "precision20", "ms_median", "ms_mean"]


def table1_row(result, groundtruth) -> dict:
    """One row of Table 1 from a :class:`trackbook.Result` (frame 0, the initialisation, excluded)."""
    gt = np.asarray(groundtruth, dtype=float)[: len(result.boxes)]
    iou = metrics.iou(result.boxes[1:], gt[1:])
    known = np.all(np.isfinite(gt[1:]), axis=1)
    sr = result.extras.get("search_rate")
    return {
        "tracker": result.tracker,
        "clip": result.clip,
        "frames": int(known.sum()),
        "misses": int(np.sum(iou[known] <= 0.5)),
        "detection_rate": metrics.tracking_rate(result.boxes[1:], gt[1:]),
        "search_rate": float(np.nanmean(sr[1:])) if sr is not None else float("nan"),
        "auc": result.scores["auc"],
        "precision20": result.scores["precision20"],
        "ms_median": result.scores["ms_median"],
        "ms_mean": result.scores["ms_mean"],
    }


def run(clip_names, trackers=("covariance", "kalman-covariance", "opencv-mil"), seed=0,
        max_frames=None, **params) -> list[dict]:
    """Table-1 rows for every tracker on every clip (params go to the seed-002 trackers)."""
    from .. import trackers as _trackers
    rows = []
    for name in clip_names:
        clip = _clips.load(name)
        for t in trackers:
            # Each tracker gets the params it has (manoeuvre_* exist only for kalman-covariance).
            fields = {f.name for f in dataclasses.fields(_trackers.get(t).Params)}
            kw = {k: v for k, v in params.items() if k in fields}
            r = evaluate(t, clip, seed=seed, max_frames=max_frames, **kw)
            rows.append(table1_row(r, clip.groundtruth))
    return rows


#: Where the committed real-sequence table lives, relative to the repository root.
REAL_CSV = os.path.join("book", "results", "seed002_real.csv")


def read_real_table(path=None) -> list[dict]:
    """The committed real-sequence Table-1 rows (numbers as floats) for chapter 7 and its lab notes.

    Looked up as ``path`` if given, else by :func:`trackbook.evaluation.results.path`, so the
    book never needs the sequences themselves.
    """
    from . import results

    with open(path if path is not None else results.path("seed002_real.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["frames"], r["misses"] = int(r["frames"]), int(r["misses"])
        for k in COLUMNS[4:]:
            r[k] = float(r[k]) if r.get(k) not in (None, "") else float("nan")
    return rows


def write_csv(rows, path) -> None:
    """Write rows atomically (a temporary file renamed into place)."""
    tmp = f"{path}.tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for row in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    os.replace(tmp, path)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) < 1 or not all("=" in a for a in argv[1:]):
        print("usage: python -m trackbook.evaluation.table_seed002 OUT.csv [param=value ...]",
              file=sys.stderr)
        return 2
    params = {k: ast.literal_eval(v) for k, v in (a.split("=", 1) for a in argv[1:])}
    seqs = _clips.find_sequences()
    if not seqs:
        print("no real sequences found (../shared/data/sequences)", file=sys.stderr)
        return 1
    rows = []
    for name in seqs:
        rows += run([seqs[name]], **params)
        for r in rows[-3:]:
            print(f"{r['clip']:14s} {r['tracker']:18s} auc={r['auc']:.3f} "
                  f"rate={r['detection_rate']:.3f} sr={r['search_rate']:.5f} "
                  f"ms={r['ms_median']:.2f}", flush=True)
    write_csv(rows, argv[0])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
