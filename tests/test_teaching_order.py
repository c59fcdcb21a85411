"""The book's teaching order: nothing is used before it is taught.

The order is the table of contents (``_toc.yml``). Two things a reader meets are held to it:

* a concept chapter's **Prerequisites** paragraph names only chapters that come before it;
* an exercise that needs a chapter taught later says so in its header (``| after <stem>``),
  and that chapter does come later (an ``after`` that names an earlier chapter, or the
  exercise's own, is a stale flag).

The exercises appendix and ``trackbook.exercises.chapters()`` list the chapters in the same
order as the table of contents.
"""
import re
from pathlib import Path

import pytest

from trackbook import exercises

from . import _toc

ROOT = Path(__file__).resolve().parents[1]
BOOK = ROOT / "book"


ORDER = _toc.stems()
CONCEPT = [s for s in ORDER if re.match(r"\d\d_", s)]
_LINK = re.compile(r"(?:\{doc\}`(?:[^`<]*<)?|\]\()(\d\d_[a-z0-9_]+)(?:\.md)?[>`)]")


def _prerequisites(stem: str) -> str:
    text = (BOOK / f"{stem}.md").read_text()
    m = re.search(r"^\*\*Prerequisites\.\*\*(.*?)(?:\n\s*\n)", text, re.M | re.S)
    assert m, f"{stem} has no **Prerequisites.** paragraph"
    return m.group(1)


def test_the_link_pattern_finds_both_link_forms():
    text = ("{doc}`the Kalman chapter <06_kalman>` and [HOG](03_hog.md) and "
            "{doc}`02_particle_filters`")
    assert _LINK.findall(text) == ["06_kalman", "03_hog", "02_particle_filters"]


@pytest.mark.parametrize("stem", CONCEPT)
def test_prerequisites_come_before_the_chapter(stem):
    here = ORDER.index(stem)
    later = [s for s in _LINK.findall(_prerequisites(stem)) if ORDER.index(s) > here]
    assert not later, f"{stem}'s prerequisites name chapters the book teaches later: {later}"


@pytest.mark.parametrize("stem", exercises.chapters())
def test_an_exercise_that_needs_a_later_chapter_names_it(stem):
    here = ORDER.index(stem)
    for e in exercises.for_chapter(stem):
        if e.after:
            assert e.after in ORDER, f"{e.number}: 'after {e.after}' is not a page of the book"
            assert ORDER.index(e.after) > here, (
                f"{e.number}: 'after {e.after}' names a chapter the book teaches before "
                f"{stem}; drop the flag")


def test_exercise_chapters_follow_the_table_of_contents():
    assert list(exercises.chapters()) == [s for s in ORDER if s in exercises.chapters()]


def test_the_after_flag_is_parsed_and_shown():
    text = "=== 3.4 ★★ modify | How much colour? | after 02_particle_filters\nRun it.\n"
    (e,) = exercises.parse(text, "03_hog")
    assert (e.title, e.after) == ("How much colour?", "02_particle_filters")
    assert "*(After {doc}`02_particle_filters`.)* Run it." in exercises.markdown(e)
    (plain,) = exercises.parse("=== 3.1 ★ use | Halve the light\nRun it.\n", "03_hog")
    assert plain.after == "" and "After" not in exercises.markdown(plain)


def _teaching():
    return (BOOK / "appendix_teaching.md").read_text()


def test_the_teaching_pages_old_to_new_table_is_the_table_of_contents():
    row = r"^\| \[[^\]]+\]\((\d\d_\w+)\.md\) \| (\d+|new) \| ([^|]+?) \| (\d+) \|$"
    rows = re.findall(row, _teaching(), re.M)
    assert sorted(r[0] for r in rows) == sorted(CONCEPT)
    parts = _toc.parts()
    for stem, old, part, now in rows:
        # the old order ran 00 ... 20 by file number; a chapter added since is "new"
        assert old == (str(int(stem[:2])) if int(stem[:2]) <= 20 else "new"), stem
        assert int(now) == CONCEPT.index(stem), f"{stem}: place now {now}"
        want = parts.get(stem, "the introduction")
        assert part.lower() == want.lower(), f"{stem}: part {part!r}, _toc.yml says {want!r}"


def test_the_core_path_follows_the_book_and_optional_pages_come_after_their_prerequisites():
    text = _teaching()
    core = re.findall(r"^\| (\d+) \| \[[^\]]+\]\((\d\d_\w+)\.md\)", text, re.M)
    weeks = {stem: int(w) for w, stem in core}
    assert [int(w) for w, _ in core] == list(range(1, len(core) + 1))
    places = [ORDER.index(s) for _, s in core]
    assert places == sorted(places), "the core path is not in the book's order"
    optional = re.findall(r"^\| \[[^\]]+\]\((\d\d_\w+)\.md\) \| (\d+) \| [^|]*\|$", text, re.M)
    assert optional, "the table of optional chapters is missing"
    for stem, after in optional:
        needed = [s for s in _LINK.findall(_prerequisites(stem)) if s in weeks]
        late = [s for s in needed if weeks[s] > int(after)]
        assert not late, f"{stem} is placed after week {after} but needs {late}"
