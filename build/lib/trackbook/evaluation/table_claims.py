"""The runs behind chapter 09's verdicts: every tracker, both presets, the real sequences, 3 seeds.

Chapter 09 judges each paper's claim on paired per-sequence scores
(:func:`trackbook.evaluation.compare.check_claims`) for the printed method
(``preset="paper"``) and for the book's defaults (``preset="book"``), and chooses between the
two presets by leave-one-sequence-out cross-validation
(:func:`~trackbook.evaluation.compare.loso_select`). Both read this one table, so no two
numbers of the chapter come from different runs. Regenerate it with::

    PYTHONPATH=src python -m trackbook.evaluation.table_claims book/results/claims_real.csv

(about 10 minutes on 2 cores; ``--seeds 0-2`` and ``--workers N`` are the defaults' knobs).
"""

from __future__ import annotations

import argparse
import csv
import os
from concurrent.futures import ProcessPoolExecutor

from .. import clips as _clips
from .. import trackers as _trackers
from .runner import evaluate

COLUMNS = ["tracker", "preset", "clip", "seed", "frames", "auc", "precision20",
           "tracking_rate", "ms_median"]
PRESETS = ("book", "paper")


def _one(job) -> dict:
    tracker, preset, path, seed = job
    r = evaluate(tracker, str(path), seed=seed, preset=preset)
    s = r.scores
    return {"tracker": tracker, "preset": preset, "clip": r.clip, "seed": seed,
            "frames": len(r.boxes), "auc": f"{s['auc']:.6g}",
            "precision20": f"{s['precision20']:.6g}",
            "tracking_rate": f"{s['tracking_rate']:.6g}", "ms_median": f"{s['ms_median']:.4g}"}


def run(out: str, seeds=range(3), workers: int | None = None, trackers=None) -> list[dict]:
    """Run every (tracker, preset, sequence, seed) and write ``out`` (CSV, sorted rows)."""
    seqs = _clips.find_sequences()
    if not seqs:
        raise SystemExit("no real sequences found: set TRACKBOOK_SEQUENCES to a folder of "
                         "OTB-style sequences.")
    names = list(trackers or _trackers.available())
    jobs = [(t, p, seqs[c], s) for t in names for p in PRESETS for c in sorted(seqs)
            for s in seeds]
    with ProcessPoolExecutor(max_workers=workers or os.cpu_count() or 1) as ex:
        rows = list(ex.map(_one, jobs, chunksize=1))
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
    return rows


def load(path) -> list[dict]:
    """The rows of a claims table, numbers as numbers (what chapter 09 reads)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["seed"], r["frames"] = int(r["seed"]), int(r["frames"])
        for k in ("auc", "precision20", "tracking_rate", "ms_median"):
            r[k] = float(r[k])
    return rows


def _seeds(text: str) -> range:
    a, _, b = text.partition("-")
    return range(int(a), int(b or a) + 1)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--seeds", default="0-2", type=_seeds)
    ap.add_argument("--workers", type=int)
    ap.add_argument("--trackers", help="comma-separated names (default: all eleven)")
    a = ap.parse_args(argv)
    run(a.out, a.seeds, a.workers, a.trackers.split(",") if a.trackers else None)
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
