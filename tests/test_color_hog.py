"""The three trackers of Lee et al. 2012 (color-pf, color-hog-pf, color-hog-ipca)."""

import cv2
import numpy as np
import pytest

from trackbook import clips, evaluate, trackers
from trackbook.clips import ArrayFrames, Clip
from trackbook.trackers.failure import FailureParams

NAMES = ["color-pf", "color-hog-pf", "color-hog-ipca"]


def moving_target_clip(n=50, seed=0):
    """A striped, two-coloured 24 x 36 target crossing a smooth grey-green background."""
    rng = np.random.default_rng(seed)
    bg = cv2.resize(rng.integers(60, 140, (12, 16, 3), dtype=np.uint8), (320, 240),
                    interpolation=cv2.INTER_CUBIC)
    target = np.zeros((36, 24, 3), np.uint8)
    target[:, :] = (30, 30, 200)                     # red (BGR)
    target[::6] = (200, 60, 20)                      # blue stripes: shape for the HOG
    target[:, :4] = (20, 200, 220)
    frames, gt = [], []
    for t in range(n):
        x = 40 + 3.5 * t + 10 * np.sin(t / 6)
        y = 100 + 30 * np.sin(t / 9)
        f = bg.copy()
        xi, yi = int(round(x)), int(round(y))
        f[yi:yi + 36, xi:xi + 24] = target
        frames.append(f)
        gt.append((xi, yi, 24, 36))
    return Clip("synthetic", ArrayFrames(np.stack(frames)), np.array(gt, float))


@pytest.fixture(scope="module")
def clip():
    return moving_target_clip()


def test_registered():
    for n in NAMES:
        assert n in trackers.available()


def test_paper_defaults():
    p = trackers.create("color-hog-ipca").params
    assert (p.n_particles, p.alpha, p.T, p.K, p.forgetting, p.resampler) == \
        (100, 0.1, 40, 2, 0.95, "multinomial")
    assert p.learn_threshold == 0.0 and p.gate_k == 0.0 and p.learn_every == 1
    assert p.anchor == 0.7          # beyond the paper (0); chosen on the dev sequences


@pytest.mark.parametrize("name", NAMES)
def test_deterministic_under_seed(name, clip):
    a = evaluate(name, clip, seed=3, max_frames=15)
    b = evaluate(name, clip, seed=3, max_frames=15)
    np.testing.assert_array_equal(a.boxes, b.boxes)
    c = evaluate(name, clip, seed=4, max_frames=15)
    assert not np.array_equal(a.boxes, c.boxes)


@pytest.mark.parametrize("name", NAMES)
def test_follows_synthetic_target(name, clip):
    """Measured (seed 0, default params): AUC 0.51 / 0.71 / 0.69 (color-pf / color-hog-pf /
    color-hog-ipca), mean centre error 4.9 / 2.6 / 2.8 px.
    A tracker that stayed at the start box would score AUC < 0.1 (the target leaves it after
    ~8 frames), so 0.4 separates following from losing with margin."""
    r = evaluate(name, clip, seed=0)
    assert r.scores["auc"] > 0.4, r.scores
    assert np.all(np.isfinite(r.boxes))


def test_learning_switches_on_after_T(clip):
    """Frames 0..T-1 (T = 10 here, the initial box included) are collected; the SVD is taken
    after frame T-1, so frame T is the first weighted by the reconstruction error."""
    t = trackers.create("color-hog-ipca", seed=0, T=10, K=4)
    t.init(clip.frames[0], clip.groundtruth[0])
    for i in range(1, 9):
        t.update(clip.frames[i])
        assert t.basis is None and not t.learning
    t.update(clip.frames[9])
    assert t.learning
    b = t.basis
    assert b["color"].shape == (256, 4) and b["hog"].shape == (192, 4)
    np.testing.assert_allclose(b["hog"].T @ b["hog"], np.eye(4), atol=1e-10)
    assert t.frame_report()["learning"] == 1.0


def test_gated_learning_skips_frames(clip):
    """A threshold of 1 can never be cleared, so nothing past the first frame is learned."""
    t = trackers.create("color-hog-ipca", seed=0, T=5, learn_threshold=1.0)
    t.init(clip.frames[0], clip.groundtruth[0])
    for i in range(1, 12):
        t.update(clip.frames[i])
    assert t.n_learned == 1 and t.basis is None


def test_read_only_views(clip):
    t = trackers.create("color-hog-pf", seed=0, n_particles=30)
    t.init(clip.frames[0], clip.groundtruth[0])
    t.update(clip.frames[1])
    assert t.particles.shape == (30, 6) and t.weights.shape == (30,)
    with pytest.raises(ValueError):
        t.particles[0, 0] = 1.0
    assert np.isclose(t.weights.sum(), 1.0)


@pytest.mark.parametrize("name", NAMES)
def test_flat_frames_and_edge_box_no_nan(name):
    """Flat grey frames (every histogram identical, every HOG uniform) and a box touching the
    frame corner: all weights equal, the tracker keeps going, never NaN."""
    flat = np.full((120, 160, 3), 128, np.uint8)
    t = trackers.create(name, seed=0, T=5) if name == "color-hog-ipca" else \
        trackers.create(name, seed=0)
    t.init(flat, (0, 0, 20, 30))
    for _ in range(12):
        ok, box = t.update(flat)
        assert np.all(np.isfinite(box)) and box[2] > 0 and box[3] > 0
    assert np.allclose(t.weights, t.weights[0])
    assert np.all(np.isfinite(t.particles))


def test_all_zero_likelihood_recovers(clip, monkeypatch):
    t = trackers.create("color-hog-pf", seed=0)
    t.init(clip.frames[0], clip.groundtruth[0])
    t.update(clip.frames[1])
    monkeypatch.setattr(t, "likelihood", lambda frame, p: np.zeros(len(p)))
    ok, box = t.update(clip.frames[2])
    assert not ok and t.lost and np.all(np.isfinite(box))
    monkeypatch.undo()
    ok, box = t.update(clip.frames[3])
    assert ok and np.all(np.isfinite(box))


def test_bad_params():
    with pytest.raises(ValueError, match="alpha"):
        trackers.create("color-hog-pf", alpha=2.0)
    with pytest.raises(ValueError, match="init"):
        trackers.create("color-pf", init="nowhere")
    with pytest.raises(ValueError, match="unknown"):
        trackers.create("color-pf", K=3)


SAMPLE = "robot-corridor-day"


@pytest.mark.slow
@pytest.mark.skipif(SAMPLE not in clips.available(), reason="sample clips not generated yet")
@pytest.mark.parametrize("name", NAMES)
def test_follows_sample_clip(name):
    """Measured (seed 0, defaults) on robot-corridor-day: AUC 0.64 / 0.79 / 0.80 and tracking
    rate 0.84 / 1.0 / 1.0 (color-pf / color-hog-pf / color-hog-ipca); 0.5 leaves margin for
    the colour-only baseline while a tracker that loses the walker scores well below it."""
    r = evaluate(name, SAMPLE, seed=0)
    assert r.scores["auc"] > 0.5, r.scores


def test_anchor_one_is_the_fixed_reference_tracker(clip):
    """anchor = 1 weighs only the first-frame Bhattacharyya term after T, so color-hog-ipca
    must reproduce color-hog-pf box for box (learning draws no random numbers)."""
    a = evaluate("color-hog-ipca", clip, seed=2, max_frames=25, T=5, anchor=1.0)
    b = evaluate("color-hog-pf", clip, seed=2, max_frames=25)
    np.testing.assert_array_equal(a.boxes, b.boxes)
    assert a.extras["learning"][-1] == 1.0


def test_anchor_mixes_the_two_distances(clip):
    from trackbook.features.color import bhattacharyya_coefficient
    t = trackers.create("color-hog-ipca", seed=0, T=5, K=2, anchor=0.3)
    t.init(clip.frames[0], clip.groundtruth[0])
    for i in range(1, 8):
        t.update(clip.frames[i])
    assert t.learning
    feats = t.features(clip.frames[8], clip.groundtruth[7:10])
    d2 = t._distances2(feats)
    for k, h in feats.items():
        sub = t._subspaces[k].reconstruction_error(np.sqrt(h).T) ** 2
        ref = 1 - bhattacharyya_coefficient(h, t.reference[k])
        np.testing.assert_allclose(d2[k], 0.3 * ref + 0.7 * sub)


def test_learn_every_k_frames(clip):
    t = trackers.create("color-hog-ipca", seed=0, T=50, learn_every=3)
    t.init(clip.frames[0], clip.groundtruth[0])
    for i in range(1, 16):
        t.update(clip.frames[i])
    assert t.n_learned == 1 + 15 // 3


def test_relative_gate_refuses_an_occlusion(clip):
    """After 20 frames of the target, frames where a grey square hides it fall far below the
    recent similarities: the relative gate refuses them, the ungated tracker learns them."""
    frames = [f.copy() for f in clip.frames[:30]]
    for i in range(20, 30):
        x, y, w, h = clip.groundtruth[i].astype(int)
        frames[i][max(0, y - 20):y + h + 20, max(0, x - 20):x + w + 20] = 128
    counts = {}
    for k in (0.0, 2.0):
        # failure=False: the failure-detection layer off, to see the learning gate alone (the
        # failure layer also stops learning: a lost frame is not learned, see the next test)
        t = trackers.create("color-hog-ipca", seed=0, T=10, gate_k=k, failure=False)
        t.init(frames[0], clip.groundtruth[0])
        for i in range(1, 20):
            t.update(frames[i])
        before = t.n_learned
        for i in range(20, 30):
            t.update(frames[i])
        counts[k] = (t.n_learned - before, t.n_rejected)
    assert counts[0.0] == (10, 0)
    assert counts[2.0][0] <= 2 and counts[2.0][1] >= 8


def test_lost_frames_are_not_learned(clip):
    """With a failure layer tight enough to judge the grey occluder lost (the calibrated
    thresholds are looser: the contract test reports how often), the occluded frames are
    reported lost and none of them joins the subspaces, even with the learning gate off."""
    frames = [f.copy() for f in clip.frames[:30]]
    for i in range(20, 30):
        x, y, w, h = clip.groundtruth[i].astype(int)
        frames[i][max(0, y - 20):y + h + 20, max(0, x - 20):x + w + 20] = 128
    t = trackers.create("color-hog-ipca", seed=0, T=10, gate_k=0.0,
                        failure=FailureParams(k_lost=3, k_found=3, m=3, window=30, warmup=5))
    t.init(frames[0], clip.groundtruth[0])
    for i in range(1, 20):
        t.update(frames[i])
    before = t.n_learned
    oks = [t.update(frames[i])[0] for i in range(20, 30)]
    assert sum(oks) <= 2
    assert t.n_learned - before == sum(oks)


def test_relative_gate_rule_by_hand(monkeypatch):
    """e = -log s against median + k * 1.4826 * MAD of the accepted energies. History of
    energies 1, 2, 3, 4, 5: median 3, MAD 1, so with k = 2 the bound is 3 + 2.9652 = 5.9652."""
    t = trackers.create("color-hog-ipca", seed=0, gate_k=2.0)
    t._gate_history, t._n_rejected = [], 0
    for e in (1.0, 2.0, 3.0, 4.0, 5.0):                 # the first five always pass
        monkeypatch.setattr(t, "_estimate_similarity", lambda f, e=e: np.exp(-e))
        assert t._gate(None)
    for e, accepted in ((5.96, True), (6.0, False), (50.0, False)):
        hist = list(t._gate_history)
        monkeypatch.setattr(t, "_estimate_similarity", lambda f, e=e: np.exp(-e))
        assert t._gate(None) == accepted, e
        t._gate_history = hist                          # judge each against the same history
    assert t.n_rejected == 2
