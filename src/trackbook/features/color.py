"""Kernel-weighted colour histograms and the Bhattacharyya coefficient.

Chapter ``01_kernel_histograms`` of the book. The histogram of a region counts the colours of its pixels, each
pixel weighted by a kernel that trusts the centre more than the border (eq. 1 of Lee et al.
2012; eq. 2-3 of Cho & Kang 2005; Comaniciu, Ramesh & Meer 2003):

    q_u = C * sum_i k(||x_i*||^2) * delta[b(x_i) - u],   k(r^2) = 1 - r^2,

with r the pixel's distance to the region centre normalised so that the farthest pixel (or
the ellipse boundary) has r = 1, and C making the bins sum to 1. (Lee et al. 2012's prose
describes the kernel as 1 - r; their eq. 1 prints 1 - r^2, which is what this module uses.)
Two histograms are compared by the Bhattacharyya coefficient rho = sum_u sqrt(p_u q_u).
"""

from __future__ import annotations

import cv2
import numpy as np

from .patches import sample_patches

#: HSV bins of Lee et al. 2012: 8 hue x 8 saturation x 4 value.
HSV_BINS = (8, 8, 4)


def hsv_bin_index(bgr: np.ndarray, bins=HSV_BINS) -> np.ndarray:
    """Bin index ``u`` of every pixel in an ``bins[0] x bins[1] x bins[2]`` HSV histogram.

    OpenCV's 8-bit HSV has H in 0..179, S and V in 0..255; each channel is cut into equal
    intervals. Returns an int array of the image's H x W (or N x h x w) shape.
    """
    bgr = np.ascontiguousarray(bgr)
    shape = bgr.shape[:-1]
    hsv = cv2.cvtColor(bgr.reshape(-1, 1, 3), cv2.COLOR_BGR2HSV).reshape(-1, 3).astype(np.int32)
    bh, bs, bv = bins
    h = np.minimum(hsv[:, 0] * bh // 180, bh - 1)
    s = hsv[:, 1] * bs // 256
    v = hsv[:, 2] * bv // 256
    return ((h * bs + s) * bv + v).reshape(shape)


def kernel_weights(height: int, width: int) -> np.ndarray:
    """Epanechnikov weights k = 1 - r^2 of a ``height x width`` patch (eq. 1, Lee et al. 2012).

    r is each pixel centre's distance to the patch centre divided by the largest such
    distance, so the corner pixels get weight 0 and the centre the most. The paper's prose
    says k = 1 - r (a cone); the book follows the printed eq. 1 (``01_kernel_histograms`` compares the two).
    """
    yy, xx = np.mgrid[0:height, 0:width].astype(float)
    dy = yy + 0.5 - height / 2
    dx = xx + 0.5 - width / 2
    r2 = dx**2 + dy**2
    return 1.0 - r2 / r2.max()


def ellipse_kernel(height: int, width: int) -> np.ndarray:
    """k(r) = max(0, 1 - r^2), r the ellipse-normalised radius of the inscribed ellipse.

    The kernel of Cho & Kang 2005 (eq. 2-3) and Comaniciu et al. 2003: pixels outside the
    ellipse inscribed in the patch get weight 0.
    """
    yy, xx = np.mgrid[0:height, 0:width].astype(float)
    dy = (yy + 0.5 - height / 2) / (height / 2)
    dx = (xx + 0.5 - width / 2) / (width / 2)
    return np.clip(1.0 - (dx**2 + dy**2), 0.0, None)


def weighted_histograms(bin_index: np.ndarray, kernel: np.ndarray, n_bins: int) -> np.ndarray:
    """Kernel-weighted, normalised histograms of N label patches in one ``bincount``.

    Parameters
    ----------
    bin_index : (N, h, w) int array of bin labels
    kernel : (h, w) weights
    n_bins : number of bins

    Returns
    -------
    (N, n_bins) array whose rows sum to 1. A patch whose kernel mass is zero (impossible for
    the kernels above, but cheap to guard) gets the uniform histogram.
    """
    n = bin_index.shape[0]
    offsets = (np.arange(n) * n_bins)[:, None, None]
    w = np.broadcast_to(kernel, bin_index.shape)
    hist = np.bincount((bin_index + offsets).ravel(), weights=w.ravel(),
                       minlength=n * n_bins).reshape(n, n_bins)
    total = hist.sum(axis=1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        hist = np.where(total > 0, hist / total, 1.0 / n_bins)
    return hist


def color_histograms(frame: np.ndarray, boxes, size=(16, 24), bins=HSV_BINS,
                     kernel: str = "patch") -> np.ndarray:
    """Kernel-weighted HSV histograms of every box, batched (eq. 1 of Lee et al. 2012).

    Each box is resampled to ``size = (width, height)`` (16 x 24 in the paper) in one call,
    binned in HSV, and accumulated with the kernel (``"patch"``: farthest pixel r = 1;
    ``"ellipse"``: the inscribed ellipse).

    Returns
    -------
    (N, prod(bins)) array, rows sum to 1.
    """
    patches = sample_patches(frame, boxes, size)
    idx = hsv_bin_index(patches, bins)
    k = kernel_weights(size[1], size[0]) if kernel == "patch" else ellipse_kernel(size[1], size[0])
    return weighted_histograms(idx, k, int(np.prod(bins)))


def bhattacharyya_coefficient(p, q) -> np.ndarray:
    """rho = sum_u sqrt(p_u q_u) along the last axis (1 for identical histograms, 0 for disjoint)."""
    p = np.asarray(p, dtype=float)
    q = np.asarray(q, dtype=float)
    return np.sqrt(np.clip(p, 0, None) * np.clip(q, 0, None)).sum(axis=-1)


def bhattacharyya_distance(p, q) -> np.ndarray:
    """D = sqrt(1 - rho), the distance in eq. 10-11 of Lee et al. 2012 (0 = identical)."""
    return np.sqrt(np.clip(1.0 - bhattacharyya_coefficient(p, q), 0.0, None))


def _channel_tables(bins) -> np.ndarray:
    """Per-channel look-up tables whose sum is the bin index of :func:`hsv_bin_index`."""
    bh, bs, bv = bins
    v = np.arange(256)
    t = np.stack([np.minimum(v * bh // 180, bh - 1) * bs * bv,   # H in 0..179
                  (v * bs // 256) * bv,
                  v * bv // 256], axis=-1)
    return t.astype(np.uint8).reshape(1, 256, 3)


_TABLES = {}


def hsv_bin_index_u8(bgr: np.ndarray, bins=HSV_BINS) -> np.ndarray:
    """:func:`hsv_bin_index` as a ``uint8`` image, for histograms of at most 256 bins.

    The same bins, computed without leaving OpenCV: ``cv2.LUT`` maps each HSV channel to its
    share of the index (h * bs * bv, s * bv, v) and ``cv2.transform`` adds the three shares.
    Faster than the integer arithmetic of :func:`hsv_bin_index` on the
    patches of a particle filter.
    """
    if int(np.prod(bins)) > 256:
        raise ValueError(f"bins = {bins} has more than 256 cells; use hsv_bin_index instead.")
    key = tuple(int(b) for b in bins)
    if key not in _TABLES:
        _TABLES[key] = _channel_tables(key)
    bgr = np.ascontiguousarray(bgr)
    shape = bgr.shape[:-1]
    # One long row: OpenCV pays per row, so the N x 1 column image of hsv_bin_index is several
    # times slower than the same pixels laid out as a single row.
    hsv = cv2.cvtColor(bgr.reshape(1, -1, 3), cv2.COLOR_BGR2HSV)
    shares = cv2.LUT(hsv, _TABLES[key])
    idx = cv2.transform(shares, np.ones((1, 3)))
    return idx.reshape(shape)
