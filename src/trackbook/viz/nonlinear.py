"""Figures of the non-linear filters section of ``06_kalman`` (and of association in ``08``).

>>> import matplotlib; matplotlib.use("Agg")
>>> import numpy as np, matplotlib.pyplot as plt
>>> from trackbook.viz.nonlinear import cov_ellipse
>>> ax = cov_ellipse(plt.figure().gca(), np.zeros(2), np.diag([4.0, 1.0]))
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ..style import OKABE_ITO
from .core import GT_COLOR, draw_ellipse

__all__ = ["cov_ellipse", "plot_estimates", "plot_polar_belief", "plot_identity_strip"]

#: One colour per filter, in the order of ``trackbook.filters.nonlinear.compare``.
FILTER_COLORS = (OKABE_ITO["black"], OKABE_ITO["vermillion"], OKABE_ITO["blue"],
                 OKABE_ITO["reddish purple"])


def cov_ellipse(ax, mean, cov, n_sigma: float = 2.0, color=OKABE_ITO["blue"], lw=1.2, ls="-",
                label=None):
    """The n_sigma ellipse of a 2-D Gaussian N(mean, cov) on ``ax``."""
    lam, V = np.linalg.eigh(np.asarray(cov, dtype=float))
    lam = np.clip(lam, 0.0, None)
    angle = np.degrees(np.arctan2(V[1, 1], V[0, 1]))
    draw_ellipse(ax, mean[0], mean[1], n_sigma * np.sqrt(lam[1]), n_sigma * np.sqrt(lam[0]),
                 angle, color=color, lw=lw, ls=ls)
    if label:
        ax.plot([], [], color=color, lw=lw, ls=ls, label=label)
    return ax


def plot_polar_belief(samples, linear, unscented, sigmas, sensor=(0.0, 0.0), ax=None,
                      title=None):
    """A range-bearing belief seen in the plane: samples, the linearised and the unscented fit.

    Parameters
    ----------
    samples : (N, 2) points of the true (curved) distribution in the plane
    linear, unscented : ``(mean, cov)`` of the linearised and of the unscented Gaussian
    sigmas : (2n + 1, 2) sigma points mapped into the plane
    """
    ax = ax or plt.figure(figsize=(6, 4)).gca()
    ax.plot(*np.asarray(samples).T, ".", ms=1, color="#BBBBBB", label="samples of the truth")
    mc_mean, mc_cov = np.mean(samples, axis=0), np.cov(np.asarray(samples).T)
    cov_ellipse(ax, mc_mean, mc_cov, color=OKABE_ITO["black"], ls=":", label="their mean, 2σ")
    ax.plot(*mc_mean, "+", color=OKABE_ITO["black"], ms=10)
    for (m, P), col, name in ((linear, OKABE_ITO["vermillion"], "linearised (EKF), 2σ"),
                              (unscented, OKABE_ITO["blue"], "unscented (UKF), 2σ")):
        cov_ellipse(ax, m, P, color=col, label=name)
        ax.plot(*m, "x", color=col, ms=8)
    ax.plot(*np.asarray(sigmas).T, "o", mfc="none", color=OKABE_ITO["blue"], label="sigma points")
    return _finish(ax, sensor, title)


def _finish(ax, sensor, title):
    """The sensor, equal axes, the legend outside the plot (never over a track), the title."""
    ax.plot(*sensor, "^", color=OKABE_ITO["black"], ms=9, label="sensor")
    ax.set_aspect("equal")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), frameon=False, fontsize=8)
    if title:
        ax.set_title(title, fontsize=10)
    return ax


def plot_estimates(truth, estimates: dict, measurements=None, sensor=(0.0, 0.0), ax=None,
                   title=None):
    """A true track, its converted measurements and the position estimates of several filters.

    ``estimates`` maps a filter's name to its (n, ≥2) estimates (or to an object with ``.x``).
    """
    ax = ax or plt.figure(figsize=(8, 4)).gca()
    truth = np.asarray(truth, dtype=float)
    if measurements is not None:
        ax.plot(*np.asarray(measurements, dtype=float)[:, :2].T, ".", ms=3, color="#BBBBBB",
                label="measurements (converted)")
    ax.plot(truth[:, 0], truth[:, 1], "-", lw=2.5, color=GT_COLOR, label="true track")
    for (name, est), col in zip(estimates.items(), FILTER_COLORS * 3):
        x = np.asarray(getattr(est, "x", est), dtype=float)
        ax.plot(x[:, 0], x[:, 1], "-", lw=1, color=col, label=name)
    return _finish(ax, sensor, title)


def plot_identity_strip(labels: dict, ax=None, title=None):
    """Which ground-truth identity each track covers, frame by frame (one row per track).

    ``labels`` maps a run's name to an (n_tracks, n_frames) array of identity indices
    (−1 where a track covers no identity), as
    ``trackbook.evaluation.identity.matched_identities`` returns.
    """
    rows = [(run, k, np.asarray(lab)[k]) for run, lab in labels.items()
            for k in range(np.asarray(lab).shape[0])]
    ax = ax or plt.figure(figsize=(9, 0.35 * len(rows) + 0.8)).gca()
    cols = [OKABE_ITO["blue"], OKABE_ITO["orange"], OKABE_ITO["bluish green"],
            OKABE_ITO["reddish purple"]]
    for i, (_, _, ids) in enumerate(rows):
        starts = np.flatnonzero(np.r_[True, ids[1:] != ids[:-1]])    # runs of one identity
        ends = np.r_[starts[1:], ids.size]
        for a, b in zip(starts, ends):
            j = int(ids[a])
            ax.broken_barh([(a - 0.5, b - a)], (i - 0.3, 0.6),
                           color="#DDDDDD" if j < 0 else cols[j % len(cols)])
    ax.set_xlim(-0.5, max(np.asarray(r[2]).size for r in rows) - 0.5)
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels([f"{run}: track {k + 1}" for run, k, _ in rows], fontsize=8)
    ax.invert_yaxis(); ax.set_xlabel("frame")
    if title:
        ax.set_title(title, fontsize=10)
    return ax
