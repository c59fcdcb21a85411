"""``color-pf`` against the values Lee et al. (2012) print in section V.

Section V prints them for the proposed tracker; section VI compares it with this colour-only
filter [14, 20] without printing its settings, so for ``color-pf`` each is the book's reading
(the paper preset runs them). The expected numbers are copied from the paper, not from the
code: a changed default fails here unless the field says why the book departs from the paper.
"""
import numpy as np

from trackbook import trackers, viz

from ._paper import assert_fields_are

# Printed in section V of Lee et al. (2012) (the seed text has no page numbers, so the
# comments name the passage):
PRINTED = {
    "n_particles": 100,        # "N = 100", the sentence after the pseudocode
    "sigma_color": 0.4,        # "all sigma_color and sigma_hog ... 0.4", after eq. 12-13
    "size_noise": 2.5,         # gamma_width, gamma_height ~ U(-2.5, 2.5), after eq. 9
    "vx_noise": 6.5,           # gamma_xdot ~ U(-6.5, 6.5), after eq. 9
    "vy_noise": 2.5,           # gamma_ydot ~ U(-2.5, 2.5), after eq. 9
    "resampler": "multinomial",  # pseudocode: one r ~ U[0, 1] per particle, smallest c_i >= r
    "init": "frame",           # pseudocode, t = 0: particles spread uniformly over the image
}
NOT_IN_PAPER = {"min_size"}     # eq. 9 has no floor on w and h


def test_fields_are_the_printed_and_the_not_printed():
    assert_fields_are("color-pf", PRINTED, NOT_IN_PAPER)


def test_section_v_values_are_readings_for_the_baseline():
    from trackbook.quotes import fields
    assert {fields.state("color-pf", k)[0] for k in PRINTED} == {"reading"}
    rows = {line.split("|")[1].strip(): line.split("|")[2].strip()
            for line in viz.departures_table("color-pf").splitlines()[2:]}
    assert rows["sigma_color"] == "0.4 (a reading)" and rows["init"] == "frame (a reading)"


def test_paper_preset_builds_the_printed_method():
    p = trackers.create("color-pf", preset="paper").params
    for name, value in PRINTED.items():
        assert getattr(p, name) == value, name


def test_departures_table_lists_exactly_the_departures():
    table = viz.departures_table("color-pf")
    lines = table.splitlines()
    assert lines[0] == "| parameter | paper | book | why |"
    rows = {line.split("|")[1].strip() for line in lines[2:]}
    assert rows == {r["param"] for r in trackers.departures("color-pf")}
    assert {"sigma_color", "init", "min_size"} <= rows


def test_paper_preset_spreads_particles_over_the_frame():
    frame = np.zeros((120, 160, 3), np.uint8)
    t = trackers.create("color-pf", preset="paper", seed=0)
    t.init(frame, (70, 50, 20, 20))
    xy = np.asarray(t.particles)[:, :2]
    # uniform over the frame: far wider than the quarter box of the book's start
    assert xy[:, 0].max() - xy[:, 0].min() > 80
    b = trackers.create("color-pf", seed=0)
    b.init(frame, (70, 50, 20, 20))
    assert np.ptp(np.asarray(b.particles)[:, 0]) <= 10 + 1e-9
