"""SORT (Bewley et al. 2016): several targets tracked by detection, a Kalman filter per track.

Every frame a detector gives boxes without identities. SORT keeps one *track* per target:

1. each track's Kalman filter **predicts** its box in the new frame (constant velocity);
2. detections are **assigned** to tracks by the Hungarian method on IoU between detection
   and predicted box (the largest total IoU), and an assigned pair with IoU below
   ``iou_threshold`` is then rejected (the gate), as Bewley et al. 2016 describe it (their
   current reference code first checks whether the pairs above the gate are already one to
   one and then keeps them without solving; that shortcut is not taken here);
   ``gate_first=True`` is the book's variant that forbids those pairs before solving;
3. an assigned track **updates** its filter with its detection; a detection left over starts a
   new (tentative) track; a track left over coasts on its prediction;
4. a track is **reported** in a frame where it was detected and its last ``min_hits`` frames
   were all detected (the frame that started it not counted); it is **deleted** once it has
   gone more than ``max_age`` frames without a detection.

The state of a track is SORT's x = (u, v, s, r, u̇, v̇, ṡ): centre (u, v), area s = w·h and aspect
ratio r = w/h, the last taken as constant; it is measured as z = (u, v, s, r).
"""

from __future__ import annotations

import numpy as np

from ..filters.kalman import KalmanFilter
from ..trackers.association import assign, iou_matrix

__all__ = ["Sort", "associate", "box_filter", "box_to_z", "z_to_box"]


def box_to_z(box) -> np.ndarray:
    """SORT's measurement z = (u, v, s, r) of a box (x, y, w, h): centre, area w·h, ratio w/h.

    >>> box_to_z((10, 20, 30, 60)).tolist()
    [25.0, 50.0, 1800.0, 0.5]
    """
    x, y, w, h = np.asarray(box, dtype=float).reshape(4)
    return np.array([x + w / 2, y + h / 2, w * h, w / h])


def z_to_box(z) -> np.ndarray:
    """The box (x, y, w, h) of a state or measurement (u, v, s, r, …): w = √(s·r), h = s / w.

    >>> z_to_box((25, 50, 1800, 0.5)).tolist()
    [10.0, 20.0, 30.0, 60.0]
    """
    u, v, s, r = np.asarray(z, dtype=float).reshape(-1)[:4]
    w = np.sqrt(s * r)
    h = s / w
    return np.array([u - w / 2, v - h / 2, w, h])


def box_filter(box) -> KalmanFilter:
    r"""The Kalman filter of one SORT track, started at ``box`` (x, y, w, h).

    x = (u, v, s, r, u̇, v̇, ṡ), z = (u, v, s, r);

    .. math::

        F = \begin{pmatrix} I_3 & 0 & I_3 \\ 0 & 1 & 0 \\ 0 & 0 & I_3 \end{pmatrix}
        \text{ (rows/columns ordered } u, v, s, r, \dot u, \dot v, \dot s),
        \qquad H = (I_4 \; 0),

    so u, v and s advance by their velocities each frame and r stays. The noise and the
    starting covariance are those of SORT's reference code: R = diag(1, 1, 10, 10) (area and
    ratio measured less surely than the centre), P₀ = diag(10, 10, 10, 10, 10⁴, 10⁴, 10⁴)
    (velocities unknown at birth), Q = diag(1, 1, 1, 1, 10⁻², 10⁻², 10⁻⁴).
    """
    kf = KalmanFilter(7, 4)
    kf.F = np.eye(7)
    kf.F[0, 4] = kf.F[1, 5] = kf.F[2, 6] = 1.0
    kf.H = np.eye(4, 7)
    kf.R = np.diag([1.0, 1.0, 10.0, 10.0])
    kf.P = np.diag([10.0, 10.0, 10.0, 10.0, 1e4, 1e4, 1e4])
    kf.Q = np.diag([1.0, 1.0, 1.0, 1.0, 1e-2, 1e-2, 1e-4])
    kf.x = np.r_[box_to_z(box), 0.0, 0.0, 0.0]
    return kf


class _Track:
    """One target's filter and its bookkeeping (hits, misses, id)."""

    def __init__(self, box, track_id: int):
        self.kf = box_filter(box)
        self.id = track_id
        self.hit_streak = 0            # consecutive detected frames, the starting one not counted
        self.time_since_update = 0     # frames since the last detection

    def predict(self) -> np.ndarray:
        # an area shrinking through zero would give a box of no size: stop its shrinking
        if self.kf.x[2] + self.kf.x[6] <= 0:
            self.kf.x[6] = 0.0
        self.kf.predict()
        if self.time_since_update > 0:
            self.hit_streak = 0
        self.time_since_update += 1
        return z_to_box(self.kf.x)

    def update(self, box) -> None:
        self.time_since_update = 0
        self.hit_streak += 1
        self.kf.update(box_to_z(box))


def associate(detections, predicted, iou_threshold: float = 0.3, *, gate_first: bool = False):
    """Assign detections to tracks' predicted boxes by the Hungarian method on IoU, gated.

    SORT's order (``gate_first=False``, as Bewley et al. 2016 describe it): the one-to-one
    matching with the largest total IoU over all pairs, then every matched pair with IoU
    below ``iou_threshold`` is rejected. (SORT's current reference code keeps the pairs above
    the threshold without solving when no detection and no track has more than one of them,
    which is what ``gate_first=True`` gives there; this function always solves.) The book's variant (``gate_first=True``):
    among the matchings whose pairs all have IoU ≥ ``iou_threshold``, one with the most pairs
    and, among those, the largest total IoU. They differ only when SORT's optimum uses a pair
    below the threshold (the several-targets chapter works an example).

    Parameters
    ----------
    detections : (n, 4) boxes (x, y, w, h)
    predicted : (m, 4) boxes (x, y, w, h)
    iou_threshold : float
    gate_first : bool

    Returns
    -------
    matches : (k, 2) int array of (detection, track) index pairs, sorted by detection
    unmatched_detections, unmatched_tracks : int arrays of indices

    >>> dets = [(0, 0, 10, 10), (100, 0, 10, 10)]
    >>> associate(dets, [(101, 0, 10, 10), (300, 0, 10, 10)])[0].tolist()
    [[1, 0]]
    """
    iou = iou_matrix(detections, predicted)
    n, m = iou.shape
    pairs = _matched(iou, iou_threshold, gate_first) if n and m else []
    matches = np.array(pairs, dtype=int).reshape(-1, 2)
    return (matches, np.setdiff1d(np.arange(n), matches[:, 0]),
            np.setdiff1d(np.arange(m), matches[:, 1]))


def _matched(iou, iou_threshold, gate_first) -> list:
    """The (row, column) pairs of ``associate`` on an IoU matrix."""
    if gate_first:
        return assign(1.0 - iou, allowed=iou >= iou_threshold)
    return [(r, c) for r, c in assign(1.0 - iou) if iou[r, c] >= iou_threshold]


def _check_detections(detections) -> np.ndarray:
    d = np.asarray(detections, dtype=float)
    if d.size == 0:
        return np.zeros((0, 4))
    if d.ndim != 2 or d.shape[1] not in (4, 5):
        raise ValueError(f"detections must be an (n, 4) array of boxes (x, y, w, h) or (n, 5) "
                         f"with a score column, got shape {d.shape}.")
    if not np.all(np.isfinite(d)) or np.any(d[:, 2:4] <= 0):
        raise ValueError("detections must be finite boxes with positive width and height; "
                         "drop the empty or non-finite rows before calling update.")
    return d[:, :4]


class Sort:
    """SORT: a constant-velocity Kalman filter per target, assignment by IoU each frame.

    Parameters
    ----------
    max_age : int
        A track is deleted once it has gone more than ``max_age`` frames without a detection.
    min_hits : int
        A track is reported only in frames where it was detected and had been detected in its
        previous ``min_hits`` frames too (detections matched to it; its first detection, the
        one that started it, not counted).
    iou_threshold : float
        The least IoU between a detection and a track's predicted box for them to be paired.
    gate_first : bool
        False (SORT): solve the assignment on all pairs, then reject pairs below
        ``iou_threshold``. True (the book's variant): forbid those pairs before solving, so
        one that cannot be kept never pushes aside two that can (see :func:`associate`).

    The defaults (1, 3, 0.3) are SORT's reference code defaults. Two differences from that code,
    both for the book's use: ids count 1, 2, … per tracker (not across all trackers of a
    process), so the same detections always give the same ids; and tracks are not reported
    before they have ``min_hits`` hits (the reference code also reports, during the first
    ``min_hits`` frames of the sequence, every track matched or started in that frame).

    Examples
    --------
    >>> import numpy as np
    >>> sort = Sort(min_hits=1)
    >>> for x in (0, 5, 10):
    ...     out = sort.update(np.array([[x, 0, 20, 40], [x + 100, 50, 20, 40]]))
    >>> out[:, 4].tolist()
    [1.0, 2.0]
    """

    def __init__(self, max_age: int = 1, min_hits: int = 3, iou_threshold: float = 0.3, *,
                 gate_first: bool = False):
        for name, value in (("max_age", max_age), ("min_hits", min_hits)):
            if int(value) != value or value < 0:
                raise ValueError(f"{name} must be a whole number >= 0, got {value!r}.")
        if not 0.0 <= float(iou_threshold) <= 1.0:
            raise ValueError(f"iou_threshold must be in [0, 1], got {iou_threshold!r}.")
        self.max_age = int(max_age)
        self.min_hits = int(min_hits)
        self.iou_threshold = float(iou_threshold)
        self.gate_first = bool(gate_first)
        self.reset()

    def reset(self) -> None:
        """Forget every track; the next track gets id 1 again."""
        self._tracks: list[_Track] = []
        self._next_id = 1
        self.frame_count = 0

    def update(self, detections) -> np.ndarray:
        """Take one frame's detections; return the reported tracks.

        Parameters
        ----------
        detections : (n, 4) array of boxes (x, y, w, h), or (n, 5) with a score column (the
            score is accepted and not used: SORT pairs by overlap only). n may be 0 — call
            ``update`` on every frame, with an empty array when nothing was detected.

        Returns
        -------
        (m, 5) float array of rows (x, y, w, h, id), the filtered box of each reported track,
        sorted by id.
        """
        dets = _check_detections(detections)
        self.frame_count += 1
        predicted = np.array([t.predict() for t in self._tracks]).reshape(-1, 4)
        alive = np.all(np.isfinite(predicted), axis=1)
        self._tracks = [t for t, ok in zip(self._tracks, alive) if ok]
        matches, new, _ = associate(dets, predicted[alive], self.iou_threshold,
                                    gate_first=self.gate_first)
        for d, t in matches:
            self._tracks[t].update(dets[d])
        for d in new:
            self._tracks.append(_Track(dets[d], self._next_id))
            self._next_id += 1
        out = [np.r_[z_to_box(t.kf.x), t.id] for t in self._tracks
               if t.time_since_update == 0 and t.hit_streak >= self.min_hits]
        self._tracks = [t for t in self._tracks if t.time_since_update <= self.max_age]
        return np.array(sorted(out, key=lambda row: row[4])).reshape(-1, 5)

    @property
    def n_tracks(self) -> int:
        """Tracks kept, tentative and coasting ones included."""
        return len(self._tracks)
