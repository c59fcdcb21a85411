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

Failure and re-detection (both)
-------------------------------
Each frame is located (the response's peak moves the box, the PSR of the response is the
confidence) and then judged by the failure-detection layer
(:class:`~trackbook.trackers.failure.FailureDetector`, the tracker's calibrated thresholds); a
frame whose grey levels span at most ``flat_range`` is lost whatever the PSR. The model learns
only on frames judged on target; a lost frame keeps the last box. MOSSE adds the rule Bolme et
al. 2010 print: a PSR below ``psr_threshold`` (7) is a failure, and the filter is not updated.
KCF (Henriques et al. 2015) prints no failure rule. ``mosse-redetect`` and ``kcf-redetect``
add the re-detection layer: while lost, windows over the whole frame are scored by the PSR of
the filter's response there (:meth:`~trackbook.trackers.base.Tracker._redetect`) and the
search restarts from the best.

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
from ..features.hog import to_gray
from ..features.patches import sample_patches
from ..filters import correlation as cf
from ..params import NOT_PRINTED, param
from ._per_frame import PerFrame
from .base import Tracker, centred_response, readonly, redetecting
from .registry import register

#: Random affine perturbations of the first patch: rotation up to ±this/2 rad and each
#: entry of the linear part up to ±this/2 (the spread of OpenCV's ``mosse.py`` sample).
PERTURBATION = 0.2

_REF_CODE = ("the authors' reference code (run_tracker.m, 'parameters according to the "
             "paper')")


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
        why="the book's 8 signed bins of the HOG chapter (exact octant binning) "
            "instead of FHOG's "
            "31 channels, so the features are the HOG cells the reader already knows; "
            "paper preset: 9 signed bins of the same cells, not FHOG")


class _CorrelationTracker(Tracker):
    """What both trackers share: the window around the centre, locating, learning, scoring.

    Confidence: ``state().confidence`` is ``confidence`` below, the peak-to-sidelobe ratio
    PSR = (g_max - mu_s) / sigma_s of the response at the last position (see
    :func:`trackbook.filters.correlation.psr`); 0 on a constant frame (nothing matched). The
    failure-detection layer judges it and decides ``ok``.

    Attributes (read-only, for drawing)
    -----------------------------------
    response : the last response map (cyclic: index 0 is "no move")
    confidence : the last frame's confidence (PSR)
    search_window : (x, y, w, h) of the last window searched
    """

    #: Minimum side of the sampled window, in px of the patch.
    min_side = 8

    # -- geometry ----------------------------------------------------------------------
    def _window_box(self, centre):
        """(x, y, w, h) of the search window centred on ``centre`` in frame pixels."""
        ww, wh = self._window
        return (centre[0] - ww / 2.0, centre[1] - wh / 2.0, ww, wh)

    def _patches(self, gray, centres):
        boxes = np.array([self._window_box(c) for c in centres], dtype=float)
        return sample_patches(gray, boxes, self._patch_size)

    def _drawn(self) -> dict:
        """The last search window and, after the first ``update``, the response over it
        (``Tracker.state()``): its cells tile the window (``step`` frame px each)."""
        sw = getattr(self, "search_window", None)
        out = {**super()._drawn(),
               "search_window": None if sw is None else tuple(float(v) for v in sw)}
        if sw is not None and self.frame_index > 0:
            R, C = np.shape(self.response)
            out.update(centred_response(self.response, (sw[0] + sw[2] / 2, sw[1] + sw[3] / 2),
                                        (sw[2] / C, sw[3] / R)))
        return out

    def _box(self):
        return self._box_at(self._centre)

    def _box_at(self, centre):
        w, h = self._size
        return np.array([centre[0] - w / 2.0, centre[1] - h / 2.0, w, h])

    def _gray(self, frame):
        """The frame in grey levels (float32), converted once per frame: ``_locate`` and
        ``_learn`` see the same frame."""
        return self._gray_of.get(
            frame, self.frame_index,
            lambda: to_gray(frame))

    # -- the two halves of a frame ----------------------------------------------------------
    def _init(self, frame, box):
        x, y, w, h = (float(v) for v in box)
        self._size = (w, h)
        self._centre = (x + w / 2.0, y + h / 2.0)
        self._setup_geometry(w, h)
        self._gray_of = PerFrame()
        self._train_first(self._gray(frame))
        self.confidence = float("inf")
        self.response = np.zeros(self._response_shape)
        self.search_window = self._window_box(self._centre)

    def _locate(self, frame):
        """The filter's response in the window at the last position; its peak places the box.

        Returns the box, the PSR of the response and, for MOSSE, whether the PSR reaches
        ``psr_threshold`` (Bolme et al.'s failure rule; KCF prints none: always True). The
        model and the position the next search starts from are not changed.
        """
        self.search_window = self._window_box(self._centre)
        if self._is_flat(frame):
            # nothing to correlate with: the response is zero, its PSR 0 (psr's convention)
            self.response, self.confidence = np.zeros(self._response_shape), 0.0
            return self._box(), 0.0, False
        feats = self._features(self._patches(self._gray(frame), [self._centre]))
        resp = self._responses(feats)[0]
        conf = float(self._confidence(resp[None])[0])
        self.response, self.confidence = resp, conf
        centre = self._moved(self._centre, *cf.peak_offset(resp))
        return self._box_at(centre), conf, self._own_ok(conf)

    def _learn(self, frame, box):
        """Move to ``box`` and update the filter with the window there."""
        self._centre = (box[0] + box[2] / 2.0, box[1] + box[3] / 2.0)
        feats = self._features(self._patches(self._gray(frame), [self._centre]))[0]
        self._update_model(feats)

    def _score_boxes(self, frame, boxes):
        """The PSR of the filter's response in the window centred on each box (one batch of
        FFTs, the model untouched): the re-detection layer's score."""
        boxes = np.asarray(boxes, dtype=float)
        centres = boxes[:, :2] + boxes[:, 2:] / 2.0
        feats = self._features(self._patches(self._gray(frame), centres))
        return np.asarray(self._confidence(self._responses(feats)), dtype=float)

    def _relocate(self, frame, box):
        """Restart the search at ``box``'s centre (the next frame's window is there)."""
        self._centre = (box[0] + box[2] / 2.0, box[1] + box[3] / 2.0)

    def _moved(self, centre, dy, dx):
        s = self._step
        return (centre[0] + dx * s, centre[1] + dy * s)

    def _own_ok(self, conf) -> bool:
        """The algorithm's own failure rule (none by default)."""
        return True

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

    Failure
    -------
    Bolme et al.'s rule: a PSR below ``psr_threshold`` (7) is an occlusion or a tracking
    failure, and the filter is not updated on that frame (the third value of ``_locate``).
    Besides it, the failure-detection layer decides ``ok`` from the PSR. ``mosse-redetect``
    adds the re-detection layer: while lost, the whole frame is searched by the filter's PSR.

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

    def _own_ok(self, conf) -> bool:
        """Bolme et al. 2010: a PSR below ``psr_threshold`` (7) is a failure, no update."""
        return conf >= self.params.psr_threshold

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

    Failure
    -------
    KCF has no failure rule of its own: the failure-detection layer decides ``ok`` from
    the PSR below, and the model is not updated on a frame judged lost. ``kcf-redetect`` adds
    the re-detection layer: while lost, windows over the whole frame are scored by the PSR of
    the KCF response there and the search restarts from the best.

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

    def _update_model(self, xf):
        p = self.params
        alphaf, _ = cf.kcf_train(xf, self._yf, p.kernel_sigma, p.lam)
        self._alphaf = (1 - p.eta) * self._alphaf + p.eta * alphaf
        self._xf = (1 - p.eta) * self._xf + p.eta * xf


register(redetecting(MosseTracker))
register(redetecting(KcfTracker))

__all__ = ["MosseTracker", "KcfTracker", "MosseParams", "KcfParams"]
