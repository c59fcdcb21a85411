"""Markdown tables the chapters display (generated, so they cannot drift from the code)."""

from __future__ import annotations

import re

from .._markdown import table


def departures_table(name, params=None) -> str:
    """The book's departures from the paper for tracker ``name``, as a Markdown table.

    Columns parameter | paper | book | why, one row per field whose default is the book's choice
    (``trackers.departures(name)``): the printed value (or "not printed"), the book's default
    and one line on why (without the quote references it carries in the source). A printed value that is the
    book's reading of an ambiguous passage (``trackbook.quotes.fields``) is marked "(a
    reading)", so that a reading never passes for a printed value. A chapter shows it with
    ``display(Markdown(viz.departures_table("color-pf")))``; ``params`` (a set of field
    names) keeps only those rows.
    """
    from .. import trackers
    from ..quotes import TEXT_REFERENCE
    from ..quotes.fields import state

    rows = [{**r, "paper": f"{r['paper']} (a reading)"}
            if state(name, r["param"])[0] == "reading" else r
            for r in trackers.departures(name) if params is None or r["param"] in params]
    # the quote references of a why are for the source's reader; the chapter beside the table
    # shows the passages themselves
    drop = re.compile(r"\s*" + TEXT_REFERENCE.pattern)
    rows = [{**r, "why": drop.sub("", str(r["why"]))} for r in rows]
    lines = [table(rows, ["param", "paper", "book", "why"], labels={"param": "parameter"})]
    if not rows:
        lines.append(f"| – | – | – | every default of `{name}` is the printed value |")
    return "\n".join(lines)
