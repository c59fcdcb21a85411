"""Baseline (2) of Kim, Kim & Choi 2016: ``hog-pf``, the HOG of Lee et al. 2012
(:func:`trackbook.features.hog.hog_descriptors`, 16 x 24 patch, 192 values summing to 1)
weighing the particles of :class:`.appearance_pf.AppearancePF`.
"""

from __future__ import annotations

from ..features.hog import hog_descriptors
from .appearance_pf import AppearancePF
from .base import redetecting
from .registry import register


@register
class HOGPF(AppearancePF):
    """Baseline (2) of Kim et al. 2016: HOG (Lee et al. 2012, 192 values) particle filter.

    Confidence: the best particle's Bhattacharyya coefficient of the HOGs, max_i rho(q, p_i),
    in [0, 1]; 0 on a constant frame. ``ok`` comes from the failure-detection layer;
    ``hog-pf-redetect`` adds the re-detection layer.
    """

    name = "hog-pf"

    def features(self, frame, boxes):
        return hog_descriptors(frame, boxes)


register(redetecting(HOGPF))
