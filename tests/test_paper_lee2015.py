"""``covariance`` and ``kalman-covariance`` against what Lee (2015) prints.

The expected values are copied from the paper (J. KIICE 19(6), 2015), not from the code: a
changed default fails here unless the field says why the book departs from the paper. The text
has no page numbers, so each comment names the section and passage.
"""
import numpy as np
import pytest

from trackbook import trackers
from trackbook.params import is_departure

from ._paper import assert_fields_are, fields

PRINTED = {
    "kalman-covariance": {
        "q": 1.0,              # sec. 2.2: Q = I (4 x 4) printed
        "r": 1.0,              # sec. 2.2: R = I (2 x 2) printed
        "init_size": 24,       # sec. 3, after Table 1: "moving in a 24x24 area"
        "features": "xyIIxIy",  # sec. 2.1, eq. 2: [x y I Ix ...], signed gradients
    },
    "covariance": {
        "fallback": "frame",   # sec. 3, Fig. 3, frame 160: the whole area is searched
        "features": "xyIIxIy",  # sec. 2.1, eq. 2
    },
}
NOT_IN_PAPER = {
    "covariance": {"stride", "search_radius", "threshold", "global_stride", "eps",
                   "model_update"},
    "kalman-covariance": {"stride", "search_radius", "threshold", "eps", "model_update", "p0",
                          "gate", "min_radius", "motion_threshold"},
}


@pytest.mark.parametrize("name", sorted(PRINTED))
def test_printed_values_are_recorded(name):
    assert_fields_are(name, PRINTED[name], NOT_IN_PAPER[name])


@pytest.mark.parametrize("name", sorted(PRINTED))
def test_paper_preset_is_the_printed_method(name):
    t = trackers.create(name, preset="paper")
    for key, value in PRINTED[name].items():
        assert getattr(t.params, key) == value, key


def test_paper_preset_has_no_book_additions():
    p = trackers.create("kalman-covariance", preset="paper").params
    assert p.model_update == 0.0          # the model is never updated
    # the manoeuvre re-search and a whole-frame search are not part of the name at all
    for key in ("manoeuvre_gate", "manoeuvre_sigma", "fallback", "global_stride"):
        assert not hasattr(p, key), key
    m = trackers.create("kalman-covariance-manoeuvre", preset="paper").params
    assert m.manoeuvre_gate == 0.0        # the variant's paper preset switches it off


def test_book_departures_are_listed_with_a_why():
    rows = {r["param"]: r for r in trackers.departures("kalman-covariance")}
    for key in ("threshold", "gate", "features"):
        assert key in rows and rows[key]["why"].strip(), key
    assert "q" not in rows and "r" not in rows     # Q = I, R = I as printed
    assert not is_departure(fields("kalman-covariance")["init_size"])
    rows = {r["param"]: r for r in trackers.departures("kalman-covariance-manoeuvre")}
    assert rows["manoeuvre_gate"]["why"].strip()


@pytest.mark.parametrize("preset", ["book", "paper"])
def test_kalman_covariance_never_searches_the_whole_frame(preset):
    # A target that vanishes: the paper's proposed tracker searches again only inside its
    # Kalman window [quote: lee2015.research_in_window]; the baseline searches the whole frame
    # [quote: lee2015.whole_frame_search].
    frame = np.full((120, 160, 3), 90, np.uint8)
    frame[40:64, 60:84] = (40, 60, 200)
    frame[45:50, 65:70] = 250
    empty = np.full_like(frame, 90)
    empty[::7] = 30
    counts = {}
    for name in ("kalman-covariance", "covariance"):
        t = trackers.create(name, preset=preset)
        t.init(frame, (60, 40, 24, 24))
        ok, _ = t.update(empty)
        assert not ok                        # no window matches: d_F above the threshold
        counts[name] = t.frame_report()["candidates"]
    t = trackers.create("kalman-covariance", preset=preset)
    t.init(frame, (60, 40, 24, 24))
    t.update(empty)
    sw = t.search_window
    # every candidate's centre lies in the Kalman window: at most its (2r + 1)^2 centres
    assert counts["kalman-covariance"] <= (sw[2] - 24 + 1) * (sw[3] - 24 + 1)
    assert counts["kalman-covariance"] < counts["covariance"]
