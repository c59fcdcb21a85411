"""Resamplers, ESS, weights (filters/particle.py) and the eq. 9 / eq. 10-14 models (motion.py)."""

import numpy as np
import pytest
from scipy import stats

from .conftest import moving_square_frames
from trackbook.filters.lee2012_models import (EQ9_NOISE, box_to_state, clamp_states, fuse,
                                              gaussian_likelihood, predict_eq9, similarity,
                                              states_to_boxes)
from trackbook.filters.particle import (RESAMPLERS, effective_sample_size, normalize_weights,
                                        weighted_mean)

W8 = np.array([0.05, 0.3, 0.0, 0.15, 0.1, 0.25, 0.05, 0.1])


@pytest.mark.parametrize("name", sorted(RESAMPLERS))
def test_resampler_counts_match_weights(name):
    """Pooled over 400 draws of N = 8 the copies of particle i are ~ N w_i each time: a
    chi-square goodness-of-fit test at the 0.1 % level (fixed seed, so not flaky)."""
    rng = np.random.default_rng(123)
    reps, n = 400, W8.size
    counts = np.zeros(n)
    for _ in range(reps):
        idx = RESAMPLERS[name](W8, rng)
        assert idx.shape == (n,) and idx.min() >= 0 and idx.max() < n
        counts += np.bincount(idx, minlength=n)
    expected = reps * n * W8
    assert counts[2] == 0                          # a zero-weight particle is never drawn
    keep = expected > 0
    chi2 = np.sum((counts[keep] - expected[keep]) ** 2 / expected[keep])
    assert chi2 < stats.chi2.ppf(0.999, keep.sum() - 1)


@pytest.mark.parametrize("name", ["systematic", "stratified", "residual"])
def test_low_variance_resamplers_keep_floor_copies(name):
    """Systematic, stratified and residual resampling give particle i floor(N w_i) or
    ceil(N w_i) copies (residual: at least the floor)."""
    rng = np.random.default_rng(7)
    w = np.array([0.34, 0.33, 0.2, 0.13])
    for _ in range(50):
        c = np.bincount(RESAMPLERS[name](w, rng), minlength=4)
        assert np.all(c >= np.floor(4 * w) - (name == "stratified"))
        if name == "systematic":
            assert np.all(c <= np.ceil(4 * w))


def test_multinomial_single_particle_binomial():
    """The copies of one particle under multinomial resampling are Binomial(N, w_i)."""
    rng = np.random.default_rng(5)
    w = np.full(20, 0.5 / 19)
    w[0] = 0.5
    c0 = [np.sum(RESAMPLERS["multinomial"](w, rng) == 0) for _ in range(2000)]
    assert stats.binomtest(int(np.sum(c0)), 2000 * 20, 0.5).pvalue > 1e-3
    assert abs(np.var(c0) - 20 * 0.5 * 0.5) < 1.0       # var of Binomial(20, 0.5) = 5


@pytest.mark.parametrize("name", sorted(RESAMPLERS))
def test_resamplers_are_pure(name):
    w = np.random.default_rng(0).dirichlet(np.ones(30))
    a = RESAMPLERS[name](w, np.random.default_rng(42))
    b = RESAMPLERS[name](w, np.random.default_rng(42))
    np.testing.assert_array_equal(a, b)
    w_copy = w.copy()
    RESAMPLERS[name](w, np.random.default_rng(1))
    np.testing.assert_array_equal(w, w_copy)               # weights untouched


def test_ess_hand_cases():
    assert effective_sample_size(np.full(10, 0.1)) == pytest.approx(10)
    assert effective_sample_size(np.r_[1.0, np.zeros(9)]) == pytest.approx(1)
    assert effective_sample_size([0.5, 0.5, 0, 0]) == pytest.approx(2)
    assert effective_sample_size([0.25, 0.75]) == pytest.approx(1 / (0.0625 + 0.5625))


def test_normalize_all_zero_or_nan_is_uniform():
    w, ok = normalize_weights(np.zeros(4))
    assert not ok and np.allclose(w, 0.25)
    w, ok = normalize_weights([np.nan, 1.0, 1.0, np.inf])
    assert ok and np.allclose(w, [0, 0.5, 0.5, 0])
    w, ok = normalize_weights(np.full(5, 3.0))
    assert ok and np.allclose(w, 0.2)


def test_weighted_mean():
    s = np.array([[0.0, 0.0], [10.0, 2.0]])
    np.testing.assert_allclose(weighted_mean(s, [0.25, 0.75]), [7.5, 1.5])


# -- eq. 8-9 ---------------------------------------------------------------------------
def test_state_box_round_trip():
    s = box_to_state((10, 20, 30, 40))
    np.testing.assert_allclose(s, [25, 40, 30, 40, 0, 0])
    np.testing.assert_allclose(states_to_boxes(s), [[10, 20, 30, 40]])


def test_predict_eq9_without_noise_is_constant_velocity():
    p = np.array([[50.0, 60.0, 20.0, 30.0, 3.0, -2.0]])
    out = predict_eq9(p, np.random.default_rng(0), noise=(0, 0, 0, 0))
    np.testing.assert_allclose(out, [[53, 58, 20, 30, 3, -2]])


def test_predict_eq9_noise_ranges_and_means():
    rng = np.random.default_rng(1)
    p = np.zeros((20000, 6))
    p[:, 2:4] = 50
    out = predict_eq9(p, rng)
    np.testing.assert_allclose(out[:, :2], 0)            # position moves by the OLD velocity (0)
    a = np.array(EQ9_NOISE)
    delta = out[:, 2:] - p[:, 2:]
    assert np.all(np.abs(delta) <= a)
    np.testing.assert_allclose(delta.max(axis=0), a, rtol=0.01)
    np.testing.assert_allclose(delta.std(axis=0), a / np.sqrt(3), rtol=0.03)   # U(-a, a)
    assert np.all(np.abs(delta.mean(axis=0)) < 0.05 * a)


def test_predict_is_deterministic_under_seed():
    p = np.tile([50.0, 60, 20, 30, 1, 1], (7, 1))
    np.testing.assert_array_equal(predict_eq9(p, np.random.default_rng(3)),
                                  predict_eq9(p, np.random.default_rng(3)))


def test_clamp_states():
    s = np.array([[-5.0, 500.0, -3.0, 1000.0, 0, 0]])
    clamp_states(s, (240, 320, 3), min_size=4)
    np.testing.assert_allclose(s, [[0, 240, 4, 240, 0, 0]])


# -- eq. 10-11 (corrected) and eq. 14 --------------------------------------------------
def test_similarity_rewards_similarity_not_the_papers_typo():
    s = similarity([0.0, 0.1, 0.5, 1.0], 0.4)
    assert s[0] == 1.0 and np.all(np.diff(s) < 0)
    np.testing.assert_allclose(s[2], np.exp(-0.5 / 0.32))


def test_gaussian_likelihood_constant():
    np.testing.assert_allclose(gaussian_likelihood(0.0, 0.4), 1 / np.sqrt(2 * np.pi * 0.16))


def test_fuse_eq14():
    np.testing.assert_allclose(fuse([1.0, 0.0], [0.0, 1.0], 0.1), [0.1, 0.9])
    with pytest.raises(ValueError, match="alpha"):
        fuse(1.0, 1.0, 1.5)


# -- the resampler registry: a user's resampler without editing the library -------------------

def _square_frames(n=6):
    """A red 20 x 20 square moving 3 px a frame over a grey noise background."""
    return moving_square_frames(n)


@pytest.fixture
def registered():
    """Register resamplers for one test and remove them afterwards."""
    from trackbook.filters import particle
    names = []

    def add(name, fn):
        particle.register_resampler(name, fn)
        names.append(name)
        return fn

    yield add
    for n in names:
        particle.RESAMPLERS.pop(n, None)


def _run(tracker, frames, box):
    tracker.init(frames[0], box)
    return [tracker.update(f)[1] for f in frames[1:]]


def test_user_resampler_is_usable_by_name(registered):
    """A resampler registered by the user is accepted by ``trackers.create`` and called once
    per frame; one that returns what ``systematic`` returns gives the same boxes."""
    from trackbook import trackers
    from trackbook.filters.particle import systematic_resample
    calls = []

    def mine(w, rng):
        calls.append(len(w))
        return systematic_resample(w, rng)

    registered("mine", mine)
    frames, box = _square_frames()
    t = trackers.create("color-pf", seed=0, resampler="mine", n_particles=50)
    boxes = _run(t, frames, box)
    assert calls == [50] * (len(frames) - 1)
    ref = _run(trackers.create("color-pf", seed=0, resampler="systematic", n_particles=50),
               frames, box)
    np.testing.assert_array_equal(boxes, ref)
    # every particle tracker's resampler param takes the new name
    assert trackers.create("condensation", resampler="mine").params.resampler == "mine"
    assert trackers.create("hsi-color-pf", resampler="mine").params.resampler == "mine"
    # what widgets and listings read (the field's choices) shows it too, in registration order
    import dataclasses
    from trackbook import params
    field = {f.name: f for f in dataclasses.fields(trackers.get("color-pf").Params)}["resampler"]
    assert params.choices_of(field)[-1] == "mine" and "mine" in list(field.metadata["choices"])


def test_unregistered_resampler_name_refused():
    from trackbook import trackers
    with pytest.raises(ValueError, match="resampler"):
        trackers.create("color-pf", resampler="not-a-resampler")


def test_ess_triggered_resampler_returning_identity_runs(registered):
    """An ESS-triggered scheme returns np.arange(N) on the frames it does not resample (the
    frame's documented contract); the tracker then runs with normalised weights."""
    from trackbook import trackers
    from trackbook.filters.particle import effective_sample_size, multinomial_resample

    def ess_triggered(w, rng):
        if effective_sample_size(w) > len(w) / 2:
            return np.arange(len(w))
        return multinomial_resample(w, rng)

    registered("ess-half", ess_triggered)
    frames, box = _square_frames()
    t = trackers.create("color-pf", seed=0, resampler="ess-half", n_particles=40)
    boxes = _run(t, frames, box)
    assert np.all(np.isfinite(boxes))
    assert np.isclose(float(np.sum(t.weights)), 1.0)


@pytest.mark.parametrize("bad, message", [
    (lambda w, rng: None, "shape"),                               # skipped: returned nothing
    (lambda w, rng: np.arange(len(w) - 1), "shape"),              # one index short
    (lambda w, rng: np.arange(len(w)) + 1, "outside"),            # past the last particle
    (lambda w, rng: np.full(len(w), 0.5), "integer"),             # not indices
    (lambda w, rng: w, "integer"),                                # returned the weights
])
def test_bad_resampler_output_fails_clearly(registered, bad, message):
    from trackbook import trackers
    registered("bad", bad)
    frames, box = _square_frames(3)
    t = trackers.create("color-pf", seed=0, resampler="bad", n_particles=20)
    t.init(frames[0], box)
    with pytest.raises(ValueError, match=f"resampler 'bad' returned.*{message}"):
        t.update(frames[1])


def test_register_resampler_refuses_bad_registrations(registered):
    from trackbook.filters import particle
    with pytest.raises(TypeError, match="callable"):
        particle.register_resampler("x", 3)
    with pytest.raises(TypeError, match="name"):
        particle.register_resampler("", particle.systematic_resample)
    with pytest.raises(ValueError, match="already registered"):
        particle.register_resampler("systematic", particle.multinomial_resample)
    # the same function again is not an error (a module imported twice)
    particle.register_resampler("systematic", particle.systematic_resample)
