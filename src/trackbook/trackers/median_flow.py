"""Median Flow (Kalal, Mikolajczyk & Matas 2010, "Forward-Backward Error: Automatic Detection of
Tracking Failures", ICPR): a box tracked by the points inside it.

On every frame:

1. A 10 x 10 grid of points is laid in the last box and tracked by pyramidal Lucas-Kanade
   from the last frame to this one and back
   (:func:`trackbook.filters.lucas_kanade.forward_backward`); each point gets its
   forward-backward error FB and the zero-mean NCC between the patches around it in the two
   frames (:func:`trackbook.filters.template_matching.patch_ncc`).
2. Failure, as published: the median FB of the grid above ``fb_threshold`` (10 px) means the
   motion cannot be trusted: ``ok=False``, the box stays.
3. Otherwise the points with FB at most the median and NCC at least the median are kept (the
   published filter: about half survive); the box moves by the median of their displacements
   and scales by the median of the ratios of their pairwise distances after and before.

The book's additions, so that "lost" means lost (each can be switched off):

- ``normalise``: each frame's grey levels are given one mean and standard deviation before
  the flow, so a camera's exposure change does not break brightness constancy;
- a frame whose grey levels span at most ``flat_range`` is lost (nothing to track), and a box
  with less than ``min_visible`` of its area in the frame is lost (the target is leaving);
- ``redetect``: while lost, the flow is still run from the last box, and resumes tracking
  only if its box passes the rules above and its patch, resampled to the first frame's box
  size, has an NCC of at least ``resume_ncc`` with the first frame's patch (a box left on an
  occluder or on the background moves consistently forward and backward, so the FB rule
  alone would call it found). Otherwise the first frame's patch, resized to the last box,
  is matched over the whole frame (:func:`trackbook.filters.template_matching.ncc_map`); a
  peak of at least ``redetect_ncc`` places the box there and tracking resumes. Median Flow
  has no detector: TLD (Kalal et al.'s later tracker) pairs it with one; this is the
  plainest.

Confidence: ``state().confidence`` is minus the median FB error (pixels) of the grid on the
frame the box was placed by the flow; on a frame where no flow placed it (a flat frame, a
frame after a flat one, a lost frame, a median FB that is infinite because more than half the
points were lost) it is minus the frame's diagonal, the largest distance in the frame; on a
re-detected frame minus ``fb_threshold`` (accepted, but not by the flow).

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
from ..filters import template_matching as tm
from ..params import NOT_PRINTED, param
from .base import Tracker
from .lost import visible_fraction
from .registry import register


@dataclasses.dataclass(frozen=True)
class MedianFlowParams:
    # Kalal, Mikolajczyk, Matas, ICPR 2010: the grid, the half kept and the 10 px failure rule
    # are the paper's; the Lucas-Kanade settings are not printed there.
    grid: int = param(
        10, 2, 30, 1, doc="points per side of the grid laid in the box (grid x grid points)",
        paper=10)           # Kalal et al. 2010: a 10 x 10 grid of points in the box
    fb_threshold: float = param(
        10.0, 0.5, 100.0, 0.5, doc="median forward-backward error (px) above which the frame "
        "is a tracking failure", paper=10.0)   # Kalal et al. 2010: failure when median FB > 10 px
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
    min_visible: float = param(
        0.5, 0.0, 1.0, 0.05, doc="a box with less than this fraction of its area in the "
        "frame is lost (the target is leaving)",
        paper=NOT_PRINTED, paper_value=0.0,
        why="the book's rule, as every tracker's: points at the border are lost one by one "
            "and the rest follow the background left in the box")
    resume_ncc: float = param(
        0.3, -1.0, 1.0, 0.05, doc="while lost, the flow from the last box resumes tracking "
        "only if the box's NCC with the first frame's patch reaches this",
        paper=NOT_PRINTED,
        why="the book's addition (part of redetect): while the target is hidden the box "
            "rests on the occluder or background, whose flow is consistent forward and "
            "backward; their NCC with "
            "the first patch is 0.2 on the lost-matrix occluder scene, the target's mostly "
            "above 0.3 on the sample clips (its 5th percentile on shelves 0.33)")
    redetect: bool = param(
        True, doc="while lost, resume by the flow (resume_ncc) or by matching the first "
        "frame's patch over the whole frame (redetect_ncc)",
        paper=NOT_PRINTED, paper_value=False,
        why="the book's addition: Median Flow has no detector, so a target that left the "
            "view is never found again without one")
    redetect_ncc: float = param(
        0.6, 0.0, 1.0, 0.05, doc="a re-detected window's NCC with the first frame's patch "
        "must reach this", paper=NOT_PRINTED,
        why="the book's addition (redetect): the best window of a frame without the target "
            "reaches an NCC of 0.32 (edge-exit scene) to 0.50 (occluder scene) with the first "
            "patch; the returning target is found on the first frame it is whole")


@register
class MedianFlowTracker(Tracker):
    """Median Flow (Kalal, Mikolajczyk & Matas 2010); the module docstring has the steps, the
    book's additions and the confidence.

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
        x, y, w, h = box
        self._template = cv2.getRectSubPix(g, (max(int(round(w)), 3), max(int(round(h)), 3)),
                                           (x + w / 2.0 - 0.5, y + h / 2.0 - 0.5))
        self._lost = False
        self._diag = float(np.hypot(*frame.shape[:2]))
        self._confidence = -self._diag
        self.fb_error = float("inf")
        self.points = np.zeros((0, 2))

    def _last_confidence(self):
        return self._confidence

    def _grid(self, box):
        x, y, w, h = box
        n = self.params.grid
        t = (np.arange(n) + 0.5) / n
        gx, gy = np.meshgrid(x + t * w, y + t * h)
        return np.stack([gx.ravel(), gy.ravel()], 1)

    def _template_ncc(self, gray, box) -> float:
        """NCC of ``box``'s patch, resampled to the first frame's box size, with its patch."""
        x, y, w, h = box
        th, tw = self._template.shape
        patch = cv2.getRectSubPix(gray, (max(int(round(w)), 3), max(int(round(h)), 3)),
                                  (x + w / 2.0 - 0.5, y + h / 2.0 - 0.5))
        patch = cv2.resize(patch, (tw, th), interpolation=cv2.INTER_AREA)
        return float(tm.patch_ncc(patch[None], self._template[None])[0])

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
        self.points = b
        x, y, w, h = box
        cx, cy = x + w / 2.0 + d[0], y + h / 2.0 + d[1]
        return np.array([cx - s * w / 2.0, cy - s * h / 2.0, s * w, s * h])

    def _redetect(self, gray):
        """The best window of the first patch, resized to the last box, over the frame."""
        H, W = gray.shape
        _, _, w, h = self.bbox
        w, h = int(round(min(max(w, 3), W))), int(round(min(max(h, 3), H)))
        t = cv2.resize(self._template, (w, h), interpolation=cv2.INTER_AREA)
        r = tm.ncc_map(gray, t)
        bx, by = tm.best_match(r, "ncc")
        if r[by, bx] < self.params.redetect_ncc:
            return None
        return np.array([bx, by, w, h], float)

    def _update(self, frame):
        p = self.params
        self.points = np.zeros((0, 2))
        self.fb_error = float("inf")
        self._confidence = -self._diag
        if self._is_flat(frame):
            self._pyr = None       # no flow from a flat frame: the target must be found again
            self._lost = True
            return False, self.bbox
        g = self._grey(frame)
        pyr = lk.pyramid(g, p.levels)
        box = None
        if self._pyr is not None and (p.redetect or not self._lost):
            box = self._flow(pyr, np.asarray(self.bbox, float))
            if box is not None and (visible_fraction(box, frame.shape) < p.min_visible or (
                    self._lost and self._template_ncc(g, box) < p.resume_ncc)):
                box = None
            if box is not None:
                self._confidence = -self.fb_error
        if box is None and self._lost and p.redetect:
            box = self._redetect(g)
            if box is not None:
                self._confidence = -p.fb_threshold
        self._pyr = pyr
        self._lost = box is None
        if box is None:
            self.points = np.zeros((0, 2))
            return False, self.bbox
        return True, box
