"""The table of the OTB benchmark's published per-sequence results and its scoring code."""
from __future__ import annotations

import json
import os
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbook.clips import read_groundtruth
from trackbook.evaluation import published

from .conftest import SEQUENCES, needs_sequences

ROOT = Path(__file__).resolve().parents[1]


# --- an independent oracle: the OTB toolkit's calcRectInt, one frame at a time ----------------

def slow_overlap(a, b):
    """calcRectInt.m for one pair: pixel boxes whose right edge is x + w - 1."""
    right_a, top_a = a[0] + a[2] - 1, a[1] + a[3] - 1
    right_b, top_b = b[0] + b[2] - 1, b[1] + b[3] - 1
    iw = max(0.0, min(right_a, right_b) - max(a[0], b[0]) + 1)
    ih = max(0.0, min(top_a, top_b) - max(a[1], b[1]) + 1)
    inter = iw * ih
    return inter / (a[2] * a[3] + b[2] * b[3] - inter)


def slow_score(boxes, gt):
    ov = [slow_overlap(a, b) for a, b in zip(boxes, gt)]
    rate = sum(1 for o in ov if o > 0.5) / len(ov)
    rates = []
    for k in range(21):
        t = k / 20
        rates.append(sum(1 for o in ov if o > t) / len(ov))
    return rate, sum(rates) / 21


# --- the committed table ---------------------------------------------------------------------

def test_every_tracker_and_sequence_once():
    rows = published.load()
    keys = [(r["tracker"], r["sequence"]) for r in rows]
    assert len(keys) == len(set(keys))
    assert set(keys) == {(t, s) for t in published.TRACKERS for s in published.SEQUENCES}


def test_rates_are_fractions_of_whole_frames():
    for r in published.load():
        assert 0.0 <= r["success_rate_iou50"] <= 1.0, r
        assert r["frames"] > 1
        k = r["success_rate_iou50"] * r["frames"]
        assert abs(k - round(k)) < 1e-6, r          # a count of frames
        assert published.SEQUENCES[r["sequence"]] == r["otb_sequence"]
        if r["alt_success_rate_iou50"] is not None:
            assert 0.0 <= r["alt_success_rate_iou50"] <= 1.0
            assert r["alt_source"]


def test_auc_where_the_boxes_are_and_only_there():
    for r in published.load():
        if r["method"] == "boxes":
            assert r["auc"] is not None and 0.0 <= r["auc"] <= 1.0, r
        else:
            assert r["method"] == "toolkit score" and r["auc"] is None, r


def test_every_row_names_repository_commit_and_path():
    pattern = re.compile(r"^github\.com/[\w.-]+/[\w.-]+@[0-9a-f]{40}:\S+\.(mat|json)$")
    for r in published.load():
        assert pattern.match(r["source"]), r["source"]
        assert r["tracker"] in published.TRACKERS


@needs_sequences
def test_frames_are_the_development_sets_lengths():
    for r in published.load():
        folder = SEQUENCES[r["sequence"]]
        gt = folder / "groundtruth.txt"
        if not gt.is_file():
            gt = folder / "groundtruth_rect.txt"
        assert r["frames"] == read_groundtruth(gt).shape[0], r


# --- the scoring code ------------------------------------------------------------------------

def test_score_equals_the_slow_loop_on_a_hand_made_case():
    gt = np.array([[10, 10, 20, 20]] * 6, dtype=float)
    boxes = np.array([
        [10, 10, 20, 20],      # the same box: IoU 1
        [20, 10, 20, 20],      # half shifted: 200 / 600 = 1/3
        [10, 10, 20, 10],      # the top half: 200 / 400 = exactly 0.5, not a success (> 0.5)
        [12, 12, 20, 20],      # 324 / 476
        [100, 100, 5, 5],      # disjoint: 0
        [14, 14, 10, 10],      # inside: 100 / 400
    ], dtype=float)
    rate, area = published.score(boxes, gt)
    want_rate, want_area = slow_score(boxes, gt)
    assert rate == pytest.approx(want_rate) == 2 / 6
    assert area == pytest.approx(want_area)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(*[st.integers(0, 60)] * 2, *[st.integers(1, 40)] * 2,
                          *[st.integers(0, 60)] * 2, *[st.integers(1, 40)] * 2),
                min_size=1, max_size=12))
def test_score_equals_the_slow_loop_on_any_boxes(pairs):
    a = np.array([p[:4] for p in pairs], dtype=float)
    b = np.array([p[4:] for p in pairs], dtype=float)
    rate, area = published.score(a, b)
    want_rate, want_area = slow_score(a, b)
    assert rate == pytest.approx(want_rate)
    assert area == pytest.approx(want_area)


def test_toolkit_boxes_follow_calcseqerrrobust():
    gt = np.array([[5, 5, 10, 10], [6, 6, 10, 10], [7, 7, 10, 10], [8, 8, 10, 10]], float)
    res = np.array([[0, 0, 1, 1], [6, 6, 10, 10], [np.nan, 0, 0, 0], [3, 3, 0, 4]], float)
    b = published.toolkit_boxes(res, gt)
    np.testing.assert_array_equal(b[0], gt[0])           # frame 1 is the ground truth
    np.testing.assert_array_equal(b[2], res[1])          # a NaN box takes the previous box
    np.testing.assert_array_equal(b[3], res[1])          # so does a box of zero width
    with pytest.raises(ValueError, match="frame range"):
        published.toolkit_boxes(res[:3], gt)
    with pytest.raises(ValueError, match="'rect' or 'ivtAff'"):
        published.toolkit_boxes(res, gt, kind="L1Aff")


def test_ivt_affine_state_to_box_by_hand():
    # M = [[161, 2, 0], [119, 0, 2.4375]] maps the 32 x 32 template's corners (+-16, +-16) to
    # x = 161 -+ 32, y = 119 -+ 39: the box (129, 80, 64, 78). The template size is read as
    # the toolkit stores it (uint8), which must not wrap round when negated.
    tmpl = np.array([32, 32], dtype=np.uint8)
    box = published.ivt_affine_to_rect(tmpl, [161, 119, 2, 0, 0, 2.4375])
    np.testing.assert_array_equal(box, [129, 80, 64, 78])
    # a fractional corner is floored, as calcRectCenter.m does: x0 = floor(10.5 - 16) = -6
    box = published.ivt_affine_to_rect((32, 32), [10.5, 20.25, 1, 0, 0, 1])
    np.testing.assert_array_equal(box, [-6, 4, 32, 32])
    with pytest.raises(ValueError, match="6 values"):
        published.ivt_affine_to_rect((32, 32), [1, 2, 3])


def test_error_num_is_a_whole_number_of_frames():
    # 13 of 471 frames at IoU >= 0.5: errorNum = 10 * 458 / 471
    assert published.rate_from_error_num(10 * 458 / 471, 471) == 13 / 471
    with pytest.raises(ValueError, match="another frame range"):
        published.rate_from_error_num(10 * 458 / 471, 770)


def test_without_first_frame_by_hand():
    # 5 successes in 10 frames, frame 1 one of them: 4 in the other 9
    assert published.without_first_frame(0.5, 10) == pytest.approx(4 / 9)


# --- side by side ----------------------------------------------------------------------------

def test_side_by_side_holds_both_sources_on_the_same_frames():
    rows = published.side_by_side()
    pub = [r for r in rows if r["source"] == "published"]
    own = [r for r in rows if r["source"] == "trackbook"]
    assert len(pub) == len(published.TRACKERS) * len(published.SEQUENCES)
    assert {r["sequence"] for r in own} == set(published.SEQUENCES)
    table = {(r["tracker"], r["sequence"]): r for r in published.load()}
    for r in pub:
        t = table[(r["tracker"], r["sequence"])]
        hits = t["success_rate_iou50"] * t["frames"]
        assert r["rate"] == pytest.approx((hits - 1) / (t["frames"] - 1))
        assert 0.0 <= r["rate"] <= 1.0
    records = json.loads((ROOT / "src/trackbook/results/real.json").read_text())["rows"]
    want = {(x["tracker"], x["clip"]): x["tracking_rate"] for x in records
            if x["clip"] in published.SEQUENCES and x["preset"] == "book"}
    assert {(r["tracker"], r["sequence"]): r["rate"] for r in own} == want


def test_side_by_side_takes_given_records():
    records = [{"tracker": "mine", "clip": "David", "tracking_rate": 0.25},
               {"tracker": "mine", "clip": "Bag", "tracking_rate": 0.75}]      # not an OTB one
    own = [r for r in published.side_by_side(records) if r["source"] == "trackbook"]
    assert own == [{"tracker": "mine", "source": "trackbook", "sequence": "David", "rate": 0.25}]


# --- recomputing the table from the result files (third-party data, not in the repository) ---

MAT = os.environ.get("TRACKBOOK_OTB_MAT")
JSON = os.environ.get("TRACKBOOK_OTB_JSON")


@needs_sequences
@pytest.mark.skipif(not (MAT and JSON),
                    reason="OTB result files not here (set TRACKBOOK_OTB_MAT and TRACKBOOK_OTB_JSON; "
                           "see benchmarks/otb_published.py)")
def test_table_recomputes_from_the_result_files():
    gts = {}
    for s in published.SEQUENCES:
        folder = SEQUENCES[s]
        gt = folder / "groundtruth.txt"
        gts[s] = read_groundtruth(gt if gt.is_file() else folder / "groundtruth_rect.txt")
    rows = published.build_rows(MAT, JSON, gts)
    committed = {(r["tracker"], r["sequence"]): r for r in published.load()}
    assert len(rows) == len(committed)
    for r in rows:
        c = committed[(r["tracker"], r["sequence"])]
        assert c["source"] == r["source"] and c["frames"] == r["frames"]
        for k in ("success_rate_iou50", "auc", "alt_success_rate_iou50"):
            if r[k] is None:
                assert c[k] is None
            else:
                assert c[k] == pytest.approx(r[k], abs=1e-9)
