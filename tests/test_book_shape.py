"""The concept chapters' shape: a sitting each, organised by concept, the papers in their case
studies.

Measured as the book's specification defines it: *prose words* are words outside code cells,
fences and the front matter; *about a paper* is what stands under a heading that names a case
study or one of the four papers (down to the next heading of the same or a higher level); an
*evidence marker* is a ``{quote}`` role. Each concept chapter (``book/NN_*.md``) has at most
3,000 prose words and 30 code cells, at most 20 % of its prose about a paper, and no evidence
marker outside its case-study section. Where a chapter misses a bound today, the test says so
with what was measured (``OVER``, ``MARKERS``: strict expected failures, so the day it fits
the mark has to go).
"""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BOOK = ROOT / "book"
CHAPTERS = sorted(p.stem for p in BOOK.glob("[0-9][0-9]_*.md"))
MAX_WORDS, MAX_CELLS, MAX_PAPER_SHARE = 3000, 30, 0.20
#: Names a heading about one of the four papers carries.
PAPER_HEADING = re.compile(r"case stud|\b(?:Lee|Kim|Cho)\b", re.I)
_FENCE = re.compile(r"^(`{3,}|~{3,})[^\n]*\n.*?^\1\s*$", re.M | re.S)
_FRONT = re.compile(r"\A---\n.*?\n---\n", re.S)
_HEADING = re.compile(r"^(#{1,6}) (.*)$", re.M)

#: chapter -> what is over today (strict expected failures).
OVER: dict[str, str] = {}
#: chapter -> the evidence markers it still carries outside a section about a paper.
MARKERS: dict[str, str] = {}


def _known(table: dict, reason: str):
    return [pytest.param(s, marks=pytest.mark.xfail(strict=True, reason=f"{reason}: {table[s]}"))
            if s in table else s for s in CHAPTERS]


def measure(text: str) -> dict:
    """Prose words, code cells, words about a paper and evidence markers outside the
    sections about a paper, of one chapter's MyST source."""
    cells = len(re.findall(r"^```\{code-cell\}", text, re.M))
    prose = _FENCE.sub("", _FRONT.sub("", text))
    words = paper = 0
    markers_outside = []
    about, level = False, 0
    pieces = _HEADING.split(prose)
    # pieces: [before, hashes, title, body, hashes, title, body, ...]
    chunks = [("", 0, pieces[0])] + [(pieces[i + 1], len(pieces[i]), pieces[i + 2])
                                     for i in range(1, len(pieces) - 1, 3)]
    for title, lvl, body in chunks:
        if title:
            if about and lvl <= level:
                about = False
            if not about and PAPER_HEADING.search(title):
                about, level = True, lvl
        n = len(title.split()) + len(body.split())
        words += n
        paper += n if about else 0
        if not about:
            markers_outside += re.findall(r"\{quote\}`([^`]+)`", title + body)
    return {"words": words, "cells": cells, "paper_share": paper / max(words, 1),
            "markers_outside": markers_outside}


def test_the_measure_on_a_made_up_chapter():
    text = ("---\nfront: matter words\n---\n# Title\n\nOne two three.\n\n```{code-cell} "
            "ipython3\nx = 1\n```\n\n## Case study: Lee et al. (2012)\n\nFour five six seven "
            "{quote}`lee2012.t40`.\n\n### Inside\n\nEight.\n\n## Summary\n\nNine "
            "{quote}`cho2005.eq1`.\n")
    m = measure(text)
    assert m["cells"] == 1
    # words: "# Title" 1 + 3, the case-study heading 6 + 5, "Inside" 1 + 1, "Summary" 1 + 2
    assert m["words"] == 20
    assert m["paper_share"] == pytest.approx(13 / 20)
    assert m["markers_outside"] == ["cho2005.eq1"]


@pytest.mark.parametrize("stem", _known(OVER, "over today"))
def test_a_concept_chapter_is_a_sitting(stem):
    m = measure((BOOK / f"{stem}.md").read_text(encoding="utf-8"))
    assert m["words"] <= MAX_WORDS and m["cells"] <= MAX_CELLS, (m["words"], m["cells"])


@pytest.mark.parametrize("stem", CHAPTERS)
def test_a_concept_chapter_speaks_of_a_paper_only_in_its_short_case_study_section(stem):
    m = measure((BOOK / f"{stem}.md").read_text(encoding="utf-8"))
    assert m["paper_share"] <= MAX_PAPER_SHARE, f"{m['paper_share']:.0%} about a paper"


@pytest.mark.parametrize("stem", _known(MARKERS, "markers outside the case-study section"))
def test_a_concept_chapter_keeps_its_evidence_markers_in_its_case_study_section(stem):
    m = measure((BOOK / f"{stem}.md").read_text(encoding="utf-8"))
    assert not m["markers_outside"], m["markers_outside"]
