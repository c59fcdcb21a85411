"""Background subtraction by a mixture of Gaussians per pixel (Stauffer & Grimson 1999), with
the adaptive number of components of Zivkovic 2004 (OpenCV's MOG2).

Every pixel keeps up to ``K`` Gaussian components (weight ``w_k``, mean ``μ_k`` of the pixel's
channels, one variance ``σ_k²`` shared by the channels), sorted by weight. For a new value
``x``, with learning rate ``α`` (Zivkovic 2004):

- every weight decays, ``w_k ← (1 − α) w_k − α c_T`` (``c_T``, the complexity reduction prior,
  makes a component that stops being seen fall to zero and be dropped: fewer components where
  the scene needs fewer);
- the first component (by weight) with squared distance ``d² = ||x − μ_k||²`` below
  ``T_g σ_k²`` owns ``x``: ``w_k ← w_k + α``, ``μ_k ← μ_k + (α / w_k)(x − μ_k)``,
  ``σ_k² ← σ_k² + (α / w_k)(d² − σ_k²)`` (clamped to ``[σ_min², σ_max²]``);
- the weights are renormalised to sum to 1;
- no owner: the others are scaled by ``1 − α`` and a new component ``(w = α, μ = x, σ² = σ_0²)``
  is added, over the lightest when all ``K`` are in use.

The **background** is the heaviest components whose weights before them sum to less than
``background_ratio`` (``B = argmin_b Σ_{k ≤ b} w_k > 1 − c_f``, Stauffer & Grimson's rule), with
the weights as decayed in the first step: the pixel is background when ``x`` is within
``T_b σ_k²`` (``var_threshold``) of one of them. As in OpenCV, the test is made while looking
for the owner, on the components up to it (the same rule when ``T_b ≥ T_g``).

All of it runs on arrays of shape H x W x K, never a loop per pixel. The order of operations
is that of OpenCV's ``BackgroundSubtractorMOG2`` (``bgfg_gaussmix2.cpp``), so with the same
parameters the masks agree with ``cv2.createBackgroundSubtractorMOG2(detectShadows=False)``
except where float32 rounding puts a distance on the other side of a threshold, a tie in
weights orders two components differently, or OpenCV prunes a component that is not the last
(it drops the last slot; this class drops the pruned one). ``tests/test_background.py``
measures the agreement.
"""

from __future__ import annotations

import cv2
import numpy as np


class MixtureOfGaussians:
    """Per-pixel mixture-of-Gaussians background model; ``apply(frame)`` gives the foreground.

    Parameters
    ----------
    learning_rate : float or None
        α. None follows OpenCV's default: ``1 / min(2 n, history)`` at the n-th frame (fast at
        first, then ``1 / history``).
    history : int
        Frames of memory when ``learning_rate`` is None.
    var_threshold : float
        T_b: squared Mahalanobis distance under which a value matches a background component.
    background_ratio : float
        1 − c_f: the heaviest components up to this total weight are the background.
    n_components : int
        K, components per pixel at most.
    var_threshold_gen : float
        T_g: squared distance under which a value is owned by an existing component.
    var_init, var_min, var_max : float
        σ_0² of a new component and the clamp of every variance.
    complexity_reduction : float
        c_T of Zivkovic 2004 (0 gives Stauffer & Grimson's fixed number of components).
    """

    def __init__(self, learning_rate: float | None = None, history: int = 500,
                 var_threshold: float = 16.0, background_ratio: float = 0.9,
                 n_components: int = 5, var_threshold_gen: float = 9.0, var_init: float = 15.0,
                 var_min: float = 4.0, var_max: float = 75.0,
                 complexity_reduction: float = 0.05):
        if learning_rate is not None and not 0.0 <= learning_rate <= 1.0:
            raise ValueError(f"learning_rate = {learning_rate!r}; pass a rate in 0..1 (or None "
                             "for 1 / min(2 n, history)).")
        for name, v in (("history", history), ("n_components", n_components)):
            if int(v) != v or v < 1:
                raise ValueError(f"{name} = {v!r}; pass a whole number >= 1.")
        if not 0.0 < background_ratio <= 1.0:
            raise ValueError(f"background_ratio = {background_ratio!r}; pass a value in (0, 1].")
        if not 0.0 < var_min <= var_init <= var_max:
            raise ValueError(f"need 0 < var_min <= var_init <= var_max, got {var_min}, "
                             f"{var_init}, {var_max}.")
        self.learning_rate, self.history = learning_rate, int(history)
        self.var_threshold, self.background_ratio = float(var_threshold), float(background_ratio)
        self.n_components, self.var_threshold_gen = int(n_components), float(var_threshold_gen)
        self.var_init, self.var_min, self.var_max = float(var_init), float(var_min), float(var_max)
        self.complexity_reduction = float(complexity_reduction)
        self.reset()

    def reset(self) -> None:
        """Forget the model: the next frame starts it again."""
        self.weights = self.means = self.variances = self.n_used = None
        self.n_frames = 0

    def _rate(self) -> float:
        if self.learning_rate is not None and self.n_frames > 1:
            return self.learning_rate
        return 1.0 / min(2 * self.n_frames, self.history)

    def apply(self, frame) -> np.ndarray:
        """Update the model with ``frame`` (H x W or H x W x C) and return its foreground mask.

        Returns
        -------
        (H, W) uint8 array: 255 where the pixel is foreground, 0 where it is background.
        """
        x = np.asarray(frame)
        if x.ndim == 2:
            x = x[..., None]
        if x.ndim != 3 or x.size == 0:
            raise ValueError(f"apply: frame has shape {np.shape(frame)}; pass an H x W or "
                             "H x W x C image.")
        x = x.astype(np.float32)
        H, W, C = x.shape
        K = self.n_components
        if self.weights is None:
            self.weights = np.zeros((H, W, K), np.float32)
            self.means = np.zeros((H, W, K, C), np.float32)
            self.variances = np.zeros((H, W, K), np.float32)
            self.n_used = np.zeros((H, W), np.int64)
        elif self.means.shape[:2] != (H, W) or self.means.shape[3] != C:
            raise ValueError(f"apply: frame has shape {x.shape} but the model was built on "
                             f"{self.means.shape[:2] + self.means.shape[3:]}; call reset() for "
                             "a new scene.")
        self.n_frames += 1
        return self._step(x, np.float32(self._rate()))

    def _step(self, x, alpha):
        K = self.n_components
        w, mu, var = self.weights, self.means, self.variances
        prune = np.float32(-alpha * self.complexity_reduction)
        alpha1 = np.float32(1.0) - alpha
        used = np.arange(K) < self.n_used[..., None]                         # H x W x K

        diff = mu - x[:, :, None, :]                                         # H x W x K x C
        sq = diff * diff
        d2 = sq[..., 0]                     # summed channel by channel, as OpenCV does (and
        for c in range(1, sq.shape[-1]):    # faster than a reduction over so short an axis)
            d2 = d2 + sq[..., c]                                             # H x W x K
        fits = used & (d2 < self.var_threshold_gen * var)
        owner = np.argmax(fits, axis=-1)                                     # first that fits
        any_fit = fits.any(axis=-1)
        first = np.zeros_like(fits)
        np.put_along_axis(first, owner[..., None], any_fit[..., None], axis=-1)
        # components up to the owner (all in use when none owns x) are checked
        checked = used & (np.arange(K) <= np.where(any_fit, owner, K)[..., None])

        w_new = np.where(used, alpha1 * w + prune, 0.0).astype(np.float32)
        dropped = used & ~first & (w_new < -prune)
        w_new[dropped] = 0.0
        # background: a checked component, the weights before it summing under the ratio
        before = np.cumsum(w_new, axis=-1) - w_new
        background = np.any(checked & (before < self.background_ratio)
                            & (d2 < self.var_threshold * var), axis=-1)

        # the owner learns x
        w_new = np.where(first, w_new + alpha, w_new)
        k = np.where(first, alpha / np.where(first, w_new, 1.0), 0.0).astype(np.float32)
        mu -= k[..., None] * diff
        var[...] = np.where(first, np.clip(var + k * (d2 - var), self.var_min, self.var_max),
                            var)
        used &= ~dropped
        n_used = used.sum(axis=-1)

        total = w_new.sum(axis=-1, keepdims=True)
        w_new = np.where(total > 0, w_new / np.where(total > 0, total, 1.0), 0.0)

        # no owner: a new component, in a free slot or over the lightest (the last, as the
        # components are kept sorted by weight)
        new = ~any_fit & (alpha > 0)
        slot = np.where(n_used == K, K - 1, np.argmin(used, axis=-1))
        onehot = new[..., None] & (np.arange(K) == slot[..., None])
        used |= onehot
        n_used = n_used + (new & (n_used < K))        # a new component fills a free slot
        alone = (n_used == 1)[..., None]
        w_new = np.where(new[..., None] & ~onehot, w_new * alpha1, w_new)
        w_new = np.where(onehot, np.where(alone, 1.0, alpha), w_new)
        mu[onehot] = np.broadcast_to(x[:, :, None, :], mu.shape)[onehot]
        var[onehot] = self.var_init

        # keep the components sorted by weight (free slots last)
        order = np.argsort(np.where(used, -w_new, np.inf), axis=-1, kind="stable")
        # most pixels are still in order: rearrange only the others (the gather is the
        # costliest step of the update on a whole frame)
        w_new = w_new.astype(np.float32).reshape(-1, K)
        mu, var = mu.reshape(-1, K, mu.shape[-1]), var.reshape(-1, K)
        order = order.reshape(-1, K)
        moved = np.flatnonzero((order != np.arange(K)).any(axis=-1))
        if moved.size:
            o = order[moved]
            w_new[moved] = np.take_along_axis(w_new[moved], o, -1)
            mu[moved] = np.take_along_axis(mu[moved], o[..., None], -2)
            var[moved] = np.take_along_axis(var[moved], o, -1)
        self.weights = w_new.reshape(used.shape)
        self.means = mu.reshape(used.shape + mu.shape[-1:])
        self.variances = var.reshape(used.shape)
        self.n_used = n_used
        return np.where(background, 0, 255).astype(np.uint8)


def detections(mask, min_area: int = 20) -> np.ndarray:
    """Boxes of the foreground's connected components (8-connected) of at least ``min_area``
    pixels, as ``(n, 4)`` rows ``(x, y, w, h)``, for :class:`trackbook.mot.Sort`."""
    m = np.asarray(mask)
    if m.ndim != 2:
        raise ValueError(f"detections: mask has shape {m.shape}; pass an H x W mask.")
    n, _, stats, _ = cv2.connectedComponentsWithStats((m > 0).astype(np.uint8), connectivity=8)
    keep = stats[1:, cv2.CC_STAT_AREA] >= min_area
    return stats[1:, :4][keep].astype(float).reshape(-1, 4)


__all__ = ["MixtureOfGaussians", "detections"]
