"""The randomised calibration scenes of the failure rule (``clips.failure_scenes``)."""

import cv2
import numpy as np
import pytest

from trackbook import clips
from trackbook.clips import failure_scenes as fs

SEEDS = (0, 1, 2)


@pytest.fixture(scope="module")
def scenes():
    return {(k, s): fs.failure_scene(k, s) for k in fs.KINDS for s in SEEDS}


def test_the_same_seed_gives_the_same_frames_and_other_seeds_differ():
    for kind in ("exit", "lookalike"):
        a, abs_a = fs.failure_scene(kind, 11)
        b, abs_b = fs.failure_scene(kind, 11)
        np.testing.assert_array_equal(a.frames.array, b.frames.array)
        np.testing.assert_array_equal(a.groundtruth, b.groundtruth)
        np.testing.assert_array_equal(abs_a, abs_b)
        c, _ = fs.failure_scene(kind, 12)
        assert c.frames.array.shape != a.frames.array.shape or \
            not np.array_equal(c.frames.array, a.frames.array)


def test_size_length_and_ground_truth(scenes):
    sizes, lengths = set(), set()
    for (kind, _s), (clip, absent) in scenes.items():
        w, h = clip.size
        assert 160 <= w <= 320 and h == w * 3 // 4
        assert 40 <= len(clip) <= 80 and absent.shape == (len(clip),)
        sizes.add((w, h))
        lengths.add(len(clip))
        gt = clip.groundtruth
        # NaN exactly on the absent frames; present boxes lie inside the frame
        np.testing.assert_array_equal(np.isnan(gt).any(axis=1), absent)
        g = gt[~absent]
        assert np.all(g[:, 2:] > 0) and np.all(g[:, :2] >= 0)
        assert np.all(g[:, 0] + g[:, 2] <= w + 1e-9) and np.all(g[:, 1] + g[:, 3] <= h + 1e-9)
        # twelve frames in full view first: the same box size as frame 0, not at the border
        assert not absent[:12].any()
        np.testing.assert_allclose(gt[:12, 2:], np.broadcast_to(gt[0, 2:], (12, 2)), atol=0.5)
        if kind == "blur":
            assert not absent.any()
        else:
            # it goes, and it comes back before the end
            assert absent.any() and not absent[np.flatnonzero(absent)[-1] + 1:].all()
            assert np.flatnonzero(absent)[-1] < len(clip) - 1
    assert len(sizes) > 5 and len(lengths) > 5            # randomised


@pytest.mark.parametrize("kind", ["exit", "occlusion", "cut", "shrink", "lookalike"])
def test_absent_frames_show_nothing_of_the_target(kind):
    # an independent check: the same scene drawn without its target has the same pixels on
    # the absent frames, and differs on every present frame
    for s in SEEDS:
        with_t, _, _, absent, share, _ = fs._render(kind, s)
        without, *_ = fs._render(kind, s, target=False)
        same = np.all(with_t == without, axis=(1, 2, 3))
        np.testing.assert_array_equal(same, absent)
        np.testing.assert_array_equal(share == 0, absent)


def test_a_faded_target_is_absent_only_in_the_dark():
    for s in SEEDS:
        with_t, _, _, absent, _, plan = fs._render("fade", s)
        without, *_ = fs._render("fade", s, target=False)
        assert absent.any()
        np.testing.assert_array_equal(absent, plan.gain < fs.FADE_ABSENT)
        diff = np.abs(with_t.astype(int) - without.astype(int)).max(axis=(1, 2, 3))
        # under a tenth of the light the target changes no pixel by more than 26 levels
        assert np.all(diff[absent] <= 26) and np.all(diff[~absent] > 0)
        assert with_t[absent].mean() < 0.1 * with_t[0].mean() + 5
        # the scene says how much light each frame has: the frames' mean brightness follows
        sc = fs.render_scene("fade", s)
        np.testing.assert_array_equal(sc.light, plan.gain)
        assert sc.light.min() == 0.0 and sc.light[0] == 1.0
        bright = with_t.reshape(len(with_t), -1).mean(axis=1)
        lit = sc.light > 0.5
        assert bright[lit].min() > bright[sc.light < 0.1].max()


def test_only_a_fade_dims_the_light():
    for kind in fs.KINDS:
        if kind != "fade":
            assert (fs.render_scene(kind, SEEDS[0]).light == 1.0).all()


def test_blur_scenes_blur_some_frames():
    for s in SEEDS:
        clip, absent = fs.failure_scene("blur", s)
        # detail at a quarter of the resolution: the sensor noise, added after the blur,
        # averages out there
        def detail(f):
            g = cv2.cvtColor(f, cv2.COLOR_BGR2GRAY)
            g = cv2.resize(g, (g.shape[1] // 4, g.shape[0] // 4), interpolation=cv2.INTER_AREA)
            return cv2.Laplacian(g, cv2.CV_64F).var()

        sharp = np.array([detail(f) for f in clip.frames])
        blurred = sharp < 0.5 * np.median(sharp)
        assert blurred.sum() >= 6 and not absent.any()


def test_the_lookalike_appears_while_the_target_is_covered():
    for s in SEEDS:
        clip, absent = fs.failure_scene("lookalike", s)
        alike = clip.targets["lookalike"]
        first = np.flatnonzero(absent)[0]
        assert np.isnan(alike[:first]).all()                 # not there before
        assert np.isfinite(alike[absent]).all(axis=1).any()  # there while the target is hidden
        shown = np.isfinite(alike).all(axis=1) & ~absent
        if shown.any():                                      # elsewhere, not on the target
            from trackbook.evaluation.metrics import iou
            assert np.all(iou(alike[shown], clip.groundtruth[shown]) < 0.5)


def test_a_shrinking_target_shrinks_goes_and_grows_back_before_the_last_12_frames():
    # every shrink scene of the calibration set, of the contract's matrix and of SEEDS: its
    # size (the box's longer side) never grows until it is gone, passes through at least two
    # sizes between whole and 4 px on the way down and again on the way up (a ramp of 4
    # frames or more), and the target is whole for the last 12 frames (a schedule cut short
    # once let the target jump back to full size; squeezed into what was left, it shrank
    # from full size to 3 px in one frame)
    cal = fs.calibration_set(seed=0, per_kind=6, kinds=("shrink",))
    matrix = fs.calibration_set(seed=1, per_kind=2, kinds=("shrink",))
    drawn = [cal[j] for j in range(len(cal))] + [matrix[j] for j in range(len(matrix))] \
        + [fs.render_scene("shrink", s) for s in SEEDS]
    for sc in drawn:
        gt, absent = np.asarray(sc.clip.groundtruth, float), np.asarray(sc.absent, bool)
        side = gt[:, 2:].max(axis=1)                       # NaN on the absent frames
        gone = np.flatnonzero(absent)
        first, last = gone[0], gone[-1]
        assert np.array_equal(gone, np.arange(first, last + 1))     # one stretch
        assert last - first + 1 >= 3
        np.testing.assert_allclose(side[:17], side[0], atol=1e-9)    # whole to frame 16
        down, up = side[:first], side[last + 1:]
        assert np.all(np.diff(down) <= 1e-9) and down[-1] <= 4
        assert up[0] <= 4 and np.all(np.diff(up) >= -1e-9)
        whole = side[0]
        assert np.sum((down < whole - 1e-9) & (down > down[-1] + 1e-9)) >= 2
        assert np.sum((up < whole - 1e-9) & (up > up[0] + 1e-9)) >= 2
        np.testing.assert_allclose(side[-12:], whole, atol=1e-9)


def test_the_share_in_view():
    for kind in ("exit", "occlusion"):
        for s in SEEDS:
            sc = fs.render_scene(kind, s)
            v = sc.visible
            assert np.all((v >= 0) & (v <= 1)) and np.all((v == 0) == sc.absent)
            assert np.all(v[:12] > 0.9)                     # in full view first
            first = np.flatnonzero(sc.absent)[0]
            assert 0 < v[first - 1] < 0.9                   # it goes gradually
            clip, absent = fs.failure_scene(kind, s)
            np.testing.assert_array_equal(clip.frames.array, sc.clip.frames.array)
            np.testing.assert_array_equal(absent, sc.absent)


def test_the_calibration_set():
    cs = fs.calibration_set(seed=3, per_kind=2)
    assert len(cs) == 14 and [k for k, _ in cs.specs] == [k for k in fs.KINDS for _ in (0, 1)]
    assert fs.calibration_set(seed=3, per_kind=2).specs == cs.specs
    assert fs.calibration_set(seed=4, per_kind=2).specs != cs.specs
    sc = cs[2]
    assert sc.kind == "occlusion" and isinstance(sc.clip, clips.Clip)
    clip, absent = fs.failure_scene(sc.kind, sc.seed)
    np.testing.assert_array_equal(sc.clip.frames.array, clip.frames.array)
    np.testing.assert_array_equal(sc.absent, absent)
    assert [x.kind for x in cs[:3]] == ["exit", "exit", "occlusion"]
    assert fs.calibration_set(per_kind=1, kinds=("fade",)).specs[0][0] == "fade"


@pytest.mark.parametrize("call, word", [
    (lambda: fs.failure_scene("exits", 0), "kinds: exit, occlusion"),
    (lambda: fs.failure_scene("exit", -1), "negative"),
    (lambda: fs.failure_scene("exit", None), "integer seed"),
    (lambda: fs.failure_scene("exit", 0, frames=20), ">= 40"),
    (lambda: fs.failure_scene("exit", 0, size=(50, 40)), "at least"),
    (lambda: fs.calibration_set(per_kind=0), "per_kind"),
    (lambda: fs.calibration_set(kinds=("exit", "wipe")), "wipe"),
])
def test_bad_input_is_refused_naming_the_fix(call, word):
    with pytest.raises(ValueError, match=word):
        call()


def test_size_and_length_can_be_given():
    clip, absent = fs.failure_scene("occlusion", 5, size=(160, 120), frames=60)
    assert clip.size == (160, 120) and len(clip) == 60 and absent.any()
