"""The one Markdown table renderer of the library (chapters, lab notes, benchmark reports).

Dependency-free, so every layer may use it. A cell is escaped (``|`` and line breaks), so no
value can break its table; a missing or non-finite number shows as an en dash.
"""

from __future__ import annotations

import math
import re
from numbers import Integral, Real

MISSING = "\u2013"


def cell(value, spec=None, missing: str = MISSING) -> str:
    """One table cell.

    Parameters
    ----------
    value : any
        ``None`` and non-finite numbers give ``missing``.
    spec : str or callable, optional
        A format spec (``".3f"``, ``".1%"``) applied with :func:`format` where it fits the
        value (else ``str(value)``), or a function ``value -> str``.
    missing : str
        What an absent value shows.
    """
    if value is None or (isinstance(value, Real) and not isinstance(value, bool)
                         and not math.isfinite(float(value))):
        return missing
    if callable(spec):
        text = spec(value)
    elif spec:
        try:
            text = format(value, spec)
        except (TypeError, ValueError):
            text = str(value)
    else:
        text = str(value)
    # a backslash escapes the next character in a table row (GFM), so the backslashes right
    # before a pipe are doubled (they stay text) and the pipe escaped (it stays text too)
    return re.sub(r"(\\*)\|", lambda m: 2 * m.group(1) + "\\|", str(text).replace("\n", " "))


def table(rows, columns=None, *, formats=None, labels=None, number=None, align=None,
          missing: str = MISSING) -> str:
    """Rows as a Markdown table (the book has no pandas).

    Parameters
    ----------
    rows : list of dict
        One dict per row; a key a row lacks is an empty cell.
    columns : list of str, optional
        Which keys, in order (default: every key, in the order first seen).
    formats : dict, optional
        Column -> format spec or function (see :func:`cell`).
    labels : dict, optional
        Column -> header text (short headers keep a table inside the page's column).
    number : str or callable, optional
        Format of the non-integer numbers of columns without an entry in ``formats``.
    align : dict, optional
        Column -> ``"left"`` or ``"right"`` (default: the renderer's own).
    missing : str
        What ``None`` and non-finite numbers show.

    Returns
    -------
    str
        Header, separator and one line per row, newline-separated (no trailing newline).
    """
    rows = list(rows)
    if columns is None:
        columns = list(dict.fromkeys(k for r in rows for k in r))
    formats, labels, align = formats or {}, labels or {}, align or {}

    def spec(c, v):
        if c in formats:
            return formats[c]
        return number if isinstance(v, Real) and not isinstance(v, Integral) else None

    sep = {"left": ":---", "right": "---:"}
    lines = ["| " + " | ".join(cell(labels.get(c, c)) for c in columns) + " |",
             "|" + "|".join(sep.get(align.get(c), "---") for c in columns) + "|"]
    for r in rows:
        lines.append("| " + " | ".join(
            cell(r[c], spec(c, r[c]), missing) if c in r else "" for c in columns) + " |")
    return "\n".join(lines)
