"""SORT (trackbook.mot): its Kalman filter against filterpy, its assignment on hand cases,
identities through a crossing and a disappearance, and the synthetic detections it runs on."""

from __future__ import annotations

import doctest
import importlib

import numpy as np
import pytest

from trackbook import mot
from trackbook.evaluation.mot import clear_mot
from trackbook.mot.sort import _Track


def filterpy_twin(kf):
    """A filterpy KalmanFilter with the same matrices and state as ``kf``."""
    filterpy = pytest.importorskip("filterpy.kalman")
    ref = filterpy.KalmanFilter(dim_x=7, dim_z=4)
    for name in ("F", "H", "Q", "R", "P"):
        setattr(ref, name, getattr(kf, name).copy())
    ref.x = kf.x.reshape(7, 1).copy()
    return ref


# --- the filter ----------------------------------------------------------------------------

def test_the_box_filter_is_sorts_model():
    kf = mot.box_filter((10, 20, 30, 60))
    # state (u, v, s, r, u̇, v̇, ṡ) = (25, 50, 1800, 0.5, 0, 0, 0) from the box's centre, area, ratio
    assert kf.x.tolist() == [25.0, 50.0, 1800.0, 0.5, 0.0, 0.0, 0.0]
    # F: u, v, s advance by their velocities, r and the velocities stay
    x = np.arange(1.0, 8.0)
    assert (kf.F @ x).tolist() == [6.0, 8.0, 10.0, 4.0, 5.0, 6.0, 7.0]
    assert (kf.H @ x).tolist() == [1.0, 2.0, 3.0, 4.0]
    assert np.diag(kf.R).tolist() == [1.0, 1.0, 10.0, 10.0]
    assert np.diag(kf.P).tolist() == [10.0] * 4 + [1e4] * 3
    assert np.diag(kf.Q).tolist() == [1.0] * 4 + [1e-2, 1e-2, 1e-4]
    for m in (kf.R, kf.P, kf.Q):
        assert np.count_nonzero(m - np.diag(np.diag(m))) == 0


def test_box_filter_predict_and_update_match_filterpy():
    rng = np.random.default_rng(3)
    kf = mot.box_filter((100, 50, 40, 80))
    ref = filterpy_twin(kf)
    box = np.array([100.0, 50.0, 40.0, 80.0])
    for k in range(25):
        kf.predict()
        ref.predict()
        np.testing.assert_allclose(kf.x, ref.x.ravel(), rtol=0, atol=1e-9)
        np.testing.assert_allclose(kf.P, ref.P, rtol=0, atol=1e-9)
        if k % 4 == 3:
            continue                                     # a missed frame: predict only
        box = box + np.r_[5.0, -2.0, 0.3, 0.5] + rng.normal(0, 1.5, 4)
        z = mot.box_to_z(box)
        kf.update(z)
        ref.update(z)
        np.testing.assert_allclose(kf.x, ref.x.ravel(), rtol=0, atol=1e-9)
        np.testing.assert_allclose(kf.P, ref.P, rtol=0, atol=1e-9)


def test_box_and_z_round_trip():
    box = np.array([12.5, -3.0, 41.0, 17.0])
    z = mot.box_to_z(box)
    assert z.tolist() == [12.5 + 20.5, -3.0 + 8.5, 41.0 * 17.0, 41.0 / 17.0]
    np.testing.assert_allclose(mot.z_to_box(z), box, rtol=0, atol=1e-12)


def test_an_area_shrinking_through_zero_stops_shrinking():
    t = _Track((0, 0, 10, 10), track_id=1)
    t.kf.x[2], t.kf.x[6] = 100.0, -150.0                # s + ṡ < 0: the next area would be < 0
    t.predict()
    assert t.kf.x[6] == 0.0 and t.kf.x[2] == 100.0


# --- assignment --------------------------------------------------------------------------

def test_associate_solves_on_all_pairs_then_gates_as_sort_does_or_gates_first():
    # 10 x 10 boxes shifted along x by d have IoU (10 − d) / (10 + d).
    # tracks t0 at x = 0, t1 at x = 4; detections d0 at x = 1, d1 at x = −3:
    #   d0–t0: d = 1, 9/11 = 0.818   d0–t1: d = 3, 7/13 = 0.538
    #   d1–t0: d = 3, 0.538          d1–t1: d = 7, 3/17 = 0.176
    # Largest total IoU: d0–t1 + d1–t0 = 1.077 beats d0–t0 + d1–t1 = 0.995. d2 and t2 are far
    # from everything (IoU 0: paired by the optimum, then rejected by any gate).
    dets = [(1, 0, 10, 10), (-3, 0, 10, 10), (500, 500, 10, 10)]
    tracks = [(0, 0, 10, 10), (4, 0, 10, 10), (-500, 0, 10, 10)]
    for gate_first in (False, True):          # at 0.3 both orders keep the two 0.538 pairs
        matches, lone_dets, lone_tracks = mot.associate(dets, tracks, iou_threshold=0.3,
                                                        gate_first=gate_first)
        assert matches.tolist() == [[0, 1], [1, 0]]
        assert lone_dets.tolist() == [2] and lone_tracks.tolist() == [2]
    # at 0.6 SORT's optimum is still the crossing pairs, both below the gate: nothing is kept;
    # gating first forbids the 0.538 pairs before solving, so d0–t0 (0.818) is kept
    assert mot.associate(dets, tracks, iou_threshold=0.6)[0].tolist() == []
    assert mot.associate(dets, tracks, iou_threshold=0.6,
                         gate_first=True)[0].tolist() == [[0, 0]]
    empty = mot.associate(np.zeros((0, 4)), tracks)
    assert empty[0].shape == (0, 2) and empty[2].tolist() == [0, 1, 2]


# --- identities --------------------------------------------------------------------------

def crossing(n_frames=40, seed=0, noise=1.5):
    """Two 40 x 80 targets crossing: A rightwards at y = 100, B leftwards at y = 120."""
    rng = np.random.default_rng(seed)
    t = np.arange(n_frames, dtype=float)
    size = np.tile([40.0, 80.0], (n_frames, 1))
    a = np.c_[100 + 6 * t, np.full(n_frames, 100.0), size]
    b = np.c_[100 + 6 * t[::-1], np.full(n_frames, 120.0), size]
    truth = [np.array([np.r_[a[k], 1], np.r_[b[k], 2]]) for k in range(n_frames)]
    dets = [np.array([b[k], a[k]]) + rng.normal(0, noise, (2, 4)) for k in range(n_frames)]
    return truth, dets


@pytest.mark.parametrize("seed", range(5))
def test_two_crossing_targets_keep_their_ids(seed):
    truth, dets = crossing(seed=seed)
    # at the crossing the two boxes overlap with IoU 0.6: the detections alone do not say who
    # is who, the predicted motion does
    sort = mot.Sort()
    tracks = [sort.update(d) for d in dets]
    s = clear_mot(truth, tracks)
    assert s.switches == 0
    assert s.misses == 2 * 3                            # the first 3 frames, before min_hits
    assert s.false_positives == 0
    assert {int(i) for t in tracks for i in t[:, 4]} == {1, 2}


def one_target(frames, n_frames):
    """Detections of one 30 x 30 target moving 2 px a frame, present in ``frames`` only."""
    return [np.array([[50 + 2.0 * k, 40.0, 30.0, 30.0]]) if k in frames else np.zeros((0, 4))
            for k in range(n_frames)]


def test_a_target_away_longer_than_max_age_comes_back_with_a_new_id():
    sort = mot.Sort(max_age=2, min_hits=1)
    frames = set(range(10)) | set(range(13, 20))       # away for 3 frames > max_age
    out = [sort.update(d) for d in one_target(frames, 20)]
    assert {int(i) for t in out[:10] for i in t[:, 4]} == {1}
    assert {int(i) for t in out[13:] for i in t[:, 4]} == {2}


def test_a_target_away_for_max_age_frames_keeps_its_id():
    sort = mot.Sort(max_age=2, min_hits=1)
    frames = set(range(10)) | set(range(12, 20))       # away for 2 frames = max_age
    out = [sort.update(d) for d in one_target(frames, 20)]
    assert {int(i) for t in out for i in t[:, 4]} == {1}
    assert all(len(out[k]) == 1 for k in range(12, 20))


def test_a_track_is_reported_after_min_hits_consecutive_matches():
    # started on frame 0, matched on 1, 2, 3: reported from frame 3. Missed on frame 6 (kept:
    # max_age 1), its streak restarts on frame 7: matched 7, 8, 9 -> reported again from 9.
    sort = mot.Sort(max_age=1, min_hits=3)
    frames = set(range(12)) - {6}
    out = [sort.update(d) for d in one_target(frames, 12)]
    reported = [k for k, t in enumerate(out) if len(t)]
    assert reported == [3, 4, 5, 9, 10, 11]
    assert {int(t[0, 4]) for t in out if len(t)} == {1}


def test_sort_is_deterministic_and_ids_start_at_one_per_tracker():
    run = mot.synthetic_detections(n_targets=5, n_frames=50, seed=4)
    first = [mot.Sort().update(d) for d in run.detections[:1]]
    a, b = mot.Sort(), mot.Sort()
    out_a = [a.update(d) for d in run.detections]
    out_b = [b.update(d) for d in run.detections]
    assert all(np.array_equal(x, y) for x, y in zip(out_a, out_b))
    assert first[0].shape == (0, 5)
    a.reset()
    again = [a.update(d) for d in run.detections]
    assert all(np.array_equal(x, y) for x, y in zip(out_a, again))
    assert min(int(i) for t in out_a for i in t[:, 4]) == 1


def test_scores_are_ignored_and_rows_are_sorted_by_id():
    run = mot.synthetic_detections(n_targets=4, n_frames=30, seed=1)
    with_score = [mot.Sort().update(d) for d in run.detections[:1]]
    s1, s2 = mot.Sort(), mot.Sort()
    for d in run.detections:
        o1, o2 = s1.update(d), s2.update(d[:, :4])
        assert np.array_equal(o1, o2)
        assert np.all(np.diff(o1[:, 4]) > 0)
    assert with_score[0].shape == (0, 5)


@pytest.mark.parametrize("bad, message", [
    (np.zeros((3, 3)), "(n, 4)"),
    (np.array([[0.0, 0.0, 0.0, 10.0]]), "positive width"),
    (np.array([[np.nan, 0.0, 5.0, 10.0]]), "finite"),
])
def test_bad_detections_are_refused(bad, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        mot.Sort().update(bad)


def test_bad_parameters_are_refused():
    with pytest.raises(ValueError, match="max_age"):
        mot.Sort(max_age=-1)
    with pytest.raises(ValueError, match="iou_threshold"):
        mot.Sort(iou_threshold=1.5)


def test_sort_is_not_a_single_target_tracker():
    from trackbook import trackers
    assert not [n for n in trackers.available() if "sort" in n.lower()]


# --- the synthetic detections ------------------------------------------------------------

def test_synthetic_runs_repeat_with_the_seed():
    a = mot.synthetic_detections(3, 20, seed=7)
    b = mot.synthetic_detections(3, 20, seed=7)
    c = mot.synthetic_detections(3, 20, seed=8)
    assert all(np.array_equal(x, y) for x, y in zip(a.detections, b.detections))
    assert all(np.array_equal(x, y) for x, y in zip(a.truth, b.truth))
    assert not all(np.array_equal(x, y) for x, y in zip(a.truth, c.truth))


def test_without_noise_misses_or_false_positives_the_detections_are_the_truth():
    run = mot.synthetic_detections(5, 15, seed=2, miss_rate=0.0, fp_rate=0.0, noise=0.0)
    for g, d in zip(run.truth, run.detections):
        assert np.array_equal(np.unique(g[:, :4], axis=0), np.unique(d[:, :4], axis=0))
        assert np.all((d[:, 4] >= 0.5) & (d[:, 4] <= 1.0))


def test_synthetic_paths_cross_and_stay_in_the_scene():
    run = mot.synthetic_detections(4, 30, seed=0, frame_size=(640, 480))
    x = np.array([g[:, 0] for g in run.truth])              # (frames, targets)
    # targets 1 and 2 go opposite ways from opposite sides: their order in x flips
    assert np.sign(x[0, 0] - x[0, 1]) == -np.sign(x[-1, 0] - x[-1, 1])
    boxes = np.vstack(run.truth)
    assert boxes[:, 0].min() >= 0 and (boxes[:, 0] + boxes[:, 2]).max() <= 640 + 1e-9
    assert boxes[:, 1].min() >= 0 and (boxes[:, 1] + boxes[:, 3]).max() <= 480 + 1e-9


def test_synthetic_rates_and_noise_are_the_ones_asked_for():
    n_targets, n_frames = 10, 300
    run = mot.synthetic_detections(n_targets, n_frames, seed=5, miss_rate=0.3, fp_rate=0.0,
                                   noise=3.0)
    seen = sum(len(d) for d in run.detections) / (n_targets * n_frames)
    assert abs(seen - 0.7) < 3 * np.sqrt(0.21 / 3000)       # 3 binomial standard deviations
    # one target, always seen: each detection minus its true box is the noise, sd 3 px
    one = mot.synthetic_detections(1, 1000, seed=5, miss_rate=0.0, fp_rate=0.0, noise=3.0)
    res = np.vstack([d[:, :4] - g[:, :4] for g, d in zip(one.truth, one.detections)])
    assert abs(res.std() - 3.0) < 0.1 and abs(res.mean()) < 0.1
    fps = mot.synthetic_detections(2, 2000, seed=6, miss_rate=0.0, fp_rate=1.5)
    per_frame = np.mean([len(d) - 2 for d in fps.detections])
    assert abs(per_frame - 1.5) < 3 * np.sqrt(1.5 / 2000)    # 3 Poisson standard deviations


@pytest.mark.parametrize("kwargs, message", [
    ({"n_targets": 0}, "n_targets"), ({"miss_rate": 1.0}, "miss_rate"),
    ({"fp_rate": -1.0}, "fp_rate"), ({"noise": -0.5}, "noise"),
])
def test_bad_synthetic_parameters_are_refused(kwargs, message):
    with pytest.raises(ValueError, match=message):
        mot.synthetic_detections(**kwargs)


@pytest.mark.parametrize("name", ["trackbook.mot", "trackbook.mot.sort", "trackbook.mot.synthetic",
                                  "trackbook.evaluation.mot"])
def test_the_docstring_examples_run(name):
    result = doctest.testmod(importlib.import_module(name))
    assert result.attempted > 0 and result.failed == 0
