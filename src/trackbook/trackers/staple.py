"""Staple (Bertinetto, Valmadre, Golodetz, Miksik & Torr, CVPR 2016): complementary learners.

Two models of the target score every translation in a search square, and their scores are
merged (:mod:`trackbook.filters.staple` holds the maths):

template
    A correlation filter on HOG cells with a linear kernel: the multi-channel ridge
    regression over all cyclic shifts of the window, solved in the Fourier domain,
    ĥ_c = ŷ* x̂_c / (Σ_k |x̂_k|² + λ), numerator and denominator kept as running averages of
    learning rate η_tmpl. Its response f_tmpl (one value per cell) is cut to the search square
    and resized to the pixel grid of the colour response.
histogram
    Foreground and background colour histograms (32 bins per RGB channel; luminance only on
    a grey sequence), kept as running averages of learning rate η_hist. Each pixel scores
    β = ρ(O) / (ρ(O) + ρ(B)), the share of its colour's frequency that is the object's; the
    score f_hist of a translation is the mean of β over the target-sized box there, from an
    integral image.
merge
    f = (1 − γ) f_tmpl + γ f_hist; its peak moves the target.

Then DSST's 1-D scale filter (Danelljan et al. 2014) picks the scale: HOG features of S
patches of sizes a^k × the target, a 1-D correlation filter along the scale axis, the peak's
scale kept between the limits the authors' code sets.

Geometry (the authors' ``initializeAllAreas.m``): the window ("background area") is the
target plus ``padding`` × (w + h) / 2 on each side's total; it is resampled so its area is
``fixed_area`` px (the normalised window); the foreground region is the target shrunk by
``inner_padding`` × (w + h) / 2; the search square has the side 2 r + 1 px of the normalised
window, r the smaller margin between the normalised target and the window.

Failure and re-detection
------------------------
Staple prints no failure rule. The confidence is the peak-to-sidelobe ratio of the merged
response; the failure-detection layer judges it, the model learns only on frames judged on
target, and a lost frame keeps the last box. ``staple-redetect`` adds the re-detection layer:
while lost, windows over the whole frame are scored by the PSR of the merged response there
and the search restarts from the best.

>>> from trackbook import trackers, clips
>>> clip = clips.load("red-cube")                                              # doctest: +SKIP
>>> t = trackers.create("staple"); t.init(clip.frames[0], clip.groundtruth[0])  # doctest: +SKIP
>>> ok, box = t.update(clip.frames[1]); t.response.shape, t.scale              # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses

import cv2
import numpy as np

from ..features.gradient_cells import orientation_cells
from ..features.hog import to_gray
from ..features.patches import sample_patches
from ..filters import correlation as cf
from ..filters import staple as st
from ..params import param
from ._per_frame import PerFrame
from .base import Tracker, centred_response, readonly, redetecting
from .registry import register

_REF_CODE = "the authors' reference code (github bertinetto/staple, params.txt)"
_REF_AREAS = "the authors' reference code (initializeAllAreas.m)"


@dataclasses.dataclass(frozen=True)
class StapleParams:
    # Bertinetto, Valmadre, Golodetz, Miksik, Torr, CVPR 2016 (bertinetto2016). The values are
    # the paper's parameter table and the authors' params.txt, which agree; the scale filter's
    # are DSST's as params.txt sets them (the paper: "scale as in DSST").
    eta_tmpl: float = param(
        0.01, 0.0, 1.0, 0.005, doc="η_tmpl, learning rate of the template's terms r̂, d̂",
        paper=0.01)    # paper's parameter table; learning_rate_cf = 0.01 in _REF_CODE
    eta_hist: float = param(
        0.04, 0.0, 1.0, 0.005, doc="η_hist, learning rate of the histograms ρ(O), ρ(B)",
        paper=0.04)    # paper's parameter table; learning_rate_pwp = 0.04 in _REF_CODE
    gamma: float = param(
        0.3, 0.0, 1.0, 0.05, doc="γ, merge factor: f = (1 − γ) f_tmpl + γ f_hist",
        paper=0.3)     # paper's parameter table and eq. of the merge; merge_factor = 0.3
    n_bins: int = param(
        32, 2, 256, 1, doc="histogram bins per colour channel (32 x 32 x 32 for RGB)",
        paper=32)      # paper's parameter table; n_bins = 2^5 in _REF_CODE
    lam: float = param(
        1e-3, 1e-8, 1.0, None, doc="λ of the template's ridge regression (and the scale "
        "filter's)", paper=1e-3)   # λ_tmpl = 1e-3 in the paper; lambda = 1e-3 in _REF_CODE
    cell: int = param(
        4, 1, 8, 1, doc="HOG cell side in pixels of the normalised window",
        paper=4)       # HOG 4 x 4 cells in the paper; hog_cell_size = 4 in _REF_CODE
    bins: int = param(
        8, 4, 18, 1, doc="signed orientation bins per cell (template channels, plus grey)",
        paper=9,       # FHOG with 9 orientations in _REF_CODE (18 signed + 9 unsigned used)
        why="the book's 8 signed bins of the HOG chapter (exact octant binning) "
            "instead of FHOG's "
            "27 orientation channels, so the features are the HOG cells the reader already "
            "knows (as for kcf); paper preset: 9 signed bins of the same cells, not FHOG")
    padding: float = param(
        1.0, 0.0, 4.0, 0.25, doc="window = target + padding × (w + h) / 2 on each axis",
        paper=1.0)     # bg_area = target_sz + avg_dim in _REF_AREAS
    inner_padding: float = param(
        0.2, 0.0, 0.9, 0.05, doc="foreground = target − inner_padding × (w + h) / 2",
        paper=0.2)     # inner_padding = 0.2 in _REF_CODE
    fixed_area: float = param(
        150.0 ** 2, 32.0 ** 2, 400.0 ** 2, None, doc="area (px) the window is resampled to",
        paper=150.0 ** 2)   # fixed_area = 150^2 in _REF_CODE
    output_sigma_factor: float = param(
        1 / 16, 0.01, 1.0, 0.005, doc="σ_y of the labels = sqrt(normalised w h) × this / cell",
        paper=1 / 16)  # output_sigma_factor = 1/16 in _REF_CODE
    n_scales: int = param(
        33, 1, 65, 2, doc="S, scales the scale filter samples",
        paper=33)      # num_scales = 33 in _REF_CODE (DSST's)
    scale_step: float = param(
        1.02, 1.001, 1.2, 0.005, doc="a, ratio between neighbouring scales",
        paper=1.02)    # scale_step = 1.02 in _REF_CODE (DSST's)
    eta_scale: float = param(
        0.025, 0.0, 1.0, 0.005, doc="learning rate of the scale filter's terms",
        paper=0.025)   # learning_rate_scale = 0.025 in _REF_CODE (DSST's)
    scale_sigma_factor: float = param(
        0.25, 0.01, 2.0, 0.05, doc="σ of the scale labels = sqrt(S) × this",
        paper=0.25)    # scale_sigma_factor = 1/4 in _REF_CODE (DSST's)
    scale_model_max_area: float = param(
        512.0, 64.0, 4096.0, None, doc="largest area (px) of the scale filter's patches",
        paper=512.0)   # scale_model_max_area = 32*16 in _REF_CODE (DSST's)


class StapleTracker(Tracker):
    """Staple, Bertinetto et al. 2016: a HOG correlation filter and a colour-histogram score,
    merged, with DSST's scale filter.

    Per frame (the authors' ``trackerMain.m``): the window at the last position, resampled to
    the normalised window, gives the template response (cut to the search square, resized to
    its pixel grid); a larger colour patch gives the per-pixel scores β and their box means;
    the merged map's peak moves the target (integer pixels of the normalised window); the
    scale filter, at the new position, picks the scale. On a frame judged on target the
    template terms, the histograms (foreground: the inner region; background: the window
    outside the target) and the scale terms are updated at the new position and scale.

    Confidence
    ----------
    ``state().confidence`` is the peak-to-sidelobe ratio of the merged response f,
    PSR = (f_max − μ_s) / σ_s, the sidelobe excluding a square of side 2 ⌈3 σ_y⌉ + 1 px of the
    normalised window around the peak (σ_y the template labels' σ in those pixels), taken
    cyclically as :func:`trackbook.filters.correlation.psr` does; 0 on a constant frame.

    Attributes (read-only, for drawing)
    -----------------------------------
    response : the merged response f over the search square (centre = no move)
    response_template, response_histogram : f_tmpl and f_hist on the same grid
    likelihood : the per-pixel scores β over the colour search patch
    scale : the target's size relative to the first frame's
    scale_response : the scale filter's response over the S scales
    confidence : the last frame's confidence (PSR)
    search_window : (x, y, w, h) of the last window
    """

    name = "staple"
    Params = StapleParams

    # -- geometry ------------------------------------------------------------------------
    def _setup_geometry(self, frame_shape, w, h):
        """The normalised window, the search square and the scale filter's sizes, once."""
        p = self.params
        avg = (w + h) / 2.0
        self._bg0 = np.array([w + p.padding * avg, h + p.padding * avg])
        self._fg0 = np.maximum(np.array([w, h]) - p.inner_padding * avg, 1.0)
        arf = np.sqrt(p.fixed_area / np.prod(self._bg0))
        nb = np.maximum(np.round(self._bg0 * arf), 2 * p.cell).astype(int)   # (w, h)
        self._norm_bg = nb
        cols, rows = nb // p.cell
        self._cf_shape = (int(rows), int(cols))
        # the target in normalised pixels, from the window (target + padding x avg): solve
        # for w and h (for padding 1 this is 0.75 W - 0.25 H, as the authors' code does)
        tot = (nb[0] + nb[1]) / (1.0 + p.padding)
        nt = np.array([(tot + nb[0] - nb[1]) / 2.0, (tot - nb[0] + nb[1]) / 2.0])
        self._norm_target = np.clip(np.round(nt), 1, nb).astype(int)
        radius = int(max(np.min(np.floor((nb - self._norm_target) / 2.0)), 1))
        self._side = 2 * radius + 1                                         # search square
        self._norm_pwp = self._norm_target + self._side - 1
        self._cells = min(st.odd_floor(self._side / p.cell), st.odd_floor(min(rows, cols)))
        self._hann = cf.hann_window(rows, cols)
        sigma = np.sqrt(np.prod(self._norm_target)) * p.output_sigma_factor / p.cell
        self._y = cf.gaussian_labels(rows, cols, max(sigma, 1e-3))
        sig_px = sigma * p.cell
        self._exclude = int(min(2 * np.ceil(3 * sig_px) + 1, max(self._side - 2, 1)))
        # scale filter (the DSST code in trackerMain.m)
        S = p.n_scales
        self._scale_factors = st.scale_factors(S, p.scale_step)
        self._scale_window = st.scale_window(S)
        self._ys = st.scale_labels(S, p.scale_sigma_factor)
        smf = min(1.0, np.sqrt(p.scale_model_max_area / np.prod(self._norm_target)))
        self._scale_model = np.maximum(np.floor(self._norm_target * smf), 4).astype(int)
        H, W = frame_shape[:2]
        lo = np.log(np.max(5.0 / self._bg0)) / np.log(p.scale_step)
        hi = np.log(np.min(np.array([W, H]) / np.array([w, h]))) / np.log(p.scale_step)
        self._min_scale = p.scale_step ** np.ceil(lo)
        self._max_scale = max(p.scale_step ** np.floor(hi), self._min_scale)

    def _k(self):
        """Frame pixels per normalised pixel, (x, y), at the current scale."""
        return self._bg0 * self.scale / self._norm_bg

    def _window_box(self, centre):
        bw, bh = self._bg0 * self.scale
        return (centre[0] - bw / 2.0, centre[1] - bh / 2.0, bw, bh)

    def _box_at(self, centre, scale):
        w, h = self._size0 * scale
        return np.array([centre[0] - w / 2.0, centre[1] - h / 2.0, w, h])

    # -- features ------------------------------------------------------------------------
    def _template_features(self, colour):
        """Windowed template features (N, C, rows, cols) of (N, h, w, 3) normalised windows.

        Channels: the gradient-orientation cells of the grey window and its grey level per
        cell minus 0.5 (the authors' code puts the grey level beside FHOG's channels).
        """
        n, h, w = colour.shape[:3]
        grey = cv2.cvtColor(colour.reshape(n * h, w, 3), cv2.COLOR_BGR2GRAY)
        grey = grey.reshape(n, h, w).astype(np.float64) / 255.0
        c = self.params.cell
        rows, cols = self._cf_shape
        hog = orientation_cells(grey, c, self.params.bins)[:, :, :rows, :cols]
        level = grey[:, :rows * c, :cols * c].reshape(n, rows, c, cols, c).mean(axis=(2, 4))
        x = np.concatenate([hog, (level - 0.5)[:, None]], axis=1)
        return x * self._hann

    def _bins(self, colour):
        """Histogram bins of colour patches (grey level only on a grey sequence)."""
        if self._grey_sequence:
            return st.colour_bins(colour[..., 0], self.params.n_bins, colour=False)
        return st.colour_bins(colour, self.params.n_bins)

    def _scale_features(self, frame, centre, scale):
        """(D, S) windowed features of the S scale patches around ``centre``."""
        sizes = self._size0[None, :] * scale * self._scale_factors[:, None]
        boxes = np.column_stack([centre[0] - sizes[:, 0] / 2, centre[1] - sizes[:, 1] / 2,
                                 sizes])
        grey = sample_patches(self._grey(frame), boxes, tuple(int(v) for v in self._scale_model))
        f = orientation_cells(grey / 255.0, self.params.cell, self.params.bins)
        return f.reshape(len(boxes), -1).T * self._scale_window[None, :]

    def _grey(self, frame):
        return self._grey_of.get(
            frame, self.frame_index,
            lambda: to_gray(frame))

    # -- the two learners on a batch of centres --------------------------------------------
    def _responses(self, frame, centres):
        """Merged, template and histogram responses and β maps at each centre (a batch)."""
        centres = np.asarray(centres, dtype=float).reshape(-1, 2)
        k = self._k()
        wins = [self._window_box(c) for c in centres]
        colour = sample_patches(frame, np.array(wins), tuple(int(v) for v in self._norm_bg))
        resp = st.dcf_response(self._num, self._den, self._template_features(colour),
                               self.params.lam)
        tmpl = st.response_on_grid(resp, self._cells, self._side)
        pw, ph = self._norm_pwp * k
        boxes = np.column_stack([centres[:, 0] - pw / 2, centres[:, 1] - ph / 2,
                                 np.full(len(centres), pw), np.full(len(centres), ph)])
        patch = sample_patches(frame, boxes, tuple(int(v) for v in self._norm_pwp))
        beta = st.object_likelihood(self._bins(patch), self._fg_hist, self._bg_hist)
        hist = st.box_means(beta, (self._norm_target[1], self._norm_target[0]))
        return st.merge_responses(tmpl, hist, self.params.gamma), tmpl, hist, beta

    def _confidence(self, merged):
        return np.atleast_1d(cf.psr(merged, self._exclude))

    # -- the two halves of a frame --------------------------------------------------------
    def _init(self, frame, box):
        x, y, w, h = (float(v) for v in box)
        self._size0 = np.array([w, h])
        self._centre = (x + w / 2.0, y + h / 2.0)
        self.scale = 1.0
        self._grey_of = PerFrame()
        self._grey_sequence = bool(np.array_equal(frame[..., 0], frame[..., 1])
                                   and np.array_equal(frame[..., 1], frame[..., 2]))
        self._n_cells = self.params.n_bins ** (1 if self._grey_sequence else 3)
        self._setup_geometry(frame.shape, w, h)
        self._train(frame, first=True)
        side = self._side
        self.response = np.zeros((side, side))
        self._response_step = None
        self.response_template = np.zeros((side, side))
        self.response_histogram = np.zeros((side, side))
        self.likelihood = np.zeros((int(self._norm_pwp[1]), int(self._norm_pwp[0])))
        self.scale_response = np.zeros(self.params.n_scales)
        self.confidence = float("inf")
        self.search_window = self._window_box(self._centre)

    def _locate(self, frame):
        """Merged response at the last position -> translation; scale filter -> scale.

        Returns the box (new centre and size), the PSR of the merged response and True
        (Staple prints no failure rule). The model and the position the next search starts
        from are not changed.
        """
        self.search_window = self._window_box(self._centre)
        if self._is_flat(frame):
            self.response = np.zeros_like(self.response)
            self._response_step = tuple(self._k())
            self.confidence = 0.0
            return self._box_at(self._centre, self.scale), 0.0, False
        merged, tmpl, hist, beta = self._responses(frame, [self._centre])
        self.response, self.response_template = merged[0], tmpl[0]
        self.response_histogram, self.likelihood = hist[0], beta[0]
        conf = float(self._confidence(merged)[0])
        self.confidence = conf
        row, col = np.unravel_index(int(np.argmax(merged[0])), merged[0].shape)
        r = self._side // 2
        kx, ky = self._k()
        self._response_step = (kx, ky)
        centre = (self._centre[0] + (col - r) * kx, self._centre[1] + (row - r) * ky)
        zs = self._scale_features(frame, centre, self.scale)
        self.scale_response = st.scale_response(self._snum, self._sden, zs, self.params.lam)
        best = int(np.argmax(self.scale_response))
        scale = float(np.clip(self.scale * self._scale_factors[best], self._min_scale,
                              self._max_scale))
        return self._box_at(centre, scale), conf, True

    def _learn(self, frame, box):
        """Move to ``box`` (its centre and its size: the scale) and update the three models."""
        self._centre = (box[0] + box[2] / 2.0, box[1] + box[3] / 2.0)
        self.scale = float(np.clip(np.sqrt(box[2] * box[3] / np.prod(self._size0)),
                                   self._min_scale, self._max_scale))
        self._train(frame, first=False)

    def _train(self, frame, first):
        """The template terms, the histograms and the scale terms at the current position."""
        p = self.params
        win = np.array([self._window_box(self._centre)])
        nb = tuple(int(v) for v in self._norm_bg)
        colour = sample_patches(frame, win, nb)
        num, den = st.dcf_terms(self._template_features(colour)[0], self._y)
        fg_mask, bg_mask = self._masks()
        bins = self._bins(colour[0])
        fg = st.colour_histogram(bins, fg_mask, self._n_cells)
        bg = st.colour_histogram(bins, bg_mask, self._n_cells)
        snum, sden = st.scale_terms(self._scale_features(frame, self._centre, self.scale),
                                    self._ys)
        if first:
            self._num, self._den = num, den
            self._fg_hist, self._bg_hist = fg, bg
            self._snum, self._sden = snum, sden
            return
        a, b, c = p.eta_tmpl, p.eta_hist, p.eta_scale
        self._num = (1 - a) * self._num + a * num
        self._den = (1 - a) * self._den + a * den
        self._fg_hist = (1 - b) * self._fg_hist + b * fg
        self._bg_hist = (1 - b) * self._bg_hist + b * bg
        self._snum = (1 - c) * self._snum + c * snum
        self._sden = (1 - c) * self._sden + c * sden

    def _masks(self):
        """Foreground (inner region) and background (window outside the target) masks on the
        normalised window's pixels (the authors' ``updateHistModel.m``)."""
        nw, nh = self._norm_bg
        u = (np.arange(nw) + 0.5) / nw * self._bg0[0]        # pixel centres, frame units
        v = (np.arange(nh) + 0.5) / nh * self._bg0[1]        # (the same at every scale)

        def inside(size):
            # at least a one-pixel margin, as the authors' code keeps (pad_offset >= 1)
            px = max((self._bg0[0] - size[0]) / 2.0, self._bg0[0] / nw)
            py = max((self._bg0[1] - size[1]) / 2.0, self._bg0[1] / nh)
            return (((v >= py) & (v < self._bg0[1] - py))[:, None]
                    & ((u >= px) & (u < self._bg0[0] - px))[None, :])
        fg = inside(self._fg0).astype(float)
        bg = (~inside(self._size0)).astype(float)
        return fg, bg

    def _score_boxes(self, frame, boxes):
        """The PSR of the merged response in the window centred on each box (the models
        untouched): the re-detection layer's score."""
        boxes = np.asarray(boxes, dtype=float)
        centres = boxes[:, :2] + boxes[:, 2:] / 2.0
        out = np.empty(len(centres))
        for a in range(0, len(centres), 64):      # batches bound the memory of the windows
            merged = self._responses(frame, centres[a:a + 64])[0]
            out[a:a + 64] = self._confidence(merged)
        return out

    def _relocate(self, frame, box):
        """Restart the search at ``box``'s centre (the next frame's window is there)."""
        self._centre = (box[0] + box[2] / 2.0, box[1] + box[3] / 2.0)

    def _drawn(self) -> dict:
        """The last search window and, after the first ``update``, the merged response over
        the search square (``Tracker.state()``): the shifts of ±side // 2 normalised px around
        the centre the search started from, ``_k()`` frame px each."""
        sw = getattr(self, "search_window", None)
        out = {**super()._drawn(),
               "search_window": None if sw is None else tuple(float(v) for v in sw)}
        if sw is not None and self.frame_index > 0:
            step = getattr(self, "_response_step", None) or tuple(self._k())
            out.update(centred_response(self.response, (sw[0] + sw[2] / 2, sw[1] + sw[3] / 2),
                                        step, cyclic=False))
        return out

    @property
    def template(self):
        """The template filter h_c = ifft2(ĥ_c) per channel (for drawing), read-only."""
        hf = st.dcf_filter(self._num, self._den, self.params.lam)
        return readonly(np.fft.irfft2(hf, s=self._cf_shape))


register(StapleTracker)
register(redetecting(StapleTracker))

__all__ = ["StapleTracker", "StapleParams"]
