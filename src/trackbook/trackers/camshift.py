"""CamShift (Bradski 1998): a hue histogram, its back-projection, and a window that adapts.

Bradski, "Computer vision face tracking for use in a perceptual user interface", Intel
Technology Journal, 1998 (bradski1998). The first box gives a hue histogram (pixels too grey,
too dark or too bright for a reliable hue left out); every frame becomes a probability image,
the histogram's value at each pixel's hue; mean-shift moves the search window to the centroid
of that image until it stops; the window's zeroth moment M00 sets its next side
``s = 2 sqrt(M00 / 256)`` and its central second moments the ellipse (centre, half-axes,
angle). :mod:`trackbook.filters.camshift` holds the computation and compares it with
``cv2.CamShift``.

>>> from trackbook import trackers, clips
>>> clip = clips.load("red-cube")                                             # doctest: +SKIP
>>> t = trackers.create("camshift"); t.init(clip.frames[0], clip.groundtruth[0])  # doctest: +SKIP
>>> ok, box = t.update(clip.frames[1]); t.state().ellipse                      # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses

import cv2
import numpy as np

from ..filters import camshift as cs
from ..params import NOT_PRINTED, param
from .base import Tracker, redetecting
from .registry import register

_OPENCV_SAMPLE = "OpenCV's camshift sample"


@dataclasses.dataclass(frozen=True)
class CamShiftParams:
    bins: int = param(
        64, 4, 180, 1, doc="hue bins of the target's histogram",
        paper=NOT_PRINTED,
        why="Bradski prints no bin count (OpenCV's camshift sample uses 16); with the "
            "book's other defaults, mean AUC over the 8 sample clips was 0.33 at 16 bins, "
            "0.64 at 32, 0.57 at 48, 0.70 at 64, 0.70 at 90: 64 keeps the target's hue apart "
            "from a background of a near hue")
    s_min: int = param(
        60, 0, 255, 1, doc="pixels with saturation below this have no trusted hue (masked)",
        paper=NOT_PRINTED,
        why="Bradski masks low-saturation pixels without printing the level; 60 of 255 "
            "leaves grey and white out of the hue histogram")
    v_min: int = param(
        32, 0, 255, 1, doc="pixels darker than this have no trusted hue (masked)",
        paper=NOT_PRINTED,
        why="Bradski masks dark pixels without printing the level; below 32 of 255 the "
            "hue of an 8-bit pixel is mostly noise")
    v_max: int = param(
        255, 0, 255, 1, doc="pixels brighter than this have no trusted hue (masked)",
        paper=NOT_PRINTED, why="no upper level is printed; 255 keeps every bright pixel")
    max_iter: int = param(
        10, 1, 100, 1, doc="mean-shift moves per frame at most",
        paper=NOT_PRINTED,
        why=f"10 as in {_OPENCV_SAMPLE}'s termination criteria; the window converges in "
            "two or three moves between frames of a sample clip")
    eps: float = param(
        1.0, 0.0, 10.0, 0.5, doc="mean-shift stops when the window moves less than this (px)",
        paper=NOT_PRINTED,
        why=f"1 px as in {_OPENCV_SAMPLE}: windows are whole pixels")
    aspect: float = param(
        1.0, 0.25, 4.0, 0.05, doc="search window height / width (side s = 2 sqrt(M00/256))",
        paper=1.2,   # Bradski 1998: a face's window is s wide and 1.2 s high
        why="1.2 is Bradski's for faces, which are taller than wide; the book's targets "
            "have any shape, so the window is square")
    background_weighted: bool = param(
        True, doc="weigh each hue bin by min(1, o*/o_u), o the hues around the first box "
        "(Comaniciu et al. 2003)",
        paper=NOT_PRINTED, paper_value=False,
        why="the book's addition: Bradski's plain hue histogram lets the window spread over "
            "any background of the target's hue (yellow-ball's floor); hues common around "
            "the first box are weighed down (mean AUC over the 8 sample clips 0.29 without, "
            "0.70 with)")


@register
class CamShiftTracker(Tracker):
    """CamShift, Bradski 1998: mean-shift on a hue back-projection with an adaptive window.

    Every frame: the back-projection ``P`` of the first frame's hue histogram
    (:func:`~trackbook.filters.camshift.back_projection`, pixels with saturation below
    ``s_min`` or value outside ``v_min..v_max`` at 0), then
    :func:`~trackbook.filters.camshift.camshift` from the last search window with Bradski's
    window rule. The box's size is the first box's times ``sqrt(M00 / M00_1)`` (M00 counts the
    target's pixels, so its square root follows the target's side), between a quarter and four
    times the first size; its centre is the centroid of ``P`` in the converged window plus the
    first frame's offset of the box centre from the centroid, scaled with the size (a target's
    colours need not sit in the middle of its box).

    Confidence
    ----------
    ``state().confidence`` is ``M00 / M00_1``: the zeroth moment of ``P`` over the last frame's
    converged window relative to the first frame's (the same computation on the first frame
    from the given box). 1 while as much of the target's colour is under the window as at the
    start, 0 on a frame with no pixel of its hues (a constant frame included); always finite.

    Failure and re-detection
    ------------------------
    Bradski prints no failure rule: the failure-detection layer decides ``ok`` from the
    confidence above (a constant frame is lost); on a frame judged lost the box and the
    search window stay where they were. ``camshift-redetect`` adds the re-detection layer:
    while lost, boxes over the whole frame are scored by the probability mass of ``P`` they
    hold (:meth:`_score_boxes`) and the search window restarts at the best.

    Drawn: ``search_window`` (the next frame's window) and ``ellipse`` (cx, cy, hx, hy,
    angle): half-axes 2 σ across and along the long axis of ``P``, angle in degrees as
    OpenCV's rotated rect gives it.
    """

    name = "camshift"
    Params = CamShiftParams

    def _hist_args(self):
        p = self.params
        return dict(s_min=p.s_min, v_min=p.v_min, v_max=p.v_max)

    def _init(self, frame, box):
        p = self.params
        x, y, w, h = (float(v) for v in box)
        self._size0 = (w, h)
        hist = cs.hue_histogram(frame, box, p.bins, **self._hist_args())
        if p.background_weighted:
            hist = hist * cs.background_weights(frame, box, p.bins, **self._hist_args())
            hist = hist * (255.0 / hist.max()) if hist.max() > 0 else hist
        self.hist = hist
        start = self._int_box(box, frame.shape)
        res = self._run(cs.back_projection(frame, self.hist, **self._hist_args()), start)
        # M00 of the first frame is the unit of the confidence; a box with no trusted hue has
        # none, and then every frame is lost (confidence 0).
        self._m00_first = res.m00
        # the target's colours need not be centred in its box: keep the first frame's offset
        # of the box centre from the centroid, in units of the box's size
        self._offset = (0.0, 0.0) if res.m00 <= 0 else (
            (x + w / 2 - (res.center[0] + 0.5)) / w, (y + h / 2 - (res.center[1] + 0.5)) / h)
        self.window = res.window if res.m00 > 0 else start
        self._located = None
        self.ellipse = (x + w / 2, y + h / 2, w / 2, h / 2, 0.0)
        self._box = np.array([x, y, w, h])

    @staticmethod
    def _int_box(box, shape):
        H, W = shape[:2]
        x, y, w, h = (int(round(v)) for v in box)
        x, y = min(max(x, 0), W - 1), min(max(y, 0), H - 1)
        return (x, y, max(min(w, W - x), 1), max(min(h, H - y), 1))

    def _run(self, prob, window):
        p = self.params
        return cs.camshift(prob, window, p.max_iter, p.eps, "bradski", p.aspect)

    def _score(self, res) -> float:
        return res.m00 / self._m00_first if self._m00_first > 0 else 0.0

    def _locate(self, frame):
        """CamShift from the last search window on the frame's back-projection; the box from
        the converged window (size from ``M00``, centre from the centroid). Returns the box
        and ``M00 / M00_1``; the window moves only in ``_learn``."""
        self._located = None
        if self._m00_first <= 0:
            # the first box had no trusted hue: nothing to place, every frame is lost
            return np.full(4, np.nan), 0.0
        if self._is_flat(frame):
            return self._box, 0.0           # a flat frame is lost whatever it scores
        prob = cs.back_projection(frame, self.hist, **self._hist_args())
        res = self._run(prob, self.window)
        conf = float(self._score(res))
        if not np.isfinite(res.center[0]):
            return np.full(4, np.nan), conf    # no mass under the window: nothing to place
        scale = float(np.clip(np.sqrt(conf), 0.25, 4.0))
        w, h = self._size0[0] * scale, self._size0[1] * scale
        cx = res.center[0] + 0.5 + self._offset[0] * w
        cy = res.center[1] + 0.5 + self._offset[1] * h
        self._located = res
        return np.array([cx - w / 2, cy - h / 2, w, h]), conf

    def _learn(self, frame, box):
        """Accept the converged window of ``_locate`` as the next search window (CamShift's
        histogram is the first frame's: there is no appearance model to update)."""
        res = self._located
        self.window = res.window
        cx, cy, hx, hy, angle = res.ellipse
        self.ellipse = (cx + 0.5, cy + 0.5, hx, hy, angle)   # pixel j covers [j, j + 1)
        self._box = np.asarray(box, dtype=float)

    def _score_boxes(self, frame, boxes):
        """For re-detection: the probability mass of the back-projection ``P`` inside each box
        relative to the first frame's ``M00`` (one integral image; the histogram untouched)."""
        if self._m00_first <= 0:
            return np.zeros(len(boxes))
        prob = cs.back_projection(frame, self.hist, **self._hist_args())
        ii = cv2.integral(prob.astype(np.float64))
        H, W = prob.shape[:2]
        b = np.asarray(boxes, dtype=float)
        x0 = np.clip(np.round(b[:, 0]), 0, W).astype(int)
        y0 = np.clip(np.round(b[:, 1]), 0, H).astype(int)
        x1 = np.clip(np.round(b[:, 0] + b[:, 2]), 0, W).astype(int)
        y1 = np.clip(np.round(b[:, 1] + b[:, 3]), 0, H).astype(int)
        mass = ii[y1, x1] - ii[y0, x1] - ii[y1, x0] + ii[y0, x0]
        return mass / self._m00_first

    def _relocate(self, frame, box):
        """Restart the mean-shift search with the window at ``box``."""
        self.window = self._int_box(box, frame.shape)

    def _drawn(self) -> dict:
        """The next search window and the last ellipse (``Tracker.state()``)."""
        return {**super()._drawn(), "search_window": tuple(float(v) for v in self.window),
                "ellipse": tuple(float(v) for v in self.ellipse)}


register(redetecting(CamShiftTracker))

__all__ = ["CamShiftParams", "CamShiftTracker"]
