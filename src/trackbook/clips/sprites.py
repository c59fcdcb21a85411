"""Sprite makers of the generated sample clips: planks, faces, walking figures, balls,
shadows and framed pictures, all cut from photographs that ship with scikit-image.

They build on the compositing engine of :mod:`trackbook.clips.rendering`.
"""

from __future__ import annotations

import functools

import cv2
import numpy as np

from .rendering import SS, Sprite, photo


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


@functools.lru_cache(maxsize=None)
def _lfw_faces() -> np.ndarray:
    from importlib.resources import files

    try:   # 200 grey 25 x 25 faces, float in [0, 1], shipped in the wheel
        return np.load(str(files("skimage.data") / "lfw_subset.npy"))
    except (ModuleNotFoundError, OSError):
        import skimage.data as data

        return data.lfw_subset()


def face(index: int, size, skin=(120, 150, 200)) -> np.ndarray:
    """A grey LFW face from ``skimage.data.lfw_subset`` tinted to skin colour, ``size=(w, h)``."""
    g = cv2.resize(_lfw_faces()[index].astype(np.float32), tuple(size),
                   interpolation=cv2.INTER_CUBIC)
    return np.clip(g[..., None] * 1.6, 0, 1.2) * np.float32(skin)


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
    h = height * SS
    w = int(round(0.5 * height)) * SS
    cx = w / 2
    img = np.zeros((h, w, 3), np.float32)
    alpha = np.zeros((h, w), np.float32)
    shirt_t = cv2.resize(shirt, (w, h), interpolation=cv2.INTER_AREA)
    trousers_t = cv2.resize(trousers, (w, h), interpolation=cv2.INTER_AREA)
    skin = np.float32(cv2.resize(head, (1, 1), interpolation=cv2.INTER_AREA)[0, 0])
    s, leg = np.sin(phase) * swing, 0.11 * h

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
            part(lambda m: cv2.fillConvexPoly(m, pts, 255), shirt_t)  # noqa: B023 (called at once)
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
    big = cv2.resize(texture, (w * SS, h * SS), interpolation=cv2.INTER_LINEAR)
    m = np.zeros((h * SS, w * SS), np.uint8)
    cv2.ellipse(m, (w * SS // 2, h * SS // 2), (w * SS // 2 - 1, h * SS // 2 - 1),
                0, 0, 360, 255, -1)
    yy, xx = np.mgrid[0:h * SS, 0:w * SS]
    r2 = ((xx - w * SS / 2) / (w * SS / 2)) ** 2 + ((yy - h * SS / 2) / (h * SS / 2)) ** 2
    shade = (1.0 - (1.0 - rim) * np.clip(r2, 0, 1) ** 2)[..., None]
    return Sprite.supersampled(big * shade, (m > 0).astype(np.float32))


def ball_sprite(radius: float, colour, texture: np.ndarray | None = None) -> Sprite:
    """A shaded ball: Lambert shading lit from the upper left, a specular highlight."""
    n = int(np.ceil(2 * radius)) * SS
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
    r = int(round(radius * SS))
    m = np.zeros((h * SS, w * SS), np.uint8)
    cv2.rectangle(m, (r, 0), (w * SS - 1 - r, h * SS - 1), 255, -1)
    cv2.rectangle(m, (0, r), (w * SS - 1, h * SS - 1 - r), 255, -1)
    for cx in (r, w * SS - 1 - r):
        for cy in (r, h * SS - 1 - r):
            cv2.circle(m, (cx, cy), r, 255, -1)
    big = cv2.resize(img, (w * SS, h * SS), interpolation=cv2.INTER_NEAREST)
    return Sprite.supersampled(big, m.astype(np.float32) / 255)
