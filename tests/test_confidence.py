"""``TrackerState.confidence``: every tracker's own confidence in its last estimate.

Each tracker stores the number its algorithm scored the last frame by (the best particle's
match, the peak-to-sidelobe ratio, minus the Förstner distance, the edge likelihood) while it
updates; ``state()`` only reads it. Checked here, for every registered tracker and the
``opencv-mil`` reference:

- it is a finite float after every update (None before the first), on a sample clip, on
  all-black and all-white frames, and on frames the target has left;
- reading it changes nothing: the boxes of a run that calls ``state()`` twice after every
  frame are those of a run that never calls it;
- on the scenario clips of ``tests/_scenarios.py`` (the target leaves across the border; a
  panel covers it), its mean over the frames where the target is in view is above its mean
  over the frames where it is not;
- its value is the definition its docstring gives, recomputed independently: a MOSSE PSR by
  a slow loop over the response, a ``color-pf`` match from the features module, a
  covariance distance from ``scipy.linalg.eigh``'s generalised eigenvalues.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest
import scipy.linalg

import trackbook
from trackbook import clips, trackers
from trackbook.features.color import (HSV_BINS, bhattacharyya_coefficient, hsv_bin_index_u8,
                                      kernel_weights, weighted_histograms)
from trackbook.features.covariance import feature_image, region_covariance
from trackbook.features.patches import sample_patches
from trackbook.filters.correlation import apce

from . import _scenarios as S

NAMES = trackers.available(reference=True)
#: Scenario clips in which the target is out of view for a while (``tests/_scenarios.py``).
LEAVING = ("edge-exit", "occluder")
N_SAMPLE = 25


def _library_names():
    """The registered trackers trackbook ships (other tests may have registered users')."""
    return [n for n in NAMES if trackers.get(n).__module__.startswith("trackbook.")]


_scenario = S.scenario


@lru_cache(maxsize=None)
def _watched(name, clip_key):
    """A run that reads ``state()`` twice after every frame: (result, confidences)."""
    clip = _clip(clip_key)
    seen = []

    def look(i, tracker, frame, box):
        first, second = tracker.state(), tracker.state()
        assert first.confidence == second.confidence or (
            first.confidence is None and second.confidence is None)
        seen.append(first.confidence)

    res = trackbook.evaluate(name, clip, seed=0, max_frames=_n(clip_key), on_frame=look)
    return res, seen


@lru_cache(maxsize=None)
def _unwatched(name, clip_key):
    """The same run without ever calling ``state()`` (on a scenario clip, the failure
    contract's run of it)."""
    if clip_key != "red-cube":
        return S.evaluated(name, clip_key)
    return trackbook.evaluate(name, _clip(clip_key), seed=0, max_frames=_n(clip_key))


def _clip(key):
    return clips.load(key) if key == "red-cube" else _scenario(key).clip


def _n(key):
    return N_SAMPLE if key == "red-cube" else None


@pytest.mark.parametrize("name", _library_names())
def test_state_before_and_after_init(name):
    t = trackers.create(name, seed=0)
    assert t.state().confidence is None
    clip = clips.load("red-cube")
    t.init(clip.frames[0], clip.groundtruth[0])
    assert t.state().confidence is None          # the first box is given, not estimated


@pytest.mark.parametrize("key", ("red-cube",) + LEAVING)
@pytest.mark.parametrize("name", _library_names())
def test_a_finite_float_after_every_update(name, key):
    _, seen = _watched(name, key)
    assert seen[0] is None
    bad = [i for i, c in enumerate(seen[1:], 1) if type(c) is not float or not np.isfinite(c)]
    assert not bad, f"{name} on {key}: confidence {[seen[i] for i in bad[:3]]} on frames {bad[:3]}"


@pytest.mark.parametrize("name", _library_names())
def test_a_finite_float_on_constant_frames(name):
    clip = clips.load("red-cube")
    t = trackers.create(name, seed=0)
    t.init(clip.frames[0], clip.groundtruth[0])
    for value in (0, 255, 0):
        t.update(np.full_like(clip.frames[1], value))
        c = t.state().confidence
        assert type(c) is float and np.isfinite(c), f"{name}: {c!r} on a frame of {value}"


@pytest.mark.parametrize("key", ("red-cube",) + LEAVING)
@pytest.mark.parametrize("name", _library_names())
def test_reading_it_changes_no_box(name, key):
    watched, _ = _watched(name, key)
    unwatched = _unwatched(name, key)
    np.testing.assert_array_equal(watched.boxes, unwatched.boxes)
    np.testing.assert_array_equal(watched.ok, unwatched.ok)


def _present_absent(name, key):
    """Mean confidence over the frames with the target in view and those without it (the
    given first frame left out)."""
    _, seen = _watched(name, key)
    c = np.asarray(seen[1:], float)
    absent = _scenario(key).absent[1:]
    return float(c[~absent].mean()), float(c[absent].mean())


@pytest.mark.parametrize("key", LEAVING)
@pytest.mark.parametrize("name", _library_names())
def test_higher_where_the_target_is(name, key):
    present, absent = _present_absent(name, key)
    assert present > absent, \
        f"{name} on {key}: mean confidence {present:.3g} in view, {absent:.3g} out of view"


# -- the definitions, recomputed ---------------------------------------------------------------
def _psr_by_hand(g, exclude=11):
    """Bolme et al. 2010's PSR, one cell at a time: the sidelobe is every cell outside the
    ``exclude`` x ``exclude`` window around the peak, the response taken as cyclic."""
    rows, cols = g.shape
    py, px = np.unravel_index(int(np.argmax(g)), g.shape)
    half = exclude // 2
    side = []
    for i in range(rows):
        for j in range(cols):
            di = min((i - py) % rows, (py - i) % rows)
            dj = min((j - px) % cols, (px - j) % cols)
            if di > half or dj > half:
                side.append(float(g[i, j]))
    mu = sum(side) / len(side)
    sd = (sum((s - mu) ** 2 for s in side) / len(side)) ** 0.5
    return (float(g[py, px]) - mu) / sd


def test_mosse_confidence_is_the_psr_of_its_response():
    clip = clips.load("red-cube")
    t = trackers.create("mosse", seed=0)
    t.init(clip.frames[0], clip.groundtruth[0])
    checked = 0
    for f in clip.frames[1:8]:
        ok, _ = t.update(f)
        g = np.asarray(t.response)
        assert g.shape[0] > 11 and g.shape[1] > 11        # a sidelobe outside 11 x 11 exists
        assert t.state().confidence == pytest.approx(_psr_by_hand(g), rel=1e-9)
        checked += ok
    assert checked >= 5                                    # most frames tracked, not lost


def test_apce_of_hand_worked_responses():
    """APCE = |g_max - g_min|^2 / mean((g - g_min)^2): a single unit peak on zeros over n
    cells gives 1 / (1 / n) = n; two unit peaks give n / 2; a constant map gives 0."""
    g = np.zeros((6, 5))
    g[2, 3] = 1.0
    assert apce(g) == pytest.approx(30.0)
    g[0, 0] = 1.0
    assert apce(g) == pytest.approx(15.0)
    assert apce(np.full((4, 4), 3.0)) == 0.0
    stack = np.stack([np.full((6, 5), 3.0), g])
    np.testing.assert_allclose(apce(stack), [0.0, 15.0])


def _colour_histogram(frame, boxes):
    """Eq. 1 of Lee et al. 2012 from the features module: HSV 8 x 8 x 4 bins of a 16 x 24
    patch, weighted by the kernel 1 - r^2."""
    patches = sample_patches(frame, np.asarray(boxes, float), (16, 24))
    return weighted_histograms(hsv_bin_index_u8(patches, HSV_BINS), kernel_weights(24, 16),
                               int(np.prod(HSV_BINS)))


def test_color_pf_confidence_is_its_best_particles_rho():
    clip = clips.load("red-cube")
    ref = _colour_histogram(clip.frames[0], [clip.groundtruth[0]])[0]
    t = trackers.create("color-pf", seed=0)
    t.init(clip.frames[0], clip.groundtruth[0])
    for f in clip.frames[1:6]:
        t.update(f)
        st = t.state()
        p = np.asarray(st.particles)            # (N, 6): cx, cy, w, h, x_dot, y_dot (eq. 8)
        boxes = np.column_stack([p[:, 0] - p[:, 2] / 2, p[:, 1] - p[:, 3] / 2, p[:, 2], p[:, 3]])
        rho = bhattacharyya_coefficient(_colour_histogram(f, boxes), ref)
        assert st.confidence == pytest.approx(float(rho.max()), abs=1e-9)
        assert 0.5 < st.confidence <= 1.0                  # the cube is there


def test_covariance_confidence_is_minus_the_forstner_distance():
    """-d_F with d_F = sqrt(sum ln^2 lambda), lambda the generalised eigenvalues of
    (C_best + eps I) x = lambda (C_model + eps I) x, C from the direct formula of eq. 4 over
    the returned box's pixels (the tracker uses integral images)."""
    clip = clips.load("red-cube")
    t = trackers.create("covariance", seed=0)
    t.init(clip.frames[0], clip.groundtruth[0])
    eps, d = t.params.eps, len(t.model)
    checked = 0
    for f in clip.frames[1:6]:
        ok, box = t.update(f)
        if not ok:
            continue                          # the returned box is the best window only if ok
        x, y, w, h = (int(v) for v in box)
        C = region_covariance(feature_image(f)[y:y + h, x:x + w])
        lam = scipy.linalg.eigh(C + eps * np.eye(d), t.model + eps * np.eye(d),
                                eigvals_only=True)
        d_f = float(np.sqrt(np.sum(np.log(lam) ** 2)))
        assert t.state().confidence == pytest.approx(-d_f, rel=1e-6)
        checked += 1
    assert checked >= 4
