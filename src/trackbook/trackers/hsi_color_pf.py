"""Baseline (1) of Kim, Kim & Choi 2016: ``hsi-color-pf``, the kernel HSI histogram of
:mod:`trackbook.features.hsi` weighing the particles of :class:`.appearance_pf.AppearancePF`.
"""

from __future__ import annotations

from ..features.hsi import hsi_histograms
from .appearance_pf import AppearancePF
from .base import redetecting
from .registry import register


@register
class HSIColorPF(AppearancePF):
    """Baseline (1) of Kim et al. 2016: kernel HSI colour histogram (8 x 8 x 4) particle filter.

    Confidence: the best particle's rho of the HSI histograms, max_i rho(q, p_i), in [0, 1];
    0 on a constant frame. ``ok`` comes from the failure-detection layer judging it;
    ``hsi-color-pf-redetect`` adds the re-detection layer (boxes over the whole frame scored
    by the same rho).
    """

    name = "hsi-color-pf"

    def features(self, frame, boxes):
        return hsi_histograms(frame, boxes)


register(redetecting(HSIColorPF))
