"""``edge-ray-x``: the edge-observation variants searched in the lab notes on Kim et al. (2016).

Development code, not part of the library: a subclass of ``edge-ray-pf`` whose params switch
on one departure from Kim et al. 2016 at a time. It is a tracker plugin
(:func:`trackbook.trackers.plugins.load`): the experiment ``kim2016_edges`` of
:mod:`trackbook.evaluation.experiments` names this file, and the benchmark's workers load it
before they run, so the variants run in worker processes like the library's trackers. The
grid of variants (labels and params) is declared there; regenerate its results with::

    python -m trackbook.evaluation.experiments run kim2016_edges --workers 2

The params that switch the departures on:

- ``dist="log"``: eq. 6 replaced by a per-ray log-ratio distance
  D = mean_j |log((p_j + c) / (m_j + c))|, likelihood exp(-D^2 / (2 obs_sigma^2)).
  Every ray counts the same whatever its length (eq. 6's L1 sum is dominated by long rays).
- ``points=5|9``: rays from several reference points of the box (centre, +-fx w, +-fy h, and
  the 4 corners of that inner grid for 9), each with its own model M_k; the likelihoods of the
  points multiply (independent observations).
- ``soft_ratio>0``: the hard Ratio window replaced by exp(-(log Ratio)^2 / (2 soft_ratio^2)).
- ``clahe``: Canny on a CLAHE-equalised grey image (illumination).
- ``top_frac<1``: estimate = weighted mean of the top fraction of particles by weight.
"""
from __future__ import annotations

import dataclasses

import cv2
import numpy as np

from trackbook.features import edge_rays as er
from trackbook.params import param
from trackbook.trackers.edge_ray import EdgeRayParams, EdgeRayPF
from trackbook.trackers.registry import register


@dataclasses.dataclass(frozen=True)
class EdgeRayXParams(EdgeRayParams):
    dist: str = param("paper", doc="ray distance", choices=("paper", "log", "logl1"))
    obs_sigma: float = param(0.3, 0.01, 5.0, 0.01, "sigma of exp(-D^2/2s^2) for dist=log")
    log_c: float = param(2.0, 0.0, 50.0, 0.5, "pixels added to each ray before the log")
    points: int = param(1, 1, 9, 1, "reference points: 1 (paper), 5 (plus), 9 (3x3 grid)")
    fx: float = param(0.25, 0.0, 0.5, 0.05, "offset of the side points, fraction of w")
    fy: float = param(0.25, 0.0, 0.5, 0.05, "offset of the side points, fraction of h")
    soft_ratio: float = param(0.0, 0.0, 5.0, 0.01, "sigma in log Ratio (0 = hard window)")
    clahe: float = param(0.0, 0.0, 10.0, 0.5, "CLAHE clip limit before Canny (0 = off)")
    top_frac: float = param(1.0, 0.01, 1.0, 0.01, "estimate from top fraction of particles")
    combine: str = param("prod", doc="combine points", choices=("prod", "mean", "pool"))
    gain: str = param("off", doc="Canny thresholds follow the gradient gain", choices=("off", "local", "global"))
    gain_roi: float = param(2.0, 1.0, 6.0, 0.5, "local gain window, multiple of the box")
    orient: float = param(0.0, 0.0, 90.0, 5.0, "a ray ignores edges whose gradient is more than this many degrees off its axis (0 = off)")
    dilate: int = param(0, 0, 3, 1, "3x3 dilations of the Canny map (rays cannot slip through)")


_CLAHE = {}


_K3 = np.ones((3, 3), np.uint8)


def edge_image_x(frame, p, gain=1.0):
    e = _edge_image_x(frame, p, gain)
    if p.dilate:
        e = cv2.dilate(e.view(np.uint8), _K3, iterations=int(p.dilate)) > 0
    return e


def grad_energy(frame, roi=None):
    grey = frame if frame.ndim == 2 else cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)
    if roi is not None:
        x0, y0, x1, y1 = roi
        grey = grey[y0:y1, x0:x1]
    gx = cv2.Sobel(grey, cv2.CV_32F, 1, 0, ksize=3)
    gy = cv2.Sobel(grey, cv2.CV_32F, 0, 1, ksize=3)
    return float(np.mean(np.abs(gx) + np.abs(gy))) + 1e-3


def _edge_image_x(frame, p, gain=1.0):
    if gain != 1.0:
        p = dataclasses.replace(p, canny_low=p.canny_low * gain, canny_high=p.canny_high * gain)
    if not p.clahe:
        return er.edge_image(frame, p.canny_low, p.canny_high, p.blur)
    grey = frame if frame.ndim == 2 else cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)
    cl = _CLAHE.get(p.clahe)
    if cl is None:
        cl = _CLAHE[p.clahe] = cv2.createCLAHE(clipLimit=float(p.clahe), tileGridSize=(8, 8))
    grey = cl.apply(grey)
    if p.blur and p.blur > 1:
        k = int(p.blur) | 1
        grey = cv2.GaussianBlur(grey, (k, k), 0)
    return cv2.Canny(grey, float(p.canny_low), float(p.canny_high)) > 0


def _mid(d):
    """Mean of the two middle values of the last axis: eq. 5's 4th and 5th of 8, as
    ``er.median_pair_mean``, but for any number of rays (the pooled 40- and 72-ray models)."""
    n = d.shape[-1]
    s = np.partition(d, (n // 2 - 1, n // 2), axis=-1)
    return 0.5 * (s[..., n // 2 - 1] + s[..., n // 2])


@register
class EdgeRayX(EdgeRayPF):
    name = "edge-ray-x"
    Params = EdgeRayXParams

    def _offsets(self):
        p = self.params
        w, h = self._size * self.scale
        dx, dy = p.fx * w, p.fy * h
        if p.points == 1:
            o = [(0, 0)]
        elif p.points == 5:
            o = [(0, 0), (dx, 0), (-dx, 0), (0, dy), (0, -dy)]
        elif p.points == 9:
            o = [(i * dx, j * dy) for j in (-1, 0, 1) for i in (-1, 0, 1)]
        else:
            raise ValueError("points must be 1, 5 or 9")
        return np.asarray(o, dtype=float)

    def _rays(self, xy):
        p = self.params
        if not p.orient:
            return super()._rays(xy)
        e = self.edges
        H, W = e.shape
        x = np.clip(np.floor(xy[:, 0]), 0, W - 1).astype(np.intp)
        y = np.clip(np.floor(xy[:, 1]), 0, H - 1).astype(np.intp)
        out = np.empty((len(x), 8), dtype=np.intp)
        for a, maps in enumerate(self._axis_edges):
            st = er.ray_steps_at(maps, x, y)
            out[:, a] = st[:, a]
            out[:, a + 4] = st[:, a + 4]
        return er.steps_to_lengths(out, p.max_ray or None, axis=1)

    def _set_edges(self, frame, gain=1.0):
        p = self.params
        self.edges = edge_image_x(frame, p, gain)
        if p.orient:
            grey = frame if frame.ndim == 2 else cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)
            gx = cv2.Sobel(grey, cv2.CV_32F, 1, 0, ksize=3)
            gy = cv2.Sobel(grey, cv2.CV_32F, 0, 1, ksize=3)
            ang = np.arctan2(gy, gx)  # gradient direction, image coords (y down)
            tol = np.cos(np.deg2rad(p.orient))
            self._axis_edges = []
            for j in range(4):  # ray axes E-W, NE-SW, N-S, NW-SE
                dx, dy = er.DIRECTIONS[j] / np.hypot(*er.DIRECTIONS[j])
                c = np.abs(np.cos(ang) * dx + np.sin(ang) * dy)
                self._axis_edges.append(self.edges & (c >= tol))

    def _multi_rays(self, xy):
        off = self._offsets()
        K, N = len(off), len(xy)
        pts = (xy[None, :, :] + off[:, None, :]).reshape(-1, 2)
        return self._rays(pts).reshape(K, N, 8)

    def _roi(self, frame, c):
        H, W = frame.shape[:2]
        half = 0.5 * self.params.gain_roi * self._size * self.scale
        x0, y0 = np.maximum(np.floor(c - half), 0).astype(int)
        x1, y1 = np.minimum(np.ceil(c + half), [W, H]).astype(int)
        if x1 - x0 < 3 or y1 - y0 < 3:
            return None
        return (x0, y0, x1, y1)

    def _gain_energy(self, frame, c):
        p = self.params
        if p.gain == "off":
            return 1.0
        return grad_energy(frame, self._roi(frame, c) if p.gain == "local" else None)

    def model(self, frame, box):
        self._set_edges(frame)
        super().model(frame, box)
        c0 = self.box_to_state(box)
        self._g0 = self._gain_energy(frame, c0)
        self.gain = 1.0
        self._set_edges(frame)
        c = self.box_to_state(box)
        self.model_k = self._multi_rays(c[None, :])[:, 0, :].astype(float)  # (K, 8)
        self.model_rays = self.model_k[0]

    def _score(self, pr, m):
        """pr (K, N, 8), m (K, 8) -> per-point log-likelihood (K, N) and ratios (K, N)."""
        p = self.params
        pr = pr.astype(float)
        mavg = _mid(m)[:, None]
        ravg = _mid(pr) / mavg
        if p.dist == "paper":
            w = 1.0 - np.abs(pr - m[:, None, :]).sum(-1) / m.sum(-1)[:, None]
            ll = np.log(np.clip(w, 1e-12, None))
            ll = np.where(w > 0, ll, -np.inf)
        elif p.dist == "log":
            d = np.abs(np.log((pr + p.log_c) / (m[:, None, :] + p.log_c))).mean(-1)
            ll = -d ** 2 / (2 * p.obs_sigma ** 2)
        else:  # logl1: Laplacian in the mean log-ratio
            d = np.abs(np.log((pr + p.log_c) / (m[:, None, :] + p.log_c))).mean(-1)
            ll = -d / p.obs_sigma
        if p.soft_ratio > 0:
            ll = ll - np.log(ravg) ** 2 / (2 * p.soft_ratio ** 2)
        else:
            inside = (ravg >= p.ratio_low) & (ravg <= p.ratio_high)
            ll = np.where(inside, ll, -np.inf)
        return ll, ravg

    def likelihood(self, frame, particles):
        p = self.params
        if p.gain != "off":
            self.gain = float(np.clip(self._gain_energy(frame, self.estimate) / self._g0, 0.1, 10.0))
        self._set_edges(frame, self.gain)
        pr = self._multi_rays(particles)
        m = self.model_k * self.scale
        if p.combine == "pool":
            K, N = pr.shape[:2]
            pr = pr.transpose(1, 0, 2).reshape(1, N, 8 * K)
            m = m.reshape(1, 8 * K)
        ll, r = self._score(pr, m)
        self.particle_rays = pr[0][:, :8]
        self.ratios = r[0]
        if p.combine in ("prod", "pool"):
            L = ll.sum(0)
        else:
            mx = ll.max(0)
            with np.errstate(invalid="ignore"):
                L = np.where(np.isfinite(mx), mx + np.log(np.exp(ll - np.where(np.isfinite(mx), mx, 0)).mean(0)), -np.inf)
        if p.dist == "paper" and p.points == 1 and p.soft_ratio == 0:
            return np.where(np.isfinite(L), np.exp(L), 0.0)
        # normalise in log space for numerical safety (weights are normalised anyway)
        top = np.max(L) if np.isfinite(L).any() else 0.0
        return np.where(np.isfinite(L), np.exp(L - top), 0.0)

    def _locate(self, frame):
        box, conf = super()._locate(frame)
        p = self.params
        if p.top_frac < 1.0 and np.all(np.isfinite(box)):
            # the estimate from the top fraction of the particles by weight (the velocity
            # follows from it when the frame is accepted, in _learn)
            w = self.weights
            n = max(1, int(round(p.top_frac * len(w))))
            idx = np.argpartition(-w, n - 1)[:n]
            ww = w[idx] / w[idx].sum()
            self._located = ww @ self._particles[idx]
            box = self.state_to_box(self._located)
            self.colour_rho = conf = float(self._colour.match(frame, np.asarray(box)[None])[0])
        return box, conf
