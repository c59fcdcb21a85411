"""The register of quotes: every passage of the four papers the book and the library rely on.

Each :class:`Quote` holds the passage word for word (Korean, or the English abstract),
a faithful English translation, where it comes from (section, table, equation) and its kind:
``printed`` (the passage states it) or ``reading`` (the passage is ambiguous and supports the
book's reading). The book shows a quote beside the sentence that relies on it with the role
``{quote}`lee2012.window40``` (the book's Sphinx extension ``book/_ext/sphinx_quotes.py``); docstrings, comments and
param docs write ``[quote: lee2012.window40]``. ``tests/test_quotes.py`` checks every original
against the papers' texts.

Examples
--------
>>> from trackbook import quotes
>>> quotes.quote("lee2012.t40").translation
'T of the proposed algorithm is defined as 40.'
>>> len(quotes.for_paper("cho2005")) > 10
True
"""

from __future__ import annotations

import difflib
import re

from . import cho2005, kim2016, lee2012, lee2015
from ._quote import KINDS, PAPERS, Quote

__all__ = ["KINDS", "PAPERS", "QUOTES", "Quote", "ROLE", "TEXT_REFERENCE", "for_paper",
           "quote", "references"]


def _register(*modules) -> dict[str, Quote]:
    out: dict[str, Quote] = {}
    for module in modules:
        for q in module.QUOTES:
            if q.key in out:
                raise ValueError(f"quote key {q.key!r} is registered twice")
            if q.paper != module.__name__.rsplit(".", 1)[-1]:
                raise ValueError(f"quote {q.key!r} sits in the register of "
                                 f"{module.__name__}: move it to its paper's module")
            out[q.key] = q
    return out


#: Every quote, by key.
QUOTES: dict[str, Quote] = _register(lee2012, kim2016, lee2015, cho2005)

#: The plain-text reference in docstrings, comments and param docs: ``[quote: lee2012.t40]``.
TEXT_REFERENCE = re.compile(r"\[quote:\s*([A-Za-z0-9_.\-]+)\s*\]")
#: The book's role: ``{quote}`lee2012.t40```.
ROLE = re.compile(r"\{quote\}`([^`]*)`")


def quote(key: str) -> Quote:
    """The quote registered under ``key``.

    Raises
    ------
    ValueError
        When no quote has that key; the message names the key and the nearest keys.
    """
    if not isinstance(key, str):
        raise TypeError(f"a quote key is a string such as 'lee2012.t40', not "
                        f"{type(key).__name__}")
    key = key.strip()
    try:
        return QUOTES[key]
    except KeyError:
        near = difflib.get_close_matches(key, QUOTES, n=3, cutoff=0.5)
        hint = f"; did you mean {', '.join(near)}?" if near else ""
        raise ValueError(f"unknown quote key {key!r}{hint} (the register is "
                         f"trackbook.quotes: add the passage to its paper's module)") from None


def for_paper(paper: str) -> list[Quote]:
    """The quotes of one paper (``lee2012``, ``kim2016``, ``lee2015`` or ``cho2005``), in the
    order of the register."""
    if paper not in PAPERS:
        raise ValueError(f"unknown paper {paper!r}: the papers are {', '.join(PAPERS)}")
    return [q for q in QUOTES.values() if q.paper == paper]


def references(text: str) -> list[str]:
    """The quote keys a text cites, in order: the book's role and the plain-text form."""
    found = [(m.start(), m.group(1).strip()) for m in ROLE.finditer(text)]
    found += [(m.start(), m.group(1).strip()) for m in TEXT_REFERENCE.finditer(text)]
    return [k for _, k in sorted(found)]
