"""Cho & Kang 2005: Condensation, mean-shift, and Condensation with candidates moved by mean-shift.

The case study ``case_study_cho2005`` (on ``08_mean_shift``; lab notes ``lab_notes_cho2005``).
Three trackers share one target model, an ellipse with a kernel-weighted colour distribution:

- ``condensation`` (baseline, Nummiaro et al. 2003): factored sampling -> predict
  ``s_t = A s_{t-1} + w`` -> weight every candidate by its Bhattacharyya likelihood; 100 candidates.
- ``mean-shift`` (baseline, Comaniciu, Ramesh & Meer 2003): one ellipse moved uphill on
  rho[p(y), q] from the last position (steps ①-⑥ of §3.3).
- ``condensation-mean-shift`` (proposed): the target's least-squares motion vector (p, q)
  (eq. 5-8) seeds the prediction of only 5 candidates (eq. 9), each candidate is moved uphill by
  mean-shift (eq. 10-13), then weighted and averaged.

State of a candidate (eq. 1): ``s = (x, y, x_dot, y_dot, Hx, Hy, a)``: the ellipse centre, its
velocity in pixels per frame, its half-axes and ``a``, the size change of this frame.

The dynamics ``s_t = A s_{t-1} + w_{t-1}`` (eq. 9) are, with all noise Gaussian and scaled by
the candidate's own half-axes so that one setting fits small and large targets::

    x_dot_t = x_dot + w_xdot        x_t = x + x_dot_t + w_x        a_t = 1 + w_a
    y_dot_t = y_dot + w_ydot        y_t = y + y_dot_t + w_y        Hx_t = a_t Hx,  Hy_t = a_t Hy

The velocity is drawn first and the position moves by the *new*, already-noised velocity
``x_dot_t`` (not by ``x_dot_{t-1}``), so the position's spread per frame is
``sqrt(noise_position^2 + noise_velocity^2)`` half-axes. The size is multiplied by ``a``, the
one non-linear step; the paper names A only as "the deterministic component"
[quote: cho2005.candidates_eq9]. The likelihood is Nummiaro's ``exp(-(1 - rho) / (2 sigma^2))``.
"""

from __future__ import annotations

import dataclasses

import cv2
import numpy as np

from ..filters.mean_shift import (BANDWIDTHS, bin_image, ellipse_rho, mean_shift,
                                  mean_shift_with_scale, region_around)
from ..filters.optical_flow import motion_vector, pyramid
from .particle_filter import ParticleFilterTracker, resampler_param
from ..params import NOT_PRINTED, param
from .base import Tracker, readonly, readonly_attr, redetecting
from .registry import register

#: Names of the seven components of a candidate (eq. 1).
STATE = ("x", "y", "x_dot", "y_dot", "Hx", "Hy", "a")


def box_to_ellipse(box) -> np.ndarray:
    """``(x, y, w, h)`` -> ``(cx, cy, Hx, Hy)``: the ellipse inscribed in the box."""
    x, y, w, h = (float(v) for v in box)
    return np.array([x + w / 2, y + h / 2, w / 2, h / 2])


def ellipse_to_box(cx, cy, hx, hy) -> np.ndarray:
    """``(cx, cy, Hx, Hy)`` -> ``(x, y, w, h)``: the box the ellipse is inscribed in."""
    return np.array([cx - hx, cy - hy, 2 * hx, 2 * hy], dtype=float)


def colour_likelihood(rho, sigma: float) -> np.ndarray:
    """Nummiaro et al. 2003: pi = exp(-(1 - rho) / (2 sigma^2)), d^2 = 1 - rho the Bhattacharyya
    distance squared (the constant 1 / (sqrt(2 pi) sigma) is dropped: weights are normalised)."""
    return np.exp(-(1.0 - np.asarray(rho, dtype=float)) / (2.0 * sigma * sigma))


@dataclasses.dataclass(frozen=True)
class EllipseColourParams:
    """Tunables of the target model the three trackers of Cho & Kang 2005 share: the colour
    distribution of an ellipse (eq. 3) and its likelihood (Nummiaro et al. 2003)."""

    sigma: float = param(0.1, 0.01, 1.0, 0.01,
                         "sigma of the likelihood exp(-(1 - rho) / 2 sigma^2) (Nummiaro et al. "
                         "2003: 0.1)",
                         paper=NOT_PRINTED,
                         why="no likelihood is printed; the book takes Nummiaro et al. "
                             "(2003)'s 0.1")
    h_bins: int = param(8, 1, 32, 1, "hue bins of the colour distribution (eq. 3)",
                        paper=NOT_PRINTED,
                        why="eq. 3 names bins u but no count; 8x8x4 HSV after Nummiaro et al. "
                            "(2003)")
    s_bins: int = param(8, 1, 32, 1, "saturation bins (eq. 3)", paper=NOT_PRINTED,
                        why="not printed; 8 saturation bins after Nummiaro et al. (2003)")
    v_bins: int = param(4, 1, 32, 1, "value bins (eq. 3)", paper=NOT_PRINTED,
                        why="not printed; 4 value bins (value is least stable under light)")
    resolution: int = param(8, 2, 64, 1,
                            "lattice pixels across the shorter half-axis: larger targets are "
                            "read every k-th pixel so the cost does not grow with their size "
                            "(speed; the paper's small 320x240 targets are read at every pixel "
                            "anyway)",
                            paper=NOT_PRINTED,
                            why="the book's addition for speed on large targets; eq. 3 sums "
                                "every pixel, which this setting matches on targets of 8 px "
                                "half-axes")
    # §3.1 after eq. 3 and §4.2 after eq. 10: a = sqrt(Hx^2 + Hy^2)
    # [quote: cho2005.bandwidth_eq3] [quote: cho2005.bandwidth_eq10]
    bandwidth: str = param("ellipse", doc="radius r of the kernel k(r) = 1 - r^2 of eq. 3 and "
                           "10 on the ellipse's pixels: 'ellipse' = ||((x - y_x) / Hx, (y - y_y) / "
                           "Hy)||, 'diagonal' = ||y - x_i|| / a with a = sqrt(Hx^2 + Hy^2) as "
                           "printed", choices=BANDWIDTHS,
                           printed="cho2005.bandwidth_eq3", paper="diagonal",
                           why="Comaniciu et al. (2003)'s normalised ellipse: the weight falls to 0 "
                               "at the ellipse's edge in every direction; with the printed a the "
                               "edge pixels keep Hy^2/a^2 to Hx^2/a^2 (1/2 on a circle), a kernel "
                               "cut off at the edge")


@dataclasses.dataclass(frozen=True)
class CondensationParams(EllipseColourParams):
    """Tunables of ``condensation`` (Nummiaro et al. 2003 as used by Cho & Kang 2005): the
    shared colour model plus the candidates of eq. 9, s_t = A s_(t-1) + w -- how many, and the
    noise w of A."""

    # Cho & Kang 2005 §5.1
    n_particles: int = param(100, 1, 100_000, 1, "N, number of candidates (100 in Cho & Kang "
                             "2005 §5.1, after Nummiaro)",
                             printed="cho2005.condensation_n100", paper=100, slider=(1, 2000))
    noise_position: float = param(0.15, 0.0, 2.0, 0.01,
                                  "std of w_x, w_y of eq. 9, in half-axes (the noise of A)",
                                  paper=NOT_PRINTED,
                                  why="eq. 9 names the noise w but prints no size; 0.15 "
                                      "half-axes chosen on the sample clips (lab notes)")
    noise_velocity: float = param(0.05, 0.0, 1.0, 0.01,
                                  "std of w_xdot, w_ydot of eq. 9, in half-axes per frame",
                                  paper=NOT_PRINTED,
                                  why="not printed; 0.05 half-axes per frame chosen on the "
                                      "sample clips (lab notes)")
    noise_scale: float = param(0.0, 0.0, 0.3, 0.005,
                               "std of w_a: the size changes by a = 1 + w_a (book default 0, "
                               "fixed size, for all three trackers: the colour likelihood alone "
                               "lets the size drift, mostly smaller; the Condensation and "
                               "mean-shift case study)",
                               paper=NOT_PRINTED,
                               why="eq. 1 has a size change a but no spread; the book fixes the "
                                   "size (0) because the colour likelihood lets it shrink "
                                   "(the Condensation and mean-shift case study)")
    # §3.2 step ①: sample from the weighted set
    resampler: str = resampler_param("factored sampling (step ①)",
                                     reading="cho2005.condensation_sampling", paper="multinomial")


@dataclasses.dataclass(frozen=True)
class CondensationMeanShiftParams(CondensationParams):
    """Tunables of ``condensation-mean-shift`` (Cho & Kang 2005): those of ``condensation``
    with 5 candidates, plus the mean-shift of every candidate and the motion vector."""

    n_particles: int = param(5, 1, 100_000, 1, "N, number of candidates (5 in Cho & Kang 2005 "
                             "§5.1)", printed="cho2005.proposed_n5", paper=5, slider=(1, 500))
    # §4, eq. 12-13: one mean-shift step moves each candidate, printed once per candidate.
    max_iter: int = param(10, 0, 100, 1, "mean-shift iterations per candidate at most "
                          "(eq. 12-13)",
                          reading="cho2005.likelihood_rises_eq13", paper=1,
                          why="eq. 12-13 print one shift per candidate, read as one iteration "
                              "(the paper preset) [quote: cho2005.likelihood_rises_eq13]; the "
                              "book repeats "
                              "steps ②-⑥ of §3.3 (halving, stop below eps) up to 10 times so "
                              "each candidate reaches its hill top (preset='paper' runs "
                              "one shift)")
    eps: float = param(0.5, 0.01, 10.0, 0.05, "mean-shift stops when the step is below eps "
                       "pixels", paper=NOT_PRINTED,
                       why="step ⑥ of §3.3 names epsilon without a value; half a pixel")
    use_motion: bool = param(True, doc="seed the prediction with the motion vector (p, q) of "
                             "eq. 8", printed="cho2005.motion_vector", paper=True)  # §4, eq. 5-9
    flow_levels: int = param(3, 1, 6, 1, "pyramid levels of the motion vector (1 = one "
                             "solve, the paper preset's reading of eq. 8)",
                             reading="cho2005.flow_eq8",
                             paper=1,  # eq. 5-8: one least-squares solve on the frame pair
                             why="one solve cannot measure motions over ~1 px; a 3-level "
                                 "pyramid measures the sample clips' 2-6 px steps (lab notes)")
    flow_iterations: int = param(1, 1, 20, 1, "solves per pyramid level (1 = one solve, "
                                 "the paper preset's reading of eq. 8; more re-warp and solve "
                                 "for the remainder)",
                                 reading="cho2005.flow_eq8", paper=1)  # eq. 8: one solve


@dataclasses.dataclass(frozen=True)
class MeanShiftParams(EllipseColourParams):
    """Tunables of ``mean-shift`` (Comaniciu, Ramesh & Meer 2003)."""

    max_iter: int = param(20, 1, 100, 1, "mean-shift iterations per frame at most (Comaniciu: "
                          "20)", paper=NOT_PRINTED,
                          why="Cho & Kang loop steps ②-⑥ until the step is below epsilon; the "
                              "cap of 20 is Comaniciu et al. (2003)'s")
    eps: float = param(0.5, 0.01, 10.0, 0.05, "stop when the step is below eps pixels (step ⑥)",
                       paper=NOT_PRINTED,
                       why="step ⑥ of §3.3 names epsilon without a value; half a pixel")
    scale_adapt: bool = param(False, doc="try ±10 % half-axes and keep the best rho "
                              "(Comaniciu §5.2)", paper=NOT_PRINTED, paper_value=False,
                              why="§3.3's steps move the centre only; the ±10 % search is "
                                  "Comaniciu et al. (2003)'s, off by default")
    gamma: float = param(0.1, 0.0, 1.0, 0.05, "scale smoothing h = gamma h_opt + (1 - gamma) "
                         "h_prev", paper=NOT_PRINTED,
                         why="only used with scale_adapt; Comaniciu et al. (2003)'s 0.1")


class _EllipseColourModel:
    """The target model the three trackers share: an ellipse and its colour distribution q."""

    def _bins(self):
        p = self.params
        return (int(p.h_bins), int(p.s_bins), int(p.v_bins))

    def _stride(self, axes) -> int:
        """Stride of the bin-image lattice: ``resolution`` lattice pixels per shorter half-axis."""
        return max(1, int(float(np.min(axes)) / self.params.resolution))

    def _set_model(self, frame, box):
        e = box_to_ellipse(box)
        self._axes0 = e[2:].copy()
        H, W = frame.shape[:2]
        self._max_axes = np.minimum(4 * self._axes0, [W / 2, H / 2])
        self._min_axes = np.maximum(0.25 * self._axes0, 2.0)
        # the model q_u is eq. 3 over every pixel of the initial ellipse (once, so no sampling)
        img = bin_image(frame, region_around(e[None, :2], e[None, 2:], 0.1), 1, self._bins())
        _, p, _ = ellipse_rho(img, np.zeros(img.n_bins), e[None, :2], e[None, 2:],
                              self.params.bandwidth)
        self.q = p[0]

    def _bin_image(self, frame, centres, axes, margin=1.0):
        return bin_image(frame, region_around(centres, axes, margin), self._stride(axes.mean(0)),
                         self._bins())

    def _score_boxes(self, frame, boxes):
        """For the re-detection layer: rho[p, q] of the ellipse inscribed in every box (eq. 3),
        from one bin image; nothing is stored, so scoring changes nothing. (For
        ``condensation-mean-shift`` too: its ``likelihood`` reads the rho its mean-shift
        reached on the frame's candidates, not the boxes'.)"""
        b = np.asarray(boxes, dtype=float)
        centres, axes = b[:, :2] + b[:, 2:] / 2, b[:, 2:] / 2
        img = self._bin_image(frame, centres, axes, margin=0.1)
        rho, _, _ = ellipse_rho(img, self.q, centres, axes, self.params.bandwidth)
        return rho

    def _clamp(self, states):
        """Keep centres in the frame and half-axes within [1/4, 4] x the initial ones."""
        H, W = self._shape[:2]
        states[:, 0] = np.clip(states[:, 0], 0, W)
        states[:, 1] = np.clip(states[:, 1], 0, H)
        states[:, 4:6] = np.clip(states[:, 4:6], self._min_axes, self._max_axes)
        return states


@register
class Condensation(_EllipseColourModel, ParticleFilterTracker):
    """Condensation with a colour distribution (Nummiaro et al. 2003), the baseline of Cho & Kang.

    Attributes (read-only, for drawings)
    ------------------------------------
    particles : (N, 7) candidates ``(x, y, x_dot, y_dot, Hx, Hy, a)`` after the last update
    weights : (N,) their normalised weights; likelihoods : (N,) unnormalised
    rho : (N,) their Bhattacharyya coefficients
    ellipse : ``(cx, cy, Hx, Hy)`` of the estimate

    Confidence and failure
    ----------------------
    ``state().confidence`` is the best candidate's Bhattacharyya coefficient of the last
    frame, max_i rho[p(s_i), q], p(s_i) the colour distribution (eq. 3) of candidate i's
    ellipse, in [0, 1]; 0 on a constant frame (not scored). The estimate itself, the weighted
    mean, is not scored again. The paper's trackers have no lost state (it reports mean-shift
    failing after targets overlap [quote: cho2005.multi_mean_shift_fails]): ``ok`` comes from
    the failure-detection layer (:class:`~trackbook.trackers.failure.FailureDetector`) judging
    that confidence. A frame judged lost keeps the last ellipse and the candidates go on from
    where they are (see :class:`ParticleFilterTracker`, "While lost");
    ``condensation-redetect`` adds the re-detection layer, which scores ellipses over the whole
    frame by the same rho and restarts the candidates at the best.
    """

    name = "condensation"
    Params = CondensationParams

    # -- ParticleFilterTracker interface -------------------------------------------------
    def model(self, frame, box):
        self._set_model(frame, box)
        self._rho = np.ones(self.params.n_particles)
        self._report = {}

    def initial_particles(self, frame, box):
        return np.repeat(self.box_to_state(box)[None, :], self.params.n_particles, axis=0)

    def box_to_state(self, box):
        cx, cy, hx, hy = box_to_ellipse(box)
        return np.array([cx, cy, 0.0, 0.0, hx, hy, 1.0])

    def state_to_box(self, state):
        return ellipse_to_box(state[0], state[1], state[4], state[5])

    def predict(self, particles):
        """Eq. 9: s_t = A s_{t-1} + w_{t-1} (see the module docstring for A and w)."""
        p, s = self.params, np.array(particles, dtype=float)
        n = s.shape[0]
        scale = s[:, 4:6]
        z = self.rng.standard_normal((n, 5))
        s[:, 2:4] += p.noise_velocity * scale * z[:, 2:4]
        s[:, 0:2] += s[:, 2:4] + p.noise_position * scale * z[:, 0:2]
        s[:, 6] = 1.0 + p.noise_scale * z[:, 4]
        s[:, 4:6] *= s[:, 6:7]
        return self._clamp(s)

    def likelihood(self, frame, particles):
        """Step ③: pi_i = p(z_t | x_t = s_t^i), the colour likelihood of every candidate."""
        img = self._bin_image(frame, particles[:, :2], particles[:, 4:6], margin=0.1)
        rho, _, labels = ellipse_rho(img, self.q, particles[:, :2], particles[:, 4:6],
                                     self.params.bandwidth)
        lik = self._weigh(rho)
        self._report.update(histograms=float(labels.shape[0]), pixels=float(labels.size))
        return lik

    def _weigh(self, rho):
        self._rho = rho
        self._match = np.asarray(rho, dtype=float)
        lik = colour_likelihood(rho, self.params.sigma)
        self._report = {"mean_likelihood": float(lik.mean()), "mean_rho": float(rho.mean())}
        return lik

    def _learn(self, frame, box):
        """Accept the weighted-mean estimate; its size change ``a`` is this frame's (eq. 1),
        so the accepted state carries ``a = 1`` (the half-axes already hold the new size)."""
        super()._learn(frame, box)
        self.estimate[6] = 1.0

    # -- for the book ------------------------------------------------------------------
    def frame_report(self) -> dict:
        """``mean_likelihood`` of this frame's candidates (Cho & Kang 2005 Fig. 5), ``mean_rho``,
        and the book's count of the cost: colour ``histograms`` computed and ``pixels`` read (the
        paper measures seconds per frame [quote: cho2005.table1_seconds])."""
        return dict(self._report)

    rho = readonly_attr("_rho")

    @property
    def ellipse(self) -> tuple:
        e = self.estimate
        return (float(e[0]), float(e[1]), float(e[4]), float(e[5]))

    def _drawn(self) -> dict:
        """The particle filter's fields plus the estimate's ``ellipse`` (cx, cy, Hx, Hy)."""
        return {**super()._drawn(), "ellipse": self.ellipse}


@register
class CondensationMeanShift(Condensation):
    """Cho & Kang 2005's proposed tracker: 5 candidates seeded by the motion vector and moved
    uphill by mean-shift before they are weighted.

    Attributes (read-only, besides those of :class:`Condensation`)
    ---------------------------------------------------------------
    predicted : (N, 7) the candidates before mean-shift moved them (Fig. 2 (a))
    rho_before : (N,) their rho before mean-shift (eq. 13: ``rho >= rho_before``)
    motion : ``(p, q, ok)`` the motion vector of the last frame (eq. 8)
    mean_shift_result : the :class:`~trackbook.filters.mean_shift.MeanShiftResult` of the last
        frame (trajectories of every candidate, for Fig. 2 (b))

    Confidence: as :class:`Condensation`'s, max_i rho of the candidates after mean-shift
    moved them (the hill tops they reached); ``ok`` comes from the failure-detection layer on
    it, and ``condensation-mean-shift-redetect`` adds the re-detection layer (whole-frame
    ellipses scored by rho while lost, the candidates restarted at the best).
    """

    name = "condensation-mean-shift"
    Params = CondensationMeanShiftParams

    def _init(self, frame, box):
        super()._init(frame, box)
        self.motion = (0.0, 0.0, False)
        self._rho_before = np.ones(self.params.n_particles)
        self._predicted = self._particles.copy()
        self.mean_shift_result = None
        if self.params.use_motion:
            self._remember(frame)

    def _flow_window(self):
        """Region (x0, y0, x1, y1) around the estimate for the motion vector, and its scale f.

        The region is reduced f times (the box becomes about 32 px), and its size is a multiple
        of f so that the reduction is an exact f x f box average (OpenCV's fast path)."""
        cx, cy, hx, hy = self.ellipse
        H, W = self._shape[:2]
        f = max(1, int(2 * max(hx, hy) // 32))
        x0, y0 = int(max(cx - 2 * hx, 0)), int(max(cy - 2 * hy, 0))
        x1, y1 = int(min(cx + 2 * hx + 1, W)), int(min(cy + 2 * hy + 1, H))
        x1, y1 = x0 + (x1 - x0) // f * f, y0 + (y1 - y0) // f * f
        return (x0, y0, x1, y1), f

    def _gray(self, frame, window, f):
        """The flow window of ``frame``, grey, reduced f times, as a pyramid (eq. 8's images)."""
        x0, y0, x1, y1 = window
        g = cv2.cvtColor(frame[y0:y1, x0:x1], cv2.COLOR_BGR2GRAY)
        if f > 1 and g.size:
            g = cv2.resize(g, ((x1 - x0) // f, (y1 - y0) // f), interpolation=cv2.INTER_AREA)
        return pyramid(g, self.params.flow_levels)

    def _window_still_fits(self) -> bool:
        """Whether the estimate's box, with half a half-axis to spare, is still inside the last
        flow window (the frame's border counts as inside), at the same scale."""
        win, f = self._flow_win, self._flow_f
        new_win, new_f = self._flow_window()
        if new_f != f:
            return False
        cx, cy, hx, hy = self.ellipse
        H, W = self._shape[:2]
        x0, y0 = max(cx - 1.5 * hx, 0), max(cy - 1.5 * hy, 0)
        x1, y1 = min(cx + 1.5 * hx, W), min(cy + 1.5 * hy, H)
        return win[0] <= x0 and win[1] <= y0 and x1 <= win[2] and y1 <= win[3]

    def _remember(self, frame, curr=None):
        """Keep frame t's grey levels for the next motion vector. The window follows the target
        only when it nears the window's edge: until then this frame's grey window, already
        computed for the motion vector, is reused (one grey conversion per frame)."""
        if curr is not None and self._window_still_fits():
            self._prev_gray = curr
            return
        self._flow_win, self._flow_f = self._flow_window()
        self._prev_gray = self._gray(frame, self._flow_win, self._flow_f)

    def _motion(self, frame):
        """Eq. 5-8: the least-squares motion (p, q) of the target region since the last frame.

        Returns ``((p, q, ok), curr)``, ``curr`` being this frame's grey window."""
        p = self.params
        win, f = self._flow_win, self._flow_f
        curr = self._gray(frame, win, f)
        cx, cy, hx, hy = self.ellipse
        box = ((cx - hx - win[0]) / f, (cy - hy - win[1]) / f, 2 * hx / f, 2 * hy / f)
        if curr[0].shape != self._prev_gray[0].shape or min(curr[0].shape) < 4:
            return (0.0, 0.0, False), None
        dp, dq, ok = motion_vector(self._prev_gray, curr, box, levels=p.flow_levels,
                                   iterations=p.flow_iterations,
                                   max_motion=max(curr[0].shape) / 2)
        return (dp * f, dq * f, ok), curr

    def _locate(self, frame):
        """The motion vector (p, q) of the target region since the last frame (eq. 5-8), then
        the SIR cycle with it (eq. 9-13). This frame's grey window is kept for
        :meth:`_learn` / :meth:`_follow`, which remember it for the next motion vector."""
        self._curr = None
        if self.params.use_motion:
            self.motion, self._curr = self._motion(frame)
        else:
            self.motion = (0.0, 0.0, False)
        return super()._locate(frame)

    def _learn(self, frame, box):
        """Accept the estimate; keep this frame's grey window (eq. 8's image t, next motion)."""
        super()._learn(frame, box)
        if self.params.use_motion:
            self._remember(frame, self._curr)

    def _follow(self, frame, box):
        """A lost frame: the candidates already moved in ``_locate``; only this frame's grey
        window is kept (around the last accepted estimate), so the next motion vector is
        measured between consecutive frames, as eq. 5-8 do.

        Parameters
        ----------
        frame : (H, W, 3) uint8 array, the lost frame
        box : (4,) float array, the box ``_locate`` found on it (not used)

        Returns
        -------
        None
        """
        if self.params.use_motion:
            self._remember(frame, self._curr)

    def predict(self, particles):
        """Eq. 9 with the velocity of every sampled candidate set to the motion vector (p, q)."""
        s = np.array(particles, dtype=float)
        if self.motion[2]:
            s[:, 2] = self.motion[0]
            s[:, 3] = self.motion[1]
        return super().predict(s)

    def refine(self, frame, particles):
        """Eq. 10-13: move every candidate uphill on rho[p(y), q] by mean-shift."""
        p = self.params
        self._predicted = particles.copy()
        img = self._bin_image(frame, particles[:, :2], particles[:, 4:6], margin=1.0)
        res = mean_shift(img, self.q, particles[:, :2], particles[:, 4:6],
                         max_iter=p.max_iter, eps=p.eps, bandwidth=p.bandwidth)
        self.mean_shift_result = res
        self._rho_before = res.rho_start
        moved = particles.copy()
        moved[:, :2] = res.centres
        self._rho_after = res.rho
        return self._clamp(moved)

    def likelihood(self, frame, particles):
        # rho at the moved candidates is what mean-shift converged to: no second evaluation
        lik = self._weigh(self._rho_after)
        res = self.mean_shift_result
        self._report.update(
            mean_likelihood_before=float(colour_likelihood(self._rho_before,
                                                           self.params.sigma).mean()),
            histograms=float(res.histograms), pixels=float(res.pixels))
        return lik

    predicted = readonly_attr("_predicted")
    rho_before = readonly_attr("_rho_before")


@register
class MeanShift(_EllipseColourModel, Tracker):
    """Comaniciu, Ramesh & Meer 2003's kernel tracker: one ellipse moved uphill every frame.

    Attributes (read-only, for drawings)
    ------------------------------------
    ellipse : ``(cx, cy, Hx, Hy)`` of the estimate
    particles : (1, 7) the single "candidate" as a Condensation state; weights : ``[1.0]``
    rho : (1,) its Bhattacharyya coefficient
    trajectory : (T, 2) the centres visited by the last frame's iterations (steps ①-⑥)

    Confidence: ``state().confidence`` is the Bhattacharyya coefficient where the climb
    stopped, rho[p(y), q] = sum_u sqrt(p_u(y) q_u), p(y) the colour distribution (eq. 3) of
    the ellipse, in [0, 1]; 0 on a constant frame (not scored). ``ok`` comes from the
    failure-detection layer on it: a lost frame reports the last box judged on target and
    teaches nothing, while the next climb starts where this one stopped (``_follow``). ``mean-shift-redetect`` adds the re-detection
    layer (the whole frame scored by rho while lost, the climb restarted at the best box).
    """

    name = "mean-shift"
    Params = MeanShiftParams

    def _init(self, frame, box):
        self._set_model(frame, box)
        e = box_to_ellipse(box)
        self._centre, self._axes = e[:2].copy(), e[2:].copy()
        self._rho = np.ones(1)
        self._trajectory = self._centre[None, :].copy()
        self._report = {}

    def _locate(self, frame):
        """Steps ①-⑥ of §3.3 from the last centre; returns ``(box, rho)``. The ellipse moves
        only in :meth:`_learn`."""
        p = self.params
        if self._is_flat(frame):
            # a constant frame (all black, all white, one grey): nothing in it can be the
            # target (the base reports it lost); not scored
            self._rho = np.zeros(1)
            self._trajectory = self._centre[None, :].copy()
            self._report = {"mean_likelihood": 0.0, "mean_rho": 0.0, "histograms": 0.0,
                            "pixels": 0.0}
            return ellipse_to_box(*self._centre, *self._axes), 0.0
        img = self._bin_image(frame, self._centre[None, :], self._axes[None, :] * 1.1, margin=1.0)
        axes = self._axes
        if p.scale_adapt:
            res, axes = mean_shift_with_scale(img, self.q, self._centre, self._axes,
                                              gamma=p.gamma, max_iter=p.max_iter, eps=p.eps,
                                              bandwidth=p.bandwidth)
            axes = np.clip(axes, self._min_axes, self._max_axes)
        else:
            res = mean_shift(img, self.q, self._centre[None, :], self._axes[None, :],
                             max_iter=p.max_iter, eps=p.eps, bandwidth=p.bandwidth)
        self._trajectory = res.trajectory[:, 0, :]
        H, W = self._shape[:2]
        centre = np.clip(res.centres[0], [0, 0], [W, H])
        self._rho = res.rho.copy()
        lik = colour_likelihood(self._rho, p.sigma)
        self._report = {"mean_likelihood": float(lik[0]), "mean_rho": float(self._rho[0]),
                        "histograms": float(res.histograms), "pixels": float(res.pixels)}
        return ellipse_to_box(*centre, *axes), float(self._rho[0])

    def _learn(self, frame, box):
        """Move the ellipse to ``box`` (the model q is the first frame's: no update)."""
        e = box_to_ellipse(box)
        self._centre, self._axes = e[:2].copy(), e[2:].copy()

    def _relocate(self, frame, box):
        """Restart the climb at ``box``'s centre (the half-axes stay)."""
        H, W = self._shape[:2]
        self._centre = np.clip(box_to_ellipse(box)[:2], [0, 0], [W, H])

    def frame_report(self) -> dict:
        """The likelihood of the single candidate (Cho & Kang 2005 Fig. 5), its rho, and the
        colour ``histograms`` computed and ``pixels`` read by this frame's iterations."""
        return dict(self._report)

    @property
    def ellipse(self) -> tuple:
        return (float(self._centre[0]), float(self._centre[1]),
                float(self._axes[0]), float(self._axes[1]))

    @property
    def particles(self) -> np.ndarray:
        return readonly(np.array([[*self._centre, 0.0, 0.0, *self._axes, 1.0]]))

    @property
    def weights(self) -> np.ndarray:
        return readonly(np.ones(1))

    rho = readonly_attr("_rho")
    trajectory = readonly_attr("_trajectory")

    def _drawn(self) -> dict:
        """The ``ellipse`` (cx, cy, Hx, Hy) and its single candidate as a particle of weight 1."""
        return {**super()._drawn(), "ellipse": self.ellipse, "particles": self.particles,
                "weights": self.weights}


register(redetecting(Condensation))
register(redetecting(CondensationMeanShift))
register(redetecting(MeanShift))
