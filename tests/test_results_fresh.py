"""The committed score tables in ``book/results`` still match the library of this commit.

Chapters read these files instead of re-running minutes of tracking, so a change to a tracker
or a feature can leave them stale without any chapter failing (``seed001_real.csv`` once kept
``hog-pf`` rows from before a HOG fix). This re-runs every deterministic tracker of each file
on one short sequence (Crossing, 120 frames) and demands the committed AUC. OpenCV's MIL is left out: it does
not repeat within a process. When a tracker changes on purpose, regenerate the file with the
command its chapter gives.
"""

import csv
import functools
import json
from pathlib import Path

import pytest

import trackbook

from .conftest import SEQUENCES, needs_sequences

RESULTS = Path(__file__).resolve().parents[1] / "book" / "results"
CLIP = "Crossing"          # 120 frames: the shortest sequence that every file covers

# file -> (tolerance on the AUC as written, column with the seed or None for seed 0)
FILES = {
    "real/results.csv": (1e-9, None),
    "seed000_real.csv": (1e-5, "seed"),      # written with 6 significant digits
    "seed001_real.csv": (1e-9, None),
    "seed000_learning.csv": (1e-5, "seed"),  # every learning configuration, seed 0 only
    "seed001_variants.csv": (1e-9, "seed"),  # the library's trackers only, seed 0 only
    "seed002_real.csv": (1e-5, None),        # 6 significant digits
    "seed003_real.csv": (5e-5, None),        # written with 4 decimals
    "claims_real.csv": (1e-5, "seed"),       # both presets; 6 significant digits
}
#: Files with many configurations per tracker: checking one seed of each is enough.
SEED0_ONLY = {"seed000_learning.csv", "seed001_variants.csv"}


@functools.lru_cache(maxsize=None)
def _auc(tracker: str, seed: int, params: str, preset: str = "book") -> float:
    return trackbook.evaluate(tracker, str(SEQUENCES[CLIP]), seed=seed, preset=preset,
                              **json.loads(params)).scores["auc"]


def _cases():
    library = set(trackbook.trackers.available())
    for name, (tol, seed_col) in FILES.items():
        with open(RESULTS / name) as f:
            for row in csv.DictReader(f):
                seed = int(row[seed_col]) if seed_col else 0
                if row["clip"] != CLIP or row["tracker"] not in library:
                    continue          # MIL (not repeatable), experiments' own trackers
                if name in SEED0_ONLY and seed != 0:
                    continue
                params = row.get("params") or "{}"
                preset = row.get("preset") or "book"
                yield pytest.param(name, row["tracker"], seed, params, preset,
                                   float(row["auc"]), tol,
                                   id=f"{name}:{row['tracker']}:{preset}{params}:seed{seed}")


@needs_sequences
@pytest.mark.shared
@pytest.mark.slow
@pytest.mark.skipif(CLIP not in SEQUENCES, reason=f"sequence {CLIP} not found")
@pytest.mark.parametrize("name, tracker, seed, params, preset, committed, tol", list(_cases()))
def test_committed_auc_is_reproduced(name, tracker, seed, params, preset, committed, tol):
    assert _auc(tracker, seed, params, preset) == pytest.approx(committed, abs=tol), (
        f"book/results/{name} is stale for {tracker} (seed {seed}) on {CLIP}; regenerate it "
        "with the command in its chapter.")
