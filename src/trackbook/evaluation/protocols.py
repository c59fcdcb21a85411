"""Evaluation protocols beyond the one-pass evaluation (OPE): OTB's temporal and spatial
robustness (TRE, SRE) and VOT's reset-based protocol with accuracy, robustness and the
expected average overlap (EAO).

Each protocol is split in two: a pure function that builds the runs or applies the rule to
boxes (:func:`tre_starts`, :func:`sre_boxes`, :func:`pooled_scores`, :func:`reset_protocol`,
:func:`eao_curve`, :func:`eao`), testable without a tracker, and a function that runs a
tracker through it (:func:`evaluate_tre`, :func:`evaluate_sre`, :func:`evaluate_reset`).

References
----------
Y. Wu, J. Lim, M.-H. Yang, "Online Object Tracking: A Benchmark", CVPR 2013 (``wu2013``):
TRE and SRE (its robustness evaluation), and its toolkit's ``splitSeqTRE.m``, ``shiftInitBB.m``,
``perfPlot.m``.

M. Kristan et al., "The Visual Object Tracking VOT2015 Challenge Results", ICCV workshops
2015 (``kristan2015``): the reset-based protocol and EAO; M. Kristan, J. Matas, A. Leonardis
et al., "A Novel Performance Evaluation Methodology for Single-Target Trackers", IEEE TPAMI
38(11), 2016: accuracy, robustness, burn-in, reliability.

Examples
--------
>>> import trackbook
>>> from trackbook.evaluation import protocols
>>> clip = trackbook.clips.load("red-cube")
>>> tre = protocols.evaluate_tre("kcf", clip, seed=0)          # doctest: +SKIP
>>> tre.starts[:3], tre.scores["auc"]                           # doctest: +SKIP
>>> sre = protocols.evaluate_sre("kcf", clip, seed=0)          # doctest: +SKIP
>>> run = protocols.evaluate_reset("kcf", clip, seed=0)        # doctest: +SKIP
>>> run.accuracy, run.n_failures, protocols.eao([run])         # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .. import clips as _clips
from .. import trackers as _trackers
from .._checks import as_box, clip_box
from . import metrics
from .runner import evaluate

__all__ = ["SRE_SHIFTS", "ProtocolResult", "ResetRun", "eao", "eao_curve", "evaluate_reset",
           "evaluate_sre", "evaluate_tre", "pooled_scores", "reset_protocol", "sre_boxes",
           "tre_starts"]


# -- OTB: TRE and SRE (Wu, Lim, Yang 2013) ----------------------------------------------------

def tre_starts(groundtruth, n_segments: int = 20, min_length: int = 20,
               exclude=()) -> np.ndarray:
    """The start frames of OTB's temporal robustness evaluation (TRE).

    Wu et al. (2013) run a tracker from 20 starting frames of a sequence, each
    initialised on that frame's ground truth and run to the end of the sequence. Wu et al.
    (2013) say only that the sequence is split into 20 segments; this follows the toolkit's
    ``splitSeqTRE.m``, which says which frames:

    1. candidates :math:`I = (i_1 < \\dots < i_M)` are the frames whose ground-truth box is
       known (finite, :math:`w, h > 0`) with its top-left corner in the image
       (:math:`x, y \\ge 0`; the toolkit's ``r(1) <= 0 | r(2) <= 0`` test in its 1-based
       pixels) and not in ``exclude`` (the toolkit's per-sequence ``initOmit`` lists of
       occluded or out-of-view frames);
    2. :math:`E` is the largest position with :math:`L - i_E \\ge m` (``min_length``
       :math:`m = 20`; :math:`L` frames in all): every segment has at least 20 frames;
    3. the starts are the candidates at the 1-based positions

       .. math:: p_k = 1 + \\lfloor k E / (S - 1) \\rfloor, \\quad
                 k = 0, 1, \\dots, \\text{while } 1 + k E / (S - 1) \\le E,

       followed by :math:`p = E` (``[floor(1:E/(S-1):E) E]``, :math:`S` = ``n_segments``).

    With :math:`E \\ge S - 1` this gives :math:`S` starts, the first the first candidate and
    the last the latest frame that leaves ``min_length`` frames. On a clip with fewer
    candidates the starts repeat, as the toolkit's do (a repeated start is a repeated run
    and counts again in the pooled scores).

    Parameters
    ----------
    groundtruth : (L, 4) array of ``(x, y, w, h)``, NaN where unknown
    n_segments : int, the number of starts :math:`S` (OTB: 20)
    min_length : int, the fewest frames a segment has, its start included (OTB: 20)
    exclude : iterable of int, 0-based frames not to start on

    Returns
    -------
    (S,) int array of 0-based start frames, non-decreasing.
    """
    gt = np.asarray(groundtruth, dtype=float)
    if gt.ndim != 2 or gt.shape[1] != 4:
        raise ValueError(f"groundtruth has shape {gt.shape}; give one (x, y, w, h) row per "
                         "frame (an L x 4 array).")
    if int(n_segments) < 2 or int(min_length) < 2:
        raise ValueError(f"n_segments = {n_segments}, min_length = {min_length}: both must be "
                         "at least 2 (OTB uses 20 and 20).")
    S, L = int(n_segments), len(gt)
    with np.errstate(invalid="ignore"):
        ok = np.all(np.isfinite(gt), axis=1) & (gt[:, 2] > 0) & (gt[:, 3] > 0) \
            & (gt[:, 0] >= 0) & (gt[:, 1] >= 0)
    ok[[int(i) for i in exclude if 0 <= int(i) < L]] = False
    cand = np.flatnonzero(ok)
    long_enough = np.flatnonzero(L - cand >= int(min_length))
    if long_enough.size == 0:
        raise ValueError(f"no frame with a known ground-truth box leaves {min_length} frames "
                         f"to the end of this {L}-frame clip; pass a smaller min_length or a "
                         "longer clip.")
    E = int(long_enough[-1]) + 1                       # 1-based position, as the toolkit's
    k = np.arange(0, (S - 1) * (E - 1) // E + 1)       # 1 + kE/(S-1) <= E
    pos = np.append(1 + (k * E) // (S - 1), E)
    return cand[pos - 1]


#: The 12 perturbations of SRE, in the toolkit's order: 4 centre shifts, 4 corner shifts,
#: 4 scalings.
SRE_SHIFTS = ("left", "right", "up", "down", "top-left", "top-right", "bottom-left",
              "bottom-right", "scale-0.8", "scale-0.9", "scale-1.1", "scale-1.2")


def sre_boxes(box) -> np.ndarray:
    """The 12 perturbed initial boxes of OTB's spatial robustness evaluation (SRE).

    Wu et al. (2013): "eight spatial shifts (4 center shifts and 4 corner shifts)
    and 4 scale variations"; the shift is 10 % of the target size and the scale factors are
    0.8, 0.9, 1.1, 1.2. Wu et al. (2013) leave "corner shift" open; this follows the toolkit's
    ``shiftInitBB.m``: a corner shift moves *one corner* outwards by 10 % of the width and
    height and keeps the opposite corner, so the box grows to :math:`1.1w \\times 1.1h`. For
    :math:`(x, y, w, h)`, :math:`\\delta_x = 0.1 w`, :math:`\\delta_y = 0.1 h`:

    ============  =====================================================
    left, right   :math:`(x \\mp \\delta_x, y, w, h)`
    up, down      :math:`(x, y \\mp \\delta_y, w, h)`
    top-left      :math:`(x - \\delta_x, y - \\delta_y, w + \\delta_x, h + \\delta_y)`
    top-right     :math:`(x, y - \\delta_y, w + \\delta_x, h + \\delta_y)`
    bottom-left   :math:`(x - \\delta_x, y, w + \\delta_x, h + \\delta_y)`
    bottom-right  :math:`(x, y, w + \\delta_x, h + \\delta_y)`
    scale-s       :math:`(c_x - s w / 2, c_y - s h / 2, s w, s h)`, same centre
    ============  =====================================================

    The toolkit rounds to whole pixels (``ceil`` for centre shifts, ``round`` otherwise, in
    1-based inclusive pixels); boxes here are continuous, so no rounding. Clamping to the
    image is left to the run (:func:`trackbook.evaluate` clips every initial box to the
    frame, as the toolkit clamps it). Some versions of the toolkit's ``calcSeqErrRobust.m``
    divide a scaled run's boxes by its factor before scoring; Wu et al. (2013) do not, nor
    does this: a run is scored on the boxes the tracker gave.

    Returns
    -------
    (12, 4) array, rows in the order of :data:`SRE_SHIFTS`.
    """
    x, y, w, h = as_box(box, name="box")
    dx, dy = 0.1 * w, 0.1 * h
    cx, cy = x + w / 2, y + h / 2
    rows = [(x - dx, y, w, h), (x + dx, y, w, h), (x, y - dy, w, h), (x, y + dy, w, h),
            (x - dx, y - dy, w + dx, h + dy), (x, y - dy, w + dx, h + dy),
            (x - dx, y, w + dx, h + dy), (x, y, w + dx, h + dy)]
    rows += [(cx - s * w / 2, cy - s * h / 2, s * w, s * h) for s in (0.8, 0.9, 1.1, 1.2)]
    return np.array(rows, dtype=float)


def pooled_scores(boxes, gts) -> dict:
    """OTB's scores of several runs: every run's frames pooled, then scored once.

    ``perfPlot.m`` sums each run's count of successful frames and divides by the sum of the
    runs' lengths, so a run weighs by its number of frames:

    .. math:: \\mathrm{SR}(t) = \\frac{\\sum_r |\\{i \\in F_r : \\mathrm{IoU}_{r,i} > t\\}|}
                                 {\\sum_r |F_r|},

    :math:`F_r` the scored frames of run :math:`r`; the AUC (the mean of SR over the 21
    thresholds) and the precision are pooled the same way. Wu et al. (2013) say only that the
    runs' results are averaged. Each run's first frame is its initialisation and is dropped,
    as :func:`trackbook.evaluate` drops it (the toolkit scores it, with the ground truth as
    the box, which lifts short TRE segments).

    Parameters
    ----------
    boxes, gts : sequences of (N_r, 4) arrays, run r's boxes and ground truth (frame 0 the
        initialisation)

    Returns
    -------
    dict of :func:`trackbook.metrics.summary` over the pooled frames.
    """
    boxes, gts = list(boxes), list(gts)
    if not boxes or len(boxes) != len(gts):
        raise ValueError(f"{len(boxes)} runs of boxes and {len(gts)} of ground truth; give "
                         "one ground truth per run (at least one run).")
    return metrics.summary(np.concatenate([np.asarray(b, float)[1:] for b in boxes]),
                           np.concatenate([np.asarray(g, float)[1:] for g in gts]))


@dataclasses.dataclass
class ProtocolResult:
    """The runs of one tracker through TRE or SRE on one clip.

    Attributes
    ----------
    protocol : ``"tre"`` or ``"sre"``
    tracker, clip : names
    starts : (R,) int, each run's first frame (0 for every SRE run)
    init_boxes : (R, 4), each run's initial box as given to the tracker (clipped to the frame)
    labels : tuple of R names (``"frame 12"`` or an entry of :data:`SRE_SHIFTS`)
    results : list of R :class:`~trackbook.evaluation.runner.Result`, run r's boxes are frames
        ``starts[r]:`` of the clip
    scores : :func:`pooled_scores` of the runs
    """

    protocol: str
    tracker: str
    clip: str
    starts: np.ndarray
    init_boxes: np.ndarray
    labels: tuple
    results: list
    scores: dict


def _from(clip, start: int):
    """The clip from frame ``start`` on (frames stay lazy: a slice reads nothing)."""
    if start == 0:
        return clip
    return dataclasses.replace(clip, frames=clip.frames[start:],
                               groundtruth=clip.groundtruth[start:], targets={})


def _name(name_or_tracker) -> str:
    if isinstance(name_or_tracker, str):
        return name_or_tracker
    return getattr(name_or_tracker, "name", type(name_or_tracker).__name__)


def evaluate_tre(name_or_tracker, clip, seed: int | None = 0, preset: str = "book",
                 n_segments: int = 20, min_length: int = 20, exclude=(),
                 **params) -> ProtocolResult:
    """OTB's temporal robustness evaluation: one run from each of :func:`tre_starts`, each
    from that frame's ground truth to the end of the clip, scored by :func:`pooled_scores`.

    Parameters are those of :func:`trackbook.evaluate` and :func:`tre_starts`; every run uses
    the same ``seed`` (a tracker is re-seeded at each ``init``).
    """
    clip = _clips.load(clip)
    starts = tre_starts(clip.groundtruth, n_segments, min_length, exclude)
    results = [evaluate(name_or_tracker, _from(clip, int(s)), seed=seed, preset=preset,
                        **params) for s in starts]
    return _collect("tre", name_or_tracker, clip, starts, [f"frame {s}" for s in starts],
                    results)


def evaluate_sre(name_or_tracker, clip, seed: int | None = 0, preset: str = "book",
                 **params) -> ProtocolResult:
    """OTB's spatial robustness evaluation: 12 runs over the whole clip from the boxes of
    :func:`sre_boxes` (around the first ground-truth box), scored by :func:`pooled_scores`
    (all runs have the same length, so this is their plain mean).

    Parameters are those of :func:`trackbook.evaluate`.
    """
    clip = _clips.load(clip)
    if not np.all(np.isfinite(clip.groundtruth[0])):
        raise ValueError(f"clip {clip.name!r} has no ground-truth box on frame 0; SRE perturbs "
                         "the first box, so the clip needs one.")
    results = [evaluate(name_or_tracker, clip, seed=seed, preset=preset, init_box=b, **params)
               for b in sre_boxes(clip.groundtruth[0])]
    return _collect("sre", name_or_tracker, clip, np.zeros(len(results), dtype=int),
                    list(SRE_SHIFTS), results)


def _collect(protocol, name_or_tracker, clip, starts, labels, results) -> ProtocolResult:
    gts = [clip.groundtruth[int(s):] for s in starts]
    return ProtocolResult(protocol, _name(name_or_tracker), clip.name, np.asarray(starts),
                          np.array([r.boxes[0] for r in results]), tuple(labels), results,
                          pooled_scores([r.boxes for r in results], gts))


# -- VOT: the reset-based protocol (Kristan et al. 2015, 2016) --------------------------------

@dataclasses.dataclass
class ResetRun:
    """One run of VOT's reset-based protocol on one clip (see :func:`reset_protocol`).

    Attributes
    ----------
    boxes : (L, 4), the tracker's box per frame; the ground truth on initialisation frames;
        NaN on the frames skipped after a failure
    overlaps : (L,), IoU with the ground truth on tracked frames; NaN on initialisation and
        skipped frames and where the ground truth is unknown
    inits : tuple of the initialisation frames (the first is the first known box)
    failures : tuple of the failure frames
    burnin : int, frames after each initialisation left out of the accuracy
    tracker, clip : names (empty when the boxes did not come from :func:`evaluate_reset`)
    """

    boxes: np.ndarray
    overlaps: np.ndarray
    inits: tuple
    failures: tuple
    burnin: int
    tracker: str = ""
    clip: str = ""

    def __len__(self) -> int:
        return len(self.overlaps)

    @property
    def skipped(self) -> tuple:
        """The frames after each failure up to the next initialisation (or the end of the
        clip when none follows): no box, no score."""
        ends = list(self.inits[1:]) + [len(self)] * (len(self.failures) + 1 - len(self.inits))
        return tuple(i for f, e in zip(self.failures, ends) for i in range(f + 1, e))

    @property
    def valid(self) -> np.ndarray:
        """(L,) bool: the frames the accuracy averages. A frame counts if the tracker gave a
        box there, its ground truth is known, it is not a failure frame (its overlap is 0 by
        definition and is counted by robustness instead) and it is not among the ``burnin``
        frames after an initialisation."""
        ok = ~np.isnan(self.overlaps)
        ok[list(self.failures)] = False
        for s in self.inits:
            ok[s + 1:s + 1 + self.burnin] = False
        return ok

    @property
    def accuracy(self) -> float:
        """VOT accuracy: :math:`A = \\frac{1}{|V|}\\sum_{i \\in V} \\mathrm{IoU}_i`, V the
        :attr:`valid` frames (NaN if there are none)."""
        v = self.overlaps[self.valid]
        return float(v.mean()) if v.size else float("nan")

    @property
    def n_failures(self) -> int:
        """VOT robustness as the raw count: the number of failures F."""
        return len(self.failures)

    @property
    def failure_rate(self) -> float:
        """Failures per 100 frames of the clip, :math:`100 F / L` (L frames in all)."""
        return 100.0 * self.n_failures / len(self)

    def reliability(self, S: int = 30) -> float:
        """Kristan et al. (2016, the AR plot): :math:`R_S = e^{-S F / L}`, the probability of
        tracking S frames without a failure if failures come at the run's rate (VOT: S = 30)."""
        return float(np.exp(-S * self.n_failures / len(self)))

    def fragments(self) -> list[tuple[np.ndarray, bool]]:
        """The run cut at its initialisations, for EAO: per initialisation s, the overlaps of
        frames s + 1 up to the failure (included) or the last frame, and whether it failed."""
        out = []
        for k, s in enumerate(self.inits):
            end = self.failures[k] if k < len(self.failures) else len(self) - 1
            out.append((self.overlaps[s + 1:end + 1].copy(), k < len(self.failures)))
        return out


def reset_protocol(segment, groundtruth, skip: int = 5, burnin: int = 10) -> ResetRun:
    """Apply VOT's reset-based protocol to the boxes of ``segment`` (no tracker needed).

    The rule (Kristan et al. 2015, 2016): the tracker starts on the first frame with a
    known ground-truth box. A **failure** is a frame whose ground truth is known and whose
    box has no overlap with it, :math:`\\mathrm{IoU}_i = 0` (an invalid box counts as no
    overlap). After a failure at frame f the frames f + 1, ..., f + skip - 1 are skipped and
    the tracker is **re-initialised** on the ground truth of frame f + ``skip`` (VOT: 5), or
    of the first later frame whose ground truth is known; if there is none the run ends.

    ``burnin`` (VOT: 10) is the number of frames after every initialisation (the first one
    too) that :attr:`ResetRun.accuracy` leaves out: after an initialisation at s the frames
    s + 1, ..., s + burnin. That is Kristan et al.'s (2015, 2016) "ten frames after re-initialization";
    the toolkit masks s, ..., s + burnin - 1 (its trajectory holds a marker on s), i.e. one
    tracked frame fewer: ``burnin=9`` here reproduces it.

    Parameters
    ----------
    segment : callable ``segment(start, box) -> iterable of boxes``
        Starts the tracker on frame ``start`` from ``box`` (the ground truth) and yields its
        boxes for frames start + 1, start + 2, ... in order; the protocol stops reading at a
        failure or at the last frame. With a tracker see :func:`evaluate_reset`; a test can
        yield scripted boxes.
    groundtruth : (L, 4) array, NaN where unknown
    skip, burnin : int

    Returns
    -------
    :class:`ResetRun`
    """
    gt = np.asarray(groundtruth, dtype=float)
    if gt.ndim != 2 or gt.shape[1] != 4 or len(gt) < 2:
        raise ValueError(f"groundtruth has shape {gt.shape}; give one (x, y, w, h) row per "
                         "frame for at least 2 frames.")
    if int(skip) < 1 or int(burnin) < 0:
        raise ValueError(f"skip = {skip}, burnin = {burnin}: skip must be at least 1 (the "
                         "failure frame itself) and burnin at least 0 (VOT: 5 and 10).")
    skip, burnin, L = int(skip), int(burnin), len(gt)
    with np.errstate(invalid="ignore"):
        known = np.all(np.isfinite(gt), axis=1) & (gt[:, 2] > 0) & (gt[:, 3] > 0)
    boxes = np.full((L, 4), np.nan)
    overlaps = np.full(L, np.nan)
    inits, failures = [], []
    start = _next_known(known, 0)
    if start is None:
        raise ValueError("no frame has a known ground-truth box; the reset protocol starts "
                         "(and restarts) on the ground truth.")
    while start is not None:
        inits.append(start)
        boxes[start] = gt[start]
        stream = iter(segment(start, gt[start].copy()))
        failed = None
        try:
            for i in range(start + 1, L):
                try:
                    b = next(stream)
                except StopIteration:
                    raise ValueError(f"segment stopped after frame {i - 1}; it must yield a box "
                                     f"for every frame after its start ({L - 1} is the last)."
                                     ) from None
                boxes[i] = np.asarray(b, dtype=float).reshape(4)
                o = float(metrics.iou(boxes[i][None], gt[i][None])[0])
                overlaps[i] = o
                if o == 0.0:
                    failed = i
                    break
        finally:
            close = getattr(stream, "close", None)
            if callable(close):
                close()
        if failed is None:
            break
        failures.append(failed)
        start = _next_known(known, failed + skip)
    return ResetRun(boxes, overlaps, tuple(inits), tuple(failures), burnin)


def _next_known(known, i):
    later = np.flatnonzero(known[i:])
    return int(i + later[0]) if later.size else None


class _ForwardFrames:
    """Frames read once, in order (a video decodes forwards; the protocol never goes back)."""

    def __init__(self, frames):
        self._it, self._i, self._frame = iter(frames), -1, None

    def at(self, i: int):
        while self._i < i:
            self._frame, self._i = next(self._it), self._i + 1
        return self._frame


def evaluate_reset(name_or_tracker, clip, seed: int | None = 0, preset: str = "book",
                   skip: int = 5, burnin: int = 10, **params) -> ResetRun:
    """Run a tracker through VOT's reset-based protocol (:func:`reset_protocol`) on a clip.

    The tracker is made once (as :func:`trackbook.evaluate` makes it from a name, ``seed``,
    ``preset`` and ``params``) and ``init`` again on the ground truth at every
    re-initialisation, which re-seeds it: same seed, same boxes. The ground truth is
    clipped to the frame before it is given, as :func:`trackbook.evaluate` does.
    """
    clip = _clips.load(clip)
    if isinstance(name_or_tracker, str):
        tracker = _trackers.create(name_or_tracker, seed=seed, preset=preset, **params)
    elif params or preset != "book":
        raise ValueError("params and preset can only be given with a tracker name, not a "
                         "tracker object.")
    elif not (hasattr(name_or_tracker, "init") and hasattr(name_or_tracker, "update")):
        raise ValueError(f"{name_or_tracker!r} is not a tracker: pass a registered name "
                         "or an object with init(frame, bbox) / update(frame) methods.")
    else:
        tracker = name_or_tracker
    frames = _ForwardFrames(clip.frames)

    def segment(start, box):
        frame = frames.at(start)
        box = clip_box(box, frame.shape)
        if type(tracker).__module__.startswith("cv2"):   # OpenCV's trackers take integers
            x, y, w, h = np.rint(box).astype(int).tolist()
            tracker.init(frame, (x, y, max(w, 1), max(h, 1)))
        else:
            tracker.init(frame, tuple(float(v) for v in box))
        i = start
        while True:
            i += 1
            yield tracker.update(frames.at(i))[1]

    try:
        run = reset_protocol(segment, clip.groundtruth, skip=skip, burnin=burnin)
    finally:
        close = getattr(tracker, "close", None)
        if isinstance(name_or_tracker, str) and callable(close):
            close()
    return dataclasses.replace(run, tracker=_name(name_or_tracker), clip=clip.name)


# -- VOT: expected average overlap -------------------------------------------------------------

def eao_curve(runs, n_max: int | None = None) -> np.ndarray:
    """The expected average overlap curve :math:`\\langle\\Phi_N\\rangle`, N = 0..n_max.

    Kristan et al. (2015, 2016): every initialisation of a reset run starts a fragment
    with overlaps :math:`\\phi_1, \\dots, \\phi_m` (the frames after the initialisation, up to
    a failure or the end; :meth:`ResetRun.fragments`). The average overlap of a fragment on a
    sequence of N frames is

    .. math:: \\Phi_N = \\frac{1}{N} \\sum_{i=1}^{N} \\phi_i,
              \\qquad \\phi_i = 0 \\text{ for } i > m \\text{ if the fragment failed,}

    defined for a failed fragment at every N (a tracker that failed would have stayed lost)
    and for one that reached the end of the clip only for :math:`N \\le m`.
    :math:`\\langle\\Phi_N\\rangle` is the mean of :math:`\\Phi_N` over the fragments, of all
    runs, where it is defined, each fragment weighing the same. This is the toolkit's
    supervised EAO curve (fragments cut at the initialisations, zero-padded after a
    failure, each of weight 1); like it, no burn-in applies here. Frames of unknown ground
    truth are left out of a fragment's mean. Two details differ from the toolkit's
    ``estimate_expected_overlap.m``: its length :math:`N_s` counts the initialisation frame
    (whose overlap it does not score), so its :math:`N_s` is N + 1 here; and a failure in the
    last ``skip`` frames of a run, after which no re-initialisation follows, leaves the
    toolkit's last fragment unpadded (as if it had reached the end), while here it is a
    failed fragment like any other.

    Returns
    -------
    (n_max + 1,) array, entry N is :math:`\\langle\\Phi_N\\rangle`; NaN at N = 0 and where no
    fragment is defined. ``n_max`` defaults to the longest run's length minus 1.
    """
    runs = list(runs)
    if not runs or not all(isinstance(r, ResetRun) for r in runs):
        raise ValueError("eao needs a list of ResetRun (from evaluate_reset or reset_protocol).")
    n_max = max(len(r) for r in runs) - 1 if n_max is None else int(n_max)
    if n_max < 1:
        raise ValueError(f"n_max = {n_max}: the curve needs sequence lengths from 1 up.")
    frags = [f for r in runs for f in r.fragments()]
    vals = np.zeros((len(frags), n_max))
    known = np.zeros((len(frags), n_max), dtype=bool)
    defined = np.zeros((len(frags), n_max), dtype=bool)
    for j, (o, failed) in enumerate(frags):
        m = min(len(o), n_max)
        vals[j, :m] = np.nan_to_num(o[:m])
        known[j, :m] = ~np.isnan(o[:m])
        known[j, m:] = failed                    # the zeros after a failure are scored
        defined[j] = failed | (np.arange(1, n_max + 1) <= len(o))
    count = np.cumsum(known, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        phi = np.cumsum(vals, axis=1) / count
    defined &= count > 0
    n_def = defined.sum(axis=0)
    curve = np.full(n_max + 1, np.nan)
    with np.errstate(invalid="ignore"):
        curve[1:] = np.where(n_def > 0, np.where(defined, phi, 0.0).sum(axis=0) / n_def, np.nan)
    return curve


def eao(runs, n_range: tuple[int, int] | None = None) -> float:
    """The expected average overlap, :math:`\\hat\\Phi = \\operatorname{mean}_{N = N_{lo}}^{N_{hi}}
    \\langle\\Phi_N\\rangle` (:func:`eao_curve`), Kristan et al. (2015, 2016).

    Kristan et al. (2015, 2016) write :math:`\\frac{1}{N_{hi} - N_{lo}} \\sum_{N = N_{lo}}^{N_{hi}}`; this takes
    the mean over the :math:`N_{hi} - N_{lo} + 1` lengths of the range, as the toolkit does
    (the printed normaliser would lift every score by
    :math:`(N_{hi} - N_{lo} + 1) / (N_{hi} - N_{lo})`).

    VOT picks :math:`[N_{lo}, N_{hi}]` from its dataset's sequence lengths, the interval
    around the mode of their density holding half the mass (VOT2015: [108, 371]); pass that
    as ``n_range``, less 1 at both ends (the toolkit's lengths count the initialisation
    frame, see :func:`eao_curve`), for such a dataset. The default for trackbook's short
    clips is :math:`[1, L - 1]`, L the longest run's length: one clip has one length, so
    there is no distribution to take an interval of, and a fixed VOT interval longer than the
    clip would leave only failed fragments defined (a tracker that never fails would have no
    score).
    On :math:`[1, L - 1]` every N has a defined fragment (the longest run's first one: it
    failed, or reached the end after L - 1 frames), and all horizons up to the clip's weigh
    the same.
    """
    runs = list(runs)
    if not runs or not all(isinstance(r, ResetRun) for r in runs):
        raise ValueError("eao needs a list of ResetRun (from evaluate_reset or reset_protocol).")
    if n_range is None:
        lo, hi = 1, max(len(r) for r in runs) - 1
    else:
        lo, hi = (int(v) for v in n_range)
    if not 1 <= lo <= hi:
        raise ValueError(f"n_range = {n_range}: give (N_lo, N_hi) with 1 <= N_lo <= N_hi.")
    curve = eao_curve(runs, hi)
    part = curve[lo:hi + 1]
    if np.isnan(part).any():
        bad = lo + int(np.flatnonzero(np.isnan(part))[0])
        raise ValueError(f"no fragment is defined at sequence length N = {bad} (no run failed "
                         f"and none is that long); choose n_range within the clips' lengths.")
    return float(part.mean())
