"""Data association for several targets: a gate and the Hungarian assignment (``case_study_cho2005``).

Independent trackers (:class:`trackbook.trackers.MultiTracker`, as in Cho & Kang 2005 §5.3)
never ask which target a box belongs to. This module adds that question as a layer on top of
them. Every frame, each per-target tracker proposes a box (a *candidate*); each *track* (one per
target identity) predicts where its target should be with the constant-velocity Kalman filter
of ``06_kalman``; candidates are **gated** (a candidate too far from a track's prediction, in
Mahalanobis distance, can never be given to it) and then **assigned** to tracks by the Hungarian
method (Kuhn 1955; ``scipy.optimize.linear_sum_assignment``). A track whose candidate fell
outside every gate coasts on its prediction and reports ``ok = False``.

>>> import numpy as np
>>> from trackbook.trackers.association import assign
>>> assign(np.array([[1.0, 5.0], [2.0, 9.0]]))        # the cheaper total is 5 + 2
[(0, 1), (1, 0)]
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment

from .._checks import check_frame, clip_box
from ..filters.kalman import constant_velocity
from .multi import target_seed

__all__ = ["AssociatedMultiTracker", "CHI2_GATE_99", "assign", "box_centres", "gate",
           "iou_matrix", "mahalanobis_matrix"]

#: The 99 % quantile of the χ² distribution with 2 degrees of freedom, −2 ln 0.01: a candidate
#: whose squared Mahalanobis distance from a track's prediction exceeds it is outside the gate.
CHI2_GATE_99 = float(-2.0 * np.log(0.01))


def box_centres(boxes) -> np.ndarray:
    """Centres (x + w/2, y + h/2) of (n, 4) boxes ``(x, y, w, h)``."""
    b = np.asarray(boxes, dtype=float).reshape(-1, 4)
    return b[:, :2] + b[:, 2:] / 2


def iou_matrix(a, b) -> np.ndarray:
    """Intersection over union of every box of ``a`` (n, 4) with every box of ``b`` (m, 4)."""
    a = np.asarray(a, dtype=float).reshape(-1, 4)[:, None, :]
    b = np.asarray(b, dtype=float).reshape(-1, 4)[None, :, :]
    w = np.minimum(a[..., 0] + a[..., 2], b[..., 0] + b[..., 2]) - np.maximum(a[..., 0], b[..., 0])
    h = np.minimum(a[..., 1] + a[..., 3], b[..., 1] + b[..., 3]) - np.maximum(a[..., 1], b[..., 1])
    inter = np.clip(w, 0, None) * np.clip(h, 0, None)
    union = a[..., 2] * a[..., 3] + b[..., 2] * b[..., 3] - inter
    with np.errstate(invalid="ignore", divide="ignore"):
        out = np.where(union > 0, inter / union, 0.0)
    return np.nan_to_num(out, nan=0.0)


def mahalanobis_matrix(predicted, S, candidates) -> np.ndarray:
    """Squared Mahalanobis distances d²_ij = (z_j − ẑ_i)ᵀ S_i⁻¹ (z_j − ẑ_i).

    Parameters
    ----------
    predicted : (n, d) predicted measurements ẑ_i of the n tracks
    S : (n, d, d) their innovation covariances S_i = H P_i⁻ Hᵀ + R
    candidates : (m, d) measurements z_j
    """
    zhat = np.asarray(predicted, dtype=float)
    z = np.asarray(candidates, dtype=float)
    S = np.asarray(S, dtype=float)
    y = z[None, :, :] - zhat[:, None, :]                        # (n, m, d) innovations
    sol = np.linalg.solve(S[:, None, :, :], y[..., None])[..., 0]
    return np.einsum("nmd,nmd->nm", y, sol)


def gate(d2, threshold: float = CHI2_GATE_99) -> np.ndarray:
    """The gate: True where a candidate may be given to a track (d² within ``threshold``)."""
    d2 = np.asarray(d2, dtype=float)
    return np.isfinite(d2) & (d2 <= threshold)


def assign(cost, allowed=None) -> list[tuple[int, int]]:
    """The Hungarian assignment of candidates (columns) to tracks (rows), respecting a gate.

    Among all one-to-one matchings that use only ``allowed`` pairs, it returns one with the
    **most** pairs and, among those, the smallest total cost. Forbidden pairs get a cost larger
    than any sum of allowed ones, ``scipy.optimize.linear_sum_assignment`` solves the square-up
    problem, and the forbidden pairs it had to use are dropped.

    Parameters
    ----------
    cost : (n, m) array; allowed : (n, m) bool array or None (everything allowed)

    Returns
    -------
    list of ``(row, column)`` pairs, sorted by row
    """
    cost = np.asarray(cost, dtype=float)
    if cost.ndim != 2:
        raise ValueError(f"assign needs a 2-D cost matrix (tracks x candidates), got shape "
                         f"{cost.shape}.")
    ok = np.isfinite(cost)
    if allowed is not None:
        allowed = np.asarray(allowed, dtype=bool)
        if allowed.shape != cost.shape:
            raise ValueError(f"allowed has shape {allowed.shape}, the cost matrix {cost.shape}; "
                             f"pass one flag per (track, candidate) pair.")
        ok &= allowed
    if cost.size == 0 or not ok.any():
        return []
    finite = np.where(ok, cost, 0.0)
    # one forbidden pair must cost more than any set of allowed pairs could save
    big = 1.0 + 2.0 * np.abs(finite).sum()
    rows, cols = linear_sum_assignment(np.where(ok, finite, big))
    return [(int(r), int(c)) for r, c in zip(rows, cols) if ok[r, c]]


class AssociatedMultiTracker:
    """Per-target trackers whose boxes are assigned to target identities by gate + Hungarian.

    Parameters
    ----------
    name : a registered tracker name; each target gets one tracker (``trackers.create``)
    seed : target k's tracker is seeded :func:`trackbook.trackers.multi.target_seed` (seed, k),
        as in :class:`~trackbook.trackers.MultiTracker`, so both start from the same trackers
    gate_threshold : squared Mahalanobis distance of the gate (default the χ²₂ 99 % quantile)
    associate : with ``False``, track k always takes tracker k's box (the independent trackers
        of :class:`~trackbook.trackers.MultiTracker`, for comparison under the same code)
    ambiguity_iou : a candidate whose box overlaps another candidate's by at least this IoU is
        *ambiguous*: it is still assigned and reported, but the track's Kalman filter is not
        updated with it (the track keeps its own velocity); ``None`` updates always
    q, r, p0 : the tracks' constant-velocity Kalman filters on box centres (``06_kalman``):
        Q = q·I₄, R = r·I₂, P₀ = p0·I₄, in pixels
    **params : the trackers' params

    Attributes
    ----------
    trackers : the per-target trackers; owner : for each track, the tracker whose box it took
        last (starts as ``[0, 1, ...]``); d2 : the last frame's (tracks × candidates) squared
        Mahalanobis distances; pairs : the last assignment; ambiguous : the last frame's
        ambiguous candidates
    """

    def __init__(self, name: str, seed: int | None = 0, gate_threshold: float = CHI2_GATE_99,
                 q: float = 1.0, r: float = 4.0, p0: float = 10.0, associate: bool = True,
                 ambiguity_iou: float | None = 0.3, **params):
        from . import create, get

        get(name)  # fail early, with the list of names, on a typo
        if not (np.isfinite(gate_threshold) and gate_threshold > 0):
            raise ValueError(f"gate_threshold must be a positive number, got {gate_threshold!r}.")
        self.name, self.seed, self._params = name, seed, dict(params)
        self.gate_threshold, self.q, self.r, self.p0 = float(gate_threshold), q, r, p0
        self.associate = bool(associate)
        if ambiguity_iou is not None and not 0.0 < float(ambiguity_iou) <= 1.0:
            raise ValueError(f"ambiguity_iou must be in (0, 1] or None, got {ambiguity_iou!r}.")
        self.ambiguity_iou = None if ambiguity_iou is None else float(ambiguity_iou)
        self.ambiguous = np.zeros(0, dtype=bool)
        self._create = create
        self.trackers: list = []
        self.kfs: list = []
        self.boxes: list = []
        self.oks: list = []
        self.owner: list = []
        self.d2 = np.zeros((0, 0))
        self.pairs: list = []

    def init(self, frame, boxes) -> None:
        """Start one tracker and one track per box of ``boxes`` on ``frame``."""
        frame = check_frame(frame)
        boxes = [clip_box(b, frame.shape) for b in boxes]
        if not boxes:
            raise ValueError("AssociatedMultiTracker.init needs at least one box; "
                             "pass [box1, box2, ...].")
        self.trackers = [self._create(self.name, seed=target_seed(self.seed, k), **self._params)
                         for k in range(len(boxes))]
        for t, b in zip(self.trackers, boxes):
            t.init(frame, b)
        self.kfs = [constant_velocity(x0=tuple(c), q=self.q, r=self.r, p0=self.p0)
                    for c in box_centres(boxes)]
        self.boxes = [tuple(float(v) for v in b) for b in boxes]
        self.oks = [True] * len(boxes)
        self.owner = list(range(len(boxes)))

    def update(self, frame):
        """Track into ``frame``: ``(oks, boxes)`` in track (target identity) order."""
        if not self.trackers:
            raise ValueError("AssociatedMultiTracker: call init(frame, [box1, ...]) before update.")
        frame = check_frame(frame)
        out = [t.update(frame) for t in self.trackers]
        cand = np.array([b for _, b in out], dtype=float)
        cand_ok = np.array([bool(ok) for ok, _ in out])
        for kf in self.kfs:
            kf.predict()
        zhat = np.array([kf.x[:2] for kf in self.kfs])
        S = np.array([kf.innovation_covariance() for kf in self.kfs])
        self.d2 = mahalanobis_matrix(zhat, S, box_centres(cand))
        allowed = gate(self.d2, self.gate_threshold) & cand_ok[None, :]
        if self.associate:
            self.pairs = assign(self.d2, allowed)
        else:
            self.pairs = [(k, k) for k in range(len(self.trackers))]
        taken = dict(self.pairs)
        # Candidates that overlap another candidate cannot be told apart by position: their
        # boxes are still reported, but the tracks keep their own motion (no Kalman update),
        # so that two trackers stalled on a crossing do not teach both tracks to stand still.
        self.ambiguous = np.zeros(len(cand), dtype=bool)
        if self.associate and self.ambiguity_iou is not None and len(cand) > 1:
            ov = iou_matrix(cand, cand)
            np.fill_diagonal(ov, 0.0)
            self.ambiguous = ov.max(axis=1) >= self.ambiguity_iou
        for i, kf in enumerate(self.kfs):
            if i in taken:
                j = taken[i]
                if not self.ambiguous[j]:
                    kf.update(box_centres(cand[j])[0])
                self.boxes[i] = tuple(float(v) for v in cand[j])
                self.oks[i], self.owner[i] = bool(cand_ok[j]), j
            else:   # nothing in the gate: coast on the prediction, keep the last size
                w, h = self.boxes[i][2:]
                # the drawn centre stays on the frame, wherever the prediction wanders
                cx = float(np.clip(kf.x[0], 0.0, frame.shape[1]))
                cy = float(np.clip(kf.x[1], 0.0, frame.shape[0]))
                self.boxes[i] = (cx - w / 2, cy - h / 2, w, h)
                self.oks[i] = False
        return list(self.oks), list(self.boxes)

    def __len__(self) -> int:
        return len(self.trackers)

