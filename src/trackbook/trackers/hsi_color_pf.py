"""Baseline (1) of Kim, Kim & Choi 2016: ``hsi-color-pf``, the kernel HSI histogram of
:mod:`trackbook.features.hsi` weighing the particles of :class:`.appearance_pf.AppearancePF`.
"""

from __future__ import annotations

import cv2
import numpy as np

from ..features.hsi import hsi_histograms
from .appearance_pf import AppearancePF
from .registry import register


def _mean_intensity(frame) -> float:
    """Mean over the frame of the HSI intensity I = (R + G + B) / 3, in grey levels."""
    return float(np.mean(cv2.mean(frame)[:3]))


@register
class HSIColorPF(AppearancePF):
    """Baseline (1) of Kim et al. 2016: kernel HSI colour histogram (8 x 8 x 4) particle filter.

    Lost rule
    ---------
    That of ``ParticleFilterTracker``, with one more look before the distance gate calls a
    frame lost: the light. The histogram's intensity bins move with the light of the whole
    frame (a lamp switched on shifts every pixel up a bin or two) while hue and saturation,
    ratios of the channels, do not; so a sudden change of light drops the match of a box that
    is still on the target, as a target that left does. The relit look tells them apart with
    the frame's own statistics: it scales the frame so that its mean intensity
    I = (R + G + B) / 3 is that of the last frame that was not lost (a grey-world
    correction: the light under which the target last matched) and scores the best particle
    again. The frame is kept when that match passes the same distance gate (at least
    ``lost_below``, or within the recent range). A target that left, or is covered, matches
    as poorly once relit: the frame stays lost. Only frames the gate would call lost pay for
    it (one frame scaling, one histogram); ``gate_contrast = 0`` turns it off with the rest of
    the second look.

    Confidence: the best particle's rho of the HSI histograms, max_i rho(q, p_i), of the
    frame as it is (the relit look does not enter it); 0 on a constant frame.
    """

    name = "hsi-color-pf"

    def model(self, frame, box):
        super().model(frame, box)
        self._intensity = _mean_intensity(frame)   # of the last frame that was not lost
        self.relit_match = float("nan")

    def features(self, frame, boxes):
        return hsi_histograms(frame, boxes)

    def _stands_out(self, frame, particles) -> bool:
        return super()._stands_out(frame, particles) or self._relit_passes(frame, particles)

    def _update(self, frame):
        ok, box = super()._update(frame)
        if ok:
            self._intensity = _mean_intensity(frame)
        return ok, box

    def _relit_passes(self, frame, particles) -> bool:
        """The relit look of the class docstring: whether the best particle, scored on the
        frame scaled to the mean intensity of the last frame that was not lost, passes the
        distance gate. Off with the second look (``gate_contrast = 0``)."""
        intensity = _mean_intensity(frame)
        if self.gate_contrast <= 0 or intensity <= 0.0:
            return False
        relit = cv2.convertScaleAbs(frame, alpha=self._intensity / intensity)
        m = self._match
        best = particles[int(np.nanargmax(m))][None, :]
        saved = {k: getattr(self, k) for k in self._probe_keeps if hasattr(self, k)}
        self.likelihood(relit, best)
        self.relit_match = float(np.nanmax(self._match))
        for k, v in saved.items():
            setattr(self, k, v)
        self._match = m
        return not self._outside_range(self.relit_match)
