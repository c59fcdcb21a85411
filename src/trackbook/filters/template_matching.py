"""Template matching: the sum of squared differences (SSD) and zero-mean normalised
cross-correlation (NCC) of a template against every window of an image, as response maps.

For a template T of h x w pixels and an image I, the response at the window whose top-left
corner is (x, y), for every (x, y) with the window inside the image ("valid" positions, an
(H - h + 1) x (W - w + 1) map, as ``cv2.matchTemplate``):

SSD (``cv2.TM_SQDIFF``)::

    R(x, y) = sum_{u,v} (T(u, v) - I(x + u, y + v))^2
            = sum T^2  -  2 sum_{u,v} T(u, v) I(x + u, y + v)  +  sum_{window} I^2

Zero-mean NCC (``cv2.TM_CCOEFF_NORMED``), with T' = T - mean(T) and I' the window minus its
own mean::

    R(x, y) = sum T'(u, v) I'(x + u, y + v) / sqrt(sum T'^2  sum_{window} I'^2)

Because sum T' = 0, the numerator equals the plain correlation sum T' I, and
sum_{window} I'^2 = sum_{window} I^2 - (sum_{window} I)^2 / (h w). So both maps need one
cross-correlation (computed by FFT, :func:`scipy.signal.fftconvolve` with the template
flipped) and two window sums of I and I^2 (from integral images): no loop over positions.
SSD is best at its minimum, NCC (in [-1, 1]) at its maximum.

:func:`patch_ncc` is the same NCC for many pairs of equal-sized patches at once (one value
per pair), as Median Flow uses it to compare the patches around a point in two frames.
"""

from __future__ import annotations

import numpy as np

__all__ = ["best_match", "ncc_map", "patch_ncc", "ssd_map", "window_sums"]


def _grey(a, name: str) -> np.ndarray:
    a = np.asarray(a)
    if a.ndim != 2:
        raise ValueError(f"{name} must be a 2-D grey image, got shape {a.shape}; convert a "
                         "colour frame first (e.g. trackbook.filters.optical_flow.to_gray).")
    return a.astype(np.float64)


def _checked(image, template):
    I, T = _grey(image, "image"), _grey(template, "template")
    if T.shape[0] > I.shape[0] or T.shape[1] > I.shape[1] or T.size == 0:
        raise ValueError(f"template of shape {T.shape} does not fit in the image of shape "
                         f"{I.shape}; pass a non-empty template no larger than the image.")
    return I, T


def window_sums(a: np.ndarray, h: int, w: int) -> np.ndarray:
    """Sum of ``a`` over every h x w window (valid positions), from an integral image.

    Returns an (H - h + 1, W - w + 1) float64 array S with S[y, x] = sum a[y:y+h, x:x+w].
    """
    a = np.asarray(a, dtype=np.float64)
    s = np.zeros((a.shape[0] + 1, a.shape[1] + 1))
    s[1:, 1:] = a.cumsum(0).cumsum(1)
    return s[h:, w:] - s[:-h, w:] - s[h:, :-w] + s[:-h, :-w]


def _correlate(I, T):
    """sum_{u,v} T(u, v) I(x + u, y + v) at every valid (x, y): a convolution with T flipped."""
    # imported here: scipy.signal takes seconds to import, and `import trackbook` (every page
    # of the book, every command) would pay for it through the trackers that use this module
    from scipy.signal import fftconvolve

    return fftconvolve(I, T[::-1, ::-1], mode="valid")


def ssd_map(image, template) -> np.ndarray:
    """SSD response map R(x, y) = sum (T - I_window)^2 (the module docstring's first equation).

    Parameters
    ----------
    image : (H, W) grey image
    template : (h, w) grey image, h <= H, w <= W

    Returns
    -------
    (H - h + 1, W - w + 1) float64 array, >= 0; the best match is its minimum. Values equal to
    ``cv2.matchTemplate(image, template, cv2.TM_SQDIFF)`` up to rounding.
    """
    I, T = _checked(image, template)
    h, w = T.shape
    r = np.sum(T * T) - 2.0 * _correlate(I, T) + window_sums(I * I, h, w)
    return np.maximum(r, 0.0)          # the FFT's rounding can dip a perfect match below 0


def ncc_map(image, template) -> np.ndarray:
    """Zero-mean NCC response map (the module docstring's second equation).

    Parameters
    ----------
    image : (H, W) grey image
    template : (h, w) grey image, h <= H, w <= W

    Returns
    -------
    (H - h + 1, W - w + 1) float64 array in [-1, 1]; the best match is its maximum. A window
    or template with no variance has no defined NCC: 0 there (no evidence either way).
    """
    I, T = _checked(image, template)
    h, w = T.shape
    n = h * w
    Tz = T - T.mean()
    num = _correlate(I, Tz)
    s1 = window_sums(I, h, w)
    var_i = np.maximum(window_sums(I * I, h, w) - s1 * s1 / n, 0.0)
    var_t = float(np.sum(Tz * Tz))
    den = np.sqrt(var_i * var_t)
    # the integral image's rounding is relative to the whole image's sum of squares: a window
    # variance within a few thousand ulps of it is a constant window, not a texture
    tiny = 1e-12 * max(float(np.sum(I * I)), 1.0)
    out = np.zeros_like(num)
    good = (var_i > tiny) & (var_t > 1e-12 * max(float(np.sum(T * T)), 1.0))
    out[good] = num[good] / den[good]
    return np.clip(out, -1.0, 1.0)


def best_match(response: np.ndarray, method: str) -> tuple[int, int]:
    """(x, y) of the best window: the minimum of an ``"ssd"`` map, the maximum of an ``"ncc"``
    one."""
    if method not in ("ssd", "ncc"):
        raise ValueError(f"method={method!r}: use 'ssd' (minimum) or 'ncc' (maximum).")
    r = np.asarray(response)
    k = int(np.argmin(r) if method == "ssd" else np.argmax(r))
    y, x = np.unravel_index(k, r.shape)
    return int(x), int(y)


def patch_ncc(a, b) -> np.ndarray:
    """Zero-mean NCC of pairs of equal patches: ``a[i]`` against ``b[i]``.

    Parameters
    ----------
    a, b : (N, h, w) arrays

    Returns
    -------
    (N,) float64 array in [-1, 1]: sum a'_i b'_i / sqrt(sum a'_i^2 sum b'_i^2), with a'_i the
    patch minus its mean; 0 for a pair in which either patch is constant.
    """
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    if a.shape != b.shape or a.ndim != 3:
        raise ValueError(f"patch_ncc needs two (N, h, w) arrays of one shape, got {a.shape} "
                         f"and {b.shape}.")
    a = a.reshape(len(a), -1)
    b = b.reshape(len(b), -1)
    a = a - a.mean(1, keepdims=True)
    b = b - b.mean(1, keepdims=True)
    den = np.sqrt(np.sum(a * a, 1) * np.sum(b * b, 1))
    num = np.sum(a * b, 1)
    out = np.zeros(len(a))
    good = den > 1e-12
    out[good] = num[good] / den[good]
    return np.clip(out, -1.0, 1.0)
