"""How a quoted passage's TeX reaches the page (``book/_ext/sphinx_quotes.py``'s ``_typeset``).

The register keeps each passage verbatim, and a passage may be cut inside an equation. On the
page its maths is typeset by MathJax where it is whole TeX; a cut display equation gets its
missing ``$$`` on the cut side; TeX the seeds print outside any ``$`` (``\\dot{x}``, ``H_x``) is
put inside ``\\( \\)``. TeX that cannot be typeset as it stands gives None, and no registered
passage does: every popover typesets its maths. ``tests/test_sphinx_quotes.py`` opens a built
page in Chromium with the book's offline MathJax and checks the popover itself.
"""

from __future__ import annotations

import re

import pytest

pytest.importorskip("sphinx")
from trackbook import quotes  # noqa: E402
from sphinx_quotes import _balanced, _typeset  # noqa: E402


@pytest.mark.parametrize("text, expected", [
    ("no maths at all", "no maths at all"),
    ("with $\\alpha = 0.1$ inline", "with $\\alpha = 0.1$ inline"),
    ("$$F = \\begin{bmatrix} 1 \\end{bmatrix},", "$$F = \\begin{bmatrix} 1 \\end{bmatrix},$$"),
    ("R = \\begin{bmatrix} 1 \\end{bmatrix}$$", "$$R = \\begin{bmatrix} 1 \\end{bmatrix}$$"),
    ("\\exp(x)$$ $$y = 1$$", "$$\\exp(x)$$ $$y = 1$$"),
    ("g(x)}{\\sum_i w_i} (12)$$", None),                      # cut inside \frac: braces
    ("$$s_t = A s$$ where \\mathbf{w}_{t-1} is noise",          # a command outside maths
     "$$s_t = A s$$ where \\(\\mathbf{w}_{t-1}\\) is noise"),
    ("여기서 \\dot{x}, \\dot{y} 는 모션, H_x, H_y 는",                # as the seeds print them
     "여기서 \\(\\dot{x}\\), \\(\\dot{y}\\) 는 모션, \\(H_x\\), \\(H_y\\) 는"),
    ("후보 집합 S'_{t-1} 을", "후보 집합 \\(S'_{t-1}\\) 을"),
    ("mean_shift and a, x alone stay text", "mean_shift and a, x alone stay text"),
    ("a price of $5", None),                                   # a lone dollar
])
def test_typeset(text, expected):
    assert _typeset(text) == expected


def test_balanced_braces():
    assert _balanced("\\frac{a}{b}") and _balanced("\\{ x \\}")
    assert not _balanced("a}{b") and not _balanced("{a")


def test_every_registered_passage_is_typeset():
    # a passage MathJax cannot typeset would show its TeX as source in the popover: the
    # register copies whole equations instead of fragments
    for paper in ("lee2012", "kim2016", "lee2015", "cho2005"):
        for q in quotes.for_paper(paper):
            tex = _typeset(q.original)
            assert tex is not None, q.key
            assert tex.count("$$") % 2 == 0, q.key
            assert tex.replace("$$", "").count("$") % 2 == 0, q.key
            # no TeX command is left outside $ $, $$ $$ or \( \)
            text = re.sub(r"\$\$.*?\$\$|\$[^$]*\$|\\\(.*?\\\)", "", tex, flags=re.S)
            assert not re.search(r"\\[A-Za-z]|(?<!\w)[A-Za-z]'*[_^]", text), (q.key, text)
