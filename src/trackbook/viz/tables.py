"""Markdown tables the chapters display (generated, so they cannot drift from the code)."""

from __future__ import annotations

from .._markdown import table


def departures_table(name) -> str:
    """The book's departures from the paper for tracker ``name``, as a Markdown table.

    Columns param | paper | book | why, one row per field whose default is the book's choice
    (``trackers.departures(name)``): the value the paper prints (or "not printed"), the book's
    default and one line on why. A paper value that is the book's reading of an ambiguous
    passage (``trackbook.quotes.fields``) is marked "(a reading)", so that it is never shown as
    printed. A chapter shows it with ``display(Markdown(viz.departures_table("color-pf")))``.
    """
    from .. import trackers
    from ..quotes.fields import FIELDS

    backed = FIELDS.get(name, {})
    rows = [{**r, "paper": f"{r['paper']} (a reading)"}
            if backed.get(r["param"], (None, None))[1] == "reading" else r
            for r in trackers.departures(name)]
    lines = [table(rows, ["param", "paper", "book", "why"])]
    if not rows:
        lines.append(f"| – | – | – | every default of `{name}` is the printed value |")
    return "\n".join(lines)
