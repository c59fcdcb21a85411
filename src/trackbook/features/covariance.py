"""Region covariance descriptors and the Förstner–Moonen metric (``07_region_covariance``, Lee 2015 §2.1).

A region R of a frame is described by the d x d covariance of per-pixel feature vectors
(eq. 2 / eq. 4 of Lee 2015). Two regions are compared with the Förstner–Moonen distance
(eq. 5–6), the natural distance on the manifold of symmetric positive-definite matrices.

Everything here is batched: :class:`IntegralCovariance` answers the covariance of *many*
rectangles at once from integral images (Tuzel, Porikli & Meer 2006), and
:func:`forstner_distance` compares one model with a stack of candidate covariances in one call.

>>> import numpy as np
>>> from trackbook.features.covariance import feature_image, IntegralCovariance
>>> frame = np.random.default_rng(0).integers(0, 256, (60, 80, 3), dtype=np.uint8)
>>> ic = IntegralCovariance(feature_image(frame))
>>> ic.covariances([[10, 10, 24, 24], [30, 20, 24, 24]]).shape
(2, 5, 5)
"""

from __future__ import annotations

import cv2
import numpy as np

#: The feature sets a tracker can use; the string spells the feature vector.
#: ``"xyIIxIy"`` is eq. 2 of Lee (2015) with signed Ix, Iy: the printed f = [x y I Ix ...]
#: stops at Ix [quote: lee2015.features_eq2], and Iy is the book's completion; the default
#: ``"xyI|Ix||Iy|"`` takes their absolute values as Tuzel et al. (2006) do (``07_region_covariance``).
FEATURE_SETS = ("xyI|Ix||Iy|", "rI|Ix||Iy|", "xyRGB|Ix||Iy|", "xyIIxIy")


def _check_feature_set(features: str) -> str:
    if features not in FEATURE_SETS:
        raise ValueError(
            f"unknown feature set {features!r}; choose one of {FEATURE_SETS} "
            "(eq. 2 of Lee 2015, completed with a signed Iy, is 'xyIIxIy', with absolute "
            "gradients 'xyI|Ix||Iy|'; "
            "eq. 3 is 'rI|Ix||Iy|')."
        )
    return features


def feature_dimension(features: str = "xyI|Ix||Iy|") -> int:
    """Length d of the feature vector f_k of a feature set (5, 4, 7 or 5)."""
    return {"xyI|Ix||Iy|": 5, "rI|Ix||Iy|": 4, "xyRGB|Ix||Iy|": 7,
            "xyIIxIy": 5}[_check_feature_set(features)]


def _grey(frame: np.ndarray) -> np.ndarray:
    if frame.ndim == 2:
        return frame.astype(np.float64)
    return cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY).astype(np.float64)


def _abs_gradients(grey: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    # The [-1 0 1] derivative of Tuzel et al.; replicated borders so a crop's edge pixels
    # still get a gradient (callers pad their crops by one pixel to make it exact).
    kx = np.array([[-1.0, 0.0, 1.0]])
    ix = cv2.filter2D(grey, cv2.CV_64F, kx, borderType=cv2.BORDER_REPLICATE)
    iy = cv2.filter2D(grey, cv2.CV_64F, kx.T, borderType=cv2.BORDER_REPLICATE)
    return np.abs(ix), np.abs(iy)


def feature_image(frame: np.ndarray, features: str = "xyI|Ix||Iy|") -> np.ndarray:
    """The feature image F(x, y) = Φ(I, x, y) of eq. 1–2 of Lee 2015, H x W x d float64.

    Parameters
    ----------
    frame : H x W x 3 uint8 BGR image (or H x W grey).
    features : one of :data:`FEATURE_SETS`
        ``"xyI|Ix||Iy|"`` — f = [x, y, I, |Ix|, |Iy|] (eq. 2 plus |·|: the book's default);
        ``"rI|Ix||Iy|"`` — f = [‖(x′, y′)‖, I, |Ix|, |Iy|] (eq. 3). The radius depends on the
        window's centre, so this image holds only the last three channels and
        :class:`IntegralCovariance` adds the radius per window;
        ``"xyRGB|Ix||Iy|"`` — f = [x, y, R, G, B, |Ix|, |Iy|] (colour option);
        ``"xyIIxIy"`` — f = [x, y, I, Ix, Iy], eq. 2 with the signed gradients it prints.

    Notes
    -----
    I is the grey level in 0..255; Ix, Iy use the [-1 0 1] filter. x and y are the column and
    row of the pixel in the array given, which does not change any covariance (eq. 4 subtracts
    the mean).
    """
    features = _check_feature_set(features)
    frame = np.asarray(frame)
    grey = _grey(frame)
    ax, ay = _abs_gradients(grey)
    H, W = grey.shape
    if features == "rI|Ix||Iy|":
        return np.stack([grey, ax, ay], axis=-1)
    y, x = np.mgrid[0:H, 0:W].astype(np.float64)
    if features == "xyI|Ix||Iy|":
        return np.stack([x, y, grey, ax, ay], axis=-1)
    if features == "xyIIxIy":
        kx = np.array([[-1.0, 0.0, 1.0]])
        ix = cv2.filter2D(grey, cv2.CV_64F, kx, borderType=cv2.BORDER_REPLICATE)
        iy = cv2.filter2D(grey, cv2.CV_64F, kx.T, borderType=cv2.BORDER_REPLICATE)
        return np.stack([x, y, grey, ix, iy], axis=-1)
    if frame.ndim != 3:
        raise ValueError("the colour feature set 'xyRGB|Ix||Iy|' needs an H x W x 3 BGR frame.")
    rgb = frame[..., ::-1].astype(np.float64)
    return np.concatenate([x[..., None], y[..., None], rgb, ax[..., None], ay[..., None]], -1)


def feature_planes(frame: np.ndarray, features: str = "xyI|Ix||Iy|", out=None) -> np.ndarray:
    """The feature image of :func:`feature_image` channels first: d x H x W float64.

    The same numbers, laid out as the contiguous planes :class:`IntegralCovariance` sums
    (pass ``channels_first=True``), written into ``out`` if given — the trackers' fast path.
    """
    features = _check_feature_set(features)
    frame = np.asarray(frame)
    grey = _grey(frame)
    H, W = grey.shape
    colour = features == "xyRGB|Ix||Iy|"
    if colour and frame.ndim != 3:
        raise ValueError("the colour feature set 'xyRGB|Ix||Iy|' needs an H x W x 3 BGR frame.")
    d = feature_dimension(features) - (1 if features == "rI|Ix||Iy|" else 0)
    out = np.empty((d, H, W)) if out is None else out
    c = 0
    if features != "rI|Ix||Iy|":
        out[0] = np.arange(W, dtype=np.float64)[None, :]
        out[1] = np.arange(H, dtype=np.float64)[:, None]
        c = 2
    if colour:
        for ch in (2, 1, 0):                                   # BGR frame -> R, G, B
            out[c] = frame[..., ch]
            c += 1
    else:
        out[c] = grey
        c += 1
    kx = np.array([[-1.0, 0.0, 1.0]])
    for kernel in (kx, kx.T):
        # Same [-1 0 1] filter and borders as _abs_gradients; signed, as eq. 2 writes I_x
        # [quote: lee2015.features_eq2].
        g = cv2.filter2D(grey, cv2.CV_64F, kernel, borderType=cv2.BORDER_REPLICATE)
        if features == "xyIIxIy":
            out[c] = g
        else:
            np.abs(g, out=out[c])
        c += 1
    return out


def region_covariance(F: np.ndarray) -> np.ndarray:
    """C_R = (1/MN) Σ (f_k − μ_R)(f_k − μ_R)ᵀ of one M x N x d feature patch (eq. 4).

    The direct (slow) formula: the oracle the integral-image version is tested against.
    """
    f = np.asarray(F, dtype=np.float64).reshape(-1, F.shape[-1])
    d = f - f.mean(axis=0)
    return d.T @ d / f.shape[0]


class Workspace:
    """Scratch arrays reused from one frame to the next.

    A tracker builds integral tables of ~20 planes every frame. Freshly allocated arrays of a
    few MB come from the operating system as new pages, and touching them for the first time
    (page faults) cost more than the sums themselves; a tracker keeps one ``Workspace`` and
    hands it to :class:`IntegralCovariance` so that memory is allocated once.
    """

    def __init__(self):
        self._flat: dict[str, np.ndarray] = {}

    def get(self, name: str, shape) -> np.ndarray:
        """A C-contiguous float64 array of ``shape`` (contents undefined), reused by ``name``."""
        n = int(np.prod(shape))
        flat = self._flat.get(name)
        if flat is None or flat.size < n:
            flat = self._flat[name] = np.empty(n)
        return flat[:n].reshape(shape)


def _integral_planes(planes, out=None) -> np.ndarray:
    """Zero-padded summed-area tables of 2-D planes: S[c, y, x] = Σ planes[c][:y, :x], float64.

    One ``cv2.integral`` per contiguous plane: faster than one call on the
    interleaved multi-channel image, and exact in float64. ``out``: where to write S.
    """
    h, w = planes[0].shape
    S = np.empty((len(planes), h + 1, w + 1)) if out is None else out
    for c, p in enumerate(planes):
        # Written straight into S[c] (contiguous, right shape and type): no copy per plane.
        cv2.integral(np.ascontiguousarray(p, dtype=np.float64), S[c], sdepth=cv2.CV_64F)
    return S


def radial_template(w: int, h: int) -> np.ndarray:
    """‖(x′, y′)‖ of eq. 3: each pixel's distance from the centre of a w x h window."""
    y, x = np.mgrid[0:h, 0:w].astype(np.float64)
    return np.hypot(x - (w - 1) / 2.0, y - (h - 1) / 2.0)


class IntegralCovariance:
    """Covariances (eq. 4 of Lee 2015) of any rectangles of a feature image in O(d²) each.

    Following Tuzel, Porikli & Meer (2006) the constructor builds the integral images
    P_i = Σ F_i and Q_ij = Σ F_i F_j (i ≤ j) (attributes ``P``: k x (h+1) x (w+1), ``Q``:
    k(k+1)/2 x (h+1) x (w+1)); a rectangle's covariance then needs four look-ups per table:
    C = (Q − P Pᵀ / n) / n.

    Parameters
    ----------
    F : h x w x d feature image (from :func:`feature_image`), or a crop of one.
    origin : (x0, y0), where pixel F[0, 0] sits in frame coordinates; boxes passed to
        :meth:`covariances` are in frame coordinates.
    radial : bool
        True for the eq. 3 feature set: F then holds [I, |Ix|, |Iy|] and the radius channel is
        added per window size with one correlation (``cv2.filter2D``) per feature.
    channels_first : bool
        True when F is d x h x w (from :func:`feature_planes`), the faster layout.
    workspace : :class:`Workspace`, optional
        Reuse its arrays for the planes and tables (a tracker passes the same one every
        frame). The tables ``P``, ``Q`` then live in the workspace: valid until the next
        ``IntegralCovariance`` built with it.

    Notes
    -----
    Precision: the sums run in float64 after subtracting each channel's mean over the image,
    so Q − P Pᵀ/n does not cancel away the digits of a 255² · 10⁵-sized sum.
    """

    def __init__(self, F: np.ndarray, origin=(0, 0), radial: bool = False,
                 workspace: Workspace | None = None, channels_first: bool = False):
        F = np.asarray(F, dtype=np.float64)
        if F.ndim == 3 and channels_first:
            F = np.moveaxis(F, 0, -1)                          # a view: h x w x d
        if F.ndim != 3 or F.shape[0] < 1 or F.shape[1] < 1:
            raise ValueError(f"F must be an h x w x d feature image, got shape {F.shape}.")
        self.origin = (int(origin[0]), int(origin[1]))
        self.shape = F.shape[:2]
        self.radial = bool(radial)
        k = F.shape[-1]
        self._iu = np.triu_indices(k)
        # Contiguous per-channel planes [F_i − offset_i, products] in one array (one pass each,
        # no strided reads of the interleaved image); one summed-area table per plane.
        shape = (k + len(self._iu[0]),) + F.shape[:2]
        planes = np.empty(shape) if workspace is None else workspace.get("planes", shape)
        planes[:k] = np.moveaxis(F, -1, 0)       # a plain copy when F came channels first
        self.offset = planes[:k].mean(axis=(1, 2))
        planes[:k] -= self.offset[:, None, None]
        for c, (i, j) in enumerate(zip(*self._iu), start=k):
            np.multiply(planes[i], planes[j], out=planes[c])
        out = None
        if workspace is not None:
            out = workspace.get("tables", (shape[0], shape[1] + 1, shape[2] + 1))
        S = _integral_planes(planes, out)
        self.P, self.Q = S[:k], S[k:]
        self._G = np.moveaxis(planes[:k], 0, -1).copy() if radial else None
        self._rcache: dict = {}
        self.d = k + (1 if radial else 0)

    def _rect_sums(self, S, x0, y0, x1, y1):
        """Sums of every plane of S over N rectangles: N x planes."""
        return (S[:, y1, x1] - S[:, y0, x1] - S[:, y1, x0] + S[:, y0, x0]).T

    def _local(self, boxes):
        b = np.asarray(boxes)
        if b.ndim == 1:
            b = b[None]
        if b.ndim != 2 or b.shape[1] != 4:
            raise ValueError(f"boxes must be N x 4 (x, y, w, h), got shape {b.shape}.")
        bi = np.rint(b).astype(np.int64)
        x0 = bi[:, 0] - self.origin[0]
        y0 = bi[:, 1] - self.origin[1]
        x1, y1 = x0 + bi[:, 2], y0 + bi[:, 3]
        h, w = self.shape
        if len(bi) and (x0.min() < 0 or y0.min() < 0 or x1.max() > w or y1.max() > h
                        or bi[:, 2].min() < 1 or bi[:, 3].min() < 1):
            raise ValueError(
                "a box lies outside the integral image (or is empty); keep candidate boxes "
                f"inside the {w}x{h} region at origin {self.origin}."
            )
        return x0, y0, x1, y1

    def means(self, boxes) -> np.ndarray:
        """μ_R of eq. 4 for N boxes (N x k, without the radial channel)."""
        x0, y0, x1, y1 = self._local(boxes)
        n = ((x1 - x0) * (y1 - y0)).astype(np.float64)
        return self._rect_sums(self.P, x0, y0, x1, y1) / n[:, None] + self.offset

    def covariances(self, boxes) -> np.ndarray:
        """C_R of eq. 4 (population form, 1/MN) for N boxes ``(x, y, w, h)``: N x d x d."""
        x0, y0, x1, y1 = self._local(boxes)
        n = ((x1 - x0) * (y1 - y0)).astype(np.float64)
        Ps = self._rect_sums(self.P, x0, y0, x1, y1)            # N x k
        Qs = self._rect_sums(self.Q, x0, y0, x1, y1)            # N x k(k+1)/2
        k = Ps.shape[1]
        N = len(n)
        C = np.empty((N, k, k))
        iu0, iu1 = self._iu
        C[:, iu0, iu1] = (Qs - Ps[:, iu0] * Ps[:, iu1] / n[:, None]) / n[:, None]
        C[:, iu1, iu0] = C[:, iu0, iu1]
        if not self.radial:
            return C
        return self._with_radius(C, Ps, n, x0, y0, x1, y1)

    def _with_radius(self, C, Ps, n, x0, y0, x1, y1):
        k = C.shape[1]
        out = np.empty((len(n), k + 1, k + 1))
        out[:, 1:, 1:] = C
        ws, hs = x1 - x0, y1 - y0
        for w, h in set(zip(ws.tolist(), hs.tolist())):
            sel = (ws == w) & (hs == h)
            r = radial_template(w, h)
            mr, vr = r.mean(), r.var()
            # Σ_window r·g at every top-left corner: one correlation per feature channel.
            if (w, h) not in self._rcache:
                self._rcache[(w, h)] = np.stack(
                    [cv2.filter2D(self._G[..., i], cv2.CV_64F, r, anchor=(0, 0),
                                  borderType=cv2.BORDER_CONSTANT) for i in range(k)], -1)
            RG = self._rcache[(w, h)][y0[sel], x0[sel]]          # M x k
            cov_rg = RG / n[sel, None] - mr * Ps[sel] / n[sel, None]
            out[sel, 0, 0] = vr
            out[sel, 0, 1:] = cov_rg
            out[sel, 1:, 0] = cov_rg
        return out


def covariance_of_box(frame: np.ndarray, box, features: str = "xyI|Ix||Iy|") -> np.ndarray:
    """C_R (eq. 4) of one box of a frame: a convenience for chapters and exercises."""
    F = feature_image(frame, features)
    return IntegralCovariance(F, radial=features == "rI|Ix||Iy|").covariances([box])[0]


def _inv_sqrt(A: np.ndarray, floor: float) -> np.ndarray:
    a, V = np.linalg.eigh(A)
    # Eigenvalues below 1e-12 of the largest are round-off of a singular matrix (a flat or
    # noise-free patch with eps = 0): flooring them there keeps C^{-1/2} finite instead of
    # 1/sqrt(tiny) ~ 1e154, whose square overflows and makes eigvalsh fail.
    a = np.maximum(a, np.maximum(floor, 1e-12 * np.abs(a).max(axis=-1, keepdims=True)))
    return (V / np.sqrt(a)[..., None, :]) @ np.swapaxes(V, -1, -2)


def generalized_eigenvalues(Ci, Cj, eps: float = 1e-6) -> np.ndarray:
    """λ_k(C_i, C_j) of eq. 6 of Lee 2015: the solutions of λ C_i x = C_j x, ascending.

    Both matrices are regularised to C + εI first, so singular covariances (a flat patch has a
    zero-variance gradient) never raise. Batched: ``Ci`` and/or ``Cj`` may be stacks
    (... x d x d); they broadcast. Computed by whitening with C_i^{-1/2} and one stacked
    ``np.linalg.eigvalsh``.
    """
    Ci = np.asarray(Ci, dtype=np.float64)
    Cj = np.asarray(Cj, dtype=np.float64)
    if Ci.shape[-1] != Ci.shape[-2] or Cj.shape[-1] != Cj.shape[-2] or Ci.shape[-1] != Cj.shape[-1]:
        raise ValueError(f"need square d x d matrices of equal d, got {Ci.shape} and {Cj.shape}.")
    if eps < 0 or not np.isfinite(eps):
        raise ValueError(f"eps must be a finite number >= 0, got {eps!r}.")
    d = Ci.shape[-1]
    I = np.eye(d)
    A = 0.5 * (Ci + np.swapaxes(Ci, -1, -2)) + eps * I
    B = 0.5 * (Cj + np.swapaxes(Cj, -1, -2)) + eps * I
    tiny = np.finfo(np.float64).tiny
    W = _inv_sqrt(A, floor=max(eps, tiny))
    with np.errstate(over="ignore", invalid="ignore"):
        M = W @ B @ np.swapaxes(W, -1, -2)
    M = 0.5 * (M + np.swapaxes(M, -1, -2))
    finite = np.all(np.isfinite(M), axis=(-2, -1))
    if not np.all(finite):
        # a matrix too large for float64 is as far from the model as can be: lambda = inf
        lam = np.full(M.shape[:-1], np.inf)
        lam[finite] = np.linalg.eigvalsh(M[finite])
        return np.maximum(lam, tiny)
    lam = np.linalg.eigvalsh(M)
    # Round-off can leave a (near-)singular B's eigenvalue at 0 or slightly below.
    return np.maximum(lam, tiny)


def forstner_distance(Ci, Cj, eps: float = 1e-6) -> np.ndarray:
    """ρ(C_i, C_j) = √(Σ_k ln² λ_k(C_i, C_j)) — the Förstner–Moonen metric, eq. 5 of Lee 2015.

    Symmetric (λ ↦ 1/λ when the arguments swap), zero only for equal matrices, and invariant
    to a common congruence C ↦ A C Aᵀ (for ``eps=0``). Batched like
    :func:`generalized_eigenvalues`: ``forstner_distance(C_model, C_candidates)`` returns one ρ
    per candidate.
    """
    lam = generalized_eigenvalues(Ci, Cj, eps)
    return np.sqrt(np.sum(np.log(lam) ** 2, axis=-1))


__all__ = [
    "FEATURE_SETS", "feature_dimension", "feature_image", "feature_planes", "region_covariance",
    "IntegralCovariance", "Workspace", "covariance_of_box", "radial_template",
    "generalized_eigenvalues", "forstner_distance",
]
