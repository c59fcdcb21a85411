"""DSST (Danelljan, Häger, Khan & Felsberg, BMVC 2014): a translation filter and a scale filter.

``dsst``
    Two discriminative correlation filters learned separately
    (:mod:`trackbook.filters.scale_filter`):

    - a **translation filter** on a window of (1 + padding) × the target, sampled at the
      current scale and resized to the first frame's window size: d channels (gradient-
      orientation histograms at every pixel and the grey level), a cosine window, and the
      multi-channel filter H^l = Ḡ F^l / (Σ_k F̄^k F^k + λ) trained on a 2-D Gaussian label;
    - a **scale filter**: S samples at scales a^n, n ∈ {−(S−1)/2 … (S−1)/2}, of the target
      size around the new position, each resized to a fixed model size and described by one
      HOG vector (cells of ``scale_cell`` px); the S vectors, times a cosine window over the
      scales, are d-channel 1-D signals over the scales, and the same multi-channel filter,
      trained on a 1-D Gaussian label over n, scores them.

    Each frame: the translation filter at the current scale moves the centre (the response's
    peak; refined by a parabola when a cell is more than one frame pixel, see ``_peak``); the scale filter at the new centre picks the scale (its response's peak); then both
    filters learn from samples at the new centre and scale, the numerators A and denominators
    B as running averages of learning rate η. The scale is kept between the reference code's
    limits (:func:`~trackbook.filters.scale_filter.scale_limits`).

Failure and re-detection
------------------------
DSST prints no failure rule. The confidence is the peak-to-sidelobe ratio (PSR) of the
translation response; the failure-detection layer judges it and the filters learn only on
frames judged on target. ``dsst-redetect`` adds the re-detection layer: while lost, windows
over the whole frame are scored by the PSR of the translation filter's response there.

>>> from trackbook import trackers, clips
>>> clip = clips.load("red-cube")                                              # doctest: +SKIP
>>> t = trackers.create("dsst"); t.init(clip.frames[0], clip.groundtruth[0])   # doctest: +SKIP
>>> ok, box = t.update(clip.frames[1]); t.confidence, t.scale                  # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses

import cv2
import numpy as np

from ..features.gradient_cells import orientation_cells
from ..filters import correlation as cf
from ..filters import scale_filter as sf
from ..params import NOT_PRINTED, param
from .base import readonly, redetecting
from .correlation import _CorrelationTracker
from .registry import register

#: Where the values marked "reference code" come from: the authors' DSST MATLAB code
#: (``run_tracker.m``, whose parameter block is headed as following the published values,
#: ``dsst.m``, ``get_translation_sample.m``, ``get_scale_sample.m``, ``get_feature_map.m``),
#: read in the copy kept in the public repository flyers/drone-tracking (trackers/DSST/) and,
#: for the parameter block, hexdjx/Visual-Tracking-Paper-List (DSST/run_tracker.m).
_REF_CODE = "the authors' DSST MATLAB code (run_tracker.m, dsst.m)"


@dataclasses.dataclass(frozen=True)
class DsstParams:
    # Danelljan, Häger, Khan, Felsberg, BMVC 2014 (danelljan2014). Danelljan et al.'s text is
    # not among the book's sources; the values below are _REF_CODE's parameter block, which
    # names each by its published symbol (λ, η, S, a) and is headed as following the
    # published values.
    padding: float = param(
        1.5, 0.0, 4.0, 0.25, doc="translation window = target size × (1 + padding)",
        paper=1.0,     # params.padding = 1.0 in _REF_CODE: a window twice the target
        why="1.5 (KCF's padding) chosen on data not reported: on the eight sample clips the "
            "mean AUC was 0.828 / 0.835 / 0.744 for padding 1 / 1.5 / 2, and leaving each "
            "real sequence out in turn, the other six chose 1.5 in six folds of seven (2 "
            "once): a window twice the target loses a target that moves more than about its "
            "half-width in a frame")
    output_sigma_factor: float = param(
        1 / 16, 0.01, 1.0, 0.005, doc="σ of the translation label = sqrt(w h) × this (px)",
        paper=1 / 16)  # params.output_sigma_factor = 1/16 in _REF_CODE
    scale_sigma_factor: float = param(
        0.25, 0.01, 2.0, 0.01, doc="σ of the scale label = S / √33 × this (scale steps)",
        paper=0.25)    # params.scale_sigma_factor = 1/4 in _REF_CODE (rule in dsst.m)
    lam: float = param(
        1e-2, 1e-6, 1.0, None, doc="λ, regulariser of both filters: H = A / (B + λ)",
        paper=1e-2)    # params.lambda = 1e-2 in _REF_CODE ("denoted lambda in the paper")
    eta: float = param(
        0.025, 0.0, 1.0, 0.005, doc="η, learning rate of the running averages A_t, B_t",
        paper=0.025)   # params.learning_rate = 0.025 in _REF_CODE ("denoted eta in the paper")
    n_scales: int = param(
        33, 1, 65, 2, doc="S, number of scale samples a^n",
        paper=33)      # params.number_of_scales = 33 in _REF_CODE ("denoted S in the paper")
    scale_step: float = param(
        1.02, 1.001, 1.2, 0.005, doc="a, ratio between neighbouring scale samples",
        paper=1.02)    # params.scale_step = 1.02 in _REF_CODE ("denoted a in the paper")
    scale_model_max_area: float = param(
        512.0, 16.0, 4096.0, 16.0, doc="most pixels of the size each scale sample is "
        "resized to", paper=512.0)  # params.scale_model_max_area = 512 in _REF_CODE
    cell: int = param(
        1, 1, 8, 1, doc="cell side (px) of the translation filter's orientation features",
        paper=1)       # fhog(im_patch, 1) in _REF_CODE's get_feature_map.m: per pixel
    scale_cell: int = param(
        4, 1, 8, 1, doc="cell side (px) of each scale sample's HOG vector",
        paper=4)       # fhog(im_patch_resized, 4) in _REF_CODE's get_scale_sample.m
    max_window_area: float = param(
        5000.0, 0.0, 1e6, 500.0, doc="most pixels of the sampled translation window (0: no "
        "limit); a larger window is sampled at a lower resolution",
        paper=NOT_PRINTED, paper_value=0.0,   # _REF_CODE samples every window at full size
        why="the book's cost bound: the per-pixel features make a frame cost grow with the "
            "window (Bag's 300 x 279 px: 40 ms of CPU a frame at full resolution, 9 ms at "
            "5000 px); chosen on the sample clips whose windows exceed 2500 px (padding 1, no "
            "failure layer), where no limit and 10000 / 5000 / 2500 px gave mean AUC 0.797 / "
            "0.797 / 0.801 / 0.804: no loss, "
            "5000 the largest that keeps Bag's frame under 10 ms. paper preset: 0, no limit")
    bins: int = param(
        8, 4, 18, 1, doc="signed orientation bins per cell (feature channels)",
        paper=9,       # FHOG's 9 orientations (18 signed + 9 unsigned + 4 texture channels)
        why="the book's 8 signed bins of the HOG chapter (exact octant binning) "
            "instead of FHOG, so "
            "the features are the HOG cells the reader already knows, as for KCF; paper "
            "preset: 9 signed bins of the same cells, not FHOG")


def _resized_crop(gray, centre, size, out_size):
    """The region of ``size = (w, h)`` px centred on ``centre`` (box coordinates), resized to
    ``out_size = (w, h)``: area averaging when shrinking, bilinear when enlarging (what the
    reference code's ``mexResize(..., 'auto')`` does). Parts outside the frame repeat the
    border (``cv2.getRectSubPix``)."""
    w = max(int(round(size[0])), 1)
    h = max(int(round(size[1])), 1)
    # box coordinates put pixel i's centre at i + 0.5; getRectSubPix puts it at i
    crop = cv2.getRectSubPix(gray, (w, h), (float(centre[0]) - 0.5, float(centre[1]) - 0.5))
    if (w, h) == tuple(out_size):
        return crop
    shrink = w * h > out_size[0] * out_size[1]
    return cv2.resize(crop, tuple(out_size),
                      interpolation=cv2.INTER_AREA if shrink else cv2.INTER_LINEAR)


@register
class DsstTracker(_CorrelationTracker):
    """DSST, Danelljan et al. 2014: separate translation and scale correlation filters.

    Translation: window (1 + ``padding``) × the target at the current scale, resized to the
    first frame's window; features are ``bins`` orientation channels on ``cell``-px cells
    (:func:`~trackbook.features.gradient_cells.orientation_cells`) and the grey level
    (I / 255 − 0.5), times a cosine window; label a Gaussian of σ = sqrt(w h) ×
    ``output_sigma_factor``. The book's addition: a window of more than
    ``max_window_area`` px is sampled at the resolution that brings it to that many (0: the
    paper's full resolution always), so a large target costs no more than a middling one. Scale: ``n_scales`` samples of the target size × a^n, each
    resized to at most ``scale_model_max_area`` px and described by orientation cells of
    ``scale_cell`` px, times a cosine window over the scales; label a Gaussian of σ =
    S / √33 × ``scale_sigma_factor`` scale steps. Both filters: A_t = (1 − η) A_{t−1} + η Ḡ F_t,
    B_t = (1 − η) B_{t−1} + η Σ_k F̄^k_t F^k_t; response F^{-1}{Σ_l Ā^l Z^l / (B + λ)}.

    Failure
    -------
    DSST prints no failure rule: the failure-detection layer decides ``ok`` from the PSR
    below, and neither filter learns on a frame judged lost. ``dsst-redetect`` adds the
    re-detection layer (the translation filter's PSR over windows of the whole frame).

    Confidence
    ----------
    ``state().confidence`` is the peak-to-sidelobe ratio of the last translation response,
    PSR = (y_max − μ_s) / σ_s, the sidelobe excluding a square of side 2⌈3σ⌉ + 1 px (σ the
    label's) around the peak; 0 on a constant frame or a flat sidelobe.

    Attributes (read-only, for drawing)
    -----------------------------------
    response : the last translation response (cyclic: index 0 is "no move")
    scale_response : the last scale response over the S scales (index i is a^{n_i})
    scale : the current scale factor relative to the first frame's box
    confidence : the last frame's confidence (PSR)
    search_window : (x, y, w, h) of the last window searched
    """

    name = "dsst"
    Params = DsstParams

    # -- geometry ----------------------------------------------------------------------
    def _setup_geometry(self, w, h):
        p = self.params
        c = p.cell
        self._base = (w, h)
        ww, wh = np.floor(w * (1 + p.padding)), np.floor(h * (1 + p.padding))
        # k: frame px per patch px; a window over max_window_area px is sampled coarser
        k = 1.0
        if p.max_window_area > 0 and ww * wh > p.max_window_area:
            k = float(np.sqrt(ww * wh / p.max_window_area))
        # the window at scale 1: whole cells of the patch, at least 2 x 2
        cols = max(int(ww / k // c), 2)
        rows = max(int(wh / k // c), 2)
        self._patch_size = (cols * c, rows * c)
        self._base_window = (cols * c * k, rows * c * k)
        self._step = c * k
        self._response_shape = (rows, cols)
        self._hann32 = cf.hann_window(rows, cols).astype(np.float32)
        sigma = max(np.sqrt(w * h) * p.output_sigma_factor / (c * k), 1e-3)
        # real DFTs in single precision: half the spectrum and half the bytes of a complex128
        # one (the features are real; see scale_filter.spectra)
        self._G = sf.spectra(cf.gaussian_labels(rows, cols, sigma).astype(np.float32), 2,
                             half=True)
        self._exclude = int(min(2 * np.ceil(3 * sigma) + 1, max(min(rows, cols) - 2, 1)))
        # the scale search
        S = p.n_scales
        self._factors = sf.scale_factors(S, p.scale_step)
        self._scale_window = sf.scale_window(S)
        self._Gs = sf.spectra(sf.scale_labels(S, sf.scale_sigma(S, p.scale_sigma_factor)), 1,
                              half=True)
        self._model_size = sf.scale_model_size((w, h), p.scale_model_max_area, p.scale_cell)
        H, W = self._shape[:2]
        self._scale_min, self._scale_max = sf.scale_limits(self._base_window, (w, h), (W, H),
                                                           p.scale_step)
        self.scale = 1.0
        self.scale_response = np.zeros(S)

    @property
    def _window(self):
        return (self._base_window[0] * self.scale, self._base_window[1] * self.scale)

    def _box_at(self, centre):
        w, h = self._base[0] * self.scale, self._base[1] * self.scale
        return np.array([centre[0] - w / 2.0, centre[1] - h / 2.0, w, h])

    def _moved(self, centre, dy, dx):
        s = self._step * self.scale
        return (centre[0] + dx * s, centre[1] + dy * s)

    def _patches(self, gray, centres):
        """The translation windows at the current scale, resized to the scale-1 window."""
        return np.stack([_resized_crop(gray, c, self._window, self._patch_size)
                         for c in centres])

    # -- features ----------------------------------------------------------------------------
    def _hog(self, patches, cell):
        """Orientation channels of a stack of grey patches, (N, bins, rows, cols)."""
        return orientation_cells(patches, cell, self.params.bins)

    def _features(self, patches):
        """Translation features: orientation channels and the grey level, cosine window ->
        spectra (N, d, rows, cols)."""
        g = np.asarray(patches, dtype=np.float32)
        c = self.params.cell
        rows, cols = self._response_shape
        grey = g.reshape(len(g), rows, c, cols, c).mean(axis=(2, 4)) / 255.0 - 0.5
        x = np.empty((len(g), 1 + self.params.bins, rows, cols), dtype=np.float32)
        x[:, 0] = grey
        x[:, 1:] = self._hog(g / 255.0, c)
        x *= self._hann32
        return sf.spectra(x, 2, half=True)

    def _scale_sample(self, gray, centre, scale):
        """The S scale samples at ``centre``: one HOG vector per scale a^n × ``scale`` × the
        first frame's target size, resized to the model size; (d, S) times the window over
        the scales, returned as its DFT along the scales."""
        bw, bh = self._base
        crops = np.stack([_resized_crop(gray, centre, (bw * scale * f, bh * scale * f),
                                        self._model_size) for f in self._factors])
        x = self._hog(np.asarray(crops, dtype=np.float64) / 255.0, self.params.scale_cell)
        x = x.reshape(len(crops), -1).T * self._scale_window[None, :]
        return sf.spectra(x, 1, half=True)

    # -- training and detection ---------------------------------------------------------
    def _train_first(self, gray):
        F = self._features(self._patches(gray, [self._centre]))[0]
        self._A, self._B = sf.multichannel_terms(F, self._G, 2)
        Fs = self._scale_sample(gray, self._centre, self.scale)
        self._As, self._Bs = sf.multichannel_terms(Fs, self._Gs, 1)

    def _responses(self, F):
        return sf.multichannel_response(self._A, self._B, F, self.params.lam, 2,
                                        self._response_shape)

    def _confidence(self, responses):
        return np.atleast_1d(cf.psr(responses, self._exclude))

    def _update_model(self, F):
        eta = self.params.eta
        A, B = sf.multichannel_terms(F, self._G, 2)
        self._A, self._B = sf.update_terms(self._A, self._B, A, B, eta)

    def _init(self, frame, box):
        self.scale = 1.0
        super()._init(frame, box)

    def _locate(self, frame):
        """Translation at the current scale, then the scale at the new centre.

        Returns the box (new centre, new scale) and the PSR of the translation response; the
        filters, the centre and the scale the next search starts from are not changed.
        """
        self.search_window = self._window_box(self._centre)
        if self._is_flat(frame):
            self.response, self.confidence = np.zeros(self._response_shape), 0.0
            self.scale_response = np.zeros(self.params.n_scales)
            return self._box(), 0.0
        gray = self._gray(frame)
        resp = self._responses(self._features(self._patches(gray, [self._centre])))[0]
        conf = float(self._confidence(resp[None])[0])
        centre = self._moved(self._centre, *self._peak(resp))
        s_resp = sf.multichannel_response(self._As, self._Bs,
                                          self._scale_sample(gray, centre, self.scale),
                                          self.params.lam, 1, (self.params.n_scales,))
        scale = float(np.clip(self.scale * self._factors[int(np.argmax(s_resp))],
                              self._scale_min, self._scale_max))
        self.response, self.scale_response, self.confidence = resp, s_resp, conf
        w, h = self._base[0] * scale, self._base[1] * scale
        return np.array([centre[0] - w / 2.0, centre[1] - h / 2.0, w, h]), conf

    def _peak(self, resp):
        """The response's peak as a signed cyclic offset (dy, dx) in cells.

        On 1-px cells of the frame the integer argmax, as the reference code; on coarser
        cells (``cell`` > 1 or a window sampled coarser) refined by a parabola through the
        neighbours (:func:`~trackbook.filters.correlation.
        peak_offset`), as KCF's here, so the box does not move in steps of whole cells.
        """
        if self._step > 1:
            return cf.peak_offset(resp)
        py, px = np.unravel_index(int(np.argmax(resp)), resp.shape)
        rows, cols = resp.shape
        return (py - rows if py > rows // 2 else py), (px - cols if px > cols // 2 else px)

    def _take(self, box):
        """Centre and scale of ``box`` (its width against the first frame's)."""
        self._centre = (box[0] + box[2] / 2.0, box[1] + box[3] / 2.0)
        self.scale = float(np.clip(box[2] / self._base[0], self._scale_min, self._scale_max))

    def _learn(self, frame, box):
        """Move to ``box`` (centre and scale) and update both filters with samples there."""
        self._take(box)
        gray = self._gray(frame)
        self._update_model(self._features(self._patches(gray, [self._centre]))[0])
        As, Bs = sf.multichannel_terms(self._scale_sample(gray, self._centre, self.scale),
                                       self._Gs, 1)
        self._As, self._Bs = sf.update_terms(self._As, self._Bs, As, Bs, self.params.eta)

    def _relocate(self, frame, box):
        """Restart the search at ``box`` (its centre and scale), no learning."""
        self._take(np.asarray(box, dtype=float))

    @property
    def filter(self):
        """The translation filter's channels h^l = F^{-1}{A^l / (B + λ)} (for drawing)."""
        H = sf.multichannel_filter(self._A, self._B, self.params.lam, 2)
        return readonly(np.fft.irfft2(H, s=self._response_shape))


register(redetecting(DsstTracker))

__all__ = ["DsstTracker", "DsstParams"]
