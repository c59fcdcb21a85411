"""Several-target measures (trackbook.evaluation.mot) against hand-worked cases and two
independent implementations: py-motmetrics (MOTA, MOTP, IDF1) and TrackEval (HOTA).

motmetrics is fed distances d = 1 − IoU with pairs of d > 0.5 forbidden (IoU ≥ 0.5 matches),
so its MOTP is the mean *distance* of the matches: ours (mean IoU) is 1 − its MOTP.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from trackbook.evaluation.mot import ALPHAS, clear_mot, hota, identity_scores, mot_scores

BOX = (0.0, 0.0, 10.0, 10.0)
FAR = (500.0, 500.0, 10.0, 10.0)


def shifted(dx, box=BOX):
    return (box[0] + dx, box[1], box[2], box[3])


# --- hand-worked cases -------------------------------------------------------------------

def test_three_frames_worked_by_hand():
    # targets 1 (at A) and 2 (at B, 100 px away), hypotheses a, b, c:
    #   frame 0: a on 1, b on 2                      -> 2 matches
    #   frame 1: a on 1, target 2 missed, c far away -> 1 match, FN 1, FP 1
    #   frame 2: b on 1, a on 2; the old pairs 1-a and 2-b no longer overlap, so the Hungarian
    #            step pairs 1-b and 2-a: both targets change hypothesis -> IDSW 2
    # MOTA = 1 − (FN + FP + IDSW) / Σ g_t = 1 − (1 + 1 + 2) / 6 = 1/3
    # IoUs: every match is exact except frame 0's b on 2, shifted by 2.5 px: IoU 7.5/12.5 = 0.6
    # MOTP = (1 + 0.6 + 1 + 1 + 1) / 5 = 0.92
    A, B = BOX, shifted(100)
    truth = [[(1, A), (2, B)], [(1, A), (2, B)], [(1, A), (2, B)]]
    hyps = [[("a", A), ("b", shifted(2.5, B))], [("a", A), ("c", FAR)], [("b", A), ("a", B)]]
    s = clear_mot(truth, hyps)
    assert (s.matches, s.misses, s.false_positives, s.switches, s.n_truth) == (5, 1, 1, 2, 6)
    assert s.mota == pytest.approx(1 / 3, abs=1e-12)
    assert s.motp == pytest.approx(0.92, abs=1e-12)
    # IDF1: co-occurrences 1-a: 2 frames, 1-b: 1, 2-b: 1, 2-a: 1; best one-to-one: 1-a, 2-b
    # IDTP = 3, G = 6, H = 6 -> IDF1 = 6 / 12
    idf = identity_scores(truth, hyps)
    assert (idf.idtp, idf.idfn, idf.idfp) == (3, 3, 3)
    assert idf.idf1 == pytest.approx(0.5, abs=1e-12)


def test_a_still_valid_match_is_kept_over_a_better_one():
    # frame 0: a exactly on the target, b far. Frame 1: a shifted 2.5 px (IoU 0.6), b exactly
    # on it. A fresh matching would take b (IoU 1); CLEAR-MOT keeps a: no switch, and b is an
    # FP in both frames. MOTA = 1 − (FN 0 + FP 2 + IDSW 0) / 2 = 0; MOTP = (1 + 0.6) / 2 = 0.8
    truth = [[(1, BOX)], [(1, BOX)]]
    hyps = [[("a", BOX), ("b", FAR)], [("a", shifted(2.5)), ("b", BOX)]]
    s = clear_mot(truth, hyps)
    assert (s.switches, s.false_positives, s.misses) == (0, 2, 0)
    assert s.mota == pytest.approx(0.0, abs=1e-12)
    assert s.motp == pytest.approx(0.8, abs=1e-12)


def test_a_match_below_the_threshold_is_released():
    # frame 1: a shifted 6 px (IoU 4/16 = 0.25 < 0.5), so 1-a is no longer valid and b takes
    # the target: one switch. FN 0, FP 1 (frame 1's a) + 1 (frame 0's b far) -> MOTA = 1 − 3/2
    truth = [[(1, BOX)], [(1, BOX)]]
    hyps = [[("a", BOX), ("b", FAR)], [("a", shifted(6)), ("b", BOX)]]
    s = clear_mot(truth, hyps)
    assert (s.switches, s.false_positives) == (1, 2)
    assert s.mota == pytest.approx(-0.5, abs=1e-12)
    # with a lower threshold the pair stays valid and is kept
    assert clear_mot(truth, hyps, threshold=0.2).switches == 0


def test_hota_of_a_perfect_run_and_of_a_broken_identity():
    truth = [[(1, BOX)]] * 4
    assert hota(truth, truth).hota == pytest.approx(1.0, abs=1e-12)
    # one target followed by a for two frames, then by b, boxes exact: DetA = 1 at every α;
    # each TP's pair (1, a) or (1, b) has |TPA| = 2 of n_1 + n_h − |TPA| = 4 + 2 − 2 = 4 -> AssA
    # = 1/2, HOTA = √(1 · 1/2)
    hyps = [[("a", BOX)], [("a", BOX)], [("b", BOX)], [("b", BOX)]]
    h = hota(truth, hyps)
    assert h.deta == pytest.approx(1.0, abs=1e-12)
    assert h.assa == pytest.approx(0.5, abs=1e-12)
    assert h.hota == pytest.approx(math.sqrt(0.5), abs=1e-12)
    assert len(h.alphas) == 19 and h.alphas[0] == 0.05 and h.alphas[-1] == 0.95


def test_hota_counts_a_box_only_at_the_thresholds_its_iou_reaches():
    # one target, one hypothesis at IoU 0.6 for two frames: a TP for α ≤ 0.6 (12 of the 19
    # thresholds 0.05 … 0.60) and an FN + FP above, where DetA_α = 0 and AssA_α = 0.
    # Below: DetA = AssA = 1. HOTA = 12/19.
    truth = [[(1, BOX)]] * 2
    hyps = [[(7, shifted(2.5))]] * 2
    h = hota(truth, hyps)
    assert np.array_equal(h.deta_alpha, (ALPHAS <= 0.6 + 1e-12).astype(float))
    assert h.hota == pytest.approx(12 / 19, abs=1e-12)


def test_empty_runs_and_array_frames():
    truth = [np.array([[0, 0, 10, 10, 1]], float), np.zeros((0, 5))]
    assert mot_scores(truth, [[], []])["mota"] == 0.0
    assert hota(truth, [[], []]).hota == 0.0
    assert mot_scores(truth, truth) == {"mota": 1.0, "motp": 1.0, "idf1": 1.0, "hota": 1.0,
                                        "deta": 1.0, "assa": 1.0}


@pytest.mark.parametrize("truth, hyps, message", [
    ([[]], [[], []], "different numbers of frames"),
    ([[(1, BOX), (1, BOX)]], [[]], "id twice"),
    ([[(1, (0, 0, -1, 4))]], [[]], "negative"),
    ([[(1, (0, 0, 4))]], [[]], "pairs"),
    ([np.zeros((2, 4))], [[]], "(k, 5)"),
])
def test_bad_runs_are_refused_with_the_fix(truth, hyps, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        clear_mot(truth, hyps)


# --- randomised runs against the oracles -------------------------------------------------

def random_run(seed: int, n_targets: int = 5, n_frames: int = 40):
    """Ground truth and hypotheses with noise, misses, false positives, swaps and new ids."""
    rng = np.random.default_rng(seed)
    start = rng.uniform(0, 200, (n_targets, 2))
    vel = rng.uniform(-4, 4, (n_targets, 2))
    size = rng.uniform(15, 40, (n_targets, 2))
    born = rng.integers(0, n_frames // 3, n_targets)
    dies = rng.integers(2 * n_frames // 3, n_frames + 1, n_targets)
    hyp_id = np.arange(n_targets) + 100            # current hypothesis id of each target
    next_id = 200
    truth, hyps = [], []
    for t in range(n_frames):
        g, h = [], []
        if rng.random() < 0.1 and n_targets > 1:      # two hypotheses swap targets
            i, j = rng.choice(n_targets, 2, replace=False)
            hyp_id[[i, j]] = hyp_id[[j, i]]
        if rng.random() < 0.08:                         # a track is re-started with a new id
            hyp_id[rng.integers(n_targets)] = next_id
            next_id += 1
        for k in range(n_targets):
            if not born[k] <= t < dies[k]:
                continue
            box = np.r_[start[k] + vel[k] * t, size[k]]
            g.append((int(k), box))
            if rng.random() < 0.15:                     # missed
                continue
            noisy = box + rng.normal(0, 0.12, 4) * np.r_[size[k], size[k]]
            noisy[2:] = np.abs(noisy[2:]) + 1
            h.append((int(hyp_id[k]), noisy))
        for _ in range(rng.poisson(0.7)):               # false positives near the action
            h.append((next_id, np.r_[rng.uniform(0, 300, 2), rng.uniform(15, 40, 2)]))
            next_id += 1
        truth.append(g)
        hyps.append(h)
    return truth, hyps


def _ids_boxes(frame):
    ids = [i for i, _ in frame]
    boxes = np.array([b for _, b in frame], float).reshape(-1, 4)
    return ids, boxes


SEEDS = list(range(8))


@pytest.mark.parametrize("seed, threshold", [(s, 0.5) for s in SEEDS] + [(0, 0.3), (1, 0.7)])
def test_mota_motp_idf1_match_motmetrics(seed, threshold):
    mm = pytest.importorskip("motmetrics")
    truth, hyps = random_run(seed)
    acc = mm.MOTAccumulator(auto_id=True)
    for g, h in zip(truth, hyps):
        gi, gb = _ids_boxes(g)
        hi, hb = _ids_boxes(h)
        # motmetrics' own iou_matrix calls a numpy function removed in numpy 2; its boxiou is
        # fine, and the "forbid d > 1 − threshold" step is the one line iou_matrix adds
        d = 1.0 - mm.distances.boxiou(gb[:, None], hb[None, :])
        acc.update(gi, hi, np.where(d > 1.0 - threshold, np.nan, d))
    summary = mm.metrics.create().compute(
        acc, metrics=["mota", "motp", "idf1", "num_switches", "num_misses",
                      "num_false_positives"], name="run").iloc[0]
    ours = clear_mot(truth, hyps, threshold)
    assert summary["num_switches"] > 0 and summary["num_misses"] > 0  # the run exercises them
    assert ours.switches == summary["num_switches"]
    assert ours.misses == summary["num_misses"]
    assert ours.false_positives == summary["num_false_positives"]
    assert abs(ours.mota - summary["mota"]) < 1e-9
    assert abs(ours.motp - (1.0 - summary["motp"])) < 1e-9
    assert abs(identity_scores(truth, hyps, threshold).idf1 - summary["idf1"]) < 1e-9


@pytest.mark.parametrize("seed", SEEDS)
def test_hota_matches_trackeval(seed):
    metrics = pytest.importorskip("trackeval.metrics")
    base = pytest.importorskip("trackeval.datasets._base_dataset")
    truth, hyps = random_run(seed)
    gmap, hmap = {}, {}
    data = {"gt_ids": [], "tracker_ids": [], "similarity_scores": []}
    for g, h in zip(truth, hyps):
        gi, gb = _ids_boxes(g)
        hi, hb = _ids_boxes(h)
        data["gt_ids"].append(np.array([gmap.setdefault(i, len(gmap)) for i in gi], int))
        data["tracker_ids"].append(np.array([hmap.setdefault(i, len(hmap)) for i in hi], int))
        data["similarity_scores"].append(
            base._BaseDataset._calculate_box_ious(gb, hb, box_format="xywh"))
    data.update(num_gt_ids=len(gmap), num_tracker_ids=len(hmap),
                num_gt_dets=sum(map(len, truth)), num_tracker_dets=sum(map(len, hyps)))
    ref = metrics.HOTA().eval_sequence(data)
    ours = hota(truth, hyps)
    assert 0.2 < ours.hota < 0.95                    # neither trivial end
    np.testing.assert_allclose(ours.hota_alpha, ref["HOTA"], rtol=0, atol=1e-9)
    np.testing.assert_allclose(ours.deta_alpha, ref["DetA"], rtol=0, atol=1e-9)
    np.testing.assert_allclose(ours.assa_alpha, ref["AssA"], rtol=0, atol=1e-9)
    assert abs(ours.hota - ref["HOTA"].mean()) < 1e-9


@pytest.mark.parametrize("seed", SEEDS[:3])
def test_renaming_the_hypotheses_changes_no_score(seed):
    # the measures compare ids only within a run: any one-to-one renaming leaves them as they
    # were (ids of another type and order included)
    truth, hyps = random_run(seed)
    names = {}
    renamed = [[(names.setdefault(i, f"h{-i * 7 % 1009}"), b) for i, b in f] for f in hyps]
    assert len(set(names.values())) == len(names)
    assert mot_scores(truth, renamed) == mot_scores(truth, hyps)


def test_a_match_is_kept_across_a_gap_where_trackeval_matches_afresh():
    # frame 0: a on the target; frame 1: a far away (a miss); frame 2: a back at IoU 0.6 and b
    # exactly on the target. The library (and py-motmetrics) keep 1-a, the last match, as it is
    # valid again: no switch. TrackEval keeps only the previous frame's matches, so frame 2 is
    # a fresh matching that takes b (IoU 1): one switch. Both: FN 1, FP 2 (frame 1's a, frame
    # 2's unmatched box), 3 targets -> MOTA 1 − 3/3 = 0 here and 1 − 4/3 in TrackEval.
    metrics = pytest.importorskip("trackeval.metrics")
    base = pytest.importorskip("trackeval.datasets._base_dataset")
    truth = [[(1, BOX)]] * 3
    hyps = [[("a", BOX)], [("a", FAR)], [("a", shifted(2.5)), ("b", BOX)]]
    ours = clear_mot(truth, hyps)
    assert (ours.switches, ours.misses, ours.false_positives) == (0, 1, 2)
    assert ours.mota == pytest.approx(0.0, abs=1e-12)
    hmap = {}
    data = {"gt_ids": [], "tracker_ids": [], "similarity_scores": []}
    for g, h in zip(truth, hyps):
        gi, gb = _ids_boxes(g)
        hi, hb = _ids_boxes(h)
        data["gt_ids"].append(np.array([0] * len(gi), int))
        data["tracker_ids"].append(np.array([hmap.setdefault(i, len(hmap)) for i in hi], int))
        data["similarity_scores"].append(
            base._BaseDataset._calculate_box_ious(gb, hb, box_format="xywh"))
    data.update(num_gt_ids=1, num_tracker_ids=len(hmap), num_timesteps=3,
                num_gt_dets=3, num_tracker_dets=4)
    ref = metrics.CLEAR().eval_sequence(data)
    assert (ref["IDSW"], ref["CLR_FN"], ref["CLR_FP"]) == (1, 1, 2)
    assert ref["MOTA"] == pytest.approx(1 - 4 / 3, abs=1e-12)
