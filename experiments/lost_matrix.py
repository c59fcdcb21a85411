"""The lost-target matrix: scenario x tracker, for the eleven trackers and ``opencv-mil``.

For each scenario of ``tests/_scenarios.py`` (leaving across the frame border and coming back
elsewhere, an occluder of another colour, black and white frames, a long run on a small
frame) and each tracker: the fraction of absent frames reported lost (``ok=False``), the
frames from the target's return to the first IoU > 0.5, and on the sample clips
(``clips.available()``) the fraction of frames with IoU > 0.5 reported lost (false losses).
The test ``tests/test_lost_matrix.py`` asserts the thresholds; this script prints the table.

    PYTHONPATH=src python experiments/lost_matrix.py [--samples] [TRACKER,...]

Scenarios only: about a minute on one core; ``--samples`` adds the sample clips (several
minutes).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import trackbook  # noqa: E402
from trackbook import clips, trackers  # noqa: E402
from trackbook.evaluation import metrics  # noqa: E402

import _scenarios as S  # noqa: E402


def scenario_row(name, scenarios):
    cells = {}
    for sc in scenarios:
        r = trackbook.evaluate(name, sc.clip, seed=0)
        cells[sc.name] = S.measure(r, sc)
    return cells


def false_lost(name):
    """Over all sample clips: frames with IoU > 0.5, and how many of them are ok=False."""
    n_on = n_lost = 0
    for c in clips.available():
        clip = clips.load(c)
        r = trackbook.evaluate(name, clip, seed=0)
        iou = np.nan_to_num(metrics.iou(r.boxes, clip.groundtruth), nan=0.0)[1:]
        on = iou > 0.5
        n_on += int(on.sum())
        n_lost += int((~np.asarray(r.ok, bool)[1:][on]).sum())
    return n_lost, n_on


def main(argv):
    samples = "--samples" in argv
    argv = [a for a in argv if a != "--samples"]
    names = argv[0].split(",") if argv else trackers.available(reference=True)
    scenarios = [f() for f in S.SCENARIOS.values()]
    head = ["tracker"] + [f"{s.name} lost/rec" for s in scenarios if s.absent.any()] \
        + ["small-long false-lost/ok-off"] + (["samples false-lost"] if samples else [])
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for name in names:
        cells = scenario_row(name, scenarios)
        row = [name]
        for s in scenarios:
            m = cells[s.name]
            if s.absent.any():
                rec = "-" if m["recover"] is None else str(m["recover"])
                row.append(f"{m['lost_absent']:.2f} / {rec}")
            else:
                row.append(f"{m['false_lost']:.3f} / {m['ok_off']:.2f} ({m['n_off']})")
        if samples:
            k, n = false_lost(name)
            row.append(f"{k / max(n, 1):.4f} ({k}/{n})")
        print("| " + " | ".join(row) + " |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
