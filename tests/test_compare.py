"""The comparison chapter's tables and claim checks, on hand-made benchmark rows."""
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbook.evaluation import compare
from trackbook.papers import PAPERS


def _row(t, clip, auc, rate, ms, **extra):
    return {"tracker": t, "clip": clip, "auc": auc, "precision20": auc, "tracking_rate": rate,
            "ms_median": ms, **extra}


ROWS = [
    _row("color-pf", "a", 0.3, 0.5, 2.0), _row("color-pf", "b", 0.5, 0.7, 4.0),
    _row("color-hog-pf", "a", 0.4, 0.6, 5.0), _row("color-hog-pf", "b", 0.6, 0.8, 7.0),
    _row("color-hog-ipca", "a", 0.2, 0.9, 6.0), _row("color-hog-ipca", "b", 0.2, 0.95, 8.0),
    _row("covariance", "a", 0.5, 0.9, 1.0, search_rate=0.004),
    _row("kalman-covariance", "a", 0.5, 0.9, 1.0, search_rate=0.003),
    _row("opencv-mil", "a", 0.5, 0.5, 20.0), _row("opencv-mil", "b", 0.5, 0.5, 30.0),
]


def test_table_means_and_median_ms():
    t = {r["tracker"]: r for r in compare.table(ROWS)}
    assert t["color-pf"]["auc"] == 0.4 and t["color-pf"]["ms_median"] == 3.0
    t = {r["tracker"]: r for r in compare.table(ROWS, clips={"a"})}
    assert t["color-pf"]["auc"] == 0.3


def _seeded(t, clip, seed, auc, rate=None):
    return {"tracker": t, "clip": clip, "seed": seed, "auc": auc,
            "tracking_rate": auc if rate is None else rate}


def test_paired_differences_pair_by_clip_and_seed():
    rows = [_seeded("a", "x", 0, 0.5), _seeded("a", "x", 1, 0.7), _seeded("b", "x", 0, 0.25),
            _seeded("b", "x", 1, 0.5), _seeded("a", "y", 0, 0.1)]          # y: b missing
    d = compare.paired_differences(rows, "a", "b")
    assert list(d) == ["x"] and d["x"] == pytest.approx([0.25, 0.2])


def test_claim_holds_fails_or_is_inconclusive_from_the_interval():
    up = [_seeded(t, c, s, base + (0.1 if t == "color-hog-pf" else 0.0) + 0.01 * s)
          for c, base in zip("abcdefg", np.linspace(0.2, 0.6, 7)) for s in range(3)
          for t in ("color-pf", "color-hog-pf")]
    pairs = {"lee2012": [("color-hog-pf", "color-pf")]}
    (r,) = compare.check_claims(up, pairs=pairs, papers={"lee2012": PAPERS["lee2012"]})
    # every paired difference is +0.1: the mean is 0.1 and so is every bootstrap mean
    assert r["mean_diff"] == pytest.approx(0.1) and r["verdict"] == "holds"
    assert r["ci_low"] == pytest.approx(0.1) and r["ci_high"] == pytest.approx(0.1)
    assert (r["sequences"], r["runs"]) == (7, 21)
    (r,) = compare.check_claims(up, pairs={"lee2012": [("color-pf", "color-hog-pf")]},
                                papers={"lee2012": PAPERS["lee2012"]})
    assert r["verdict"] == "fails"
    # half the sequences better by 0.1, half worse by 0.1: the interval straddles 0
    mixed = [dict(x, auc=x["auc"] - (0.2 if x["tracker"] == "color-hog-pf" and x["clip"] in "abc"
                                     else 0.0)) for x in up]
    (r,) = compare.check_claims(mixed, pairs=pairs, papers={"lee2012": PAPERS["lee2012"]})
    assert r["ci_low"] < 0 < r["ci_high"] and r["verdict"] == "inconclusive"


def test_claims_for_trackers_not_run_are_inconclusive_with_no_runs():
    rows = [_seeded("color-pf", "a", 0, 0.3)]
    out = compare.check_claims(rows)
    assert {r["verdict"] for r in out} == {"inconclusive"}
    assert all(r["runs"] == 0 for r in out)


def test_bootstrap_interval_matches_scipy_with_one_run_per_sequence():
    """With one seed per sequence the cluster bootstrap is the ordinary one: scipy's
    percentile interval is an independent oracle (Monte Carlo error ~0.005 at 20 000 draws)."""
    scipy_stats = pytest.importorskip("scipy.stats")
    x = np.array([0.12, -0.05, 0.3, 0.07, 0.21, -0.11, 0.16])
    mean, low, high = compare.bootstrap_mean_difference(
        {str(i): [v] for i, v in enumerate(x)}, n_boot=20_000)
    ref = scipy_stats.bootstrap((x,), np.mean, n_resamples=20_000, method="percentile",
                                random_state=1).confidence_interval
    assert mean == pytest.approx(x.mean())
    assert low == pytest.approx(ref.low, abs=0.01) and high == pytest.approx(ref.high, abs=0.01)


@given(st.lists(st.lists(st.floats(0.001, 1.0), min_size=1, max_size=4), min_size=1,
                max_size=8))
@settings(max_examples=60, deadline=None)
def test_all_positive_sequence_means_always_hold(per_seq):
    """Every bootstrap mean is a weighted mean of sequence means, so when every sequence's
    differences are positive the interval is above 0 whatever the draw."""
    d = {str(i): v for i, v in enumerate(per_seq)}
    mean, low, high = compare.bootstrap_mean_difference(d, n_boot=500)
    assert low > 0 and low <= mean <= high
    assert compare.verdict(low, high) == "holds"


def test_loso_selection_by_hand():
    # config "tuned" is best on a and b only by a fluke on c; worked by hand:
    scores = {"p": {"a": 0.5, "b": 0.5, "c": 0.5}, "q": {"a": 0.4, "b": 0.4, "c": 0.9}}
    r = compare.loso_select(scores)
    # hold out a: means on (b, c) p 0.5, q 0.65 -> q, scores 0.4 on a; likewise b -> q, 0.4;
    # hold out c: means on (a, b) p 0.5, q 0.4 -> p, scores 0.5 on c.
    assert r["chosen"] == {"a": "q", "b": "q", "c": "p"}
    assert r["cv"] == pytest.approx((0.4 + 0.4 + 0.5) / 3)
    assert r["tuned_config"] == "q" and r["tuned"] == pytest.approx(1.7 / 3)
    assert r["cv"] < r["tuned"]              # tuning on the scored sequences overstates
    with pytest.raises(ValueError, match="at least two sequences"):
        compare.loso_select({"p": {"a": 1.0}})


def test_per_attribute_picks_the_best_tracker():
    rows = compare.per_attribute(ROWS, {"a": ("OCC",), "b": ("IV", "OCC")})
    by = {r["difficulty"]: r for r in rows}
    assert by["illumination change (IV)"]["best"] == "color-hog-pf"     # 0.6 on clip b
    assert by["occlusion (OCC)"]["clips"] == 2
    assert "fast motion (FM)" not in by


def test_speed_ratios_against_mil_and_paper():
    r = {x["tracker"]: x for x in compare.speed_ratios(ROWS)}
    assert r["color-pf"]["÷ MIL"] == 3.0 / 25.0
    assert r["color-hog-ipca"]["paper ÷ ours"] == 55.0 / 7.0
    assert math.isnan(r["covariance"]["paper ms"])
    assert "opencv-mil" not in r


def test_markdown_renders_nan_as_dash():
    md = compare.markdown([{"a": "x", "b": float("nan"), "c": 0.5}])
    assert md.splitlines()[2] == "| x | – | 0.500 |"
