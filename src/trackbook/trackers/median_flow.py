"""Median Flow (Kalal, Mikolajczyk & Matas 2010, "Forward-Backward Error: Automatic Detection of
Tracking Failures", ICPR): a box tracked by the points inside it.

On every frame:

1. A 10 x 10 grid of points is laid in the last box and tracked by pyramidal Lucas-Kanade
   from the last frame to this one and back
   (:func:`trackbook.filters.lucas_kanade.forward_backward`); each point gets its
   forward-backward error FB and the zero-mean NCC between the patches around it in the two
   frames (:func:`trackbook.filters.template_matching.patch_ncc`).
2. Failure, as in the authors' released code: the median FB of the grid above
   ``fb_threshold`` (10 px) means the motion cannot be trusted: ``ok=False``, the box stays.
3. Otherwise the points with FB at most the median and NCC at least the median are kept (the
   paper drops the worse half of the predictions; the authors' code applies the two median
   tests together, which keeps at most half); the box moves by the median of their
   displacements and scales by the median of the ratios of their pairwise distances after
   and before.

The failure-detection layer judges the confidence below on every frame besides Median Flow's
own rule (step 2): a frame it judges lost, or a frame whose grey levels span at most
``flat_range``, keeps the last box, and the next frame's flow starts from the last frame
judged on target and its box (the last frame is the only model Median Flow has).
``median-flow-redetect`` adds the re-detection layer: while lost, boxes of the last size over
the whole frame are scored by their zero-mean NCC with the first frame's patch (Median Flow
has no appearance model of its own; TLD, Kalal et al.'s later tracker, pairs it with a
detector) and the flow restarts from the best.

The book's addition ``normalise`` gives each frame's grey levels one mean and standard
deviation before the flow, so a camera's exposure change does not break brightness constancy.

Confidence: the forward-backward error certifies that the points moved as the flow says, not
that they belong to the target: on a textured background the points follow while the target
is gone, their error is as small as on the target, so it cannot say "the target is not here"
(the chapter "Template matching and optical flow" shows it on ``occluder``).
``state().confidence`` is therefore the failure layer's generic one, as for ``edge-ray-pf``:
the Bhattacharyya coefficient rho between the kernel colour histogram of the box the flow
placed and that of the first box
(:meth:`~trackbook.trackers.generic_confidence.ColourCheck.match`), in [0, 1]; where the flow
placed no box (a flat frame, a median FB above ``fb_threshold`` or infinite because more than
half the points were lost, fewer than two points kept), that of the box the flow started
from. The colour never moves the box, and Median Flow's own rule (step 2) still fails a frame
whatever the colour says; ``fb_error`` keeps the frame's median FB error.

>>> from trackbook import trackers, clips
>>> clip = clips.load("red-cube")                                       # doctest: +SKIP
>>> t = trackers.create("median-flow")                                  # doctest: +SKIP
>>> t.init(clip.frames[0], clip.groundtruth[0])                         # doctest: +SKIP
>>> ok, box = t.update(clip.frames[1]); t.state().confidence            # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses

import cv2
import numpy as np

from ..filters import lucas_kanade as lk
from ..features.patches import sample_patches
from ..filters import template_matching as tm
from ..params import NOT_PRINTED, param
from .base import Tracker, redetecting
from .generic_confidence import ColourCheck
from .registry import register


@dataclasses.dataclass(frozen=True)
class MedianFlowParams:
    # Kalal, Mikolajczyk, Matas, ICPR 2010: the grid in the box, the worse half dropped and
    # the medians are the paper's; the 10 x 10 grid, the two median tests (FB and NCC) and the
    # 10 px failure rule are also those of the authors' released TLD code;
    # the Lucas-Kanade settings are the book's.
    grid: int = param(
        10, 2, 30, 1, doc="points per side of the grid laid in the box (grid x grid points)",
        paper=10)           # Kalal et al. 2010: a 10 x 10 grid of points in the box
    fb_threshold: float = param(
        10.0, 0.5, 100.0, 0.5, doc="median forward-backward error (px) above which the frame "
        "is a tracking failure", paper=10.0)
    # the authors' released code (OpenTLD's tldTrack.m, BIG_FB = 10): failure when the median
    # FB error exceeds 10 px
    half_win: int = param(
        5, 1, 20, 1, doc="Lucas-Kanade window half-side r (px): a (2r + 1) x (2r + 1) window",
        paper=NOT_PRINTED,
        why="not printed in the paper; an 11 px window keeps inside a small target's box "
            "while holding enough texture for the 2 x 2 system")
    levels: int = param(
        3, 1, 6, 1, doc="pyramid levels of Lucas-Kanade (1: full resolution only)",
        paper=NOT_PRINTED,
        why="not printed in the paper; three levels reach motions of about 4 x the window "
            "half-width, more than the sample clips move in a frame")
    ncc_window: int = param(
        11, 3, 41, 1, doc="side (px) of the patches around a point compared by NCC",
        paper=NOT_PRINTED,
        why="not printed in the paper; the same side as the Lucas-Kanade window, so a point's "
            "NCC judges the pixels its flow was solved on")
    normalise: bool = param(
        True, doc="scale each frame's grey levels to one mean and spread before the flow",
        paper=NOT_PRINTED, paper_value=False,
        why="the book's addition: a camera's exposure jump (robot-corridor-day's mean grey "
            "level falls from 120 to 66 in one frame) breaks brightness constancy for every "
            "point at once, and the FB rule then fails a target that did not move")


@register
class MedianFlowTracker(Tracker):
    """Median Flow (Kalal, Mikolajczyk & Matas 2010); the module docstring has the steps, the
    failure rule (the released code's median FB > ``fb_threshold``, then the failure-detection
    layer),
    the book's addition and the confidence; ``median-flow-redetect`` adds the re-detection
    layer.

    Attributes (read-only, for drawing)
    -----------------------------------
    points : (n, 2) the grid points kept on the last frame, where they landed (empty when
        the flow did not place the box)
    fb_error : median forward-backward error of the last frame's grid (px; inf when none)
    """

    name = "median-flow"
    Params = MedianFlowParams

    def _grey(self, frame):
        """The frame's grey levels, with ``normalise`` mapped to mean 128 and standard
        deviation 50 (a global gain and offset, so an exposure change cancels)."""
        g = lk.to_gray(frame)
        if self.params.normalise:
            g = (g - g.mean()) * np.float32(50.0 / max(float(g.std()), 1.0)) + np.float32(128.0)
        return g

    def _init(self, frame, box):
        g = self._grey(frame)
        self._pyr = lk.pyramid(g, self.params.levels)
        self._from = np.asarray(box, float)        # the box the next flow starts from
        x, y, w, h = box
        self._template = cv2.getRectSubPix(g, (max(int(round(w)), 3), max(int(round(h)), 3)),
                                           (x + w / 2.0 - 0.5, y + h / 2.0 - 0.5))
        self._colour = ColourCheck(frame, box)
        self._located = None
        self.fb_error = float("inf")
        self.points = np.zeros((0, 2))

    def _grid(self, box):
        x, y, w, h = box
        n = self.params.grid
        t = (np.arange(n) + 0.5) / n
        gx, gy = np.meshgrid(x + t * w, y + t * h)
        return np.stack([gx.ravel(), gy.ravel()], 1)

    def _flow(self, pyr, box):
        """One Median Flow step from the last frame's pyramid to ``pyr``: the new box, or None
        on failure; sets ``fb_error`` and ``points``."""
        p = self.params
        pts = self._grid(box)
        fwd, fb, status = lk.forward_backward(self._pyr, pyr, pts, win=2 * p.half_win + 1,
                                              levels=p.levels)
        self.fb_error = float(np.median(fb))              # inf when over half were lost
        if not self.fb_error <= p.fb_threshold or status.sum() < 2:
            return None
        ncc = np.full(len(pts), -np.inf)
        ncc[status] = tm.patch_ncc(lk.patches_at(self._pyr[0], pts[status], p.ncc_window),
                                   lk.patches_at(pyr[0], fwd[status], p.ncc_window))
        fb_ok, ncc_ok = fb[status], ncc[status]
        keep = status & (fb <= np.median(fb_ok)) & (ncc >= np.median(ncc_ok))
        if keep.sum() < 2:
            return None
        a, b = pts[keep], fwd[keep]
        d = np.median(b - a, axis=0)
        i, j = np.triu_indices(len(a), 1)
        before = np.linalg.norm(a[i] - a[j], axis=1)
        after = np.linalg.norm(b[i] - b[j], axis=1)
        s = float(np.median(after[before > 0] / before[before > 0]))
        self.points = b.copy()
        x, y, w, h = box
        cx, cy = x + w / 2.0 + d[0], y + h / 2.0 + d[1]
        return np.array([cx - s * w / 2.0, cy - s * h / 2.0, s * w, s * h])

    def _locate(self, frame):
        """One Median Flow step from the last frame judged on target (its pyramid and box) to
        ``frame``. Returns the box, its colour match with the first box (the confidence; of
        the box the flow started from where it placed none) and whether Median Flow's own
        rule passed (median FB at most ``fb_threshold``, at least two points kept)."""
        self.points = np.zeros((0, 2))
        self.fb_error = float("inf")
        self._located = None
        if self._is_flat(frame):
            return self._from, self._match(frame, self._from), False
        pyr = lk.pyramid(self._grey(frame), self.params.levels)
        box = self._flow(pyr, self._from)
        if box is None:
            self.points = np.zeros((0, 2))
            return self._from, self._match(frame, self._from), False
        self._located = pyr
        return box, self._match(frame, box), True

    def _match(self, frame, box) -> float:
        """The confidence: rho of ``box``'s colour histogram against the first box's."""
        return float(self._colour.match(frame, np.asarray(box, float)[None])[0])

    def _learn(self, frame, box):
        """The next flow starts from this frame and ``box``."""
        self._pyr = self._located
        self._from = np.asarray(box, float)

    def _score_boxes(self, frame, boxes):
        """For re-detection: the zero-mean NCC of each box's patch, resampled to the first
        frame's box size, with the first frame's patch (vectorised; nothing is changed)."""
        g = self._grey(frame)
        th, tw = self._template.shape
        patches = sample_patches(g, np.asarray(boxes, float), (tw, th))
        return tm.patch_ncc(patches, np.broadcast_to(self._template, patches.shape))

    def _relocate(self, frame, box):
        """Restart the flow from ``frame`` with ``box``."""
        self._pyr = lk.pyramid(self._grey(frame), self.params.levels)
        self._from = np.asarray(box, float)


register(redetecting(MedianFlowTracker))

__all__ = ["MedianFlowParams", "MedianFlowTracker"]
