"""Kernel mean-shift on an ellipse target (Comaniciu, Ramesh & Meer 2003; §3.3 of Cho & Kang 2005).

Chapter ``08_mean_shift`` of the book. The target is an ellipse with centre ``y`` and half-axes ``(Hx, Hy)``.
Its colour distribution counts the colours of the pixels inside the ellipse, each weighted by
the Epanechnikov profile ``k(r) = 1 - r^2`` of its ellipse-normalised radius
``r^2 = ((x - y_x) / Hx)^2 + ((y - y_y) / Hy)^2`` (eq. 2-3 of Cho & Kang 2005).

Mean-shift climbs the Bhattacharyya coefficient ``rho(y) = sum_u sqrt(p_u(y) q_u)`` from a
start ``y0``: every pixel gets the weight ``w_i = sqrt(q_u / p_u(y0))`` of its bin ``u``, and
because the Epanechnikov profile has a constant derivative (``g = -k' = 1``), the new centre is
just the weighted mean of the pixel positions inside the ellipse.

How the sums of eq. 3 are taken, fast
-------------------------------------
``h(x)`` is read from a bin-index image of the region holding all candidates, computed ONCE per
frame (:func:`bin_image`), on a lattice of every ``stride``-th pixel (stride 1 for the paper's
small targets; larger targets are sub-sampled so that their shorter half-axis spans a fixed
number of lattice pixels and the cost does not grow with their size). An ellipse is centred
on the lattice pixel nearest to its centre ``y`` (a pixel grid does the same with stride 1), so
its pixels are FIXED offsets from that centre and their kernel weights ``k(r_i)`` are computed
once per call (:func:`ellipse_window`). Every histogram of every iteration of every
candidate is then one gather and one ``np.bincount``. Because the histogram only depends on
the lattice pixel under ``y``, a mean-shift step that stays on that pixel has reached a fixed
point (step ⑥ stops there too).
"""

from __future__ import annotations

import dataclasses
import functools

import cv2
import numpy as np

from ..features.color import HSV_BINS


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
            h, w = self.labels.shape
            out = np.full((h + 2 * pad, w + 2 * pad), self.n_bins, dtype=self.labels.dtype)
            out[pad:pad + h, pad:pad + w] = self.labels
            self._padded[pad] = out
        return self._padded[pad]


@functools.lru_cache(maxsize=8)
def _bin_luts(bins):
    """Per-channel lookup tables: HSV value -> its share of the bin index ``(h bs + s) bv + v``."""
    bh, bs, bv = bins
    v = np.arange(256)
    lut_h = np.minimum(v * bh // 180, bh - 1) * (bs * bv)
    return lut_h.astype(np.intp), (v * bs // 256 * bv).astype(np.intp), (v * bv // 256).astype(np.intp)


def hsv_bin_image(bgr: np.ndarray, bins=HSV_BINS) -> np.ndarray:
    """The bin index of :func:`trackbook.features.color.hsv_bin_index` for an H x W x 3 image,
    converted to HSV as one 2-D image (OpenCV converts an N x 1 column, as that function
    passes it, row by row, which is much slower) and binned by three lookup tables."""
    hsv = cv2.cvtColor(np.ascontiguousarray(bgr), cv2.COLOR_BGR2HSV)
    lut_h, lut_s, lut_v = _bin_luts(tuple(int(b) for b in bins))
    return lut_h.take(hsv[..., 0]) + lut_s.take(hsv[..., 1]) + lut_v.take(hsv[..., 2])


def bin_image(frame: np.ndarray, region, stride: int = 1, bins=HSV_BINS) -> BinImage:
    """Bin-index image ``h(x_i)`` of ``region = (x0, y0, x1, y1)`` of a BGR frame, on the
    lattice of every ``stride``-th pixel of the frame (the ``delta[h(x_i) - u]`` of eq. 3;
    the region is widened to start on that lattice). The region is clipped to the frame;
    an empty region gives a 1x1 lattice far away that no ellipse can reach.
    """
    H, W = frame.shape[:2]
    stride = max(1, int(stride))
    x0, y0, x1, y1 = (int(np.floor(v)) for v in region)
    # the lattice is every stride-th pixel of the FRAME (not of the region), so an ellipse
    # snaps to the same lattice pixel whatever region a tracker happens to bin
    x0, y0 = max(x0, 0) // stride * stride, max(y0, 0) // stride * stride
    x1, y1 = min(x1, W), min(y1, H)
    if x1 <= x0 or y1 <= y0:
        return BinImage(np.zeros((1, 1), dtype=np.intp), np.array([-1e9, -1e9]), stride,
                        int(np.prod(bins)))
    labels = hsv_bin_image(frame[y0:y1:stride, x0:x1:stride], bins)
    return BinImage(labels, np.array([x0 + 0.5, y0 + 0.5]), stride, int(np.prod(bins)))


@dataclasses.dataclass
class EllipseWindow:
    """The lattice pixels of N ellipses as fixed offsets from their centres' lattice pixels.

    Attributes
    ----------
    dxy : (P, 2) image-coordinate offsets ``(dx, dy)`` of the window's lattice pixels
    flat : (P,) the same offsets in the flattened padded label array (:meth:`BinImage.padded`)
    k : (N, P) kernel weight ``k(r_i) = 1 - r_i^2`` of each pixel for each ellipse, 0 outside
        it (eq. 2; ``r_i`` measured from the lattice pixel under the centre)
    inside : (N, P) bool ``k > 0``, or None when every window pixel is inside every ellipse
    pad : int, the sentinel frame of the padded label array
    reach : (2,) int, how far (lattice pixels) a centre may lie outside the region before its
        window is pure sentinel
    dxy1 : (P, 3) ``(dx, dy, 1)``: one matrix product gives step ③'s weighted sums and total
    k_total : (N,) the kernel's sum over each ellipse
    """

    dxy: np.ndarray
    flat: np.ndarray
    k: np.ndarray
    inside: np.ndarray | None
    pad: int
    reach: np.ndarray
    dxy1: np.ndarray
    k_total: np.ndarray


#: How the kernel's radius r of eq. 3 is measured: ``"ellipse"`` r^2 = (dx / Hx)^2 +
#: (dy / Hy)^2 (Comaniciu et al. 2003's normalised ellipse, the book's default); ``"diagonal"``
#: r = ||y - x_i|| / a with a = sqrt(Hx^2 + Hy^2), as eq. 3 and 10 of Cho & Kang 2005 print it
#: [quote: cho2005.bandwidth_eq3].
BANDWIDTHS = ("ellipse", "diagonal")


def kernel_weights(dx, dy, Hx: float, Hy: float, bandwidth: str = "ellipse") -> np.ndarray:
    """k(r) = 1 - r^2 (eq. 2 of Cho & Kang 2005) of pixels at offsets ``(dx, dy)`` from the
    centre of an ellipse with half-axes ``(Hx, Hy)``; 0 outside the ellipse.

    ``bandwidth="ellipse"``: r^2 = (dx / Hx)^2 + (dy / Hy)^2. ``"diagonal"``: eq. 3 and 10 of
    Cho & Kang 2005, k(||y - x_i|| / a) over the I pixels inside the ellipse, with the
    bandwidth a = sqrt(Hx^2 + Hy^2) [quote: cho2005.bandwidth_eq3]. Since a exceeds both
    half-axes, every pixel inside the ellipse then has a positive weight, and the weight falls
    off alike in every direction.
    """
    dx, dy = np.asarray(dx, dtype=float), np.asarray(dy, dtype=float)
    r2_ellipse = (dx / Hx) ** 2 + (dy / Hy) ** 2
    if bandwidth == "ellipse":
        return np.clip(1.0 - r2_ellipse, 0.0, None)
    if bandwidth == "diagonal":
        a2 = Hx * Hx + Hy * Hy                                       # a = sqrt(Hx^2 + Hy^2)
        return np.where(r2_ellipse < 1.0, 1.0 - (dx * dx + dy * dy) / a2, 0.0)
    raise ValueError(f"bandwidth {bandwidth!r} is not one of {', '.join(BANDWIDTHS)}")


@functools.lru_cache(maxsize=32)
def _window_kernel(stride: int, axes: tuple, bandwidth: str = "ellipse"):
    axes = np.array(axes, dtype=float).reshape(-1, 2)
    rx, ry = (np.floor(axes.max(axis=0) / stride).astype(int) + 1)
    dj, di = np.meshgrid(np.arange(-rx, rx + 1), np.arange(-ry, ry + 1))
    dj, di = dj.ravel(), di.ravel()
    k = kernel_weights((dj * stride)[None, :], (di * stride)[None, :], axes[:, :1], axes[:, 1:],
                       bandwidth)
    keep = (k > 0).any(axis=0)
    dj, di, k = dj[keep], di[keep], np.ascontiguousarray(k[:, keep])
    inside = None if (k > 0).all() else k > 0
    dxy1 = np.stack([dj * stride, di * stride, np.ones(dj.size)], axis=1).astype(float)
    k_total = k.sum(axis=1)
    for a in (dj, di, k, inside, dxy1, k_total):
        if a is not None:
            a.flags.writeable = False
    return dj, di, k, inside, int(rx), int(ry), dxy1, k_total


def ellipse_window(img: BinImage, axes, bandwidth: str = "ellipse") -> EllipseWindow:
    """Offsets and kernel weights of the lattice pixels of N ellipses with half-axes ``axes``.

    The window covers the largest ellipse; window pixels outside every ellipse are dropped, so
    for N ellipses of one size the window is exactly the ellipse's pixels. (The kernels are
    cached by size: a tracker whose ellipses keep their size computes them once.)
    ``bandwidth`` is the kernel's radius (:func:`kernel_weights`).
    """
    axes = np.atleast_2d(np.asarray(axes, dtype=float))
    dj, di, k, inside, rx, ry, dxy1, k_total = _window_kernel(int(img.stride),
                                                              tuple(axes.ravel().tolist()),
                                                              bandwidth)
    pad = 2 * max(rx, ry) + 2
    wp = img.labels.shape[1] + 2 * pad
    return EllipseWindow(dxy1[:, :2], di * wp + dj, k, inside, pad, np.array([rx + 1, ry + 1]),
                         dxy1, k_total)


def lattice_pixel(img: BinImage, centres) -> np.ndarray:
    """(N, 2) int ``(j, i)``: the lattice pixel nearest to each centre (may lie outside)."""
    return np.rint((np.atleast_2d(centres) - img.origin) / img.stride).astype(np.intp)


def ellipse_labels(img: BinImage, ji, win: EllipseWindow) -> np.ndarray:
    """``h(x_i)`` of the window pixels of N ellipses centred on lattice pixels ``ji``: (N, P).

    Pixels outside the region (or the frame) read the sentinel m. A centre farther out than
    the window's reach is clamped to where its window is all sentinel.
    """
    h, w = img.labels.shape
    j = np.minimum(np.maximum(ji[:, 0], -win.reach[0]), w - 1 + win.reach[0])
    i = np.minimum(np.maximum(ji[:, 1], -win.reach[1]), h - 1 + win.reach[1])
    base = (i + win.pad) * (w + 2 * win.pad) + (j + win.pad)
    return img.padded(win.pad).ravel().take(base[:, None] + win.flat[None, :])


def _histograms(labels, k, m: int) -> np.ndarray:
    """(N, m + 1) kernel-weighted counts of ``labels`` (column m = the sentinel), one bincount."""
    n = labels.shape[0]
    idx = labels + (np.arange(n) * (m + 1))[:, None]
    return np.bincount(idx.ravel(), weights=k.ravel(), minlength=n * (m + 1)).reshape(n, m + 1)


def _normalise(counts, m: int) -> np.ndarray:
    """Eq. 3's f: the in-frame bins sum to 1; an ellipse wholly outside gets all zeros.
    The sentinel column is set to 1 so that step ② can divide by it (its q is 0)."""
    mass = counts[:, :m].sum(axis=1, keepdims=True)
    p = counts / np.where(mass > 0, mass, 1.0)
    p[:, m] = 1.0
    return p


def ellipse_histograms(labels, k, n_bins: int) -> np.ndarray:
    """Colour distributions p_y of eq. 3 of Cho & Kang 2005 (eq. 2 of Comaniciu et al. 2003).

    ``p_u = f * sum_i k(r_i) delta[h(x_i) - u]``, f making the bins sum to 1, for N ellipses
    whose pixels have the labels ``(N, P)`` (:func:`ellipse_labels`; the sentinel m marks a
    pixel outside the frame and is not counted) and kernel weights ``k (N, P)``. An ellipse
    with no pixel in the frame gets the all-zero histogram (rho = 0 against any model).
    """
    labels = np.atleast_2d(labels)
    k = np.broadcast_to(np.asarray(k, dtype=float), labels.shape)
    return _normalise(_histograms(labels, k, n_bins), n_bins)[:, :n_bins]


def ellipse_rho(img: BinImage, q, centres, axes, bandwidth: str = "ellipse"):
    """``(rho, p, labels)``: the Bhattacharyya coefficient rho[p(y), q] of N ellipses, their
    colour distributions (eq. 3, (N, m)) and their pixels' labels (:func:`ellipse_labels`);
    ``bandwidth`` is the kernel's radius (:func:`kernel_weights`)."""
    c = np.atleast_2d(np.asarray(centres, dtype=float))
    a = np.atleast_2d(np.asarray(axes, dtype=float))
    if a.shape[0] == 1 and c.shape[0] > 1:
        a = np.repeat(a, c.shape[0], axis=0)
    win = ellipse_window(img, a, bandwidth)
    labels = ellipse_labels(img, lattice_pixel(img, c), win)
    p = ellipse_histograms(labels, win.k, img.n_bins)
    return np.sqrt(p * np.asarray(q, dtype=float)).sum(axis=1), p, labels


def mean_shift_weights(labels, p0, q) -> np.ndarray:
    """Step ② (eq. 11 of Cho & Kang 2005): w_i = sqrt(q_u / p_u(y0)) for u = h(x_i).

    ``labels`` (N, P) may hold the sentinel m (pixel outside the frame: weight 0); ``p0`` is
    (N, m) and ``q`` is (m,). A window pixel outside the ellipse (k = 0) may sit in a bin with
    p_u = 0; its weight is 0 (step ③ gives it no say anyway, its g is 0).
    """
    p0 = np.atleast_2d(p0)
    n, m = p0.shape
    pe = np.concatenate([p0, np.ones((n, 1))], axis=1)
    qe = np.append(np.asarray(q, dtype=float), 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        w = _weights(labels, pe, qe)
    return np.where(np.isfinite(w), w, 0.0)


def _weights(labels, p_ext, q_ext) -> np.ndarray:
    n, m1 = p_ext.shape
    pu = p_ext.ravel().take(labels + (np.arange(n) * m1)[:, None])
    return np.sqrt(q_ext.take(labels) / pu)


def mean_shift_step(w, ji, img: BinImage, win: EllipseWindow) -> np.ndarray:
    """Step ③ (eq. 12 of Cho & Kang 2005): the new centre y1 = sum x_i w_i g / sum w_i g.

    With the Epanechnikov profile g = -k' is constant inside the ellipse and 0 outside, so y1
    is the weighted mean of the positions x_i of the pixels inside it, i.e. the centre's
    lattice pixel plus ``(w g) @ dxy / sum w g``. An ellipse with zero total weight (nothing of
    the model's colours) stays on its lattice pixel.
    """
    wg = w if win.inside is None else np.where(win.inside, w, 0.0)
    total = wg.sum(axis=1, keepdims=True)
    shift = (wg @ win.dxy) / np.where(total > 0, total, 1.0)
    return img.origin + ji * img.stride + shift


@dataclasses.dataclass
class MeanShiftResult:
    """What :func:`mean_shift` found for N starts.

    Attributes
    ----------
    centres : (N, 2) the converged centres
    rho : (N,) rho[p(y), q] at the converged centres
    rho_start : (N,) rho at the starts (eq. 13 says rho >= rho_start)
    iterations : (N,) mean-shift iterations each start used
    evaluations : int, batched histogram evaluations (one at the starts, one per iteration,
        one per round of step halving that needed one)
    histograms : int, colour histograms computed (candidates per evaluation, summed): the
        book's count of the cost (the paper measures seconds per frame
        [quote: cho2005.table1_seconds])
    pixels : int, pixels read for them (histograms x pixels per ellipse)
    trajectory : (T, N, 2) the centres after every iteration, the starts first (for drawings)
    rho_trajectory : (T, N) rho along the trajectory
    hist : (N, m) colour distributions at the converged centres
    """

    centres: np.ndarray
    rho: np.ndarray
    rho_start: np.ndarray
    iterations: np.ndarray
    evaluations: int
    histograms: int
    pixels: int
    trajectory: np.ndarray
    rho_trajectory: np.ndarray
    hist: np.ndarray


def mean_shift(img: BinImage, q, centres, axes, max_iter: int = 20, eps: float = 0.5,
               max_halvings: int = 3, bandwidth: str = "ellipse") -> MeanShiftResult:
    """Comaniciu et al.'s mean-shift tracker, steps ①-⑥ of §3.3 of Cho & Kang 2005, for N starts.

    ① p(y0), rho0 at the start; ② weights w_i = sqrt(q_u / p_u(y0)); ③ y1 = weighted mean of
    the pixel positions (Epanechnikov profile: g constant); ④ p(y1), rho1; ⑤ while
    rho1 < rho0, y1 <- (y0 + y1) / 2 (at most ``max_halvings`` times; if rho still decreased,
    the step is refused and the start stays put, so an accepted step never lowers rho);
    ⑥ stop when ||y1 - y0|| < eps (image pixels) or after ``max_iter`` iterations.

    The histogram of an ellipse only depends on the lattice pixel under its centre (module
    docstring), so a step (or a halved step) that lands on the same lattice pixel as y0 has
    p(y1) = p(y0): rho cannot change, and the next step would land on the same point: it is a
    fixed point, and ⑥ stops there without evaluating anything. The N starts move in
    lock-step; the p(y1) of ④ is the p(y0) of the next ②, so an iteration costs ONE batched
    histogram evaluation (plus one per round of halvings that is really needed).

    Parameters
    ----------
    img : the bin-index image of the region holding the ellipses (:func:`bin_image`)
    q : (m,) target model
    centres : (N, 2) starts y0 (image coordinates); axes : (N, 2) or (1, 2) half-axes, fixed
    bandwidth : the kernel's radius of eq. 3 (:func:`kernel_weights`). Either way g = -k' is
        constant on the ellipse's pixels, so step ③ is the same weighted mean.
    """
    m, m1 = img.n_bins, img.n_bins + 1
    y0 = np.array(np.atleast_2d(centres), dtype=float)
    n = y0.shape[0]
    axes = np.atleast_2d(np.asarray(axes, dtype=float))
    if axes.shape[0] == 1 and n > 1:
        axes = np.repeat(axes, n, axis=0)
    win = ellipse_window(img, axes, bandwidth)
    # Prepared once. Each candidate's labels live in its own block of m + 1 bins (the last is
    # the sentinel "outside the frame", whose model value is 0). The state kept per candidate
    # is sqrt(counts), the square root of its unnormalised eq. 3 sums: step ②'s weights
    # sqrt(q_u / p_u) only change by one factor per candidate if p is not normalised, and
    # step ③'s weighted mean does not see that factor; rho divides it out once.
    sqrt_q = np.sqrt(np.append(np.asarray(q, dtype=float), 0.0))
    sqrt_q_tiled = np.tile(sqrt_q, n)
    rows = (np.arange(n) * m1)[:, None]
    kflat = win.k.ravel()
    k_total, dxy1 = win.k_total, win.dxy1
    flat = img.padded(win.pad).ravel()
    h, w_ = img.labels.shape
    lo, hi = -win.reach, np.array([w_ - 1, h - 1]) + win.reach
    to_flat = np.array([1, w_ + 2 * win.pad])
    corner = win.pad * (to_flat[0] + to_flat[1])
    origin, stride = img.origin, float(img.stride)

    def pixel(y):               # the lattice pixel under each centre
        return np.rint((y - origin) / stride).astype(np.intp)

    def evaluate(ji, need=None, old=None):
        """① / ④: labels (+ block offsets), sqrt(counts) and rho at the lattice pixels ji;
        with ``need`` (bool mask), only those rows are computed, the others come from ``old``
        (once most candidates have stopped, the few still moving cost only their own pixels)."""
        if need is not None and need.all():
            need = None
        r = slice(None) if need is None else np.flatnonzero(need)
        k = n if need is None else r.size
        cost[0] += k
        base = np.minimum(np.maximum(ji[r], lo), hi) @ to_flat + corner
        lab = flat.take(base[:, None] + win.flat)
        block = rows[:k]
        kr = kflat if need is None else win.k[r].ravel()
        counts = np.bincount((lab + block).ravel(), kr, k * m1).reshape(k, m1)
        sc = np.sqrt(counts)
        mass = np.maximum(k_total[r] - counts[:, m], 1e-300)     # eq. 3's 1 / f
        rho = (sc @ sqrt_q) / np.sqrt(mass)
        if need is None:
            return lab + rows, sc, rho
        L, S, R = (a.copy() for a in old)
        L[r], S[r], R[r] = lab + rows[r], sc, rho
        return L, S, R

    cost = [0]                  # histograms computed
    ji0 = pixel(y0)
    L0, sc0, rho0 = evaluate(ji0)                                  # ①
    evaluations = 1
    rho_start = rho0
    iterations = np.zeros(n, dtype=int)
    active = np.ones(n, dtype=bool)
    traj, rtraj = [y0], [rho0]
    eps2 = float(eps) ** 2
    with np.errstate(divide="ignore", invalid="ignore"):
        for _ in range(int(max_iter)):
            w = (sqrt_q_tiled / sc0.ravel()).take(L0)              # ② (eq. 11)
            if win.inside is not None:
                w = np.where(win.inside, w, 0.0)                   # g = 0 outside the ellipse
            mom = w @ dxy1                                         # ③ (eq. 12): weighted mean
            y1 = mom[:, :2] / mom[:, 2:]
            y1 += ji0 * stride + origin
            still = active & (mom[:, 2] > 0)    # no pixel of the model's colours: stay put
            if not still.all():
                y1 = np.where(still[:, None], y1, y0)
            ji1 = pixel(y1)
            fixed = (ji1 == ji0).all(axis=1)    # same lattice pixel: same p, a fixed point
            todo = still & ~fixed
            L1, sc1, rho1 = L0, sc0, rho0
            refused = todo & False
            if todo.any():
                L1, sc1, rho1 = evaluate(ji1, todo, (L0, sc0, rho0))   # ④
                evaluations += 1
                for _h in range(int(max_halvings)):                # ⑤ only where rho went down
                    bad = todo & (rho1 < rho0)
                    if not bad.any():
                        break
                    y1 = np.where(bad[:, None], 0.5 * (y0 + y1), y1)
                    ji1 = pixel(y1)
                    back = bad & (ji1 == ji0).all(axis=1)   # halved onto y0's pixel: fixed
                    if back.any():                          # ... with y0's values
                        L1 = np.where(back[:, None], L0, L1)
                        sc1 = np.where(back[:, None], sc0, sc1)
                        rho1 = np.where(back, rho0, rho1)
                    fixed |= back
                    todo &= ~back
                    if (todo & bad).any():
                        L1, sc1, rho1 = evaluate(ji1, todo & bad, (L1, sc1, rho1))
                        evaluations += 1
                refused = todo & (rho1 < rho0)  # still lower after the halvings: stay at y0
            d = y1 - y0
            small = (d * d).sum(axis=1) < eps2
            iterations += active
            if refused.any():
                keep = refused[:, None]
                y1, ji1 = np.where(keep, y0, y1), np.where(keep, ji0, ji1)
                L1, sc1 = np.where(keep, L0, L1), np.where(keep, sc0, sc1)
                rho1 = np.where(refused, rho0, rho1)
            # rows that did not move (stopped, fixed, refused) have the same values in both
            y0, ji0, L0, sc0, rho0 = y1, ji1, L1, sc1, rho1
            active &= ~(small | fixed | refused)                   # ⑥
            traj.append(y0)
            rtraj.append(rho0)
            if not active.any():
                break
    counts = sc0 * sc0
    mass = k_total - counts[:, m]
    hist = counts[:, :m] / np.where(mass > 0, mass, 1.0)[:, None]
    return MeanShiftResult(y0, rho0, rho_start, iterations, evaluations, cost[0],
                           cost[0] * win.flat.size, np.array(traj), np.array(rtraj), hist)


def mean_shift_with_scale(img: BinImage, q, centre, axes, factors=(0.9, 1.0, 1.1),
                          gamma: float = 0.1, max_iter: int = 20, eps: float = 0.5,
                          bandwidth: str = "ellipse"):
    """Comaniciu et al. 2003 §5.2 scale adaptation: run mean-shift with the half-axes scaled by
    each of ``factors`` (±10 %), keep the run with the best rho, and move the half-axes a
    fraction ``gamma`` of the way to its size (h_new = gamma h_opt + (1 - gamma) h_prev).

    Returns ``(result_of_best_run, new_axes)``; ``result`` is a :class:`MeanShiftResult` with N = 1.
    """
    axes = np.asarray(axes, dtype=float).reshape(2)
    f = np.asarray(factors, dtype=float)
    trial_axes = f[:, None] * axes[None, :]
    starts = np.repeat(np.asarray(centre, dtype=float).reshape(1, 2), len(f), axis=0)
    res = mean_shift(img, q, starts, trial_axes, max_iter=max_iter, eps=eps,
                     bandwidth=bandwidth)
    best = int(np.argmax(res.rho))
    new_axes = gamma * trial_axes[best] + (1.0 - gamma) * axes
    pick = slice(best, best + 1)
    one = MeanShiftResult(res.centres[pick], res.rho[pick], res.rho_start[pick],
                          res.iterations[pick], res.evaluations, res.histograms, res.pixels,
                          res.trajectory[:, pick], res.rho_trajectory[:, pick], res.hist[pick])
    return one, new_axes


def region_around(centres, axes, margin: float = 1.0):
    """``(x0, y0, x1, y1)`` covering every ellipse plus ``margin`` half-axes on each side."""
    centres = np.atleast_2d(centres)
    axes = np.atleast_2d(axes)
    ext = axes * (1.0 + margin)
    lo = (centres - ext).min(axis=0)
    hi = (centres + ext).max(axis=0)
    return (np.floor(lo[0]), np.floor(lo[1]), np.ceil(hi[0]) + 1, np.ceil(hi[1]) + 1)
