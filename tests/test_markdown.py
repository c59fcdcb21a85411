"""The one Markdown table renderer: hand-worked tables, and no value can break a table."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from trackbook._markdown import cell, table


def test_a_hand_worked_table():
    rows = [{"name": "a|b", "auc": 0.51234, "n": 3, "ok": None},
            {"name": "c", "auc": float("inf"), "n": 4}]
    assert table(rows, formats={"n": "03d"}, number=".2f", labels={"auc": "AUC"},
                 align={"auc": "right", "name": "left"}) == (
        "| name | AUC | n | ok |\n"
        "|:---|---:|---|---|\n"
        "| a\\|b | 0.51 | 003 | \u2013 |\n"
        "| c | \u2013 | 004 |  |")


def test_cells():
    assert cell(0.25, ".1%") == "25.0%" and cell("x", ".3f") == "x"
    assert cell(float("nan")) == "\u2013" and cell(True) == "True"
    assert cell("a\\|b") == "a\\\\\\|b" and separators("| " + cell("x\\|") + " |") == 2
    assert cell("two\nlines") == "two lines" and cell(7, lambda v: f"<{v}>") == "<7>"


@given(st.lists(st.dictionaries(st.sampled_from("abc"), st.one_of(
    st.text(), st.floats(allow_nan=True), st.integers(), st.none())), max_size=5))
def test_no_value_breaks_the_table(rows):
    cols = ["a", "b", "c"]
    lines = table(rows, cols, number=".3f").split("\n")
    assert len(lines) == 2 + len(rows)
    for line in lines:   # an unescaped pipe separates cells: one more than the columns
        assert separators(line) == len(cols) + 1, line


def separators(line: str) -> int:
    """Cell separators of a GFM table row, read as GFM does: a backslash escapes the next
    character."""
    n, i = 0, 0
    while i < len(line):
        if line[i] == "\\":
            i += 2
            continue
        n += line[i] == "|"
        i += 1
    return n
