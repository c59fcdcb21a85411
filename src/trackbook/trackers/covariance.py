"""Lee (2015): region-covariance tracking, with and without a Kalman search window.

``covariance`` (the paper's baseline, Fig. 3 [quote: lee2015.frames184])
    compares the target's covariance (eq. 4) with every candidate window of the target's size
    around the last position (Förstner distance d_F = ρ, eq. 5–6); the smallest ρ wins. When
    even the best ρ is above ``threshold`` the match has not converged and the whole frame is
    searched (the paper describes this whole-frame search for covariance alone, Fig. 3, frame
    160 [quote: lee2015.whole_frame_search]).
``kalman-covariance`` (proposed, Fig. 1)
    predicts the target's centre with a constant-velocity Kalman filter (eq. 7–13), searches
    only inside the predicted search window, takes the best candidate's centre as the
    measurement and updates the filter. When the match does not converge (best ρ above
    ``threshold``) the paper searches again, in our reading *inside the Kalman window*
    [quote: lee2015.research_in_window]: no update, so the next, larger window is searched.
    No size of the window from S is printed: its half-size of ``gate`` σ of the innovation
    covariance S = H P⁻ Hᵀ + R is the book's, as is the value of ``threshold``.
``kalman-covariance-manoeuvre`` (the book's variant, compared with the IMM)
    ``kalman-covariance`` plus a manoeuvre re-search, not in the paper: when the best ρ is
    much worse than usual (``manoeuvre_gate``) the target has probably changed velocity (a
    bounce); the window is searched again as if the velocity were uncertain by
    ``manoeuvre_sigma`` px/frame (case_study_lee2015, "The bounce").

All of them report ``ok`` from the failure-detection layer
(:class:`~trackbook.trackers.failure.FailureDetector` on the confidence -d_F), and also lost
when the paper's own test fails (best ρ above ``threshold``)
[quote: lee2015.research_in_window]; a lost frame keeps the last box
and teaches nothing. The ``-redetect`` names add the re-detection layer (the whole frame
scored with -d_F while lost).

Both count exactly the candidate windows they evaluate and report per frame (``frame_report``)
``search_rate`` = evaluated / all windows of the target's size in the frame at ``stride`` —
the "averaging search rate" of Table 1 once averaged over the frames.

>>> from trackbook import trackers, clips
>>> clip = clips.load("red-cube")                                              # doctest: +SKIP
>>> t = trackers.create("kalman-covariance")                                   # doctest: +SKIP
>>> t.init(clip.frames[0], clip.groundtruth[0]); ok, box = t.update(clip.frames[1])  # doctest: +SKIP
>>> t.search_window, t.kalman.x, t.frame_report()                              # doctest: +SKIP
"""

from __future__ import annotations

import collections
import dataclasses

import numpy as np

from ..features.covariance import (FEATURE_SETS, IntegralCovariance, Workspace,
                                   feature_dimension, feature_planes, forstner_distance)
from ..features.frame_difference import find_moving_region
from ..filters.kalman import constant_velocity
from ..params import NOT_PRINTED, param
from .base import Tracker, redetecting
from .registry import register

#: How many accepted frames the relative gate's median ρ looks back (one second at 25 fps).
RHO_HISTORY = 25


@dataclasses.dataclass(frozen=True)
class _CovarianceModelParams:
    """The tunables the two covariance trackers share: the model, its candidates, the test."""

    # Section numbers are those of Lee (2015), J. KIICE 19(6), pp. 1477-1484.
    features: str = param(
        "xyI|Ix||Iy|", doc="feature vector f_k: eq. 2 with |Ix|, |Iy| (default), eq. 2 as "
        "printed ('xyIIxIy'), eq. 3 ('rI|Ix||Iy|') or colour ('xyRGB|Ix||Iy|')",
        choices=FEATURE_SETS,
        reading="lee2015.features_eq2",
        paper="xyIIxIy",   # sec. 2.1, eq. 2: f_k = [x y I(x,y) I_x(x,y) ...], signed gradients
        why="|Ix|, |Iy| as in Tuzel et al. (2006): a dark-on-light and a light-on-dark edge "
            "give the same feature (the region-covariance chapter)")
    stride: int = param(
        1, 1, 8, 1, doc="pixels between neighbouring candidate windows",
        paper=NOT_PRINTED,   # sec. 2.1 and 3 give no candidate spacing
        why="every pixel (1), the finest grid; the search rate of Table 1 is counted at it")
    search_radius: int = param(
        8, 1, 64, 1, doc="candidates' centres within ±radius px of the last position",
        paper=NOT_PRINTED,   # sec. 2.3 names a "search range" with no size
        why="the book's choice: ±8 px, 17 x 17 = 289 candidates at stride 1 (the "
            "covariance case study compares the search rates)")
    threshold: float = param(
        3.0, 0.1, 20.0, 0.1, doc="d_F (eq. 5) above which the match has not converged (sec. "
        "2.3): the frame is lost (covariance then searches the whole frame, `fallback`)",
        paper=NOT_PRINTED,   # sec. 2.3 says only "if it does not converge"
        why="on RedCube the tracked cube scores d_F ≈ 0.5 and background windows above 4; 3 lies "
            "between (the covariance case study measures it)")
    eps: float = param(
        1e-6, 0.0, 1.0, None, doc="ε of the regularised C + εI in eq. 6",
        paper=NOT_PRINTED,   # eq. 5-6 assume positive-definite matrices
        why="a flat window has a singular C (zero gradient variance); εI keeps eq. 6 solvable")
    model_update: float = param(
        0.0, 0.0, 1.0, 0.05, doc="α of C_model ← (1−α)C_model + αC_best (0: fixed model)",
        paper=NOT_PRINTED, paper_value=0.0,   # sec. 2.3: the target's covariance is computed once
        why="no model update is printed; 0 keeps the model fixed")


@dataclasses.dataclass(frozen=True)
class CovarianceParams(_CovarianceModelParams):
    """Tunables of ``covariance``: the shared ones and its whole-frame search (Fig. 3)."""

    fallback: str = param(
        "frame", doc="where to search again when the best d_F is above `threshold`: the whole "
        "frame ('frame', as printed) or nowhere else ('window')",
        choices=("frame", "window"),
        printed="lee2015.whole_frame_search",
        paper="frame")     # sec. 3, Fig. 3, frame 160: covariance alone searches the whole frame
    global_stride: int = param(
        4, 1, 16, 1, doc="stride of the coarse whole-frame search (refined at `stride` "
        "around its best window)",
        paper=NOT_PRINTED, paper_value=1,   # sec. 3: every window of the frame is a candidate
        why="coarse-to-fine (4 px, then refined at `stride` around the best window) evaluates "
            "about 16 times fewer windows than the exhaustive search")


@dataclasses.dataclass(frozen=True)
class KalmanCovarianceParams(_CovarianceModelParams):
    """Tunables of ``kalman-covariance``: the shared ones and the Kalman filter's."""

    q: float = param(1.0, 0.01, 100.0, 0.1, doc="Q = q·I (eq. 10)",
                     printed="lee2015.q_identity", paper=1.0)   # sec. 2.2: Q = I_4 printed
    r: float = param(1.0, 0.01, 100.0, 0.1, doc="R = r·I (eq. 11)",
                     printed="lee2015.r_identity", paper=1.0)   # sec. 2.2: R = I_2 printed
    p0: float = param(
        1.0, 0.01, 1000.0, 1.0, doc="P₀ = p0·I, the initial state covariance",
        paper=NOT_PRINTED,   # sec. 2.2 prints F, H, Q, R but no P_0
        why="P₀ = I, the same scale as Q and R; the window settles within a few frames")
    gate: float = param(
        3.0, 0.5, 10.0, 0.5, doc="search-window half-size in σ of S = HP⁻Hᵀ + R",
        paper=NOT_PRINTED,   # Fig. 2 draws the window; no size from S is printed
        why="the book sizes the window from S: 3σ holds the measurement 99 % of the time if "
            "the model is right")
    min_radius: int = param(
        4, 0, 64, 1, doc="smallest search-window half-size in px",
        paper=NOT_PRINTED,   # no window size printed
        why="a floor under the gate (with Q = R = I, 3σ of S settles near ±7 px); 4 px keeps a "
            "search area if q, r are set small")
    motion_threshold: float = param(
        10.0, 1.0, 100.0, 1.0, doc="grey-level change that counts as motion in "
        "`init_from_motion`'s frame difference",
        paper=NOT_PRINTED,   # sec. 2.3 / Fig. 2: frame differencing, no threshold printed
        why="at 25 grey levels RedCube's 1.6 px move between frames 0 and 1 leaves only its "
            "bottom edge (a 19x3 strip, 0 % tracking); 10 sees the whole cube")
    init_size: int = param(
        24, 4, 128, 1, doc="side (px) of the model window centred on the moving region "
        "when initialising without a box (`init_from_motion`)",
        reading="lee2015.window24", paper=24)   # sec. 3, Table 1: "tracked with a 24x24 area"


def n_windows(frame_shape, size, stride: int) -> int:
    """All windows of ``size = (w, h)`` at ``stride`` in a frame: the search-rate denominator."""
    H, W = frame_shape[:2]
    w, h = size
    return ((W - w) // stride + 1) * ((H - h) // stride + 1)


def grid_boxes(frame_shape, size, center, radius, stride: int) -> np.ndarray:
    """Integer boxes of ``size`` whose centres lie within ±radius of ``center`` at ``stride``.

    The grid is anchored at the window centred on ``center`` (clamped into the frame) and
    keeps only windows wholly inside the frame; every box is distinct, so ``len`` is the exact
    number of candidates.
    """
    H, W = frame_shape[:2]
    w, h = size
    rx, ry = radius
    x0 = int(np.clip(round(center[0] - w / 2.0), 0, W - w))
    y0 = int(np.clip(round(center[1] - h / 2.0), 0, H - h))
    kx = int(rx // stride)
    ky = int(ry // stride)
    xs = x0 + stride * np.arange(-kx, kx + 1)
    ys = y0 + stride * np.arange(-ky, ky + 1)
    xs = xs[(xs >= 0) & (xs <= W - w)]
    ys = ys[(ys >= 0) & (ys <= H - h)]
    X, Y = np.meshgrid(xs, ys)
    n = X.size
    return np.column_stack([X.ravel(), Y.ravel(), np.full(n, w), np.full(n, h)]).astype(np.int64)


class _CovarianceSearch(Tracker):
    """The part common to both trackers of Lee (2015): the model, candidate scoring, whole-frame
    search.

    Attributes (read-only, for drawing)
    -----------------------------------
    model : d x d covariance of the target (eq. 4)
    candidates : (n, 4) boxes evaluated on the last frame
    distances : (n,) their ρ (eq. 5)
    search_window : (x, y, w, h) the area the last local search covered
    best_rho : ρ of the chosen window on the last frame

    Lost rule
    ---------
    ``ok`` comes from the failure-detection layer on the confidence below; the paper's own
    test, a best ρ above ``threshold`` (the match "does not converge", sec. 2.3), also makes
    the frame lost [quote: lee2015.research_in_window]. A lost frame keeps the last box and does not update the model. Candidate
    windows stay inside the frame, so a target leaving across the border raises the best ρ
    as its visible part shrinks.

    Confidence
    ----------
    ``state().confidence`` is the negative Förstner distance of the last frame's best window,
    -d_F = -sqrt(sum_k ln^2 λ_k) (eq. 5-6, λ_k the generalised eigenvalues of
    λ (C_model + εI) x = (C_best + εI) x), i.e. ``-best_rho``: at most 0, larger is surer. On
    a frame that searched the whole frame it is that of the best window found; a distance
    beyond float64 is given as the most negative float.
    """

    Params = CovarianceParams

    # -- scoring -------------------------------------------------------------------------
    def _covariances(self, frame, boxes):
        """C_R of integer ``boxes`` from integral images of the smallest crop holding them."""
        H, W = frame.shape[:2]
        x0, y0 = boxes[:, 0].min(), boxes[:, 1].min()
        x1, y1 = (boxes[:, 0] + boxes[:, 2]).max(), (boxes[:, 1] + boxes[:, 3]).max()
        # One pixel of context so the [-1 0 1] gradients at the crop's edge are the frame's.
        cx0, cy0 = max(x0 - 1, 0), max(y0 - 1, 0)
        cx1, cy1 = min(x1 + 1, W), min(y1 + 1, H)
        if not hasattr(self, "_workspace"):
            self._workspace = Workspace()
        ws, features = self._workspace, self.params.features
        radial = features == "rI|Ix||Iy|"
        d = feature_dimension(features) - (1 if radial else 0)
        F = feature_planes(frame[cy0:cy1, cx0:cx1], features,
                           out=ws.get("features", (d, cy1 - cy0, cx1 - cx0)))
        ic = IntegralCovariance(F, origin=(cx0, cy0), radial=radial, workspace=ws,
                                channels_first=True)
        return ic.covariances(boxes)

    def _score(self, frame, boxes):
        Cs = self._covariances(frame, boxes)
        rho = forstner_distance(self._model, Cs, self.params.eps)
        self._n_evaluated += len(boxes)
        return rho

    def _search(self, frame, center, radius):
        """Best window around ``center``; returns (box, ρ, boxes, ρs)."""
        boxes = grid_boxes(frame.shape, self._size, center, radius, self.params.stride)
        rho = self._score(frame, boxes)
        i = int(np.argmin(rho))
        return boxes[i].astype(float), float(rho[i]), boxes, rho

    #: The coarse whole-frame search scores at most about this many windows (its stride grows
    #: with the frame beyond ``global_stride``), so a lost frame's cost is bounded.
    max_global_windows = 600

    def _whole_frame_search(self, frame):
        """Coarse search over the whole frame at ``global_stride`` (coarser on a large frame:
        at most about ``max_global_windows`` windows), refined in steps of a quarter of the
        stride down to ``stride`` around the best window."""
        H, W = frame.shape[:2]
        w, h = self._size
        n1 = (W - w + 1) * (H - h + 1)
        g = max(self.params.global_stride, int(np.ceil(np.sqrt(n1 / self.max_global_windows))))
        centre = (W / 2.0, H / 2.0)
        box, rho, _, _ = self._search_with_stride(frame, centre, (W, H), g)
        while g > self.params.stride:
            g2 = max(self.params.stride, g // 4)
            c = (box[0] + w / 2.0, box[1] + h / 2.0)
            boxes = grid_boxes(frame.shape, self._size, c, (g - 1, g - 1), g2)
            rhos = self._score(frame, boxes)
            i = int(np.argmin(rhos))
            if rhos[i] < rho:
                box, rho = boxes[i].astype(float), float(rhos[i])
            g = g2
        return box, rho

    def _search_with_stride(self, frame, center, radius, stride):
        H, W = frame.shape[:2]
        w, h = self._size
        xs = np.arange(0, W - w + 1, stride)
        ys = np.arange(0, H - h + 1, stride)
        X, Y = np.meshgrid(xs, ys)
        boxes = np.column_stack([X.ravel(), Y.ravel(), np.full(X.size, w), np.full(X.size, h)])
        rho = self._score(frame, boxes)
        i = int(np.argmin(rho))
        return boxes[i].astype(float), float(rho[i]), boxes, rho

    # -- shared bookkeeping ----------------------------------------------------------------
    def _init_model(self, frame, box):
        H, W = frame.shape[:2]
        w = int(np.clip(round(box[2]), 2, W))
        h = int(np.clip(round(box[3]), 2, H))
        x = int(np.clip(round(box[0]), 0, W - w))
        y = int(np.clip(round(box[1]), 0, H - h))
        self._size = (w, h)
        self._model = self._covariances(frame, np.array([[x, y, w, h]]))[0]
        self._n_evaluated = 0
        self._n_all = n_windows(frame.shape, self._size, self.params.stride)
        self.candidates = np.zeros((0, 4))
        self.distances = np.zeros(0)
        self.search_window = (float(x), float(y), float(w), float(h))
        self.best_rho = 0.0
        self._recent_rho = collections.deque(maxlen=RHO_HISTORY)
        return np.array([x, y, w, h], dtype=float)

    def typical_rho(self) -> float:
        """Median best ρ of the last accepted frames (NaN before the first one)."""
        return float(np.median(self._recent_rho)) if self._recent_rho else float("nan")

    def _accept(self, frame, box, rho):
        self._recent_rho.append(rho)
        a = self.params.model_update
        if a > 0:
            C = self._covariances(frame, np.asarray(box, dtype=np.int64)[None])[0]
            self._model = (1 - a) * self._model + a * C

    def _window_of(self, center, radius):
        w, h = self._size
        return (center[0] - w / 2.0 - radius[0], center[1] - h / 2.0 - radius[1],
                w + 2.0 * radius[0], h + 2.0 * radius[1])

    @staticmethod
    def _confidence(rho) -> float:
        """-d_F (see "Confidence"), finite: a distance beyond float64 is the most negative float."""
        return -min(float(rho), float(np.finfo(float).max))

    def _score_boxes(self, frame, boxes):
        """-d_F of every box (moved inside the frame, whole pixels) against the model; for the
        re-detection layer. Counts nothing and changes nothing."""
        H, W = frame.shape[:2]
        w, h = self._size
        b = np.asarray(boxes, dtype=float)
        x = np.clip(np.round(b[:, 0] + b[:, 2] / 2.0 - w / 2.0), 0, W - w)
        y = np.clip(np.round(b[:, 1] + b[:, 3] / 2.0 - h / 2.0), 0, H - h)
        ib = np.column_stack([x, y, np.full(len(b), w), np.full(len(b), h)]).astype(np.int64)
        rho = forstner_distance(self._model, self._covariances(frame, ib), self.params.eps)
        return -np.minimum(rho, np.finfo(float).max)

    def frame_report(self) -> dict:
        """Per-frame numbers for Table 1: search rate, candidate count, best ρ."""
        return {"search_rate": self._n_evaluated / self._n_all,
                "candidates": self._n_evaluated, "rho": self.best_rho}

    @property
    def model(self):
        return self._model

    def _drawn(self) -> dict:
        """The last local search's window and its candidate boxes."""
        return {**super()._drawn(), "search_window": self.search_window,
                "candidates": np.asarray(self.candidates, dtype=float)[:, :4]}


@register
class CovarianceTracker(_CovarianceSearch):
    """Baseline of Lee 2015 (Fig. 3): covariance search around the last position.

    Candidates are target-sized windows whose centres lie within ±``search_radius`` px of
    the last box's centre (every ``stride`` px). If the best ρ exceeds ``threshold`` the
    whole frame is searched, as the paper prints (``fallback="frame"``)
    [quote: lee2015.whole_frame_search]; if that fails too, the frame is lost.

    Confidence: -d_F of the last frame's best window (the negative Förstner distance, see
    "Confidence" of the shared search below). ``ok`` comes from the failure-detection layer
    on it (and the paper's ρ > ``threshold``); ``covariance-redetect`` adds the re-detection
    layer.
    """

    name = "covariance"
    Params = CovarianceParams

    def _init(self, frame, box):
        b = self._init_model(frame, box)
        self._center = (b[0] + b[2] / 2.0, b[1] + b[3] / 2.0)

    def _locate(self, frame):
        """The local search and, when it does not converge, the whole-frame search (Fig. 3).
        Returns ``(box, -d_F, d_F <= threshold)``; the model and the search centre stay."""
        self._n_evaluated = 0
        r = self.params.search_radius
        box, rho, boxes, rhos = self._search(frame, self._center, (r, r))
        self.candidates, self.distances = boxes, rhos
        self.search_window = self._window_of(self._center, (r, r))
        if rho > self.params.threshold and self.params.fallback == "frame":
            gbox, grho = self._whole_frame_search(frame)
            if grho < rho:
                box, rho = gbox, grho
        self.best_rho = rho
        return box, self._confidence(rho), rho <= self.params.threshold

    def _learn(self, frame, box):
        self._accept(frame, box, self.best_rho)
        self._center = (box[0] + box[2] / 2.0, box[1] + box[3] / 2.0)

    def _relocate(self, frame, box):
        self._center = (box[0] + box[2] / 2.0, box[1] + box[3] / 2.0)


register(redetecting(CovarianceTracker))


@register
class KalmanCovarianceTracker(_CovarianceSearch):
    """Proposed tracker of Lee 2015 (Fig. 1): covariance search inside a Kalman window.

    Per frame: predict (eq. 9–10); the search window is the predicted centre ±
    max(``gate``·σ, ``min_radius``) with σ² the diagonal of S = H P⁻ Hᵀ + R; the best
    candidate's centre is the measurement y_k (eq. 8) and updates the filter (eq. 11–13).
    Best ρ above ``threshold`` (the match does not converge): the frame is lost, no update,
    so P keeps growing and the next Kalman window, searched again, is larger (the paper's
    re-search inside the Kalman window). ``gate`` and the value of ``threshold`` are the
    book's choices. The prediction is the filter's own state and moves on every frame, lost
    or not (as a particle filter's particles do); only the update, the model and the
    velocity it learns wait for a frame judged on target.

    ``ok`` comes from the failure-detection layer on the confidence below (and the paper's
    ρ > ``threshold``); ``kalman-covariance-redetect`` adds the re-detection layer (the whole
    frame scored with -d_F while lost, the filter restarted at rest at the best window). The
    book's manoeuvre re-search is the variant ``kalman-covariance-manoeuvre``
    (:class:`KalmanCovarianceManoeuvre`).

    Attributes (read-only, for drawing)
    -----------------------------------
    kalman : the :class:`~trackbook.filters.kalman.KalmanFilter` (``kalman.x``, ``kalman.P``)
    prediction : (x⁻, P⁻) of the last frame, before the update
    manoeuvre : True when the last frame's measurement came from the manoeuvre window (only
        ``kalman-covariance-manoeuvre``; always False here)
    ellipse : (cx, cy, hx, hy, angle°) the predicted position's ``gate``-σ uncertainty ellipse
    search_window, candidates, distances, best_rho, model : as for ``covariance``

    Confidence: as ``covariance``'s, -d_F of the last frame's best window.
    """

    name = "kalman-covariance"
    Params = KalmanCovarianceParams

    def _init(self, frame, box):
        b = self._init_model(frame, box)
        p = self.params
        self._kf = constant_velocity((b[0] + b[2] / 2.0, b[1] + b[3] / 2.0), q=p.q, r=p.r,
                                     p0=p.p0)
        self.prediction = (self._kf.x.copy(), self._kf.P.copy())
        self.manoeuvre = False

    def init_from_motion(self, frame0, frame1, **kwargs):
        """Initialise with no box: the moving region between two frames (Fig. 1 of Lee 2015).

        Section 2.3 of Lee (2015): the moving region's *centre* becomes the centre of the first
        Kalman search window. Its *box* is not the target: a difference image covers where
        the object was and where it is, and a flat object changes only at its leading and
        trailing edges (on red-cube, frames 0→1 give a 19×3 strip). So the model window is
        ``init_size`` × ``init_size`` px (the paper's 24×24, Table 1) centred on the region's
        centre, measured on ``frame1``; the Kalman filter starts there with zero velocity.

        ``kwargs`` go to :func:`~trackbook.features.frame_difference.find_moving_region` (its
        ``threshold`` defaults to ``motion_threshold``). Returns the
        model box ``(x, y, w, h)`` (the tracker is then initialised on ``frame1``); raises
        ``ValueError`` if nothing moved.
        """
        kwargs.setdefault("threshold", self.params.motion_threshold)
        region = find_moving_region(frame0, frame1, **kwargs)
        if region is None:
            raise ValueError("no moving region between the two frames; lower `threshold` or "
                             "pass a box to init(frame, bbox).")
        self.motion_region = region
        s = float(self.params.init_size)
        cx, cy = region[0] + region[2] / 2.0, region[1] + region[3] / 2.0
        box = (cx - s / 2.0, cy - s / 2.0, s, s)
        self.init(frame1, box)
        # The model window is whole pixels; the filter starts at the region's exact centre.
        self._kf.x[:2] = (cx, cy)
        self.prediction = (self._kf.x.copy(), self._kf.P.copy())
        return tuple(float(v) for v in self.bbox)

    @property
    def kalman(self):
        return self._kf

    def _drawn(self) -> dict:
        """As ``covariance``'s, plus the Kalman gate ``ellipse`` (cx, cy, hx, hy, angle)."""
        return {**super()._drawn(), "ellipse": self.ellipse}

    @property
    def ellipse(self):
        """(cx, cy, hx, hy, angle°): the ``gate``-σ ellipse of S = HP⁻Hᵀ + R at the prediction."""
        x, P = self.prediction
        S = self._kf.H @ P @ self._kf.H.T + self._kf.R
        ev, V = np.linalg.eigh(S)
        angle = float(np.degrees(np.arctan2(V[1, 1], V[0, 1])))
        g = self.params.gate
        return (float(x[0]), float(x[1]), g * float(np.sqrt(ev[1])), g * float(np.sqrt(ev[0])),
                angle)

    def _predict_window(self, frame_shape):
        """Predict (eq. 9–10) and return the search window's centre and half-size from S."""
        H, W = frame_shape[:2]
        kf, p = self._kf, self.params
        kf.predict()
        # A prediction that left the frame cannot be searched; stop it at the border.
        cx, cy = float(np.clip(kf.x[0], 0, W - 1)), float(np.clip(kf.x[1], 0, H - 1))
        if (cx, cy) != (kf.x[0], kf.x[1]):
            kf.x[:2] = (cx, cy)
            kf.x[2:] = 0.0
        sigma = np.sqrt(np.diag(kf.innovation_covariance()))
        radius = (max(p.gate * sigma[0], p.min_radius), max(p.gate * sigma[1], p.min_radius))
        return (cx, cy), radius

    def _manoeuvre_search(self, frame, posterior, found):
        """Hook of :class:`KalmanCovarianceManoeuvre`; ``kalman-covariance`` has none."""
        return found

    def _locate(self, frame):
        """Predict, search the Kalman window; returns ``(box, -d_F, d_F <= threshold)``.
        The filter is not updated here (see the class docstring)."""
        self._n_evaluated = 0
        kf = self._kf
        posterior = (kf.x.copy(), kf.P.copy())
        centre, radius = self._predict_window(frame.shape)
        found = self._search(frame, centre, radius) + (centre, radius)
        self.manoeuvre = False
        box, rho, boxes, rhos, centre, radius = self._manoeuvre_search(frame, posterior, found)
        self.prediction = (kf.x.copy(), kf.P.copy())
        self.candidates, self.distances = boxes, rhos
        self.search_window = self._window_of(centre, radius)
        self.best_rho = rho
        return box, self._confidence(rho), rho <= self.params.threshold

    def _learn(self, frame, box):
        """Update the filter with the window's centre (eq. 11-13) and the model."""
        w, h = self._size
        self._accept(frame, box, self.best_rho)
        self._kf.update((box[0] + w / 2.0, box[1] + h / 2.0))

    def _follow(self, frame, box):
        """On a lost frame: nothing. The filter already predicted in ``_locate``, so P grows
        and the next Kalman window, searched again, is larger (the paper's re-search).

        Parameters
        ----------
        frame : (H, W, 3) uint8 array
            The lost frame.
        box : (4,) float array
            The box ``_locate`` found on it.

        Returns
        -------
        None
        """

    def _relocate(self, frame, box):
        """Restart the filter at rest at ``box``'s centre, P = P₀ (for the re-detection layer)."""
        b = np.asarray(box, dtype=float)
        p = self.params
        self._kf = constant_velocity((b[0] + b[2] / 2.0, b[1] + b[3] / 2.0), q=p.q, r=p.r,
                                     p0=p.p0)


register(redetecting(KalmanCovarianceTracker))


__all__ = ["CovarianceTracker", "KalmanCovarianceTracker", "CovarianceParams",
           "KalmanCovarianceParams", "n_windows", "grid_boxes", "find_moving_region"]
