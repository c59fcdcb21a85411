"""``edge-ray-pf``: the particle filter with the 8-ray edge observation model.

Kim, Kim & Choi, "Tracking moving objects using particle filter and edge observation model",
J. KSII 2016 (the book's ``05_edge_rays``). Table 2 of the paper, step by step:

1. init: Canny edges of the first frame; the model M = the 8 nearest-edge distances mDis_j
   from the centre of the box (eq. 1); N particles around the centre with equal weights.
2. each frame: Canny edges; for every particle its 8 distances pDis_j (eq. 4) -- 8 look-ups
   in per-pixel ray maps computed once for the frame; Ratio = pAvg / mAvg (eq. 5); weight 0
   outside the Ratio window [0.8, 1.2], else eq. 6; estimate C = sum_i w_i x_i (eq. 7) with
   normalised weights; resample in proportion to the weights.

The distances are computed only along the image lines through the particles (rows, columns
and diagonals), not as 8 whole-frame maps: exactly the same numbers, several times faster.

Options beyond the paper (off by default): ``max_ray`` caps the rays, ``adapt_scale`` lets the box follow the
weighted mean Ratio (sum_i w_i Ratio_i), ``model_rate`` blends M towards the rays at the current estimate.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..features import edge_rays as er
from ..params import NOT_PRINTED, param
from .centre_pf import CentreParticleFilter, CentrePFParams
from .lost import ColourCheck, MatchGate, visible_fraction
from .registry import register


@dataclasses.dataclass(frozen=True)
class EdgeRayParams(CentrePFParams):
    # Kim et al. (2016), section 3.2 after eq. 5: "the range of Ratio is set to 0.8-1.2".
    ratio_low: float = param(0.8, 0.1, 1.0, 0.05, "lower bound of the Ratio window (eq. 5)",
                             printed="kim2016.ratio_window", paper=0.8)
    ratio_high: float = param(1.2, 1.0, 5.0, 0.05, "upper bound of the Ratio window (eq. 5)",
                              printed="kim2016.ratio_window", paper=1.2)
    canny_low: float = param(
        50.0, 0.0, 500.0, 5.0, "Canny low hysteresis threshold", paper=NOT_PRINTED,
        why="no edge detector or threshold is printed; the book uses Canny (1986) "
        "with the common 50/150 pair")
    canny_high: float = param(
        150.0, 0.0, 1000.0, 5.0, "Canny high hysteresis threshold", paper=NOT_PRINTED,
        why="no edge detector or threshold is printed; the book uses Canny (1986) "
        "with the common 50/150 pair")
    blur: int = param(
        0, 0, 15, 2, "Gaussian blur kernel before Canny (0 = none)", paper=NOT_PRINTED,
        paper_value=0, why="no smoothing is printed; the book's default is none, "
        "an option for noisy video")
    max_ray: float = param(
        0.0, 0.0, 1000.0, 5.0, "cap on every ray in pixels (0 = up to the frame border)",
        paper=NOT_PRINTED, paper_value=0.0,
        why="eq. 1 and 4 give no cap; the book's option, off by default")
    adapt_scale: bool = param(
        False, doc="box size follows the weighted mean Ratio sum_i w_i Ratio_i (the book's "
        "addition)",
        paper=NOT_PRINTED, paper_value=False,
        why="the paper tracks the position only (eq. 3 [quote: kim2016.state_eq3]); the "
        "book's option, off by default")
    model_rate: float = param(
        0.0, 0.0, 0.5, 0.01, "rate of blending M towards the estimate's rays (0 = off)",
        paper=NOT_PRINTED, paper_value=0.0,
        why="the paper builds M in the first frame [quote: kim2016.edge_model_eight_rays] "
        "and leaves its update to further research [quote: kim2016.model_not_updated]; the "
        "book's option, off by default")
    lost_check: bool = param(
        True, doc="the book's lost rule: the estimate must be in view and match the first "
        "frame's colours; while lost, a whole-frame colour search restarts the filter",
        paper=NOT_PRINTED, paper_value=False,
        why="the book's addition (the docstring's Lost rule): edge rays alone cannot say that "
        "the target is gone; off, only the frame's rules remain (every weight zero, a flat "
        "frame)")


@register
class EdgeRayPF(CentreParticleFilter):
    """Particle filter weighted by the 8-ray edge observation model (Kim, Kim & Choi 2016).

    Attributes (read-only, for the book's drawings)
    ----------
    model_rays : (8,) mDis_j of the model M (eq. 1), in the order E, NE, N, NW, W, SW, S, SE.
    particle_rays : (N, 8) pDis_j of the last frame's particles (eq. 4).
    ratios : (N,) Ratio of eq. 5 of the last frame's particles.
    edges : (H, W) bool Canny edge map of the last frame.
    particles, weights, likelihoods, estimate, lost : see ``ParticleFilterTracker``.
    colour_rho : rho of the estimate's colour histogram against the first frame's (lost rule).

    Lost rule
    ---------
    Edge rays cannot say that the target is gone: a textured background has edges everywhere
    and many particles fall inside the Ratio window. So besides the rules of
    ``ParticleFilterTracker`` (every weight zero, a constant frame), a frame is lost when less
    than ``min_visible`` of the estimate's box is inside the frame, or when the first frame's
    colours match the estimate's poorly (the kernel colour histogram, HSV 8 x 8 x 4, of eq. 1
    of Lee et al. 2012): rho below 0.5, or below 0.7 and far outside its recent range
    (:class:`~trackbook.trackers.lost.MatchGate`) unless it stands out from the boxes around
    it (the second look of ``ParticleFilterTracker``: a sudden change of light). The edge rays alone still place the box;
    the colour only vetoes it. While lost, the spread widens (``lost_growth``) and the whole
    frame is searched by colour (:meth:`~trackbook.trackers.lost.ColourCheck.search`, at most
    325 histograms a frame, paid only while lost); a box that passes the gate restarts the
    filter there (``ok=True``). ``lost_check=False`` (the paper preset) leaves only the rules of
    ``ParticleFilterTracker``.

    Confidence
    ----------
    ``state().confidence`` is the edge likelihood of the best particle of the last frame,
    max_i w_i with w_i = 1 - sum_j |pDis_j - mDis_j| / sum_j mDis_j (eq. 6, 0 outside the
    Ratio window), in [0, 1]; 0 on a constant frame (not scored). It cannot say that the
    target is gone on a textured background: edges everywhere put some particle's rays near
    the model's, so a frame without the target can score as high as one with it (the reason
    for the colour lost rule above, which the confidence does not include).
    """

    name = "edge-ray-pf"
    #: Less than this fraction of the box in the frame: the target is leaving (lost).
    min_visible = 0.5
    Params = EdgeRayParams

    def model(self, frame, box):
        p = self.params
        if p.ratio_low > p.ratio_high:
            raise ValueError(
                f"ratio_low={p.ratio_low} is above ratio_high={p.ratio_high}; the Ratio window "
                "needs low <= high (the paper preset: 0.8 and 1.2).")
        super().model(frame, box)
        c = self.box_to_state(box)
        self.edges = er.edge_image(frame, p.canny_low, p.canny_high, p.blur)
        self.model_rays = self._rays(c[None, :])[0]
        self._m0 = self.model_rays.astype(float)
        self.particle_rays = np.zeros((0, 8))
        self.ratios = np.zeros(0)
        self._colour = ColourCheck(frame, box)
        self._colour_gate = MatchGate()
        self.colour_rho = 1.0

    def _drawn(self) -> dict:
        """The particle filter's fields plus ``rays``: pDis of every particle (eq. 4)."""
        d = super()._drawn()
        if len(self.particle_rays) != len(d["particles"]):
            return d                    # before the first weighted frame (or a flat one)
        return {**d, "rays": self.particle_rays}

    def _rays(self, xy):
        """pDis_j (eq. 4) of centres ``xy`` (N, 2) in the current edge map, capped at max_ray.

        A centre is continuous; its pixel is the one that contains it, ``floor(c)`` (pixel i
        covers [i, i + 1)). ``np.rint(c - 0.5)`` would round halves to even, so 21.0 would map to
        pixel 20 while 20.0 maps to 20; floor maps every centre to its own pixel. The
        distances are computed along the lines through the particles only
        (:func:`~trackbook.features.edge_rays.ray_steps_at`): the same numbers as 8 per-pixel
        maps of the whole frame, at a fraction of the cost.
        """
        cap = self.params.max_ray
        # a cap under one pixel is the shortest ray there is: 1 px (0 still means "no cap")
        return er.rays_at_points(self.edges, np.floor(xy), max(cap, 1.0) if cap > 0 else None)

    def likelihood(self, frame, particles):
        p = self.params
        self.edges = er.edge_image(frame, p.canny_low, p.canny_high, p.blur)
        self.particle_rays = self._rays(particles)
        m = self.model_rays * self.scale
        self.ratios = er.ratio(self.particle_rays, m)
        return er.edge_weight(self.particle_rays, m, (p.ratio_low, p.ratio_high))

    def _update(self, frame):
        previous = np.array(self.estimate, dtype=float)
        ok, box = super()._update(frame)
        if not self.params.lost_check:
            return self._adapt(ok, box)
        if ok and not self._confirmed(frame, box):
            # the edges placed the box, but it is not on the target (see "Lost rule")
            self.estimate, self.lost = previous, True
            self.on_lost()
            ok, box = False, self.state_to_box(previous)
        if not ok and not self._is_flat(frame):
            ok, box = self._search(frame, box)
            return ok, box
        return self._adapt(ok, box)

    def _adapt(self, ok, box):
        """The book's options on a frame that is not lost: the scale and the model M."""
        p = self.params
        if ok and (p.adapt_scale or p.model_rate > 0):
            if p.adapt_scale:
                # the weighted mean Ratio says how much larger the median ray is than the model's
                r = float(self.weights @ self.ratios)
                self.scale = float(np.clip(self.scale * r, 0.25, 4.0))
            if p.model_rate > 0:
                here = self._rays(self.estimate[None, :])[0] / self.scale
                self.model_rays = (1 - p.model_rate) * self.model_rays + p.model_rate * here
            box = self.state_to_box(self.estimate)
        return ok, box

    def _confirmed(self, frame, box) -> bool:
        """The lost rule's checks of an estimate the edges accepted: in view, colour match."""
        if visible_fraction(box, frame.shape) < self.min_visible:
            return False
        b = np.asarray(box, float)
        rho = self.colour_rho = float(self._colour.match(frame, b[None])[0])
        return not self._colour_gate.lost(rho, lambda: self._colour.stands_out(frame, b, rho))

    def _search(self, frame, box):
        """Lost: search the whole frame by colour; restart the filter on a box that passes."""
        found, rho = self._colour.search(frame, max_boxes=300, size=self._size * self.scale)
        if visible_fraction(found, frame.shape) < self.min_visible or self._colour_gate.lost(rho):
            return False, box
        self.colour_rho = rho
        c = self.box_to_state(found)
        n = self._particles.shape[0]
        self._particles = self._clip(c + self.rng.normal(0.0, self.params.sigma, size=(n, 2)))
        self._weights = np.full(n, 1.0 / n)
        self.estimate, self.lost, self._lost_run = c, False, 0
        self.velocity = np.zeros(2)
        return True, self.state_to_box(c)

    def _last_confidence(self) -> float:
        """The best particle's edge likelihood of eq. 6 (see "Confidence")."""
        lik = self._likelihoods
        return float(lik.max()) if lik.size else 0.0

    def frame_report(self) -> dict:
        """Per-frame numbers: the fraction of particles inside the Ratio window, the scale."""
        p = self.params
        inside = (self.ratios >= p.ratio_low) & (self.ratios <= p.ratio_high)
        return {"accepted": float(inside.mean()) if inside.size else 0.0, "scale": self.scale}
