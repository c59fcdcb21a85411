"""Recompute ``src/trackbook/data/otb_published.csv`` from the OTB result files.

The table sets the OTB benchmark's published per-sequence results (success rate at IoU 0.5,
and the AUC where the boxes are available) beside the book's trackers on the development set's
OTB sequences (David, Jogging1, MotorRolling, Couple, Crossing). This script downloads
nothing: it reads two clones made beforehand (third-party data, never committed here):

    git clone https://github.com/zhangzheng0131/Tracker_Benchmark_tb100 otb-mat
    git -C otb-mat checkout 61282dbf14495f7091163917def33a83046f7ca9
    git clone https://github.com/jwlim/tracker_benchmark otb-py
    git -C otb-py checkout e2480f733ffd60332b205374783ff4d682090929

    python benchmarks/otb_published.py \\
        --mat otb-mat/results/results_OPE/results_OPE_OTB100 --json otb-py/results/OPE

``--sequences`` is the development set (default ``$TRACKBOOK_SEQUENCES``, else the
``shared/data/sequences`` beside the checkout); every file's length is checked against its
ground truth. ``--check`` compares with the committed table instead of writing it (exit code 1
on a difference). What the numbers mean and cannot mean: ``trackbook.evaluation.published``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from trackbook.clips import find_sequences, read_groundtruth
from trackbook.evaluation import published

TABLE = Path(__file__).resolve().parents[1] / "src" / "trackbook" / "data" / "otb_published.csv"


def groundtruth(root=None) -> dict:
    """The development set's ground truth of the OTB sequences, by development-set name."""
    found = find_sequences(root)
    missing = [s for s in published.SEQUENCES if s not in found]
    if missing:
        raise FileNotFoundError(f"sequences {missing} not found (looked in {root or 'the default'}"
                                "); pass --sequences DIR or set TRACKBOOK_SEQUENCES.")
    out = {}
    for s in published.SEQUENCES:
        folder = found[s]
        gt = folder / "groundtruth.txt"
        if not gt.is_file():
            gt = folder / "groundtruth_rect.txt"
        out[s] = read_groundtruth(gt)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--mat", required=True, type=Path,
                    help="folder results/results_OPE/results_OPE_OTB100 of the MATLAB toolkit copy")
    ap.add_argument("--json", required=True, type=Path,
                    help="folder results/OPE of the Python toolkit copy")
    ap.add_argument("--sequences", type=Path, default=None, help="the development set's folder")
    ap.add_argument("--out", type=Path, default=TABLE, help=f"where to write (default {TABLE})")
    ap.add_argument("--check", action="store_true",
                    help="compare with the committed table instead of writing it")
    a = ap.parse_args(argv)
    try:
        rows = published.build_rows(a.mat, a.json, groundtruth(a.sequences))
    except (FileNotFoundError, ValueError) as e:
        print(f"otb_published: {e}", file=sys.stderr)
        return 2
    if a.check:
        tmp = a.out.with_suffix(".recomputed.csv")
        published.write_csv(rows, tmp)
        same = tmp.read_text() == a.out.read_text()
        tmp.unlink()
        print("identical to the committed table" if same else f"differs from {a.out}")
        return 0 if same else 1
    a.out.parent.mkdir(parents=True, exist_ok=True)
    published.write_csv(rows, a.out)
    for r in rows:
        auc = "" if r["auc"] is None else f"  AUC {r['auc']:.3f}"
        alt = ("" if r["alt_success_rate_iou50"] is None
               else f"  (other copy {r['alt_success_rate_iou50']:.3f})")
        print(f"{r['tracker']:7s} {r['sequence']:13s} {r['success_rate_iou50']:.3f}{auc}{alt}")
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
