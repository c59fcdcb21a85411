"""The lost-and-found test (tests/test_lost_and_found.py) over more seeds: for each tracker, on
``leave_and_return`` clips with seeds 0-2 and tracker seeds 0-3, how many absent frames it
calls ``ok=True`` and how many frames after the target's return it needs to reach IoU > 0.5
again (99: not within the clip's 20 frames).

    PYTHONPATH=src python experiments/lost_and_found_sweep.py [TRACKER,...]

The test (tests/test_lost_and_found.py) checks clip seed 0 and tracker seed 0 only; this sweep
says how typical that case is. About a minute on two cores.
"""

from __future__ import annotations

import sys

import numpy as np

import trackbook
from trackbook import trackers
from trackbook.clips.synthetic import leave_and_return
from trackbook.evaluation import metrics

N_BEFORE, N_ABSENT, N_AFTER = 12, 18, 20


def sweep(name, clip_seeds=range(3), tracker_seeds=range(4)):
    """(max ok=True frames while absent, sorted frames-to-recover) over all seed pairs."""
    worst_ok, recover = 0, []
    for cs in clip_seeds:
        clip = leave_and_return(N_BEFORE, N_ABSENT, N_AFTER, seed=cs)
        for seed in tracker_seeds:
            r = trackbook.evaluate(name, clip, seed=seed)
            absent = r.ok[N_BEFORE:N_BEFORE + N_ABSENT]
            iou = metrics.iou(r.boxes, clip.groundtruth)[N_BEFORE + N_ABSENT:]
            worst_ok = max(worst_ok, int(absent.sum()))
            recover.append(int(np.argmax(iou > 0.5)) if np.any(iou > 0.5) else 99)
    return worst_ok, sorted(recover)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    names = argv[0].split(",") if argv else trackers.available(reference=False)
    for name in names:
        worst_ok, rec = sweep(name)
        print(f"{name:24s} ok=True on absent frames: at most {worst_ok} of {N_ABSENT}; "
              f"IoU > 0.5 within 10 frames of the return: {sum(r < 10 for r in rec)}/{len(rec)} "
              f"(frames needed: {rec})", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
