"""Several targets at once: tracking by detection with SORT (Bewley et al. 2016).

The single-target trackers of :mod:`trackbook.trackers` are given one box and follow it through
the images. Here a detector has already found boxes in every frame, without identities, and the
tracker's job is to join them into trajectories: one id per target, kept through misses,
false detections and crossings. The API is its own — ``Sort.update(detections)`` once per
frame, returning ``(x, y, w, h, id)`` rows — and such trackers are not in the single-target
registry.

* :class:`Sort` — SORT: a constant-velocity Kalman filter per track, Hungarian assignment on IoU.
* :func:`synthetic_detections` — ground truth and noisy detections of targets on crossing
  paths, boxes only, to run a tracker on in milliseconds.

Scored with the several-target measures of :mod:`trackbook.evaluation.mot`:

>>> import numpy as np
>>> from trackbook import mot
>>> from trackbook.evaluation.mot import mot_scores
>>> run = mot.synthetic_detections(n_targets=4, n_frames=60, seed=0,
...                                miss_rate=0.1, fp_rate=0.5, noise=2.0)
>>> sort = mot.Sort(max_age=1, min_hits=3, iou_threshold=0.3)
>>> tracks = [sort.update(d) for d in run.detections]
>>> scores = mot_scores(run.truth, tracks)
>>> {k: round(v, 3) for k, v in scores.items() if k in ("mota", "idf1", "hota")}
{'mota': 0.713, 'idf1': 0.751, 'hota': 0.618}

With ``max_age=1`` a target missed in two frames running loses its track and comes back under a
new id: IDF1 and HOTA's association accuracy see that, MOTA barely does.
"""

from __future__ import annotations

from .sort import Sort, associate, box_filter, box_to_z, z_to_box
from .synthetic import SyntheticRun, synthetic_detections

__all__ = ["Sort", "SyntheticRun", "associate", "box_filter", "box_to_z",
           "synthetic_detections", "z_to_box"]
