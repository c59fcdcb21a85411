"""Correlation filters: ridge regression over all cyclic shifts, solved in the Fourier domain.

The book's ``10_correlation_filters``. The pure steps shared by the ``mosse``
(Bolme et al. 2010) and ``kcf`` (Henriques et al. 2015) trackers, each on arrays whose last
two axes are an image (rows, columns):

- :func:`hann_window`, :func:`gaussian_labels`: the cosine window and the desired response;
- :func:`mosse_terms`, :func:`mosse_filter`, :func:`linear_response`: the MOSSE filter
  H* = Σ G ⊙ F* / (Σ F ⊙ F* + λ) (Bolme et al. 2010, with a regularising λ);
- :func:`gaussian_correlation`, :func:`kcf_train`, :func:`kcf_response`: the Gaussian kernel
  correlation k^{xz} computed with FFTs over multi-channel features, the dual solution
  α̂ = ŷ / (k̂^{xx} + λ) and the detection response f̂(z) = k̂^{xz} ⊙ α̂ (Henriques et al.
  2015);
- :func:`psr`, :func:`peak_offset`: the peak-to-sidelobe ratio and the sub-cell peak.

Conventions (the tests check them against slow loops and ``numpy.linalg.solve``): the
response of a filter h on an image f is the circular cross-correlation
``g[t] = Σ_y f[y] h[y − t]`` = ``ifft2(F ⊙ conj(H))``, so a target that moved by ``d``
(``f = np.roll(x, d)``) puts the peak at index ``d`` (wrapped: indices past the middle are
negative moves). The labels' peak is at index (0, 0).
"""

from __future__ import annotations

import numpy as np

#: Side of the window around the peak that the sidelobe excludes (11 x 11, Bolme et al. 2010).
SIDELOBE_EXCLUDE = 11


def hann_window(rows: int, cols: int) -> np.ndarray:
    """The cosine (Hann) window, outer product of two 1-D Hann windows, zero at the edges.

    It tapers the patch so the cyclic shifts do not see a jump where the patch wraps around.
    """
    return np.outer(np.hanning(rows), np.hanning(cols))


def signed_index(n: int) -> np.ndarray:
    """Indices 0..n-1 as signed cyclic offsets: 0, 1, …, then −⌊n/2⌋…−1 for the upper half."""
    i = np.arange(n)
    return np.where(i > n // 2, i - n, i)


def gaussian_labels(rows: int, cols: int, sigma: float) -> np.ndarray:
    """Desired response y: a Gaussian of ``sigma`` (in samples) peaked at index (0, 0), wrapped.

    Sample t of y is the label of the patch cyclically shifted by t; the peak at zero shift
    says "the target is where the window is centred".
    """
    dy = signed_index(rows)[:, None]
    dx = signed_index(cols)[None, :]
    return np.exp(-0.5 * (dy * dy + dx * dx) / (float(sigma) ** 2))


# -- MOSSE ----------------------------------------------------------------------------------
def mosse_terms(F: np.ndarray, G: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Numerator A = G ⊙ F* and denominator B = F ⊙ F* of one training image (Bolme et al.).

    ``F`` may hold a stack of training images (…, rows, cols); the terms are summed over the
    stack, the sums over the training set of Bolme et al. 2010.
    """
    F = np.asarray(F)
    A = G * np.conj(F)
    B = (F.real * F.real + F.imag * F.imag)
    if F.ndim > 2:
        A = A.reshape(-1, *F.shape[-2:]).sum(axis=0)
        B = B.reshape(-1, *F.shape[-2:]).sum(axis=0)
    return A, B


def mosse_filter(A: np.ndarray, B: np.ndarray, lam: float) -> np.ndarray:
    """H* = A / (B + λ): the minimiser of Σ_i |F_i ⊙ H* − G_i|² + λ|H|², one frequency at a time.

    With the FFTs unnormalised (numpy's), Parseval makes this exactly the spatial ridge
    regression min_h Σ_i Σ_t (<h, shift_t f_i> − g_i[t])² + λ‖h‖² over all cyclic shifts.
    """
    return A / (B + lam)


def linear_response(H_conj: np.ndarray, F: np.ndarray) -> np.ndarray:
    """Response g = ifft2(F ⊙ H*) of the filter on the image(s) with spectrum ``F``."""
    return np.fft.ifft2(F * H_conj).real


# -- KCF ------------------------------------------------------------------------------------
def gaussian_correlation(xf: np.ndarray, zf: np.ndarray, sigma: float, x_sq: float | None = None,
                         z_sq=None) -> np.ndarray:
    """Gaussian kernel correlation k^{xz} of Henriques et al. 2015, over feature channels.

    ``k[t] = exp(−max(0, ‖x‖² + ‖z‖² − 2 Σ_c (x_c ⋆ z_c)[t]) / (σ² n))`` where ``⋆`` is the
    circular cross-correlation ``Σ_y z[y] x[y − t]`` computed as ``ifft2(ẑ ⊙ x̂*)``, so
    ``k[t] = κ(z, roll(x, t))``. The squared distance is divided by the number of feature
    values n (rows × cols × channels), as in the authors' reference code: σ is then a
    fraction of a typical feature value whatever the window's size.

    Parameters
    ----------
    xf : (C, rows, cols) spectrum of the model features x.
    zf : (…, C, rows, cols) spectra of one or several feature images z.
    sigma : the kernel's bandwidth σ.
    x_sq, z_sq : ‖x‖², ‖z‖² (computed from the spectra by Parseval when not given).

    Returns
    -------
    (…, rows, cols) real array k^{xz}.
    """
    xf = np.asarray(xf)
    zf = np.asarray(zf)
    rows, cols = xf.shape[-2:]
    n_pix = rows * cols
    if x_sq is None:
        x_sq = float(np.sum(xf.real ** 2 + xf.imag ** 2)) / n_pix
    if z_sq is None:
        z_sq = np.sum(zf.real ** 2 + zf.imag ** 2, axis=(-3, -2, -1)) / n_pix
    z_sq = np.asarray(z_sq, dtype=float)[..., None, None]
    # Σ over channels in the Fourier domain first: one inverse FFT instead of C.
    xz = np.fft.ifft2(np.sum(zf * np.conj(xf), axis=-3)).real
    d = np.maximum(x_sq + z_sq - 2.0 * xz, 0.0) / (n_pix * xf.shape[-3])
    return np.exp(-d / (float(sigma) ** 2))


def kcf_train(xf: np.ndarray, yf: np.ndarray, sigma: float, lam: float):
    """Dual coefficients α̂ = ŷ / (k̂^{xx} + λ) (Henriques et al. 2015).

    The kernel matrix of all cyclic shifts of x is circulant, K = C(k^{xx}), so the kernel
    ridge regression (K + λI) α = y is diagonalised by the DFT.

    Returns ``(alphaf, x_sq)``: α̂ and ‖x‖² (kept with the model for detection).
    """
    x_sq = float(np.sum(xf.real ** 2 + xf.imag ** 2)) / (xf.shape[-2] * xf.shape[-1])
    k = gaussian_correlation(xf, xf, sigma, x_sq, x_sq)
    return yf / (np.fft.fft2(k) + lam), x_sq


def kcf_response(alphaf: np.ndarray, xf: np.ndarray, zf: np.ndarray, sigma: float,
                 x_sq: float | None = None) -> np.ndarray:
    """Detection response f(z) = ifft2(k̂^{xz} ⊙ α̂) (Henriques et al. 2015).

    ``f[t] = Σ_s α_s κ(roll(z, −t), roll(x, −s))``: the regression evaluated at every cyclic
    shift of z at once; ``zf`` may be a stack (…, C, rows, cols).
    """
    k = gaussian_correlation(xf, zf, sigma, x_sq)
    return np.fft.ifft2(alphaf * np.fft.fft2(k)).real


# -- confidence and peak --------------------------------------------------------------------
def psr(response: np.ndarray, exclude: int = SIDELOBE_EXCLUDE) -> np.ndarray:
    """Peak-to-sidelobe ratio (g_max − μ_sl) / σ_sl of Bolme et al. 2010.

    The sidelobe is the response without the ``exclude`` x ``exclude`` window around the peak,
    taken cyclically (the response of a correlation filter wraps around). A flat sidelobe
    (σ_sl = 0, e.g. a zero response on a blank frame) gives 0: nothing stands out.

    Parameters
    ----------
    response : (…, rows, cols) one or a stack of responses.

    Returns
    -------
    float, or an array of the stack's shape.
    """
    r = np.asarray(response, dtype=float)
    rows, cols = r.shape[-2:]
    flat = r.reshape(-1, rows * cols)
    k = flat.argmax(axis=1)
    py, px = np.divmod(k, cols)
    half = exclude // 2
    dy = (np.arange(rows)[None, :] - py[:, None] + rows // 2) % rows - rows // 2
    dx = (np.arange(cols)[None, :] - px[:, None] + cols // 2) % cols - cols // 2
    inside = (np.abs(dy)[:, :, None] <= half) & (np.abs(dx)[:, None, :] <= half)
    side = ~inside.reshape(len(flat), -1)
    n = side.sum(axis=1)
    out = np.zeros(len(flat))
    ok = n > 1
    if np.any(ok):
        s = np.where(side, flat, 0.0)
        mu = s.sum(axis=1) / np.maximum(n, 1)
        var = np.where(side, (flat - mu[:, None]) ** 2, 0.0).sum(axis=1) / np.maximum(n, 1)
        sd = np.sqrt(var)
        peak = flat[np.arange(len(flat)), k]
        good = ok & (sd > 1e-12 * np.maximum(np.abs(peak), 1e-300))
        out[good] = (peak[good] - mu[good]) / sd[good]
    out = out.reshape(r.shape[:-2])
    return float(out) if out.ndim == 0 else out


def apce(response: np.ndarray) -> np.ndarray:
    """Average peak-to-correlation energy |g_max - g_min|^2 / mean((g - g_min)^2) (Wang et
    al. 2017): how sharp the peak is against the whole response (a sharp single peak is
    large, a noisy or multi-peaked map small). Not what the trackers report (they report the
    PSR); a second measure to compare it with. A constant response gives 0.

    Parameters
    ----------
    response : (…, rows, cols) one or a stack of responses.

    Returns
    -------
    float, or an array of the stack's shape.
    """
    r = np.asarray(response, dtype=float)
    flat = r.reshape(-1, r.shape[-2] * r.shape[-1])
    lo = flat.min(axis=1)
    span2 = (flat.max(axis=1) - lo) ** 2
    energy = np.mean((flat - lo[:, None]) ** 2, axis=1)
    out = np.where(energy > 0, span2 / np.where(energy > 0, energy, 1.0), 0.0)
    out = out.reshape(r.shape[:-2])
    return float(out) if out.ndim == 0 else out


def peak_offset(response: np.ndarray) -> tuple[float, float]:
    """The response's peak as a signed cyclic offset (dy, dx), refined by a parabola.

    The integer peak is the argmax; each axis is refined by the vertex of the parabola
    through the peak and its two cyclic neighbours (at most half a sample either way).
    """
    r = np.asarray(response, dtype=float)
    rows, cols = r.shape
    py, px = np.unravel_index(int(np.argmax(r)), r.shape)

    def vertex(left, mid, right):
        den = left - 2.0 * mid + right
        if not np.isfinite(den) or den >= 0:
            return 0.0
        return float(np.clip(0.5 * (left - right) / den, -0.5, 0.5))

    oy = vertex(r[(py - 1) % rows, px], r[py, px], r[(py + 1) % rows, px]) if rows > 2 else 0.0
    ox = vertex(r[py, (px - 1) % cols], r[py, px], r[py, (px + 1) % cols]) if cols > 2 else 0.0
    sy = py - rows if py > rows // 2 else py
    sx = px - cols if px > cols // 2 else px
    return float(sy + oy), float(sx + ox)


__all__ = ["SIDELOBE_EXCLUDE", "hann_window", "signed_index", "gaussian_labels", "mosse_terms",
           "mosse_filter", "linear_response", "gaussian_correlation", "kcf_train",
           "kcf_response", "psr", "apce", "peak_offset"]
