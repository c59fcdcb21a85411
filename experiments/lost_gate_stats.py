"""How often each tracker reports a lost frame on the real sequences, and how many of those
frames still had the box on the target (IoU > 0.5): the check behind chapter 2's sentence on
the distance gate.

    PYTHONPATH=src python experiments/lost_gate_stats.py [--seed 0]

Sequences are found as everywhere else (``../shared/data/sequences`` or
``TRACKBOOK_SEQUENCES``). About a minute on two cores.
"""

from __future__ import annotations

import argparse

import trackbook
from trackbook import clips
from trackbook.evaluation import metrics

TRACKERS = ("color-pf", "color-hog-pf", "color-hog-ipca", "hsi-color-pf", "hog-pf",
            "condensation", "condensation-mean-shift", "mean-shift")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args(argv)
    seqs = clips.find_sequences()
    if not seqs:
        raise SystemExit("no sequences found: put them in ../shared/data/sequences or set "
                         "TRACKBOOK_SEQUENCES")
    for name in TRACKERS:
        n_lost = n_on = n_frames = 0
        for path in seqs.values():
            c = clips.load(path)
            r = trackbook.evaluate(name, c, seed=a.seed)
            iou = metrics.iou(r.boxes, c.groundtruth)[1:]
            lost = ~r.ok[1:]
            n_frames += lost.size
            n_lost += int(lost.sum())
            n_on += int((lost & (iou > 0.5)).sum())
        print(f"{name:24s} lost {n_lost:4d} of {n_frames} frames; IoU > 0.5 on {n_on} of them",
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
