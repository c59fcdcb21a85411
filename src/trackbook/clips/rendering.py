"""The compositing engine of the generated sample clips.

Every sample clip is made of photographs that ship inside scikit-image (``skimage.data``:
astronaut, chelsea, coffee, rocket, brick, grass, gravel, ...; none of them needs a download),
cut into sprites and pasted at sub-pixel positions on a textured background. Because the
target is rendered here, its box is known exactly: it is the axis-aligned extent of the pasted
sprite's support (the pixels where its alpha is at least one half), also when something hides
it.

* :func:`photo`, :func:`crop`, :func:`duotone`, :func:`tile` - textures from the photographs;
* :class:`Sprite` and :class:`Canvas` - a sprite with an alpha mask, and a frame that
  composites sprites (translation, rotation, scale) and remembers which sprite owns each
  pixel, so the visible part of a target is known too;
* :func:`view` - a sub-pixel window on a large background (camera motion, shake);
* :func:`expose` - lighting: global gain, a spatial light map, tint, contrast, noise;
* :func:`path` and :func:`steps` - smooth keyed trajectories and sudden light changes;
* :class:`Film` and :class:`Rendering` - a scene's frames, boxes and target masks.

The sprite makers are in :mod:`trackbook.clips.sprites`, the scenes in
:mod:`trackbook.clips.scenes`, the registry of sample clips in :mod:`trackbook.clips.samples`.
"""

from __future__ import annotations

import dataclasses
import functools

import cv2
import numpy as np

H, W = 240, 320          # frame size of every sample clip (the papers' 320 x 240)
SS = 4                   # supersampling factor for drawn shapes (smooth, anti-aliased edges)


# --------------------------------------------------------------------------- photographs
# the files behind the skimage.data loaders we use (all inside the installed wheel)
_PHOTO_FILES = {
    "astronaut": "astronaut.png", "brick": "brick.png", "camera": "camera.png",
    "chelsea": "chelsea.png", "coffee": "coffee.png", "coins": "coins.png",
    "colorwheel": "color.png", "grass": "grass.png", "gravel": "gravel.png",
    "hubble_deep_field": "hubble_deep_field.jpg", "immunohistochemistry": "ihc.png",
    "motorcycle": "motorcycle_left.png", "retina": "retina.jpg", "rocket": "rocket.jpg",
}


@functools.lru_cache(maxsize=None)
def photo(name: str) -> np.ndarray:
    """A photograph bundled with scikit-image, as read-only BGR ``uint8``.

    Parameters
    ----------
    name : str
        A ``skimage.data`` photograph whose file ships in the wheel: one of the keys of
        ``_PHOTO_FILES`` (``"astronaut"``, ``"chelsea"``, ``"coffee"``, ``"rocket"``,
        ``"brick"``, ``"grass"``, ``"gravel"``, ...; ``"motorcycle"`` is the left image of
        ``stereo_motorcycle``). Grey images come back with three equal channels.

    Notes
    -----
    The file is read with OpenCV straight from the installed ``skimage/data`` folder: the
    same pixels as ``skimage.data.<name>()`` without importing skimage's image I/O stack
    (half a second on first use). The skimage loader is the fallback if the file moved.
    Nothing is ever downloaded.
    """
    from importlib.resources import files

    img = None
    try:
        img = cv2.imread(str(files("skimage.data") / _PHOTO_FILES[name]), cv2.IMREAD_COLOR)
    except (KeyError, ModuleNotFoundError, OSError):
        pass
    if img is None:
        import skimage.data as data

        img = data.stereo_motorcycle()[0] if name == "motorcycle" else getattr(data, name)()
        if img.ndim == 2:
            img = cv2.cvtColor(img, cv2.COLOR_GRAY2BGR)
        else:
            img = cv2.cvtColor(img[..., :3], cv2.COLOR_RGB2BGR)
    img.setflags(write=False)
    return img


def crop(name: str, x0: int, y0: int, x1: int, y1: int, size=None) -> np.ndarray:
    """Float32 BGR crop ``[y0:y1, x0:x1]`` of :func:`photo` ``name``, resized to ``(w, h)``."""
    img = photo(name)[y0:y1, x0:x1]
    if size is not None:
        img = cv2.resize(img, (int(size[0]), int(size[1])), interpolation=cv2.INTER_AREA)
    return img.astype(np.float32)


def duotone(img: np.ndarray, dark, light) -> np.ndarray:
    """Map an image's brightness between two BGR colours (colours a grey texture)."""
    g = img.mean(axis=2, keepdims=True) if img.ndim == 3 else img[..., None]
    g = (g - g.min()) / max(float(np.ptp(g)), 1e-6)
    dark, light = np.float32(dark), np.float32(light)
    return (dark + g * (light - dark)).astype(np.float32)


def tile(img: np.ndarray, w: int, h: int) -> np.ndarray:
    """Cover ``w x h`` by mirror-tiling ``img`` (mirroring hides the seams)."""
    ny, nx = -(-h // img.shape[0]), -(-w // img.shape[1])
    row = np.concatenate([img if k % 2 == 0 else img[:, ::-1] for k in range(nx)], axis=1)
    col = np.concatenate([row if k % 2 == 0 else row[::-1] for k in range(ny)], axis=0)
    return np.ascontiguousarray(col[:h, :w])


# ------------------------------------------------------------------------------ sprites
class Sprite:
    """An image with an alpha mask, pasted by :meth:`Canvas.paste`.

    Parameters
    ----------
    bgr : ndarray, h x w x 3
        Colour (straight, not premultiplied), 0..255.
    alpha : ndarray, h x w
        Opacity in [0, 1]. The sprite's *support* is ``alpha >= 0.5``; its box in a frame
        is the extent of the transformed support.

    Notes
    -----
    Pixel ``(r, c)`` covers the unit square ``[c, c+1) x [r, r+1)`` (its centre is at
    ``(c + 0.5, r + 0.5)``). The support is the region where the bilinearly interpolated
    alpha is at least 1/2, which is exactly what a bilinear warp samples at each pixel
    centre. Its convex hull is traced once, to a quarter pixel; the box of a transformed
    sprite is the extent of the transformed hull (an affine map's extremes are reached at
    hull vertices), so it is continuous, exact to a quarter pixel, and costs a few points.
    """

    def __init__(self, bgr: np.ndarray, alpha: np.ndarray):
        self.bgr = np.asarray(bgr, np.float32)
        self.alpha = np.clip(np.asarray(alpha, np.float32), 0.0, 1.0)
        # premultiplied colour + alpha in one array: one warpAffine per paste, no dark fringes
        self.premult = np.dstack([self.bgr * self.alpha[..., None], self.alpha])
        # the support, where the bilinearly interpolated alpha (what warpAffine samples)
        # reaches 1/2, traced on a 4x finer grid; zero padding = warpAffine's constant border
        f = 4
        fine = cv2.resize(np.pad(self.alpha, 1), None, fx=f, fy=f,
                          interpolation=cv2.INTER_LINEAR)
        inside = fine >= 0.5
        if not inside.any():
            raise ValueError("a sprite needs some pixels with alpha >= 0.5")
        # only the first and last inside cell of every row and column can be on the hull
        r = np.flatnonzero(inside.any(axis=1))
        c = np.flatnonzero(inside.any(axis=0))
        rows, cols = inside[r], inside[:, c]
        xs = np.concatenate([np.argmax(rows, 1), rows.shape[1] - 1 - np.argmax(rows[:, ::-1], 1),
                             c, c])
        ys = np.concatenate([r, r, np.argmax(cols, 0),
                             cols.shape[0] - 1 - np.argmax(cols[::-1], 0)])
        corners = np.concatenate([np.c_[xs + dx, ys + dy] for dx in (0, 1) for dy in (0, 1)])
        hull = cv2.convexHull(corners.astype(np.float32)).reshape(-1, 2).astype(float)
        self.hull = hull / f - 1.0

    @property
    def size(self) -> tuple[int, int]:
        """``(w, h)`` of the sprite image."""
        return self.alpha.shape[1], self.alpha.shape[0]

    def flipped(self) -> Sprite:
        """The mirror image (a walker turning round)."""
        return Sprite(self.bgr[:, ::-1], self.alpha[:, ::-1])

    @classmethod
    def supersampled(cls, bgr: np.ndarray, alpha: np.ndarray, factor: int = SS) -> Sprite:
        """A sprite drawn at ``factor`` times its size, area-averaged down (soft edges)."""
        h, w = alpha.shape
        size = (w // factor, h // factor)
        a = cv2.resize(alpha.astype(np.float32), size, interpolation=cv2.INTER_AREA)
        pm = cv2.resize(bgr.astype(np.float32) * alpha[..., None], size,
                        interpolation=cv2.INTER_AREA)
        return cls(pm / np.maximum(a, 1e-6)[..., None], a)


def _affine(angle: float, scale: float) -> np.ndarray:
    """2 x 2 rotation (degrees, counter-clockwise on screen) times scale."""
    t = np.deg2rad(angle)
    c, s = np.cos(t) * scale, np.sin(t) * scale
    return np.array([[c, s], [-s, c]])


def sprite_box(sprite: Sprite, center, angle: float = 0.0, scale: float = 1.0) -> np.ndarray:
    """Box ``(x, y, w, h)`` of ``sprite`` pasted with its centre at ``center`` (continuous)."""
    w, h = sprite.size
    pts = (sprite.hull - (w / 2, h / 2)) @ _affine(angle, scale).T + np.asarray(center, float)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    return np.array([lo[0], lo[1], hi[0] - lo[0], hi[1] - lo[1]])


@dataclasses.dataclass
class Placement:
    """Where :meth:`Canvas.paste` put a sprite: its exact box, its layer and its ROI mask."""

    box: np.ndarray          # (x, y, w, h), continuous, may reach outside the frame
    layer: int               # id in Canvas.owner
    roi: tuple               # (slice rows, slice cols) of the frame, or None if off-frame
    mask: np.ndarray         # support (alpha >= 0.5) inside roi, bool


class Canvas:
    """One frame being composited, back to front.

    Parameters
    ----------
    background : ndarray, H x W x 3
        Copied into :attr:`img` (float32), or adopted as it is with ``copy=False``.

    Attributes
    ----------
    img : ndarray, H x W x 3 float32
    owner : ndarray, H x W int16
        Which paste is on top at each pixel (0 for the background), so that the visible
        part of a target is ``support & (owner == layer)``.
    """

    def __init__(self, background: np.ndarray, copy: bool = True):
        # copy=False adopts a fresh float32 H x W x 3 array (saves a copy per frame)
        self.img = np.array(background[..., :3], dtype=np.float32, copy=copy)
        self.owner = np.zeros(self.img.shape[:2], np.int16)
        self._layers = 0

    def paste(self, sprite: Sprite, center, angle: float = 0.0, scale: float = 1.0,
              opacity: float = 1.0, opaque: bool = True) -> Placement:
        """Composite ``sprite`` centred at ``center=(cx, cy)``, rotated and scaled about it.

        ``opaque=False`` pastes without taking ownership of pixels (shadows, glows).
        """
        A = _affine(angle, scale)
        box = sprite_box(sprite, center, angle, scale)
        self._layers += 1
        hh, ww = self.owner.shape
        # warp only a region of interest around the box (1 px margin for the bilinear tail)
        x0, y0 = max(int(np.floor(box[0])) - 1, 0), max(int(np.floor(box[1])) - 1, 0)
        x1 = min(int(np.ceil(box[0] + box[2])) + 1, ww)
        y1 = min(int(np.ceil(box[1] + box[3])) + 1, hh)
        if x1 <= x0 or y1 <= y0:
            return Placement(box, self._layers, None, np.zeros((0, 0), bool))
        w, h = sprite.size
        # pixel centres are at integer + 0.5 in box coordinates and at integers for OpenCV
        t = A @ (0.5 - np.array([w / 2, h / 2])) + np.asarray(center, float) - 0.5 - (x0, y0)
        warped = cv2.warpAffine(sprite.premult, np.hstack([A, t[:, None]]), (x1 - x0, y1 - y0),
                                flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT)
        a = warped[..., 3]
        roi = (slice(y0, y1), slice(x0, x1))
        dst = self.img[roi]
        dst *= 1.0 - opacity * a[..., None]
        dst += opacity * warped[..., :3]
        mask = a >= 0.5
        if opaque:
            self.owner[roi][mask] = self._layers
        return Placement(box, self._layers, roi, mask)

    def support(self, p: Placement) -> np.ndarray:
        """Full-frame bool mask of a placement's support (hidden parts included)."""
        m = np.zeros(self.owner.shape, bool)
        if p.roi is not None:
            m[p.roi] = p.mask
        return m

    def visible(self, p: Placement) -> np.ndarray:
        """Full-frame bool mask of the part of a placement nothing was pasted over."""
        return self.support(p) & (self.owner == p.layer)


# ------------------------------------------------------------------ camera and lighting
def view(scene: np.ndarray, x: float, y: float, size=(W, H)) -> np.ndarray:
    """The ``size=(w, h)`` window of ``scene`` whose top-left corner is at ``(x, y)``.

    Sub-pixel (bilinear), so a scrolling or shaking camera moves smoothly. ``scene`` has 1 or
    3 float32 channels; a window reaching outside it repeats the edge pixels.
    """
    w, h = size
    # getRectSubPix takes the window's centre in pixel-centre coordinates; it is several
    # times faster than warpAffine for a pure translation
    return cv2.getRectSubPix(scene, (int(w), int(h)), (x + (w - 1) / 2, y + (h - 1) / 2))


def expose(img: np.ndarray, gain=1.0, light: np.ndarray | None = None, contrast: float = 1.0,
           noise: np.ndarray | None = None) -> np.ndarray:
    """Light a composited frame and quantise it to ``uint8`` (rounded, saturated).

    Parameters
    ----------
    img : ndarray, H x W x 3 float32
    gain : float or sequence of 3 floats
        Global exposure (a per-channel gain also tints: night light is bluish).
    light : ndarray, H x W, optional
        Spatial light map (lamp pools, vignetting); multiplies every channel.
    contrast : float
        Scales deviations from mid-grey (< 1 flattens the image, as in dim light).
    noise : ndarray, H x W x 3, optional
        Added last (sensor noise, visible in dark frames).
    """
    # OpenCV's arithmetic is several times faster than numpy's on whole frames
    out = np.asarray(img, np.float32)
    if contrast != 1.0:
        out = cv2.addWeighted(out, contrast, out, 0.0, 110.0 * (1.0 - contrast))
    g = np.broadcast_to(np.asarray(gain, float), (3,))
    out = cv2.multiply(out, (float(g[0]), float(g[1]), float(g[2]), 0.0))
    if light is not None:
        out = cv2.multiply(out, cv2.merge([np.asarray(light, np.float32)] * 3))
    if noise is not None:
        out = cv2.max(cv2.add(out, noise), 0.0)   # no negative values: convertScaleAbs takes |x|
    return cv2.convertScaleAbs(out)


def path(n: int, keys, sigma: float = 3.0) -> np.ndarray:
    """A smooth trajectory through keyframes.

    Parameters
    ----------
    n : int
        Number of frames.
    keys : sequence of (frame, value) or (frame, x, y, ...)
        Piecewise-linear between keys, then Gaussian-smoothed so speed changes gradually;
        two consecutive keys with the same value make the object stop.
    sigma : float
        Smoothing in frames (0: piecewise linear).

    Returns
    -------
    ndarray, n or n x k
    """
    keys = np.asarray(keys, float)
    t = np.arange(n)
    cols = [np.interp(t, keys[:, 0], keys[:, j]) for j in range(1, keys.shape[1])]
    out = np.stack(cols, axis=1)
    if sigma > 0:
        r = int(np.ceil(3 * sigma))
        k = np.exp(-0.5 * (np.arange(-r, r + 1) / sigma) ** 2)
        k /= k.sum()
        padded = np.pad(out, ((r, r), (0, 0)), mode="edge")
        out = np.stack([np.convolve(padded[:, j], k, mode="valid") for j in range(out.shape[1])],
                       axis=1)
    return out[:, 0] if out.shape[1] == 1 else out


def steps(n: int, keys, flicker=(), rng: np.random.Generator | None = None) -> np.ndarray:
    """Per-frame gain that jumps at keyframes (lights switched, clouds), with flicker.

    Parameters
    ----------
    keys : sequence of (frame, gain)
        The gain holds from each key's frame to the next one: sudden steps.
    flicker : sequence of (start, stop, amplitude)
        Frames ``start..stop-1`` get a random factor in ``1 +- amplitude`` (a failing tube).
    rng : numpy.random.Generator
        Needed when there is flicker.
    """
    g = np.ones(n)
    for f, v in sorted(keys):
        g[int(f):] = v
    for a, b, amp in flicker:
        g[a:b] *= 1.0 + rng.uniform(-amp, amp, b - a)
    return g


def noise_source(rng: np.random.Generator, sigma: float):
    """A function ``i -> H x W x 3`` noise: random windows of one field (cheap per frame)."""
    field = rng.normal(0.0, sigma, (2 * H, 2 * W, 3)).astype(np.float32)
    offs = rng.integers(0, (H, W), size=(4096, 2))
    return lambda i: field[offs[i, 0]:offs[i, 0] + H, offs[i, 1]:offs[i, 1] + W]


# ---------------------------------------------------------------------- recording
@dataclasses.dataclass
class Rendering:
    """A scenario rendered with everything the tests need.

    Attributes
    ----------
    frames : ndarray, N x H x W x 3 uint8 (BGR)
    targets : dict of str -> N x 4 ndarray
        Exact boxes; the first is the primary target (the clip's ground truth).
    support : ndarray, N x H x W bool
        The primary target's sprite support, hidden parts included.
    visible : ndarray, N x H x W bool
        The part of ``support`` that nothing covers.
    """

    frames: np.ndarray
    targets: dict
    support: np.ndarray
    visible: np.ndarray


class Film:
    """Collects frames, boxes and the primary target's masks while a scenario renders."""

    def __init__(self, n: int, names=("target",)):
        self.frames = np.empty((n, H, W, 3), np.uint8)
        self.support = np.zeros((n, H, W), bool)
        self.visible = np.zeros((n, H, W), bool)
        self.targets = {k: np.zeros((n, 4)) for k in names}

    def record(self, i: int, canvas: Canvas, frame: np.ndarray, **placements: Placement):
        """Store frame ``i``, the boxes of ``placements`` (by target name) and the masks of
        the primary (first) target."""
        self.frames[i] = frame
        for k, p in placements.items():
            self.targets[k][i] = p.box
        p = placements[next(iter(self.targets))]
        if p.roi is not None:          # masks are zero outside the placement's ROI
            self.support[i][p.roi] = p.mask
            self.visible[i][p.roi] = p.mask & (canvas.owner[p.roi] == p.layer)

    def done(self) -> Rendering:
        return Rendering(self.frames, self.targets, self.support, self.visible)


def mask_box(mask: np.ndarray) -> np.ndarray:
    """Extent ``(x, y, w, h)`` of a bool mask's pixels (NaN if empty)."""
    ys, xs = np.nonzero(mask)
    if len(xs) == 0:
        return np.full(4, np.nan)
    return np.array([xs.min(), ys.min(), xs.max() + 1 - xs.min(), ys.max() + 1 - ys.min()], float)
