"""Correlation-filter trackers: MOSSE (Bolme et al. 2010) and KCF (Henriques et al. 2015).

``mosse``
    A linear filter on the grey patch (log transform, zero mean and unit norm, cosine
    window), trained so its response on the target is a Gaussian peak:
    H* = A / (B + λ) with A = Σ G ⊙ F*, B = Σ F ⊙ F* kept as running averages of learning
    rate η (Bolme et al. 2010). The first frame trains on random affine
    perturbations of the first patch. The peak-to-sidelobe ratio (PSR) of the response is
    the confidence.
``kcf``
    Kernel ridge regression over all cyclic shifts of a padded window of gradient-orientation
    cells (``trackbook.features.gradient_cells``: the HOG cells of ``03_hog``), Gaussian
    kernel, solved in the Fourier domain: α̂ = ŷ / (k̂^{xx} + λ); detection
    f̂(z) = k̂^{xz} ⊙ α̂; the model (α̂ and the features x) is linearly interpolated with
    rate η. No scale search: the paper's KCF has none.

Lost rule (both)
----------------
In order, on every frame:

1. A frame whose grey levels span at most ``flat_range`` (all black, all white) carries
   nothing to match: ``ok=False``, the box stays, the model is not updated.
2. The filter's peak moves the box. A box with less than ``min_visible`` of its area in the
   frame (:func:`~trackbook.trackers.lost.visible_fraction`) is a target leaving: lost.
3. A peak whose confidence (the peak-to-sidelobe ratio, PSR) reaches the threshold must also
   match the first frame's kernel colour histogram (HSV 8 x 8 x 4, eq. 1 of Lee et al. 2012,
   :class:`~trackbook.trackers.lost.ColourCheck`, when ``colour_check``): the match may not
   fall far below its recent range (:class:`~trackbook.trackers.lost.MatchGate`) unless the
   box stands out by colour from the boxes around it. Passed: ``ok=True`` and the model
   learns the frame. Nothing else updates the model.
4. Otherwise, with ``redetect``, the whole frame is searched: first by colour
   (:meth:`~trackbook.trackers.lost.ColourCheck.search`, about 325 histograms), the best
   box taken if its colours pass the gate, it is in view and the filter answers there with
   a PSR at the threshold; else by the filter itself over overlapping tiles of the window's
   size (a bounded number per frame, swept round robin), the best tile taken if its PSR
   reaches ``redetect_factor`` x the threshold and its colours pass the gate.
5. Otherwise a peak below the threshold whose box is in view and stands out by colour from
   the boxes around it is kept, ``ok=True`` without learning (the filter's template has
   faded; the target is still the best colour match around). Anything else: ``ok=False``,
   the box stays.

The gate has no absolute floor: under a sudden change of light every colour match drops,
and the target is told from a drift by its range and by standing out. The paper preset runs
only the rule Bolme et al. 2010 give for MOSSE (PSR below 7 is lost) and, for KCF
(Henriques et al. 2015, no lost rule), never reports a loss: ``min_visible = 0``, no colour
check, no re-detection.

>>> from trackbook import trackers, clips
>>> clip = clips.load("red-cube")                                              # doctest: +SKIP
>>> t = trackers.create("kcf"); t.init(clip.frames[0], clip.groundtruth[0])    # doctest: +SKIP
>>> ok, box = t.update(clip.frames[1]); t.confidence, t.response.shape         # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses

import cv2
import numpy as np

from ..features.gradient_cells import orientation_cells
from ..features.patches import sample_patches
from ..filters import correlation as cf
from ..params import NOT_PRINTED, param
from .base import Tracker, readonly
from .lost import ColourCheck, MatchGate, visible_fraction
from .registry import register

#: Random affine perturbations of the first patch: rotation up to ±this/2 rad and each
#: entry of the linear part up to ±this/2 (the spread of OpenCV's ``mosse.py`` sample).
PERTURBATION = 0.2

#: At most about this many re-detection tiles cover a frame.
MAX_TILES = 400
#: Patch pixels searched per lost frame (a bounded cost per frame; see ``_redetect``).
TILE_PIXELS = 150_000
_REF_CODE = ("the authors' reference code (run_tracker.m, 'parameters according to the "
             "paper')")


def _redetect_param(threshold_name: str):
    return param(
        True, doc="search the whole frame in tiles while the target is lost",
        paper=NOT_PRINTED, paper_value=False,   # in neither paper
        why=f"the book's addition: without it a target that leaves the view and reappears "
            f"outside the search window is never found again; a tile must pass "
            f"redetect_factor x {threshold_name}")


def _redetect_factor_param():
    return param(
        1.5, 1.0, 5.0, 0.1, doc="a re-detected tile's confidence must reach this times the "
        "threshold",
        paper=NOT_PRINTED,   # not in the paper
        why="the book's addition: among dozens of tiles one background tile can pass the "
            "plain threshold by chance; a margin keeps the absent target lost")


def _min_visible_param():
    return param(
        0.5, 0.0, 1.0, 0.05, doc="a box with less than this fraction of its area in the frame "
        "is lost (the target is leaving)",
        paper=NOT_PRINTED, paper_value=0.0,   # neither paper has a border rule
        why="the book's rule, as every tracker's: a filter keeps finding a peak on the "
            "background left in its window when the target leaves across the border")


def _colour_check_param():
    return param(
        True, doc="check the box against the first frame's kernel colour histogram (eq. 1 "
        "of Lee et al. 2012) and search the frame by colour while lost",
        paper=NOT_PRINTED, paper_value=False,   # in neither paper
        why="the book's rule, as opencv-mil's: a filter that has drifted onto texture, or "
            "onto an occluder, can still answer with a sharp peak; the target's colours "
            "are not there")


@dataclasses.dataclass(frozen=True)
class MosseParams:
    # Bolme, Beveridge, Draper, Lui, CVPR 2010 (bolme2010). The paper's text is not among the
    # book's sources; the values marked paper= are those the public re-implementations
    # attribute to it (OpenCV's mosse.py sample uses η = 0.125).
    eta: float = param(
        0.125, 0.0, 1.0, 0.005, doc="η, learning rate of the running averages A_i, B_i",
        paper=0.125)   # Bolme et al. 2010's η; OpenCV's mosse.py sample uses it too
    psr_threshold: float = param(
        7.0, 0.0, 50.0, 0.5, doc="PSR below this: target lost, no update",
        paper=7.0)     # Bolme et al. 2010: a PSR near 7 signals occlusion or failure
    n_perturbations: int = param(
        8, 1, 128, 1, doc="random affine perturbations of the first patch trained on",
        paper=8)       # Bolme et al. 2010: eight perturbations of the first window
    sigma: float = param(
        2.0, 0.5, 10.0, 0.25, doc="σ (px) of the Gaussian target response g",
        paper=NOT_PRINTED,   # not quoted here from the paper's text; the book uses 2 px
        why="2 px as in OpenCV's mosse.py sample, a reimplementation of the paper; "
            "the peak is then sharp against an 11 x 11 excluded window")
    lam: float = param(
        1e-5, 1e-8, 1.0, None, doc="λ (ε) added to the denominator B of H* = A / (B + λ)",
        paper=NOT_PRINTED,   # the paper's regulariser is not quoted here with a value
        why="1e-5 as in OpenCV's mosse.py sample: with unit-norm patches B averages 1 per "
            "frequency, so λ only guards frequencies with no energy")
    redetect: bool = _redetect_param("psr_threshold")
    redetect_factor: float = _redetect_factor_param()
    min_visible: float = _min_visible_param()
    colour_check: bool = _colour_check_param()


@dataclasses.dataclass(frozen=True)
class KcfParams:
    # Henriques, Caseiro, Martins, Batista, TPAMI 2015 (henriques2015), Gaussian kernel, HOG.
    padding: float = param(
        1.5, 0.0, 4.0, 0.25, doc="window = target size × (1 + padding)",
        paper=1.5)   # 1.5 in the paper's parameters and in _REF_CODE
    lam: float = param(
        1e-4, 1e-8, 1.0, None, doc="λ of the kernel ridge regression",
        paper=1e-4)  # 1e-4 in the paper's parameters and in _REF_CODE
    kernel_sigma: float = param(
        0.5, 0.05, 5.0, 0.05, doc="σ of the Gaussian kernel, HOG features",
        paper=0.5)   # 0.5 for HOG features in the paper's parameters and in _REF_CODE
    eta: float = param(
        0.02, 0.0, 1.0, 0.005, doc="η, interpolation factor of the model (α̂ and x)",
        paper=0.02)  # 0.02 for HOG features in the paper's parameters and in _REF_CODE
    output_sigma_factor: float = param(
        0.1, 0.01, 1.0, 0.01, doc="σ_y of the labels = sqrt(w h) × this / cell",
        paper=0.1)   # 0.1 (spatial bandwidth) in the paper's parameters and in _REF_CODE
    cell: int = param(
        4, 1, 8, 1, doc="HOG cell side in pixels",
        paper=4)     # cell_size = 4 in _REF_CODE (FHOG cells)
    bins: int = param(
        8, 4, 18, 1, doc="signed orientation bins per cell (feature channels)",
        paper=9,     # hog_orientations = 9 in _REF_CODE: FHOG's 18 signed + 9 unsigned + 4
        why="the book's 8 signed bins of 03_hog (exact octant binning) instead of FHOG's "
            "31 channels, so the features are the HOG cells the reader already knows; "
            "paper preset: 9 signed bins of the same cells, not FHOG")
    psr_threshold: float = param(
        7.0, 0.0, 50.0, 0.5, doc="PSR of the response below this: target lost, no update",
        paper=NOT_PRINTED, paper_value=0.0,   # the paper's KCF never declares a loss
        why="the book's choice: MOSSE's PSR rule and threshold of 7 (Bolme et al. 2010) on "
            "KCF's response, its sidelobe excluding ±3 σ_y around the peak; the peak value "
            "separated target from background less well on the lost-and-found probe")
    redetect: bool = _redetect_param("psr_threshold")
    redetect_factor: float = _redetect_factor_param()
    min_visible: float = _min_visible_param()
    colour_check: bool = _colour_check_param()


class _CorrelationTracker(Tracker):
    """What both trackers share: the window around the centre, the lost rule, re-detection.

    Confidence: ``state().confidence`` is ``confidence`` below, the peak-to-sidelobe ratio
    PSR = (g_max - mu_s) / sigma_s of the response that placed the box (the re-detected
    window's when re-detection found the target, else the window at the last position; see
    :func:`trackbook.filters.correlation.psr`); 0 on a constant frame (nothing matched).

    Attributes (read-only, for drawing)
    -----------------------------------
    response : the last response map (cyclic: index 0 is "no move")
    confidence : the last frame's confidence (PSR or peak value)
    search_window : (x, y, w, h) of the last window searched
    """

    #: Minimum side of the sampled window, in px of the patch.
    min_side = 8
    #: Whether a peak at ``redetect_factor`` x the threshold or above is kept whatever the
    #: colour says (see each tracker's "Lost rule").
    firm_peak_vouches = False

    # -- geometry ----------------------------------------------------------------------
    def _window_box(self, centre):
        """(x, y, w, h) of the search window centred on ``centre`` in frame pixels."""
        ww, wh = self._window
        return (centre[0] - ww / 2.0, centre[1] - wh / 2.0, ww, wh)

    def _patches(self, gray, centres):
        boxes = np.array([self._window_box(c) for c in centres], dtype=float)
        return sample_patches(gray, boxes, self._patch_size)

    def _tile_centres(self, shape):
        """Centres of the re-detection tiles: every half target size, windows kept in frame."""
        H, W = shape[:2]
        ww, wh = self._window
        # Half a target size apart, but never more than about MAX_TILES tiles (a tiny box in
        # a large frame would otherwise make tens of thousands).
        spread = np.sqrt(W * H / MAX_TILES)
        sx, sy = max(self._size[0] / 2.0, spread, 1.0), max(self._size[1] / 2.0, spread, 1.0)
        x0, x1 = min(ww / 2.0, W / 2.0), max(W - ww / 2.0, W / 2.0)
        y0, y1 = min(wh / 2.0, H / 2.0), max(H - wh / 2.0, H / 2.0)
        xs = np.append(np.arange(x0, x1, sx), x1)
        ys = np.append(np.arange(y0, y1, sy), y1)
        X, Y = np.meshgrid(xs, ys)
        return np.column_stack([X.ravel(), Y.ravel()])

    def _drawn(self) -> dict:
        """The last search window (``Tracker.state()``)."""
        sw = getattr(self, "search_window", None)
        return {**super()._drawn(),
                "search_window": None if sw is None else tuple(float(v) for v in sw)}

    def _box(self):
        w, h = self._size
        return np.array([self._centre[0] - w / 2.0, self._centre[1] - h / 2.0, w, h])

    # -- the loop ------------------------------------------------------------------------
    def _init(self, frame, box):
        x, y, w, h = (float(v) for v in box)
        self._size = (w, h)
        self._centre = (x + w / 2.0, y + h / 2.0)
        self._setup_geometry(w, h)
        gray = cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY).astype(np.float32)
        self._train_first(gray)
        self.confidence = float("inf")
        self.response = np.zeros(self._response_shape)
        self.search_window = self._window_box(self._centre)
        self._sweep = 0
        self._colour = ColourCheck(frame, box) if self.params.colour_check else None
        # No absolute floor: under a sudden change of light every colour match drops, and
        # the target is told from a drift by standing out from the boxes around it.
        self._gate = MatchGate(floor=0.0)

    def _update(self, frame):
        if self._is_flat(frame):
            self.confidence = 0.0
            return False, self._box()
        gray = cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY).astype(np.float32)
        feats = self._features(self._patches(gray, [self._centre]))
        resp = self._responses(feats)[0]
        conf = float(self._confidence(resp[None])[0])
        self.response, self.confidence = resp, conf
        self.search_window = self._window_box(self._centre)
        dy, dx = cf.peak_offset(resp)
        centre = self._moved(self._centre, dy, dx)
        sure = conf >= self._threshold()
        in_view = self._in_view(centre, frame.shape)
        firm = self.firm_peak_vouches and \
            conf >= self.params.redetect_factor * self._threshold()
        if sure and in_view and (firm or self._colour_ok(frame, centre, True)):
            self._centre = centre
            self._learn(gray)
            return True, self._box()
        if self.params.redetect:
            found = self._redetect(frame, gray)
            if found is not None:
                self._centre = found
                self._sweep = 0
                return True, self._box()
        if not sure and in_view and self._colour_ok(frame, centre, False):
            self._centre = centre
            return True, self._box()
        return False, self._box()

    def _last_confidence(self) -> float:
        """The PSR of the last frame's response (``confidence``), stored by ``_update``."""
        return float(self.confidence)

    def _box_at(self, centre):
        w, h = self._size
        return np.array([centre[0] - w / 2.0, centre[1] - h / 2.0, w, h])

    def _in_view(self, centre, shape):
        """Whether at least ``min_visible`` of the box at ``centre`` is in the frame."""
        return visible_fraction(self._box_at(centre), shape) >= self.params.min_visible

    def _colour_ok(self, frame, centre, sure):
        """The colour half of the lost rule. A sure peak (PSR at the threshold or above) must
        match the first frame's colours (``MatchGate``: not poor, not far below its recent
        range unless it stands out from the boxes around it); an unsure peak is kept only
        when its colours pass the gate *and* stand out (the filter's template has faded, the
        target is still the best colour match around)."""
        if self._colour is None:
            return sure
        box = self._box_at(centre)
        rho = float(self._colour.match(frame, box[None])[0])

        def stands_out():
            return self._colour.stands_out(frame, box, rho, floor=0.0)

        if sure:
            return not self._gate.lost(rho, stands_out)
        return stands_out() and not self._gate.lost(rho, lambda: True)

    def _moved(self, centre, dy, dx):
        s = self._step
        return (centre[0] + dx * s, centre[1] + dy * s)

    def _redetect(self, frame, gray):
        """While lost: the best colour match of the frame (``ColourCheck.search``, bounded),
        taken when its colours pass the gate and the filter answers there at the threshold;
        else the filter over the frame's tiles (``_tile_sweep``)."""
        if self._colour is not None:
            box, rho = self._colour.search(frame, max_boxes=300, size=self._size)
            c = (box[0] + box[2] / 2.0, box[1] + box[3] / 2.0)
            if self._in_view(c, frame.shape) and not self._gate.lost(rho):
                resp = self._responses(self._features(self._patches(gray, [c])))[0]
                conf = float(self._confidence(resp[None])[0])
                found = self._moved(c, *cf.peak_offset(resp))
                if conf >= self._threshold() and self._in_view(found, frame.shape):
                    self.response, self.confidence = resp, conf
                    self.search_window = self._window_box(c)
                    return found
        return self._tile_sweep(frame, gray)

    def _tile_sweep(self, frame, gray):
        """Search the frame's tiles for the target; the tiles are swept ``TILE_PIXELS`` of
        patch a frame at a time (round robin), so a lost frame costs a bounded time and a
        full sweep of a large frame takes a few frames. The best tile must pass
        ``redetect_factor`` x the threshold, and the colour gate when it is on."""
        centres = self._tile_centres(gray.shape)
        n = len(centres)
        k = int(min(n, max(1, TILE_PIXELS // (self._patch_size[0] * self._patch_size[1]))))
        pick = (self._sweep + np.arange(k)) % n
        self._sweep = int((self._sweep + k) % n)
        centres = centres[pick]
        feats = self._features(self._patches(gray, centres))
        resp = self._responses(feats)
        conf = self._confidence(resp)
        i = int(np.argmax(conf))
        if not conf[i] >= self.params.redetect_factor * self._threshold():
            return None
        dy, dx = cf.peak_offset(resp[i])
        found = self._moved(centres[i], dy, dx)
        if not self._in_view(found, frame.shape):
            return None
        if self._colour is not None and self._gate.lost(
                float(self._colour.match(frame, self._box_at(found)[None])[0])):
            return None
        self.response, self.confidence = resp[i], float(conf[i])
        self.search_window = self._window_box(centres[i])
        return found

    def _learn(self, gray):
        feats = self._features(self._patches(gray, [self._centre]))[0]
        self._update_model(feats)

    # -- what each tracker implements -----------------------------------------------------
    def _setup_geometry(self, w, h):  # pragma: no cover
        raise NotImplementedError

    def _train_first(self, gray):  # pragma: no cover
        raise NotImplementedError

    def _features(self, patches):  # pragma: no cover
        raise NotImplementedError

    def _responses(self, feats):  # pragma: no cover
        raise NotImplementedError

    def _confidence(self, responses):  # pragma: no cover
        raise NotImplementedError

    def _threshold(self):  # pragma: no cover
        raise NotImplementedError

    def _update_model(self, feats):  # pragma: no cover
        raise NotImplementedError


@register
class MosseTracker(_CorrelationTracker):
    """MOSSE, Bolme et al. 2010: an adaptive linear correlation filter on the grey patch.

    The window is the target's box (the paper's tracking window), sampled at the box's own
    size (at least ``min_side`` px a side). Preprocessing: log(I + 1), zero mean
    and unit norm, cosine window. Training: A = Σ G ⊙ F*, B = Σ F ⊙ F* over
    ``n_perturbations`` random affine warps of the first patch, then A_i = η G ⊙ F_i* +
    (1 − η) A_{i−1} and B_i likewise on every accepted frame; H* = A / (B + λ).
    Lost rule
    ---------
    The module's rule, with the PSR threshold ``psr_threshold`` (7, Bolme et al.'s). The
    window is the target's box alone, so a PSR of ``redetect_factor`` x the threshold or more
    is the target's own grey pattern: such a peak is kept without asking the colours (the log
    and unit-norm preprocessing make the filter blind to a change of light; the colour
    histogram is not).

    Confidence
    ----------
    ``state().confidence`` is Bolme et al.'s peak-to-sidelobe ratio of the last response g,
    PSR = (g_max - mu_s) / sigma_s, mu_s and sigma_s the mean and standard deviation of the
    sidelobe: the response without the 11 x 11 window around the peak (cyclic); 0 on a
    constant frame or a flat sidelobe. :func:`trackbook.filters.correlation.apce` gives the
    average peak-to-correlation energy of a response, another sharpness measure.
    """

    name = "mosse"
    Params = MosseParams
    # The window is the target's box alone: a firm peak is the target's own grey pattern
    # (log and unit-norm preprocessing make it blind to a change of light, which the colour
    # histogram is not).
    firm_peak_vouches = True

    def _setup_geometry(self, w, h):
        ww, wh = max(w, self.min_side), max(h, self.min_side)
        pw, ph = int(round(ww)), int(round(wh))
        self._patch_size = (pw, ph)
        self._window = (ww, wh)
        self._response_shape = (ph, pw)
        self._hann = cf.hann_window(ph, pw)
        self._G = np.fft.fft2(cf.gaussian_labels(ph, pw, self.params.sigma))

    def _moved(self, centre, dy, dx):
        sx = self._window[0] / self._patch_size[0]
        sy = self._window[1] / self._patch_size[1]
        return (centre[0] + dx * sx, centre[1] + dy * sy)

    def _features(self, patches):
        """Preprocessing of Bolme et al.: log, zero mean, unit norm, cosine window -> spectra."""
        f = np.log1p(np.asarray(patches, dtype=np.float64))
        f -= f.mean(axis=(1, 2), keepdims=True)
        norm = np.sqrt(np.sum(f * f, axis=(1, 2), keepdims=True))
        f = np.where(norm > 1e-9, f / np.where(norm > 1e-9, norm, 1.0), 0.0)
        return np.fft.fft2(f * self._hann)

    def _train_first(self, gray):
        p = self._patches(gray, [self._centre])[0]
        ph, pw = p.shape
        warps = []
        for _ in range(self.params.n_perturbations):
            a = (self.rng.random() - 0.5) * PERTURBATION
            c, s = np.cos(a), np.sin(a)
            T = np.array([[c, -s], [s, c]]) + (self.rng.random((2, 2)) - 0.5) * PERTURBATION
            centre = np.array([pw / 2.0, ph / 2.0])
            M = np.column_stack([T, centre - T @ centre])
            warps.append(cv2.warpAffine(p, M, (pw, ph), borderMode=cv2.BORDER_REFLECT))
        F = self._features(np.stack(warps))
        self._A, self._B = cf.mosse_terms(F, self._G)
        self._H = cf.mosse_filter(self._A, self._B, self.params.lam)

    def _responses(self, F):
        return cf.linear_response(self._H, F)

    def _confidence(self, responses):
        return np.atleast_1d(cf.psr(responses))

    def _threshold(self):
        return self.params.psr_threshold

    def _update_model(self, F):
        eta = self.params.eta
        A, B = cf.mosse_terms(F, self._G)
        self._A = eta * A + (1 - eta) * self._A
        self._B = eta * B + (1 - eta) * self._B
        self._H = cf.mosse_filter(self._A, self._B, self.params.lam)

    @property
    def filter(self):
        """The spatial filter h = ifft2(conj(H*)) (for drawing)."""
        return readonly(np.fft.ifft2(np.conj(self._H)).real)


@register
class KcfTracker(_CorrelationTracker):
    """KCF, Henriques et al. 2015: kernelised correlation filter on gradient-orientation cells.

    The window is the target's size × (1 + ``padding``), cut into ``cell``-px cells
    (targets of sqrt(w h) ≥ 100 px are sampled at half resolution, as in the authors'
    reference code). Features: :func:`~trackbook.features.gradient_cells.orientation_cells`
    times a cosine window. Labels: a Gaussian of σ_y = sqrt(w h) · ``output_sigma_factor`` /
    cell cells. Training: α̂ = ŷ / (k̂^{xx} + λ) with the Gaussian kernel correlation;
    detection f(z) = ifft2(k̂^{xz} ⊙ α̂); model α̂ ← (1 − η) α̂ + η α̂_new, x̂ likewise.
    Lost rule
    ---------
    The module's rule, with the PSR threshold ``psr_threshold`` on KCF's response (its
    sidelobe excluding ±3 σ_y around the peak). Every accepted peak must pass the colour
    check, however high its PSR: the padded window is mostly background, which keeps matching
    the model while an occluder covers the target.

    Confidence
    ----------
    ``state().confidence`` is the peak-to-sidelobe ratio of the last response f(z),
    PSR = (f_max - mu_s) / sigma_s, with the sidelobe excluding a square of side
    2 ceil(3 sigma_y) + 1 cells around the peak (the labels' own peak; Bolme et al.'s 11 x 11
    is in pixels, KCF's response is in cells); 0 on a constant frame or a flat sidelobe.
    """

    name = "kcf"
    Params = KcfParams

    def _setup_geometry(self, w, h):
        p = self.params
        scale = 2.0 if np.sqrt(w * h) >= 100 else 1.0
        c = p.cell
        cols = max(int((w * (1 + p.padding)) / scale // c), 3)
        rows = max(int((h * (1 + p.padding)) / scale // c), 3)
        self._patch_size = (cols * c, rows * c)
        self._window = (cols * c * scale, rows * c * scale)
        self._step = c * scale
        self._response_shape = (rows, cols)
        self._hann = cf.hann_window(rows, cols)
        sigma_y = np.sqrt(w * h) / scale * p.output_sigma_factor / c
        self._yf = np.fft.fft2(cf.gaussian_labels(rows, cols, max(sigma_y, 1e-3)))
        # The sidelobe leaves out ±3 σ_y around the peak (the labels' own peak), and keeps at
        # least a ring of cells whatever the window's size.
        self._exclude = int(min(2 * np.ceil(3 * sigma_y) + 1, max(min(rows, cols) - 2, 1)))

    def _features(self, patches):
        x = orientation_cells(np.asarray(patches, dtype=np.float64) / 255.0, self.params.cell,
                              self.params.bins)
        return np.fft.fft2(x * self._hann)

    def _train_first(self, gray):
        xf = self._features(self._patches(gray, [self._centre]))[0]
        self._xf = xf
        self._alphaf, _ = cf.kcf_train(xf, self._yf, self.params.kernel_sigma, self.params.lam)

    def _responses(self, zf):
        return cf.kcf_response(self._alphaf, self._xf, zf, self.params.kernel_sigma)

    def _confidence(self, responses):
        return np.atleast_1d(cf.psr(responses, self._exclude))

    def _threshold(self):
        return self.params.psr_threshold

    def _update_model(self, xf):
        p = self.params
        alphaf, _ = cf.kcf_train(xf, self._yf, p.kernel_sigma, p.lam)
        self._alphaf = (1 - p.eta) * self._alphaf + p.eta * alphaf
        self._xf = (1 - p.eta) * self._xf + p.eta * xf


__all__ = ["MosseTracker", "KcfTracker", "MosseParams", "KcfParams"]
