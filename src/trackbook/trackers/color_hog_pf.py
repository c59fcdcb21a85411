"""``color-hog-pf``: colour + HOG fused by eq. 14 of Lee et al. 2012, fixed first-frame
references, no learning (chapter ``03_hog``; Lee et al. compare it as a baseline
[quote: lee2012.baselines], after Jin et al. 2010).

Everything but the measurement is :class:`~trackbook.trackers.color_pf.ColorPF`'s: the state
and motion of eq. 8-9, the initial particles, the resampling and the confidence.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..features.hog import gray_patches, hog_of_patches
from ..filters.lee2012_models import fuse, gaussian_likelihood, similarity, states_to_boxes
from ..params import param
from .base import redetecting
from .color_pf import BASELINE_READING, ColorPF, ColorPFParams
from .registry import register

#: Why the book's sigma_hog is not 0.4 (the baseline and the proposed tracker alike).
SIGMA_HOG_WHY = ("same reason as sigma_color: at 0.4 the HOG weights are nearly flat; 0.2 "
                 "scored higher on the seven public sequences we tuned on (the colour and HOG lab notes)")


@dataclasses.dataclass(frozen=True)
class ColorHogPFParams(ColorPFParams):
    """Knobs of ``color-hog-pf``: colour + HOG fused by eq. 14 against fixed first-frame
    references (Lee et al. 2012 compare it as a baseline [quote: lee2012.baselines], after Jin
    et al. 2010).

    The HOG chapter builds it. Like ``color-pf`` it is a baseline whose settings the paper does
    not print [quote: lee2012.baselines]: each value of section V is a reading here
    (``reading=``), printed for the proposed ``color-hog-ipca`` only; ``trackers.departures("color-hog-pf")`` lists the
    book's choices.
    """

    # alpha = 0.1: section V, the sentence after eq. 14 ("alpha = 0.1").
    alpha: float = param(0.1, 0.0, 1.0, 0.05, "alpha of eq. 14: weight of colour vs HOG",
                         reading="lee2012.alpha01", paper=0.1,
                         why="alpha = 0.1 is " + BASELINE_READING)
    # sigma_hog = 0.4: section V, after eq. 12-13 ("all sigma ... 0.4").
    sigma_hog: float = param(0.2, 0.02, 1.0, 0.02, "sigma_hog of eq. 11 and 13",
                             reading="lee2012.sigma04", paper=0.4,
                             why=SIGMA_HOG_WHY + "; 0.4 is " + BASELINE_READING)


@register
class ColorHogPF(ColorPF):
    """``color-hog-pf``: colour + HOG fused by eq. 14, no learning (Jin et al. 2010).

    ``features`` returns ``"color"`` (eq. 1) and ``"hog"`` (eq. 2-5) of every box, both from one
    resampling of the boxes to ``PATCH_SIZE``; ``similarities`` and ``reference`` have both keys.

    Confidence: the colour match of the best particle, max_i rho_color,i = 1 - D^2_color,i
    (the colour Bhattacharyya coefficient, as ``color-pf``'s): whether the target is there at
    all; the HOG term, which swings with small misalignments and on small boxes, is not in it.
    ``ok`` comes from the failure-detection layer judging it; ``color-hog-pf-redetect`` adds
    the re-detection layer (boxes over the whole frame scored by that colour match).
    """

    name = "color-hog-pf"
    Params = ColorHogPFParams

    def features(self, frame, boxes) -> dict:
        """Colour histogram (eq. 1) and HOG (eq. 2-5) of every box, from ONE resampling of
        the boxes to 16 x 24 px: the same as ``color_histograms`` and ``hog_descriptors``,
        with a single ``cv2.remap`` for both."""
        feats, patches = self._colour_and_patches(frame, boxes)
        feats["hog"] = hog_of_patches(gray_patches(patches))
        return feats

    def likelihood(self, frame, particles):
        """p(z|x) = alpha p_color + (1 - alpha) p_hog, eq. 14 of Lee et al. 2012, each term
        exp(-D^2 / 2 sigma^2) / sqrt(2 pi sigma^2) (eq. 10-11 sign corrected, or 12-13)."""
        p = self.params
        d2 = self._distances2(self.features(frame, states_to_boxes(particles)))
        self._similarities = {"color": similarity(d2["color"], p.sigma_color),
                              "hog": similarity(d2["hog"], p.sigma_hog)}
        # the match 1 - D^2 (the confidence) is the colour term alone: whether the target is
        # there at all; HOG's match swings with small misalignments and on small boxes
        self._match = np.clip(1.0 - d2["color"], 0.0, 1.0)
        return fuse(gaussian_likelihood(d2["color"], p.sigma_color),
                    gaussian_likelihood(d2["hog"], p.sigma_hog), p.alpha)   # eq. 14


register(redetecting(ColorHogPF))
