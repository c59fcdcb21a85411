"""OTB scores of a run: overlap, centre error, success and precision curves.

Every function takes ``(pred, gt)`` as N x 4 arrays of boxes ``(x, y, w, h)`` and scores every
row whose ground truth is finite. A prediction that is NaN or has w <= 0 or h <= 0 (negative
sizes included: such a box covers no pixel) scores IoU 0 and an infinite centre error (a
tracker that gave up is wrong, not excused). Ground truth of zero size (or NaN) is OTB's
"target absent" and is not scored; ground truth with a *negative* width or height is refused
with ``ValueError`` naming the row: it is a typing error (two corners written as x, y, w, h),
not an absent target. Boxes use continuous coordinates: a box covers [x, x + w) x [y, y + h).

Which frames to score is the caller's choice; :func:`trackbook.evaluate` drops frame 0, the
initialisation, before calling these.
"""

from __future__ import annotations

import numpy as np

from .._checks import check_boxes

#: IoU thresholds of the success curve: 0, 0.05, ..., 1.
SUCCESS_THRESHOLDS = np.linspace(0.0, 1.0, 21)
#: Centre-error thresholds of the precision curve in pixels: 0, 1, ..., 50.
PRECISION_THRESHOLDS = np.arange(0, 51, dtype=float)


def _pair(pred, gt):
    p = check_boxes(pred, name="pred")
    g = check_boxes(gt, name="gt")
    with np.errstate(invalid="ignore"):
        neg = np.flatnonzero((g[:, 2] < 0) | (g[:, 3] < 0))
    if neg.size:
        i = int(neg[0])
        raise ValueError(
            f"gt row {i} ({', '.join(f'{v:g}' for v in g[i])}) has a negative width or height "
            f"({neg.size} such rows); ground truth is x, y, w, h with w, h >= 0 (not two "
            "corners); write NaN or 0, 0, 0, 0 where the target is absent.")
    if p.shape[0] != g.shape[0]:
        raise ValueError(
            f"pred has {p.shape[0]} boxes but gt has {g.shape[0]}; give one box per frame each."
        )
    return p, g


def _valid_pred(p):
    with np.errstate(invalid="ignore"):
        return np.all(np.isfinite(p), axis=1) & (p[:, 2] > 0) & (p[:, 3] > 0)


def _known_gt(g):
    with np.errstate(invalid="ignore"):
        return np.all(np.isfinite(g), axis=1) & (g[:, 2] > 0) & (g[:, 3] > 0)


def iou(pred, gt) -> np.ndarray:
    """Intersection over union per frame.

    Returns an array of length N: IoU in [0, 1] where the ground truth is known, NaN where it
    is not. Invalid predictions score 0.
    """
    p, g = _pair(pred, gt)
    out = np.full(p.shape[0], np.nan)
    known = _known_gt(g)
    ok = known & _valid_pred(p)
    out[known] = 0.0
    if ok.any():
        a, b = p[ok], g[ok]
        ix = np.clip(np.minimum(a[:, 0] + a[:, 2], b[:, 0] + b[:, 2]) - np.maximum(a[:, 0], b[:, 0]), 0, None)
        iy = np.clip(np.minimum(a[:, 1] + a[:, 3], b[:, 1] + b[:, 3]) - np.maximum(a[:, 1], b[:, 1]), 0, None)
        inter = ix * iy
        union = a[:, 2] * a[:, 3] + b[:, 2] * b[:, 3] - inter
        out[ok] = np.clip(inter / union, 0.0, 1.0)
    return out


def center_error(pred, gt) -> np.ndarray:
    """Euclidean distance between box centres per frame, in pixels.

    NaN where the ground truth is unknown; ``inf`` for invalid predictions.
    """
    p, g = _pair(pred, gt)
    out = np.full(p.shape[0], np.nan)
    known = _known_gt(g)
    ok = known & _valid_pred(p)
    out[known] = np.inf
    if ok.any():
        cp = p[ok, :2] + p[ok, 2:] / 2
        cg = g[ok, :2] + g[ok, 2:] / 2
        out[ok] = np.hypot(*(cp - cg).T)
    return out


def _scored(values: np.ndarray) -> np.ndarray:
    v = values[~np.isnan(values)]
    if v.size == 0:
        raise ValueError(
            "no frame has a known ground truth box; check the ground truth file "
            "(rows of NaN or zero size mean 'unknown')."
        )
    return v


def success_curve(pred, gt, thresholds=SUCCESS_THRESHOLDS):
    """OTB success plot: fraction of scored frames with IoU **>** t for each threshold t.

    Returns ``(thresholds, rates)``.
    """
    v = _scored(iou(pred, gt))
    t = np.asarray(thresholds, dtype=float)
    return t, (v[None, :] > t[:, None]).mean(axis=1)


def auc(pred, gt) -> float:
    """Area under the success curve: the mean of its 21 rates (OTB's AUC)."""
    return float(success_curve(pred, gt)[1].mean())


def precision_curve(pred, gt, thresholds=PRECISION_THRESHOLDS):
    """OTB precision plot: fraction of scored frames with centre error **<=** t, t = 0..50 px.

    Returns ``(thresholds, rates)``.
    """
    v = _scored(center_error(pred, gt))
    t = np.asarray(thresholds, dtype=float)
    return t, (v[None, :] <= t[:, None]).mean(axis=1)


def precision(pred, gt, threshold: float = 20.0) -> float:
    """The precision score: fraction of scored frames with centre error <= ``threshold`` px."""
    return float(precision_curve(pred, gt, [threshold])[1][0])


def tracking_rate(pred, gt, iou_threshold: float = 0.5) -> float:
    """The tracking rate: fraction of scored frames with IoU > ``iou_threshold``.

    This is the book's reading of the papers' success counts, not a criterion any of them
    prints: Lee et al. (2012) count "Frame Pos", the frames in which tracking succeeded
    [quote: lee2012.frame_pos]; Kim et al. (2016) the "Correct" frames [quote: kim2016.correct];
    Lee (2015) the frames "in which the region was detected", eq. 14
    [quote: lee2015.detection_rate_eq14]. Cho and Kang (2005) count no frames: they report
    error curves, the candidates' mean likelihood and seconds per frame
    [quote: cho2005.error_curves] [quote: cho2005.mean_likelihood]
    [quote: cho2005.table1_seconds]. IoU > 0.5 is the threshold of the OTB benchmark's
    success rate, which turns "tracked correctly" into a rule.
    """
    v = _scored(iou(pred, gt))
    return float((v > iou_threshold).mean())


def mean_center_error(pred, gt) -> float:
    """Mean centre error over scored frames with a valid prediction (lost frames left out)."""
    v = _scored(center_error(pred, gt))
    v = v[np.isfinite(v)]
    return float(v.mean()) if v.size else float("inf")


def summary(pred, gt) -> dict:
    """All headline scores of one run as a dict (what tables print)."""
    return {
        "auc": auc(pred, gt),
        "precision20": precision(pred, gt),
        "tracking_rate": tracking_rate(pred, gt),
        "mean_center_error": mean_center_error(pred, gt),
        "frames_scored": int((~np.isnan(iou(pred, gt))).sum()),
    }


def false_losses(ok, pred, gt, in_view=None) -> tuple[int, int]:
    """Frames a run reported lost while its box was on the target.

    Over frames 1..N-1 (frame 0 is the given box), two counts ``(lost, on)``: ``on`` counts the
    frames whose box overlaps the ground truth with IoU > 0.5 (and, when ``in_view`` is
    given, whose target is in view there: a bool array over the clip's frames) and ``lost``
    those of them with ``ok`` False. ``lost / on`` is the share the failure contract bounds.
    """
    pred = np.asarray(pred, dtype=float)
    n = len(pred)
    overlap = np.nan_to_num(iou(pred, np.asarray(gt, dtype=float)[:n]), nan=0.0)[1:]
    on = overlap > 0.5
    if in_view is not None:
        in_view = np.asarray(in_view, bool)
        if in_view.ndim != 1 or len(in_view) < n:
            raise ValueError(f"in_view must hold one flag per frame of the run ({n}), got "
                             f"shape {in_view.shape}; pass the clip's whole mask.")
        on &= in_view[1:n]
    ok = np.asarray(ok, bool)[1:n]
    return int((~ok[on]).sum()), int(on.sum())


def scores_line(scores: dict, *, ms: bool = True, sep: str = " \u00b7 ") -> str:
    """A run's headline scores as one line of text (the playground, the animations, the CLI).

    ``"AUC 0.512 · precision@20px 0.640 · tracking rate 58.0% · 4.21 ms/frame"``; without
    ground truth (no ``"auc"`` in ``scores``) ``"no ground truth"`` stands for the three
    scores. ``ms=False`` leaves out the timing (``scores["ms_median"]``).
    """
    if "auc" in scores:
        parts = [f"AUC {scores['auc']:.3f}", f"precision@20px {scores['precision20']:.3f}",
                 f"tracking rate {scores['tracking_rate']:.1%}"]
    else:
        parts = ["no ground truth"]
    if ms and "ms_median" in scores:
        parts.append(f"{scores['ms_median']:.2f} ms/frame")
    return sep.join(parts)


__all__ = [
    "iou", "center_error", "success_curve", "auc", "precision_curve", "precision",
    "tracking_rate", "mean_center_error", "summary", "false_losses", "SUCCESS_THRESHOLDS",
    "PRECISION_THRESHOLDS", "scores_line",
]
