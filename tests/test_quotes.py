"""The register of quotes: every original occurs, as printed, in its paper's text.

The papers' texts sit in ``shared/seeds`` beside the repository (found like the sequences:
``$TRACKBOOK_PAPER_TEXTS``, else ``shared/seeds`` in the repository's folder or a parent);
the tests that need them skip cleanly when they are absent. Each paper's file is recognised by
its title on the first lines, not by its file name. Only runs of whitespace are normalised
(line and page breaks, table cells): every other character must match.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

from trackbook import quotes
from trackbook.quotes import PAPERS, QUOTES

REPO = Path(__file__).resolve().parents[1]

#: A phrase of each paper's title (on its first lines; the bibliographies cite each other).
TITLES = {
    "lee2012": "Robust Object Tracking in Mobile Robots using Object Features",
    "kim2016": "Tracking moving objects using particle filter and edge observation model",
    "lee2015": "A Fast Moving Object Tracking Method by the Combination of Covariance Matrix",
    "cho2005": "Integration of Condensation and Mean-shift algorithms",
}


def _texts_dir() -> Path | None:
    env = os.environ.get("TRACKBOOK_PAPER_TEXTS")
    if env:
        return Path(env) if Path(env).is_dir() else None
    for a in (REPO, *REPO.parents):
        cand = a / "shared" / "seeds"
        if cand.is_dir():
            return cand
    return None


def _ws(s: str) -> str:
    return re.sub(r"\s+", " ", s).strip()


def _paper_texts() -> dict[str, str]:
    folder = _texts_dir()
    if folder is None:
        return {}
    out = {}
    for p in sorted(folder.glob("*.txt")):
        text = p.read_text(encoding="utf-8")
        for paper, title in TITLES.items():
            if title in text[:1500]:
                out[paper] = _ws(text)
    return out


TEXTS = _paper_texts()
needs_texts = pytest.mark.skipif(
    len(TEXTS) < len(PAPERS), reason="the papers' texts (shared/seeds) are not beside the "
    "repository (set TRACKBOOK_PAPER_TEXTS)")


@needs_texts
@pytest.mark.parametrize("key", sorted(QUOTES))
def test_original_occurs_verbatim_in_its_paper(key):
    q = QUOTES[key]
    assert _ws(q.original) in TEXTS[q.paper], (
        f"{key}: the original is not in the text of {q.paper} (copy it as printed)")


@needs_texts
def test_an_altered_passage_is_not_found():
    # the check must be able to fail: one changed digit, one changed word
    assert _ws("제안된 알고리즘의 T는 41으로 정의하였다.") not in TEXTS["lee2012"]
    assert _ws("본 논문에서는 최대 99개의 파티클을 사용하였다.") not in TEXTS["kim2016"]
    assert _ws(QUOTES["lee2012.t40"].original) in TEXTS["lee2012"]


def test_keys_are_unique_and_name_their_paper():
    keys = [q.key for p in PAPERS for q in quotes.for_paper(p)]
    assert len(keys) == len(set(keys)) == len(QUOTES)
    for key, q in QUOTES.items():
        assert q.key == key and key.split(".")[0] == q.paper in PAPERS


def test_every_paper_has_entries():
    counts = {p: len(quotes.for_paper(p)) for p in PAPERS}
    assert all(n >= 10 for n in counts.values()), counts
    assert sum(counts.values()) >= 60


def test_fields_are_filled():
    for q in QUOTES.values():
        assert q.translation.strip() and q.where.strip() and q.original.strip(), q.key
        assert q.kind in ("printed", "reading"), q.key
        # a translation is English: no Hangul left in it
        assert not re.search(r"[\uac00-\ud7a3]", q.translation), q.key


def test_language_tells_korean_from_english():
    assert QUOTES["lee2012.t40"].language == "ko"
    assert QUOTES["lee2012.abstract_rates"].language == "en"


def test_register_covers_the_passages_the_chapters_need():
    # the passages behind the attributions the book makes most often
    for key in ["lee2012.window40", "lee2012.m1", "lee2012.remove_old", "lee2012.frame_pos",
                "lee2012.failed_for_a_while", "lee2012.hardware", "kim2016.correct",
                "kim2016.ratio_eq5", "kim2016.weight_eq6", "kim2016.ratio_window",
                "kim2016.max999", "lee2015.detection_rate_eq14", "lee2015.frames184",
                "lee2015.table1", "lee2015.q_identity", "lee2015.r_identity",
                "lee2015.features_eq2", "lee2015.hardware", "cho2005.table1_seconds",
                "cho2005.table2_seconds", "cho2005.bandwidth_eq3", "cho2005.bandwidth_eq10",
                "cho2005.multi_mean_shift_fails", "cho2005.error_curves", "cho2005.hardware",
                "cho2005.mean_shift_step3"]:
        assert key in QUOTES, key


def test_quote_and_for_paper_refuse_unknown_names():
    with pytest.raises(ValueError, match="lee2012.window41"):
        quotes.quote("lee2012.window41")
    with pytest.raises(ValueError, match="lee2013"):
        quotes.for_paper("lee2013")
    with pytest.raises(TypeError):
        quotes.quote(40)


def test_a_malformed_record_is_refused():
    with pytest.raises(ValueError, match="paper"):
        quotes.Quote("lee2013.x", "§1", "a", "b")
    with pytest.raises(ValueError, match="kind"):
        quotes.Quote("lee2012.x", "§1", "a", "b", kind="guess")
    with pytest.raises(ValueError, match="translation"):
        quotes.Quote("lee2012.x", "§1", "a", " ")


def test_references_finds_both_forms_in_order():
    text = "T is 40 {quote}`lee2012.t40`, n = 40 [quote: lee2012.window40] and {quote}`x.y`"
    assert quotes.references(text) == ["lee2012.t40", "lee2012.window40", "x.y"]


def _files_with_text_references():
    files = [REPO / "README.md", *sorted((REPO / "src").rglob("*.py"))]
    return [p for p in files if p.is_file()]


def test_every_text_reference_in_src_and_readme_resolves():
    unknown = []
    for p in _files_with_text_references():
        for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1):
            for m in quotes.TEXT_REFERENCE.finditer(line):
                if m.group(1) not in QUOTES:
                    unknown.append(f"{p.relative_to(REPO)}:{n}: {m.group(1)}")
    assert not unknown, "quote references with no entry in the register:\n" + "\n".join(unknown)


def test_every_role_in_the_book_resolves():
    unknown = []
    for p in sorted((REPO / "book").glob("*.md")):
        for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1):
            for m in quotes.ROLE.finditer(line):
                if m.group(1).strip() not in QUOTES:
                    unknown.append(f"{p.relative_to(REPO)}:{n}: {m.group(1)}")
    assert not unknown, "quote roles with no entry in the register:\n" + "\n".join(unknown)
