"""The book's figure check (``book/_ext/figure_check.py``) on figures made to break it.

Every page runs with the check installed (``book/_ext/execute_pages.py``); here it must flag a
tracker drawn in another tracker's colour and a legend over data, and let the right ones
pass. The palette itself: one colour per registered tracker, none shared, none the ground
truth's.
"""

from __future__ import annotations


import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Patch, Rectangle  # noqa: E402

from trackbook import trackers  # noqa: E402
from trackbook.style import GT_COLOR, TRACKER_COLORS, tracker_color  # noqa: E402

import figure_check  # noqa: E402  (book/_ext, put on the path by tests/conftest.py)


@pytest.fixture
def ax():
    fig, ax = plt.subplots(figsize=(4, 3))
    yield ax
    plt.close(fig)


def test_every_registered_tracker_has_its_own_colour():
    # the library's own trackers; a plugin another test loaded (experiments/*.py, a student's
    # file) registers from its own module and draws in the colour its caller gives
    names = [n for n in trackers.available()
             if trackers.get(n).__module__.startswith("trackbook.")]
    bases = {n[: -len("-redetect")] if n.endswith("-redetect") else n for n in names}
    assert bases <= set(TRACKER_COLORS), bases - set(TRACKER_COLORS)
    colours = [c.lower() for c in TRACKER_COLORS.values()]
    assert len(set(colours)) == len(colours), "two trackers share a colour"
    assert GT_COLOR.lower() not in colours
    assert tracker_color("kcf-redetect") == tracker_color("kcf")
    assert tracker_color("my-tracker") is None and tracker_color("my-tracker", "#123456") == "#123456"


def test_a_tracker_in_another_colour_is_flagged(ax):
    ax.plot([0, 1], [0, 1], color=tracker_color("mosse"), label="kcf")
    (p,) = figure_check.problems(ax.figure)
    assert "'kcf'" in p and tracker_color("kcf") in p


@pytest.mark.parametrize("label", ["kcf", "kcf-redetect", "kcf (paper)", "kcf, AUC 0.58"])
def test_a_tracker_in_its_colour_passes(ax, label):
    ax.plot([0, 1], [0, 1], color=tracker_color("kcf"), label=label)
    ax.add_patch(Rectangle((0.2, 0.2), 0.1, 0.1, fill=False, edgecolor=tracker_color("dsst"),
                           label="dsst"))
    assert figure_check.problems(ax.figure) == []


def test_boxes_markers_and_legend_proxies_are_checked(ax):
    ax.add_patch(Rectangle((0.2, 0.2), 0.1, 0.1, fill=False, edgecolor="#000000", label="bacf"))
    ax.scatter([0.5], [0.5], color="#000000", label="staple")
    ax.legend(handles=[Patch(color="#000000", label="mosse")], loc="lower right")
    found = figure_check.problems(ax.figure)
    assert len(found) == 3 and all(any(n in p for p in found) for n in ("bacf", "staple", "mosse"))


def test_labels_that_are_not_trackers_are_free(ax):
    ax.plot([0, 1], [0, 1], color="#000000", label="ground truth")
    ax.plot([0, 1], [1, 0], color="#000000", label="my-tracker")
    ax.plot([0, 1], [1, 1], color="#000000", label="_hidden")
    assert figure_check.problems(ax.figure) == []


def test_a_legend_over_data_is_flagged_and_one_beside_it_passes(ax):
    x = np.linspace(0, 1, 50)
    ax.plot(x, np.full_like(x, 0.95), color="#000000", label="a curve along the top")
    ax.set_ylim(0, 1)
    ax.legend(loc="upper center")
    (p,) = figure_check.problems(ax.figure)
    assert "legend covers" in p
    ax.legend(loc="lower center")
    assert figure_check.problems(ax.figure) == []


def test_a_point_clipped_outside_the_axes_is_not_under_a_legend_outside_them(ax):
    ax.plot([0, 3], [0, 1], color="#000000", label="runs past the right edge")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.2)
    ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.75))
    assert figure_check.problems(ax.figure) == []


def test_a_scatter_under_the_legend_is_flagged(ax):
    ax.scatter([0.5], [0.5], color="#000000", label="points")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.legend(loc="center")
    assert any("legend covers 1" in p for p in figure_check.problems(ax.figure))


def test_a_description_says_what_each_panel_shows():
    fig, (a, b) = plt.subplots(1, 2)
    a.plot([0, 1], [0, 1], color=tracker_color("kcf"), label="kcf")
    a.plot([0, 1], [1, 0], color=tracker_color("dsst"), label="dsst")
    a.set(title="Success plot", xlabel="overlap threshold", ylabel="success rate")
    a.legend(loc="center left", bbox_to_anchor=(1, 0.5))
    b.imshow(np.zeros((4, 4)))
    b.set_title("frame $t$")
    fig.suptitle("two trackers")
    text = figure_check.describe(fig)
    plt.close(fig)
    assert text == ("two trackers. 2 panels. Success plot: success rate against overlap "
                    "threshold; showing kcf, dsst | frame t: an image")


def test_the_alt_text_goes_to_the_image_of_its_figure(tmp_path):
    """figure_alt.py puts the description written under the PNG's hash on the image MyST-NB
    names by that hash, and leaves an image that has its own alt text alone."""
    from docutils import nodes
    import figure_alt

    (tmp_path / "ab12.txt").write_text("success rate against overlap threshold\n")
    doc = nodes.document(None, None)
    doc += nodes.image(uri="../_images/ab12.png")
    doc += nodes.image(uri="../_images/cd34.png", alt="a photo")
    doc += nodes.image(uri="../_images/ef56.png")
    old, figure_alt.ALTS = figure_alt.ALTS, tmp_path
    try:
        figure_alt.set_alt_texts(None, doc, "page")
    finally:
        figure_alt.ALTS = old
    alts = [i.get("alt") for i in doc.findall(nodes.image)]
    assert alts == ["success rate against overlap threshold", "a photo", None]


def test_a_page_with_a_bad_figure_fails_to_execute(tmp_path, monkeypatch):
    """End to end, as the book runs a page: the kernel's startup installs the check, the cell
    that shows the figure fails with the problem, the others run."""
    nbclient = pytest.importorskip("nbclient")
    nbformat = pytest.importorskip("nbformat")
    monkeypatch.setenv("IPYTHONDIR", str(figure_check.ipython_dir(tmp_path)))
    monkeypatch.setenv(figure_check.ALTS_ENV, str(tmp_path / "alts"))
    nb = nbformat.v4.new_notebook(cells=[
        nbformat.v4.new_code_cell(
            "import matplotlib.pyplot as plt\n"
            "fig, ax = plt.subplots()\n"
            "ax.plot([0, 1], [0, 1], label='a line')\n"
            "ax.set(xlabel='x', ylabel='y')"),
        nbformat.v4.new_code_cell(
            "import matplotlib.pyplot as plt\n"
            "fig, ax = plt.subplots()\n"
            "ax.plot([0, 1], [0, 1], color='#000000', label='kcf')\n"
            "plt.show()"),
        nbformat.v4.new_code_cell("print('ran')"),
    ])
    nbclient.NotebookClient(nb, timeout=120, kernel_name="python3",
                            allow_errors=True).execute()
    # the good figure: shown, its description written under its PNG's hash
    import base64
    import hashlib
    png = [o for o in nb.cells[0].outputs if "image/png" in o.get("data", {})][0]
    sha = hashlib.sha256(base64.b64decode(png.data["image/png"])).hexdigest()
    assert (tmp_path / "alts" / f"{sha}.txt").read_text() == "y against x; showing a line"
    errors = [o for o in nb.cells[1].outputs if o.output_type == "error"]
    assert len(errors) == 1 and errors[0].ename == "FigureCheckError"
    assert "'kcf' is drawn in #000000" in errors[0].evalue
    assert nb.cells[2].outputs[0].text == "ran\n"
    with pytest.raises(nbclient.exceptions.CellExecutionError, match="FigureCheckError"):
        nbclient.NotebookClient(nb, timeout=120, kernel_name="python3").execute()


def test_a_check_that_cannot_run_fails_the_cell_and_still_shows_the_figure(tmp_path, monkeypatch):
    """An error inside the check must not be swallowed by IPython's display formatter (which
    prints it, drops the figure and lets the cell pass): the cell fails, naming it."""
    nbclient = pytest.importorskip("nbclient")
    nbformat = pytest.importorskip("nbformat")
    monkeypatch.setenv("IPYTHONDIR", str(figure_check.ipython_dir(tmp_path)))
    nb = nbformat.v4.new_notebook(cells=[
        nbformat.v4.new_code_cell(
            "import figure_check\n"
            "def broken(fig):\n"
            "    raise RuntimeError('boom')\n"
            "figure_check.problems = broken\n"
            "import matplotlib.pyplot as plt\n"
            "fig, ax = plt.subplots()\n"
            "ax.plot([0, 1], [0, 1])\n"
            "plt.show()"),
    ])
    nbclient.NotebookClient(nb, timeout=120, kernel_name="python3",
                            allow_errors=True).execute()
    outputs = nb.cells[0].outputs
    errors = [o for o in outputs if o.output_type == "error"]
    assert len(errors) == 1 and errors[0].ename == "FigureCheckError", outputs
    assert "RuntimeError: boom" in errors[0].evalue
    assert any("image/png" in o.get("data", {}) for o in outputs)


def test_a_series_that_is_no_tracker_never_takes_a_tracker_s_colour_of_its_plot():
    from trackbook.style import CYCLE, label_colors
    # CYCLE[0] is kcf's vermillion: a student's tracker listed first must not get it
    assert CYCLE[0].lower() == tracker_color("kcf").lower()
    mine, kcf, other = label_colors(["my-tracker", "kcf [0.5]", "another"])
    assert kcf == tracker_color("kcf")
    assert mine.lower() != kcf.lower() and other.lower() != kcf.lower() and mine != other
    assert label_colors(["a", "b"]) == CYCLE[:2]            # no tracker: the cycle as it is
