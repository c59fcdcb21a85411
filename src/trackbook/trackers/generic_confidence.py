"""The failure layer's generic confidence: the colour match of a box against the first frame.

Where an algorithm defines no confidence of its own that can say "the target is not here"
(edge rays: a textured background has edges everywhere; OpenCV's MIL: its classifier's
margin is not exposed), the tracker reports instead the Bhattacharyya coefficient of its
box's kernel colour histogram against the first frame's (eq. 1 of Lee et al. 2012, HSV
8 x 8 x 4 bins, the patch resampled to 16 x 24). The failure-detection layer judges that
number like any other confidence.
"""

from __future__ import annotations

import numpy as np

from ..features.color import (HSV_BINS, bhattacharyya_coefficient, hsv_bin_index_u8,
                              kernel_weights, weighted_histograms)
from ..features.patches import sample_patches

#: Patch every box is resampled to before its histogram is taken (as Lee et al. 2012).
PATCH_SIZE = (16, 24)
_KERNEL = kernel_weights(PATCH_SIZE[1], PATCH_SIZE[0])
_N_BINS = int(np.prod(HSV_BINS))


class ColourCheck:
    """The first frame's kernel colour histogram of the target, to check boxes against.

    Parameters
    ----------
    frame : (H, W, 3) uint8 BGR, the first frame
    box : (x, y, w, h), the target on it
    """

    def __init__(self, frame, box):
        self.reference = self.histograms(frame, np.asarray(box, float)[None])[0]

    @staticmethod
    def histograms(frame, boxes) -> np.ndarray:
        """The kernel colour histogram of every box (rows sum to 1)."""
        patches = sample_patches(frame, np.asarray(boxes, float), PATCH_SIZE)
        return weighted_histograms(hsv_bin_index_u8(patches, HSV_BINS), _KERNEL, _N_BINS)

    def match(self, frame, boxes) -> np.ndarray:
        """rho (Bhattacharyya coefficient) of every box against the reference."""
        return bhattacharyya_coefficient(self.histograms(frame, boxes), self.reference)


__all__ = ["ColourCheck", "PATCH_SIZE"]
