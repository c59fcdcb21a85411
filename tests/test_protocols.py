"""The evaluation protocols of ``trackbook.evaluation.protocols`` on hand-made runs.

Expected values are worked out by hand from the definitions in the module's docstrings (OTB's
``splitSeqTRE.m`` / ``shiftInitBB.m`` / pooled success, Wu et al. 2013; VOT's reset rule,
burn-in and EAO, Kristan et al. 2015, 2016), with the arithmetic written out. The boxes come
from a script indexed by frame number, either fed straight to the pure functions or returned
by a scripted tracker that reads the frame number off the frame it is given (so a wrong frame
handed to the tracker shows as a wrong box). One integration test runs ``kcf`` on the
``red-cube`` sample through each protocol for shapes, ranges and determinism only.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import trackbook
from trackbook.clips.clip import ArrayFrames, Clip
from trackbook.evaluation import protocols as P
from trackbook.trackers import Tracker

# -- a scripted world: a 10 x 10 target that never moves -------------------------------------
GT = (10.0, 10.0, 10.0, 10.0)
HALF = (10.0, 10.0, 5.0, 10.0)      # inside GT, half its area: IoU = 50 / 100 = 0.5
MISS = (40.0, 40.0, 10.0, 10.0)     # disjoint from GT: IoU = 0, a failure

#: 40 frames; the box the tracker reports on each frame (absolute frame number).
SCRIPT = {12: HALF, 14: MISS, 25: HALF, 31: MISS}
L = 40


def script_box(i: int):
    return SCRIPT.get(i, GT)


def gt_of(n: int) -> np.ndarray:
    return np.tile(np.array(GT), (n, 1))


def scripted_segment(script=script_box):
    """``segment(start, box)`` for :func:`reset_protocol` yielding the scripted boxes."""
    calls = []

    def segment(start, box):
        calls.append((start, tuple(box)))
        i = start
        while True:
            i += 1
            yield script(i)

    return segment, calls


class Scripted(Tracker):
    """Returns ``SCRIPT``'s box for the frame number written in pixel (0, 0) of each frame.
    Not registered: handed to the protocols as an object, so the registry stays as it is."""

    name = "scripted"

    def _init(self, frame, box):
        self.inits = getattr(self, "inits", []) + [int(frame[0, 0, 0])]

    def _update(self, frame):
        return True, script_box(int(frame[0, 0, 0]))


def numbered_clip(n: int = L) -> Clip:
    frames = np.zeros((n, 48, 64, 3), np.uint8)
    frames[:, 0, 0, 0] = np.arange(n)            # the frame number, read by Scripted
    frames[:, 30:, 30:] = 200                    # not flat
    return Clip("numbered", ArrayFrames(frames), gt_of(n))


# -- VOT reset-based protocol -----------------------------------------------------------------
# Defaults skip = 5, burnin = 10. By hand:
#   init 0; frames 1..13 tracked (12 is HALF); frame 14 MISS -> failure 1.
#   skip 15, 16, 17, 18; re-init on frame 14 + 5 = 19.
#   frames 20..30 tracked (25 is HALF); frame 31 MISS -> failure 2.
#   skip 32..35; re-init on 36; frames 37, 38, 39 tracked; the clip ends.
#   burn-in: 1..10 after init 0, 20..29 after 19, 37..46 after 36.
#   accuracy frames: 11, 12, 13 and 30 (14 and 31 are failures) -> IoU 1, 0.5, 1, 1
#   accuracy = (1 + 0.5 + 1 + 1) / 4 = 3.5 / 4 = 0.875.

def test_reset_protocol_reinitialises_five_frames_after_each_failure():
    segment, calls = scripted_segment()
    run = P.reset_protocol(segment, gt_of(L))
    assert run.inits == (0, 19, 36)
    assert run.failures == (14, 31)
    assert [c[0] for c in calls] == [0, 19, 36]
    assert all(c[1] == GT for c in calls)                 # restarted on the ground truth
    assert run.skipped == (15, 16, 17, 18, 32, 33, 34, 35)
    assert np.isnan(run.boxes[list(run.skipped)]).all()
    assert np.isnan(run.overlaps[[0, 19, 36]]).all()      # initialisations are not scored
    assert run.overlaps[12] == 0.5 and run.overlaps[14] == 0.0 and run.overlaps[13] == 1.0


def test_reset_accuracy_skips_the_burn_in_and_the_failures():
    segment, _ = scripted_segment()
    run = P.reset_protocol(segment, gt_of(L))
    assert list(np.flatnonzero(run.valid)) == [11, 12, 13, 30]
    assert run.accuracy == pytest.approx(3.5 / 4)
    # HALF on frame 25 is inside the second burn-in (20..29): it does not lower accuracy.
    # The toolkit's mask (s .. s + 9) is burnin=9 here: frames 10 and 29 join, both IoU 1:
    # (1 + 1 + 0.5 + 1 + 1 + 1) / 6 = 5.5 / 6.
    run9 = P.reset_protocol(scripted_segment()[0], gt_of(L), burnin=9)
    assert list(np.flatnonzero(run9.valid)) == [10, 11, 12, 13, 29, 30]
    assert run9.accuracy == pytest.approx(5.5 / 6)
    # burnin=0: every tracked non-failure frame; 1..13 minus 14, 20..30, 37..39:
    # 13 + 11 + 3 = 27 frames, two of them HALF: (27 - 2 * 0.5) / 27 = 26 / 27.
    run0 = P.reset_protocol(scripted_segment()[0], gt_of(L), burnin=0)
    assert run0.valid.sum() == 27
    assert run0.accuracy == pytest.approx(26 / 27)


def test_reset_robustness_counts_failures_per_100_frames():
    run = P.reset_protocol(scripted_segment()[0], gt_of(L))
    assert run.n_failures == 2
    assert run.failure_rate == pytest.approx(100 * 2 / 40)        # 5 per 100 frames
    assert run.reliability() == pytest.approx(math.exp(-30 * 2 / 40))


def test_reset_run_ends_when_the_restart_frame_is_past_the_clip():
    # 20 frames, a miss on frame 17: the restart would be on 22 > 19, so the run ends there.
    run = P.reset_protocol(scripted_segment(lambda i: MISS if i == 17 else GT)[0], gt_of(20))
    assert run.inits == (0,) and run.failures == (17,)
    assert run.skipped == (18, 19)
    assert run.fragments()[0][1] is True and len(run.fragments()) == 1


def test_reset_restarts_on_the_next_known_ground_truth_and_unknown_frames_never_fail():
    gt = gt_of(30)
    gt[3] = np.nan            # a miss here is not a failure: nothing to overlap with
    gt[11] = np.nan           # the restart frame after the failure on 6 (6 + 5 = 11) is unknown
    script = {3: MISS, 6: MISS}
    run = P.reset_protocol(scripted_segment(lambda i: script.get(i, GT))[0], gt)
    assert run.failures == (6,)
    assert run.inits == (0, 12)
    assert run.skipped == (7, 8, 9, 10, 11)
    assert np.isnan(run.overlaps[3])


def test_reset_protocol_refuses_a_segment_that_stops_early():
    def short(start, box):
        yield GT

    with pytest.raises(ValueError, match="yield a box for every frame"):
        P.reset_protocol(short, gt_of(5))


def test_evaluate_reset_gives_the_tracker_the_right_frames():
    tracker = Scripted(seed=0)
    run = P.evaluate_reset(tracker, numbered_clip())
    pure = P.reset_protocol(scripted_segment()[0], gt_of(L))
    assert tracker.inits == [0, 19, 36]          # init saw the frames numbered 0, 19, 36
    assert run.inits == pure.inits and run.failures == pure.failures
    np.testing.assert_array_equal(run.boxes, pure.boxes)
    assert run.tracker == "scripted" and run.clip == "numbered"


# -- EAO --------------------------------------------------------------------------------------
# Fragments of the run above (overlaps of the frames after each initialisation):
#   F1 frames 1..14:  eleven 1s (1..11), 0.5 (12), 1 (13), 0 (14)   m = 14, failed, sum 12.5
#   F2 frames 20..31: five 1s (20..24), 0.5 (25), five 1s (26..30), 0 (31)
#                                                                    m = 12, failed, sum 10.5
#   F3 frames 37..39: 1, 1, 1                                        m = 3, reached the end
F1 = [1.0] * 11 + [0.5, 1.0, 0.0]
F2 = [1.0] * 5 + [0.5] + [1.0] * 5 + [0.0]
F3 = [1.0, 1.0, 1.0]


def test_fragments_are_cut_at_the_initialisations():
    run = P.reset_protocol(scripted_segment()[0], gt_of(L))
    fr = run.fragments()
    assert [f[1] for f in fr] == [True, True, False]
    for (o, _), want in zip(fr, (F1, F2, F3)):
        np.testing.assert_array_equal(o, want)


def test_eao_curve_by_hand():
    run = P.reset_protocol(scripted_segment()[0], gt_of(L))
    curve = P.eao_curve([run], 20)
    # N = 3: all three fragments defined, each 3 / 3 = 1.
    assert curve[3] == pytest.approx(1.0)
    # N = 12: F3 is undefined (12 > 3); F1 = (11 + 0.5) / 12, F2 = 10.5 / 12 -> 22 / 24.
    assert curve[12] == pytest.approx((11.5 / 12 + 10.5 / 12) / 2)
    # N = 13: F1 = 12.5 / 13, F2 = (10.5 + 0) / 13 (zero after its failure) -> 23 / 26.
    assert curve[13] == pytest.approx(23 / 26)
    # N = 20: F1 = 12.5 / 20, F2 = 10.5 / 20 -> (0.625 + 0.525) / 2 = 0.575.
    assert curve[20] == pytest.approx(0.575)
    assert np.isnan(curve[0])
    assert P.eao([run], (12, 13)) == pytest.approx((22 / 24 + 23 / 26) / 2)


def test_eao_default_range_is_one_to_the_clip_length():
    run = P.reset_protocol(scripted_segment()[0], gt_of(L))
    # the definition, written as loops over the hand-made fragments, N = 1 .. 39
    per_n = []
    for n in range(1, L):
        phis = []
        for o, failed in ((F1, True), (F2, True), (F3, False)):
            if n <= len(o):
                phis.append(sum(o[:n]) / n)
            elif failed:
                phis.append(sum(o) / n)          # zeros after the failure
        per_n.append(sum(phis) / len(phis))
    assert P.eao([run]) == pytest.approx(sum(per_n) / len(per_n))


def test_eao_of_a_run_without_failure_is_undefined_past_its_length():
    run = P.reset_protocol(scripted_segment(lambda i: GT)[0], gt_of(10))
    assert run.failures == () and P.eao([run]) == pytest.approx(1.0)
    with pytest.raises(ValueError, match="N = 10"):
        P.eao([run], (5, 12))


# -- OTB TRE ----------------------------------------------------------------------------------

def test_tre_starts_on_a_40_frame_clip():
    # Every frame known. E = last candidate leaving >= 20 frames: 40 - i >= 20 -> i <= 20,
    # position E = 21. Positions 1 + floor(21 k / 19), k = 0..18 (1 + 21k/19 <= 21):
    # 21k = 0, 21, ..., 189 -> 0..9; 210 -> 11, 231 -> 12, ..., 378 -> 19; then E = 21.
    # 0-based frames: 0..9, 11..20.
    want = list(range(10)) + list(range(11, 21))
    assert list(P.tre_starts(gt_of(40))) == want


def test_tre_starts_skip_unknown_frames_and_repeat_on_short_clips():
    # 25 frames, frame 2 unknown: candidates 0, 1, 3, 4, 5, ...; 25 - i >= 20 -> i <= 5, so
    # candidates 0, 1, 3, 4, 5 and E = 5. k <= 19 * 4 / 5 = 15.2 -> k = 0..15,
    # 5k // 19 = 0,0,0,0, 1,1,1,1, 2,2,2,2, 3,3,3,3 -> positions 1..4 four times each, then 5.
    gt = gt_of(25)
    gt[2] = np.nan
    want = [0] * 4 + [1] * 4 + [3] * 4 + [4] * 4 + [5]
    assert list(P.tre_starts(gt)) == want
    # a box poking out on the left (x < 0) and an excluded frame are not starts either
    gt[1, 0] = -3.0
    assert 1 not in P.tre_starts(gt)
    assert 0 not in P.tre_starts(gt_of(40), exclude=[0])


def test_tre_refuses_a_clip_shorter_than_a_segment():
    with pytest.raises(ValueError, match="min_length"):
        P.tre_starts(gt_of(19))


def test_evaluate_tre_starts_each_run_on_its_frame():
    res = P.evaluate_tre(Scripted(seed=0), numbered_clip())
    assert list(res.starts) == list(range(10)) + list(range(11, 21))
    for s, r in zip(res.starts, res.results):
        assert len(r.boxes) == L - s
        np.testing.assert_array_equal(r.boxes[1:], [script_box(i) for i in range(s + 1, L)])
    np.testing.assert_array_equal(res.init_boxes, gt_of(20))


# -- OTB SRE ----------------------------------------------------------------------------------

def test_sre_boxes_by_hand():
    # (x, y, w, h) = (10, 20, 50, 30): dx = 5, dy = 3, centre (35, 35).
    want = [
        (5, 20, 50, 30), (15, 20, 50, 30), (10, 17, 50, 30), (10, 23, 50, 30),  # centre shifts
        (5, 17, 55, 33), (10, 17, 55, 33), (5, 20, 55, 33), (10, 20, 55, 33),   # corner shifts
        (35 - 20, 35 - 12, 40, 24), (35 - 22.5, 35 - 13.5, 45, 27),             # 0.8, 0.9
        (35 - 27.5, 35 - 16.5, 55, 33), (35 - 30, 35 - 18, 60, 36),             # 1.1, 1.2
    ]
    np.testing.assert_allclose(P.sre_boxes((10, 20, 50, 30)), want)
    assert len(P.SRE_SHIFTS) == 12


def test_evaluate_sre_initialises_on_each_perturbed_box():
    res = P.evaluate_sre(Scripted(seed=0), numbered_clip())
    np.testing.assert_allclose(res.init_boxes, P.sre_boxes(GT))
    assert res.labels == P.SRE_SHIFTS and list(res.starts) == [0] * 12


# -- pooling ----------------------------------------------------------------------------------

def test_pooled_scores_weigh_runs_by_their_frames():
    # Run A scores IoU 1, 0.5; run B scores 0, 1, 1 (frame 0 of each is the init, dropped).
    # Success thresholds 0, 0.05, ..., 1: IoU 1 beats 20 of 21, IoU 0.5 beats 10, IoU 0 none.
    # Pooled AUC = (20 + 10 + 0 + 20 + 20) / (5 * 21) = 70 / 105 = 2 / 3, whereas the plain
    # mean of the runs' AUCs would be (30 / 42 + 40 / 63) / 2 = 85 / 126.
    a = [GT, GT, HALF]
    b = [GT, MISS, GT, GT]
    s = P.pooled_scores([a, b], [gt_of(3), gt_of(4)])
    assert s["auc"] == pytest.approx(2 / 3)
    assert s["tracking_rate"] == pytest.approx(3 / 5)     # IoU > 0.5: 1, 1, 1 of 5
    assert s["frames_scored"] == 5


# -- a real tracker ---------------------------------------------------------------------------

def test_kcf_through_every_protocol_is_deterministic():
    full = trackbook.clips.load("red-cube")
    clip = dataclasses.replace(full, frames=full.frames[:40], groundtruth=full.groundtruth[:40],
                               targets={})
    tre = [P.evaluate_tre("kcf", clip, seed=3) for _ in range(2)]
    assert tre[0].starts.shape == (20,) and len(tre[0].results) == 20
    assert 0.0 <= tre[0].scores["auc"] <= 1.0
    assert tre[0].scores == tre[1].scores
    sre = [P.evaluate_sre("kcf", clip, seed=3) for _ in range(2)]
    assert sre[0].init_boxes.shape == (12, 4) and len(sre[0].results) == 12
    assert sre[0].scores["frames_scored"] == 12 * 39
    assert sre[0].scores == sre[1].scores
    runs = [P.evaluate_reset("kcf", clip, seed=3) for _ in range(2)]
    r = runs[0]
    assert r.boxes.shape == (40, 4) and r.inits[0] == 0
    assert 0.0 <= r.accuracy <= 1.0 and r.n_failures >= 0
    assert 0.0 <= P.eao([r]) <= 1.0
    np.testing.assert_array_equal(r.boxes, runs[1].boxes)
    assert (r.accuracy, r.failures, P.eao([r])) == (runs[1].accuracy, runs[1].failures,
                                                    P.eao([runs[1]]))


def test_a_real_failure_restarts_five_frames_later():
    # mosse loses the target behind the panel of the ``occluder`` sample: the structure of
    # the run, not its numbers, is checked (a failure, a restart 5 frames on, same twice).
    runs = [P.evaluate_reset("mosse", "occluder", seed=0) for _ in range(2)]
    r = runs[0]
    assert r.n_failures >= 1
    for f, s in zip(r.failures, r.inits[1:]):
        assert s == f + 5
        assert np.isnan(r.boxes[f + 1:s]).all()
        np.testing.assert_array_equal(r.boxes[s], trackbook.clips.load("occluder").groundtruth[s])
    assert r.failures == runs[1].failures
    np.testing.assert_array_equal(r.boxes, runs[1].boxes)


def test_reset_starts_on_the_first_known_box_and_eao_refuses_no_runs():
    gt = gt_of(12)
    gt[:3] = np.nan
    segment, calls = scripted_segment()
    run = P.reset_protocol(segment, gt)
    assert run.inits == (3,) and calls[0][0] == 3
    with pytest.raises(ValueError, match="list of ResetRun"):
        P.eao([])
