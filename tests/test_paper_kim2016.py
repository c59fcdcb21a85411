"""``edge-ray-pf`` (and its two comparison filters) against what Kim, Kim & Choi (2016) print.

The expected numbers are copied from the paper, not from the code: a changed default fails here
unless the field says why the book departs from the paper. The seed text has no page numbers,
so each comment names the section and passage.
"""
import numpy as np

from trackbook import trackers, viz
from trackbook.features import edge_rays as er

from ._paper import assert_fields_are

PRINTED = {
    # section 3, before eq. 2: "at most 999 particles were used" (최대 999개), a maximum the
    # paper preset reads as the setting: a reading, not a printed setting
    "n_particles": 999,
    "ratio_low": 0.8,     # section 3.2, after eq. 5: "the range of Ratio is 0.8-1.2"
    "ratio_high": 1.2,    # same sentence
}
READINGS = {"n_particles"}
NOT_IN_PAPER = {"sigma", "velocity_gain", "resampler", "canny_low",
                "canny_high", "blur", "max_ray", "adapt_scale", "model_rate"}


def test_eight_rays_at_45_degrees():
    # Section 2, eq. 1: theta_j = 45 j degrees, j = 0..7 (8 directions)
    assert len(er.DIRECTIONS) == 8
    np.testing.assert_allclose(er.THETAS, 45.0 * np.arange(8))


def test_ratio_window_constant_is_the_printed_one():
    assert er.RATIO_WINDOW == (PRINTED["ratio_low"], PRINTED["ratio_high"])


def test_fields_are_the_printed_and_the_not_printed():
    assert_fields_are("edge-ray-pf", PRINTED, NOT_IN_PAPER)
    from trackbook.quotes import fields
    for name in PRINTED:
        assert fields.state("edge-ray-pf", name)[0] == (
            "reading" if name in READINGS else "printed"), name
    # the two filters it compares with: the paper names them and prints none of their settings
    # (its at most 999 particles are the proposed filter's: the paper preset gives them 999 as a
    # reading)
    shared = {"sigma", "velocity_gain", "resampler"}
    for name in ("hsi-color-pf", "hog-pf"):
        assert_fields_are(name, {}, shared | {"n_particles", "obs_sigma"})
        assert trackers.create(name, preset="paper").params.n_particles == 999


def test_velocity_gain_paper_reading_is_one():
    # Section 3, prediction step: particles move by the object's displacement (no factor).
    assert trackers.create("edge-ray-pf", preset="paper").params.velocity_gain == 1.0
    assert trackers.create("edge-ray-pf").params.velocity_gain == 1.0


def test_paper_preset_builds_the_printed_method():
    p = trackers.create("edge-ray-pf", preset="paper").params
    for name, value in PRINTED.items():
        assert getattr(p, name) == value, name
    assert (p.max_ray, p.adapt_scale, p.model_rate, p.blur) == (0.0, False, 0.0, 0)


def test_departures_table_lists_exactly_the_departures():
    table = viz.departures_table("edge-ray-pf")
    rows = {line.split("|")[1].strip() for line in table.splitlines()[2:]}
    assert rows == {r["param"] for r in trackers.departures("edge-ray-pf")}
    assert {"n_particles", "canny_low", "sigma"} <= rows
    assert "ratio_low" not in rows
