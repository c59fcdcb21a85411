"""A particle filter over the box centre only: the common frame of the kim2016 trackers.

Kim, Kim & Choi 2016 track the state X = {x, y} (eq. 3) with a fixed box, and compare their
edge observation model with an HSI-colour and a HOG particle filter. To make that comparison
about the observation model alone, all three trackers share this class: the same state, the
same motion model (random walk plus the estimated motion), the same resampling and estimate
(eq. 7), and the same behaviour when every particle scores zero (no estimate: lost). Each subclass only says how
a particle is weighted (``likelihood``).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .particle_filter import ParticleFilterTracker, resampler_param
from ..params import NOT_PRINTED, param


@dataclasses.dataclass(frozen=True)
class CentrePFParams:
    """The knobs every kim2016 tracker shares: the filter, not the observation model."""

    # Kim et al. (2016), section 3 before eq. 2: "at most 999 particles" (최대 999개): a
    # maximum, not a setting, so 999 in the paper preset is the book's reading of it.
    n_particles: int = param(
        300, 1, 999, 1, "N, number of particles (Kim et al. 2016: at most 999)",
        reading="kim2016.max999", paper=999,
        why="the paper gives only a maximum, at most 999 particles [quote: kim2016.max999]; "
        "the paper preset reads it as the setting, and 300 keeps a chapter's clips within "
        "seconds")
    sigma: float = param(
        4.0, 0.5, 40.0, 0.5, "random-walk sigma of the prediction (and of the Gaussian start "
        "spread around the box centre), pixels", paper=NOT_PRINTED,
        why="no spread is printed (only 'N random particles with equal weights' "
        "[quote: kim2016.init_equal_weights]); 4 px is the book's choice, "
        "tuned on the seven public sequences")
    velocity_gain: float = param(
        1.0, 0.0, 1.0, 0.05, "fraction g of the last motion of the estimate added in the "
        "prediction", paper=NOT_PRINTED, paper_value=1.0,
        why="the prediction step of section 3 moves the particles 'by the object's displacement' with no factor; "
        "the book reads that as g = 1")
    resampler: str = resampler_param(
        "resampling scheme", paper=NOT_PRINTED,
        why="Table 2 says 'resample with the updated weights' without a scheme; "
        "multinomial is the textbook SIR choice")


class CentreParticleFilter(ParticleFilterTracker):
    """SIR particle filter on the centre ``(x, y)`` of a box of fixed size (scale a hook).

    Params (:class:`CentrePFParams`, which a subclass's ``Params`` extends): ``n_particles``,
    ``sigma`` (the random-walk standard deviation in pixels), ``velocity_gain``,
    ``resampler``.

    Motion model: ``x_t = x_{t-1} + v + N(0, sigma^2)``, with ``v = g (C_t - C_{t-1})`` the
    last change of the accepted estimate times the gain ``g = velocity_gain`` (1 by default,
    the book's reading of the paper's prediction step, which prints no gain). A gain below 1
    damps a velocity measured from two noisy estimates (``03_hog`` measures it).

    While lost (frames the failure-detection layer judges lost) the estimate does not move,
    so the motion it measures is zero: the particles move by the random walk alone, from
    where they are; and the first accepted frame after a lost spell sets ``v = 0`` (the jump
    back is a relocation, not a motion). ``v = 0`` also right after ``init``.

    Attributes
    ----------
    velocity : (2,) the estimated motion per frame added in the prediction.
    spread : the random-walk sigma of the prediction (``sigma``).
    scale : the box scale relative to the initial box (1 unless a subclass estimates it).
    """

    def model(self, frame, box):
        self._size = np.asarray(box[2:4], dtype=float)
        self.velocity = np.zeros(2)
        self.spread = float(self.params.sigma)
        self.scale = 1.0

    def initial_particles(self, frame, box):
        c = self.box_to_state(box)
        n = int(self.params.n_particles)
        return self._clip(c + self.rng.normal(0.0, self.params.sigma, size=(n, 2)))

    def _clip(self, xy):
        return np.clip(xy, 0.0, self._frame_wh - 1e-6)

    def predict(self, particles):
        # a lost frame kept the estimate where it was: its measured motion is zero
        v = self.velocity if self.ok else 0.0
        moved = particles + v + self.rng.normal(0.0, self.spread, size=particles.shape)
        return self._clip(moved)

    def _learn(self, frame, box):
        previous = np.array(self.estimate, dtype=float)
        super()._learn(frame, box)
        # right after a lost spell the jump back is a relocation, not a motion
        g = float(self.params.velocity_gain)
        self.velocity = g * (self.estimate - previous) if self.ok else np.zeros(2)

    def box_to_state(self, box):
        b = np.asarray(box, dtype=float)
        return b[:2] + b[2:4] / 2.0

    def state_to_box(self, state):
        w, h = self._size * self.scale
        return np.array([state[0] - w / 2.0, state[1] - h / 2.0, w, h])
