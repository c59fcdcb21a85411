"""Randomised short scenes in which the target disappears: the calibration set of the
failure rule (:mod:`trackbook.trackers.failure`).

Each scene is drawn from a seed: frame size (160 x 120 to 320 x 240), length (40-80 frames),
background (a window of one of the photographs bundled with scikit-image, sometimes
recoloured or mirror-tiled), target (a framed picture, an oval or a shaded ball cut from
another photograph), its size and speed, and when and how the event happens. Seven kinds:

``exit``
    the target leaves across one of the four edges and comes back across a random edge;
``occlusion``
    a panel cut from another photograph slides over the target, covers it whole, slides off;
``cut``
    the camera cuts to another background without the target, which enters later;
``fade``
    the picture fades to black and back;
``shrink``
    the target shrinks below 4 px and vanishes, then grows back;
``blur``
    heavy motion or defocus blur for some frames (the target stays present);
``lookalike``
    the target is covered, and a copy with the same colours (its mirror image) appears
    elsewhere and stays.

Ground truth is NaN, and ``absent`` True, on the frames where no part of the target is in
view: off the frame, fully covered, not drawn, or (``fade``) lit at under a tenth of the
light, where 8-bit noise buries it. An absent frame is rendered without the target, so none
of its anti-aliased fringe is left either. Otherwise the box is the target's exact extent
(hidden parts included), clipped to the frame. Every scene starts with at least 12 frames of
the target in full view.

Separate from the sample clips (:mod:`trackbook.clips.scenes`) and from any test scenario:
these scenes choose thresholds, they never score a tracker.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import cv2
import numpy as np

from .._checks import check_seed
from .clip import ArrayFrames, Clip
from .rendering import Canvas, crop, duotone, expose, photo, tile
from .sprites import ball_sprite, ellipse_sprite, rect_sprite

KINDS = ("exit", "occlusion", "cut", "fade", "shrink", "blur", "lookalike")
#: Under this share of the light a faded target counts as absent.
FADE_ABSENT = 0.1
_ATTRIBUTES = {"exit": ("OV",), "occlusion": ("OCC",), "cut": ("OV",), "fade": ("IV",),
               "shrink": ("SV", "LR"), "blur": ("MB",), "lookalike": ("OCC", "BC")}
_PHOTOS = ("astronaut", "brick", "camera", "chelsea", "coffee", "coins", "colorwheel",
           "grass", "gravel", "hubble_deep_field", "immunohistochemistry", "motorcycle",
           "retina", "rocket")
_START = 12                  # frames of the target in full view before any event


@dataclasses.dataclass(frozen=True)
class FailureScene:
    """One calibration scene.

    Attributes
    ----------
    kind : str
    seed : int
    clip : Clip
    absent : ndarray of bool
        Frames with no part of the target in view.
    visible : ndarray of float
        Share of the target's area in view per frame (0 where absent; a target half out of
        the frame or half covered shows 0.5).
    light : ndarray of float
        Share of the light the frame is exposed with (1 but while a ``fade`` scene fades:
        down to 0, and the target is absent under :data:`FADE_ABSENT`).
    """

    kind: str
    seed: int
    clip: Clip
    absent: np.ndarray
    visible: np.ndarray
    light: np.ndarray


# ------------------------------------------------------------------ random ingredients
def _window(rng, name: str, frac=(0.3, 1.0)) -> np.ndarray:
    """A random window (a share ``frac`` of each side) of photograph ``name``, float32."""
    img = photo(name)
    h, w = img.shape[:2]
    ww = int(w * rng.uniform(*frac))
    wh = int(min(h, ww * rng.uniform(0.6, 1.0)))
    x0, y0 = int(rng.integers(0, w - ww + 1)), int(rng.integers(0, h - wh + 1))
    return crop(name, x0, y0, x0 + ww, y0 + wh)


def _background(rng, name: str, w: int, h: int) -> np.ndarray:
    """An H x W float32 background from photograph ``name``: resized, recoloured or tiled."""
    how = rng.integers(3)
    if how == 2:                              # a small window, mirror-tiled: a repeating texture
        t = _window(rng, name, (0.2, 0.4))
        s = rng.uniform(0.3, 0.7)
        t = cv2.resize(t, (max(int(t.shape[1] * s), 16), max(int(t.shape[0] * s), 16)),
                       interpolation=cv2.INTER_AREA)
        return tile(t, w, h)
    bg = cv2.resize(_window(rng, name), (w, h), interpolation=cv2.INTER_AREA)
    if how == 1:                              # recoloured between two random colours
        dark = rng.uniform(0, 110, 3)
        bg = duotone(bg, dark, dark + rng.uniform(80, 145, 3))
    return np.ascontiguousarray(bg, np.float32)


def _target(rng, name: str, w: int, h: int):
    """The target sprite, about ``w x h`` px: a framed picture, an oval or a shaded ball."""
    how = rng.integers(3)
    if how == 2:
        colour = rng.uniform(30, 230, 3)
        return ball_sprite(min(w, h) / 2, colour, _window(rng, name, (0.2, 0.5)))
    img = cv2.resize(_window(rng, name, (0.15, 0.5)), (w, h), interpolation=cv2.INTER_AREA)
    if how == 1:
        return ellipse_sprite(img)
    return rect_sprite(img, int(rng.integers(0, 3)), rng.uniform(0, 255, 3))


def _fold(p, lo, hi):
    """Reflect positions into ``[lo, hi]`` (a bounce off the walls); vectorised."""
    span = max(hi - lo, 1e-6)
    q = np.mod(np.asarray(p, float) - lo, 2 * span)
    return lo + np.where(q > span, 2 * span - q, q)


def _wander(rng, n: int, start, speed: float, lo, hi) -> np.ndarray:
    """``n`` centres from ``start`` at ``speed`` px/frame, turning smoothly, bouncing inside
    the box ``[lo, hi]`` (per axis)."""
    turn = np.cumsum(rng.normal(0.0, 0.08, n))
    a = rng.uniform(0, 2 * np.pi) + turn
    step = speed * np.c_[np.cos(a), np.sin(a)]
    p = np.asarray(start, float) + np.r_[np.zeros((1, 2)), np.cumsum(step[:-1], axis=0)]
    return np.c_[_fold(p[:, 0], lo[0], hi[0]), _fold(p[:, 1], lo[1], hi[1])]


_EDGES = ("left", "right", "top", "bottom")


def _enter(rng, n: int, edge: str, half, size, speed: float) -> np.ndarray:
    """``n`` centres of a target entering across ``edge`` from just outside the frame, then
    bouncing inside it."""
    w, h = size
    axis = 0 if edge in ("left", "right") else 1
    dim = (w, h)[axis]
    lo, hi = half[axis], dim - half[axis]
    # the inward coordinate: starts one half-size (plus a pixel) outside, increases
    s = -half[axis] - 1 + speed * np.arange(n)
    s = np.where(s >= lo, _fold(s, lo, hi), s)
    along = s if edge in ("left", "top") else dim - s
    other = 1 - axis
    o_lo, o_hi = half[other], (w, h)[other] - half[other]
    cross = _fold(rng.uniform(o_lo, o_hi) + rng.uniform(-0.5, 0.5) * speed * np.arange(n),
                  o_lo, o_hi)
    out = np.empty((n, 2))
    out[:, axis], out[:, other] = along, cross
    return out


def _leave(rng, n_in: int, edge: str, half, size, speed: float) -> np.ndarray:
    """``n_in`` centres ending one half-size (plus a pixel) outside ``edge``: the last frame is
    the first with the target fully out; the first is fully inside."""
    return _enter(rng, n_in, edge, half, size, speed)[::-1]


# ------------------------------------------------------------------------- the scenes
@dataclasses.dataclass
class _Plan:
    """Everything a scene draws, per frame."""

    n: int
    size: tuple
    backgrounds: list
    bg_index: np.ndarray               # (n,) which background
    target: object                     # Sprite
    centre: np.ndarray                 # (n, 2)
    scale: np.ndarray                  # (n,)
    shown: np.ndarray                  # (n,) bool: the target is drawn
    gain: np.ndarray                   # (n,)
    noise: float
    blur: dict = dataclasses.field(default_factory=dict)     # frame -> kernel
    occluder: object = None
    occ_centre: np.ndarray | None = None
    alike: object = None
    alike_centre: np.ndarray | None = None     # (n, 2), NaN where not drawn


def _plan(kind: str, rng, size, n) -> _Plan:
    if size is None:
        w = int(rng.integers(20, 41)) * 8                        # 160 .. 320
        size = (w, w * 3 // 4)                                   # 120 .. 240
    w, h = (int(v) for v in size)
    n = int(rng.integers(40, 81)) if n is None else int(n)
    names = rng.permutation(len(_PHOTOS))
    bg_name, t_name, other = (_PHOTOS[i] for i in names[:3])
    tw = int(max(14, w * rng.uniform(0.08, 0.16)))
    th = int(max(14, tw * rng.uniform(0.7, 1.4)))
    target = _target(rng, t_name, tw, th)
    half = np.array(target.size, float) / 2 + 1
    lo, hi = half, np.array([w, h]) - half
    speed = rng.uniform(0.5, 2.5)
    start = rng.uniform(lo, hi)
    p = _Plan(n=n, size=(w, h), backgrounds=[_background(rng, bg_name, w, h)],
              bg_index=np.zeros(n, int), target=target,
              centre=_wander(rng, n, start, speed, lo, hi), scale=np.ones(n),
              shown=np.ones(n, bool), gain=np.ones(n), noise=float(rng.uniform(0, 4)))
    # the event starts at frame a (12 frames in full view before it, room for >= 7 frames
    # of it and 12 after it) and lasts gap frames
    a = int(rng.integers(_START + 4, n - 2 * _START + 6))
    gap = min(int(rng.integers(6, 15)), n - a - _START)
    edge_speed = rng.uniform(1.5, 4.0)
    if kind == "exit":
        edge = _EDGES[rng.integers(4)]
        axis = 0 if edge in ("left", "right") else 1
        # out over frames 0 .. a (fully out at a), fast enough to be in full view before 12
        v = max(edge_speed, (2 * half[axis] + 2) / (a - _START))
        p.centre[:a + 1] = _leave(rng, a + 1, edge, half, (w, h), v)
        p.shown[a:a + gap] = False
        back = _EDGES[rng.integers(4)]
        p.centre[a + gap:] = _enter(rng, n - a - gap, back, half, (w, h), edge_speed)
    elif kind == "cut":
        p.backgrounds.append(_background(rng, other, w, h))
        p.bg_index[a:] = 1
        p.shown[a:a + gap] = False
        p.centre[a + gap:] = _enter(rng, n - a - gap, _EDGES[rng.integers(4)], half, (w, h),
                                    edge_speed)
    elif kind == "fade":
        down, up = int(rng.integers(3, 9)), int(rng.integers(3, 9))
        hold = max(gap - 3, 3)
        g = np.r_[np.linspace(1, 0, down + 1)[1:], np.zeros(hold), np.linspace(0, 1, up + 1)[1:]]
        g = g[:n - a - _START]
        p.gain[a:a + g.size] = g
    elif kind == "shrink":
        smin = 3.0 / max(target.size)                                # <= 4 px: then gone
        down, up = int(rng.integers(6, 15)), int(rng.integers(6, 15))
        # shrink, stay gone, grow back, all before the last 12 frames (cutting the schedule
        # short instead let the target jump back to full size): the event starts earlier
        # when it would not fit, never before frame 16; only a clip too short even then has
        # its ramps shortened in proportion, to no fewer than 4 frames, and the absence to
        # what is left, no fewer than 3 (room >= 12 here, as n >= 40)
        a = max(_START + 4, min(a, n - _START - (down + gap + up)))
        room = n - a - _START
        if down + gap + up > room:
            f = room / (down + gap + up)
            down, up = max(4, int(down * f)), max(4, int(up * f))
            while down + up > room - 3:
                if down >= up:
                    down -= 1
                else:
                    up -= 1
            gap = min(gap, room - down - up)
        s = np.r_[np.geomspace(1, smin, down), np.full(gap, smin), np.geomspace(smin, 1, up)]
        p.scale[a:a + s.size] = s
        p.shown[a + down:a + down + gap] = False
    elif kind == "blur":
        for i in range(a, a + gap):
            p.blur[i] = _blur_kernel(rng)
    elif kind in ("occlusion", "lookalike"):
        ow = int(target.size[0] * rng.uniform(1.4, 2.0)) + 6
        oh = int(target.size[1] * rng.uniform(1.4, 2.0)) + 6
        img = cv2.resize(_window(rng, other, (0.2, 0.6)), (ow, oh), interpolation=cv2.INTER_AREA)
        p.occluder = rect_sprite(img, 2, rng.uniform(0, 255, 3))
        # the target slows while covered, so the panel that follows it covers it whole
        p.centre[:] = _wander(rng, n, start, min(speed, 1.0), lo, hi)
        app, dep = int(rng.integers(6, 12)), rng.uniform(2.0, 5.0)
        t = np.arange(n)
        off = (np.hypot(w, h) / 2 + max(ow, oh)) * _unit(rng)
        leave = _unit(rng)
        k = np.clip((a - t) / app, 0, None)[:, None]                 # approach: 1 -> 0 at a
        gone = np.clip(t - (a + gap - 1), 0, None)[:, None]          # departure after a + gap
        p.occ_centre = p.centre + k * off + gone * dep * leave
        if kind == "lookalike":
            p.alike = p.target.flipped()
            d = rng.uniform(1.5, 4.0) * max(target.size)
            pos = p.centre[a] + d * _unit(rng)
            pos = np.clip(pos, lo, hi)
            p.alike_centre = np.full((n, 2), np.nan)
            p.alike_centre[a:] = _wander(rng, n - a, pos, min(speed, 1.0), lo, hi)
    else:
        raise ValueError(f"unknown failure scene kind {kind!r}; kinds: {', '.join(KINDS)}.")
    return p


def _unit(rng) -> np.ndarray:
    a = rng.uniform(0, 2 * np.pi)
    return np.array([np.cos(a), np.sin(a)])


def _blur_kernel(rng) -> np.ndarray:
    """A heavy blur: a motion streak (9-25 px, any angle) or a defocus disc (radius 3-8)."""
    if rng.integers(2):
        length = int(rng.integers(9, 26))
        k = np.zeros((length, length), np.float32)
        c = (length - 1) / 2
        a = rng.uniform(0, np.pi)
        d = (length - 1) / 2 * np.array([np.cos(a), np.sin(a)])
        cv2.line(k, (int(round(c - d[0])), int(round(c - d[1]))),
                 (int(round(c + d[0])), int(round(c + d[1]))), 1.0, 1)
    else:
        r = int(rng.integers(3, 9))
        k = np.zeros((2 * r + 1, 2 * r + 1), np.float32)
        cv2.circle(k, (r, r), r, 1.0, -1)
    return k / k.sum()


def _render(kind: str, seed: int, size=None, frames=None, target: bool = True):
    """Frames, target boxes, lookalike boxes and absent flags of one scene; ``target=False``
    draws the same scene without the target (same noise, same everything else)."""
    rng = np.random.default_rng([seed, KINDS.index(kind) if kind in KINDS else 99])
    p = _plan(kind, rng, size, frames)
    w, h = p.size
    noise_rng = np.random.default_rng([seed, 7919])
    out = np.empty((p.n, h, w, 3), np.uint8)
    gt = np.full((p.n, 4), np.nan)
    alike = np.full((p.n, 4), np.nan)
    absent = np.zeros(p.n, bool)
    share = np.zeros(p.n)
    area = float((p.target.alpha >= 0.5).sum())
    for i in range(p.n):
        noise = (noise_rng.normal(0.0, p.noise, (h, w, 3)).astype(np.float32)
                 if p.noise > 0 else None)
        img, box, seen, abox = _compose(p, i, draw_target=target and p.shown[i])
        if target and p.shown[i] and not seen:
            img, _, _, _ = _compose(p, i, draw_target=False)   # none of its fringe either
        lit = p.gain[i] >= FADE_ABSENT
        absent[i] = not (target and p.shown[i] and seen and lit)
        if not absent[i]:
            share[i] = min(seen / (area * p.scale[i] ** 2), 1.0)
            x0, y0 = max(box[0], 0.0), max(box[1], 0.0)
            x1, y1 = min(box[0] + box[2], w), min(box[1] + box[3], h)
            gt[i] = (x0, y0, x1 - x0, y1 - y0)
        alike[i] = abox
        if i in p.blur:
            img = cv2.filter2D(img, -1, p.blur[i], borderType=cv2.BORDER_REFLECT)
        out[i] = expose(img, p.gain[i], noise=noise)
    return out, gt, alike, absent, share, p


def _compose(p: _Plan, i: int, draw_target: bool):
    """Composite frame ``i`` (float, before light): returns the image, the target's box,
    how many of its pixels are in view, and the lookalike's box (NaN if not drawn)."""
    canvas = Canvas(p.backgrounds[p.bg_index[i]])
    abox = np.full(4, np.nan)
    if p.alike is not None and np.all(np.isfinite(p.alike_centre[i])):
        ap = canvas.paste(p.alike, p.alike_centre[i])
        if canvas.visible(ap).any():
            abox = ap.box
    box, seen = np.full(4, np.nan), 0
    tp = canvas.paste(p.target, p.centre[i], scale=p.scale[i]) if draw_target else None
    if p.occluder is not None:
        canvas.paste(p.occluder, p.occ_centre[i])
    if tp is not None:
        box, seen = tp.box, int(canvas.visible(tp).sum())
    return canvas.img, box, seen, abox


def failure_scene(kind: str, seed: int, size=None, frames: int | None = None):
    """One randomised calibration scene of ``kind`` drawn from ``seed``: ``(clip, absent)``.

    :func:`render_scene` gives the same scene with the share of the target in view.

    Parameters
    ----------
    kind : str
        One of :data:`KINDS`: ``"exit"``, ``"occlusion"``, ``"cut"``, ``"fade"``, ``"shrink"``,
        ``"blur"``, ``"lookalike"``.
    seed : int
        Same kind and seed, same frames.
    size : (w, h), optional
        The frame size (default: drawn, 160 x 120 to 320 x 240).
    frames : int, optional
        The length (default: drawn, 40-80); at least 40.

    Returns
    -------
    clip : Clip
        Ground truth NaN where no part of the target is in view; for ``lookalike`` the
        copy's boxes are ``clip.targets["lookalike"]``.
    absent : ndarray of bool
        The frames with no part of the target in view.
    """
    sc = render_scene(kind, seed, size, frames)
    return sc.clip, sc.absent


def _check(kind, seed, size, frames) -> None:
    if kind not in KINDS:
        raise ValueError(f"unknown failure scene kind {kind!r}; kinds: {', '.join(KINDS)}.")
    check_seed(seed)
    if seed is None:
        raise ValueError("failure_scene needs an integer seed (0, 1, ...): a scene is "
                         "drawn from it, and the same seed gives the same frames.")
    if frames is not None and (isinstance(frames, bool) or frames < 40
                               or not isinstance(frames, (int, np.integer))):
        raise ValueError(f"frames = {frames!r}: give a whole number >= 40 (12 frames before "
                         "the event, the event, 12 frames after it).")
    if size is not None:
        w, h = (int(v) for v in size)
        if w < 96 or h < 72:
            raise ValueError(f"size = {tuple(size)}: give (w, h) of at least (96, 72).")


def render_scene(kind: str, seed: int, size=None, frames: int | None = None) -> FailureScene:
    """The scene of :func:`failure_scene` as a :class:`FailureScene` (with ``visible``)."""
    _check(kind, seed, size, frames)
    frames_, gt, alike, absent, share, plan = _render(kind, int(seed), size, frames)
    light = np.asarray(plan.gain, float).copy()
    targets = {"target": gt}
    if kind == "lookalike":
        targets["lookalike"] = alike
    clip = Clip(f"failure-{kind}-{seed}", ArrayFrames(frames_), gt, fps=30.0, targets=targets,
                description=f"calibration scene: {kind}", attributes=_ATTRIBUTES[kind],
                source="generated")
    absent.setflags(write=False)
    share.setflags(write=False)
    light.setflags(write=False)
    return FailureScene(kind, int(seed), clip, absent, share, light)


class CalibrationSet(Sequence):
    """``per_kind`` scenes of every kind, drawn from one seed and rendered when read.

    Indexing renders the scene (nothing is kept, so memory stays one clip however large the
    set); ``set[i]`` is a :class:`FailureScene`. ``specs`` lists ``(kind, scene seed)``.
    """

    def __init__(self, seed: int = 0, per_kind: int = 6, kinds=KINDS):
        check_seed(seed)
        if seed is None:
            raise ValueError("calibration_set needs an integer seed (0, 1, ...).")
        if isinstance(per_kind, bool) or not isinstance(per_kind, (int, np.integer)) \
                or per_kind < 1:
            raise ValueError(f"per_kind = {per_kind!r}: give a whole number >= 1.")
        unknown = [k for k in kinds if k not in KINDS]
        if unknown:
            raise ValueError(f"unknown kinds {unknown}; kinds: {', '.join(KINDS)}.")
        self.seed, self.per_kind, self.kinds = int(seed), int(per_kind), tuple(kinds)
        # scene seeds from (set seed, j): two sets' scenes do not repeat each other
        self.specs = [(k, int(np.random.SeedSequence([self.seed, j]).generate_state(1)[0]))
                      for k in self.kinds for j in range(self.per_kind)]

    def __len__(self) -> int:
        return len(self.specs)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        kind, s = self.specs[i]
        return render_scene(kind, s)

    def __repr__(self) -> str:
        return (f"CalibrationSet(seed={self.seed}, per_kind={self.per_kind}, "
                f"{len(self)} scenes)")


def calibration_set(seed: int = 0, per_kind: int = 6, kinds=KINDS) -> CalibrationSet:
    """The calibration scenes: ``per_kind`` of each kind in :data:`KINDS`, from ``seed``.

    >>> s = calibration_set(seed=0, per_kind=2)      # doctest: +SKIP
    >>> len(s), s[0].kind, s[0].clip, s[0].absent.sum()  # doctest: +SKIP
    """
    return CalibrationSet(seed, per_kind, kinds)


__all__ = ["CalibrationSet", "FADE_ABSENT", "FailureScene", "KINDS", "calibration_set",
           "failure_scene", "render_scene"]
