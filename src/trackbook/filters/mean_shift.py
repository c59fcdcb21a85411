"""Kernel mean-shift on an ellipse target (Comaniciu, Ramesh & Meer 2003; §3.3 of Cho & Kang 2005).

Chapter 07 of the book. The target is an ellipse with centre ``y`` and half-axes ``(Hx, Hy)``.
Its colour distribution counts the colours of the pixels inside the ellipse, each weighted by
the Epanechnikov profile ``k(r) = 1 - r^2`` of its ellipse-normalised radius
``r^2 = ((x - y_x) / Hx)^2 + ((y - y_y) / Hy)^2`` (eq. 2-3 of Cho & Kang 2005).

Mean-shift climbs the Bhattacharyya coefficient ``rho(y) = sum_u sqrt(p_u(y) q_u)`` from a
start ``y0``: every pixel gets the weight ``w_i = sqrt(q_u / p_u(y0))`` of its bin ``u``, and
because the Epanechnikov profile has a constant derivative (``g = -k' = 1``), the new centre is
just the weighted mean of the pixel positions inside the ellipse.

Everything here is batched over N ellipses ("candidates") at once: the bin-index image of the
region that holds them is computed once (:func:`bin_image`), and each iteration gathers the
labels under all N ellipses with one fancy-indexing call. Large targets are handled on a
sub-sampled pixel lattice (``stride`` > 1) so that the cost does not grow with the target's size.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from ..features.color import HSV_BINS, bhattacharyya_coefficient, hsv_bin_index, weighted_histograms


@dataclasses.dataclass
class BinImage:
    """The HSV bin index of every lattice pixel of a region of a frame.

    Lattice pixel ``[i, j]`` is image pixel ``(x0 + j*stride, y0 + i*stride)``; its centre, in
    the continuous image coordinates boxes use, is ``origin + stride * (j, i)``.

    Attributes
    ----------
    labels : (h, w) int array of bin indices u
    origin : (2,) float, image coordinates ``(x, y)`` of the centre of lattice pixel [0, 0]
    stride : int, image pixels between lattice pixels
    n_bins : int, m, the number of histogram bins
    """

    labels: np.ndarray
    origin: np.ndarray
    stride: int
    n_bins: int
    _padded: dict = dataclasses.field(default_factory=dict, repr=False)

    def padded(self, pad: int) -> np.ndarray:
        """``labels`` framed by ``pad`` pixels of the sentinel label m (= "not in the frame")."""
        if pad not in self._padded:
            self._padded[pad] = np.pad(self.labels, pad, constant_values=self.n_bins)
        return self._padded[pad]


def bin_image(frame: np.ndarray, region, stride: int = 1, bins=HSV_BINS) -> BinImage:
    """Bin-index image ``h(x_i)`` of ``region = (x0, y0, x1, y1)`` of a BGR frame, every
    ``stride``-th pixel (the ``delta[h(x_i) - u]`` of eq. 3). The region is clipped to the frame;
    an empty region gives a 1x1 lattice far away that no ellipse can reach.
    """
    H, W = frame.shape[:2]
    stride = max(1, int(stride))
    x0, y0, x1, y1 = (int(np.floor(v)) for v in region)
    x0, y0 = max(x0, 0), max(y0, 0)
    x1, y1 = min(x1, W), min(y1, H)
    if x1 <= x0 or y1 <= y0:
        return BinImage(np.zeros((1, 1), dtype=np.int64), np.array([-1e9, -1e9]), stride,
                        int(np.prod(bins)))
    labels = hsv_bin_index(frame[y0:y1:stride, x0:x1:stride], bins)
    return BinImage(labels, np.array([x0 + 0.5, y0 + 0.5]), stride, int(np.prod(bins)))


@dataclasses.dataclass
class EllipseSamples:
    """The lattice pixels around N ellipses (one fixed-size window per ellipse, flattened).

    Attributes
    ----------
    x, y : (N, P) image coordinates of the pixel centres x_i
    labels : (N, P) bin index h(x_i) (0 where the pixel is outside the frame)
    k : (N, P) kernel weight k(r_i) = 1 - r_i^2 inside the ellipse and the frame, else 0 (eq. 2)
    inside : (N, P) bool, r_i < 1 and the pixel lies in the lattice
    """

    x: np.ndarray
    y: np.ndarray
    labels: np.ndarray
    k: np.ndarray
    inside: np.ndarray


def window_radius(img: BinImage, axes) -> np.ndarray:
    """Half-size ``(rx, ry)`` in lattice pixels of a window that holds every ellipse of ``axes``."""
    axes = np.atleast_2d(np.asarray(axes, dtype=float))
    return np.ceil(axes.max(axis=0) / img.stride).astype(int) + 1


@functools.lru_cache(maxsize=64)
def _offsets(rx: int, ry: int):
    di, dj = np.divmod(np.arange((2 * ry + 1) * (2 * rx + 1)), 2 * rx + 1)
    return di - ry, dj - rx


def ellipse_samples(img: BinImage, centres, axes, radius=None) -> EllipseSamples:
    """Gather the lattice pixels of N ellipses ``centres (N, 2)``, ``axes (N, 2) = (Hx, Hy)``.

    The window is the same for all N (``radius``, default sized by the largest half-axes), so
    the N ellipses are gathered with one ``take`` from the label image framed by a sentinel;
    pixels outside an ellipse or outside the frame get k = 0.
    """
    centres = np.atleast_2d(np.asarray(centres, dtype=float))
    axes = np.atleast_2d(np.asarray(axes, dtype=float))
    s = img.stride
    rx, ry = window_radius(img, axes) if radius is None else radius
    pad = int(max(rx, ry))
    lab = img.padded(pad)
    hp, wp = lab.shape
    di, dj = _offsets(int(rx), int(ry))
    base = np.rint((centres - img.origin) / s).astype(int)           # nearest lattice pixel
    # far-away ellipses look at the sentinel frame: their pixels are "outside the frame"
    bj = np.minimum(np.maximum(base[:, 0], rx - pad), wp - pad - rx - 1)
    bi = np.minimum(np.maximum(base[:, 1], ry - pad), hp - pad - ry - 1)
    labels = lab.ravel()[((bi + pad) * wp + bj + pad)[:, None] + (di * wp + dj)[None, :]]
    x = img.origin[0] + (bj[:, None] + dj[None, :]) * s
    y = img.origin[1] + (bi[:, None] + di[None, :]) * s
    r2 = ((x - centres[:, :1]) / axes[:, :1]) ** 2 + ((y - centres[:, 1:]) / axes[:, 1:]) ** 2
    inside = (r2 < 1.0) & (labels < img.n_bins)
    k = np.where(inside, 1.0 - r2, 0.0)
    labels = np.where(inside, labels, 0)
    return EllipseSamples(x, y, labels, k, inside)


def ellipse_histograms(samples: EllipseSamples, n_bins: int) -> np.ndarray:
    """Colour distributions p_y of eq. 3 of Cho & Kang 2005 (eq. 2 of Comaniciu et al. 2003).

    ``p_u = f * sum_i k(r_i) delta[h(x_i) - u]``, f making the bins sum to 1. An ellipse with no
    pixel in the frame gets the all-zero histogram (rho = 0 against any model), not a uniform one.
    """
    hist = weighted_histograms(samples.labels[:, None, :], samples.k[:, None, :], n_bins)
    empty = samples.k.sum(axis=1) <= 0
    hist[empty] = 0.0
    return hist


def ellipse_rho(img: BinImage, q, centres, axes, radius=None):
    """``(rho, p, samples)``: the Bhattacharyya coefficient rho[p(y), q] of N ellipses, their
    colour distributions (eq. 3) and the gathered pixels."""
    samples = ellipse_samples(img, centres, axes, radius)
    p = ellipse_histograms(samples, img.n_bins)
    return bhattacharyya_coefficient(p, q), p, samples


def mean_shift_weights(samples: EllipseSamples, p0, q) -> np.ndarray:
    """Step ② (eq. 11 of Cho & Kang 2005): w_i = sqrt(q_u / p_u(y0)) for u = h(x_i), 0 outside.

    ``p0`` is (N, m), ``q`` is (m,). A bin that no pixel of the ellipse falls in has p_u = 0 but
    then no pixel needs its weight, so the division is guarded rather than regularised.
    """
    n, m = p0.shape
    pu = p0.ravel()[samples.labels + (np.arange(n) * m)[:, None]]
    qu = np.asarray(q)[samples.labels]
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(samples.inside & (pu > 0), np.sqrt(qu / np.where(pu > 0, pu, 1.0)), 0.0)
    return w


def mean_shift_step(samples: EllipseSamples, w, centres) -> np.ndarray:
    """Step ③ (eq. 12 of Cho & Kang 2005): the new centre y1 = sum x_i w_i g / sum w_i g.

    With the Epanechnikov profile g = -k' is constant on the ellipse, so y1 is the plain
    weighted mean of the pixel positions inside it. An ellipse with zero total weight stays put.
    """
    total = w.sum(axis=1)
    mx = (w * samples.x).sum(axis=1)
    my = (w * samples.y).sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        y1 = np.stack([mx / total, my / total], axis=1)
    return np.where((total > 0)[:, None], y1, centres)


@dataclasses.dataclass
class MeanShiftResult:
    """What :func:`mean_shift` found for N starts.

    Attributes
    ----------
    centres : (N, 2) the converged centres
    rho : (N,) rho[p(y), q] at the converged centres
    rho_start : (N,) rho at the starts (eq. 13 says rho >= rho_start)
    iterations : (N,) mean-shift iterations each start used
    trajectory : (T, N, 2) the centres after every iteration, the starts first (for drawings)
    rho_trajectory : (T, N) rho along the trajectory
    hist : (N, m) colour distributions at the converged centres
    """

    centres: np.ndarray
    rho: np.ndarray
    rho_start: np.ndarray
    iterations: np.ndarray
    trajectory: np.ndarray
    rho_trajectory: np.ndarray
    hist: np.ndarray


def mean_shift(img: BinImage, q, centres, axes, max_iter: int = 20, eps: float = 0.5,
               max_halvings: int = 3) -> MeanShiftResult:
    """Comaniciu et al.'s mean-shift tracker, steps ①-⑥ of §3.3 of Cho & Kang 2005, for N starts.

    ① p(y0), rho0 at the start; ② weights w_i = sqrt(q_u / p_u(y0)); ③ y1 = weighted mean of
    the pixel positions (Epanechnikov profile: g constant); ④ p(y1), rho1; ⑤ while
    rho1 < rho0, y1 <- (y0 + y1) / 2 (at most ``max_halvings`` times; if rho still decreased,
    the step is refused and the start stays put, so an accepted step never lowers rho);
    ⑥ stop when ||y1 - y0|| < eps (image pixels) or after ``max_iter`` iterations.

    Parameters
    ----------
    img : the bin-index image of the region holding the ellipses (:func:`bin_image`)
    q : (m,) target model
    centres : (N, 2) starts y0 (image coordinates); axes : (N, 2) half-axes (Hx, Hy), fixed
    """
    q = np.asarray(q, dtype=float)
    y0 = np.array(np.atleast_2d(centres), dtype=float)
    axes = np.atleast_2d(np.asarray(axes, dtype=float))
    if axes.shape[0] == 1 and y0.shape[0] > 1:
        axes = np.repeat(axes, y0.shape[0], axis=0)
    n = y0.shape[0]
    radius = window_radius(img, axes)
    rho0, p0, s0 = ellipse_rho(img, q, y0, axes, radius)
    X, Y, L, K, IN = s0.x, s0.y, s0.labels, s0.k, s0.inside     # pixels at the current y0
    rho_start = rho0.copy()
    iterations = np.zeros(n, dtype=int)
    active = np.ones(n, dtype=bool)
    traj, rtraj = [y0.copy()], [rho0.copy()]
    for _ in range(int(max_iter)):
        a = np.flatnonzero(active)
        if a.size == 0:
            break
        sa = EllipseSamples(X, Y, L, K, IN) if a.size == n else \
            EllipseSamples(X[a], Y[a], L[a], K[a], IN[a])
        w = mean_shift_weights(sa, p0[a], q)                       # ②
        y1 = mean_shift_step(sa, w, y0[a])                         # ③
        rho1, p1, s1 = ellipse_rho(img, q, y1, axes[a], radius)    # ④
        for _h in range(int(max_halvings)):                        # ⑤ only where rho went down
            bad = np.flatnonzero(rho1 < rho0[a])
            if bad.size == 0:
                break
            y1[bad] = 0.5 * (y0[a[bad]] + y1[bad])
            rho1[bad], p1[bad], sb = ellipse_rho(img, q, y1[bad], axes[a[bad]], radius)
            for f in ("x", "y", "labels", "k", "inside"):
                getattr(s1, f)[bad] = getattr(sb, f)
        ok = rho1 >= rho0[a]          # a step that still lowers rho is refused: stay at y0
        acc = a[ok]
        step = np.linalg.norm(y1 - y0[a], axis=1)
        iterations[a] += 1
        y0[acc], rho0[acc], p0[acc] = y1[ok], rho1[ok], p1[ok]
        X[acc], Y[acc], L[acc], K[acc], IN[acc] = s1.x[ok], s1.y[ok], s1.labels[ok], s1.k[ok], \
            s1.inside[ok]
        active[a[(step < eps) | ~ok]] = False                      # ⑥
        traj.append(y0.copy())
        rtraj.append(rho0.copy())
    return MeanShiftResult(y0, rho0, rho_start, iterations, np.array(traj), np.array(rtraj), p0)


def mean_shift_with_scale(img: BinImage, q, centre, axes, factors=(0.9, 1.0, 1.1),
                          gamma: float = 0.1, max_iter: int = 20, eps: float = 0.5):
    """Comaniciu et al. 2003 §5.2 scale adaptation: run mean-shift with the half-axes scaled by
    each of ``factors`` (±10 %), keep the run with the best rho, and move the half-axes a
    fraction ``gamma`` of the way to its size (h_new = gamma h_opt + (1 - gamma) h_prev).

    Returns ``(result_of_best_run, new_axes)``; ``result`` is a :class:`MeanShiftResult` with N = 1.
    """
    axes = np.asarray(axes, dtype=float).reshape(2)
    f = np.asarray(factors, dtype=float)
    trial_axes = f[:, None] * axes[None, :]
    starts = np.repeat(np.asarray(centre, dtype=float).reshape(1, 2), len(f), axis=0)
    res = mean_shift(img, q, starts, trial_axes, max_iter=max_iter, eps=eps)
    best = int(np.argmax(res.rho))
    new_axes = gamma * trial_axes[best] + (1.0 - gamma) * axes
    pick = slice(best, best + 1)
    one = MeanShiftResult(res.centres[pick], res.rho[pick], res.rho_start[pick],
                          res.iterations[pick], res.trajectory[:, pick], res.rho_trajectory[:, pick],
                          res.hist[pick])
    return one, new_axes


def region_around(centres, axes, margin: float = 1.0):
    """``(x0, y0, x1, y1)`` covering every ellipse plus ``margin`` half-axes on each side."""
    centres = np.atleast_2d(centres)
    axes = np.atleast_2d(axes)
    ext = axes * (1.0 + margin)
    lo = (centres - ext).min(axis=0)
    hi = (centres + ext).max(axis=0)
    return (np.floor(lo[0]), np.floor(lo[1]), np.ceil(hi[0]) + 1, np.ceil(hi[1]) + 1)
