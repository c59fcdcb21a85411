"""show_frame and draw_box draw every box they are given, or raise."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

from trackbook import viz  # noqa: E402
from trackbook.style import CYCLE, GT_COLOR  # noqa: E402

FRAME = np.zeros((60, 80, 3), np.uint8)


def _rects(ax):
    # (x, y, w, h) of every rectangle drawn, back in box coordinates (draw_box shifts by 0.5)
    return [(p.get_x() + 0.5, p.get_y() + 0.5, p.get_width(), p.get_height())
            for p in ax.patches if isinstance(p, Rectangle)]


@pytest.fixture
def ax():
    fig, ax = plt.subplots()
    yield ax
    plt.close(fig)


@pytest.mark.parametrize("boxes", [[(10, 5, 20, 30)], np.array([[10, 5, 20, 30]]),
                                   (10, 5, 20, 30), {"best": (10, 5, 20, 30)}])
def test_one_box_in_any_form_is_drawn(ax, boxes):
    viz.show_frame(FRAME, ax=ax, boxes=boxes)
    assert _rects(ax) == [(10, 5, 20, 30)]
    assert matplotlib.colors.same_color(ax.patches[0].get_edgecolor(), CYCLE[0])


def test_a_list_of_boxes_draws_each_with_gt(ax):
    boxes = [(1, 2, 3, 4), (5, 6, 7, 8), (9, 10, 11, 12)]
    viz.show_frame(FRAME, ax=ax, boxes=boxes, gt=(20, 20, 10, 10))
    assert _rects(ax) == [(20, 20, 10, 10)] + boxes
    assert matplotlib.colors.same_color(ax.patches[0].get_edgecolor(), GT_COLOR)
    for patch, colour in zip(ax.patches[1:], CYCLE):
        assert matplotlib.colors.same_color(patch.get_edgecolor(), colour)


def test_lost_box_draws_nothing(ax):
    viz.draw_box(ax, (np.nan, 1, 2, 3))
    viz.draw_box(ax, None)
    assert _rects(ax) == []


@pytest.mark.parametrize("bad", [(1, 2, 3), np.zeros((2, 4)), np.zeros(8)])
def test_draw_box_raises_on_what_it_cannot_draw(ax, bad):
    with pytest.raises(ValueError, match="one box"):
        viz.draw_box(ax, bad)


@pytest.mark.parametrize("bad", [np.zeros((2, 3)), np.zeros((1, 2, 4))])
def test_show_frame_raises_on_malformed_boxes(ax, bad):
    with pytest.raises(ValueError, match="boxes must be"):
        viz.show_frame(FRAME, ax=ax, boxes=bad)


def _paper_column(name):
    lines = viz.departures_table(name).splitlines()[2:]
    return {line.split("|")[1].strip(): line.split("|")[2].strip() for line in lines}


@pytest.mark.parametrize("name", ["color-pf", "color-hog-ipca", "kalman-covariance"])
def test_departures_table_marks_readings_and_only_readings(name):
    from trackbook import trackers
    from .test_param_provenance import FIELDS   # the table the declarations replaced

    paper = _paper_column(name)
    for row in trackers.departures(name):
        state = FIELDS.get(name, {}).get(row["param"], (None, None))[1]
        shown = paper[row["param"]]
        assert shown.endswith("(a reading)") == (state == "reading"), (row["param"], shown)
        assert shown.startswith(str(row["paper"])), (row["param"], shown)


def test_anchor_of_lee2012_is_shown_as_a_reading():
    # eq. 12-13 print no anchor term; 0.0 is the book's reading of the garbled print
    assert _paper_column("color-hog-ipca")["anchor"] == "0.0 (a reading)"
