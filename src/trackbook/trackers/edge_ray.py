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
from .base import redetecting
from .generic_confidence import ColourCheck
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
    colour_rho : the confidence of the last frame (see "Confidence").

    Confidence
    ----------
    The edge likelihood cannot say that the target is gone: a textured background has edges
    everywhere and some particle's rays fall near the model's, so a frame without the target
    can weigh as much as one with it. The confidence is therefore the failure layer's
    generic one, the appearance match of the estimate against the first frame's model: the
    Bhattacharyya coefficient rho between the kernel colour histogram (HSV 8 x 8 x 4, eq. 1 of
    Lee et al. 2012) of the estimate's box and that of the first box
    (:meth:`~trackbook.trackers.generic_confidence.ColourCheck.match`), in [0, 1]; on a frame without an
    estimate (every particle outside the Ratio window), that of the last box. The colour
    never moves the box: the edge rays alone place it. ``ok`` comes from the
    failure-detection layer judging that confidence; ``edge-ray-pf-redetect`` adds the
    re-detection layer, which scores boxes over the whole frame by the same colour match.
    """

    name = "edge-ray-pf"
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

    def _locate(self, frame):
        """The SIR cycle of Table 2 (edge likelihood), with the colour confidence."""
        box, _ = super()._locate(frame)
        at = box if np.all(np.isfinite(box)) else np.asarray(self.bbox, dtype=float)
        self.colour_rho = float(self._colour.match(frame, np.asarray(at, float)[None])[0])
        return box, self.colour_rho

    def _learn(self, frame, box):
        """Accept the estimate, then the book's options: the scale and the model M."""
        super()._learn(frame, box)
        p = self.params
        if p.adapt_scale:
            # the weighted mean Ratio says how much larger the median ray is than the model's
            r = float(self.weights @ self.ratios)
            self.scale = float(np.clip(self.scale * r, 0.25, 4.0))
        if p.model_rate > 0:
            here = self._rays(self.estimate[None, :])[0] / self.scale
            self.model_rays = (1 - p.model_rate) * self.model_rays + p.model_rate * here

    def _score_boxes(self, frame, boxes):
        """The confidence's colour match (rho against the first box's histogram) of each box."""
        return self._colour.match(frame, np.asarray(boxes, dtype=float))

    def frame_report(self) -> dict:
        """Per-frame numbers: the fraction of particles inside the Ratio window, the scale."""
        p = self.params
        inside = (self.ratios >= p.ratio_low) & (self.ratios <= p.ratio_high)
        return {"accepted": float(inside.mean()) if inside.size else 0.0, "scale": self.scale}


register(redetecting(EdgeRayPF))
