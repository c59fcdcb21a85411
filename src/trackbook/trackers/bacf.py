"""BACF (Kiani Galoogahi, Fagg & Lucey, ICCV 2017): a background-aware correlation filter.

``bacf``
    A multi-channel correlation filter h of the target's size, trained on every cyclic shift
    of a window five times the target's size (a square of side 5 √(w h)); the cropping
    operator P keeps the target-sized centre of each shift, so the shifts show the real
    background around the target instead of periodic copies of it. Trained by ADMM in the
    Fourier domain (:mod:`trackbook.filters.bacf`: the per-frequency ĝ-subproblem by
    Sherman–Morrison, the h-subproblem as a spatial projection, the multiplier ζ̂ and the
    penalty μ ← min(β μ, μ_max)), restarted from zero on every frame on the features of the
    model, x̂_model ← (1 − η) x̂_model + η x̂, the online update of the paper. Features: the
    31 channels of Felzenszwalb's HOG (:func:`trackbook.features.fhog.fhog`) in cells of 4 px
    times a cosine window. Scale: the window is searched at five scales 1.01^{−2…2} (the
    paper's scale pyramid) and the scale of the best response is kept.

Failure and re-detection
------------------------
BACF prints no failure rule. The confidence is the peak-to-sidelobe ratio of the best scale's
response, judged by the failure-detection layer; the model learns only on frames judged on
target. ``bacf-redetect`` adds the re-detection layer: while lost, the filter (the
target-sized h, zero elsewhere) is correlated with the FHOG of the whole frame at the current
scale in one FFT, and each candidate box is scored by the strongest response within
``exclude // 2`` cells of its centre, in standard deviations of the whole frame's response
above its mean.

>>> from trackbook import trackers, clips
>>> clip = clips.load("red-cube")                                              # doctest: +SKIP
>>> t = trackers.create("bacf"); t.init(clip.frames[0], clip.groundtruth[0])   # doctest: +SKIP
>>> ok, box = t.update(clip.frames[1]); t.confidence, t.scale                  # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses

import cv2
import numpy as np
import scipy.fft as sfft
from scipy import ndimage

from ..features.fhog import fhog
from ..filters import bacf as bf
from ..filters import correlation as cf
from ..params import param
from ._per_frame import PerFrame
from .base import Tracker, centred_response, readonly, redetecting
from .registry import register

_REF_CODE = ("the authors' release (run_BACF.m, BACF_optimized.m, BACF_Demo_single_seq.m; "
             "mirrored in github.com/hexdjx/Visual-Tracking-Paper-List, folder BACF)")

#: The authors' code reduces the cell size when the window holds fewer than this share of
#: ``filter_max_cells``² cells (``cell_selection_thresh = 0.75^2`` in run_BACF.m).
CELL_SELECTION = 0.75 ** 2
#: Smallest window side, in cells, the scale may shrink to (``5 ./ sz`` in BACF_optimized.m,
#: there in pixels of the window; kept here as the reference writes it).
MIN_WINDOW = 5


@dataclasses.dataclass(frozen=True)
class BacfParams:
    # Kiani Galoogahi, Fagg & Lucey, ICCV 2017 (kianigaloogahi2017). Every value below is the
    # one of the authors' release (_REF_CODE), which says "Default parameters used in the ICCV
    # 2017 BACF paper"; each comment names the variable.
    search_area_scale: float = param(
        5.0, 1.5, 10.0, 0.25, doc="window side = √(w h × this²): square, this × the target",
        paper=5.0)      # search_area_scale = 5, search_area_shape = 'square' (run_BACF.m)
    filter_max_cells: int = param(
        50, 16, 128, 2, doc="most cells a side of the window; larger targets are sampled "
        "at a coarser resolution", paper=50)   # filter_max_area = 50^2 (run_BACF.m)
    cell: int = param(
        4, 1, 8, 1, doc="FHOG cell side in pixels of the sampled window",
        paper=4)        # t_global.cell_size = 4 (run_BACF.m); FHOG of 31 channels, nDim = 31
    output_sigma_factor: float = param(
        1 / 16, 0.01, 0.5, 0.005, doc="σ_y of the labels = √(cells of the target) × this",
        paper=1 / 16)   # output_sigma_factor = 1/16 (run_BACF.m)
    lam: float = param(
        0.01, 1e-6, 10.0, None, doc="λ, weight of ‖h‖² (the paper's eq. 1)",
        paper=0.01)     # admm_lambda = 0.01 (run_BACF.m)
    eta: float = param(
        0.013, 0.0, 1.0, 0.001, doc="η, learning rate of the model's features x̂_model",
        paper=0.013)    # learning_rate = 0.013 (BACF_Demo_single_seq.m, passed to run_BACF)
    admm_iterations: int = param(
        2, 1, 50, 1, doc="ADMM iterations per frame (the paper's section 4)",
        paper=2)        # admm_iterations = 2 (run_BACF.m and BACF_optimized.m)
    mu: float = param(
        1.0, 1e-3, 1e3, None, doc="μ⁽⁰⁾, the initial ADMM penalty",
        paper=1.0)      # mu = 1 (BACF_optimized.m)
    beta: float = param(
        10.0, 1.0, 100.0, 0.5, doc="β, growth of the penalty: μ ← min(β μ, μ_max)",
        paper=10.0)     # betha = 10 (BACF_optimized.m)
    mu_max: float = param(
        1e4, 1.0, 1e6, None, doc="μ_max, the penalty's cap", paper=1e4)  # mumax = 10000
    n_scales: int = param(
        5, 1, 33, 2, doc="scales searched (the scale pyramid), odd",
        paper=5)        # number_of_scales = 5 (run_BACF.m)
    scale_step: float = param(
        1.01, 1.001, 1.2, 0.005, doc="ratio between neighbouring scales of the pyramid",
        paper=1.01)     # scale_step = 1.01 (run_BACF.m)


@register
class BacfTracker(Tracker):
    """BACF, Kiani Galoogahi et al. 2017: a target-sized filter trained on real background.

    Geometry (as the authors' code): the window is a square of side ``search_area_scale`` ×
    √(w h); if it would hold more than ``filter_max_cells``² cells of ``cell`` px, the frame is
    sampled at the coarser resolution that makes it hold that many (the scale factor s₀ > 1),
    and if it holds fewer than 0.75² of them the cell shrinks (down to 1 px). The filter's
    support is the target's size in cells, centred in the window. Labels: a Gaussian of σ_y =
    √(target cells) × ``output_sigma_factor`` cells peaked at shift 0.

    Each frame: the window at the current scale s, times each of the ``n_scales`` factors
    ``scale_step``^{−2…2}, is resized to the window's size, described by FHOG (31 channels,
    cosine window) and correlated with ĝ; the scale with the highest peak is kept, the peak
    moves the centre (refined by a parabola) and s is multiplied by that factor. Then the
    window at the new centre and scale updates the model's features with rate ``eta`` and the
    filter is trained again by ``admm_iterations`` ADMM iterations from zero.

    Failure
    -------
    BACF prints no failure rule: the failure-detection layer decides ``ok`` from the PSR
    below, and the model is not updated on a frame judged lost. ``bacf-redetect`` adds the
    re-detection layer (see the module docstring).

    Confidence
    ----------
    ``state().confidence`` is the peak-to-sidelobe ratio of the best scale's response,
    PSR = (r_max − μ_s) / σ_s, the sidelobe excluding a square of side 2⌈3 σ_y⌉ + 1 cells
    around the peak; 0 on a constant frame or a flat sidelobe.

    Attributes (read-only, for drawing)
    -----------------------------------
    response : the best scale's last response map (cyclic: index 0 is "no move")
    confidence : the last frame's PSR
    scale : the current size relative to the first frame's box
    search_window : (x, y, w, h) of the last window searched (the middle scale's)
    """

    name = "bacf"
    Params = BacfParams

    # -- geometry -----------------------------------------------------------------------------
    def _setup_geometry(self, w, h, frame_shape):
        p = self.params
        target = np.array([max(np.floor(h), 1.0), max(np.floor(w), 1.0)])    # (rows, cols) px
        cell = p.cell
        max_area = p.filter_max_cells ** 2
        area = np.prod(target / cell * p.search_area_scale)
        if area < CELL_SELECTION * max_area:
            # small targets: a finer cell so the window still holds enough cells
            cell = int(min(cell, max(1, np.ceil(np.sqrt(np.prod(target * p.search_area_scale)
                                                        / (CELL_SELECTION * max_area))))))
            area = np.prod(target / cell * p.search_area_scale)
        s0 = float(np.sqrt(area / max_area)) if area > max_area else 1.0
        base = target / s0                                  # target at the sampling resolution
        side = np.sqrt(np.prod(base * p.search_area_scale))
        cells = max(int(round(side / cell)), 4)
        self._cell = cell
        self._cells = cells                                 # window side in cells
        self._win_px = cells * cell                         # window side in sampled px
        self._s0 = s0
        self._base = base                                   # (rows, cols), sampled px
        support = np.clip(np.floor(base / cell).astype(int), 1, cells)
        self._mask = bf.support_mask((cells, cells), tuple(support))
        sigma_y = np.sqrt(np.prod(np.maximum(np.floor(base / cell), 1))) * p.output_sigma_factor
        self._sigma_y = sigma_y
        y = cf.gaussian_labels(cells, cells, max(sigma_y, 1e-3)).astype(np.float32)
        self._yf = sfft.rfft2(y)
        self._hann = cf.hann_window(cells, cells).astype(np.float32)
        self._exclude = int(min(2 * np.ceil(3 * sigma_y) + 1, max(cells - 2, 1)))
        k = np.arange(p.n_scales) - (p.n_scales - 1) // 2
        self._factors = p.scale_step ** k
        H, W = frame_shape[:2]
        step = p.scale_step
        # the scale's bounds as the authors' code sets them (relative to s0 = 1 there)
        self._min_scale = step ** np.ceil(np.log(MIN_WINDOW / self._win_px) / np.log(step))
        self._max_scale = step ** np.floor(np.log(min(H / base[0], W / base[1])) / np.log(step))

    def _window_box(self, centre, scale):
        side = self._win_px * scale
        return (centre[0] - side / 2.0, centre[1] - side / 2.0, side, side)

    def _box_at(self, centre, scale):
        h, w = self._base * scale
        return np.array([centre[0] - w / 2.0, centre[1] - h / 2.0, w, h])

    # -- features -----------------------------------------------------------------------------
    def _patch(self, frame, centre, scale):
        """The square of side window × ``scale`` frame px around ``centre``, resized to the
        window (border pixels repeated), as the authors' ``get_pixels``: area averaging
        when shrinking, bilinear when enlarging."""
        side = self._win_px * scale
        n = max(int(round(side)), 1)
        x0 = int(np.floor(centre[0] - n / 2.0))
        y0 = int(np.floor(centre[1] - n / 2.0))
        H, W = frame.shape[:2]
        if x0 >= 0 and y0 >= 0 and x0 + n <= W and y0 + n <= H:
            crop = frame[y0:y0 + n, x0:x0 + n]
        else:
            # the part inside the frame, its border pixels repeated out to the square
            ax, ay = min(max(x0, 0), W - 1), min(max(y0, 0), H - 1)
            bx, by = max(min(x0 + n, W), ax + 1), max(min(y0 + n, H), ay + 1)
            pads = (ay - y0, y0 + n - by, ax - x0, x0 + n - bx)
            if min(pads) >= 0:
                crop = cv2.copyMakeBorder(frame[ay:by, ax:bx], *pads, cv2.BORDER_REPLICATE)
            else:                       # a square wholly outside the frame: index it
                crop = frame[np.ix_(np.clip(np.arange(y0, y0 + n), 0, H - 1),
                                    np.clip(np.arange(x0, x0 + n), 0, W - 1))]
        size = self._win_px
        interp = cv2.INTER_AREA if n > size else cv2.INTER_LINEAR
        return cv2.resize(crop, (size, size), interpolation=interp)

    def _features(self, patches):
        """FHOG (31 channels) of each patch times the cosine window: (n, 31, cells, cells)."""
        out = np.stack([np.moveaxis(fhog(p, self._cell), -1, 0) for p in patches])
        return out * self._hann

    def _spectra(self, frame, centre, scales):
        patches = [self._patch(frame, centre, s) for s in scales]
        return sfft.rfft2(self._features(patches))

    # -- the two halves of a frame ----------------------------------------------------------
    def _init(self, frame, box):
        x, y, w, h = (float(v) for v in box)
        self._setup_geometry(w, h, frame.shape)
        self._centre = (x + w / 2.0, y + h / 2.0)
        self._scale = self._s0
        self._initial = self._s0
        self._full_of = PerFrame()
        xf = self._spectra(frame, self._centre, [self._scale])[0]
        self._model_xf = xf
        self._train()
        self.confidence = float("inf")
        self.response = np.zeros((self._cells, self._cells))
        self._response_step = None
        self.search_window = self._window_box(self._centre, self._scale)

    def _train(self):
        p = self.params
        self._gf, _, self._h = bf.admm(self._model_xf, self._yf, self._mask, p.lam,
                                       iterations=p.admm_iterations, mu=p.mu, beta=p.beta,
                                       mu_max=p.mu_max)

    def _locate(self, frame):
        """The filter at every scale of the pyramid around the last centre: the best scale's
        peak places the box. The model and the search's start are not changed."""
        self.search_window = self._window_box(self._centre, self._scale)
        if self._is_flat(frame):
            self.response, self.confidence = np.zeros((self._cells, self._cells)), 0.0
            self._response_step = self._cell * self._scale
            return self._box_at(self._centre, self._scale), 0.0
        scales = self._scale * self._factors
        zf = self._spectra(frame, self._centre, scales)
        resp = bf.response(self._gf, zf, (self._cells, self._cells))
        best = int(np.argmax(resp.reshape(len(scales), -1).max(axis=1)))
        r = resp[best]
        conf = float(cf.psr(r, self._exclude))
        dy, dx = cf.peak_offset(r)
        step = self._cell * scales[best]
        centre = (self._centre[0] + dx * step, self._centre[1] + dy * step)
        scale = float(np.clip(scales[best], self._min_scale, self._max_scale))
        self.response, self.confidence = r, conf
        self._response_step = step
        return self._box_at(centre, scale), conf

    def _learn(self, frame, box):
        """Move to ``box`` (its size sets the scale), update the model's features with rate η
        and train the filter again by ADMM."""
        self._relocate(frame, box)
        self._scale = float(np.clip(box[3] / self._base[0], self._min_scale, self._max_scale))
        eta = self.params.eta
        xf = self._spectra(frame, self._centre, [self._scale])[0]
        self._model_xf = (1 - eta) * self._model_xf + eta * xf
        self._train()

    def _relocate(self, frame, box):
        """Restart the search at ``box``'s centre (the scale is kept)."""
        self._centre = (box[0] + box[2] / 2.0, box[1] + box[3] / 2.0)

    # -- re-detection ------------------------------------------------------------------------
    def _full_response(self, frame):
        """The filter h correlated with the FHOG of the whole frame at the current scale (one
        FFT; cached for the frame): the score of the target centred on each cell."""
        return self._full_of.get(frame, self.frame_index,
                                 lambda: self._correlate_frame(frame), self._scale)

    def _correlate_frame(self, frame):
        H, W = frame.shape[:2]
        s = self._scale
        size = (max(int(round(W / s)), 2 * self._cell), max(int(round(H / s)), 2 * self._cell))
        interp = cv2.INTER_AREA if s > 1 else cv2.INTER_LINEAR
        small = cv2.resize(frame, size, interpolation=interp)
        feats = np.moveaxis(fhog(small, self._cell), -1, 0)
        return bf.correlate_full(self._h, self._mask, feats)

    def _score_boxes(self, frame, boxes):
        """For each box, the whole-frame response's highest value in the square of side
        ``2 (exclude // 2) + 1`` cells centred on the cell of its centre (the square the PSR
        leaves out around a peak), less the frame's mean response, over the frame's standard
        deviation (the model untouched): the re-detection layer's score.

        One response for the whole frame, one mean and one deviation: the boxes are ranked
        by how strongly the filter answers at them. (A PSR per window would not rank them:
        a window reaching past the frame's edge is padded with zeros, which changes its
        sidelobe, so a box on background could outscore the box on the target.) The square
        lets a box a few cells off the peak, as the grid's are, score it.
        """
        boxes = np.asarray(boxes, dtype=float)
        full = self._full_response(frame)
        sd = float(full.std())
        if not sd > 0:                       # nothing answers anywhere: no box is better
            return np.zeros(len(boxes))
        unit = self._cell * self._scale                     # frame px per cell
        rows, cols = full.shape
        cx = np.round((boxes[:, 0] + boxes[:, 2] / 2.0) / unit - 0.5).astype(int)
        cy = np.round((boxes[:, 1] + boxes[:, 3] / 2.0) / unit - 0.5).astype(int)
        near = ndimage.maximum_filter(full, size=2 * (self._exclude // 2) + 1, mode="nearest")
        return (near[np.clip(cy, 0, rows - 1), np.clip(cx, 0, cols - 1)] - full.mean()) / sd

    # -- drawing ------------------------------------------------------------------------------
    @property
    def scale(self) -> float:
        """The current size relative to the first frame's box."""
        return float(self._scale / self._initial)

    @property
    def filter(self):
        """The spatial filter h (31, cells, cells), zero off the target-sized support."""
        return readonly(self._h)

    def _drawn(self) -> dict:
        """The last search window and, after the first ``update``, the best scale's response
        (``Tracker.state()``): cells of ``cell`` × that scale frame px around the centre the
        search started from."""
        sw = getattr(self, "search_window", None)
        out = {**super()._drawn(),
               "search_window": None if sw is None else tuple(float(v) for v in sw)}
        if sw is not None and self.frame_index > 0:
            step = getattr(self, "_response_step", None) or self._cell * self._scale
            out.update(centred_response(self.response, (sw[0] + sw[2] / 2, sw[1] + sw[3] / 2),
                                        (step, step)))
        return out


register(redetecting(BacfTracker))

__all__ = ["BacfParams", "BacfTracker"]
