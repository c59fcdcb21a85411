"""``kalman-covariance-manoeuvre``: Lee (2015)'s ``kalman-covariance`` with the book's
manoeuvre re-search (not in the paper), kept as a named variant because the region-covariance
chapter ("The bounce") introduces it and the IMM section of the Kalman-filter design chapter
compares against it."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..params import NOT_PRINTED, param
from .base import redetecting
from .covariance import KalmanCovarianceParams, KalmanCovarianceTracker
from .failure import calibrated_params, load_calibration
from .registry import register


@dataclasses.dataclass(frozen=True)
class KalmanCovarianceManoeuvreParams(KalmanCovarianceParams):
    """Tunables of ``kalman-covariance-manoeuvre``: those of ``kalman-covariance`` plus the
    book's manoeuvre re-search."""

    manoeuvre_gate: float = param(
        3.0, 0.0, 10.0, 0.5, doc="κ: a best d_F above κ·(median d_F of the last accepted "
        "frames) signals a manoeuvre; 0 = never",
        paper=NOT_PRINTED, paper_value=0.0,   # not in the paper; 0 switches it off
        why="the book's addition: a ball's bounce leaves the constant-velocity window while d_F "
            "stays below `threshold` (the covariance case study, the bounce)")
    manoeuvre_sigma: float = param(
        8.0, 0.0, 30.0, 1.0, doc="σ_v (px/frame) of the velocity change allowed on a "
        "manoeuvre: the second, larger window",
        paper=NOT_PRINTED,   # not in the paper; unused when manoeuvre_gate = 0
        why="the book's addition: 8 px/frame, about a bouncing ball's speed change")


@register
class KalmanCovarianceManoeuvre(KalmanCovarianceTracker):
    """``kalman-covariance-manoeuvre``: ``kalman-covariance`` with the book's manoeuvre
    re-search (not in Lee 2015; the IMM section of the Kalman-filter design chapter compares
    against it).

    A constant-velocity model with Q = I cannot follow a bounce (the velocity reverses in one
    frame), and the best window inside the small Kalman window is then some background whose
    Förstner distance d_F (``rho`` in the code, the letter of Lee 2015's eq. 5
    [quote: lee2015.distance_eq5]) can still be below
    ``threshold``. So when the best d_F exceeds ``manoeuvre_gate`` times the median d_F of the
    last accepted frames, the prediction is redone from the previous
    posterior with σ_v² = ``manoeuvre_sigma``² added to the velocity variance (an impulsive
    process noise, the "adjustable process noise" of manoeuvring-target tracking). Its S and
    window are larger, and if its best window is better the update uses that P⁻, whose
    larger velocity gain lets the velocity estimate jump with the target
    (``manoeuvre_gate=0`` gives ``kalman-covariance``).

    Everything else, the confidence -d_F (of the manoeuvre window's best window when that
    was better) and the failure layer included, is ``kalman-covariance``'s, and so are the
    failure layer's thresholds (the same confidence) until this name is calibrated itself.
    """

    name = "kalman-covariance-manoeuvre"
    Params = KalmanCovarianceManoeuvreParams

    def __init__(self, *args, seed=0, failure=True, **params):
        if failure is True:
            own = self.name.removesuffix("-redetect")
            failure = calibrated_params(own if own in load_calibration()
                                        else KalmanCovarianceTracker.name)
        super().__init__(*args, seed=seed, failure=failure, **params)

    def _manoeuvre_search(self, frame, posterior, found):
        kf, p = self._kf, self.params
        rho = found[1]
        if not (p.manoeuvre_gate > 0 and p.manoeuvre_sigma > 0
                and rho > p.manoeuvre_gate * self.typical_rho()):
            return found
        # Much worse than usual: the target probably changed velocity (a bounce, a turn).
        # Re-predict as if the velocity had been uncertain by σ_v — P⁺'s velocity block
        # grows by σ_v² — so S, the window, and on update the velocity gain grow with it.
        first = (kf.x.copy(), kf.P.copy())
        kf.x, kf.P = posterior[0].copy(), posterior[1].copy()
        kf.P[2:, 2:] += p.manoeuvre_sigma ** 2 * np.eye(2)
        centre2, radius2 = self._predict_window(frame.shape)
        second = self._search(frame, centre2, radius2) + (centre2, radius2)
        if second[1] < rho:
            self.manoeuvre = True
            return second
        kf.x, kf.P = first
        return found


register(redetecting(KalmanCovarianceManoeuvre))


__all__ = ["KalmanCovarianceManoeuvre", "KalmanCovarianceManoeuvreParams"]
