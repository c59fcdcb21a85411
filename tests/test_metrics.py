"""OTB scores on hand-worked cases and their definitions (the OTB conventions)."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbook import metrics

NAN = float("nan")


def test_iou_hand_cases():
    gt = np.array([[0, 0, 10, 10]] * 5, dtype=float)
    pred = np.array([
        [0, 0, 10, 10],     # identical -> 1
        [5, 0, 10, 10],     # half overlap: 50 / (100 + 100 - 50) = 1/3
        [20, 20, 5, 5],     # disjoint -> 0
        [0, 0, 5, 5],       # inside: 25 / 100
        [10, 0, 10, 10],    # touching edge (continuous coordinates) -> 0
    ], dtype=float)
    np.testing.assert_allclose(metrics.iou(pred, gt), [1, 1 / 3, 0, 0.25, 0])


def test_invalid_prediction_scores_zero_and_infinite_error():
    gt = np.array([[0, 0, 10, 10]] * 3, dtype=float)
    pred = np.array([[NAN, 0, 10, 10], [0, 0, 0, 10], [0, 0, 10, -1]])
    assert np.all(metrics.iou(pred, gt) == 0)
    assert np.all(np.isinf(metrics.center_error(pred, gt)))


def test_unknown_groundtruth_rows_are_skipped():
    gt = np.array([[0, 0, 10, 10], [NAN, NAN, NAN, NAN], [0, 0, 10, 10]])
    pred = np.array([[0, 0, 10, 10], [50, 50, 10, 10], [0, 0, 10, 10]], dtype=float)
    assert np.isnan(metrics.iou(pred, gt)[1])
    assert metrics.auc(pred, gt) == pytest.approx(np.mean(np.linspace(0, 1, 21) < 1.0))
    assert metrics.tracking_rate(pred, gt) == 1.0


def test_center_error_hand_case():
    gt = np.array([[0, 0, 10, 10]], dtype=float)      # centre (5, 5)
    pred = np.array([[3, 4, 10, 10]], dtype=float)    # centre (8, 9): distance 5
    assert metrics.center_error(pred, gt)[0] == pytest.approx(5.0)


def test_success_curve_uses_strict_greater_and_21_thresholds():
    gt = np.array([[0, 0, 10, 10]] * 2, dtype=float)
    pred = np.array([[0, 0, 10, 10], [5, 0, 10, 10]], dtype=float)  # IoU 1 and 1/3
    t, s = metrics.success_curve(pred, gt)
    assert len(t) == 21 and t[0] == 0 and t[-1] == 1
    # IoU 1 is > t for every t < 1 but not for t = 1 (strict)
    assert s[-1] == 0.0
    assert s[0] == 1.0
    # at t = 0.35 only the perfect frame counts
    assert s[7] == 0.5
    # AUC is the mean of the 21 rates: frame 1 contributes 20/21, frame 2 (1/3 > t for t in
    # 0..0.30, i.e. 7 thresholds) contributes 7/21
    assert metrics.auc(pred, gt) == pytest.approx((20 / 21 + 7 / 21) / 2)


def test_precision_curve_uses_less_equal_and_20px_score():
    gt = np.array([[0, 0, 10, 10]] * 4, dtype=float)
    pred = gt + np.array([[0, 0, 0, 0], [20, 0, 0, 0], [21, 0, 0, 0], [0, 50, 0, 0]])
    t, p = metrics.precision_curve(pred, gt)
    assert len(t) == 51 and t[-1] == 50
    assert p[0] == 0.25            # only the exact frame has error <= 0
    assert p[20] == 0.5            # error 20 counts (<=), 21 does not
    assert metrics.precision(pred, gt) == 0.5
    assert p[50] == 1.0


def test_tracking_rate_threshold():
    gt = np.array([[0, 0, 10, 10]] * 2, dtype=float)
    pred = np.array([[0, 0, 10, 10], [5, 0, 10, 10]], dtype=float)   # IoU 1, 1/3
    assert metrics.tracking_rate(pred, gt) == 0.5
    assert metrics.tracking_rate(pred, gt, iou_threshold=0.3) == 1.0


def test_shape_errors_are_clear():
    with pytest.raises(ValueError, match="N x 4"):
        metrics.iou(np.zeros((3, 3)), np.zeros((3, 4)))
    with pytest.raises(ValueError, match="one box per frame"):
        metrics.iou(np.zeros((3, 4)), np.zeros((2, 4)))
    with pytest.raises(ValueError, match="no frame has a known ground truth"):
        metrics.auc(np.zeros((2, 4)), np.full((2, 4), NAN))


boxes = st.tuples(st.floats(-50, 300), st.floats(-50, 300), st.floats(0.5, 200), st.floats(0.5, 200))


@settings(max_examples=200, deadline=None)
@given(a=boxes, b=boxes)
def test_iou_in_unit_interval_and_symmetric(a, b):
    a, b = np.array([a]), np.array([b])
    v = metrics.iou(a, b)[0]
    assert 0.0 <= v <= 1.0
    assert v == pytest.approx(metrics.iou(b, a)[0])


@settings(max_examples=100, deadline=None)
@given(a=boxes, dx=st.floats(-100, 100), dy=st.floats(-100, 100))
def test_center_error_is_the_shift(a, dx, dy):
    a = np.array([a])
    b = a + np.array([[dx, dy, 0, 0]])
    assert metrics.center_error(b, a)[0] == pytest.approx(np.hypot(dx, dy), abs=1e-9)


def test_false_losses_counts_frames_reported_lost_with_the_box_on_the_target():
    # frame 0 is the given box and never counts; IoUs below by hand: a 10 x 10 box against
    # the same box (1), shifted 2 px (80/120 = 0.67), shifted 5 px (50/150 = 0.33), no box
    gt = np.array([[0, 0, 10, 10]] * 6, dtype=float)
    pred = np.array([[0, 0, 10, 10], [0, 0, 10, 10], [2, 0, 10, 10], [5, 0, 10, 10],
                     [0, 0, 10, 10], [np.nan] * 4])
    ok = np.array([False, False, True, False, False, False])
    # on target (IoU > 0.5): frames 1, 2, 4; reported lost there: 1, 4
    assert metrics.false_losses(ok, pred, gt) == (2, 3)
    # frame 4 with the target mostly hidden: neither on target nor a false loss
    in_view = np.array([True, True, True, True, False, True])
    assert metrics.false_losses(ok, pred, gt, in_view) == (1, 2)
    # a run shorter than the clip (max_frames) reads the mask's first frames; a mask shorter
    # than the run is refused, not broadcast
    assert metrics.false_losses(ok[:3], pred[:3], gt, in_view) == (1, 2)
    with pytest.raises(ValueError, match="one flag per frame"):
        metrics.false_losses(ok, pred, gt, in_view[:2])
