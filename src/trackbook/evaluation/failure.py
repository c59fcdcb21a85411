"""How well a tracker's confidence tells "on target" from "target absent", and the thresholds
of the failure rule chosen on calibration runs.

* :func:`roc_curve`, :func:`roc_auc` - the confidence as a score, frame by frame: on-target
  frames are the positives, target-absent frames the negatives;
* :func:`detection_rates` - what :class:`~trackbook.trackers.failure.FailureDetector` does on
  whole runs: the share of absent frames it flags lost, and of on-target frames it flags
  lost by mistake;
* :func:`calibrate` - the thresholds (:class:`~trackbook.trackers.failure.FailureParams`)
  of one tracker, chosen on its calibration runs by a stated objective.

The rule itself lives in :mod:`trackbook.trackers.failure`, where every tracker uses it.
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
from scipy.stats import rankdata

from ..trackers.failure import CALIBRATION_FILE, FailureDetector, FailureParams, load_calibration

#: Default grid of ``k_lost`` (in spreads below the reference; ``inf``: the spread test off):
#: a very steady confidence, as on a rendered clip, has a tiny spread, so an ordinary dip is
#: many spreads deep.
K_LOST_GRID = (3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 15.0, 20.0, 30.0, 50.0, math.inf)
#: Default grid of ``ratio_lost`` (the fraction of the reference; 0: the ratio test off).
RATIO_GRID = tuple(round(0.1 * j, 1) for j in range(10))
#: Default hysteresis ``h``, tried for every pair: the found thresholds are ``h`` times as far
#: below the reference as the lost ones, ``k_found = h k_lost`` and
#: ``ratio_found = ratio_lost ** h`` (the same shrink of the distance in log units).
HYSTERESIS = (0.5, 0.75, 1.0)
#: The found thresholds :func:`floor_found` imposes, chosen before any measurement: back to
#: four fifths of the reference (ratio test) and within 4 spreads of it (spread test).
FOUND_RATIO = 0.8
FOUND_K = 4.0


def params_for(k_lost: float, ratio_lost: float, h: float, **fixed) -> FailureParams:
    """The :class:`FailureParams` of one grid point: lost thresholds and a hysteresis ``h``
    in (0, 1] (see :data:`HYSTERESIS`)."""
    if not 0 < h <= 1:
        raise ValueError(f"hysteresis h = {h!r}: give a number in (0, 1].")
    return FailureParams(k_lost=k_lost, k_found=h * k_lost, ratio_lost=ratio_lost,
                         ratio_found=ratio_lost ** h if ratio_lost > 0 else 0.0, **fixed)


def floor_found(params: FailureParams, ratio: float = FOUND_RATIO,
                k: float = FOUND_K) -> FailureParams:
    """``params`` with found thresholds at least as strict as ``ratio`` times the reference
    and ``k`` spreads below it, for the tests that are on (a test that is off stays off).

    Why: :func:`calibrate` replays the rule on runs without the layer, where the tracker kept
    learning after it would have been lost; with the layer on, a lost tracker stops learning
    and scores what it sees with its model from before the loss, and a background it stares
    at while lost can score above a loose found threshold. A floor asks the confidence to
    come back near its level before the loss. Which of the two, :func:`calibrate`'s result or
    this one, a tracker keeps is measured with the layer on (``experiments/
    calibrate_failure.py``); the floor can also delay a true return.
    """
    k_found = min(params.k_found, float(k)) if math.isfinite(params.k_lost) else params.k_found
    ratio_found = max(params.ratio_found, float(ratio)) if params.ratio_lost > 0 else 0.0
    return dataclasses.replace(params, k_found=k_found, ratio_found=ratio_found)


def objective(absent_lost: float, false_lost: float, target: float = 0.95,
              max_false: float = 0.01) -> tuple:
    """The calibration's objective as a key, larger is better: first false losses at most
    ``max_false`` (else the fewest), then ``min(absent_lost, target)``, then the fewest
    false losses, then the most absent frames flagged."""
    ok = false_lost <= max_false
    return (ok, 0.0 if ok else -false_lost, min(absent_lost, target), -false_lost,
            absent_lost)


def _scores(values, name: str) -> np.ndarray:
    v = np.asarray(values, float).ravel()
    if v.size == 0:
        raise ValueError(f"{name} is empty: the ROC needs at least one confidence of each "
                         "class (frames on target and frames with the target absent).")
    return np.where(np.isnan(v), -np.inf, v)


def roc_curve(confidence_present, confidence_absent):
    """ROC of the confidence as a test of "on target" (positive) against "target absent".

    A frame is called on target at threshold ``t`` when its confidence is ``>= t``.

    Parameters
    ----------
    confidence_present : array_like
        Confidences of frames where the tracker is on the target (e.g. IoU > 0.5).
    confidence_absent : array_like
        Confidences of frames where no part of the target is in view. NaN (no score) counts
        as ``-inf`` in both: below every threshold.

    Returns
    -------
    fpr : ndarray
        Share of absent frames called on target, per threshold (non-decreasing, from 0).
    tpr : ndarray
        Share of on-target frames called on target, per threshold.
    thresholds : ndarray
        ``+inf`` (nothing called on target), then the distinct confidences, decreasing.

    Notes
    -----
    The same points as ``sklearn.metrics.roc_curve(y, c, drop_intermediate=False)`` with
    ``y = 1`` on target, 0 absent.
    """
    pos = _scores(confidence_present, "confidence_present")
    neg = _scores(confidence_absent, "confidence_absent")
    c = np.concatenate([pos, neg])
    y = np.concatenate([np.ones(pos.size, bool), np.zeros(neg.size, bool)])
    order = np.argsort(-c, kind="mergesort")
    c, y = c[order], y[order]
    # the last index of each run of equal confidences: all of a tie switch together
    last = np.r_[np.flatnonzero(np.diff(c) != 0), c.size - 1]
    tp = np.cumsum(y)[last]
    fp = (last + 1) - tp
    return (np.r_[0.0, fp / neg.size], np.r_[0.0, tp / pos.size], np.r_[np.inf, c[last]])


def roc_auc(confidence_present, confidence_absent) -> float:
    """Area under :func:`roc_curve`: P(c_on > c_absent) + P(c_on = c_absent) / 2.

    Computed from average ranks (the Mann-Whitney statistic), so ties count one half.
    0.5 is chance; 1 separates the classes perfectly.
    """
    pos = _scores(confidence_present, "confidence_present")
    neg = _scores(confidence_absent, "confidence_absent")
    ranks = rankdata(np.concatenate([pos, neg]))      # average ranks over ties
    u = ranks[:pos.size].sum() - pos.size * (pos.size + 1) / 2.0
    return float(u / (pos.size * neg.size))


def _runs(series) -> list[np.ndarray]:
    """One array per run: a list of 1-D series, or one 1-D series."""
    if (isinstance(series, np.ndarray) and series.ndim == 1) or (
            len(series) and np.ndim(series[0]) == 0):
        series = [series]
    return [np.asarray(s).ravel() for s in series]


def counted_on_target(absent, on_target, grace: int) -> np.ndarray:
    """On-target frames a false loss is charged on: on target (and not absent) on this frame
    and on the ``grace`` frames before it (frames before the first count as on target: the
    run starts on the given box). A rule that needs ``m`` frames in a row to trust the
    target is not charged for them after the target comes back or the tracker finds it
    again."""
    absent = np.asarray(absent, bool)
    on = np.asarray(on_target, bool) & ~absent
    if grace > 0:
        off = (~on).astype(int)
        # frames i with a frame not on target among i - grace .. i - 1
        recent = np.convolve(off, np.ones(grace, int))[:off.size]
        on &= np.r_[0, recent[:-1]] == 0
    return on


def _check(series, absent, on_target):
    s, a, o = _runs(series), _runs(absent), _runs(on_target)
    if not (len(s) == len(a) == len(o)):
        raise ValueError(f"{len(s)} confidence series, {len(a)} absent masks and {len(o)} "
                         "on_target masks: give one of each per run.")
    for j, (x, y, z) in enumerate(zip(s, a, o)):
        if not (x.size == y.size == z.size):
            raise ValueError(f"run {j}: {x.size} confidences, {y.size} absent flags and "
                             f"{z.size} on_target flags; give one of each per frame.")
    return ([x.astype(float) for x in s], [y.astype(bool) for y in a],
            [z.astype(bool) for z in o])


def detection_rates(series, absent, on_target, params: FailureParams,
                    grace: int | None = None) -> dict:
    """What the failure rule does on whole runs.

    Parameters
    ----------
    series : list of 1-D arrays (or one array)
        The confidence of every frame the rule judges, one array per run.
    absent : list of bool arrays
        Frames where no part of the target is in view.
    on_target : list of bool arrays
        Frames where the tracker is on the target (e.g. IoU > 0.5 with the ground truth).
    params : FailureParams
    grace : int, optional
        Frames at the start of every stretch on target not charged as false losses (default
        ``params.m``: the rule needs ``m`` frames to trust a return); see
        :func:`counted_on_target`.

    Returns
    -------
    dict
        ``absent_lost`` (share of absent frames judged lost), ``false_lost`` (share of charged
        on-target frames judged lost), ``n_absent``, ``n_on`` (their counts), ``n_absent_lost``
        and ``n_false_lost``. A share over no frames is NaN.
    """
    s, a, o = _check(series, absent, on_target)
    det = FailureDetector(params)
    return judged_rates([det.run(x) for x in s], a, o, params.m if grace is None else grace)


def judged_rates(ok, absent, on_target, grace: int) -> dict:
    """The rates of :func:`detection_rates` from judgements already made: ``ok`` per frame
    of each run (e.g. a tracker run with its layer on), with the same ``absent`` and
    ``on_target`` masks and ``grace``."""
    s, a, o = _check(ok, absent, on_target)
    n_abs = n_abs_lost = n_on = n_false = 0
    for x, ab, on in zip(s, a, o):
        lost = x == 0
        on = counted_on_target(ab, on, int(grace))
        n_abs += int(ab.sum())
        n_abs_lost += int((lost & ab).sum())
        n_on += int(on.sum())
        n_false += int((lost & on).sum())
    return {"absent_lost": n_abs_lost / n_abs if n_abs else float("nan"),
            "false_lost": n_false / n_on if n_on else float("nan"),
            "n_absent": n_abs, "n_on": n_on, "n_absent_lost": n_abs_lost,
            "n_false_lost": n_false}


@dataclasses.dataclass(frozen=True)
class Calibration:
    """The thresholds :func:`calibrate` chose and what they achieve on the calibration runs.

    Attributes
    ----------
    params : FailureParams
    absent_lost, false_lost : float
        The rates of :func:`detection_rates` with ``params``.
    feasible : bool
        Whether ``false_lost <= max_false`` (else ``params`` are the fewest false losses).
    meets_target : bool
        Whether also ``absent_lost >= target``.
    n_absent, n_on : int
        Frames the rates are over.
    """

    params: FailureParams
    absent_lost: float
    false_lost: float
    feasible: bool
    meets_target: bool
    n_absent: int
    n_on: int


def calibrate(series, absent, on_target, *, target: float = 0.95, max_false: float = 0.01,
              k_lost_grid=K_LOST_GRID, ratio_grid=RATIO_GRID, hysteresis=HYSTERESIS,
              m: int = 3, window: int = 30, warmup: int = 5,
              grace: int | None = None) -> Calibration:
    """Choose the thresholds of the failure rule for one tracker from its calibration runs.

    The rule is stateful (a loss freezes the reference; recovery takes ``m`` frames), so it
    is judged on whole runs with per-frame labels, not on two pools of values.

    Objective, over the grid ``k_lost in k_lost_grid``, ``ratio_lost in ratio_grid``,
    ``h in hysteresis`` (:func:`params_for`; the pair ``k_lost = inf``, ``ratio_lost = 0``,
    no test at all, is left out):

    1. constraint: false losses ``<= max_false`` (on-target frames judged lost);
    2. maximise ``min(absent_lost, target)``: flag the absent frames, but detection beyond
       the target buys nothing;
    3. then the fewest false losses; 4. then the most absent frames flagged;
    5. then the largest ``k_lost`` and the smallest ``ratio_lost`` (the farthest from the
       on-target noise), then the smallest ``h`` (the widest hysteresis band: the least
       flapping).

    When no grid point meets the constraint, the fewest false losses win (then 2-5), and
    the result says ``feasible=False``.

    Parameters
    ----------
    series, absent, on_target
        As for :func:`detection_rates`: one confidence array and two bool masks per run.
    target : float
        The share of absent frames to flag (0.95).
    max_false : float
        The most on-target frames that may be flagged lost (0.01).
    k_lost_grid, ratio_grid, hysteresis
        The candidates.
    m, window, warmup
        Fixed :class:`FailureParams` fields.
    grace : int, optional
        See :func:`detection_rates` (default ``m``).

    Returns
    -------
    Calibration
    """
    s, a, o = _check(series, absent, on_target)
    if not any(x.any() for x in a) or not any(x.any() for x in o):
        raise ValueError("calibrate needs runs with absent frames and runs with on-target "
                         "frames; the calibration set's scenes give both.")
    best, best_key = None, None
    for k in sorted({float(v) for v in k_lost_grid}):
        for ratio in sorted({float(v) for v in ratio_grid}):
            if math.isinf(k) and ratio == 0:
                continue
            for h in sorted({float(v) for v in hysteresis}):
                p = params_for(k, ratio, h, m=m, window=window, warmup=warmup)
                r = detection_rates(s, a, o, p, grace=grace)
                key = objective(r["absent_lost"], r["false_lost"], target, max_false) + (
                    k, -ratio, -h)
                if best_key is None or key > best_key:
                    best, best_key = (p, r), key
    p, r = best
    feasible = r["false_lost"] <= max_false
    return Calibration(p, r["absent_lost"], r["false_lost"], feasible,
                       feasible and r["absent_lost"] >= target, r["n_absent"], r["n_on"])


def calibration_table(path=None) -> dict:
    """The whole calibration file as written: its settings and one row per tracker.

    Each row holds the chosen thresholds (``k_lost``, ``k_found``, ``ratio_lost``,
    ``ratio_found``, ``m``, ``window``, ``warmup``; a ``k`` of null is a spread test turned
    off), what the first pass's thresholds reach on the calibration scenes, replayed
    (``absent_lost``, ``false_lost``, ``meets_target``), the confidence's ROC area and
    thinned curve (``roc_auc``, ``roc``), the same per kind of scene (``per_kind``), the
    second pass with the layer on (``found_floored``: whether the found thresholds kept are
    :func:`floor_found`'s; ``with_layer``: both candidates' found thresholds and rates) and,
    when the real sequences were present, on them (``real_roc_auc``, ``real_roc``: on target
    against off target).
    ``load_calibration`` gives only the thresholds.
    """
    path = Path(CALIBRATION_FILE if path is None else path)
    load_calibration(path)                       # the same checks and error as the thresholds
    return json.loads(path.read_text(encoding="utf-8"))


__all__ = ["CALIBRATION_FILE", "FOUND_K", "FOUND_RATIO", "Calibration", "FailureDetector",
           "FailureParams", "HYSTERESIS", "K_LOST_GRID", "RATIO_GRID", "calibrate",
           "calibration_table", "counted_on_target", "detection_rates", "floor_found",
           "judged_rates", "load_calibration", "objective", "params_for", "roc_auc",
           "roc_curve"]
