"""How far any setting of the failure layer could go on the scenes the contract misses.

The contract (``tests/test_failure_contract.py``) holds one setting of the layer per tracker
(its calibrated :class:`~trackbook.trackers.failure.FailureParams`) to two sides at once:
``ok=False`` on at least 95 % of the absent frames of every scene of the matrix, and on at
most 1 % of the frames on target on every sample clip and over the real sequences. Where a
cell is missed, was the calibration's choice the obstacle, or the confidence itself?

For every canonical tracker this script records, once per clip, what the layer is given on
every frame (the confidence, NaN where the box is mostly out of view, the frame is flat or
the algorithm's own rule fails, and whether the frame may enter the reference) while the
tracker runs as if every frame the layer judges were on target (the layer's own losses --
out of view, flat frame, the algorithm's own rule -- still stop it learning; a tracker's
confidence is finite, so a NaN given to the layer is one of those). It replays each of the
calibration's candidate settings on those records: the grid of
:func:`trackbook.evaluation.failure.calibrate` (``k_lost`` x ``ratio_lost`` x hysteresis,
``m``, ``window`` and ``warmup`` fixed at 3, 30 and 5), and each point with the found
thresholds of its second pass (:func:`~trackbook.evaluation.failure.floor_found`): 546 in
all, every calibrated setting among them. A setting is *admissible* when, replayed, it keeps
the contract's false-loss side (at most 1 % on every sample clip, and on the real sequences
pooled). Per (tracker, scene) cell, ``bound`` is the largest share of the absent frames an
admissible setting flags, replayed, the setting chosen for that cell alone.

A replay cannot see that a tracker judged lost stops learning and searches from its last
box, so its later confidences differ from the recorded ones (the calibration's first pass
makes the same approximation; its second pass runs the layer). So each admissible setting is
then run with the layer on over the cell's scene, the best replayed first, until one flags
95 % (``run_bound``: the most any of those runs flags; every judged cell of the matrix,
missed or not). The verdict per cell
(:func:`verdict`):

``beyond``
    no admissible setting, run with the layer on, flags 95 % of the absent frames: at none
    of the settings the replay admits does the rule tell this scene's absent frames from the
    frames on target it must keep;
``within``
    one does (chosen for this scene alone: one setting for all of a tracker's scenes is
    another question, and choosing on the test's scenes would tune on the test);
``undecided``
    the replay rejects the calibrated setting itself on the false-loss side, although the
    contract's committed runs may keep it: the settings the replay admits are then not the
    ones the calibration could have chosen, and the script cannot say (``run_bound`` still
    gives what the admitted settings do when run; with none admitted there is none).

Both words are about the settings the replay admits. The false-loss side itself is only
replayed, never run: a run with the layer reports its last box once lost, so it can count
false losses differently from the replay (in either direction). And the candidates are a
grid, with ``m``, ``window`` and ``warmup`` fixed; the long run on a small clip, the third
place of the contract's false-loss side, is not part of it. On a clip with fewer than 100
frames on target, "at most 1 %" allows none.

``--check`` also records, for the calibrated setting, the share replayed and the share of
the contract's own run (``replayed``, ``run``).

    PYTHONPATH=src python experiments/failure_bound.py [--out FILE] [--workers N]
        [--check] [--force] [TRACKER,...]

Writes ``experiments/failure_bound.json`` by default (``--force`` to overwrite it) and prints
the table. With the real sequences present (``../shared/data/sequences``) it took 17 minutes
on two cores; ``tests/test_failure_bound.py`` checks that the file is this commit's.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import trackbook  # noqa: E402
from trackbook import clips, trackers  # noqa: E402
from trackbook.clips import samples  # noqa: E402
from trackbook.evaluation import metrics  # noqa: E402
from trackbook.evaluation.bench import resolve_clips  # noqa: E402
from trackbook.evaluation.runs import code_fingerprint, code_text  # noqa: E402
from trackbook.evaluation.failure import (HYSTERESIS, K_LOST_GRID, RATIO_GRID,  # noqa: E402
                                          floor_found, params_for)
from trackbook.trackers.failure import FailureDetector, calibrated_params  # noqa: E402

from tests import test_failure_contract as T  # noqa: E402

OUT = ROOT / "experiments" / "failure_bound.json"
TARGET, MAX_FALSE = 0.95, 0.01


class _Recorder:
    """Stands in for the tracker's FailureDetector: notes what it is given, calls every frame
    on target (so the tracker runs as the algorithm alone would, with the layer's own
    out-of-view, flat-frame and own-rule judgements folded into a NaN confidence)."""

    lost = False

    def __init__(self):
        self.steps = []

    def step(self, confidence, learn=True):
        self.steps.append((float(confidence), bool(learn)))
        return True


def record(name: str, clip) -> dict:
    """The layer's input on every frame of ``clip`` (frame 0 is the given box)."""
    t = trackers.create(name, seed=0)
    try:
        t.init(clip.frames[0], clip.groundtruth[0])
        rec = t._detector = _Recorder()
        boxes = [np.asarray(clip.groundtruth[0], float)]
        for i in range(1, len(clip)):
            _, box = t.update(clip.frames[i])
            boxes.append(np.asarray(box, float))
            if len(rec.steps) != i:
                raise RuntimeError(f"{name}: the layer was not asked about frame {i}")
    finally:
        close = getattr(t, "close", None)
        if callable(close):
            close()
    c, learn = (np.array(v) for v in zip(*rec.steps))
    return {"c": c, "learn": learn.astype(bool), "boxes": np.asarray(boxes)}


def replay(params, r: dict) -> np.ndarray:
    """``ok`` per frame (frame 0 True) of the layer with ``params`` on a record: a NaN input
    (out of view, flat, the algorithm's own rule) is never ok, as in the base class."""
    det = FailureDetector(params)
    ok = [det.step(c, learn) and not math.isnan(c) for c, learn in zip(r["c"], r["learn"])]
    return np.r_[True, np.asarray(ok, bool)]


def grid() -> list:
    """The calibration's candidates: its grid, and each point with the found thresholds
    :func:`~trackbook.evaluation.failure.floor_found` imposes (its second pass)."""
    out = []
    for k in sorted(set(K_LOST_GRID)):
        for ratio in sorted(set(RATIO_GRID)):
            if math.isinf(k) and ratio == 0:
                continue
            for h in sorted(set(HYSTERESIS)):
                p = params_for(k, ratio, h, m=3, window=30, warmup=5)
                out += [p] if floor_found(p) == p else [p, floor_found(p)]
    return list(dict.fromkeys(out))


def bound(name: str, check: bool = False) -> dict:
    t0 = time.perf_counter()
    cells = [k for k in T.SCENES if T._judged(name, k)]
    scenes = {k: record(name, T.scene(k)[0]) for k in cells}
    refs = resolve_clips(["samples", "shared"] if clips.find_sequences() else ["samples"])
    places = {}
    for ref in refs:
        clip = ref.load()
        sample = ref.identity.startswith("sample:")
        view = samples.in_view(ref.name) if sample else None
        places[ref.name] = (sample, clip.groundtruth, view, record(name, clip))
    settings = grid()
    absent = {}
    for k in cells:
        a = T.scene(k)[1].copy()
        a[0] = False
        absent[k] = a
    rows = []
    for p in settings:
        worst_sample, real_lost, real_on = 0.0, 0, 0
        for sample, gt, view, r in places.values():
            lost, on = metrics.false_losses(replay(p, r), r["boxes"], gt, view)
            if sample:
                worst_sample = max(worst_sample, lost / on if on else 0.0)
            else:
                real_lost, real_on = real_lost + lost, real_on + on
        real = real_lost / real_on if real_on else 0.0
        shares = {k: float((~replay(p, scenes[k])[absent[k]]).mean()) for k in cells}
        rows.append((p, worst_sample, real, shares))
    admissible = [row for row in rows if row[1] <= MAX_FALSE and row[2] <= MAX_FALSE]
    out = {"tracker": name, "settings": len(rows), "admissible": len(admissible),
           "cells": {}, "most_cells_met": 0, "seconds": None}
    for k in cells:
        shares = [row[3][k] for row in admissible]
        best = max(shares, default=float("nan"))
        cell = out["cells"][k] = {"bound": best}
        if not admissible:
            continue
        # The replay cannot see a lost tracker stop learning: run the admissible settings
        # with the layer on, the best replayed first, until one reaches the target (or all
        # have run: then the bound holds for every one of them).
        order = sorted(range(len(admissible)), key=lambda j: -shares[j])
        cell["run_bound"] = 0.0
        for j in order:
            cell["run_bound"] = max(cell["run_bound"],
                                    _run_share(name, k, admissible[j][0], absent[k]))
            if cell["run_bound"] >= TARGET:
                break
    if admissible:
        met = [sum(s >= TARGET for s in row[3].values()) for row in admissible]
        j = int(np.argmax(met))
        p = admissible[j][0]
        out["most_cells_met"] = int(met[j])
        out["most_cells_setting"] = {"k_lost": p.k_lost, "ratio_lost": p.ratio_lost,
                                     "k_found": p.k_found, "ratio_found": p.ratio_found}
    cal = calibrated_params(name)
    c = next(row for row in rows if row[0] == cal)
    out["calibrated"] = {"worst_sample": c[1], "real": c[2],
                         "admissible": c[1] <= MAX_FALSE and c[2] <= MAX_FALSE,
                         "cells_met": int(sum(s >= TARGET for s in c[3].values()))}
    if check:
        for k in cells:
            ok, _, _ = T.run(name, k)
            out["cells"][k]["replayed"] = float((~replay(cal, scenes[k])[absent[k]]).mean())
            out["cells"][k]["run"] = float((~ok[absent[k]]).mean())
    out["seconds"] = round(time.perf_counter() - t0, 1)
    return out


#: What else decides the file besides the trackers: this script, the scenes, the counting and
#: the grid (their code without docstrings or comments). Not the contract's test file, whose
#: expected-failure lists change with every measurement; ``tests/test_failure_bound.py``
#: checks instead that the file has the cells that test judges.
SOURCES = ("experiments/failure_bound.py", "tests/_scenarios.py",
           "src/trackbook/clips/failure_scenes.py", "src/trackbook/evaluation/metrics.py",
           "src/trackbook/evaluation/failure.py")


def source_fingerprint() -> str:
    h = hashlib.blake2b(digest_size=16)
    for f in SOURCES:
        h.update(f.encode() + b";" + code_text(ROOT / f))
    return h.hexdigest()


def _run_share(name, key, params, absent) -> float:
    """The share of ``absent`` frames a run with the layer at ``params`` reports lost."""
    r = trackbook.evaluate(trackers.create(name, seed=0, failure=params), T.scene(key)[0])
    return float((~np.asarray(r.ok, bool)[absent]).mean())


def _safe(x):
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {k: _safe(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_safe(v) for v in x]
    return x


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("names", nargs="?", default="")
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--force", action="store_true", help="overwrite an existing --out")
    a = ap.parse_args(argv)
    names = [n for n in a.names.split(",") if n] or T.CANONICAL
    if a.out.exists() and not a.force:
        sys.exit(f"failure_bound: {a.out} exists; pass --force to overwrite it, or --out FILE")
    with ProcessPoolExecutor(a.workers) as ex:
        found = list(ex.map(bound, names, [a.check] * len(names)))
    for row in found:       # what made it: stale once the tracker or its thresholds change
        row["code"] = code_fingerprint(row["tracker"], versions=False)
    data = {"description": "per canonical tracker and contract cell, the largest share of "
                           "absent frames any admissible setting of the failure layer's "
                           "calibration candidates flags",
            "command": "PYTHONPATH=src python experiments/failure_bound.py --check --force",
            "target": TARGET, "max_false": MAX_FALSE, "candidates": len(grid()),
            "source": source_fingerprint(),
            "sequences": sorted(clips.find_sequences()), "rows": found}
    a.out.write_text(json.dumps(_safe(data), indent=1) + "\n")
    print("tracker | admissible settings | judged cells one setting meets, replayed | the "
          "contract's missed cells: bound replayed / run (verdict)")
    for row in found:
        missed = [k for k in row["cells"] if (row["tracker"], k) in T.KNOWN_ABSENT]
        cells = ", ".join(f"{k} {_pct(row['cells'][k]['bound'])} / "
                          f"{_pct(row['cells'][k].get('run_bound'))} ({verdict(row, k)})"
                          for k in missed)
        print(f"{row['tracker']} | {row['admissible']}/{row['settings']} | "
              f"{row['most_cells_met']}/{len(row['cells'])} | {cells or '-'}", flush=True)


def verdict(row: dict, key: str) -> str:
    """``"beyond"``: no admissible setting, run with the layer on, flags 95 % of the cell's
    absent frames; ``"within"``: one does; ``"undecided"``: the replay rejects the calibrated
    setting itself on the false-loss side, so the admissible settings are not the ones the
    calibration could have chosen (see the module's docstring)."""
    if not row["calibrated"]["admissible"]:
        return "undecided"
    return "within" if row["cells"][key]["run_bound"] >= TARGET else "beyond"


def _pct(v):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.0%}"


if __name__ == "__main__":
    main()
