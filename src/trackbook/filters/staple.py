"""Staple's two learners and their merge (Bertinetto, Valmadre, Golodetz, Miksik & Torr 2016).

Pure steps of the ``staple`` tracker, each on arrays whose last axes are an image:

Template (a correlation filter on HOG cells, linear kernel)
    :func:`dcf_terms`, :func:`dcf_response`: the multi-channel filter
    ĥ_c = ŷ* x̂_c / (Σ_k |x̂_k|² + λ) with numerator and denominator averaged over the cyclic
    shifts (divided by their number n), as the authors' code does ("compute expectations over
    circular shifts"): for one training image it is the exact minimiser of

        (1/n) Σ_t ( Σ_c ⟨h_c, x_c shifted by t⟩ − y[t] )² + λ Σ_c ‖h_c‖²,

    because the per-frequency system (x̂ x̂ᴴ + nλ I) ĥ = x̂ ŷ* has rank one plus nλ I, whose
    solution is x̂ ŷ* / (x̂ᴴ x̂ + nλ) (Sherman–Morrison). With running averages of the
    numerator and the denominator over frames (learning rate η_tmpl) it is the approximation
    of Danelljan et al. 2014 that Staple adopts.
    :func:`crop_response`, :func:`response_on_grid`: the cyclic response (in cells) cut to the
    square of translations searched and resized to the colour response's pixel grid, as the
    authors' ``cropFilterResponse.m`` and ``mexResize`` do.

Histogram (colour)
    :func:`colour_bins`, :func:`colour_histogram`, :func:`object_likelihood`: each pixel's
    colour bin, the foreground and background frequencies ρ(O), ρ(B) (histograms normalised
    by the number of pixels counted) and the per-pixel score β = ρ(O) / (ρ(O) + ρ(B)) of the
    pixel's bin, 0 for a colour seen in neither region (the authors' ``getColourMap.m``).
    :func:`box_means`: the histogram response, the mean of β over a target-sized box at
    every placement, from an integral image (four look-ups a box).

Merge
    :func:`merge_responses`: f(x) = (1 − γ) f_tmpl(x) + γ f_hist(x).

Scale (Danelljan et al. 2014's 1-D scale filter, as Staple's code uses it)
    :func:`scale_factors`, :func:`scale_labels`, :func:`scale_terms`, :func:`scale_response`:
    features of patches at S scales of the target, a 1-D filter along the scale axis,
    Ĥ_d = Ŷ* X̂_d / (Σ_k |X̂_k|² + λ); its peak is the scale change.

Conventions are those of :mod:`trackbook.filters.correlation`: the response of a filter h on
an image f is ``g[t] = Σ_y f[y] h[y − t]`` = ``ifft2(F ⊙ conj(H))``; index 0 is "no move".
"""

from __future__ import annotations

import cv2
import numpy as np


# -- template: the multi-channel correlation filter ---------------------------------------
def dcf_terms(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Numerator r̂ = ŷ* ⊙ x̂_c / n and denominator d̂ = Σ_c |x̂_c|² / n of one training image.

    The spectra are those of real images, so only the half-plane ``numpy.fft.rfft2`` keeps
    is computed and stored (the other half is its conjugate mirror).

    Parameters
    ----------
    x : (C, rows, cols) windowed feature channels of the training window.
    y : (rows, cols) desired response (peak at index (0, 0)).

    Returns
    -------
    num : (C, rows, cols // 2 + 1) complex; den : (rows, cols // 2 + 1) real.
    n = rows × cols: the terms are averages over the n cyclic shifts, so λ weighs against the
    mean squared error.
    """
    x = np.asarray(x, dtype=np.float64)
    n = x.shape[-2] * x.shape[-1]
    xf = np.fft.rfft2(x)
    num = np.conj(np.fft.rfft2(y)) * xf / n
    den = np.sum(xf.real * xf.real + xf.imag * xf.imag, axis=-3) / n
    return num, den


def dcf_filter(num: np.ndarray, den: np.ndarray, lam: float) -> np.ndarray:
    """ĥ_c = r̂_c / (d̂ + λ): the filter's half spectra (one per channel)."""
    return num / (den + lam)


def dcf_response(num: np.ndarray, den: np.ndarray, z: np.ndarray, lam: float) -> np.ndarray:
    """Template response f_tmpl = ifft2(Σ_c conj(ĥ_c) ⊙ ẑ_c), ĥ_c = r̂_c / (d̂ + λ).

    Parameters
    ----------
    num, den : the (running) terms of :func:`dcf_terms`.
    z : (…, C, rows, cols) one or a stack of windowed feature images.
    lam : λ.

    Returns
    -------
    (…, rows, cols) real, cyclic: index (0, 0) is the window's centre, index t the response
    to the target moved by t.
    """
    z = np.asarray(z, dtype=np.float64)
    zf = np.fft.rfft2(z)
    hf = dcf_filter(num, den, lam)
    return np.fft.irfft2(np.sum(np.conj(hf) * zf, axis=-3), s=z.shape[-2:])


def odd_floor(x: float) -> int:
    """The largest odd integer ≤ x (at least 1): a crop with an exact centre."""
    return max(2 * int(np.floor((x - 1) / 2)) + 1, 1)


def crop_response(response: np.ndarray, side: int) -> np.ndarray:
    """The ``side`` x ``side`` square of a cyclic response centred on "no move" (index 0).

    Row i of the result is the shift i − side // 2 (the authors' ``cropFilterResponse.m``);
    ``side`` must be odd so the centre is exact.
    """
    if side % 2 != 1:
        raise ValueError(f"side={side} must be odd (the crop's centre is the zero shift).")
    r = np.asarray(response)
    h = side // 2
    iy = np.arange(-h, h + 1) % r.shape[-2]
    ix = np.arange(-h, h + 1) % r.shape[-1]
    return r[..., iy[:, None], ix[None, :]]


def response_on_grid(response: np.ndarray, cells: int, side: int) -> np.ndarray:
    """The template response on the colour response's grid: crop, then resize.

    The cyclic response (one sample per cell) is cut to the ``cells`` x ``cells`` square of
    shifts (:func:`crop_response`) and resized bilinearly to ``side`` x ``side`` pixels
    (``cv2.resize``, pixel centres aligned, so the two centres coincide), as the authors'
    code does with ``cropFilterResponse`` and ``mexResize``.

    Parameters
    ----------
    response : (…, rows, cols) cyclic responses.
    cells, side : odd sizes of the crop and of the grid.

    Returns
    -------
    (…, side, side) float array.
    """
    c = np.asarray(crop_response(response, cells), dtype=np.float64)
    lead = c.shape[:-2]
    stack = c.reshape(-1, cells, cells).transpose(1, 2, 0)    # the stack as channels: one call
    out = np.empty((side, side, stack.shape[2]))
    # cv2.resize takes at most 512 channels at once
    for a in range(0, stack.shape[2], 512):
        part = cv2.resize(np.ascontiguousarray(stack[:, :, a:a + 512]), (side, side),
                          interpolation=cv2.INTER_LINEAR)
        out[:, :, a:a + 512] = part.reshape(side, side, -1)
    return out.transpose(2, 0, 1).reshape(lead + (side, side))


# -- histogram: the colour model ------------------------------------------------------------
def colour_bins(patch: np.ndarray, n_bins: int, colour: bool = True) -> np.ndarray:
    """Each pixel's histogram bin: ⌊v / (256 / n_bins)⌋ per channel, joined into one index.

    Parameters
    ----------
    patch : (…, h, w, 3) uint8 colour patches (``colour=True``), or (…, h, w) grey patches.
    n_bins : bins per channel.
    colour : whether the last axis holds the three colour channels.

    Returns
    -------
    (…, h, w) int array in [0, n_bins^d), d = 3 for colour, 1 for grey; for colour the index
    is (b_0 n_bins + b_1) n_bins + b_2 over the channels in their order.
    """
    p = np.asarray(patch)
    # one look-up per value instead of a product and a division per pixel
    lut = (np.arange(256, dtype=np.int64) * int(n_bins)) // 256
    b = lut[p] if p.dtype == np.uint8 else (p.astype(np.int64) * int(n_bins)) // 256
    if colour:
        if p.shape[-1] != 3:
            raise ValueError(f"colour patches need 3 channels on the last axis, got {p.shape}.")
        return (b[..., 0] * n_bins + b[..., 1]) * n_bins + b[..., 2]
    return b


def colour_histogram(bins: np.ndarray, mask: np.ndarray, n_cells: int) -> np.ndarray:
    """Frequencies ρ of the bins over the pixels of ``mask``: counts / number counted.

    Parameters
    ----------
    bins : (h, w) bin indices (:func:`colour_bins`).
    mask : (h, w) weights in [0, 1] (1 = the pixel belongs to the region).
    n_cells : number of bins of the histogram (n_bins^d).

    Returns
    -------
    (n_cells,) float array summing to 1 (all zeros for an empty region).
    """
    m = np.asarray(mask, dtype=np.float64)
    counts = np.bincount(np.asarray(bins).ravel(), weights=m.ravel(), minlength=n_cells)
    total = m.sum()
    return counts / total if total > 0 else counts


def object_likelihood(bins: np.ndarray, fg_hist: np.ndarray, bg_hist: np.ndarray) -> np.ndarray:
    """Per-pixel score β = ρ(O) / (ρ(O) + ρ(B)) of each pixel's bin; 0 where both are 0.

    ρ(O), ρ(B) are the foreground and background frequencies of the bin. A colour never
    seen in either region scores 0, as in the authors' code (``likelihood_map(isnan) = 0``).
    """
    fg = np.asarray(fg_hist)[bins]
    bg = np.asarray(bg_hist)[bins]
    s = fg + bg
    return np.where(s > 0, fg / np.where(s > 0, s, 1.0), 0.0)


def box_means(image: np.ndarray, box: tuple[int, int]) -> np.ndarray:
    """Mean of ``image`` over every ``box = (h, w)`` placement inside it, by an integral image.

    Entry (i, j) is the mean over rows i..i+h−1 and columns j..j+w−1, computed as
    (S[i+h, j+w] − S[i, j+w] − S[i+h, j] + S[i, j]) / (h w) with S the summed-area table
    padded by a zero row and column (the authors' ``getCenterLikelihood.m``).

    Parameters
    ----------
    image : (…, H, W) float array.
    box : (h, w) with 1 ≤ h ≤ H, 1 ≤ w ≤ W.

    Returns
    -------
    (…, H − h + 1, W − w + 1) float array.
    """
    a = np.asarray(image, dtype=np.float64)
    h, w = (int(v) for v in box)
    H, W = a.shape[-2:]
    if not (1 <= h <= H and 1 <= w <= W):
        raise ValueError(f"box {h}x{w} does not fit in an image of {H}x{W}.")
    S = np.zeros(a.shape[:-2] + (H + 1, W + 1))
    S[..., 1:, 1:] = a.cumsum(axis=-2).cumsum(axis=-1)
    total = (S[..., h:, w:] - S[..., :H - h + 1, w:] - S[..., h:, :W - w + 1]
             + S[..., :H - h + 1, :W - w + 1])
    return total / (h * w)


# -- merge ---------------------------------------------------------------------------------
def merge_responses(template: np.ndarray, histogram: np.ndarray, gamma: float) -> np.ndarray:
    """Staple's merged score f = (1 − γ) f_tmpl + γ f_hist, on one grid (same shape)."""
    t = np.asarray(template, dtype=np.float64)
    h = np.asarray(histogram, dtype=np.float64)
    if t.shape != h.shape:
        raise ValueError(f"the responses must share a grid: {t.shape} and {h.shape}.")
    return (1.0 - gamma) * t + gamma * h


# -- scale: the 1-D scale filter of Danelljan et al. 2014 -------------------------------------
def scale_factors(n_scales: int, step: float) -> np.ndarray:
    """a^k for k = ⌈S/2⌉ − s, s = 1..S: the relative sizes sampled, largest first, 1 in the
    middle (index ⌈S/2⌉ − 1)."""
    s = np.arange(1, n_scales + 1)
    return float(step) ** (np.ceil(n_scales / 2) - s)


def scale_labels(n_scales: int, sigma_factor: float) -> np.ndarray:
    """Desired scale response: a Gaussian of σ = √S × ``sigma_factor`` over s − ⌈S/2⌉,
    peaked at the middle scale (the current size)."""
    ss = np.arange(1, n_scales + 1) - np.ceil(n_scales / 2)
    sigma = np.sqrt(n_scales) * sigma_factor
    return np.exp(-0.5 * ss ** 2 / sigma ** 2)


def scale_window(n_scales: int) -> np.ndarray:
    """Hann window over the scales (for an even S, the S + 1 window without its first
    sample, as in the DSST code)."""
    if n_scales % 2 == 0:
        return np.hanning(n_scales + 1)[1:]
    return np.hanning(n_scales)


def scale_terms(xs: np.ndarray, ys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Numerator Ŷ X̂_d* and denominator Σ_d |X̂_d|² of the 1-D scale filter.

    Parameters
    ----------
    xs : (D, S) features (one column per scale, already windowed).
    ys : (S,) desired scale response (:func:`scale_labels`).

    Returns
    -------
    num : (D, S) complex; den : (S,) real. Unlike the template's terms they are not divided
    by S (the DSST code's convention): λ weighs against the summed squared error.
    """
    xsf = np.fft.fft(np.asarray(xs, dtype=np.float64), axis=-1)
    num = np.fft.fft(ys)[None, :] * np.conj(xsf)
    den = np.sum(xsf.real ** 2 + xsf.imag ** 2, axis=0)
    return num, den


def scale_response(num: np.ndarray, den: np.ndarray, zs: np.ndarray, lam: float) -> np.ndarray:
    """Scale response ifft(Σ_d num_d ⊙ Ẑ_d / (den + λ)), (S,) real; its argmax is the scale."""
    zsf = np.fft.fft(np.asarray(zs, dtype=np.float64), axis=-1)
    return np.fft.ifft(np.sum(num * zsf, axis=0) / (den + lam)).real


__all__ = ["dcf_terms", "dcf_filter", "dcf_response", "odd_floor", "crop_response", "response_on_grid",
           "colour_bins", "colour_histogram", "object_likelihood", "box_means",
           "merge_responses", "scale_factors", "scale_labels", "scale_window", "scale_terms",
           "scale_response"]
