"""The book's table of contents and the notebook export for class use."""
import os
import re
from pathlib import Path

import pytest

from trackbook import cli

from . import _toc

ROOT = Path(__file__).resolve().parents[1]
FIXED_CHAPTERS = ["00_introduction", "01_kernel_histograms", "02_particle_filters",
                  "03_hog", "04_incremental_svd", "05_edge_rays", "06_kalman",
                  "07_region_covariance", "08_mean_shift", "09_trackers_compared",
                  "10_correlation_filters", "11_knowing_you_are_lost",
                  "12_template_matching_and_optical_flow", "13_camshift",
                  "14_tracking_by_detection", "15_background_subtraction",
                  "16_several_targets", "17_kalman_filter_design",
                  "18_sigma_points_and_proposals", "19_evaluation_protocols",
                  "20_correlation_filters_ii", "21_bayes_filter"]


def _toc_files():
    return _toc.files()


def test_toc_lists_existing_chapters_only_and_every_chapter():
    listed = _toc_files()
    for f in listed:
        assert (ROOT / f"{f}.md").is_file(), f"_toc.yml lists {f} but it does not exist"
    pages = {f"book/{p.stem}" for p in (ROOT / "book").glob("*.md")}
    assert pages == set(listed), f"pages not in the toc: {pages - set(listed)}"


def test_chapter_names_are_the_fixed_ones():
    for p in (ROOT / "book").glob("[0-9][0-9]_*.md"):
        stem = p.stem
        assert any(stem == c or stem.startswith(c + "_") for c in FIXED_CHAPTERS), stem


def test_chapters_import_only_trackbook_and_commit_no_outputs():
    for p in (ROOT / "book").glob("*.md"):
        text = p.read_text()
        assert "sys.path" not in text, f"{p.name} manipulates sys.path"
        assert "outputs:" not in text
    assert not list((ROOT / "book").glob("*.ipynb")), "executed notebooks must not be committed"


def test_ci_runs_the_readme_commands():
    readme = (ROOT / "README.md").read_text()
    ci = (ROOT / ".ci" / "run").read_text()
    assert "<!-- ci:test -->" in readme and "<!-- ci:book -->" in readme
    assert "readme_cmd test" in ci and "readme_cmd book" in ci


def _pages():
    return [f.split("/")[-1] for f in _toc_files()]


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    """All chapters exported with the documented command, as a teacher would."""
    out = tmp_path_factory.mktemp("nb") / "notebooks"
    assert cli.main(["notebooks", "--book", str(ROOT / "book"), "--out", str(out)]) == 0
    return out


def test_export_writes_every_page(exported):
    assert sorted(p.stem for p in exported.glob("*.ipynb")) == sorted(_pages())


#: The exported pages run by default: one that reads committed results and has a playground,
#: one that loads a user's tracker, one with the new canon. The book build executes every page
#: (from book/); an exported notebook differs only in its folder, and nothing a page reads
#: depends on it (committed results are package data). TRACKBOOK_EXPORT_ALL=1 runs them all.
EXPORTED_BY_DEFAULT = ("02_particle_filters", "appendix_own_tracker", "10_correlation_filters")


def _exported_pages():
    if os.environ.get("TRACKBOOK_EXPORT_ALL") == "1":
        return _pages()
    return [p for p in _pages() if p in EXPORTED_BY_DEFAULT]


@pytest.mark.slow
@pytest.mark.parametrize("page", _exported_pages())
def test_exported_notebook_runs(exported, page):
    """Each exported notebook runs end to end in a plain kernel from its own folder."""
    jupytext = pytest.importorskip("jupytext")
    nbclient = pytest.importorskip("nbclient")
    nb = jupytext.read(exported / f"{page}.ipynb")
    nbclient.NotebookClient(nb, timeout=900, kernel_name="python3",
                            resources={"metadata": {"path": str(exported)}}).execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
              if o.get("output_type") == "error"]
    assert not errors


#: A code cell of a page, its MyST options and its source.
_CELL = re.compile(r"```\{code-cell\}[^\n]*\n(.*?)^```", re.S | re.M)
#: The width of the book's column in monospace characters (PEP 8's 79).
CODE_COLUMNS = 79


def _long_visible_code_lines(text: str) -> list[tuple[int, int]]:
    """``(line, length)`` of each line over CODE_COLUMNS in a code cell a reader can see (not
    tagged ``remove-cell`` or ``remove-input``)."""
    out = []
    for m in _CELL.finditer(text):
        tags = re.search(r"^:tags:\s*\[(.*?)\]", m.group(1), re.M)
        if tags and re.search(r"remove-(?:cell|input)", tags.group(1)):
            continue
        first = text.count("\n", 0, m.start(1)) + 1
        out += [(first + i, len(line)) for i, line in enumerate(m.group(1).split("\n"))
                if len(line) > CODE_COLUMNS]
    return out


def test_the_column_rule_sees_what_a_reader_sees():
    long = "x = " + "1" * 80
    page = (f"```{{code-cell}} ipython3\n{long}\n```\n\n"
            f"```{{code-cell}} ipython3\n:tags: [remove-cell]\n{long}\n```\n\n"
            f"```{{code-cell}} ipython3\n:tags: [hide-input]\n{long}\n```\n")
    assert _long_visible_code_lines(page) == [(2, 84), (12, 84)]


@pytest.mark.parametrize("page", sorted(p.name for p in (ROOT / "book").glob("*.md")))
def test_visible_code_fits_the_column(page):
    """Code a reader sees (open or behind "Show code") fits the book's column: no line over
    79 characters, so nothing scrolls sideways at 1280 px."""
    found = _long_visible_code_lines((ROOT / "book" / page).read_text(encoding="utf-8"))
    assert not found, f"code lines over {CODE_COLUMNS} characters (line, length): {found}"
