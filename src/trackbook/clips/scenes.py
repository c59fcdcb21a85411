"""The scenes of the generated sample clips, each registered with :func:`samples.sample`.

A scene is a function ``render(n) -> Rendering`` that composites ``n`` frames with the engine
of :mod:`trackbook.clips.rendering` and the sprites of :mod:`trackbook.clips.sprites`; its
decorator records the clip's paper, frame count, frame rate, OTB attributes and description,
which :func:`trackbook.clips.catalogue` lists without rendering anything. Each scene stands in
for the experiment of one paper; the descriptions say which.
"""

from __future__ import annotations

import functools

import cv2
import numpy as np

from .clip import ArrayFrames, Clip
from .rendering import (SS, Canvas, Film, H, Rendering, Sprite, W, crop, duotone, expose, path,
                        steps, noise_source, tile, view, photo)
from .samples import sample
from .sprites import (ball_sprite, cylinder_shading, ellipse_sprite, face, planks, rect_sprite,
                      shadow_sprite, walk_poses, walker)


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


def _robot(night: bool, n: int) -> Rendering:
    """The robot's side view: the robot follows the person with a lag (ego-motion)."""
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
    film = Film(n)
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
(the book's scene for the trackers of Lee et al. 2012, whose own videos are not public). The robot lags behind the person, so the wall and its doors and photographs
scroll sideways (camera motion) while the person, wearing the astronaut's orange suit, walks
with changing speed, slows to a halt around frame 62 and turns back, pauses again around
frames 104-112 and then hurries away. {light} Three passers-by dressed in similar
red-orange colours cross behind the target (from frames 8, 55 and 100)."""


@sample("robot-corridor-day", "lee2012", frames=150, fps=30.0,
        attributes=("IV", "CM", "BC", "DEF", "OPR"),
        description=_ROBOT.format(light="The lights change abruptly (dimmer at frame 34, much "
                                  "brighter at 58, dim at 84, bright at 121) and flicker at "
                                  "frames 60-67 and 110-120."))
def _robot_day(n: int) -> Rendering:
    return _robot(night=False, n=n)


@sample("robot-corridor-night", "lee2012", frames=150, fps=30.0,
        attributes=("IV", "CM", "BC", "DEF", "OPR"),
        description=_ROBOT.format(light="At night: dark, low-contrast, bluish and noisy frames, "
                                  "lit by pools of lamp light that the person walks through, "
                                  "with the same abrupt steps and flicker of the lights as "
                                  "the day clip."))
def _robot_night(n: int) -> Rendering:
    return _robot(night=True, n=n)


@sample("patterned-object", "kim2016", frames=150, fps=30.0,
        attributes=("BC", "CM", "IPR", "SV"),
        description="""
A multicoloured object, a photograph of an espresso cup and saucer mounted as a small
board, glides over a wooden plank table of the same browns and reds (the scenario of Kim et al. 2016). A hand-held
camera shakes (random shifts of up to 4 px every frame), the object turns in the image
plane by up to 10 degrees, and it comes closer and recedes (scale 1.0 -> 1.3 -> 0.85 ->
1.1, i.e. about 30 % size change).""")
def _patterned_object(n: int) -> Rendering:
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
    film = Film(n)
    for i in range(n):
        canvas = Canvas(view(table, m + shake[i, 0], m + shake[i, 1]))
        c = centre[i] - shake[i]            # the camera moved: the scene moves the other way
        canvas.paste(shadow, c + 3 * scale[i], angle[i], scale[i], opacity=0.55, opaque=False)
        p = canvas.paste(obj, c, angle[i], scale[i])
        film.record(i, canvas, expose(canvas.img), target=p)
    return film.done()


@sample("red-cube", "lee2015", frames=184, fps=25.0, attributes=("FM",),
        description="""
A small red cube (24 x 24 px) with a printed digit slides over a concrete floor (Lee
2015's clip: 320 x 240, 184 frames at 25 fps). It moves slowly and smoothly (about 1.6 px per
frame) along a gentle curve until, at frames 139-142 (the steps into frames 138 to 142,
counting from 0), it suddenly accelerates to about 9 px per frame and turns by about 140
degrees, as in the paper's clip [quote: lee2015.covariance_loses_139]
[quote: lee2015.miss_causes] (the angle is the book's); then it continues at about 2 px per frame in the new
direction.""")
def _red_cube(n: int) -> Rendering:
    rng = np.random.default_rng(1002)
    floor = tile(duotone(crop("gravel", 0, 0, 512, 512, (320, 320)), (105, 115, 125),
                         (175, 185, 190)), W, H)
    floor *= np.linspace(0.9, 1.08, H, dtype=np.float32)[:, None, None]
    # the cube: front face with a digit, lit top face and shaded right face (drawn 4x)
    s, b = 20 * SS, 4 * SS
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
    cv2.putText(ink, "7", (b + 3 * SS, s + b - 4 * SS), cv2.FONT_HERSHEY_SIMPLEX, 2.0,
                255, 3 * SS, cv2.LINE_AA)
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
    film = Film(n)
    for i in range(n):
        canvas = Canvas(floor)
        canvas.paste(shadow, centre[i] + (3, 4), opacity=0.5, opaque=False)
        p = canvas.paste(cube, centre[i])
        film.record(i, canvas, expose(canvas.img), target=p)
    return film.done()


@sample("yellow-ball", "lee2015", frames=120, fps=25.0, attributes=("FM", "LR"),
        description="""
A small yellow ball (18 px across) bounces fast across a lawn in parabolic arcs,
rebounding from the ground and from the side of the picture (Lee 2015's "YellowBall").
Its speed reaches 12 px per frame near the ground and drops near the top of each arc;
its soft shadow follows it on the grass.""")
def _yellow_ball(n: int) -> Rendering:
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
    film = Film(n)
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


@sample("occluder", "cho2005", frames=140, fps=25.0, attributes=("OCC", "DEF"),
        description="""
A person in a striped shirt (cut from the flag in the astronaut photo) walks from left to
right along a brick wall and passes behind a tree trunk (the scenario of Cho and Kang 2005). The ground truth
stays the person's true box while hidden (OTB convention): the trunk starts to cover the
person at frame 53, hides more than 80 % of it at frames 64-82 and all of it at frames
71-76, and releases it at frame 94 (frames counted from 0).""")
def _occluder(n: int) -> Rendering:
    rng = np.random.default_rng(1004)
    bg = _outdoor()
    trunk_w, trunk_x = 50, 150
    bark = duotone(crop("gravel", 0, 0, 120, 512, (trunk_w * SS, H * SS)), (20, 35, 50),
                   (75, 100, 120))
    bark = cv2.resize(bark, (trunk_w * SS, H * SS), interpolation=cv2.INTER_AREA)
    bark *= cylinder_shading(trunk_w * SS, H * SS, 0.45, 1.1, -0.3)
    tree = Sprite.supersampled(bark, np.ones(bark.shape[:2], np.float32))
    right, left = _flag_walker(96)
    x = path(n, [(0, 30), (60, 150), (66, 160), (100, 228), (139, 292)], sigma=4)
    x += rng.normal(0, 0.02, n)
    idx, facing = walk_poses(x)
    film = Film(n)
    for i in range(n):
        canvas = Canvas(bg)
        p = canvas.paste((right if facing[i] else left)[idx[i]], (x[i], 222 - 48))
        canvas.paste(tree, (trunk_x + trunk_w / 2, H / 2))
        film.record(i, canvas, expose(canvas.img, 1.05), target=p)
    return film.done()


@sample("shelves", "cho2005", frames=160, fps=25.0, attributes=("BC", "DEF", "OPR"),
        description="""
A person in an orange suit walks back and forth in front of shelves crowded with
colourful boxes (the scenario of Cho and Kang 2005): reds, oranges and skin tones in the clutter resemble the
target's colours. The person walks right, pauses and turns at frames 40-55, walks left,
pauses and turns again at 100-115, then walks right once more.""")
def _shelves_clip(n: int) -> Rendering:
    rng = np.random.default_rng(1005)
    bg = _shelves(rng)
    right, left = _astronaut_walker(150)
    x = path(n, [(0, 60), (40, 205), (55, 210), (100, 85), (115, 80), (159, 255)], sigma=4)
    idx, facing = walk_poses(x, stride=20)
    film = Film(n)
    for i in range(n):
        canvas = Canvas(bg)
        p = canvas.paste((right if facing[i] else left)[idx[i]], (x[i], 236 - 75))
        film.record(i, canvas, expose(canvas.img), target=p)
    return film.done()


@sample("two-faces", "cho2005", frames=120, fps=30.0, attributes=("OCC", "BC"),
        description="""
Two faces, the astronaut's (face1, the ground truth) and the cat's from "chelsea"
(face2), drift towards each other in front of a blurred garage, cross and overlap with
the cat in front (it partly hides face1 at frames 50-76) and separate again (Cho and Kang 2005's
multi-target experiment). Both boxes are given in Clip.targets.""")
def _two_faces(n: int) -> Rendering:
    return _crossing_faces(n, crop("chelsea", 95, 20, 375, 295, (60, 58)))


def _crossing_faces(n: int, texture2: np.ndarray) -> Rendering:
    """The astronaut's face and a second face (``texture2``, 60 x 58) crossing: ``two-faces``."""
    bg = crop("motorcycle", 40, 0, 707, 500, (W, H))
    bg = cv2.GaussianBlur(bg, (0, 0), 2.0) * np.float32(0.9)
    f1 = ellipse_sprite(crop("astronaut", 170, 40, 285, 185, (48, 60)))
    f2 = ellipse_sprite(texture2)
    t = np.arange(n)
    c1 = np.c_[path(n, [(0, 50), (119, 255)], sigma=0), 108 + 7 * np.sin(t / 9)]
    c2 = np.c_[path(n, [(0, 270), (119, 60)], sigma=0), 128 + 6 * np.cos(t / 11)]
    s2 = 1 + 0.12 * np.exp(-0.5 * ((t - 60) / 18) ** 2)   # the cat comes closer as it passes
    film = Film(n, names=("face1", "face2"))
    for i in range(n):
        canvas = Canvas(bg)
        p1 = canvas.paste(f1, c1[i], angle=4 * np.sin(i / 13))
        p2 = canvas.paste(f2, c2[i], scale=s2[i])
        film.record(i, canvas, expose(canvas.img), face1=p1, face2=p2)
    return film.done()


def two_faces_alike(n: int = 120) -> Clip:
    """``two-faces`` with the cat replaced by the astronaut's own face, mirrored: one colour.

    Same background, paths, scales and frames as the ``two-faces`` sample; only face2's texture
    differs (the astronaut crop, flipped left-right, at the cat's size), so the two targets
    have the same colour histogram up to resampling. Not a registered sample:
    ``case_study_cho2005`` builds it to test Cho and Kang 2005's two-face claim with two faces of
    one colour.
    """
    twin = np.ascontiguousarray(crop("astronaut", 170, 40, 285, 185, (60, 58))[:, ::-1])
    r = _crossing_faces(int(n), twin)
    r.frames.setflags(write=False)
    return Clip("two-faces-alike", ArrayFrames(r.frames), r.targets["face1"], fps=30.0,
                targets=r.targets, attributes=("OCC", "BC"), source="generated",
                description="two faces of one colour cross (two-faces with a twin for the cat)")


# ---------------------------------------------------------------- lost-and-found test clip
def leave_and_return(n_before: int = 12, n_absent: int = 18, n_after: int = 20,
                     seed: int = 0) -> Clip:
    """A clip whose target leaves the view and comes back somewhere else (the lost-and-found probe).

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
