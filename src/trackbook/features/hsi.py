"""HSI colour and HSI histograms: the colour model of Kim, Kim & Choi 2016's baseline (1).

The paper compares its edge model with "a particle filter based on the HSI colour model"
[quote: kim2016.baselines] (Nummiaro et al. 2003 use a colour histogram in a similar hue/saturation space). HSI is the
textbook (Gonzalez & Woods) conversion from RGB in [0, 1]:

    I = (R + G + B) / 3
    S = 1 - 3 min(R, G, B) / (R + G + B)            (S = 0 for black)
    H = theta if B <= G else 360 - theta,
    theta = arccos( ((R - G) + (R - B)) / 2 / sqrt((R - G)^2 + (R - B)(G - B)) )

in degrees; for grey pixels (R = G = B) the hue is undefined and set to 0.
"""

from __future__ import annotations

import numpy as np

from .color import kernel_weights, weighted_histograms
from .patches import sample_patches

#: Bins of the HSI histogram: hue x saturation x intensity (as the HSV bins of Lee et al. 2012).
HSI_BINS = (8, 8, 4)


def bgr_to_hsi(bgr: np.ndarray) -> np.ndarray:
    """HSI of a BGR uint8 image (any leading shape, last axis 3).

    Returns
    -------
    float array of the same shape: H in [0, 360) degrees, S and I in [0, 1].
    """
    a = np.asarray(bgr)
    if a.shape[-1] != 3:
        raise ValueError(f"bgr_to_hsi needs 3 channels in the last axis, got shape {a.shape}.")
    x = a.astype(np.float32) / 255.0
    b, g, r = x[..., 0], x[..., 1], x[..., 2]
    total = r + g + b
    i = total / 3.0
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.where(total > 0, 1.0 - 3.0 * np.minimum(np.minimum(r, g), b) / total, 0.0)
        num = 0.5 * ((r - g) + (r - b))
        den = np.sqrt((r - g) ** 2 + (r - b) * (g - b))
        cos = np.where(den > 1e-8, num / den, 1.0)
    theta = np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))
    h = np.where(b <= g, theta, 360.0 - theta)
    h = np.where(den > 1e-8, h, 0.0) % 360.0
    return np.stack([h, np.clip(s, 0.0, 1.0), i], axis=-1).astype(np.float32)


def hsi_bin_index(bgr: np.ndarray, bins=HSI_BINS) -> np.ndarray:
    """Bin index of every pixel in a ``bins[0] x bins[1] x bins[2]`` HSI histogram.

    Each channel is cut into equal intervals (H over [0, 360), S and I over [0, 1]).

    The same bins as binning :func:`bgr_to_hsi` (up to rounding within a float32 step of a bin
    edge), without its arccos: the hue's bin is found by comparing cos(theta) with the
    cosines of the bin edges (theta = arccos(cos) is decreasing in cos), so a particle
    filter's patches are binned about twice as fast.
    """
    a = np.asarray(bgr)
    if a.shape[-1] != 3:
        raise ValueError(f"hsi_bin_index needs 3 channels in the last axis, got shape {a.shape}.")
    bh, bs, bi = bins
    x = a.astype(np.float32) / 255.0            # the arithmetic of bgr_to_hsi, step by step
    b, g, r = x[..., 0], x[..., 1], x[..., 2]
    total = r + g + b
    i = np.minimum((total / 3.0 * bi).astype(np.int32), bi - 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.where(total > 0, 1.0 - 3.0 * np.minimum(np.minimum(r, g), b) / total, 0.0)
        # cos(theta) from the 0..255 integers, exact in float32 (a hue of exactly 90 degrees
        # has cos 0, not a rounding error away from it)
        y = a.astype(np.float32)
        rg, rb = y[..., 2] - y[..., 1], y[..., 2] - y[..., 0]
        den = np.sqrt(rg * rg + rb * (y[..., 1] - y[..., 0]))
        cos = np.where(den > 0, 0.5 * (rg + rb) / den, np.float32(2.0))
    s = np.minimum((np.clip(s, 0.0, 1.0) * bs).astype(np.int32), bs - 1)
    # theta >= edge  <=>  cos <= cos(edge); H = theta (B <= G) or 360 - theta (B > G)
    edges = np.arange(1, bh) * (360.0 / bh)
    up = np.zeros(cos.shape, np.int32)          # number of edges e <= theta
    down = np.zeros(cos.shape, np.int32)        # number of edges e <= 360 - theta
    def cos_of(deg):             # exact 0 at 90 degrees (np.cos gives 6e-17)
        c = np.cos(np.radians(deg))
        return np.float32(0.0 if abs(c) < 1e-12 else c)

    for e in edges:
        if e <= 180.0:
            up += cos <= cos_of(e)
        if 360.0 - e >= 180.0:
            down += 1
        else:
            down += cos >= cos_of(360.0 - e)
    # theta = 0 with B > G is H = 360 = 0; no hue (grey, den ~ 0, cos = 2) is bin 0
    h = np.where(b <= g, up, np.where(cos >= 1.0, 0, down))
    h = np.where(cos > 1.5, 0, h)
    return (h * bs + s) * bi + i


def hsi_histograms(frame: np.ndarray, boxes, size=(16, 24), bins=HSI_BINS) -> np.ndarray:
    """Kernel-weighted HSI histograms of every box, batched (baseline (1) of Kim et al. 2016).

    The boxes are resampled to ``size = (width, height)`` in one call, each pixel gets its HSI
    bin, and the bins are accumulated with the kernel k = 1 - r^2 (as eq. 1 of Lee et al. 2012
    and Nummiaro et al. 2003), so the centre of the box counts more than its border.

    Returns
    -------
    (N, prod(bins)) array whose rows sum to 1.
    """
    patches = sample_patches(frame, boxes, size)
    idx = hsi_bin_index(patches, bins)
    return weighted_histograms(idx, kernel_weights(size[1], size[0]), int(np.prod(bins)))
