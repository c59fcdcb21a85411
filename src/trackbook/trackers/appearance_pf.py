"""What the two baselines of Kim, Kim & Choi 2016 share: ``hsi-color-pf``
(:mod:`.hsi_color_pf`) and ``hog-pf`` (:mod:`.hog_pf`).

The paper names them only ("HSI colour model based particle filter", "particle filter using
HOG") [quote: kim2016.baselines]. To compare observation models and nothing else, both share everything with
``edge-ray-pf`` (state (x, y), fixed box, random walk plus the estimated motion, eq. 7
estimate, resampling, behaviour while lost: :class:`CentreParticleFilter`) and weigh a particle by

    w = exp(-D^2 / (2 sigma^2)),   D^2 = 1 - rho(q, p)

with rho the Bhattacharyya coefficient between the model's and the particle's histogram
(Nummiaro et al. 2003).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..features.color import bhattacharyya_coefficient
from ..params import NOT_PRINTED, param
from .centre_pf import CentreParticleFilter, CentrePFParams


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
        "their settings [quote: kim2016.baselines]; 0.2 is the book's choice (the particle-filter "
        "and HOG chapters)")


class AppearancePF(CentreParticleFilter):
    """Centre particle filter weighted by a histogram compared with the Bhattacharyya coefficient.

    Attributes
    ----------
    reference : the model histogram of the initial box.
    particles, weights, likelihoods, estimate, lost : see ``ParticleFilterTracker``.

    Confidence: ``state().confidence`` is the best particle's Bhattacharyya coefficient of the
    last frame, max_i rho(q, p_i) = 1 - min_i D^2_i, in [0, 1]; 0 on a constant frame. The
    paper's trackers have no lost state: ``ok`` comes from the failure-detection layer judging
    that confidence; the ``-redetect`` names add the re-detection layer (boxes over the whole
    frame scored by the same rho).
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
        self._match = np.clip(1.0 - d2, 0.0, 1.0)        # rho, the confidence
        return np.exp(-np.clip(d2, 0.0, None) / (2.0 * self.params.obs_sigma ** 2))
