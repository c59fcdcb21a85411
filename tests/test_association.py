"""Data association of ``08_mean_shift``: gate, Hungarian assignment, identity switches."""
import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbook import clips
from trackbook.evaluation.identity import identity_switches, matched_identities
from trackbook.trackers.association import (CHI2_GATE_99, AssociatedMultiTracker, assign, gate,
                                            iou_matrix, mahalanobis_matrix)


def brute_force(cost, allowed):
    """Best matching by trying every injection of the smaller side: most pairs, then least cost."""
    n, m = cost.shape
    best = (0, 0.0)
    if n <= m:
        perms = ((list(range(n)), list(p)) for p in itertools.permutations(range(m), n))
    else:
        perms = ((list(p), list(range(m))) for p in itertools.permutations(range(n), m))
    for rows, cols in perms:
        pairs = [(r, c) for r, c in zip(rows, cols) if allowed[r, c]]
        key = (-len(pairs), sum(cost[r, c] for r, c in pairs))
        if key < (-best[0], best[1]):
            best = (len(pairs), key[1])
    return best


@settings(max_examples=80, deadline=None)
@given(st.integers(1, 4), st.integers(1, 4), st.integers(0, 2 ** 31 - 1), st.floats(0.0, 1.0))
def test_assignment_equals_brute_force_over_permutations(n, m, seed, p_forbid):
    rng = np.random.default_rng(seed)
    cost = rng.uniform(-5, 20, (n, m))
    allowed = rng.random((n, m)) >= p_forbid
    pairs = assign(cost, allowed)
    # a matching: one-to-one, allowed pairs only
    assert len({r for r, _ in pairs}) == len(pairs) == len({c for _, c in pairs})
    assert all(allowed[r, c] for r, c in pairs)
    n_best, cost_best = brute_force(cost, allowed)
    assert len(pairs) == n_best
    assert sum(cost[r, c] for r, c in pairs) == pytest.approx(cost_best, abs=1e-9)


def test_assign_by_hand_and_degenerate_inputs():
    # 1 + 1 = 2 beats 0 + 10 = 10: the greedy choice of the single cheapest pair is wrong
    assert assign(np.array([[0.0, 1.0], [1.0, 10.0]])) == [(0, 1), (1, 0)]
    # a forbidden pair is never used, even when it is the cheapest
    assert assign(np.array([[0.0, 1.0], [5.0, 9.0]]), np.array([[False, True], [True, True]])) \
        == [(0, 1), (1, 0)]
    assert assign(np.zeros((2, 0))) == []
    assert assign(np.ones((2, 2)), np.zeros((2, 2), bool)) == []
    with pytest.raises(ValueError, match="2-D"):
        assign(np.ones(3))
    with pytest.raises(ValueError, match="one flag per"):
        assign(np.ones((2, 2)), np.ones((3, 2), bool))


def test_gate_excludes_what_lies_outside_the_chi2_quantile():
    # S = diag(4, 1): d² = (dx/2)² + dy²; the 99 % gate of 2 dof is -2 ln 0.01 = 9.21
    assert CHI2_GATE_99 == pytest.approx(9.2103, abs=1e-4)
    zhat, S = np.array([[0.0, 0.0]]), np.array([np.diag([4.0, 1.0])])
    cands = np.array([[6.0, 0.0], [6.2, 0.0], [0.0, 3.0], [0.0, 3.1], [4.0, 2.0]])
    d2 = mahalanobis_matrix(zhat, S, cands)
    np.testing.assert_allclose(d2[0], [9.0, 9.61, 9.0, 9.61, 8.0])
    np.testing.assert_array_equal(gate(d2)[0], [True, False, True, False, True])
    # the Mahalanobis distance against numpy's solve, for a correlated S
    S2 = np.array([[[3.0, 1.2], [1.2, 2.0]]])
    y = np.array([1.5, -2.0])
    assert mahalanobis_matrix(np.zeros((1, 2)), S2, y[None])[0, 0] == \
        pytest.approx(y @ np.linalg.inv(S2[0]) @ y)


def test_iou_matrix_by_hand():
    a = np.array([[0, 0, 10, 10], [100, 100, 5, 5]], float)
    b = np.array([[5, 0, 10, 10], [0, 0, 10, 10], [200, 0, 1, 1]], float)
    np.testing.assert_allclose(iou_matrix(a, b), [[50 / 150, 1.0, 0.0], [0.0, 0.0, 0.0]])


GT = {"a": np.array([[10.0 * k, 0, 10, 10] for k in range(8)]),
      "b": np.array([[100.0 - 10 * k, 40, 10, 10] for k in range(8)])}   # never overlaps "a"


def test_no_switch_when_each_track_follows_its_target():
    assert identity_switches([GT["a"], GT["b"]], GT) == 0
    assert identity_switches({"t2": GT["b"], "t1": GT["a"]}, GT) == 0
    np.testing.assert_array_equal(matched_identities([GT["b"], GT["a"]], GT), [[1] * 8, [0] * 8])


def test_a_swap_counts_one_switch_per_identity():
    t1 = np.vstack([GT["a"][:5], GT["b"][5:]])
    t2 = np.vstack([GT["b"][:5], GT["a"][5:]])
    assert identity_switches([t1, t2], GT) == 2


def test_a_lost_track_that_returns_to_its_target_is_no_switch():
    t1 = GT["a"].copy()
    t1[3:5] = [300.0, 300, 10, 10]             # lost for two frames, then back on "a"
    assert identity_switches([t1, GT["b"]], GT) == 0
    m = matched_identities([t1, GT["b"]], GT)
    np.testing.assert_array_equal(m[0], [0, 0, 0, -1, -1, 0, 0, 0])
    # the other track taking over "a" while t1 is away is a switch, and t1 coming back another
    t2 = GT["b"].copy()
    t2[3:5] = GT["a"][3:5]
    assert identity_switches([t1, t2], GT) == 2


def test_both_tracks_on_one_target_keep_the_earlier_correspondence():
    # from frame 4 both tracks sit on "a" (the second one slightly off): "a" stays with track 0
    t2 = GT["b"].copy()
    t2[4:] = GT["a"][4:] + [1.0, 0, 0, 0]
    assert identity_switches([GT["a"], t2], GT) == 0
    m = matched_identities([GT["a"], t2], GT)
    np.testing.assert_array_equal(m[1, 4:], [-1] * 4)


def test_identity_bad_input():
    with pytest.raises(ValueError, match="same frames"):
        identity_switches([GT["a"][:3]], GT)


@pytest.mark.skipif("two-faces" not in clips.available(), reason="sample clip two-faces not built")
def test_associated_tracker_swaps_back_boxes_that_crossed():
    # Give the two faces' trackers to the wrong tracks on purpose: association must hand each
    # track the box that continues its own motion, so the boxes end in identity order.
    clip = clips.load("two-faces")
    mt = AssociatedMultiTracker("mean-shift", seed=0)
    mt.init(clip.frames[0], [clip.targets["face1"][0], clip.targets["face2"][0]])
    mt.trackers.reverse()
    oks, boxes = mt.update(clip.frames[1])
    assert oks == [True, True] and mt.owner == [1, 0]
    for box, name in zip(boxes, ["face1", "face2"]):
        assert iou_matrix(box, clip.targets[name][1])[0, 0] > 0.5


def test_associated_tracker_coasts_when_nothing_is_in_the_gate():
    clip = clips.load("occluder")
    mt = AssociatedMultiTracker("mean-shift", seed=0, gate_threshold=1e-9)
    mt.init(clip.frames[0], [clip.groundtruth[0]])
    mt.kfs[0].x[:2] += 50.0                     # the track predicts far from the tracker's box
    oks, boxes = mt.update(clip.frames[1])
    assert oks == [False] and np.all(np.isfinite(boxes[0]))
    mt.kfs[0].x[:2] = [-1e4, 1e4]               # a prediction far off the frame
    oks, boxes = mt.update(clip.frames[2])
    x, y, w, h = boxes[0]
    H, W = clip.frames[2].shape[:2]
    assert oks == [False] and (x + w / 2, y + h / 2) == (0.0, float(H))
    with pytest.raises(ValueError, match="gate_threshold"):
        AssociatedMultiTracker("mean-shift", gate_threshold=-1)
    with pytest.raises(ValueError, match="init"):
        AssociatedMultiTracker("mean-shift").update(clip.frames[0])


@pytest.mark.skipif("two-faces" not in clips.available(), reason="sample clip two-faces not built")
def test_without_association_it_is_the_independent_multi_tracker():
    from trackbook.trackers import MultiTracker

    clip = clips.load("two-faces")
    starts = [clip.targets[k][0] for k in clip.targets]
    a = AssociatedMultiTracker("condensation-mean-shift", seed=3, associate=False)
    b = MultiTracker("condensation-mean-shift", seed=3)
    a.init(clip.frames[0], starts)
    b.init(clip.frames[0], starts)
    for frame in list(clip.frames)[1:6]:
        assert a.update(frame) == b.update(frame)


class _Stub:
    """A tracker that proposes a given box every frame."""

    def __init__(self, box, ok=True):
        self.box, self.ok = box, ok

    def update(self, frame):
        return self.ok, self.box


def _started(boxes):
    clip = clips.load("occluder")
    mt = AssociatedMultiTracker("mean-shift", seed=0)
    mt.init(clip.frames[0], boxes)
    return mt, clip.frames[1]


def test_overlapping_candidates_are_assigned_but_do_not_update_the_tracks():
    mt, frame = _started([(40.0, 40, 30, 30), (120.0, 40, 30, 30)])
    mt.trackers = [_Stub((41.0, 40, 30, 30)), _Stub((45.0, 42, 30, 30))]   # IoU about 0.7
    predicted = [kf.F @ kf.x for kf in mt.kfs]
    oks, boxes = mt.update(frame)
    assert mt.ambiguous.tolist() == [True, True]
    for kf, x in zip(mt.kfs, predicted):
        np.testing.assert_allclose(kf.x, x)      # predicted only: no Kalman update
    assert boxes[0] == (41.0, 40, 30, 30) and oks[0]


def test_separate_candidates_update_the_tracks_and_swapped_boxes_are_given_back():
    mt, frame = _started([(40.0, 40, 30, 30), (120.0, 40, 30, 30)])
    mt.trackers = [_Stub((121.0, 40, 30, 30)), _Stub((41.0, 40, 30, 30))]  # each on the other
    oks, boxes = mt.update(frame)
    assert mt.ambiguous.tolist() == [False, False]
    assert boxes == [(41.0, 40, 30, 30), (121.0, 40, 30, 30)] and mt.owner == [1, 0]
    assert mt.kfs[0].x[0] > 40 + 15            # updated towards the new centre (56)
    # a candidate its tracker flags as lost is never assigned: the track coasts, ok = False
    mt.trackers = [_Stub((121.0, 40, 30, 30)), _Stub((41.0, 40, 30, 30), ok=False)]
    oks, boxes = mt.update(frame)
    assert oks == [False, True]
    with pytest.raises(ValueError, match="ambiguity_iou"):
        AssociatedMultiTracker("mean-shift", ambiguity_iou=1.5)


def test_two_faces_alike_is_two_faces_with_a_twin():
    from trackbook.clips.scenes import two_faces_alike

    alike, faces = two_faces_alike(), clips.load("two-faces")
    assert len(alike) == len(faces) and list(alike.targets) == list(faces.targets)
    for k in faces.targets:
        np.testing.assert_allclose(alike.targets[k], faces.targets[k])
    # frame 0: identical outside face2's box, different inside it
    a, b = np.asarray(alike.frames[0], float), np.asarray(faces.frames[0], float)
    x, y, w, h = np.round(faces.targets["face2"][0]).astype(int)
    inside = np.zeros(a.shape[:2], bool)
    inside[max(y - 2, 0):y + h + 2, max(x - 2, 0):x + w + 2] = True
    assert np.abs(a - b)[~inside].max() == 0 and np.abs(a - b)[inside].mean() > 10


def test_invisible_ground_truth_frames_match_nothing_and_switch_nothing():
    gt = {k: v.copy() for k, v in GT.items()}
    gt["a"][3:5] = np.nan                       # "a" out of view for two frames
    m = matched_identities([GT["a"], GT["b"]], gt)
    np.testing.assert_array_equal(m[0], [0, 0, 0, -1, -1, 0, 0, 0])
    assert identity_switches([GT["a"], GT["b"]], gt) == 0


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2 ** 31 - 1))
def test_switch_count_does_not_depend_on_the_order_of_the_tracks(seed):
    # three tracks that trade the two targets at random frames, never two on one target (ties
    # between equal overlaps are broken by order, as in any matching)
    rng = np.random.default_rng(seed)
    choice = np.array([rng.permutation(3) for _ in range(8)]).T   # 0: on "a", 1: on "b", 2: away
    far = np.array([[500.0, 500, 10, 10]] * 8)
    tracks = [np.where((c == 0)[:, None], GT["a"], np.where((c == 1)[:, None], GT["b"], far))
              for c in choice]
    n = identity_switches(tracks, GT)
    assert n == identity_switches(tracks[::-1], GT) == identity_switches(tracks[1:] + tracks[:1], GT)
