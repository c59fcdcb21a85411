"""The generated sample clips: registry, shapes, determinism, exact ground truth."""

from __future__ import annotations

import functools
from importlib.resources import files

import cv2
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from trackbook import clips
from trackbook.clips import samples, synthetic
from trackbook.clips.synthetic import Canvas, Sprite, mask_box

EXPECTED = {
    "robot-corridor-day": "lee2012", "robot-corridor-night": "lee2012",
    "patterned-object": "kim2016", "red-cube": "lee2015", "yellow-ball": "lee2015",
    "occluder": "cho2005", "shelves": "cho2005", "two-faces": "cho2005",
}
OTB_CODES = {"IV", "OCC", "FM", "SV", "BC", "DEF", "MB", "IPR", "OPR", "LR", "OV", "CM"}
NAMES = sorted(EXPECTED)


@functools.lru_cache(maxsize=None)
def rendered(name):
    """One rendering per clip for the whole module (rendering is the slow part)."""
    return synthetic.render(name)


def edges(box):
    """(left, top, right, bottom) of (x, y, w, h) boxes."""
    b = np.asarray(box, float)
    return np.concatenate([b[..., :2], b[..., :2] + b[..., 2:]], axis=-1)


def iou(a, b):
    ea, eb = edges(a), edges(b)
    w = np.clip(np.minimum(ea[..., 2], eb[..., 2]) - np.maximum(ea[..., 0], eb[..., 0]), 0, None)
    h = np.clip(np.minimum(ea[..., 3], eb[..., 3]) - np.maximum(ea[..., 1], eb[..., 1]), 0, None)
    inter = w * h
    return inter / (a[..., 2] * a[..., 3] + b[..., 2] * b[..., 3] - inter)


def visible_fraction(r):
    return r.visible.sum(axis=(1, 2)) / np.maximum(r.support.sum(axis=(1, 2)), 1)


# ------------------------------------------------------------------ registry and loading
def test_the_eight_sample_clips_are_registered_with_their_papers():
    assert set(clips.available()) == set(EXPECTED)
    for name, paper in EXPECTED.items():
        assert samples.info(name).paper == paper
        assert name in clips.available(paper)
        assert len(samples.info(name).description) > 80
        assert clips.describe(name).startswith(f"{name} ({paper}): ")


@pytest.mark.parametrize("old", ["000", "002", "003"])
def test_the_old_paper_numbers_are_refused_with_the_key_to_use(old):
    key = {"000": "lee2012", "002": "lee2015", "003": "cho2005"}[old]
    with pytest.raises(ValueError, match=f"paper='{key}'"):
        clips.available(old)
    with pytest.raises(ValueError, match="lee2012, kim2016, lee2015, cho2005"):
        clips.catalogue(paper="lee")


def test_the_catalogue_lists_every_clip_without_rendering(monkeypatch):
    # rendering is refused while listing: the catalogue must come from the registry alone
    def refuse(*a, **k):
        raise AssertionError("a listing rendered a clip")
    monkeypatch.setattr(samples, "render", refuse)
    infos = clips.catalogue()
    assert [s.name for s in infos] == clips.available()
    assert [s.name for s in clips.catalogue("cho2005")] == ["occluder", "shelves", "two-faces"]


@pytest.mark.parametrize("name", NAMES)
def test_the_catalogue_says_what_loading_gives(name):
    info = next(s for s in clips.catalogue() if s.name == name)
    clip = clips.load(name)
    assert (info.frames, info.size, info.fps) == (len(clip), clip.size, clip.fps)
    assert info.attributes == clip.attributes and info.description == clip.description


@pytest.mark.parametrize("name", clips.available())
def test_every_sample_loads_as_a_well_formed_clip(name):
    clip = clips.load(name)
    n = len(clip)
    assert clip.name == name and clip.source == "sample"
    assert 100 <= n <= 184
    arr = clip.frames.array
    assert arr.shape == (n, 240, 320, 3) and arr.dtype == np.uint8
    assert clip.frames[n - 1].shape == (240, 320, 3) and clip.size == (320, 240)
    assert sum(1 for _ in clip.frames) == n
    assert 25 <= clip.fps <= 30
    assert not arr.flags.writeable              # shared through the cache: read-only
    gt = clip.groundtruth
    assert gt.shape == (n, 4) and np.isfinite(gt).all()
    assert (gt[:, 2] > 0).all() and (gt[:, 3] > 0).all()
    for boxes in clip.targets.values():       # every target stays inside the picture
        assert boxes.shape == (n, 4) and np.isfinite(boxes).all()
        e = edges(boxes)
        assert (e[:, :2] >= 0).all() and (e[:, 2] <= 320).all() and (e[:, 3] <= 240).all()
    np.testing.assert_array_equal(next(iter(clip.targets.values())), gt)
    assert clip.attributes and set(clip.attributes) <= OTB_CODES
    assert clip.description == samples.info(name).description
    assert name in clips.describe(name)


def test_frames_are_bgr():
    # the red cube must be red in OpenCV's channel order (B, G, R), the ball yellow
    for name, check in (("red-cube", lambda c: c[2] > c[1] + 60 and c[2] > c[0] + 60),
                        ("yellow-ball", lambda c: min(c[1], c[2]) > c[0] + 60)):
        r = rendered(name)
        colour = r.frames[r.visible].reshape(-1, 3).mean(axis=0)
        assert check(colour), (name, colour)


def test_red_cube_matches_the_paper_clip():
    clip = clips.load("red-cube")
    assert len(clip) == 184 and clip.size == (320, 240)


def test_every_photograph_ships_in_the_installed_wheel():
    # photo() reads these files; nothing may need a download (pooch) at run time
    folder = files("skimage.data")
    for fname in list(synthetic._PHOTO_FILES.values()) + ["lfw_subset.npy"]:
        assert (folder / fname).is_file(), fname
    assert synthetic.photo("astronaut").shape == (512, 512, 3)


# ------------------------------------------------------------------------- determinism
@pytest.mark.parametrize("name", NAMES)
def test_building_twice_gives_identical_clips(name):
    a, b = samples.build.__wrapped__(name), samples.build.__wrapped__(name)  # no cache
    assert a.frames.array is not b.frames.array
    np.testing.assert_array_equal(a.frames.array, b.frames.array)
    np.testing.assert_array_equal(a.groundtruth, b.groundtruth)
    for k in a.targets:
        np.testing.assert_array_equal(a.targets[k], b.targets[k])
    # and the rendering with masks is the very same clip
    r = rendered(name)
    np.testing.assert_array_equal(r.frames, a.frames.array)
    np.testing.assert_array_equal(next(iter(r.targets.values())), a.groundtruth)


def test_generation_leaves_the_global_rng_alone():
    np.random.seed(123)
    expected = np.random.random(3)
    np.random.seed(123)
    samples.build.__wrapped__("yellow-ball")
    np.testing.assert_array_equal(np.random.random(3), expected)


# ------------------------------------------------------------------ exact ground truth
@pytest.mark.parametrize("name", NAMES)
def test_groundtruth_is_the_extent_of_the_sprite_mask(name):
    r = rendered(name)
    gt = next(iter(r.targets.values()))
    masks = synthetic.render_masks(name)
    np.testing.assert_array_equal(masks, r.support)
    assert masks.shape == r.frames.shape[:3] and masks.dtype == bool
    for i in range(len(gt)):
        err = np.abs(edges(mask_box(masks[i])) - edges(gt[i]))
        assert err.max() <= 1.0, (i, gt[i], mask_box(masks[i]))
    assert (r.visible <= r.support).all()        # visible pixels are part of the support


@pytest.mark.parametrize("name", NAMES)
def test_the_target_stands_out_from_its_surroundings(name):
    # mean colour of the visible target vs. a ring of 8 px around its box
    r = rendered(name)
    gt = next(iter(r.targets.values()))
    vis = visible_fraction(r)
    dist = []
    for i in np.flatnonzero(vis > 0.9):
        x0, y0, x1, y1 = edges(gt[i])
        x0, y0, x1, y1 = int(x0), int(y0), int(np.ceil(x1)), int(np.ceil(y1))
        ring = np.zeros(r.support[i].shape, bool)
        ring[max(y0 - 8, 0):y1 + 8, max(x0 - 8, 0):x1 + 8] = True
        ring[y0:y1, x0:x1] = False
        f = r.frames[i].astype(float)
        dist.append(np.linalg.norm(f[r.visible[i]].mean(0) - f[ring].mean(0)))
    assert len(dist) > 0.5 * len(gt)
    assert np.percentile(dist, 10) > 5.0, np.percentile(dist, 10)


@pytest.mark.parametrize("name", ["red-cube", "yellow-ball", "occluder", "shelves"])
def test_what_moves_is_inside_the_groundtruth(name):
    # static camera, one moving sprite: the per-pixel median over time is the background;
    # the target's pixels differ from it, and what differs lies on the target (or its shadow)
    r = rendered(name)
    bg = np.median(r.frames, axis=0)
    vis = visible_fraction(r)
    near = np.ones((7, 7), np.uint8)
    for i in range(len(r.frames)):
        diff = np.abs(r.frames[i] - bg).max(axis=-1)
        if vis[i] > 0.5:
            assert diff[r.visible[i]].mean() > 40, i
        changed = diff > 40
        on_target = cv2.dilate(r.support[i].astype(np.uint8), near) > 0
        if changed.sum() > 20:
            assert (changed & on_target).sum() >= 0.7 * changed.sum(), i


def test_a_shifted_box_would_fail_the_mask_check():
    # the accuracy check above can fail: a box 2 px off is caught
    r = rendered("red-cube")
    gt = r.targets["target"][10] + (2.0, 0, 0, 0)
    assert np.abs(edges(mask_box(r.support[10])) - edges(gt)).max() > 1.0


# ------------------------------------------------------------- what each scenario shows
def test_red_cube_jumps_at_frames_139_to_142():
    gt = rendered("red-cube").targets["target"]
    centre = gt[:, :2] + gt[:, 2:] / 2
    step = np.diff(centre, axis=0)               # step[i - 1] moves into frame i
    speed = np.linalg.norm(step, axis=1)
    before = np.median(speed[:137])
    assert (speed[138:142] >= 4 * before).all(), (speed[136:144], before)   # into 139..142
    assert speed[143:].max() < 3 * before         # then it calms down again
    # and it turns: the direction of the jump differs from the heading before it
    v0, v1 = step[127:137].mean(0), step[138:142].mean(0)
    cos = v0 @ v1 / np.linalg.norm(v0) / np.linalg.norm(v1)
    assert cos < 0, cos


def test_two_faces_cross_and_overlap():
    clip = clips.load("two-faces")
    assert set(clip.targets) == {"face1", "face2"}
    np.testing.assert_array_equal(clip.groundtruth, clip.targets["face1"])
    overlap = iou(clip.targets["face1"], clip.targets["face2"])
    assert overlap.max() > 0.2
    assert overlap[:10].max() == 0 and overlap[-10:].max() == 0      # disjoint at both ends
    # they swap sides: face1 starts left of face2 and ends right of it
    c1 = clip.targets["face1"][:, 0] + clip.targets["face1"][:, 2] / 2
    c2 = clip.targets["face2"][:, 0] + clip.targets["face2"][:, 2] / 2
    assert c1[0] < c2[0] and c1[-1] > c2[-1]
    # face2 passes in front: face1 is partly hidden while they overlap
    vis = visible_fraction(rendered("two-faces"))
    assert vis.min() < 0.8 and vis[:10].min() == 1.0


def test_occluder_hides_the_walker_for_a_few_frames():
    r = rendered("occluder")
    vis = visible_fraction(r)
    hidden = np.flatnonzero(vis < 0.2)
    assert len(hidden) >= 3
    assert np.flatnonzero(vis == 0).tolist() == list(range(71, 77))   # as the description says
    assert vis[:20].min() == 1.0 and vis[-20:].min() == 1.0
    # the ground truth keeps moving through the occlusion (OTB: the true box, not NaN)
    gt = r.targets["target"]
    dx = np.diff(gt[:, 0] + gt[:, 2] / 2)
    assert np.isfinite(gt[hidden]).all() and (dx[hidden[0]:hidden[-1]] > 0.3).all()


def test_robot_night_is_the_day_clip_in_the_dark():
    day, night = clips.load("robot-corridor-day"), clips.load("robot-corridor-night")
    np.testing.assert_array_equal(day.groundtruth, night.groundtruth)
    d, n = day.frames.array.mean(), night.frames.array.mean()
    assert n < 0.6 * d
    assert night.frames.array.std() < day.frames.array.std()      # low contrast


@pytest.mark.parametrize("name", ["robot-corridor-day", "robot-corridor-night"])
def test_robot_clips_have_sudden_light_changes_and_camera_motion(name):
    frames = clips.load(name).frames.array.astype(np.float32)
    level = frames.mean(axis=(1, 2, 3))
    jumps = np.abs(np.diff(level)) / level[:-1]
    assert (jumps > 0.15).sum() >= 3               # several abrupt illumination steps
    # the wall scrolls: its photographs and doors (rows above the people) shift sideways,
    # one way and then back (the robot follows the person, who turns round)
    shifts = []
    for i in range(len(frames) - 1):
        a, b = (np.ascontiguousarray(frames[j, 25:100].mean(-1)) for j in (i, i + 1))
        (dx, dy), _ = cv2.phaseCorrelate(a / a.mean(), b / b.mean())
        shifts.append((dx, dy))
    dx, dy = np.array(shifts).T                     # robust statistics: noisy night frames
    assert np.percentile(dx, 90) > 1.5 and np.percentile(dx, 10) < -1.5
    assert np.median(np.abs(dx)) > 1.0 and np.median(np.abs(dy)) < 1.0


def test_robot_target_stops_and_turns_back():
    gt = clips.load("robot-corridor-day").groundtruth
    cx = gt[:, 0] + gt[:, 2] / 2
    v = np.convolve(np.diff(cx), np.ones(5) / 5, mode="valid")    # smooth the gait jitter
    assert v.max() > 1.0 and v.min() < -1.0         # it walks both ways in the picture


def test_patterned_object_changes_scale_and_the_camera_shakes():
    r = rendered("patterned-object")
    gt = r.targets["target"]
    side = np.sqrt(r.support.sum(axis=(1, 2)))
    assert side.max() / side.min() > 1.4            # 0.85 .. 1.3: perspective scale change
    # shake: the background under a fixed window moves from frame to frame
    corner = r.frames[:, :20, :20].astype(float).mean(axis=(1, 2, 3))
    assert np.abs(np.diff(corner)).mean() > 0.5
    assert np.isfinite(gt).all()


# ----------------------------------------------------------- compositor, by hypothesis
@settings(max_examples=60, deadline=None)
@given(w=st.integers(10, 60), h=st.integers(10, 60), cx=st.floats(70, 250),
       cy=st.floats(70, 170), angle=st.floats(-45, 45), scale=st.floats(0.6, 1.6),
       shape=st.sampled_from(["ellipse", "rounded", "rect"]))
def test_pasted_sprite_mask_matches_its_box(w, h, cx, cy, angle, scale, shape):
    # sprites of at least 6 px and of aspect <= 3 (as in the clips): the thin tip of a very
    # long, narrow ellipse can fall between pixel centres, like a sharp rotated corner
    assume(max(w, h) <= 3 * min(w, h))
    rng = np.random.default_rng(0)
    img = rng.uniform(0, 255, (h, w, 3)).astype(np.float32)
    if shape == "ellipse":
        sprite = synthetic.ellipse_sprite(img)
    elif shape == "rounded":
        sprite = synthetic.rect_sprite(img, radius=2.0)
    else:
        sprite = synthetic.rect_sprite(img)
        angle = 0.0                       # a sharp corner rotated can slip between pixels
    canvas = Canvas(np.zeros((240, 320, 3), np.float32))
    p = canvas.paste(sprite, (cx, cy), angle, scale)
    mask = canvas.support(p)
    assert mask.any()
    err = np.abs(edges(mask_box(mask)) - edges(p.box)).max()
    assert err <= 1.0, (err, p.box, mask_box(mask))
    if angle == 0.0 and shape == "rect":
        np.testing.assert_allclose(p.box[2:], (w * scale, h * scale), atol=1e-9)
        np.testing.assert_allclose(p.box[:2], (cx - w * scale / 2, cy - h * scale / 2))
    np.testing.assert_array_equal(canvas.visible(p), mask)       # nothing pasted over it


@settings(max_examples=30, deadline=None)
@given(dx=st.floats(-20, 20), w=st.integers(5, 40))
def test_a_sprite_pasted_on_top_hides_the_one_below(dx, w):
    canvas = Canvas(np.zeros((240, 320, 3), np.float32))
    img = np.full((30, w, 3), 200, np.float32)
    below = canvas.paste(synthetic.rect_sprite(img), (160, 120))
    above = canvas.paste(synthetic.rect_sprite(img * 0.5), (160 + dx, 120))
    vis = canvas.visible(below)
    assert not (vis & canvas.support(above)).any()
    assert (vis | canvas.support(above) >= canvas.support(below)).all()
    # the colour seen where the sprite on top covers it is the top sprite's (away from its
    # anti-aliased rim)
    inner = cv2.erode(canvas.visible(above).astype(np.uint8), np.ones((3, 3), np.uint8)) > 0
    assert inner.any() and np.allclose(canvas.img[inner], 100, atol=1e-3)


@given(keys=st.lists(st.tuples(st.integers(0, 99), st.floats(-100, 100)), min_size=2,
                     max_size=6, unique_by=lambda k: k[0]))
def test_path_goes_through_its_keys_and_smoothing_keeps_its_range(keys):
    keys = sorted(keys)
    raw = synthetic.path(100, keys, sigma=0)
    for f, v in keys:
        assert raw[f] == pytest.approx(v)
    smooth = synthetic.path(100, keys, sigma=3)
    assert smooth.shape == (100,)
    assert smooth.min() >= raw.min() - 1e-9 and smooth.max() <= raw.max() + 1e-9


def test_sprite_support_needs_opaque_pixels():
    with pytest.raises(ValueError, match="alpha"):
        Sprite(np.zeros((5, 5, 3)), np.zeros((5, 5)))


def test_the_clips_command_lists_without_rendering_and_cuts_at_a_word(monkeypatch, capsys):
    from trackbook import cli

    def refuse(*a, **k):
        raise AssertionError("trackbook clips rendered a clip")
    monkeypatch.setattr(samples, "render", refuse)
    assert cli.main(["clips"]) == 0
    lines = capsys.readouterr().out.splitlines()
    for info in clips.catalogue():
        line = next(ln for ln in lines if ln.split()[:2] == [info.name, info.paper])
        assert f"{info.frames} frames {info.size[0]}x{info.size[1]}" in line
        shown = line.split(f"{info.size[1]}  ", 1)[1].removesuffix(" ...")
        assert info.description.startswith(shown)
        # the listing stops between two words of the description, never inside one
        rest = info.description[len(shown):]
        assert rest == "" or rest.startswith(" ")
