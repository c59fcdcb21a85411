"""Discriminative correlation filters on d-channel features, and DSST's 1-D scale filter.

The maths of DSST (Danelljan, Häger, Khan & Felsberg, BMVC 2014, "Accurate scale estimation
for robust visual tracking"), pure functions on arrays:

- :func:`multichannel_terms`, :func:`multichannel_filter`, :func:`multichannel_response`:
  the filter h = (h^1 … h^d) over d feature channels f^l that minimises

      ε = ‖ Σ_l h^l ⋆ f^l − g ‖² + λ Σ_l ‖h^l‖²,

  solved frequency by frequency: H^l = Ḡ F^l / (Σ_k F̄^k F^k + λ) (capitals are DFTs, the bar
  complex conjugation). The tracker keeps the numerator A^l = Ḡ F^l and the denominator
  B = Σ_k F̄^k F^k as running averages of learning rate η,
  A_t = (1 − η) A_{t−1} + η Ḡ F_t, B_t likewise, and scores a new sample z by
  y = F^{-1}{ Σ_l Ā^l Z^l / (B + λ) }. The same functions serve the 2-D translation filter
  (channels × rows × cols) and the 1-D scale filter (channels × scales): ``ndim`` says how
  many trailing axes are the signal, the axis before them holds the channels.
- :func:`scale_exponents`, :func:`scale_labels`, :func:`scale_window`,
  :func:`scale_model_size`, :func:`scale_limits`: the scale search's geometry: S scales
  a^n, n ∈ {−(S−1)/2 … (S−1)/2}, the 1-D Gaussian label over n, the cosine window over the
  scales, the fixed size every scale sample is resized to, and the scale factors the tracker
  is kept between.

Conventions (the tests check them against the ridge regression over all cyclic shifts solved
with ``numpy.linalg.solve``): ``h ⋆ f`` is the circular cross-correlation
``(h ⋆ f)[t] = Σ_y f[y] h[y − t]``, whose DFT is H̄ F, so the response of h on a sample that
moved by d peaks d samples after where g peaks. DFTs are numpy's (unnormalised); Parseval then
makes λ the same number in the spatial and the Fourier form of ε.

With one training sample, H^l above is the exact minimiser of ε (per frequency the data are
the single row (F^1 … F^d), and (f^H f + λ I)^{-1} f^H = f^H / (‖f‖² + λ)). With running
averages of A and B over many samples it is the approximation the paper adopts: the exact
multi-sample solution needs a d × d system per frequency.
"""

from __future__ import annotations

import numpy as np
import scipy.fft


def _axes(ndim: int) -> tuple[int, ...]:
    if ndim not in (1, 2):
        raise ValueError(f"ndim must be 1 (a scale filter) or 2 (a translation filter), "
                         f"got {ndim!r}.")
    return tuple(range(-ndim, 0))


def spectra(x: np.ndarray, ndim: int, half: bool = False) -> np.ndarray:
    """DFT of every channel of ``x`` over its last ``ndim`` axes (the signal's).

    ``half=True`` gives the real DFT (``scipy.fft.rfftn``: the last axis keeps its first
    n // 2 + 1 frequencies) in ``x``'s precision (float32 in, complex64 out): the features
    are real, so the other half is the conjugate of this one and every product and sum of
    the filter keeps that symmetry; pass ``shape`` to :func:`multichannel_response` to
    invert it. (SciPy's, not NumPy's: NumPy computes a float32 transform in double precision
    and converts, several times slower.)
    """
    _axes(ndim)
    if half:
        x = np.asarray(x)
        if x.dtype not in (np.float32, np.float64):
            x = x.astype(np.float64)
        return scipy.fft.rfftn(x, axes=_axes(ndim))
    x = np.asarray(x, dtype=np.float64)
    return np.fft.fft2(x) if ndim == 2 else np.fft.fft(x, axis=-1)


def multichannel_terms(F: np.ndarray, G: np.ndarray, ndim: int = 2):
    """Numerator A^l = Ḡ F^l and denominator B = Σ_k F̄^k F^k of one training sample.

    Parameters
    ----------
    F : (…, d, *signal) complex, the DFTs of the sample's d channels.
    G : (*signal) complex, the DFT of the desired output g.
    ndim : 1 (scale filter: signal = scales) or 2 (translation filter: rows × cols).

    Returns
    -------
    A : array of F's shape, B : F's shape without the channel axis.
    """
    _axes(ndim)
    F = np.asarray(F)
    A = np.conj(G) * F
    B = np.sum(F.real * F.real + F.imag * F.imag, axis=-(ndim + 1))
    return A, B


def multichannel_filter(A: np.ndarray, B: np.ndarray, lam: float, ndim: int = 2) -> np.ndarray:
    """The filter's DFT H^l = A^l / (B + λ) (eq. of the d-dimensional filter)."""
    _axes(ndim)
    return np.asarray(A) / (np.expand_dims(np.asarray(B), -(ndim + 1)) + lam)


def multichannel_response(A: np.ndarray, B: np.ndarray, Z: np.ndarray, lam: float,
                          ndim: int = 2, shape=None) -> np.ndarray:
    """Correlation scores y = F^{-1}{ Σ_l Ā^l Z^l / (B + λ) } of a sample with DFT ``Z``.

    ``Z`` may be a stack (…, d, *signal); the channels are summed in the Fourier domain, so a
    stack costs one inverse DFT per sample, not one per channel.

    ``shape``: the signal's shape when A, B and Z are real DFTs (``spectra(..., half=True)``).

    Returns
    -------
    (…, *signal) real array: score t is the filter's output for the sample shifted by t.
    """
    axes = _axes(ndim)
    num = np.sum(np.conj(A) * np.asarray(Z), axis=-(ndim + 1))
    Y = num / (np.asarray(B) + lam)
    if shape is not None:
        return scipy.fft.irfftn(Y, s=tuple(shape), axes=axes)
    return (np.fft.ifft2(Y) if ndim == 2 else np.fft.ifft(Y, axis=-1)).real


def update_terms(A, B, A_new, B_new, eta: float):
    """Running averages A_t = (1 − η) A_{t−1} + η A_new, B_t likewise (the paper's update).

    ``A`` and ``B`` are updated in place (and returned): the model is the largest array a
    tracker keeps, and a new one per frame would cost an allocation each time.
    """
    for old, new in ((A, A_new), (B, B_new)):
        old *= 1.0 - eta
        old += eta * new
    return A, B


# -- the scale search ------------------------------------------------------------------------
def scale_exponents(n_scales: int) -> np.ndarray:
    """The exponents n of the S scales a^n, ascending, centred on 0 (−(S−1)/2 … (S−1)/2).

    For an even S the exponents are the integers from −S/2 + 1 to S/2 (as the reference code,
    whose label peaks at index ⌈S/2⌉), so 0 is always one of them.
    """
    S = int(n_scales)
    if S < 1:
        raise ValueError(f"n_scales must be at least 1, got {n_scales!r}.")
    return np.arange(S) - (S - 1) // 2


def scale_factors(n_scales: int, step: float) -> np.ndarray:
    """The relative scales a^n of the scale samples (:func:`scale_exponents`)."""
    return float(step) ** scale_exponents(n_scales).astype(float)


def scale_labels(n_scales: int, sigma: float) -> np.ndarray:
    """The 1-D Gaussian desired output over the scales, exp(−n² / 2σ²), peaked at n = 0.

    Not wrapped: index i belongs to exponent ``scale_exponents(S)[i]``, so the argmax of a
    response is the index of the scale sample that matches the model.
    """
    n = scale_exponents(n_scales).astype(float)
    return np.exp(-0.5 * n * n / float(sigma) ** 2)


def scale_sigma(n_scales: int, sigma_factor: float) -> float:
    """σ of the scale label in scale steps: S / √33 × factor (the reference code's rule)."""
    return float(n_scales) / np.sqrt(33.0) * float(sigma_factor)


def scale_window(n_scales: int) -> np.ndarray:
    """The cosine (Hann) window over the S scale samples, zero at both ends.

    For an even S, the last S values of the window of S + 1 (the reference code's choice),
    so its peak stays on the label's.
    """
    S = int(n_scales)
    return np.hanning(S) if S % 2 else np.hanning(S + 1)[1:]


def scale_model_size(target_size, max_area: float, min_side: int = 1) -> tuple[int, int]:
    """(width, height) every scale sample is resized to: the first frame's target, shrunk to at
    most ``max_area`` pixels keeping its aspect ratio, never below ``min_side`` a side."""
    w, h = (float(v) for v in target_size)
    f = np.sqrt(max_area / (w * h)) if w * h > max_area else 1.0
    return max(int(np.floor(w * f)), min_side), max(int(np.floor(h * f)), min_side)


def scale_limits(window_size, target_size, image_size, step: float) -> tuple[float, float]:
    """Smallest and largest scale factor (powers of ``step``) the tracker may take.

    The smallest keeps the search window at least 5 px a side; the largest keeps the target
    no larger than the image (the reference code's rule).

    Parameters
    ----------
    window_size : (width, height) of the search window at scale 1.
    target_size : (width, height) of the target at scale 1.
    image_size : (width, height) of the frames.
    """
    ln = np.log(float(step))
    low = np.ceil(np.log(np.max(5.0 / np.asarray(window_size, dtype=float))) / ln)
    high = np.floor(np.log(np.min(np.asarray(image_size, dtype=float)
                                  / np.asarray(target_size, dtype=float))) / ln)
    return float(step) ** low, float(step) ** max(high, low)


__all__ = ["spectra", "multichannel_terms", "multichannel_filter", "multichannel_response",
           "update_terms", "scale_exponents", "scale_factors", "scale_labels", "scale_sigma",
           "scale_window", "scale_model_size", "scale_limits"]
