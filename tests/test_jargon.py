"""No words on a reader's page that belong to the repository rather than the reader.

Scans every book page (``book/*.md``): the prose and the code cells (their comments and
strings are displayed). Reports every hit as ``file:line: word``.
"""
import pathlib
import re

import pytest

BOOK = pathlib.Path(__file__).resolve().parents[1] / "book"

PATTERNS = {
    "SPEC": re.compile(r"\bSPEC\b"),
    "seed 00x": re.compile(r"\bseed[ -]00\d\b", re.I),
    "paper 00x": re.compile(r"\bpaper[ -]00\d\b", re.I),
    "../shared": re.compile(r"\.\./shared"),
    "this machine": re.compile(r"\bthis machine\b", re.I),
    "an earlier version": re.compile(r"\ban earlier version\b", re.I),
    # "development sequences" is fine when qualified ("the seven public development sequences")
    "unqualified development sequences": re.compile(
        r"(?<!public )(?<!seven )\bdevelopment sequences?\b", re.I),
    # numeric citations such as [20] or [3-5]; Markdown links [text](...) and list indices
    # in code (x[0]) are not citations: require a space or line start before the bracket
    # (an interval such as [0, 1] or a kernel [1, 4, 6, 4, 1] has a 0 or 1 in it; reference
    # numbers of the papers' bibliographies run from 2 up, so a lone [1] is left alone too)
    "numeric citation": re.compile(r"(?:^|(?<=\s))\[(?![01]\b)\d+(?:\s*[-–]\s*\d+)?\](?!\()"),
}


#: Patterns checked in prose only: in code, ``[5, 6]`` is a list, not a citation.
PROSE_ONLY = {"numeric citation"}


def _hits(path):
    out = []
    in_code = False
    for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if line.lstrip().startswith("```"):
            in_code = not in_code
            continue
        for word, rx in PATTERNS.items():
            if in_code and word in PROSE_ONLY:
                continue
            if rx.search(line):
                out.append(f"{path.relative_to(BOOK.parent)}:{n}: {word}: {line.strip()[:100]}")
    return out


PAGES = sorted(BOOK.glob("*.md"))


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_no_repository_jargon_on_the_page(page):
    hits = _hits(page)
    assert not hits, "repository words on a reader's page:\n" + "\n".join(hits)


def test_patterns_catch_what_they_should():
    bad = ["see SPEC section 4", "(seed 002)", "paper 000's", "../shared/data",
           "on this machine", "an earlier version of", "the development sequences",
           "the baseline [20] uses", "see [3-5]"]
    good = ["the seven public development sequences", "[chapter 2](02_particle_filters.md)",
            "x[0] + y[1]", "seeded by the motion vector", "specification"]
    for s in bad:
        assert any(rx.search(s) for rx in PATTERNS.values()), s
    for s in good:
        assert not any(rx.search(s) for rx in PATTERNS.values()), s
