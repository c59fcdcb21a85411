"""How a quoted passage's TeX reaches the page (``trackbook.sphinx_quotes._typeset``).

The register keeps each passage verbatim, and a passage may be cut inside an equation. On the
page its maths is typeset by MathJax where it is whole TeX; a cut display equation gets its
missing ``$$`` on the cut side; TeX that cannot be typeset as it stands is shown as source code
(None here), never as raw TeX in the text. The browser test checks the built pages themselves.
"""

from __future__ import annotations

import pytest

pytest.importorskip("sphinx")
from trackbook import quotes  # noqa: E402
from trackbook.sphinx_quotes import _balanced, _typeset  # noqa: E402


@pytest.mark.parametrize("text, expected", [
    ("no maths at all", "no maths at all"),
    ("with $\\alpha = 0.1$ inline", "with $\\alpha = 0.1$ inline"),
    ("$$F = \\begin{bmatrix} 1 \\end{bmatrix},", "$$F = \\begin{bmatrix} 1 \\end{bmatrix},$$"),
    ("R = \\begin{bmatrix} 1 \\end{bmatrix}$$", "$$R = \\begin{bmatrix} 1 \\end{bmatrix}$$"),
    ("\\exp(x)$$ $$y = 1$$", "$$\\exp(x)$$ $$y = 1$$"),
    ("g(x)}{\\sum_i w_i} (12)$$", None),                      # cut inside \frac: braces
    ("$$s_t = A s$$ where \\mathbf{w} is noise", None),       # a command outside maths
    ("a price of $5", None),                                   # a lone dollar
])
def test_typeset(text, expected):
    assert _typeset(text) == expected


def test_balanced_braces():
    assert _balanced("\\frac{a}{b}") and _balanced("\\{ x \\}")
    assert not _balanced("a}{b") and not _balanced("{a")


def test_every_registered_passage_is_typeset_or_shown_as_code():
    for paper in ("lee2012", "kim2016", "lee2015", "cho2005"):
        for q in quotes.for_paper(paper):
            tex = _typeset(q.original)
            if tex is not None:
                assert tex.count("$$") % 2 == 0, q.key
                assert tex.replace("$$", "").count("$") % 2 == 0, q.key
