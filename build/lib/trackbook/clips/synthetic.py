"""Generated sample clips with exact ground truth (SPEC section 3).

A fresh install has no dataset, so the book tracks on clips rendered here. Every clip is
made of photographs that ship inside scikit-image (``skimage.data``: astronaut, chelsea,
coffee, rocket, brick, grass, gravel, ...; none of them needs a download), cut into sprites
and pasted at sub-pixel positions on a textured background. Because we render the target
ourselves, its box is known exactly: it is the axis-aligned extent of the pasted sprite's
support (the pixels where its alpha is at least one half), also when something hides it.

The building blocks are small and reused by every scenario:

* :class:`Sprite` and :class:`Canvas` – a sprite with an alpha mask, and a frame that
  composites sprites (translation, rotation, scale) and remembers which sprite owns
  each pixel, so the visible part of a target is known too;
* :func:`view` – a sub-pixel window on a large background (camera motion, shake);
* :func:`expose` – lighting: global gain, a spatial light map, tint, contrast, noise;
* :func:`path` and :func:`steps` – smooth keyed trajectories and sudden light changes;
* :func:`render` / :func:`render_masks` – a scenario's frames, boxes and target masks
  (``make()`` of each registered sample keeps only what a :class:`Clip` holds).

>>> from trackbook.clips import synthetic
>>> r = synthetic.render("red-cube")
>>> r.frames.shape
(184, 240, 320, 3)
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable

import cv2
import numpy as np

from .clip import ArrayFrames, Clip
from .samples import sample

H, W = 240, 320          # frame size of every sample clip (the papers' 320 x 240)
_SS = 4                  # supersampling factor for drawn shapes (smooth, anti-aliased edges)


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


@functools.lru_cache(maxsize=None)
def _lfw_faces() -> np.ndarray:
    from importlib.resources import files

    try:   # 200 grey 25 x 25 faces, float in [0, 1], shipped in the wheel
        return np.load(str(files("skimage.data") / "lfw_subset.npy"))
    except (ModuleNotFoundError, OSError):
        import skimage.data as data

        return data.lfw_subset()


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


def planks(w: int, h: int, plank_h: int, rng: np.random.Generator,
           length=(90, 190)) -> np.ndarray:
    """A floor or panel of wooden planks cut from the table in the ``coffee`` photograph.

    Every plank is a random window of the wood (grain along the plank) with its own
    brightness and a thin dark joint, so large areas show no repeating tile.
    """
    wood = np.rot90(photo("coffee")[0:400, 495:600]).astype(np.float32)   # 105 x 400
    wood = cv2.resize(wood, (320, 84), interpolation=cv2.INTER_AREA)
    out = np.empty((h, w, 3), np.float32)
    for y in range(0, h, plank_h):
        ph = min(plank_h, h - y)
        x = -int(rng.integers(0, length[0]))
        while x < w:
            n = int(rng.integers(*length))
            ox, oy = int(rng.integers(0, 320 - n)), int(rng.integers(0, 84 - ph))
            a, b = max(x, 0), min(x + n, w)
            out[y:y + ph, a:b] = wood[oy:oy + ph, ox + a - x:ox + b - x] * rng.uniform(0.8, 1.1)
            out[y:y + ph, a:a + 1] *= 0.55
            x += n
        out[y:y + 1] *= 0.55
    return out


def face(index: int, size, skin=(120, 150, 200)) -> np.ndarray:
    """A grey LFW face from ``skimage.data.lfw_subset`` tinted to skin colour, ``size=(w, h)``."""
    g = cv2.resize(_lfw_faces()[index].astype(np.float32), tuple(size),
                   interpolation=cv2.INTER_CUBIC)
    return np.clip(g[..., None] * 1.6, 0, 1.2) * np.float32(skin)


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
    def supersampled(cls, bgr: np.ndarray, alpha: np.ndarray, factor: int = _SS) -> Sprite:
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


def cylinder_shading(w: int, h: int, lo: float = 0.72, hi: float = 1.08,
                     light: float = -0.25) -> np.ndarray:
    """A ``h x w x 1`` shading, darker towards the sides (a rounded body lit from the left)."""
    x = (np.arange(w) + 0.5) / w * 2 - 1 - light
    s = hi - (hi - lo) * np.clip(x, -1.3, 1.3) ** 2 / 1.69
    return np.broadcast_to(s[None, :, None], (h, w, 1)).astype(np.float32)


# ------------------------------------------------------------------------ sprite makers
def figure(height: int, head: np.ndarray, shirt: np.ndarray, trousers: np.ndarray,
           phase: float, swing: float = 1.0) -> Sprite:
    """A person-like figure (head, torso, arms, legs) textured with photo crops.

    Parameters
    ----------
    height : int
        Height of the figure in pixels; the sprite is ``0.5 * height`` wide.
    head, shirt, trousers : ndarray
        BGR textures (any size; resized onto the body parts). ``head`` is a face crop.
    phase : float
        Gait phase in radians: legs and arms swing with ``sin(phase)``.
    swing : float
        Stride amplitude (0 for a figure standing still).

    Returns
    -------
    Sprite
        Facing right; :meth:`Sprite.flipped` faces left.
    """
    h = height * _SS
    w = int(round(0.5 * height)) * _SS
    cx = w / 2
    img = np.zeros((h, w, 3), np.float32)
    alpha = np.zeros((h, w), np.float32)
    shirt_t = cv2.resize(shirt, (w, h), interpolation=cv2.INTER_AREA)
    trousers_t = cv2.resize(trousers, (w, h), interpolation=cv2.INTER_AREA)
    skin = np.float32(cv2.resize(head, (1, 1), interpolation=cv2.INTER_AREA)[0, 0])
    s, leg, arm = np.sin(phase) * swing, 0.11 * h, 0.08 * h

    def part(draw, texture, shade=1.0):
        m = np.zeros((h, w), np.uint8)
        draw(m)
        x, y, bw, bh = cv2.boundingRect(m)       # work on the part's rectangle only
        sel = m[y:y + bh, x:x + bw] > 0
        src = texture[y:y + bh, x:x + bw] if texture.ndim == 3 else texture
        np.copyto(img[y:y + bh, x:x + bw], src * np.float32(shade), where=sel[..., None])
        alpha[y:y + bh, x:x + bw][sel] = 1.0

    def limb(x0, y0, x1, y1, thick):
        p0, p1 = (int(cx + x0), int(y0)), (int(cx + x1), int(y1))
        return lambda m: cv2.line(m, p0, p1, 255, int(thick))

    def foot(x, y):
        return lambda m: cv2.ellipse(m, (int(cx + x + 0.02 * h), int(y)),
                                     (int(0.04 * h), int(0.02 * h)), 0, 0, 360, 255, -1)

    dark = np.float32((30, 30, 35))
    hip, foot_y, sh = 0.05 * h, 0.965 * h, 0.145 * h
    # painter's order: far arm and leg, neck and torso, near leg and arm, then the head.
    # The body is seen from the front, the stride from the side: a readable stylisation.
    for side in (-1, 1):
        near = side > 0
        hand = (side * sh - 0.03 * h * s * side, 0.56 * h)
        part(limb(side * sh, 0.26 * h, *hand, 0.05 * h), shirt_t, 0.95 if near else 0.75)
        part(lambda m, x=hand[0]: cv2.circle(m, (int(cx + x), int(0.57 * h)), int(0.028 * h),
                                             255, -1), skin, 0.95 if near else 0.8)
        part(limb(side * hip, 0.56 * h, side * hip * 0.4 + side * leg * s, 0.94 * h, 0.075 * h),
             trousers_t, 1.0 if near else 0.72)
        part(foot(side * hip * 0.4 + side * leg * s, foot_y), dark)
        if not near:
            part(lambda m: cv2.rectangle(m, (int(cx - 0.03 * h), int(0.17 * h)),
                                         (int(cx + 0.03 * h), int(0.24 * h)), 255, -1),
                 skin, 0.8)
            body = [(-0.09, 0.212), (0.09, 0.212), (0.13, 0.24), (0.14, 0.28), (0.105, 0.58),
                    (-0.105, 0.58), (-0.14, 0.28), (-0.13, 0.24)]
            pts = np.int32([(cx + a * h, b * h) for a, b in body])
            part(lambda m: cv2.fillConvexPoly(m, pts, 255), shirt_t)
    # the head: the face crop fills an ellipse (slightly wider face texture is cropped by it)
    hw, hh = int(0.15 * h), int(0.2 * h)
    head_t = np.zeros((h, w, 3), np.float32)
    hx0, hy0 = int(cx - hw / 2), int(0.008 * h)
    head_t[hy0:hy0 + hh, hx0:hx0 + hw] = cv2.resize(head, (hw, hh), interpolation=cv2.INTER_AREA)
    part(lambda m: cv2.ellipse(m, (int(cx), hy0 + hh // 2), (hw // 2, hh // 2), 0, 0, 360,
                               255, -1), head_t)
    img *= cylinder_shading(w, h)
    return Sprite.supersampled(np.clip(img, 0, 255), alpha)


def walker(height: int, head, shirt, trousers, n_phases: int = 8):
    """Gait cycle of :func:`figure`: ``(right, left)`` lists of ``n_phases`` sprites each.

    Index 0 is the standing pose (legs together), used while the figure stops.
    """
    right = [figure(height, head, shirt, trousers, 2 * np.pi * k / n_phases)
             for k in range(n_phases)]
    return right, [s.flipped() for s in right]


def walk_poses(x: np.ndarray, world_speed: np.ndarray | None = None, stride: float = 14.0,
               n_phases: int = 8):
    """Pose index and facing per frame for a walker at positions ``x``.

    The gait phase advances with the distance walked (``world_speed`` if the camera moves),
    the pose is the standing one when nearly still, and the figure keeps its facing until it
    clearly walks the other way (no flicker when it stops).
    """
    v = np.gradient(x) if world_speed is None else world_speed
    phase = np.cumsum(np.abs(v)) / stride * 2 * np.pi
    idx = np.round(phase / (2 * np.pi) * n_phases).astype(int) % n_phases
    idx[np.abs(v) < 0.3] = 0
    facing = np.empty(len(v), bool)   # True: facing right
    cur = v[np.argmax(np.abs(v) > 0.3)] >= 0 if np.any(np.abs(v) > 0.3) else True
    for i, vi in enumerate(v):
        if abs(vi) > 0.3:
            cur = vi > 0
        facing[i] = cur
    return idx, facing


def ellipse_sprite(texture: np.ndarray, rim: float = 0.9) -> Sprite:
    """An elliptical cut of ``texture`` (a face), darkened a little at the rim."""
    h, w = texture.shape[:2]
    big = cv2.resize(texture, (w * _SS, h * _SS), interpolation=cv2.INTER_LINEAR)
    m = np.zeros((h * _SS, w * _SS), np.uint8)
    cv2.ellipse(m, (w * _SS // 2, h * _SS // 2), (w * _SS // 2 - 1, h * _SS // 2 - 1),
                0, 0, 360, 255, -1)
    yy, xx = np.mgrid[0:h * _SS, 0:w * _SS]
    r2 = ((xx - w * _SS / 2) / (w * _SS / 2)) ** 2 + ((yy - h * _SS / 2) / (h * _SS / 2)) ** 2
    shade = (1.0 - (1.0 - rim) * np.clip(r2, 0, 1) ** 2)[..., None]
    return Sprite.supersampled(big * shade, (m > 0).astype(np.float32))


def ball_sprite(radius: float, colour, texture: np.ndarray | None = None) -> Sprite:
    """A shaded ball: Lambert shading lit from the upper left, a specular highlight."""
    n = int(np.ceil(2 * radius)) * _SS
    yy, xx = (np.mgrid[0:n, 0:n] + 0.5) / n * 2 - 1
    r2 = xx ** 2 + yy ** 2
    z = np.sqrt(np.clip(1 - r2, 0, 1))
    light = np.array([-0.45, -0.55, 0.7])
    lam = np.clip(xx * light[0] + yy * light[1] + z * light[2], 0, 1)
    col = np.float32(colour) * (0.3 + 0.8 * lam)[..., None]
    if texture is not None:  # felt: a little of a photo's grain
        tex = cv2.resize(texture, (n, n), interpolation=cv2.INTER_AREA)
        col *= 0.85 + 0.3 * (tex / 255.0)
    col += 255 * 0.6 * np.clip(lam, 0, 1)[..., None] ** 40
    return Sprite.supersampled(col, (r2 <= 1).astype(np.float32))


def shadow_sprite(w: int, h: int, blur: float = 0.25) -> Sprite:
    """A soft dark ellipse (a shadow on the ground); paste it with ``opaque=False``."""
    yy, xx = (np.mgrid[0:h, 0:w] + 0.5)
    r2 = ((xx - w / 2) / (w / 2)) ** 2 + ((yy - h / 2) / (h / 2)) ** 2
    a = np.clip((1 - r2) / blur, 0, 1)
    a[h // 2, w // 2] = max(a[h // 2, w // 2], 0.5)   # keep a non-empty support
    return Sprite(np.zeros((h, w, 3), np.float32), a)


def rect_sprite(img: np.ndarray, border: int = 0, border_colour=(40, 40, 40),
                radius: float = 0.0) -> Sprite:
    """An opaque rectangle showing ``img``, with an optional frame and rounded corners.

    Rounded corners (``radius`` in px) keep the box of a rotated sprite within a pixel of
    its rendered mask: a sharp corner can poke between pixel centres.
    """
    if border:
        img = cv2.copyMakeBorder(img, border, border, border, border, cv2.BORDER_CONSTANT,
                                 value=tuple(float(c) for c in border_colour))
    h, w = img.shape[:2]
    if radius <= 0:
        return Sprite(img, np.ones((h, w), np.float32))
    r = int(round(radius * _SS))
    m = np.zeros((h * _SS, w * _SS), np.uint8)
    cv2.rectangle(m, (r, 0), (w * _SS - 1 - r, h * _SS - 1), 255, -1)
    cv2.rectangle(m, (0, r), (w * _SS - 1, h * _SS - 1 - r), 255, -1)
    for cx in (r, w * _SS - 1 - r):
        for cy in (r, h * _SS - 1 - r):
            cv2.circle(m, (cx, cy), r, 255, -1)
    big = cv2.resize(img, (w * _SS, h * _SS), interpolation=cv2.INTER_NEAREST)
    return Sprite.supersampled(big, m.astype(np.float32) / 255)


# ------------------------------------------------------------------ rendering / registry
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


class _Film:
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


@dataclasses.dataclass(frozen=True)
class _Meta:
    fps: float
    attributes: tuple
    description: str


_SCENES: dict[str, tuple[Callable[[], Rendering], _Meta]] = {}


def _scenario(name: str, paper: str, fps: float, attributes: tuple, description: str):
    """Register ``render_fn() -> Rendering`` as sample clip ``name`` (see ``samples.sample``)."""
    description = " ".join(description.split())

    def deco(render_fn):
        meta = _Meta(fps, tuple(attributes), description)
        _SCENES[name] = (render_fn, meta)

        def make() -> Clip:
            r = render_fn()
            r.frames.setflags(write=False)
            return Clip(name, ArrayFrames(r.frames), next(iter(r.targets.values())),
                        fps=meta.fps, targets=r.targets, description=meta.description,
                        attributes=meta.attributes, source="sample")

        make.__name__ = make.__qualname__ = f"make_{name.replace('-', '_')}"
        make.__doc__ = f"Build the sample clip {name!r}: {description}"
        sample(name, paper, description)(make)
        return render_fn
    return deco


def render(name: str) -> Rendering:
    """Render sample clip ``name`` with its target masks (not cached; see ``samples.build``)."""
    if name not in _SCENES:
        raise ValueError(f"unknown generated clip {name!r}; known: {', '.join(_SCENES)}")
    return _SCENES[name][0]()


def render_masks(name: str, visible: bool = False) -> np.ndarray:
    """N x H x W bool masks of the primary target of clip ``name``.

    ``visible=False`` gives the sprite's full support (its box is the ground truth, also
    while occluded); ``visible=True`` only the pixels nothing is drawn over.
    """
    r = render(name)
    return r.visible if visible else r.support


def mask_box(mask: np.ndarray) -> np.ndarray:
    """Extent ``(x, y, w, h)`` of a bool mask's pixels (NaN if empty)."""
    ys, xs = np.nonzero(mask)
    if len(xs) == 0:
        return np.full(4, np.nan)
    return np.array([xs.min(), ys.min(), xs.max() + 1 - xs.min(), ys.max() + 1 - ys.min()], float)


# ------------------------------------------------------------- backgrounds of the scenes
def _corridor(width: int, rng: np.random.Generator) -> np.ndarray:
    """A long corridor: painted wall, wooden wainscot, doors and framed photographs above a
    gravel floor; ``H x width``."""
    wall_h, panel = 172, 112
    bg = np.empty((H, width, 3), np.float32)
    plaster = cv2.GaussianBlur(crop("gravel", 0, 0, 512, 512, (256, 256)), (0, 0), 1.2)
    bg[:panel] = tile(duotone(plaster, (150, 170, 185), (180, 198, 210)), width, panel)
    bg[panel:wall_h] = planks(width, wall_h - panel, 12, rng) * 0.8
    bg[panel - 3:panel] = (60, 75, 95)                         # dado rail
    floor = duotone(crop("gravel", 0, 0, 512, 256, (512, 128)), (60, 70, 78), (130, 140, 150))
    bg[wall_h:] = tile(floor, width, H - wall_h)
    bg[wall_h:] *= np.linspace(0.8, 1.1, H - wall_h, dtype=np.float32)[:, None, None]
    bg[wall_h - 6:wall_h] = (45, 50, 55)                      # skirting board
    door = np.rot90(planks(wall_h - 36, 60, 15, rng, (60, 130)))
    pictures = [("rocket", 150, 60, 500, 420), ("chelsea", 60, 0, 420, 300),
                ("hubble_deep_field", 0, 0, 500, 400), ("coffee", 100, 0, 500, 400)]
    x, k = 40, 0
    while x < width - 80:
        if k % 3 == 2:   # a door: wooden planks in a dark frame, with a handle
            bg[30:wall_h - 6, x:x + 60] = door * 0.85
            bg[30:33, x:x + 60] = (35, 40, 45)
            bg[30:wall_h - 6, x:x + 3] = bg[30:wall_h - 6, x + 57:x + 60] = (35, 40, 45)
            cv2.circle(bg, (x + 50, 105), 3, (150, 170, 180), -1)
            x += 60 + int(rng.integers(50, 90))
        else:            # a framed photograph
            n, *c = pictures[k % len(pictures)]
            bg[30:90, x:x + 80] = rect_sprite(crop(n, *c, (72, 52)), 4, (40, 45, 55)).bgr
            x += 80 + int(rng.integers(50, 100))
        k += 1
    return bg


def _lamps(width: int, spacing: float, x0: float) -> np.ndarray:
    """Light map of ceiling lamps every ``spacing`` px: pools of light on dark walls."""
    x = np.arange(width, dtype=np.float32)
    d = (x - x0 + spacing / 2) % spacing - spacing / 2
    pool = np.exp(-0.5 * (d / 55.0) ** 2)
    y = np.arange(H, dtype=np.float32)[:, None]
    return (0.22 + 0.95 * pool[None, :] * (0.55 + 0.45 * np.exp(-y / 120.0))).astype(np.float32)


def _outdoor() -> np.ndarray:
    """A sunny brick wall above a lawn: the background of the occluder clip."""
    bg = np.empty((H, W, 3), np.float32)
    bg[:150] = duotone(crop("brick", 0, 100, 512, 340, (W, 150)), (100, 115, 140),
                       (175, 190, 210))
    bg[150:] = duotone(crop("grass", 0, 0, 512, 144, (W, H - 150)), (30, 80, 45),
                       (90, 170, 120))
    bg[146:152] = (70, 80, 90)
    return bg


def _shelves(rng: np.random.Generator) -> np.ndarray:
    """Shelves crowded with product boxes cut from colourful photographs."""
    bg = tile(duotone(crop("brick", 0, 0, 512, 512, (200, 200)), (30, 32, 38), (60, 62, 70)),
              W, H)
    sources = [("rocket", 0, 0, 640, 427), ("coffee", 0, 0, 600, 400),
               ("chelsea", 0, 0, 451, 300), ("astronaut", 0, 0, 512, 512),
               ("immunohistochemistry", 0, 0, 512, 512), ("retina", 200, 200, 1200, 1200),
               ("colorwheel", 0, 0, 370, 370), ("hubble_deep_field", 0, 0, 1000, 872),
               ("motorcycle", 0, 0, 741, 500)]
    imgs = [photo(s[0])[s[2]:s[4], s[1]:s[3]] for s in sources]
    wood = tile(crop("coffee", 440, 0, 600, 400, (160, 400)).transpose(1, 0, 2), W, 10)
    for top in (2, 62, 122, 182):
        floor = top + 52
        x = int(rng.integers(0, 8))
        while x < W:
            bw, bh = int(rng.integers(14, 34)), int(rng.integers(26, 50))
            img = imgs[int(rng.integers(len(imgs)))]
            # a random window of a random photo, so every product looks different
            cw = int(rng.integers(img.shape[1] // 6, img.shape[1] // 2))
            ch = min(int(cw * bh / bw), img.shape[0] - 1)
            cx0 = int(rng.integers(0, img.shape[1] - cw))
            cy0 = int(rng.integers(0, img.shape[0] - ch))
            box = cv2.resize(img[cy0:cy0 + ch, cx0:cx0 + cw], (bw, bh),
                             interpolation=cv2.INTER_AREA).astype(np.float32)
            box *= cylinder_shading(bw, bh, 0.7, 1.05)
            box *= np.linspace(1.05, 0.85, bh, dtype=np.float32)[:, None, None]
            y0 = floor - bh
            x1 = min(x + bw, W)
            bg[y0:floor, x:x1] = box[:, :x1 - x]
            bg[y0:floor, x:x + 1] = bg[y0:floor, x:x + 1] * 0.5
            x += bw + int(rng.integers(0, 4))
        board = bg[floor:floor + 8]                 # the lowest board runs off the picture
        board[:] = wood[:len(board)] * 0.9
        bg[floor + 8:floor + 10] = 25
    return bg


# ---------------------------------------------------------------------------- scenarios
@functools.lru_cache(maxsize=None)   # shared by clips; sprites are never modified
def _astronaut_walker(height: int):
    """The robot clips' target: the astronaut's face and orange suit, dark trousers."""
    return walker(height, crop("astronaut", 168, 22, 288, 172),
                  crop("astronaut", 50, 250, 160, 480),
                  duotone(crop("camera", 60, 200, 200, 450), (35, 25, 20), (95, 75, 65)))


@functools.lru_cache(maxsize=None)   # shared by clips; sprites are never modified
def _distractor_walkers(height: int):
    """Two passers-by dressed in similar colours (red-orange; dark trousers)."""
    suit = crop("astronaut", 200, 380, 300, 500)   # more of the orange suit, other folds
    red = crop("coffee", 120, 100, 300, 380)       # the red-brown saucer: close in colour
    dark = duotone(crop("gravel", 0, 0, 200, 400), (40, 30, 25), (90, 80, 70))
    return [walker(height, face(25, (30, 40)), suit * 0.9, dark),
            walker(height, face(37, (30, 40)), red, dark)]


def _robot(night: bool) -> Rendering:
    """The robot's side view: the robot follows the person with a lag (ego-motion)."""
    n = 150
    rng = np.random.default_rng(1000 + night)
    # the person's path along the corridor (world x): walk, slow, stop, turn back, stop, run
    xw = path(n, [(0, 0), (38, 105), (52, 132), (62, 136), (68, 132), (98, 48), (106, 40),
                  (112, 42), (149, 215)], sigma=3)
    # the robot follows the person (exponential lag): the view scrolls, the target drifts
    cam = np.empty(n)
    cam[0] = xw[0]
    for i in range(1, n):
        cam[i] = cam[i - 1] + 0.07 * (xw[i] - cam[i - 1])
    fx = xw - cam + 150                                       # target centre in the frame
    margin = 40
    scene_w = int(np.ceil(cam.max() - cam.min())) + W + 2 * margin
    world0 = cam.min() - 150 - margin                         # world x of scene column 0
    bg = _corridor(scene_w, rng)
    light = _lamps(scene_w, 210.0, 120.0) if night else None
    right, left = _astronaut_walker(100)
    idx, facing = walk_poses(xw)
    others = _distractor_walkers(92)
    # passers-by (world x0, speed, start frame): each crosses the target's region
    passers = [(cam[8] + 340, -2.6, 8), (cam[55] - 60, 3.0, 55), (cam[100] + 360, -3.2, 100)]
    gain = steps(n, [(0, 1.0), (34, 0.55), (58, 1.3), (84, 0.75), (121, 1.15)],
                 flicker=[(60, 68, 0.3), (110, 121, 0.35)], rng=rng)
    noise = noise_source(rng, 6.0) if night else None
    tint = np.float32([1.0, 0.8, 0.64]) if night else np.float32([1.0, 1.0, 1.0])  # dim, bluish
    film = _Film(n)
    for i in range(n):
        # frame column c shows world x = c + cam - 150; the lamps are fixed to the walls
        canvas = Canvas(view(bg, cam[i] - 150 - world0, 0), copy=False)
        lit = view(light, cam[i] - 150 - world0, 0) if night else None
        for k, (x0, v, f0) in enumerate(passers):
            if i < f0:
                continue
            px = x0 + v * (i - f0) - cam[i] + 150
            if -40 < px < W + 40:
                r, lft = others[k % 2]
                pose = int((i - f0) * abs(v) / 14 * 8) % 8
                canvas.paste((r if v > 0 else lft)[pose], (px, 196 - 46))
        bob = 1.2 * abs(np.sin(np.pi * idx[i] / 4)) if idx[i] else 0.0
        target = canvas.paste((right if facing[i] else left)[idx[i]], (fx[i], 212 - 50 - bob))
        frame = expose(canvas.img, gain[i] * tint, light=lit,
                       contrast=0.55 if night else 1.0,
                       noise=noise(i) if night else None)
        film.record(i, canvas, frame, target=target)
    return film.done()


_ROBOT = """Side view from a camera on a mobile robot that follows a person down a corridor
(the scenario of Lee et al. 2012). The robot lags behind the person, so the wall and its doors and photographs
scroll sideways (camera motion) while the person, wearing the astronaut's orange suit, walks
with changing speed, slows to a halt around frame 62 and turns back, pauses again around
frames 104-112 and then hurries away. {light} Three passers-by dressed in similar
red-orange colours cross behind the target (from frames 8, 55 and 100)."""


@_scenario("robot-corridor-day", "000", 30.0, ("IV", "CM", "BC", "DEF", "OPR"),
           _ROBOT.format(light="The lights change abruptly (dimmer at frame 34, much brighter "
                               "at 58, dim at 84, bright at 121) and flicker at frames "
                               "60-67 and 110-120."))
def _robot_day() -> Rendering:
    return _robot(night=False)


@_scenario("robot-corridor-night", "000", 30.0, ("IV", "CM", "BC", "DEF", "OPR"),
           _ROBOT.format(light="At night: dark, low-contrast, bluish and noisy frames, lit "
                               "by pools of lamp light that the person walks through, with "
                               "the same abrupt steps and flicker of the lights as the day "
                               "clip."))
def _robot_night() -> Rendering:
    return _robot(night=True)


@_scenario("patterned-object", "001", 30.0, ("BC", "CM", "IPR", "SV"), """
A multicoloured object, a photograph of an espresso cup and saucer mounted as a small
board, glides over a wooden plank table of the same browns and reds (the scenario of Kim et al. 2016). A hand-held
camera shakes (random shifts of up to 4 px every frame), the object turns in the image
plane by up to 10 degrees, and it comes closer and recedes (scale 1.0 -> 1.3 -> 0.85 ->
1.1, i.e. about 30 % size change).""")
def _patterned_object() -> Rendering:
    n = 150
    rng = np.random.default_rng(1001)
    m = 8                                                   # shake margin of the table
    table = planks(W + 2 * m, H + 2 * m, 28, rng, (120, 260)) * np.float32(0.95)
    obj = rect_sprite(crop("coffee", 110, 20, 470, 350, (56, 52)), 3, (70, 110, 170), 3.0)
    shadow = shadow_sprite(70, 64, 0.6)
    t = np.arange(n)
    centre = np.c_[160 + 80 * np.sin(2 * np.pi * t / 150 * 1.3),
                   120 + 42 * np.sin(2 * np.pi * t / 150 * 2 + 0.6)]
    angle = 10 * np.sin(2 * np.pi * t / 70)
    scale = path(n, [(0, 1.0), (50, 1.3), (100, 0.85), (149, 1.1)], sigma=6)
    shake = np.clip(rng.normal(0, 1.8, (n, 2)), -4, 4)
    film = _Film(n)
    for i in range(n):
        canvas = Canvas(view(table, m + shake[i, 0], m + shake[i, 1]))
        c = centre[i] - shake[i]            # the camera moved: the scene moves the other way
        canvas.paste(shadow, c + 3 * scale[i], angle[i], scale[i], opacity=0.55, opaque=False)
        p = canvas.paste(obj, c, angle[i], scale[i])
        film.record(i, canvas, expose(canvas.img), target=p)
    return film.done()


@_scenario("red-cube", "002", 25.0, ("FM",), """
A small red cube (24 x 24 px) with a printed digit slides over a concrete floor (paper
002, 320 x 240, 184 frames at 25 fps). It moves slowly and smoothly (about 1.6 px per
frame) along a gentle curve until, at frames 139-142 (the steps into frames 138 to 142,
counting from 0), it suddenly accelerates to about 9 px per frame and turns by about 140
degrees, as in the paper's clip; then it continues at about 2 px per frame in the new
direction.""")
def _red_cube() -> Rendering:
    n = 184
    rng = np.random.default_rng(1002)
    floor = tile(duotone(crop("gravel", 0, 0, 512, 512, (320, 320)), (105, 115, 125),
                         (175, 185, 190)), W, H)
    floor *= np.linspace(0.9, 1.08, H, dtype=np.float32)[:, None, None]
    # the cube: front face with a digit, lit top face and shaded right face (drawn 4x)
    s, b = 20 * _SS, 4 * _SS
    img = np.zeros((s + b, s + b, 3), np.float32)
    alpha = np.zeros((s + b, s + b), np.float32)
    red = np.float32((35, 35, 190))
    top = np.int32([(0, b), (b, 0), (s + b, 0), (s, b)])
    side = np.int32([(s, b), (s + b, 0), (s + b, s), (s, s + b)])
    for poly, shade in ((top, 1.25), (side, 0.6)):
        m = np.zeros(alpha.shape, np.uint8)
        cv2.fillConvexPoly(m, poly, 255)
        img[m > 0] = red * shade
        alpha[m > 0] = 1
    img[b:, :s] = red * np.linspace(1.05, 0.85, s, dtype=np.float32)[:, None, None]
    alpha[b:, :s] = 1
    ink = np.zeros(alpha.shape, np.uint8)     # OpenCV draws text on 8-bit images only
    cv2.putText(ink, "7", (b + 3 * _SS, s + b - 4 * _SS), cv2.FONT_HERSHEY_SIMPLEX, 2.0,
                255, 3 * _SS, cv2.LINE_AA)
    k = (ink / np.float32(255))[..., None]
    img = img * (1 - k) + k * np.float32((235, 240, 245))
    cube = Sprite.supersampled(img, alpha)
    shadow = shadow_sprite(30, 30, 0.5)
    # velocity: slow heading that curves gently; a burst of speed and a turn at 138..142
    heading = np.deg2rad(path(n, [(0, 15), (60, 40), (100, 5), (137, 30)], sigma=8))
    speed = np.full(n, 1.6) + 0.2 * np.sin(np.arange(n) / 9)
    speed[138:143] = [8.0, 9.5, 10.0, 9.5, 8.5]
    speed[143:] = 2.1
    heading[138:] = np.deg2rad(-150)
    heading[143:] += np.deg2rad(path(n - 143, [(0, 0), (40, -25)], sigma=4))
    step = np.c_[np.cos(heading), np.sin(heading)] * speed[:, None]
    step[0] = 0
    step += rng.normal(0, 0.05, step.shape)                 # a hand-pushed, not robotic, cube
    centre = np.array([45.0, 55.0]) + np.cumsum(step, axis=0)
    film = _Film(n)
    for i in range(n):
        canvas = Canvas(floor)
        canvas.paste(shadow, centre[i] + (3, 4), opacity=0.5, opaque=False)
        p = canvas.paste(cube, centre[i])
        film.record(i, canvas, expose(canvas.img), target=p)
    return film.done()


@_scenario("yellow-ball", "002", 25.0, ("FM", "LR"), """
A small yellow ball (18 px across) bounces fast across a lawn in parabolic arcs,
rebounding from the ground and from the side of the picture (Lee 2015's "YellowBall").
Its speed reaches 12 px per frame near the ground and drops near the top of each arc;
its soft shadow follows it on the grass.""")
def _yellow_ball() -> Rendering:
    n = 120
    rng = np.random.default_rng(1003)
    lawn = duotone(crop("grass", 0, 64, 512, 448, (W, H)), (25, 85, 40), (95, 185, 125))
    lawn *= np.linspace(0.75, 1.1, H, dtype=np.float32)[:, None, None]
    ball = ball_sprite(9, (40, 215, 245), crop("gravel", 0, 0, 100, 100))
    shadow = shadow_sprite(24, 8, 0.8)
    ground, g, r = 222.0, 0.55, 9.0
    pos = np.empty((n, 2))
    x, y, vx, vy = 20.0, 70.0, 4.6, 0.0
    for i in range(n):                           # ballistic flight, 4 sub-steps per frame
        pos[i] = x, y
        for _ in range(4):
            vy += g / 4
            x, y = x + vx / 4, y + vy / 4
            if y > ground - r:
                y, vy = 2 * (ground - r) - y, -abs(vy) * 0.92
            if not r + 4 < x < W - r - 4:
                x, vx = np.clip(x, r + 4, W - r - 4), -vx * 0.95
    pos += rng.normal(0, 0.03, pos.shape)
    film = _Film(n)
    for i in range(n):
        canvas = Canvas(lawn)
        height = ground - r - pos[i, 1]
        canvas.paste(shadow, (pos[i, 0] + 2, ground - 2), scale=1 - height / 400,
                     opacity=0.45 - height / 600, opaque=False)
        p = canvas.paste(ball, pos[i])
        film.record(i, canvas, expose(canvas.img), target=p)
    return film.done()


@functools.lru_cache(maxsize=None)   # shared by clips; sprites are never modified
def _flag_walker(height: int):
    """The occluder clip's walker: a shirt cut from the astronaut's flag, blue jeans."""
    jeans = duotone(crop("brick", 0, 0, 300, 512), (90, 45, 25), (175, 120, 85))
    return walker(height, face(31, (30, 40), (115, 145, 200)),
                  crop("astronaut", 0, 120, 75, 330), jeans)


@_scenario("occluder", "003", 25.0, ("OCC", "DEF"), """
A person in a striped shirt (cut from the flag in the astronaut photo) walks from left to
right along a brick wall and passes behind a tree trunk (the scenario of Cho and Kang 2005). The ground truth
stays the person's true box while hidden (OTB convention): the trunk starts to cover the
person at frame 53, hides more than 80 % of it at frames 64-82 and all of it at frames
71-76, and releases it at frame 94 (frames counted from 0).""")
def _occluder() -> Rendering:
    n = 140
    rng = np.random.default_rng(1004)
    bg = _outdoor()
    trunk_w, trunk_x = 50, 150
    bark = duotone(crop("gravel", 0, 0, 120, 512, (trunk_w * _SS, H * _SS)), (20, 35, 50),
                   (75, 100, 120))
    bark = cv2.resize(bark, (trunk_w * _SS, H * _SS), interpolation=cv2.INTER_AREA)
    bark *= cylinder_shading(trunk_w * _SS, H * _SS, 0.45, 1.1, -0.3)
    tree = Sprite.supersampled(bark, np.ones(bark.shape[:2], np.float32))
    right, left = _flag_walker(96)
    x = path(n, [(0, 30), (60, 150), (66, 160), (100, 228), (139, 292)], sigma=4)
    x += rng.normal(0, 0.02, n)
    idx, facing = walk_poses(x)
    film = _Film(n)
    for i in range(n):
        canvas = Canvas(bg)
        p = canvas.paste((right if facing[i] else left)[idx[i]], (x[i], 222 - 48))
        canvas.paste(tree, (trunk_x + trunk_w / 2, H / 2))
        film.record(i, canvas, expose(canvas.img, 1.05), target=p)
    return film.done()


@_scenario("shelves", "003", 25.0, ("BC", "DEF", "OPR"), """
A person in an orange suit walks back and forth in front of shelves crowded with
colourful boxes (the scenario of Cho and Kang 2005): reds, oranges and skin tones in the clutter resemble the
target's colours. The person walks right, pauses and turns at frames 40-55, walks left,
pauses and turns again at 100-115, then walks right once more.""")
def _shelves_clip() -> Rendering:
    n = 160
    rng = np.random.default_rng(1005)
    bg = _shelves(rng)
    right, left = _astronaut_walker(150)
    x = path(n, [(0, 60), (40, 205), (55, 210), (100, 85), (115, 80), (159, 255)], sigma=4)
    idx, facing = walk_poses(x, stride=20)
    film = _Film(n)
    for i in range(n):
        canvas = Canvas(bg)
        p = canvas.paste((right if facing[i] else left)[idx[i]], (x[i], 236 - 75))
        film.record(i, canvas, expose(canvas.img), target=p)
    return film.done()


@_scenario("two-faces", "003", 30.0, ("OCC", "BC"), """
Two faces, the astronaut's (face1, the ground truth) and the cat's from "chelsea"
(face2), drift towards each other in front of a blurred garage, cross and overlap with
the cat in front (it partly hides face1 at frames 50-76) and separate again (Cho and Kang 2005's
multi-target experiment). Both boxes are given in Clip.targets.""")
def _two_faces() -> Rendering:
    n = 120
    bg = crop("motorcycle", 40, 0, 707, 500, (W, H))
    bg = cv2.GaussianBlur(bg, (0, 0), 2.0) * np.float32(0.9)
    f1 = ellipse_sprite(crop("astronaut", 170, 40, 285, 185, (48, 60)))
    f2 = ellipse_sprite(crop("chelsea", 95, 20, 375, 295, (60, 58)))
    t = np.arange(n)
    c1 = np.c_[path(n, [(0, 50), (119, 255)], sigma=0), 108 + 7 * np.sin(t / 9)]
    c2 = np.c_[path(n, [(0, 270), (119, 60)], sigma=0), 128 + 6 * np.cos(t / 11)]
    s2 = 1 + 0.12 * np.exp(-0.5 * ((t - 60) / 18) ** 2)   # the cat comes closer as it passes
    film = _Film(n, names=("face1", "face2"))
    for i in range(n):
        canvas = Canvas(bg)
        p1 = canvas.paste(f1, c1[i], angle=4 * np.sin(i / 13))
        p2 = canvas.paste(f2, c2[i], scale=s2[i])
        film.record(i, canvas, expose(canvas.img), face1=p1, face2=p2)
    return film.done()


# ---------------------------------------------------------------- lost-and-found test clip
def leave_and_return(n_before: int = 12, n_absent: int = 18, n_after: int = 20,
                     seed: int = 0) -> Clip:
    """A clip whose target leaves the view and comes back somewhere else (issue 13's probe).

    A textured patch of the astronaut photograph drifts right over a blurred gravel
    background for ``n_before`` frames, is out of view for ``n_absent`` frames (ground truth
    NaN: nothing of it is in the frame) and reappears at x = 62, left of where it left, for
    ``n_after`` frames, drifting slowly. The background has a little sensor noise so no two
    frames are identical. Not a registered sample: the lost-target tests build it.
    """
    rng = np.random.default_rng(seed)
    n = n_before + n_absent + n_after
    bg = cv2.GaussianBlur(crop("gravel", 0, 0, 512, 384, (W, H)), (0, 0), 3.0)
    bg = expose(bg, gain=0.8)
    target = rect_sprite(crop("astronaut", 150, 20, 330, 260, (40, 52)), border=2,
                         border_colour=(30, 30, 200))
    frames = np.empty((n, H, W, 3), np.uint8)
    gt = np.full((n, 4), np.nan)
    for i in range(n):
        canvas = Canvas(bg)
        if i < n_before:
            p = canvas.paste(target, (150 + 2.0 * i, 120 + np.sin(i / 3)))
            gt[i] = p.box
        elif i >= n_before + n_absent:
            k = i - n_before - n_absent
            p = canvas.paste(target, (62 + 22 + 1.0 * k, 110))
            gt[i] = p.box
        noisy = canvas.img + rng.normal(0, 2.0, canvas.img.shape).astype(np.float32)
        frames[i] = np.clip(noisy, 0, 255).astype(np.uint8)
    frames.setflags(write=False)
    return Clip("leave-and-return", ArrayFrames(frames), gt, fps=30.0,
                description="the target leaves the view and comes back elsewhere",
                attributes=("OV",), source="generated")
