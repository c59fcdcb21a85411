"""The two baselines of Kim, Kim & Choi 2016: ``hsi-color-pf`` (method 1) and ``hog-pf`` (2).

The paper names them only ("HSI colour model based particle filter", "particle filter using
HOG") [quote: kim2016.baselines]. To compare observation models and nothing else, both share everything with
``edge-ray-pf`` (state (x, y), fixed box, random walk plus the estimated motion, eq. 7
estimate, resampling, lost handling: :class:`CentreParticleFilter`) and weigh a particle by

    w = exp(-D^2 / (2 sigma^2)),   D^2 = 1 - rho(q, p)

with rho the Bhattacharyya coefficient between the model's and the particle's histogram
(Nummiaro et al. 2003). ``hsi-color-pf`` uses the kernel HSI histogram of
:mod:`trackbook.features.hsi`; ``hog-pf`` the HOG of Lee et al. 2012
(:func:`trackbook.features.hog.hog_descriptors`, 16 x 24 patch, 192 values summing to 1).
"""

from __future__ import annotations

import dataclasses

import cv2
import numpy as np

from ..features.color import bhattacharyya_coefficient
from ..features.hog import hog_descriptors
from ..features.hsi import hsi_histograms
from ..params import NOT_PRINTED, param
from .centre_pf import CentreParticleFilter, CentrePFParams
from .particle_filter import lost_below_param, lost_k_param
from .registry import register


@dataclasses.dataclass(frozen=True)
class AppearanceParams(CentrePFParams):
    n_particles: int = param(
        300, 1, 999, 1, "N, number of particles", paper=NOT_PRINTED, paper_value=999,
        why="the paper prints no setting of its baselines; 300 as for edge-ray-pf, and the "
        "paper preset gives them the proposed filter's 999 [quote: kim2016.max999] so that the "
        "three filters differ in their observation model only (a reading)")
    obs_sigma: float = param(
        0.2, 0.01, 1.0, 0.01, "sigma of the likelihood exp(-D^2 / 2 sigma^2)",
        paper=NOT_PRINTED,
        why="Kim et al. (2016) name the HSI and HOG filters they compare with but print none of "
        "their settings [quote: kim2016.baselines]; 0.2 is the book's choice (02_particle_filters, 03_hog)")
    # The book's distance gate (02_particle_filters): the paper's trackers have no lost state.
    lost_below: float = lost_below_param()
    lost_k: float = lost_k_param()


class _AppearancePF(CentreParticleFilter):
    """Centre particle filter weighted by a histogram compared with the Bhattacharyya coefficient.

    Attributes
    ----------
    reference : the model histogram of the initial box.
    particles, weights, likelihoods, estimate, lost : see ``ParticleFilterTracker``.

    Confidence: ``state().confidence`` is the best particle's Bhattacharyya coefficient of the
    last frame, max_i rho(q, p_i) = 1 - min_i D^2_i, in [0, 1]; 0 on a constant frame.
    """

    Params = AppearanceParams

    def features(self, frame, boxes):  # pragma: no cover
        raise NotImplementedError

    def model(self, frame, box):
        super().model(frame, box)
        self.reference = self.features(frame, np.asarray(box, dtype=float)[None, :])[0]

    def _boxes(self, particles):
        w, h = self._size * self.scale
        n = particles.shape[0]
        return np.column_stack([particles[:, 0] - w / 2, particles[:, 1] - h / 2,
                                np.full(n, w), np.full(n, h)])

    def likelihood(self, frame, particles):
        feats = self.features(frame, self._boxes(particles))
        d2 = 1.0 - bhattacharyya_coefficient(feats, self.reference)
        self._match = np.clip(1.0 - d2, 0.0, 1.0)        # rho, for the lost gate
        return np.exp(-np.clip(d2, 0.0, None) / (2.0 * self.params.obs_sigma ** 2))


def _mean_intensity(frame) -> float:
    """Mean over the frame of the HSI intensity I = (R + G + B) / 3, in grey levels."""
    return float(np.mean(cv2.mean(frame)[:3]))


@register
class HSIColorPF(_AppearancePF):
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


@register
class HOGPF(_AppearancePF):
    """Baseline (2) of Kim et al. 2016: HOG (Lee et al. 2012, 192 values) particle filter.

    Confidence: the best particle's Bhattacharyya coefficient of the HOGs, max_i rho(q, p_i),
    in [0, 1]; 0 on a constant frame.
    """

    name = "hog-pf"
    #: No second look: a textured background's HOG stands out from its surroundings as much
    #: as the target's does, so only the distance gate decides (see ``ParticleFilterTracker``).
    gate_contrast = 0.0

    def features(self, frame, boxes):
        return hog_descriptors(frame, boxes)
