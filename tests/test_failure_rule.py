"""The failure rule (``trackers.failure``) and its scoring and calibration
(``evaluation.failure``), on hand-made confidence series whose answers are known by
construction."""

import math

import numpy as np
import pytest
from sklearn.metrics import roc_auc_score
from sklearn.metrics import roc_curve as sk_roc_curve

from trackbook.evaluation.failure import (FOUND_K, FOUND_RATIO, calibrate, counted_on_target,
                                          detection_rates, floor_found, judged_rates, objective,
                                          roc_auc, roc_curve)
from trackbook.trackers.failure import (MAD_TO_SIGMA, FailureDetector, FailureParams, judge,
                                        robust_reference, threshold)


# --------------------------------------------------------------------------- the rule
def test_robust_reference_by_hand():
    # median 10; |dev| = 1, 1, 1, 1, 0 -> MAD 1
    assert robust_reference([9, 11, 9, 11, 10]) == (10.0, pytest.approx(MAD_TO_SIGMA))
    # more than half equal the median: MAD 0, mean |dev| = 2/5 scaled by sqrt(pi/2)
    r, s = robust_reference([10, 10, 10, 11, 9])
    assert r == 10.0 and s == pytest.approx(np.sqrt(np.pi / 2) * 0.4)
    assert robust_reference([3, 3, 3]) == (3.0, 0.0)


def test_a_steady_series_then_a_drop_is_lost_on_the_frame_of_the_drop():
    p = FailureParams(k_lost=3, k_found=1, m=2, window=10, warmup=4)
    c = [5.0, 6.0] * 10 + [1.0] + [5.5] * 4
    ok = judge(c, p)
    # r = 5.5, s = 0.5 * 1.4826 = 0.741; 1.0 < 5.5 - 3 * 0.741 = 3.28: lost at frame 20
    assert ok[:20].all() and not ok[20]
    # found threshold 5.5 - 0.741 = 4.76: frames 21, 22 are >= it; m = 2 -> ok from frame 22
    assert list(ok[21:]) == [False, True, True, True]


def test_a_constant_series_loses_on_any_drop():
    ok = judge([2.0] * 8 + [1.999], FailureParams(window=8, warmup=3))
    assert ok[:8].all() and not ok[8]


def test_noise_within_the_band_is_never_lost():
    g = np.random.default_rng(0)
    c = 20 + g.uniform(-1, 1, 500)           # |c - 20| <= 1 always
    p = FailureParams(k_lost=4, k_found=2, m=3, window=30, warmup=10)
    # the reference of uniform(-1, 1) noise: median near 20, s near 1.48 * 0.5 = 0.74, so
    # the lost threshold r - 4 s lies well below the band's floor, 19
    d = FailureDetector(p)
    for i, x in enumerate(c):
        assert d.step(x)
        r, s = d.reference
        assert i < p.warmup or r - 4 * s < 19.0


def test_recovery_needs_m_frames_in_a_row():
    p = FailureParams(k_lost=3, k_found=1, m=3, window=10, warmup=4)
    base = [9.0, 11.0] * 5                    # r = 10, s = 1.4826
    hi, lo = 10.0, 0.0                        # 10 >= found threshold 8.52; 0 below both
    c = base + [lo, hi, hi, lo, hi, hi, hi, hi]
    ok = judge(c, p)
    assert ok[:10].all()
    # lost at the drop; two good frames then a bad one restart the count; the third of the
    # next run of good frames is the first ok
    assert list(ok[10:]) == [False, False, False, False, False, False, True, True]


def test_the_reference_is_frozen_while_lost():
    p = FailureParams(k_lost=3, k_found=1, m=2, window=10, warmup=4)
    d = FailureDetector(p)
    for x in [9.0, 11.0] * 5:
        d.step(x)
    before = d.reference
    for x in [0.0] * 40:                      # a long loss at a low level
        assert not d.step(x)
        assert d.reference == before          # it did not learn the low level
    # found threshold 10 - 1.48 = 8.52, two frames in a row
    assert [d.step(x) for x in (8.0, 8.9, 8.9)] == [False, False, True]


def test_hysteresis_a_value_between_the_thresholds_keeps_the_state():
    p = FailureParams(k_lost=4, k_found=1, m=1, window=10, warmup=4)
    base = [9.0, 11.0] * 5                     # lost below 4.07, found at 8.52 and above
    mid = 6.0
    ok = judge(base + [mid, 2.0, mid, mid, 9.0], p)
    assert list(ok[10:]) == [True, False, False, False, True]


@pytest.mark.parametrize("a, b", [(2.0, 3.0), (0.5, -7.0), (4.0, -100.0), (1.0, 0.25)])
def test_the_ok_sequence_is_invariant_under_positive_affine_maps(a, b):
    # integer series and power-of-two scales: median and MAD scale exactly and no value lies
    # within rounding of a threshold, so the claim is tested exactly, not up to a tolerance
    g = np.random.default_rng(3)
    c = np.concatenate([g.integers(40, 48, 60), g.integers(0, 10, 8), g.integers(40, 48, 30),
                        g.integers(20, 30, 5), g.integers(40, 48, 20)]).astype(float)
    p = FailureParams(k_lost=3, k_found=1.5, m=2, window=16, warmup=5)
    ok = judge(c, p)
    assert (~ok).any() and ok[70:].any()      # the series exercises loss and recovery
    np.testing.assert_array_equal(judge(a * c + b, p), ok)
    # a PSR-like positive scale and a negated-distance-like negative one: the same answer
    np.testing.assert_array_equal(judge(c - c.max() - 1, p), ok)


def test_a_negative_scale_is_not_invariant():
    # the rule is meant for c -> a c + b with a > 0 only: flipping the sign flips the meaning
    c = np.array([10.0, 11.0] * 10 + [0.0])
    p = FailureParams(window=10, warmup=4)
    assert not judge(c, p)[-1] and judge(-c, p)[-1]


def test_nan_and_infinite_confidences():
    p = FailureParams(k_lost=3, k_found=1, m=1, window=10, warmup=4)
    base = [9.0, 11.0] * 5
    ok = judge(base + [np.nan, 10.0, np.inf, -np.inf], p)
    assert list(ok[10:]) == [False, True, True, False]
    d = FailureDetector(p)
    for x in [np.inf] * 6 + base:
        d.step(x)
    assert d.reference == (10.0, pytest.approx(MAD_TO_SIGMA))   # +inf is never learned


def test_warmup_keeps_the_first_frames_ok():
    ok = judge([10.0, 0.0, 10.0, 10.0, 0.0], FailureParams(window=10, warmup=4))
    # the reference holds 10, 0, 10, 10 (median 10, MAD 0, mean |dev| 2.5): s = 3.13, the
    # lost threshold 10 - 4 * 3.13 < 0, so the last 0 is not below it either
    assert ok.all()
    ok = judge([10.0, 10.0, 10.0, 10.0, 0.0], FailureParams(window=10, warmup=4))
    assert list(ok) == [True, True, True, True, False]


@pytest.mark.parametrize("kw, word", [({"k_lost": 1.0, "k_found": 2.0}, "k_found <= k_lost"),
                                      ({"k_lost": -1.0, "k_found": -2.0}, ">= 0"),
                                      ({"k_lost": float("nan")}, "number >= 0"),
                                      ({"ratio_lost": 1.5, "ratio_found": 1.5}, "in \\[0, 1\\]"),
                                      ({"ratio_lost": 0.6, "ratio_found": 0.5},
                                       "ratio_found >= ratio_lost"),
                                      ({"k_lost": float("inf"), "k_found": float("inf")},
                                       "turn both tests"),
                                      ({"m": 0}, "m = 0"), ({"window": 1}, "window"),
                                      ({"warmup": 40, "window": 30}, "warmup <= window")])
def test_bad_params_are_refused_naming_the_fix(kw, word):
    with pytest.raises(ValueError, match=word):
        FailureParams(**kw)
    with pytest.raises(TypeError, match="FailureParams"):
        FailureDetector({"k_lost": 3})


# ---------------------------------------------------------------------- the ratio test
def test_threshold_by_hand():
    # the larger of r - k s and the ratio's fraction of r
    assert threshold(10.0, 1.0, 3.0, 0.5) == 7.0              # spread test is the higher
    assert threshold(10.0, 1.0, 8.0, 0.5) == 5.0              # ratio test is the higher
    assert threshold(10.0, 1.0, float("inf"), 0.5) == 5.0     # spread test off
    assert threshold(10.0, 1.0, 3.0, 0.0) == 7.0              # ratio test off
    assert threshold(10.0, 1.0, float("inf"), 0.0) == float("-inf")
    # a negated distance: r = -2 is a distance of 2; lost when it passes 2 / 0.5 = 4
    assert threshold(-2.0, 0.1, float("inf"), 0.5) == -4.0
    assert threshold(0.0, 0.0, float("inf"), 0.5) == 0.0


def test_the_ratio_test_alone_by_hand():
    p = FailureParams(k_lost=float("inf"), k_found=float("inf"), ratio_lost=0.5,
                      ratio_found=0.8, m=1, window=10, warmup=4)
    base = [0.8, 1.0] * 5                     # r = 0.9: lost below 0.45, found at 0.72
    ok = judge(base + [0.46, 0.44, 0.7, 0.73], p)
    assert list(ok[10:]) == [True, False, False, True]
    # a negated distance, d = 2 on target: lost when d > 4, found when d <= 2 / 0.8 = 2.5
    ok = judge([-2.0] * 10 + [-3.9, -4.1, -2.6, -2.5], p)
    assert list(ok[10:]) == [True, False, False, True]


@pytest.mark.parametrize("a", [0.25, 2.0, 8.0])
def test_with_the_ratio_test_the_rule_is_invariant_under_scaling_not_shifting(a):
    g = np.random.default_rng(5)
    c = np.concatenate([g.integers(40, 48, 60), g.integers(0, 10, 8),
                        g.integers(40, 48, 30)]).astype(float)
    p = FailureParams(k_lost=8, k_found=4, ratio_lost=0.5, ratio_found=0.75, m=2, window=16,
                      warmup=5)
    ok = judge(c, p)
    assert (~ok).any() and ok[-20:].all()
    np.testing.assert_array_equal(judge(a * c, p), ok)
    # shifted up by 100 the drop from ~44 to ~5 is no longer to half of the reference
    # (~105 of ~144), and the spread test alone (8 spreads) is what still sees it
    shifted = judge(c + 100, FailureParams(k_lost=float("inf"), k_found=float("inf"),
                                           ratio_lost=0.5, ratio_found=0.75, window=16,
                                           warmup=5))
    assert shifted.all() and (~judge(c, FailureParams(k_lost=float("inf"),
                                                      k_found=float("inf"), ratio_lost=0.5,
                                                      ratio_found=0.75, window=16,
                                                      warmup=5))).any()


def test_calibrate_picks_the_ratio_test_where_no_spread_serves_every_scene():
    # steady scenes (s = 0.074) dip to 9 on target: 13.5 spreads, so k_lost >= 14; noisy
    # scenes (s = 7.4) lose the target at 4: 0.81 spreads, which no k >= 14 flags. A ratio
    # flags 4 and keeps 9 for 0.4 < ratio <= 0.9; the smallest such on the grid is 0.5
    steady, noisy = [10.0, 10.1] * 5, [5.0, 15.0] * 5
    runs = []
    for _ in range(5):
        runs.append(steady + [9.0] * 5 + [4.0] * 5)
        runs.append(noisy + [4.0] * 5)
    absent = [np.r_[np.zeros(len(r) - 5, bool), np.ones(5, bool)] for r in runs]
    on = [~a for a in absent]
    for j in range(0, 10, 2):                 # the dip to 9 is on target too
        on[j] = ~absent[j]
    grid = tuple(float(k) for k in range(1, 21)) + (float("inf"),)
    cal = calibrate(runs, absent, on, k_lost_grid=grid, hysteresis=(1.0,), m=1, window=10,
                    warmup=4)
    assert cal.params.k_lost == float("inf") and cal.params.ratio_lost == 0.5
    assert cal.absent_lost == 1.0 and cal.false_lost == 0.0 and cal.meets_target
    # the spread test alone cannot: keeping the dips needs k_lost >= 15, and then neither
    # the noisy scenes' 4 (0.81 spreads) nor the steady scenes' 4 is flagged (by then the
    # reference has learned the dip: median 9.5, s = 0.74, and 4 is 7.4 spreads down)
    alone = calibrate(runs, absent, on, k_lost_grid=grid[:-1], ratio_grid=(0.0,),
                      hysteresis=(1.0,), m=1, window=10, warmup=4)
    assert alone.params.k_lost >= 15 and alone.false_lost == 0.0
    assert alone.absent_lost == 0.0


# ----------------------------------------------------------------------------- the ROC
def test_roc_matches_sklearn_on_random_data_with_ties():
    g = np.random.default_rng(7)
    for _ in range(20):
        pos = g.integers(0, 12, g.integers(1, 60)).astype(float)     # many ties
        neg = g.integers(-3, 8, g.integers(1, 60)).astype(float)
        y = np.r_[np.ones(pos.size), np.zeros(neg.size)]
        c = np.r_[pos, neg]
        fpr, tpr, thr = roc_curve(pos, neg)
        sf, st, sth = sk_roc_curve(y, c, drop_intermediate=False)
        np.testing.assert_allclose(fpr, sf)
        np.testing.assert_allclose(tpr, st)
        np.testing.assert_array_equal(thr[1:], sth[1:])
        assert roc_auc(pos, neg) == pytest.approx(roc_auc_score(y, c), abs=1e-12)


def test_roc_by_hand():
    # on target 3, 2, 2; absent 2, 1: thresholds inf, 3, 2, 1
    fpr, tpr, thr = roc_curve([3, 2, 2], [2, 1])
    np.testing.assert_array_equal(thr, [np.inf, 3, 2, 1])
    np.testing.assert_allclose(tpr, [0, 1 / 3, 1, 1])
    np.testing.assert_allclose(fpr, [0, 0, 1 / 2, 1])
    # pairs (on, absent): 3>2, 3>1, 2=2 (1/2), 2>1, 2=2 (1/2), 2>1 -> 5 / 6
    assert roc_auc([3, 2, 2], [2, 1]) == pytest.approx(5 / 6)
    assert roc_auc([1, 2], [3, 4]) == 0.0 and roc_auc([5], [5]) == 0.5
    assert roc_auc([1.0], [np.nan]) == 1.0       # no score is below every score


def test_roc_refuses_an_empty_class():
    with pytest.raises(ValueError, match="confidence_absent is empty"):
        roc_curve([1.0], [])


# -------------------------------------------------------------------- rates, calibration
S = MAD_TO_SIGMA
PREFIX = [9.0, 11.0] * 5          # a reference with r = 10, s = 1.4826 (window = 10)


def _run(tail_values, tail_absent):
    """A run: the prefix (on target), then ``tail_values`` with their absent flags; tail
    frames not absent are on target."""
    c = np.array(PREFIX + list(tail_values))
    absent = np.array([False] * len(PREFIX) + list(tail_absent))
    return c, absent, ~absent


def _level(q):
    """The confidence ``q`` spreads below the reference: lost exactly when k_lost < q."""
    return 10.0 - q * S


def test_counted_on_target_leaves_grace_frames_after_an_absence_or_a_miss():
    absent = np.array([0, 0, 1, 1, 0, 0, 0, 0], bool)
    on = np.ones(8, bool)
    np.testing.assert_array_equal(counted_on_target(absent, on, 2),
                                  [1, 1, 0, 0, 0, 0, 1, 1])
    np.testing.assert_array_equal(counted_on_target(absent, on, 0), ~absent)
    # the tracker off the target (not absent) for a frame: found again, the same grace
    on = np.array([1, 1, 0, 1, 1, 1, 1], bool)
    np.testing.assert_array_equal(counted_on_target(np.zeros(7, bool), on, 2),
                                  [1, 1, 0, 0, 0, 1, 1])


def test_detection_rates_by_hand():
    p = FailureParams(k_lost=3, k_found=1, m=1, window=10, warmup=4)
    runs = [_run([_level(4)], [True]), _run([_level(2)], [True]), _run([_level(3.5)], [False])]
    r = detection_rates(*zip(*runs), p)
    # absent: q = 4 lost, q = 2 not; on target: 30 prefix frames + one at q = 3.5 (lost)
    assert (r["n_absent"], r["n_absent_lost"], r["n_on"], r["n_false_lost"]) == (2, 1, 31, 1)
    assert r["absent_lost"] == 0.5 and r["false_lost"] == pytest.approx(1 / 31)


def test_judged_rates_by_hand():
    # two runs: ok as a tracker reported it, not replayed from a confidence
    ok = [np.array([1, 1, 0, 0, 0, 1], bool), np.array([1, 0, 1, 1], bool)]
    absent = [np.array([0, 0, 1, 1, 0, 0], bool), np.zeros(4, bool)]
    on = [np.array([1, 1, 0, 0, 1, 1], bool), np.array([1, 1, 1, 1], bool)]
    r = judged_rates(ok, absent, on, grace=1)
    # run 1: absent frames 2, 3 both lost; on target (grace 1 after the absence): 0, 1, 5;
    # frame 4 is the grace frame. Run 2: on target 0..3, frame 1 lost
    assert (r["n_absent"], r["n_absent_lost"], r["n_on"], r["n_false_lost"]) == (2, 2, 7, 1)
    assert r["absent_lost"] == 1.0 and r["false_lost"] == pytest.approx(1 / 7)


def test_floor_found_raises_only_the_found_thresholds_of_the_tests_that_are_on():
    assert (FOUND_RATIO, FOUND_K) == (0.8, 4.0)
    ratio_only = FailureParams(k_lost=math.inf, k_found=math.inf, ratio_lost=0.4,
                               ratio_found=0.5)
    assert floor_found(ratio_only) == FailureParams(k_lost=math.inf, k_found=math.inf,
                                                    ratio_lost=0.4, ratio_found=0.8)
    spread_only = FailureParams(k_lost=20, k_found=10, m=2, window=12, warmup=3)
    assert floor_found(spread_only) == FailureParams(k_lost=20, k_found=4, m=2, window=12,
                                                     warmup=3)
    # already stricter than the floor: unchanged
    strict = FailureParams(k_lost=30, k_found=2, ratio_lost=0.85, ratio_found=0.9)
    assert floor_found(strict) == strict
    # a spread test looser than the floor's k: k_found = k_lost, never above it
    assert floor_found(FailureParams(k_lost=3, k_found=3)).k_found == 3


def test_objective_orders_by_false_losses_then_detection():
    feasible_weak, feasible_strong = objective(0.5, 0.01), objective(0.9, 0.005)
    infeasible = objective(1.0, 0.02)
    assert feasible_strong > feasible_weak > infeasible
    # beyond the target detection buys nothing; then the fewer false losses win
    assert objective(0.96, 0.001) > objective(1.0, 0.002)
    # without a feasible point, the fewest false losses win
    assert objective(0.1, 0.015) > objective(1.0, 0.02)


GRID = tuple(float(k) for k in range(1, 11))


def test_calibrate_picks_the_largest_k_meeting_the_target_and_a_k_found_that_recovers():
    # absent at 6.5 spreads: flagged for k_lost <= 6; the target comes back 3.5 spreads
    # down: recovered only with k_found >= 3.5. m = 2 frames of grace after each absence
    back = [_level(3.5)] * 6
    runs = [_run([_level(6.5)] * 3 + back, [True] * 3 + [False] * 6) for _ in range(10)]
    cal = calibrate(*zip(*runs), k_lost_grid=GRID, ratio_grid=(0.0,),
                    hysteresis=(0.25, 0.5, 0.75, 1.0), m=2, window=10, warmup=4)
    # k_lost = 6: k_found in 1.5, 3, 4.5, 6 -> 4.5 and 6 recover, 4.5 leaves the wider band
    assert (cal.params.k_lost, cal.params.k_found) == (6.0, 4.5)
    assert cal.absent_lost == 1.0 and cal.false_lost == 0.0
    assert cal.feasible and cal.meets_target
    assert cal.n_absent == 30 and cal.n_on == 10 * (10 + 6 - 2)


def test_calibrate_when_false_losses_forbid_the_target():
    # on-target dips 3.5 spreads down (10 runs: 10 of 310 on-target frames > 1 %): k_lost
    # must be >= 4. Absent frames at 2.5, 4.5, 5.5, 6.5 spreads: k_lost = 4 flags 3 of 4.
    runs = [_run([_level(3.5)], [False]) for _ in range(10)]
    runs += [_run([_level(q)], [True]) for q in (2.5, 4.5, 5.5, 6.5) for _ in range(5)]
    cal = calibrate(*zip(*runs), k_lost_grid=GRID, ratio_grid=(0.0,), hysteresis=(0.5,), m=1,
                    window=10, warmup=4)
    assert cal.params.k_lost == 4.0
    assert cal.absent_lost == 0.75 and cal.false_lost == 0.0
    assert cal.feasible and not cal.meets_target


def test_calibrate_without_a_feasible_point_says_so():
    runs = [_run([_level(30)], [False]) for _ in range(10)]        # dips below every k
    runs += [_run([_level(40)], [True]) for _ in range(5)]
    cal = calibrate(*zip(*runs), k_lost_grid=GRID, ratio_grid=(0.0,), m=1, window=10,
                    warmup=4)
    assert not cal.feasible and not cal.meets_target
    assert cal.false_lost == pytest.approx(10 / 160)


def test_calibrate_refuses_mismatched_runs():
    c, a, o = _run([1.0], [True])
    with pytest.raises(ValueError, match="one of each per frame"):
        calibrate([c], [a[:-1]], [o])
    with pytest.raises(ValueError, match="one of each per run"):
        calibrate([c, c], [a], [o])
