"""The contract of ``ok``, held over a seeded scenario matrix that the calibration never saw.

Every tracker runs its published algorithm under the one failure-detection layer
(``trackbook.trackers.failure``, thresholds from ``src/trackbook/data/failure_calibration.json``,
chosen on ``calibration_set(seed=0)``). The matrix here is drawn from another seed
(``calibration_set(seed=1, per_kind=2)``: two scenes of each kind -- the target leaves across
an edge, is occluded, the camera cuts away, the light fades, the target shrinks away, the
frame blurs, a look-alike appears while it is covered) plus the hand-built scenarios of
``tests/_scenarios.py`` (an exit across the border and back elsewhere, an occluder, black and
white frames) and ``clips.synthetic.leave_and_return`` (gone for 18 frames, back 88 px to the
left). ``experiments/failure_contract.py`` prints the whole table. The contract:

1. while the target is absent, ``ok=False`` on at least 95 % of the frames, for every tracker
   (re-detecting variants included: a box found elsewhere must not be a confident wrong box)
   and every scenario -- except the look-alike for a tracker that sees only colour (a
   histogram cannot tell the target from a copy with its colours: reported, documented);
2. ``ok=False`` on at most 1 % of the frames where the box is on the target (IoU > 0.5) on the
   sample clips and the real sequences (every name; read from the committed runs, kept fresh
   by ``tests/test_results_fresh.py``), and on a long run on a small clip (the names without
   re-detection);
3. with the re-detection layer (the ``-redetect`` names), IoU > 0.5 within 10 frames of the
   target's return.

Where a tracker misses the contract today, the cell is an expected failure with the measured
number (``KNOWN_ABSENT``, ``KNOWN_RECOVERY``, ``FALSE_LOSSES``), strict: the day it passes, the mark has to go.
Which of a canonical tracker's missed scenes other settings of the layer could meet while
keeping item 2 on the sample clips and the real sequences, ``experiments/failure_bound.py``
estimates (``tests/test_failure_bound.py``).
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest

import trackbook
from trackbook import clips, results, trackers
from trackbook.clips import samples
from trackbook.clips.failure_scenes import calibration_set
from trackbook.clips.synthetic import leave_and_return
from trackbook.evaluation import metrics

from . import _scenarios as S

CANONICAL = [n for n in trackers.available(reference=True) if not n.endswith("-redetect")]
REDETECTING = [n for n in trackers.available(reference=False) if n.endswith("-redetect")]
MATRIX = calibration_set(seed=1, per_kind=2)
HAND_BUILT = ["edge-exit", "occluder", "black", "white", "leave-and-return"]
SCENES = [f"{k}-{j}" for j, (k, _) in enumerate(MATRIX.specs)] + HAND_BUILT
#: Trackers whose confidence sees only colour: a look-alike with the target's colours is the
#: target to them (the contract's documented exception).
COLOUR_ONLY = {"color-pf", "hsi-color-pf", "mean-shift", "condensation",
               "condensation-mean-shift", "camshift", "edge-ray-pf", "median-flow",
               "opencv-mil"}
#: (tracker, scene) -> what was measured where the contract is not kept, strict expected
#: failures (``experiments/failure_contract.py`` prints the whole table): absent frames
#: reported ok=True ...
KNOWN_ABSENT: dict = {
    ('color-hog-pf', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('color-hog-ipca', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('hsi-color-pf', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('hsi-color-pf', 'shrink-9'): 'ok=False on 0% of the absent frames',
    ('covariance', 'exit-0'): 'ok=False on 0% of the absent frames',
    ('covariance', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('covariance', 'cut-4'): 'ok=False on 0% of the absent frames',
    ('covariance', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('covariance', 'shrink-9'): 'ok=False on 0% of the absent frames',
    ('covariance', 'lookalike-12'): 'ok=False on 55% of the absent frames',
    ('covariance', 'lookalike-13'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance', 'exit-0'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance', 'occlusion-2'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance', 'cut-4'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance', 'shrink-9'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance', 'lookalike-13'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre', 'exit-0'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre', 'occlusion-2'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre', 'cut-4'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre', 'shrink-9'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre', 'lookalike-12'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre', 'lookalike-13'): 'ok=False on 0% of the absent frames',
    ('condensation', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('condensation', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('condensation-mean-shift', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('condensation-mean-shift', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('mean-shift', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('mean-shift', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('mosse', 'occluder'): 'ok=False on 87% of the absent frames',
    ('kcf', 'occlusion-3'): 'ok=False on 0% of the absent frames',
    ('kcf', 'cut-5'): 'ok=False on 75% of the absent frames',
    ('kcf', 'fade-7'): 'ok=False on 67% of the absent frames',
    ('kcf', 'shrink-9'): 'ok=False on 0% of the absent frames',
    ('dsst', 'exit-0'): 'ok=False on 23% of the absent frames',
    ('dsst', 'occlusion-3'): 'ok=False on 0% of the absent frames',
    ('staple', 'occlusion-2'): 'ok=False on 0% of the absent frames',
    ('staple', 'occlusion-3'): 'ok=False on 0% of the absent frames',
    ('staple', 'fade-6'): 'ok=False on 0% of the absent frames',
    ('staple', 'fade-7'): 'ok=False on 50% of the absent frames',
    ('bacf', 'exit-0'): 'ok=False on 0% of the absent frames',
    ('color-pf-redetect', 'occlusion-3'): 'ok=False on 12% of the absent frames',
    ('color-hog-pf-redetect', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('color-hog-pf-redetect', 'occlusion-3'): 'ok=False on 12% of the absent frames',
    ('color-hog-pf-redetect', 'lookalike-12'): 'ok=False on 27% of the absent frames',
    ('color-hog-ipca-redetect', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('color-hog-ipca-redetect', 'occlusion-3'): 'ok=False on 12% of the absent frames',
    ('color-hog-ipca-redetect', 'lookalike-12'): 'ok=False on 27% of the absent frames',
    ('hsi-color-pf-redetect', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('hsi-color-pf-redetect', 'shrink-9'): 'ok=False on 0% of the absent frames',
    ('hog-pf-redetect', 'occlusion-3'): 'ok=False on 12% of the absent frames',
    ('covariance-redetect', 'exit-0'): 'ok=False on 0% of the absent frames',
    ('covariance-redetect', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('covariance-redetect', 'occlusion-2'): 'ok=False on 17% of the absent frames',
    ('covariance-redetect', 'cut-4'): 'ok=False on 0% of the absent frames',
    ('covariance-redetect', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('covariance-redetect', 'shrink-9'): 'ok=False on 0% of the absent frames',
    ('covariance-redetect', 'lookalike-12'): 'ok=False on 27% of the absent frames',
    ('covariance-redetect', 'lookalike-13'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-redetect', 'exit-0'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-redetect', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-redetect', 'occlusion-2'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-redetect', 'cut-4'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-redetect', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-redetect', 'shrink-9'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-redetect', 'lookalike-13'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre-redetect', 'exit-0'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre-redetect', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre-redetect', 'occlusion-2'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre-redetect', 'cut-4'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre-redetect', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre-redetect', 'shrink-9'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre-redetect', 'lookalike-12'): 'ok=False on 0% of the absent frames',
    ('kalman-covariance-manoeuvre-redetect', 'lookalike-13'): 'ok=False on 0% of the absent frames',
    ('condensation-redetect', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('condensation-redetect', 'occlusion-3'): 'ok=False on 19% of the absent frames',
    ('condensation-redetect', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('condensation-mean-shift-redetect', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('condensation-mean-shift-redetect', 'occlusion-3'): 'ok=False on 44% of the absent frames',
    ('condensation-mean-shift-redetect', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('mean-shift-redetect', 'exit-1'): 'ok=False on 0% of the absent frames',
    ('mean-shift-redetect', 'occlusion-3'): 'ok=False on 19% of the absent frames',
    ('mean-shift-redetect', 'cut-4'): 'ok=False on 20% of the absent frames',
    ('mean-shift-redetect', 'shrink-8'): 'ok=False on 0% of the absent frames',
    ('mean-shift-redetect', 'shrink-9'): 'ok=False on 43% of the absent frames',
    ('camshift-redetect', 'occlusion-3'): 'ok=False on 31% of the absent frames',
    ('mosse-redetect', 'occlusion-3'): 'ok=False on 12% of the absent frames',
    ('mosse-redetect', 'cut-4'): 'ok=False on 40% of the absent frames',
    ('mosse-redetect', 'cut-5'): 'ok=False on 25% of the absent frames',
    ('mosse-redetect', 'occluder'): 'ok=False on 93% of the absent frames',
    ('kcf-redetect', 'occlusion-3'): 'ok=False on 0% of the absent frames',
    ('kcf-redetect', 'cut-5'): 'ok=False on 75% of the absent frames',
    ('kcf-redetect', 'fade-7'): 'ok=False on 67% of the absent frames',
    ('kcf-redetect', 'shrink-9'): 'ok=False on 0% of the absent frames',
    ('dsst-redetect', 'exit-0'): 'ok=False on 0% of the absent frames',
    ('dsst-redetect', 'occlusion-3'): 'ok=False on 0% of the absent frames',
    ('staple-redetect', 'exit-0'): 'ok=False on 0% of the absent frames',
    ('staple-redetect', 'occlusion-2'): 'ok=False on 0% of the absent frames',
    ('staple-redetect', 'occlusion-3'): 'ok=False on 0% of the absent frames',
    ('staple-redetect', 'fade-6'): 'ok=False on 0% of the absent frames',
    ('staple-redetect', 'fade-7'): 'ok=False on 50% of the absent frames',
    ('bacf-redetect', 'exit-0'): 'ok=False on 0% of the absent frames',
}
#: The cells of ``KNOWN_ABSENT`` whose box held none of the target on the frame before it
#: went, with ``ok`` from the last frame it held some on: the tracker slid off the target,
#: unflagged, while the target was still there. From then on it scores something else, and the
#: target's going need not change that score; the loss to catch was the slide, before the
#: target went (README, "What `ok` promises"). In the other cells the box held some of the
#: target on that frame, or the rule had flagged a loss since (a re-detecting name may then
#: move the box onto the background and judge it found), and the rule did not flag enough of
#: the absent frames.
OFF_BEFORE_IT_WENT: set = {
    ('covariance', 'exit-0'), ('covariance', 'exit-1'), ('kalman-covariance', 'exit-0'),
    ('kalman-covariance', 'exit-1'), ('kalman-covariance-manoeuvre', 'exit-0'),
    ('kalman-covariance-manoeuvre', 'exit-1'), ('kalman-covariance-manoeuvre', 'shrink-9'),
    ('covariance-redetect', 'exit-0'), ('covariance-redetect', 'exit-1'),
    ('kalman-covariance-redetect', 'exit-0'), ('kalman-covariance-redetect', 'exit-1'),
    ('kalman-covariance-manoeuvre-redetect', 'exit-0'),
    ('kalman-covariance-manoeuvre-redetect', 'exit-1'),
    ('kalman-covariance-manoeuvre-redetect', 'shrink-9'),
}
#: ... and a re-detecting name that does not find the target within 10 frames of its return.
KNOWN_RECOVERY: dict = {
    ('color-pf-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('color-pf-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('color-pf-redetect', 'cut-5'): 'IoU > 0.5 never after the return',
    ('color-hog-pf-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('color-hog-pf-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('color-hog-pf-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('color-hog-ipca-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('color-hog-ipca-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('color-hog-ipca-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('color-hog-ipca-redetect', 'cut-5'): 'IoU > 0.5 first 11 frames after the return',
    ('hsi-color-pf-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('hsi-color-pf-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('hog-pf-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('hog-pf-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('hog-pf-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('hog-pf-redetect', 'cut-5'): 'IoU > 0.5 first 21 frames after the return',
    ('edge-ray-pf-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('edge-ray-pf-redetect', 'cut-5'): 'IoU > 0.5 never after the return',
    ('covariance-redetect', 'exit-0'): 'IoU > 0.5 never after the return',
    ('covariance-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('covariance-redetect', 'occlusion-2'): 'IoU > 0.5 never after the return',
    ('covariance-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('kalman-covariance-redetect', 'exit-0'): 'IoU > 0.5 never after the return',
    ('kalman-covariance-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('kalman-covariance-redetect', 'occlusion-2'): 'IoU > 0.5 never after the return',
    ('kalman-covariance-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('kalman-covariance-manoeuvre-redetect', 'exit-0'): 'IoU > 0.5 never after the return',
    ('kalman-covariance-manoeuvre-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('kalman-covariance-manoeuvre-redetect', 'occlusion-2'): 'IoU > 0.5 never after the return',
    ('kalman-covariance-manoeuvre-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('condensation-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('condensation-redetect', 'occlusion-3'): 'IoU > 0.5 first 11 frames after the return',
    ('condensation-mean-shift-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('condensation-mean-shift-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('mean-shift-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('mean-shift-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('mean-shift-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('camshift-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('camshift-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('mosse-redetect', 'exit-0'): 'IoU > 0.5 never after the return',
    ('mosse-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('mosse-redetect', 'occlusion-2'): 'IoU > 0.5 never after the return',
    ('mosse-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('mosse-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('mosse-redetect', 'cut-5'): 'IoU > 0.5 never after the return',
    ('kcf-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('kcf-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('kcf-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('kcf-redetect', 'cut-5'): 'IoU > 0.5 first 12 frames after the return',
    ('kcf-redetect', 'occluder'): 'IoU > 0.5 never after the return',
    ('dsst-redetect', 'exit-0'): 'IoU > 0.5 never after the return',
    ('dsst-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('dsst-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('staple-redetect', 'exit-0'): 'IoU > 0.5 never after the return',
    ('staple-redetect', 'occlusion-2'): 'IoU > 0.5 never after the return',
    ('staple-redetect', 'occlusion-3'): 'IoU > 0.5 never after the return',
    ('staple-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('bacf-redetect', 'exit-0'): 'IoU > 0.5 never after the return',
    ('bacf-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('median-flow-redetect', 'exit-1'): 'IoU > 0.5 never after the return',
    ('median-flow-redetect', 'occlusion-2'): 'IoU > 0.5 never after the return',
    ('median-flow-redetect', 'cut-4'): 'IoU > 0.5 never after the return',
    ('median-flow-redetect', 'cut-5'): 'IoU > 0.5 never after the return',
    ('median-flow-redetect', 'leave-and-return'): 'IoU > 0.5 never after the return',
}
#: ("samples" | "real" | "small-long", tracker) -> the false losses measured where there are
#: more than 1 %.
FALSE_LOSSES: dict = {
    ('samples', 'color-hog-ipca'): 'ok=False with IoU > 0.5 on robot-corridor-day: 26 of 147',
    ('samples', 'edge-ray-pf'): 'ok=False with IoU > 0.5 on robot-corridor-day: 11 of 77',
    ('samples', 'camshift'): 'ok=False with IoU > 0.5 on robot-corridor-day: 32 of 65',
    ('samples', 'mosse'): 'ok=False with IoU > 0.5 on robot-corridor-day: 3 of 72, robot-corridor-night: 3 of 69, shelves: 10 of 62',
    ('samples', 'median-flow'): 'ok=False with IoU > 0.5 on robot-corridor-night: 11 of 102, shelves: 3 of 159',
    ('samples', 'opencv-mil'): 'ok=False with IoU > 0.5 on robot-corridor-day: 21 of 144, robot-corridor-night: 15 of 121',
    ('samples', 'color-hog-ipca-redetect'): 'ok=False with IoU > 0.5 on robot-corridor-day: 26 of 149',
    ('samples', 'edge-ray-pf-redetect'): 'ok=False with IoU > 0.5 on robot-corridor-day: 11 of 128',
    ('samples', 'camshift-redetect'): 'ok=False with IoU > 0.5 on robot-corridor-day: 3 of 86',
    ('samples', 'mosse-redetect'): 'ok=False with IoU > 0.5 on robot-corridor-day: 3 of 107, robot-corridor-night: 3 of 69, shelves: 10 of 62',
    ('samples', 'median-flow-redetect'): 'ok=False with IoU > 0.5 on robot-corridor-night: 11 of 68, shelves: 3 of 159',
    ('real', 'color-pf'): 'ok=False on 3 of the 178 frames with IoU > 0.5',
    ('real', 'edge-ray-pf'): 'ok=False on 33 of the 476 frames with IoU > 0.5',
    ('real', 'mosse'): 'ok=False on 80 of the 324 frames with IoU > 0.5',
    ('real', 'median-flow'): 'ok=False on 19 of the 528 frames with IoU > 0.5',
    ('real', 'opencv-mil'): 'ok=False on 97 of the 514 frames with IoU > 0.5',
    ('real', 'edge-ray-pf-redetect'): 'ok=False on 37 of the 509 frames with IoU > 0.5',
    ('real', 'mosse-redetect'): 'ok=False on 28 of the 601 frames with IoU > 0.5',
    ('real', 'median-flow-redetect'): 'ok=False on 16 of the 539 frames with IoU > 0.5',
    ('small-long', 'condensation'): 'ok=False on 6.1% of the frames with IoU > 0.5',
}


def test_the_readme_names_the_trackers_that_keep_every_absent_cell():
    keep = sorted(n for n in CANONICAL if not any(k[0] == n for k in KNOWN_ABSENT))
    readme = " ".join((Path(__file__).resolve().parents[1] / "README.md")
                      .read_text(encoding="utf-8").split())
    named = ", ".join(f"`{n}`" for n in keep[:-1]) + f" and `{keep[-1]}`"
    words = dict(enumerate("no one two three four five six seven eight nine ten".split()))
    assert f"On the test's scenes {words[len(keep)]} trackers flag" in readme, keep
    assert f"in every scene they are held to: {named}" in readme, keep
    assert not any(n in REDETECTING for n in keep)
    # the README says which of them are let off the look-alike scenes
    held = [n for n in keep if n not in COLOUR_ONLY]
    assert held == ["hog-pf"], held
    assert ("the confidence of all but `hog-pf` sees only colour, so the look-alike scenes are "
            "not held against those five; `hog-pf`'s sees gradients, so they are held against "
            "it, and it flags them too") in readme


def test_the_matrix_is_not_the_calibration_set():
    calibrated = set(calibration_set(seed=0, per_kind=6).specs)
    assert not calibrated & set(MATRIX.specs)


@lru_cache(maxsize=None)
def scene(key: str):
    """``(clip, absent, back)``: ``back`` is the first frame with the target in view again
    after its last absent frame, 99 % of it at least (its anti-aliased edge keeps the share
    of a target that is wholly back just under 1 in some scenes); None if it never is."""
    if key == "leave-and-return":            # 12 frames in view, 18 gone, back 88 px left
        clip = leave_and_return(12, 18, 20)
        absent = ~np.isfinite(clip.groundtruth).all(axis=1)
        return clip, absent, int(np.flatnonzero(absent)[-1]) + 1
    if key in HAND_BUILT:
        sc = S.scenario(key)
        return sc.clip, np.asarray(sc.absent, bool), sc.back
    sc = MATRIX[int(key.rsplit("-", 1)[1])]
    absent = np.asarray(sc.absent, bool)
    back = None
    if absent.any():
        after = np.flatnonzero((np.arange(len(absent)) > np.flatnonzero(absent)[-1])
                               & (np.asarray(sc.visible) >= 0.99))
        back = int(after[0]) if after.size else None
    return sc.clip, absent, back


def kind(key: str) -> str:
    return key.rsplit("-", 1)[0] if key not in HAND_BUILT else key


@lru_cache(maxsize=None)
def run(name: str, key: str):
    clip, absent, back = scene(key)
    r = (S.evaluated(name, key) if key in S.SCENARIOS
         else trackbook.evaluate(name, clip, seed=0))
    iou = np.nan_to_num(metrics.iou(r.boxes, clip.groundtruth), nan=0.0)
    return np.asarray(r.ok, bool), iou, np.asarray(r.boxes, float)


def _cells(names, keys, keep, known):
    for n in names:
        for k in keys:
            if not keep(n, k):
                continue
            reason = known.get((n, k))
            marks = [pytest.mark.xfail(strict=True, reason=reason)] if reason else []
            yield pytest.param(n, k, marks=marks, id=f"{n}-{k}")


def _judged(n, k):
    clip, absent, _ = scene(k)
    return absent[1:].any() and not (kind(k) == "lookalike"
                                     and n.removesuffix("-redetect") in COLOUR_ONLY)


@pytest.mark.parametrize("name,key", list(_cells(CANONICAL + REDETECTING, SCENES, _judged,
                                                  KNOWN_ABSENT)))
def test_lost_while_the_target_is_absent(name, key):
    ok, _, _ = run(name, key)
    _, absent, _ = scene(key)
    absent = absent.copy()
    absent[0] = False                                   # frame 0 is the given box
    share = float((~ok[absent]).mean())
    assert share >= 0.95, (f"{name} on {key}: ok=False on {share:.0%} of the "
                           f"{int(absent.sum())} absent frames")


def share_held(boxes, targets) -> np.ndarray:
    """Per row, the share of the target's box (x, y, w, h) inside the box."""
    b, t = np.asarray(boxes, float), np.asarray(targets, float)
    w = np.minimum(b[:, 0] + b[:, 2], t[:, 0] + t[:, 2]) - np.maximum(b[:, 0], t[:, 0])
    h = np.minimum(b[:, 1] + b[:, 3], t[:, 1] + t[:, 3]) - np.maximum(b[:, 1], t[:, 1])
    return np.clip(w, 0, None) * np.clip(h, 0, None) / (t[:, 2] * t[:, 3])


def slid_off_unflagged(name: str, key: str) -> tuple[bool, str]:
    """Whether the box held none of the target on the frame before it went, with ``ok`` on
    every frame from the last one it held some of the target on; and what was measured. (A
    lost tracker reports its last box, so that frame may itself be lost: a re-detecting name
    that flagged the loss and was then moved onto the background is not this case.)"""
    clip, absent, _ = scene(key)
    went = int(np.flatnonzero(absent[1:])[0]) + 1
    ok, _, boxes = run(name, key)
    held = share_held(boxes[:went], np.asarray(clip.groundtruth, float)[:went])
    last = int(np.flatnonzero(held > 0)[-1])                   # frame 0: the given box
    unflagged = bool(ok[last:went].all())
    return held[-1] == 0 and unflagged, (
        f"its box held {held[-1]:.0%} of the target on frame {went - 1}, the last before it "
        f"went, and some of it last on frame {last}; ok on every frame from then: {unflagged}")


@pytest.mark.parametrize("name,key", list(KNOWN_ABSENT))
def test_the_cells_whose_box_slid_off_the_target_unflagged_are_the_marked_ones(name, key):
    slid, measured = slid_off_unflagged(name, key)
    assert slid == ((name, key) in OFF_BEFORE_IT_WENT), (
        f"{name} on {key}: {measured}; {'add the cell to' if slid else 'take the cell out of'}"
        " OFF_BEFORE_IT_WENT")


def test_the_marked_cells_are_missed_cells():
    assert OFF_BEFORE_IT_WENT <= set(KNOWN_ABSENT)


def _comes_back(n, k):
    return scene(k)[2] is not None and kind(k) in {"exit", "occlusion", "cut", "edge-exit",
                                                   "occluder", "leave-and-return"}


@pytest.mark.parametrize("name,key", list(_cells(REDETECTING, SCENES, _comes_back,
                                                  KNOWN_RECOVERY)))
def test_redetection_finds_the_target_within_10_frames_of_its_return(name, key):
    _, iou, _ = run(name, key)
    back = scene(key)[2]
    hit = np.flatnonzero(iou[back:] > 0.5)
    assert hit.size and hit[0] < 10, (f"{name} on {key}: first IoU > 0.5 "
                                      f"{'never' if not hit.size else f'{hit[0]} frames'} "
                                      f"after the return (frame {back})")


def _false_loss_cells(where, names=CANONICAL):
    for n in names:
        reason = FALSE_LOSSES.get((where, n))
        yield pytest.param(n, marks=[pytest.mark.xfail(strict=True, reason=reason)]
                           if reason else [])


@pytest.mark.parametrize("name", list(_false_loss_cells("small-long")))
def test_a_long_run_on_a_small_clip_has_no_false_losses(name):
    sc = S.SCENARIOS["small-long"]()
    r = trackbook.evaluate(name, sc.clip, seed=0)
    m = S.measure(r, sc)
    assert m["false_lost"] <= 0.01, \
        f"{name}: ok=False on {m['false_lost']:.1%} of the frames with IoU > 0.5"


# Item 2 on the sample clips and the real sequences reads the committed runs of every tracker
# there (``failure_samples`` and ``real``, whose rows carry ``false_losses = [lost, on]`` and
# the fingerprint of the code that made them): ``tests/test_results_fresh.py`` demands that
# every such row's fingerprint is this commit's (a change to a tracker or its thresholds makes
# the files stale) and re-runs one clip per tracker to check the counting itself. Re-running
# the ~3,000 frames per tracker here took a CI run six minutes (MIL and Median Flow alone,
# four). For OpenCV's MIL the fingerprint covers the wrapper and its child script, not
# OpenCV's own tracker: its counts are those of the OpenCV build that wrote the file.
SAMPLES_RESULT, REAL_RESULT = "failure_samples", "real"


def _committed(result: str, name: str) -> dict:
    rows = {r["clip"]: r["false_losses"] for r in results.load(result).where(tracker=name)}
    assert rows, (f"{result} has no row of {name}; regenerate it: "
                  f"python -m trackbook.evaluation.experiments run {result}")
    return rows


@pytest.mark.parametrize("result", [SAMPLES_RESULT, REAL_RESULT])
def test_the_committed_false_loss_runs_cover_every_tracker_and_clip(result):
    table = results.load(result)
    clips_of = {}
    for r in table:
        clips_of.setdefault(r["tracker"], []).append(r["clip"])
        assert len(r["false_losses"]) == 2 and 0 <= r["false_losses"][0] <= r["false_losses"][1]
    missing = sorted(set(CANONICAL) - set(clips_of))
    assert not missing, f"{result} misses {missing}"
    every = sorted({c for cs in clips_of.values() for c in cs})
    if result == SAMPLES_RESULT:
        assert every == sorted(clips.available())
    for n in CANONICAL:
        assert sorted(clips_of[n]) == every, f"{result}: {n} has clips {sorted(clips_of[n])}"


@pytest.mark.parametrize("name", list(_false_loss_cells("samples", CANONICAL + REDETECTING)))
def test_no_false_losses_on_the_sample_clips(name):
    worst = [f"{c}: {lost} of {on}" for c, (lost, on) in
             sorted(_committed(SAMPLES_RESULT, name).items()) if lost > 0.01 * on]
    assert not worst, f"{name} reports ok=False with IoU > 0.5 on more than 1 %: {worst}"


@pytest.mark.parametrize("name", list(_false_loss_cells("real", CANONICAL + REDETECTING)))
def test_no_false_losses_on_the_real_sequences(name):
    counts = _committed(REAL_RESULT, name).values()
    lost, on = sum(c[0] for c in counts), sum(c[1] for c in counts)
    assert lost <= 0.01 * on, (f"{name}: ok=False on {lost} of the {on} frames with IoU > 0.5 "
                               "of the real sequences")


@pytest.mark.parametrize("name,clip", [("mean-shift", "occluder"), ("mosse", "shelves")])
def test_the_library_count_is_an_independent_count_and_the_committed_one(name, clip):
    """``metrics.false_losses`` with the clip's in-view mask against ``tests/_scenarios.py``'s
    own count of the same run, written apart; and against the committed row (mosse on shelves
    is one of the counts above 1 %)."""
    c = clips.load(clip)
    r = trackbook.evaluate(name, c, seed=0)
    got = metrics.false_losses(r.ok, r.boxes, c.groundtruth, samples.in_view(clip))
    assert got == S.false_losses(r, c)
    assert np.array_equal(samples.in_view(clip), S.in_view(clip))
    assert list(got) == _committed(SAMPLES_RESULT, name)[clip]
