"""The attribution check: a sentence that speaks for a paper cites, in that very sentence, a
quote of that paper.

Hand-made sentences the check must flag and must let pass, in Markdown and in Python source,
then the check itself on the files that already follow the rule (the register, the Sphinx role,
the evidence paragraph of the teaching appendix), the rule for works outside the register, and
the check over the whole book, the README and every module.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from trackbook.quotes import attributions
from trackbook.quotes.attributions import unquoted

REPO = Path(__file__).resolve().parents[1]

FLAGGED = [
    "The paper says old features are removed.",
    "The papers report only the tracking rate.",
    "the paper prints no forgetting factor",
    "The paper's own text counts frames.",
    "The paper never reports a lost target.",
    "Lee et al. (2012) never report a lost target.",
    "Kim et al. 2016 use up to 999 particles.",
    "Kim et al. say the gain is one.",
    "Lee (2015) prints Q = I.",
    "Lee 2015 uses a 24 x 24 window.",
    "Cho and Kang measure seconds per frame.",
    "Cho & Kang (2005) report error curves.",
    "By the paper's measure the proposed tracker is cheaper.",
    "The paper's gain is 1.",
    "features = 'xyIIxIy' as printed",
    "0 = every frame, as the paper",
    "Not in the paper, which never reports a lost target.",
    "The paper tracks two faces with one tracker each.",
    "The paper evaluated on eight private videos.",
    "the papers' own tracking rate (IoU > 0.5)",
    "The papers' own timings came from a Pentium 4.",
    "not the one the paper's argument suggests",
    "Lee et al. (2012) shrink it for a particle filter.",
    "Lee (2015) writes the feature image as a mapping.",
    "Lee et al.'s tracker uses 100 particles.",
    "Kim et al.'s method sets the gain to one.",
    "Cho and Kang's tracker uses five candidates.",
    "According to Lee (2015), Q is the identity.",
    "According to the paper, T = 40.",
    "The four papers use colour histograms.",
    "Neither paper prints a threshold.",
    "Each paper reports a tracking rate.",
    "Both papers use a particle filter.",
    "In the paper, T = 40.",
    "Per the paper, the window is 24 px.",
    "In Lee et al. (2012), N is 100.",
    "Lee et al. obtain 55 ms per frame.",
    "Kim et al. initialise the weights equally.",
    "Lee et al. (2012), who use 100 particles, start anywhere.",
    "Lee (2015)'s tracker uses Q = I.",
    "The Lee 2012 paper uses HSV.",
]


def _key_of(sentence: str) -> str:
    """A register key of the paper a specimen sentence names (lee2012 when it names none)."""
    if "Kim" in sentence:
        return "kim2016.max999"
    if "2015" in sentence:
        return "lee2015.abstract_rate"
    if "Cho" in sentence:
        return "cho2005.table1_seconds"
    return "lee2012.t40"

PASSED = [
    "The book's tracker keeps the last estimate.",
    "Lee et al. (2012) is the first of the four papers.",      # names the paper, says nothing
    "Papers of the period use colour histograms.",
    "We measure the tracking rate at IoU > 0.5.",
    "The lee2012 preset builds the printed method with T = 40.",
    "Kim and Lee went to the market.",                         # no year, not a citation
    "the paper-ready figure",
    "Lee et al. (2012) and Kim et al. (2016) are two of the papers.",
    "Lee et al. (2012), section V, eq. 9.",
    "The paper by Lee et al. (2012) is in Korean.",
    "The book checks the four papers' claims with their uncertainty.",
    "Each paper's claim, checked",
    "The three Lee et al. trackers are in the lab notes.",
    "The mean-centred update (Ross et al., scikit-learn) is exact.",
    "The distance $|x| = |y|$ is symmetric, see Sec. 3 of this page.",
]


@pytest.mark.parametrize("sentence", FLAGGED)
def test_attribution_without_quote_is_flagged(sentence):
    found = unquoted(f"Some context.\n{sentence}\nMore context.\n")
    assert [line for line, _ in found] == [2], (sentence, found)


@pytest.mark.parametrize("sentence", FLAGGED)
def test_attribution_with_a_quote_in_its_sentence_passes(sentence):
    key = _key_of(sentence)
    body = sentence.rstrip(".")
    assert unquoted(f"{body} {{quote}}`{key}`.\n") == []
    assert unquoted(f"{body} [quote: {key}].\n") == []
    # a role right after the stop cites the sentence it closes
    assert unquoted(f"{sentence} {{quote}}`{key}` Next.\n") == []


@pytest.mark.parametrize("sentence", FLAGGED)
def test_a_quote_elsewhere_in_the_paragraph_does_not_clear_it(sentence):
    key = _key_of(sentence)
    sentence = sentence.rstrip(".") + "."
    for text in (f"T = 40 here {{quote}}`{key}`. {sentence}\n",
                 f"{sentence} The next sentence cites {{quote}}`{key}`.\n",
                 f"{sentence}\n\nT = 40 {{quote}}`{key}`.\n"):
        assert len(unquoted(text)) == 1, (text, unquoted(text))


# A sentence that names one of the four must cite a quote of that paper, not of another one.
WRONG_PAPER = [
    "Kim et al. (2016) use at most 999 particles {quote}`lee2012.n100`.",
    "Lee (2015) prints Q = I {quote}`kim2016.max999`.",
    "Cho and Kang report seconds per frame [quote: lee2012.processing_55ms].",
    "Lee et al. (2012) use T = 40 {quote}`cho2005.table1_seconds`.",
    "Kim's tracker uses 999 particles {quote}`lee2012.n100`.",
    "Lee's tracker uses Q = I {quote}`kim2016.max999`.",
]


@pytest.mark.parametrize("sentence", WRONG_PAPER)
def test_a_quote_of_another_paper_does_not_support_the_sentence(sentence):
    assert len(unquoted(sentence + "\n")) == 1, sentence


def test_a_bare_lee_is_either_lee_paper():
    assert unquoted("Lee's tracker uses Q = I {quote}`lee2015.q_identity`.\n") == []
    assert unquoted("Lee's tracker uses T = 40 {quote}`lee2012.t40`.\n") == []


def test_a_sentence_naming_two_papers_may_cite_either():
    s = ("Lee et al. (2012) use 100 particles {quote}`lee2012.n100`, and Kim et al. (2016) "
         "use at most 999 {quote}`kim2016.max999`.\n")
    assert unquoted(s) == []


def test_table_rows_and_list_items_are_sentences_of_their_own():
    table = ("| value | source |\n|---|---|\n| T = 40 | the paper prints it |\n"
             "| N = 100 | section V {quote}`lee2012.n100` |\n")
    assert [line for line, _ in unquoted(table)] == [3]
    items = "- the paper prints T = 40\n- N = 100 {quote}`lee2012.n100`\n"
    assert [line for line, _ in unquoted(items)] == [1]


def test_a_role_in_a_python_f_string_cites():
    cell = 'display(Markdown(f"The paper prints {t} {{quote}}`lee2012.t40`."))\n'
    assert unquoted(cell) == []
    assert len(unquoted(cell.replace("{{quote}}`lee2012.t40`", ""))) == 1


@pytest.mark.parametrize("sentence", PASSED)
def test_other_sentences_pass(sentence):
    assert unquoted(sentence + "\n") == []


def test_the_quote_must_be_in_the_same_paragraph():
    text = "The paper says T = 40.\n\nT = 40 {quote}`lee2012.t40`.\n"
    assert [line for line, _ in unquoted(text)] == [1]


def test_the_report_names_the_sentence():
    (line, sentence), = unquoted("First sentence. The paper prints N = 100. Last one.\n")
    assert line == 1 and sentence == "The paper prints N = 100."


def test_the_sentence_survives_abbreviations():
    (line, sentence), = unquoted("See eq. 5. Lee et al. (2012) print it as eq. 10 (Fig. 2). Next.\n")
    assert sentence == "Lee et al. (2012) print it as eq. 10 (Fig. 2)."


def test_python_comments_docstrings_and_param_docs():
    src = '''"""Module doc.

The paper says old features go.
"""
x = 1  # the paper prints N = 100 [quote: lee2012.n100]
y = param(1, "alpha of eq. 14, "
          "as printed")
# Cho and Kang report seconds per frame.
z = "the paper says in code strings too [quote: lee2012.t40]"
w = param(1, why="the paper prints it; the paper says so twice", quote="lee2012.t40")
v = param(1, why="Kim et al. (2016) print it", quote="lee2012.t40")
'''
    found = unquoted(src, python=True)
    # a param's quote= key cites every sentence of its why -- when it is the named paper's
    assert [line for line, _ in found] == [3, 7, 8, 11], found


def test_python_names_are_not_prose():
    # an identifier or a call is not a sentence: only comments and literals are read
    src = "the_paper_says = 1\nprints = the_paper_prints()\n"
    assert unquoted(src, python=True) == []


def test_scan_refuses_a_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="nope.md"):
        attributions.scan(tmp_path / "nope.md")


def test_main_lists_and_exits(tmp_path, capsys):
    page = tmp_path / "page.md"
    page.write_text("Intro.\n\nThe paper says so.\n", encoding="utf-8")
    assert attributions.main([str(page)]) == 1
    assert f"{page}:3: The paper says so." in capsys.readouterr().out
    page.write_text("The paper says so {quote}`lee2012.t40`.\n", encoding="utf-8")
    assert attributions.main([str(page)]) == 0
    assert attributions.main([]) == 2
    assert attributions.main([str(tmp_path / "missing.md")]) == 2


# --- the files that already follow the rule --------------------------------------------------

OWN_FILES = [
    *sorted((REPO / "src" / "trackbook" / "quotes").glob("*.py")),
    REPO / "book" / "_ext" / "sphinx_quotes.py",
]


@pytest.mark.parametrize("path", OWN_FILES, ids=lambda p: p.name)
def test_own_files_cite_their_attributions(path):
    found = attributions.scan(path, root=REPO)
    assert not found, "attribution sentences without a quote:\n" + "\n".join(map(str, found))


def _section(page: Path, heading: str) -> tuple[str, int]:
    text = page.read_text(encoding="utf-8")
    start = text.index(heading)
    end = text.find("\n## ", start + len(heading))
    return text[start:end if end >= 0 else None], text.count("\n", 0, start) + 1


def test_the_evidence_paragraph_of_the_teaching_appendix_cites_its_quotes():
    section, first = _section(REPO / "book" / "appendix_teaching.md",
                              "## How to read the evidence markers")
    found = [(first + line - 1, s) for line, s in unquoted(section)]
    assert not found, found
    assert section.count("{quote}`") >= 2


# --- works outside the register: named and cited -------------------------------------------

OTHER_WORKS = [
    "Bolme et al. {cite:p}`bolme2010` measure it by the peak-to-sidelobe ratio.",
    "{cite:t}`henriques2015` solve kernel ridge regression; Henriques et al. use FHOG.",
    "Henriques et al. 2015 use Felzenszwalb's 31-channel FHOG.",
    "Nummiaro et al. (2003) use a colour histogram.",
    "Pérez et al. {cite:p}`perez2002` use a colour likelihood.",
]

NOT_EXCUSED = [
    # "the paper" speaks for the four, whatever else the paragraph cites
    "The paper uses FHOG, as {cite:t}`henriques2015` describe.",
    "The paper compares with an HSI filter (Nummiaro et al. 2003 use a similar space).",
    # a work named without its citation
    "Bolme et al. measure it by the peak-to-sidelobe ratio.",
    # one of the four, even with another work cited beside it
    "Lee et al. (2012) use the colour histogram of Pérez et al. {cite:p}`perez2002`.",
    "Kim et al. 2016 use Canny edges (Canny 1986).",
    # a citation of another author does not back a sentence about a third one
    "Bolme et al. measure the PSR; {cite:t}`henriques2015` keep it.",
]


@pytest.mark.parametrize("sentence", OTHER_WORKS)
def test_a_named_and_cited_work_outside_the_register_passes(sentence):
    assert unquoted(sentence + "\n") == []


@pytest.mark.parametrize("sentence", NOT_EXCUSED)
def test_the_citation_rule_does_not_excuse_the_four_or_an_uncited_work(sentence):
    assert len(unquoted(sentence + "\n")) == 1, sentence


def test_the_rule_in_python_source():
    src = '''"""Bolme et al. 2010 give a PSR of 7.

Bolme et al. give a PSR of 7.
"""
'''
    assert [line for line, _ in unquoted(src, python=True)] == [3]


# --- the whole book, the README and every module ---------------------------------------------

def _all_files():
    import subprocess
    try:
        src = subprocess.run(["git", "ls-files", "src/*.py", "book/_ext/*.py"], cwd=REPO,
                             capture_output=True, text=True, check=True).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        src = [str(p.relative_to(REPO)) for d in ("src", "book/_ext")
               for p in (REPO / d).rglob("*.py")]
    return [*sorted((REPO / "book").glob("*.md")), REPO / "README.md",
            *sorted(REPO / s for s in src)]


def test_every_attribution_in_the_book_readme_and_sources_cites_its_evidence():
    files = _all_files()
    assert len(files) > 50 and any(f.name == "README.md" for f in files)
    found = [a for f in files for a in attributions.scan(f, root=REPO)]
    assert not found, ("attribution sentences without a quote (cite one with {quote}`key` or "
                       "[quote: key], or correct the sentence):\n" + "\n".join(map(str, found)))
