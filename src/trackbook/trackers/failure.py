"""The one rule that turns a tracker's confidence series into ``ok``: :class:`FailureDetector`.

Every tracker reports a confidence each frame (larger is surer), but on its own scale: a
peak-to-sidelobe ratio lies in [0, 50], a Bhattacharyya coefficient in [0, 1], a negated
distance in (-inf, 0]. One fixed threshold cannot serve them all, so the rule compares each
frame with the tracker's *own* recent confidence -- a drop to a fraction of its recent median,
or a drop of many robust spreads below it -- with hysteresis. The thresholds of each tracker
are a few numbers (:class:`FailureParams`), chosen on calibration runs by
:func:`trackbook.evaluation.failure.calibrate`.

This module imports nothing of the package, so the trackers can use it.
"""

from __future__ import annotations

import collections
import dataclasses
import functools
import json
import math
from pathlib import Path

import numpy as np

#: The thresholds ``experiments/calibrate_failure.py`` chose for every tracker: package data,
#: read by :func:`calibrated_params` when a tracker is made.
CALIBRATION_FILE = Path(__file__).resolve().parents[1] / "data" / "failure_calibration.json"

#: A box with less than this share of its area inside the frame is out of view (:func:`in_view`).
MIN_IN_VIEW = 0.5

#: 1 / Phi^-1(3/4): scales the median absolute deviation to a Gaussian's standard deviation.
MAD_TO_SIGMA = 1.482602218505602
#: sqrt(pi / 2): scales the mean absolute deviation to a Gaussian's standard deviation.
MEAN_AD_TO_SIGMA = 1.2533141373155003


@dataclasses.dataclass(frozen=True)
class FailureParams:
    """The thresholds of :class:`FailureDetector` for one tracker.

    Two tests, either of which declares a loss: a drop to a fraction of the reference (the
    *ratio* test, ``ratio_lost``) and a drop of many spreads below it (the *spread* test,
    ``k_lost``). A ratio of 0 or a ``k`` of ``inf`` turns that test off (not both: a rule
    that can never declare a loss is ``failure=False``); the defaults use the spread test
    alone.

    Attributes
    ----------
    k_lost : float
        Lost when the confidence falls more than ``k_lost`` spreads below the reference
        (``math.inf``: never by this test).
    k_found : float
        Found again only at no more than ``k_found`` spreads below the reference;
        ``k_found <= k_lost`` (the band between them is the hysteresis).
    ratio_lost : float
        Lost when the confidence falls below ``ratio_lost`` times a reference ``r >= 0``; for
        a negative reference (a negated distance ``-d``), when the distance exceeds
        ``|r| / ratio_lost``. In [0, 1]; 0: never by this test.
    ratio_found : float
        Found again only at no less than ``ratio_found`` times a reference ``r >= 0`` (for a
        negative one, at a distance of at most ``|r| / ratio_found``);
        ``ratio_lost <= ratio_found <= 1``.
    m : int
        Frames in a row at or above the found thresholds needed to recover (>= 1).
    window : int
        How many of the last confidences added to the reference make it (>= 2): the finite
        ones of frames judged ok, except those stepped with ``learn=False`` after the warm-up.
    warmup : int
        Finite confidences the reference must hold before the rule may declare a loss
        (1 <= warmup <= window): a reference of one or two values has no spread to speak of.
    """

    k_lost: float = 4.0
    k_found: float = 2.0
    m: int = 3
    window: int = 30
    warmup: int = 5
    ratio_lost: float = 0.0
    ratio_found: float = 0.0

    def __post_init__(self):
        for name in ("k_lost", "k_found"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or math.isnan(v) \
                    or v < 0:
                raise ValueError(f"FailureParams.{name} = {v!r}: give a number >= 0 (a "
                                 "multiple of the confidence's spread), or math.inf to turn "
                                 "the spread test off.")
        if self.k_found > self.k_lost:
            raise ValueError(f"FailureParams: k_found = {self.k_found} is above k_lost = "
                             f"{self.k_lost}; recovering must be at least as strict as staying "
                             "on target, so give k_found <= k_lost.")
        for name in ("ratio_lost", "ratio_found"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not 0 <= v <= 1:
                raise ValueError(f"FailureParams.{name} = {v!r}: give a fraction in [0, 1] "
                                 "of the reference (0 turns the ratio test off).")
        if math.isinf(self.k_lost) and self.ratio_lost == 0:
            raise ValueError("FailureParams: k_lost = inf and ratio_lost = 0 turn both tests "
                             "off, so no frame could ever be lost; give a finite k_lost or a "
                             "ratio_lost > 0 (or failure=False for no failure layer at all).")
        if self.ratio_found < self.ratio_lost:
            raise ValueError(f"FailureParams: ratio_found = {self.ratio_found} is below "
                             f"ratio_lost = {self.ratio_lost}; recovering must be at least as "
                             "strict as staying on target, so give ratio_found >= ratio_lost.")
        for name, low in (("m", 1), ("window", 2), ("warmup", 1)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < low:
                raise ValueError(f"FailureParams.{name} = {v!r}: give a whole number >= {low}.")
        if self.warmup > self.window:
            raise ValueError(f"FailureParams: warmup = {self.warmup} exceeds window = "
                             f"{self.window}; the reference never holds that many frames, so "
                             "give warmup <= window.")


def threshold(r: float, s: float, k: float, ratio: float) -> float:
    r"""The confidence below which a frame fails against a reference ``(r, s)``.

    .. math::

        \theta(r, s) = \max\bigl(r - k\, s,\; \phi^{\operatorname{sign} r}\, r\bigr)

    with :math:`\phi` = ``ratio``: :math:`\phi r` for a reference :math:`r \ge 0` (a
    similarity: lost below a fraction of it), :math:`r / \phi` for :math:`r < 0` (a negated
    distance: lost when the distance grows by the factor :math:`1/\phi`). A test that is
    off (``k = inf``, ``ratio = 0``) contributes :math:`-\infty`.
    """
    spread = r - k * s if math.isfinite(k) else -math.inf
    if ratio <= 0:
        return spread
    return max(spread, r * ratio if r >= 0 else r / ratio)


def robust_reference(values) -> tuple[float, float]:
    """Centre and spread ``(r, s)`` of confidences: the median and a scaled absolute deviation.

    ``s = 1.4826 * median|c - r|`` (the median absolute deviation, MAD, in the units of a
    Gaussian's standard deviation); when more than half of the values equal the median (a
    quantised confidence) the MAD is 0 although the values vary, and ``s`` falls back to
    ``1.2533 * mean|c - r|``, zero only when all values are equal. Both are equivariant under
    ``c -> a c + b`` (``a > 0``): ``r -> a r + b``, ``s -> a s``.
    """
    v = np.asarray(values, float)
    r = float(np.median(v))
    dev = np.abs(v - r)
    s = MAD_TO_SIGMA * float(np.median(dev))
    if s == 0.0:
        s = MEAN_AD_TO_SIGMA * float(dev.mean())
    return r, s


class FailureDetector:
    r"""Judge each frame on target or lost from the tracker's confidence alone.

    With :math:`r_t, s_t` the median and the scaled MAD (:func:`robust_reference`) of the
    last ``window`` confidences added to the reference before frame :math:`t` (those of frames
    judged ok, but see ``learn`` below), and
    :math:`\theta` the threshold of :func:`threshold`:

    .. math::

        \text{on target} \to \text{lost} &\iff
            c_t < \theta_\text{lost} = \max(r_t - k_\text{lost} s_t,\ \phi_\text{lost} r_t), \\
        \text{lost} \to \text{on target} &\iff c_{t-j} \ge
            \theta_\text{found} = \max(r - k_\text{found} s,\ \phi_\text{found} r)
        \text{ for } j = 0, \dots, m - 1,

    (for a negative reference :math:`\phi r` reads :math:`r / \phi`, see :func:`threshold`),
    with :math:`k_\text{found} \le k_\text{lost}`,
    :math:`\phi_\text{lost} \le \phi_\text{found}`, and :math:`r, s` frozen at the loss while
    lost (a reference that learned from lost frames would drift down to them and declare the
    target found). A frame judged ok adds its confidence to the reference; a lost one does
    not, nor does one stepped with ``learn=False`` once the warm-up is over (the base class
    asks this of a located box that reaches past the frame's edge, :func:`reaches_out`). The
    reference can then span more than the last ``window`` frames, as it does after a loss: a
    target that stays across the edge after the warm-up is judged against what it scored
    before, however long it stays.
    Until the reference holds ``warmup`` finite values, every frame is ok.

    Why two tests: trackers' confidences differ in scale *and* sign (a peak-to-sidelobe
    ratio in [0, 50], a Bhattacharyya coefficient in [0, 1], a negated distance in
    (-inf, 0]). The spread test is in units of the tracker's own spread: median and MAD are
    equivariant under every positive affine map ``c -> a c + b`` (``a > 0``), so with the
    ratio test off the rule gives the same ``ok`` sequence for ``c`` and ``a c + b``. But a
    spread is only as good as the frames it was measured on: on a steady scene it is tiny and
    an ordinary wobble is many spreads deep, so a ``k`` safe on every scene must be so large
    that the threshold can fall below the confidence's whole range (a Bhattacharyya
    coefficient 70 spreads below 0.93 is -0.36). The ratio test measures the drop against the
    confidence's own zero (no match, no peak above the sidelobes, zero distance), which every
    confidence here has: it is unchanged by ``c -> a c`` (``a > 0``), not by a shift. The
    calibration chooses, per tracker, either test or both. Median and MAD also ignore the
    few outlying frames (a brief occlusion the tracker survived) that would pull a mean and
    standard deviation.

    Conventions: a NaN or ``-inf`` confidence (the tracker found nothing to score) is below
    any threshold; ``+inf`` is above any threshold and is not added to the reference (it
    carries no finite value). A constant reference has ``s = 0``: then any value below ``r`` is
    a drop, the only scale-free reading of a series that never varied.

    Parameters
    ----------
    params : FailureParams, optional
        The thresholds; the defaults of :class:`FailureParams` when left out.

    Examples
    --------
    >>> d = FailureDetector(FailureParams(k_lost=4, k_found=2, m=2, window=10, warmup=3))
    >>> [d.step(c) for c in [10, 11, 10, 11, 10, 2, 2, 10, 10, 11]]
    [True, True, True, True, True, False, False, False, True, True]
    """

    def __init__(self, params: FailureParams | None = None):
        if params is None:
            params = FailureParams()
        if not isinstance(params, FailureParams):
            raise TypeError(f"FailureDetector takes a FailureParams, not {type(params).__name__}"
                            "; build one with FailureParams(k_lost=..., k_found=...).")
        self.params = params
        self.reset()

    def reset(self) -> None:
        """Forget everything (a new clip, or the tracker was initialised again)."""
        self._ref = collections.deque(maxlen=self.params.window)
        self.lost = False
        self._frozen = (math.nan, math.nan)
        self._run = 0

    @property
    def reference(self) -> tuple[float, float]:
        """``(r, s)`` the next frame is judged against (frozen while lost; NaN before any)."""
        if self.lost:
            return self._frozen
        if not self._ref:
            return math.nan, math.nan
        return robust_reference(self._ref)

    @property
    def ok(self) -> bool:
        """The judgement of the last frame."""
        return not self.lost

    def step(self, confidence, learn: bool = True) -> bool:
        """Judge the next frame from its confidence; returns ``ok``.

        ``learn=False`` judges the frame as usual but, if it is on target (or ends a loss),
        keeps its confidence out of the reference, so it does not lower (or raise) the
        standard the next frames are judged by; during the warm-up it enters all the same,
        since the reference must first exist. A lost frame never enters it.
        """
        c = float(confidence)
        p = self.params
        if not self.lost:
            warm = len(self._ref) >= p.warmup
            if warm:
                r, s = robust_reference(self._ref)
                if not c >= threshold(r, s, p.k_lost, p.ratio_lost):  # NaN: lost
                    self.lost, self._frozen, self._run = True, (r, s), 0
                    return False
            if learn or not warm:
                self._learn(c)
            return True
        r, s = self._frozen
        self._run = self._run + 1 if c >= threshold(r, s, p.k_found, p.ratio_found) else 0
        if self._run >= p.m:
            self.lost = False
            if learn:
                self._learn(c)
            return True
        return False

    def _learn(self, c: float) -> None:
        if math.isfinite(c):
            self._ref.append(c)

    def run(self, confidences) -> np.ndarray:
        """``ok`` for every value of a series, from a fresh start (the detector is reset)."""
        self.reset()
        return np.array([self.step(c) for c in np.asarray(confidences, float).ravel()], bool)


def in_view(box, frame_shape) -> float:
    r"""The share of ``box = (x, y, w, h)``'s area that lies inside a frame of ``frame_shape``.

    .. math::

        v(b) = \frac{|b \cap F|}{|b|}

    with :math:`F` the frame. The layer judges a frame lost, whatever the confidence says, when
    the box the algorithm located has :math:`v(b) <` :data:`MIN_IN_VIEW` = 1/2: most of what
    it scores there is outside the picture (a target that left across the border, a box that
    slid after it). Such a box is never on target: for a ground-truth box :math:`g` inside the
    frame (:math:`b \cup g \supseteq b`, and :math:`b \cap g \subseteq b \cap F`),

    .. math::

        \operatorname{IoU}(b, g) = \frac{|b \cap g|}{|b \cup g|} \le \frac{|b \cap g|}{|b|}
        \le \frac{|b \cap F|}{|b|} = v(b) < \tfrac12 .

    The bound is about the located box. On a lost frame ``update`` reports the last box judged
    on target, which may still overlap the target by more than half; counted on that box, a
    frame this rule flags can be a false loss. A ground-truth box that reaches outside the
    frame (an annotation not clipped to it) can also overlap a box less than half in view by
    more than half.

    Examples
    --------
    >>> in_view((-10, 0, 20, 10), (100, 100, 3))
    0.5
    """
    x, y, w, h = (float(v) for v in box)
    if not w > 0 or not h > 0:
        return 0.0
    height, width = frame_shape[:2]
    dx = min(x + w, width) - max(x, 0.0)
    dy = min(y + h, height) - max(y, 0.0)
    return max(dx, 0.0) * max(dy, 0.0) / (w * h)


#: How far past an edge, in pixels, a box must reach (more than this) to count as reaching out
#: (:func:`reaches_out`): a box placed flush with the edge by arithmetic (``x = cx - w / 2``)
#: can land a rounding error past it.
EDGE_TOLERANCE = 1e-6


def reaches_out(box, frame_shape) -> bool:
    """Whether ``box = (x, y, w, h)`` reaches past an edge of a frame of ``frame_shape`` by
    more than :data:`EDGE_TOLERANCE` pixels; for a box with finite coordinates and
    ``w, h > 0`` (the layer asks only of those).

    The layer keeps the confidence of such a box out of the reference
    (:meth:`FailureDetector.step` with ``learn=False``): part of what it scores is not in the
    picture (a target leaving across the border, or a box resting there after it left), and
    a reference that learned it would be pulled toward the background's score by a slow
    exit. Compared edge by edge (``x < -t``, ``x + w > W + t``, ..., with ``t`` =
    :data:`EDGE_TOLERANCE`), not as
    :func:`in_view` ``< 1``: the share in view is computed in floating point and can fall a
    rounding error short of 1 for a box well inside the frame.

    Examples
    --------
    >>> reaches_out((0, 0, 10, 10), (10, 10, 3)), reaches_out((0.5, 0, 10, 10), (10, 10, 3))
    (False, True)
    """
    x, y, w, h = (float(v) for v in box)
    height, width = frame_shape[:2]
    t = EDGE_TOLERANCE
    return x < -t or y < -t or x + w > width + t or y + h > height + t


def load_calibration(path=None) -> dict:
    """``{tracker name: FailureParams}`` from a calibration file.

    Parameters
    ----------
    path : str or Path, optional
        The JSON file ``experiments/calibrate_failure.py`` wrote; default the committed one,
        ``trackbook/data/failure_calibration.json``.

    Raises
    ------
    FileNotFoundError
        When there is no such file, naming the command that makes it.
    """
    path = Path(CALIBRATION_FILE if path is None else path)
    if not path.is_file():
        raise FileNotFoundError(f"no calibration file {path}; make it with: python "
                                "experiments/calibrate_failure.py (--out FILE to write "
                                "elsewhere).")
    fields = [f.name for f in dataclasses.fields(FailureParams)]
    rows = json.loads(path.read_text(encoding="utf-8"))["rows"]
    # JSON has no infinity: a test turned off (k = inf) is written null
    return {r["tracker"]: FailureParams(**{k: math.inf if r[k] is None else r[k]
                                           for k in fields if k in r}) for r in rows}


@functools.lru_cache(maxsize=1)
def _committed() -> dict:
    return load_calibration() if CALIBRATION_FILE.is_file() else {}


def calibrated_params(name: str) -> FailureParams:
    """The committed thresholds of tracker ``name``, or :class:`FailureParams`' defaults.

    A re-detecting variant (``kcf-redetect``) uses the thresholds of the algorithm it wraps
    (``kcf``): the layer judges the same confidence. A tracker the calibration has not seen
    (a student's own) gets the defaults until it is calibrated.
    """
    table = _committed()
    base = name[:-len("-redetect")] if name.endswith("-redetect") else name
    return table.get(name) or table.get(base) or FailureParams()


def judge(confidences, params: FailureParams | None = None) -> np.ndarray:
    """``ok`` per frame of one confidence series: ``FailureDetector(params).run(confidences)``."""
    return FailureDetector(params).run(confidences)


__all__ = ["CALIBRATION_FILE", "EDGE_TOLERANCE", "MIN_IN_VIEW", "FailureDetector",
           "FailureParams", "calibrated_params", "in_view", "judge", "load_calibration",
           "reaches_out", "robust_reference", "threshold"]
