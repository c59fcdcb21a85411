"""Detections of several targets on crossing paths, with misses, false positives and noise.

Boxes only, no images: a detector's output as SORT sees it, with the ground truth beside it,
so a several-target tracker can be run and scored in milliseconds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["SyntheticRun", "synthetic_detections"]


@dataclass(frozen=True)
class SyntheticRun:
    """Ground truth and detections of one synthetic clip.

    Attributes
    ----------
    truth : list, one (k, 5) float array per frame, rows (x, y, w, h, id), ids 1..n_targets
        (the run layout of :mod:`trackbook.evaluation.mot`)
    detections : list, one (n, 5) float array per frame, rows (x, y, w, h, score), in random
        order (the order says nothing about identity); what :meth:`Sort.update` takes
    frame_size : (width, height) of the scene the paths cross
    """

    truth: list
    detections: list
    frame_size: tuple


def synthetic_detections(n_targets: int = 4, n_frames: int = 60, seed: int = 0,
                         miss_rate: float = 0.1, fp_rate: float = 0.5, noise: float = 2.0, *,
                         frame_size: tuple = (640, 480)) -> SyntheticRun:
    """Targets walking straight across the scene, alternately from the left and from the right.

    Target k (id k + 1) has a fixed size (width 30–60 px, height 60–120 px) and moves at
    constant velocity from a random height at one side of the scene to a random height at the
    other, reaching it on the last frame; targets going opposite ways cross. Each frame:

    * each target is missed with probability ``miss_rate``; otherwise its detection is its box
      plus independent N(0, noise²) pixels on x, y, w and h (w, h kept ≥ 2 px), score
      uniform in [0.5, 1];
    * Poisson(``fp_rate``) false positives appear anywhere in the scene, with sizes like the
      targets' and score uniform in [0.3, 0.8].

    Parameters
    ----------
    n_targets, n_frames : int, ≥ 1
    seed : int
        The same seed gives the same run.
    miss_rate : float in [0, 1)
    fp_rate : float ≥ 0, expected false positives per frame
    noise : float ≥ 0, the standard deviation (pixels) of the detection noise
    frame_size : (width, height)

    Returns
    -------
    SyntheticRun

    >>> run = synthetic_detections(n_targets=2, n_frames=3, seed=0, miss_rate=0, fp_rate=0)
    >>> [len(d) for d in run.detections], run.truth[0][:, 4].tolist()
    ([2, 2, 2], [1.0, 2.0])
    """
    if int(n_targets) != n_targets or n_targets < 1:
        raise ValueError(f"n_targets must be a whole number >= 1, got {n_targets!r}.")
    if int(n_frames) != n_frames or n_frames < 1:
        raise ValueError(f"n_frames must be a whole number >= 1, got {n_frames!r}.")
    if not 0.0 <= miss_rate < 1.0:
        raise ValueError(f"miss_rate must be in [0, 1), got {miss_rate!r}.")
    if not fp_rate >= 0.0:
        raise ValueError(f"fp_rate must be >= 0 (false positives per frame), got {fp_rate!r}.")
    if not noise >= 0.0:
        raise ValueError(f"noise must be >= 0 (pixels), got {noise!r}.")
    W, H = (float(v) for v in frame_size)
    n_targets, n_frames = int(n_targets), int(n_frames)
    rng = np.random.default_rng(seed)

    size = np.c_[rng.uniform(30, 60, n_targets), rng.uniform(60, 120, n_targets)]
    rightwards = np.arange(n_targets) % 2 == 0
    x_left, x_right = np.zeros(n_targets), W - size[:, 0]
    x0 = np.where(rightwards, x_left, x_right)
    x1 = np.where(rightwards, x_right, x_left)
    y0 = rng.uniform(0, 1, n_targets) * (H - size[:, 1])
    y1 = rng.uniform(0, 1, n_targets) * (H - size[:, 1])
    frac = np.linspace(0.0, 1.0, n_frames)[:, None] if n_frames > 1 else np.zeros((1, 1))
    xs = x0 + frac * (x1 - x0)                          # (n_frames, n_targets)
    ys = y0 + frac * (y1 - y0)
    ids = np.arange(1, n_targets + 1, dtype=float)

    truth, detections = [], []
    for t in range(n_frames):
        boxes = np.c_[xs[t], ys[t], size]
        truth.append(np.c_[boxes, ids])
        seen = rng.random(n_targets) >= miss_rate
        det = boxes[seen] + rng.normal(0.0, noise, (int(seen.sum()), 4))
        det[:, 2:] = np.maximum(det[:, 2:], 2.0)
        det = np.c_[det, rng.uniform(0.5, 1.0, len(det))]
        n_fp = rng.poisson(fp_rate)
        fp_size = np.c_[rng.uniform(30, 60, n_fp), rng.uniform(60, 120, n_fp)]
        fp = np.c_[rng.uniform(0, 1, (n_fp, 2)) * ([W, H] - fp_size), fp_size,
                   rng.uniform(0.3, 0.8, n_fp)]
        both = np.vstack([det, fp]).reshape(-1, 5)
        detections.append(both[rng.permutation(len(both))])
    return SyntheticRun(truth=truth, detections=detections, frame_size=(W, H))
