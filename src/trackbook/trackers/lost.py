"""Shared pieces of the trackers' lost rules: how much of a box is in view, a relative gate on
a match, and a colour check with a bounded whole-frame search.

A tracker whose own observation model cannot say "the target is not here" (edge rays: a
textured background has edges everywhere; OpenCV's MIL: its classifier's response is not
exposed) checks its estimate against the first frame's kernel colour histogram (eq. 1 of Lee
et al. 2012, HSV 8 x 8 x 4 bins), and while lost searches the whole frame for it with
:meth:`ColourCheck.search`, at a cost bounded by ``max_boxes`` histograms per frame.
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


def visible_fraction(box, frame_shape) -> float:
    """Fraction of the area of ``box = (x, y, w, h)`` that lies inside the frame."""
    H, W = frame_shape[:2]
    x, y, w, h = (float(v) for v in box)
    if w <= 0 or h <= 0:
        return 0.0
    iw = max(0.0, min(x + w, W) - max(x, 0.0))
    ih = max(0.0, min(y + h, H) - max(y, 0.0))
    return iw * ih / (w * h)


class MatchGate:
    """The distance gate of :class:`~trackbook.trackers.particle_filter.ParticleFilterTracker`
    for one number per frame: a frame is lost when its match ``m = 1 - D^2`` is below
    ``below`` and its ``D^2`` is above ``med + k max(1.4826 MAD, med / 2)`` of the last
    ``window`` frames that passed (the first five pass); a match below ``floor`` is lost
    whatever the range, so a slow drift off the target cannot teach the gate that a poor match
    is normal. After ``patience`` lost frames in a row the range is rebuilt."""

    def __init__(self, below=0.7, k=3.0, window=30, patience=30, floor=0.5):
        self.below, self.k, self.window, self.patience, self.floor = below, k, window, \
            patience, floor
        self.history: list = []
        self.lost_in_a_row = 0

    def lost(self, match: float, second_look=None) -> bool:
        """Whether a frame whose best match is ``match`` is lost (and record it if not).

        ``second_look()``, if given, is asked only when the range test fires (not below
        ``floor``): True keeps the frame (not lost, not recorded in the range)."""
        d2 = 1.0 - float(match)
        if not np.isfinite(d2) or match < self.floor:
            self.lost_in_a_row += 1
            return True
        if self.lost_in_a_row >= self.patience:
            self.history.clear()
        h = self.history
        if len(h) >= 5 and match < self.below:
            v = np.asarray(h)
            med = float(np.median(v))
            spread = max(1.4826 * float(np.median(np.abs(v - med))), med / 2.0)
            if d2 > med + self.k * spread:
                if second_look is not None and second_look():
                    self.lost_in_a_row = 0
                    return False
                self.lost_in_a_row += 1
                return True
        h.append(d2)
        del h[:-self.window]
        self.lost_in_a_row = 0
        return False


class ColourCheck:
    """The first frame's kernel colour histogram of the target, to check boxes against.

    Parameters
    ----------
    frame : (H, W, 3) uint8 BGR, the first frame
    box : (x, y, w, h), the target on it
    """

    def __init__(self, frame, box):
        self.reference = self.histograms(frame, np.asarray(box, float)[None])[0]
        self.size = np.asarray(box, float)[2:4].copy()

    @staticmethod
    def histograms(frame, boxes) -> np.ndarray:
        patches = sample_patches(frame, np.asarray(boxes, float), PATCH_SIZE)
        return weighted_histograms(hsv_bin_index_u8(patches, HSV_BINS), _KERNEL, _N_BINS)

    def match(self, frame, boxes) -> np.ndarray:
        """rho (Bhattacharyya coefficient) of every box against the reference."""
        return bhattacharyya_coefficient(self.histograms(frame, boxes), self.reference)

    def match_near(self, frame, box, slack: float = 0.25):
        """Best rho of ``box`` and its eight shifts by ``slack`` of its size (a box placed by
        another cue, e.g. MIL's, need not be where the colour fits best). Returns
        ``(rho, box)``; cost: 9 histograms."""
        b = np.asarray(box, float)
        d = np.array([(i, j) for j in (-1, 0, 1) for i in (-1, 0, 1)]) * slack * b[2:]
        boxes = np.column_stack([b[:2] + d, np.tile(b[2:], (9, 1))])
        rho = self.match(frame, boxes)
        i = int(np.argmax(rho))
        return float(rho[i]), boxes[i]

    def stands_out(self, frame, box, rho, contrast=0.12, floor=0.5) -> bool:
        """The second look of ``ParticleFilterTracker``: whether ``rho`` (the match of
        ``box``) is at least ``floor`` and beats the median match of eight boxes of its size
        1.5 box sizes around it by ``contrast`` (the target under a sudden change of light
        stays the best match around; a target that left leaves no such peak)."""
        if rho < floor:
            return False
        H, W = frame.shape[:2]
        b = np.asarray(box, float)
        off = np.array([(-1.5, 0), (1.5, 0), (0, -1.5), (0, 1.5), (-1.5, -1.5), (1.5, -1.5),
                        (-1.5, 1.5), (1.5, 1.5)]) * b[2:]
        c = b[:2] + b[2:] / 2 + off
        c = c[(c[:, 0] >= 0) & (c[:, 0] < W) & (c[:, 1] >= 0) & (c[:, 1] < H)]
        if len(c) < 2:
            return False
        probes = np.column_stack([c - b[2:] / 2, np.tile(b[2:], (len(c), 1))])
        return rho - float(np.median(self.match(frame, probes))) >= contrast

    def search(self, frame, max_boxes: int = 300, size=None):
        """Best box of ``size`` (default the first box's) over the whole frame: centres on a
        grid of at most ``max_boxes`` points, refined once on a grid a quarter as fine around
        the best. Returns ``(box, rho)``; cost: at most ``2 * max_boxes`` histograms."""
        H, W = frame.shape[:2]
        w, h = self.size if size is None else size
        step = max(np.sqrt(W * H / max_boxes), 1.0)
        xs = np.arange(step / 2, W, step)
        ys = np.arange(step / 2, H, step)
        best, rho = self._best(frame, xs, ys, w, h)
        f = step / 4
        xs = best[0] + w / 2 + f * np.arange(-2, 3)
        ys = best[1] + h / 2 + f * np.arange(-2, 3)
        best2, rho2 = self._best(frame, xs, ys, w, h)
        return (best2, rho2) if rho2 > rho else (best, rho)

    def _best(self, frame, xs, ys, w, h):
        X, Y = np.meshgrid(xs, ys)
        n = X.size
        boxes = np.column_stack([X.ravel() - w / 2, Y.ravel() - h / 2, np.full(n, w),
                                 np.full(n, h)])
        rho = self.match(frame, boxes)
        i = int(np.argmax(rho))
        return boxes[i], float(rho[i])
