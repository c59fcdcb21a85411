r"""Background-aware correlation filters: a target-sized filter trained on a large window, by ADMM.

Kiani Galoogahi, Fagg & Lucey, ICCV 2017 ("Learning background-aware correlation filters for
visual tracking"), the ``bacf`` tracker. The pure steps, on arrays whose last two axes are an
image of :math:`T = M \times N` feature cells and whose third-last axis is the :math:`K`
channels.

The problem (the paper's eq. 1-3, one training image). A filter :math:`h_k` of the target's
size :math:`D \ll T` per channel is correlated with *every* cyclic shift of a window
:math:`x_k` much larger than the target; the cropping matrix :math:`P` (:math:`D \times T`,
binary) keeps the :math:`D` central cells of each shift, so the shifts that move the target
out of the centre show real background, not periodic copies of the target:

.. math::
    E(h) = \tfrac12 \sum_{j=1}^{T} \Bigl(y(j) - \sum_{k=1}^K h_k^\top P\, x_k[\Delta\tau_j]
           \Bigr)^2 + \tfrac{\lambda}{2} \sum_k \|h_k\|^2 .

Written with the zero-padded filter :math:`g_k = P^\top h_k` (a :math:`T`-cell image that is
zero outside the support: :func:`support_mask`), the response on the shifts is the circular
cross-correlation :math:`r[j] = \sum_k \sum_t g_k[t]\, x_k[t + j]`, so
:math:`\hat r = \sum_k \hat x_k \odot \overline{\hat g_k}` with unnormalised DFTs (numpy's), and
by Parseval

.. math::
    E = \frac{1}{2T} \Bigl\| \hat y - \sum_k \hat x_k \odot \overline{\hat g_k} \Bigr\|^2
        + \frac{\lambda}{2} \|h\|^2 \quad \text{s.t.} \quad \hat g = \mathrm{DFT}(P^\top h),

the paper's eq. 4 (its :math:`\sqrt T F` is numpy's unnormalised ``fft2``). ADMM splits it with
the Lagrange multiplier :math:`\hat\zeta` and the penalty :math:`\mu` (the augmented Lagrangian
:math:`\mathcal L = E + \mathrm{Re}\,\hat\zeta^H(\hat g - \hat h) + \tfrac{\mu}{2}\|\hat g -
\hat h\|^2`, the paper's eq. 5), and iterates (:func:`admm`):

1. **ĝ-subproblem** (eq. 6-10): independent per frequency :math:`\omega`; with
   :math:`\mathbf x = \hat x(\omega) \in \mathbb C^K` it is the :math:`K \times K` system
   :math:`(\mathbf x \mathbf x^H + T\mu I)\,\mathbf g = \mathbf x\,\overline{\hat y} + T\mu\,
   \hat{\mathbf h} - T\hat{\boldsymbol\zeta}`, solved by Sherman–Morrison
   (:func:`g_step`): with :math:`\mathbf q = (\mathbf x \overline{\hat y} - T\hat{\boldsymbol
   \zeta})/(T\mu) + \hat{\mathbf h}`, :math:`\mathbf g = \mathbf q - \mathbf x\,(\mathbf x^H
   \mathbf q) / (T\mu + \mathbf x^H \mathbf x)`.
2. **h-subproblem** (eq. 11): a spatial projection,
   :math:`h = P\,\frac{T}{\lambda + \mu T}\,\mathrm{IDFT}(\mu \hat g + \hat\zeta)`
   (:func:`h_step`): the least-squares minimiser, then zero outside the support.
3. **Lagrangian** (eq. 12): :math:`\hat\zeta \leftarrow \hat\zeta + \mu(\hat g - \hat h)`.
4. **Penalty** (eq. 13): :math:`\mu \leftarrow \min(\beta\mu, \mu_{\max})`.

Everything runs on the half spectrum of real signals (``rfft2``): the features, labels and
filter are real, so the other half is the conjugate and carries nothing new. The
Sherman–Morrison step is one batch of numpy operations over every frequency and channel. The
transforms are ``scipy.fft``'s, which keep single precision and are several times faster
than ``numpy.fft`` on stacks of small images.

Conventions (checked by the tests against dense solvers on the explicit data matrix): the
labels' peak is at index (0, 0); a window whose target sits where the support is centred
responds with its peak at index (0, 0), and a target moved by ``d`` puts it at ``d`` (wrapped).
"""

from __future__ import annotations

import numpy as np
import scipy.fft as sfft


def support_mask(shape: tuple[int, int], support: tuple[int, int]) -> np.ndarray:
    """The cropping operator :math:`P` as a boolean (M, N) image: True on the filter's support.

    The support is ``support = (rows, cols)`` cells placed as the authors' code places it
    (``get_subwindow_no_window(h, floor(use_sz/2), small_filter_sz)``): rows
    ``floor(M/2) - floor(rows/2)`` to that plus ``rows - 1`` (0-based), likewise columns, so an
    even support is centred on the window's centre.
    """
    M, N = (int(v) for v in shape)
    r, c = (int(v) for v in support)
    if not (1 <= r <= M and 1 <= c <= N):
        raise ValueError(f"support {support} must fit in the window {shape} and be >= 1.")
    mask = np.zeros((M, N), dtype=bool)
    r0, c0 = M // 2 - r // 2, N // 2 - c // 2
    mask[r0:r0 + r, c0:c0 + c] = True
    return mask


def g_step(xf: np.ndarray, yf: np.ndarray, hf: np.ndarray, lf: np.ndarray, mu: float,
           T: int, sxx: np.ndarray | None = None) -> np.ndarray:
    r"""The ĝ-subproblem solved per frequency by Sherman–Morrison (the paper's eq. 10).

    At every frequency, the :math:`K`-vector :math:`\mathbf g` solving
    :math:`(\mathbf x \mathbf x^H + T\mu I)\,\mathbf g = \mathbf x\,\overline{\hat y} + T\mu\,
    \mathbf h - T\mathbf l` (the rank-one system is inverted in closed form: no :math:`K \times K`
    solve).

    Parameters
    ----------
    xf : (K, M, F) spectra of the training features :math:`\hat x_k`.
    yf : (M, F) spectrum of the labels :math:`\hat y`.
    hf, lf : (K, M, F) spectra of the filter :math:`\hat h` and of the multiplier
        :math:`\hat\zeta`.
    mu : the penalty :math:`\mu`.
    T : the number of cells of the window (the :math:`T` of the Parseval factor).
    sxx : (M, F) :math:`\mathbf x^H \mathbf x` per frequency, if already computed.

    Returns
    -------
    (K, M, F) complex array :math:`\hat g`.
    """
    if sxx is None:
        sxx = np.sum(xf.real * xf.real + xf.imag * xf.imag, axis=-3)
    tmu = T * mu
    q = xf * (np.conj(yf) / tmu) - lf / mu + hf
    xq = np.sum(np.conj(xf) * q, axis=-3)
    return q - xf * (xq / (tmu + sxx))


def h_step(gf: np.ndarray, lf: np.ndarray, mu: float, lam: float, mask: np.ndarray,
           shape: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    r"""The h-subproblem (the paper's eq. 11): the projection of the least-squares minimiser.

    :math:`h = P\,\frac{T}{\lambda + \mu T}\,\mathrm{IDFT}(\mu \hat g + \hat\zeta)`: the
    minimiser of :math:`\frac{\lambda}{2}\|h\|^2 + \mathrm{Re}\,\hat\zeta^H(\hat g - \hat h) +
    \frac{\mu}{2}\|\hat g - \hat h\|^2` is separable per cell, so restricting it to the support
    is setting the other cells to zero.

    Returns
    -------
    (h, hf): the spatial filter (K, M, N), zero off ``mask``, and its half spectrum.
    """
    T = shape[0] * shape[1]
    h = sfft.irfft2(mu * gf + lf, s=shape) * (T / (lam + mu * T))
    h = h * mask
    return h, sfft.rfft2(h)


def admm(xf: np.ndarray, yf: np.ndarray, mask: np.ndarray, lam: float, *, iterations: int = 2,
         mu: float = 1.0, beta: float = 10.0, mu_max: float = 1e4, shape=None):
    r"""Train the background-aware filter by ADMM from zero (the paper's section 4, eq. 6-13).

    Parameters
    ----------
    xf : (K, M, F) half spectra (``rfft2``) of the training features.
    yf : (M, F) half spectrum of the labels.
    mask : (M, N) boolean support of the filter (:func:`support_mask`; all True is the
        unconstrained multi-channel filter).
    lam : :math:`\lambda`, the ridge weight on :math:`\|h\|^2`.
    iterations : ADMM iterations.
    mu, beta, mu_max : the initial penalty :math:`\mu^{(0)}`, its growth :math:`\beta` and its
        cap: :math:`\mu^{(i+1)} = \min(\beta\mu^{(i)}, \mu_{\max})`.
    shape : (M, N), the spatial shape (default ``mask.shape``).

    Returns
    -------
    (gf, hf, h): :math:`\hat g` (the last ĝ-subproblem's solution, which the authors' code
    detects with), :math:`\hat h` and the spatial filter :math:`h` (zero off the support).
    """
    shape = tuple(mask.shape) if shape is None else tuple(shape)
    T = shape[0] * shape[1]
    sxx = np.sum(xf.real * xf.real + xf.imag * xf.imag, axis=-3)
    gf = np.zeros_like(xf)
    hf = np.zeros_like(xf)
    lf = np.zeros_like(xf)
    h = np.zeros(xf.shape[:-2] + shape, dtype=xf.real.dtype)
    for _ in range(int(iterations)):
        gf = g_step(xf, yf, hf, lf, mu, T, sxx)
        h, hf = h_step(gf, lf, mu, lam, mask, shape)
        lf = lf + mu * (gf - hf)
        mu = min(beta * mu, mu_max)
    return gf, hf, h


def unconstrained_filter(xf: np.ndarray, yf: np.ndarray, lam: float) -> np.ndarray:
    r"""The multi-channel correlation filter without the crop (:math:`P = I`), in closed form.

    Per frequency, :math:`(\mathbf x \mathbf x^H + \lambda I)\,\mathbf g = \mathbf x\,
    \overline{\hat y}`, so by Sherman–Morrison :math:`\hat g_k = \hat x_k\,\overline{\hat y} /
    (\sum_j |\hat x_j|^2 + \lambda)` (Kiani Galoogahi, Sim & Lucey's multi-channel filter with
    one training image): the ridge regression over all cyclic shifts of the whole window.
    """
    sxx = np.sum(xf.real * xf.real + xf.imag * xf.imag, axis=-3)
    return xf * (np.conj(yf) / (sxx + lam))


def response(gf: np.ndarray, zf: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    r"""Response :math:`r = \mathrm{IDFT}(\sum_k \hat z_k \odot \overline{\hat g_k})` on one or a
    stack of windows ``zf`` (…, K, M, F): the filter correlated with every cyclic shift."""
    return sfft.irfft2(np.sum(zf * np.conj(gf), axis=-3), s=shape)


def correlate_full(h: np.ndarray, mask: np.ndarray, features: np.ndarray) -> np.ndarray:
    r"""The support-limited filter correlated with a whole feature image, without wrap-around.

    ``r[i, j] = Σ_k Σ_{(a, b) in support} h_k[a, b] · features_k[i + a - a_c, j + b - b_c]``
    with (a_c, b_c) the window centre ``(M // 2, N // 2)``, zero outside the image: the
    filter's score for the target centred on cell (i, j) of the image. Used to search a whole
    frame (re-detection) in one FFT instead of one window per position.

    Parameters
    ----------
    h : (K, M, N) spatial filter, zero off ``mask``.
    mask : (M, N) its support.
    features : (K, R, C) feature image.

    Returns
    -------
    (R, C) array.
    """
    rows = np.flatnonzero(mask.any(axis=1))
    cols = np.flatnonzero(mask.any(axis=0))
    M, N = mask.shape
    k = h[:, rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]
    dr, dc = rows[0] - M // 2, cols[0] - N // 2          # offset of the kernel's first cell
    K, R, C = features.shape
    kr, kc = k.shape[-2:]
    # linear (not circular) correlation: pad to R + kr - 1, C + kc - 1
    PR, PC = R + kr, C + kc
    F = sfft.rfft2(features, s=(PR, PC))
    H = sfft.rfft2(k, s=(PR, PC))
    full = sfft.irfft2(np.sum(F * np.conj(H), axis=0), s=(PR, PC))
    # full[t] = Σ_s features[s + t] k[s] (t may be negative, wrapped); we want t = i + dr.
    ii = (np.arange(R) + dr) % PR
    jj = (np.arange(C) + dc) % PC
    return full[np.ix_(ii, jj)]


__all__ = ["admm", "correlate_full", "g_step", "h_step", "response", "support_mask",
           "unconstrained_filter"]
