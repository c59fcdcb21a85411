"""Markdown tables the chapters display (generated, so they cannot drift from the code)."""

from __future__ import annotations


def _cell(value) -> str:
    """One table cell: text with the pipe escaped, so a value cannot break the table."""
    return str(value).replace("|", "\\|").replace("\n", " ")


def departures_table(name) -> str:
    """The book's departures from the paper for tracker ``name``, as a Markdown table.

    Columns param | paper | book | why, one row per field whose default is the book's choice
    (``trackers.departures(name)``): the value the paper prints (or "not printed"), the book's
    default and one line on why. A chapter shows it with
    ``display(Markdown(viz.departures_table("color-pf")))``.
    """
    from .. import trackers

    rows = trackers.departures(name)
    lines = ["| param | paper | book | why |", "|---|---|---|---|"]
    for r in rows:
        lines.append("| " + " | ".join(_cell(r[k]) for k in ("param", "paper", "book", "why"))
                     + " |")
    if not rows:
        lines.append(f"| – | – | – | every default of `{name}` is the printed value |")
    return "\n".join(lines)
