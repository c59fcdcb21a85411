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
        "fallback": "window",  # sec. 2.3: if it does not converge, search again in the Kalman window
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
    "kalman-covariance": {"stride", "search_radius", "threshold", "global_stride", "eps",
                          "model_update", "p0", "gate", "min_radius", "manoeuvre_gate",
                          "manoeuvre_sigma", "motion_threshold"},
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
    assert p.manoeuvre_gate == 0.0        # the manoeuvre re-search is off
    assert p.model_update == 0.0          # the model is never updated
    assert p.fallback == "window"         # never the whole frame


def test_book_departures_are_listed_with_a_why():
    rows = {r["param"]: r for r in trackers.departures("kalman-covariance")}
    for key in ("threshold", "gate", "fallback", "features", "manoeuvre_gate"):
        assert key in rows and rows[key]["why"].strip(), key
    assert "q" not in rows and "r" not in rows     # Q = I, R = I as printed
    assert not is_departure(fields("kalman-covariance")["init_size"])


def test_kalman_paper_preset_never_searches_the_whole_frame():
    # A target that vanishes: the book's tracker searches the whole frame, the paper's only
    # searches again inside its Kalman window, so it evaluates far fewer windows.
    frame = np.full((120, 160, 3), 90, np.uint8)
    frame[40:64, 60:84] = (40, 60, 200)
    frame[45:50, 65:70] = 250
    empty = np.full_like(frame, 90)
    empty[::7] = 30
    counts = {}
    for preset in ("book", "paper"):
        t = trackers.create("kalman-covariance", preset=preset)
        t.init(frame, (60, 40, 24, 24))
        t.update(empty)
        counts[preset] = t.frame_report()["candidates"]
        area = t.search_window[2] * t.search_window[3]
        assert counts[preset] >= 1 and area < frame.shape[0] * frame.shape[1]
    assert counts["paper"] < counts["book"]
