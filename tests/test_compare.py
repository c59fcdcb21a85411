"""The comparison chapter's tables and claim checks, on hand-made benchmark rows."""
import math

from trackbook.evaluation import compare


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


def test_claims_hold_or_not_from_the_numbers():
    c = {r["paper"].split(",")[0]: r for r in compare.check_claims(ROWS, clips={"a", "b"})}
    assert c["Lee et al. 2012"]["holds"] == "yes"          # rates 0.6 < 0.7 < 0.925
    assert c["Lee 2015"]["holds"] == "yes"                 # same rate, fewer windows
    assert c["Kim"]["holds"] == "n/a"                      # those trackers did not run
    worse = [dict(r, tracking_rate=0.1) if r["tracker"] == "color-hog-ipca" else r for r in ROWS]
    c = {r["paper"].split(",")[0]: r for r in compare.check_claims(worse, clips={"a", "b"})}
    assert c["Lee et al. 2012"]["holds"] == "no"


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
