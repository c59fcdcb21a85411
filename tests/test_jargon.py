"""No words that belong to how the repository was made rather than to the reader.

Two scopes:

* every tracked text file under ``src/``, ``tests/``, ``experiments/``, ``benchmarks/`` and
  ``book/`` (prose and code cells), plus ``README.md``, ``_config.yml``, ``_toc.yml`` and
  ``pyproject.toml``, and every tracked file NAME, are checked for process words (the old
  numbered names of the papers, a specification or ticket number, the words of how the work
  was planned: see ``PROCESS_WORDS``);
  chapters are named by file stem (``06_kalman``) or title, never by a typed number;
* the book pages (``book/*.md``) are also checked for words a reader cannot act on ("this
  machine", "an earlier version", numeric citations, unqualified "development sequences").

Files are listed with ``git ls-files`` from the repository root; outside a git checkout the
folders are walked. Every hit is reported as ``file:line: word: text``.

The patterns are built from pieces (``_SD`` ...) so this file does not match itself.
"""
import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
BOOK = ROOT / "book"
FOLDERS = ("src", "tests", "experiments", "benchmarks", "book")
TOP_FILES = ("README.md", "_config.yml", "_toc.yml", "pyproject.toml")

# Files being replaced by the experiment pipeline (the branch that declares experiments as
# data deletes or renames each of them, together with every line that names them). Until
# that branch is merged they, and a line elsewhere that names one of them, are not scanned.
# Delete this list (and its two uses below) once that branch is merged.
BEING_REPLACED_BY_THE_EXPERIMENT_PIPELINE = ()

# the words, in pieces
_SD, _SPC, _ISU, _MSN = "se" + "ed", "SP" + "EC", "is" + "sue", "mis" + "sion"
_BGT, _PPR, _CHP = "bud" + "get", "pa" + "per", "chap" + "ter"
_START = r"(?<![A-Za-z0-9])"                 # a word start that an underscore also makes

#: Process words, checked everywhere (code, prose, file names).
PROCESS_WORDS = {
    # the word, then 00 and a digit, joined by nothing, a space, "_" or "-"; also inside a name
    "seed 00x": re.compile(_SD + r"[ _-]?00\d", re.I),
    "spec": re.compile(_START + _SPC + r"\b"),
    "issue N": re.compile(_START + _ISU + r"s?[\s_]*#?\d+|" + _START + _ISU + r"'s\b", re.I),
    "planning word": re.compile(_START + _MSN, re.I),
    # a cost limit named as a process word; Chrome's own --virtual-time-... flag is its word
    "cost-limit word": re.compile(r"(?<!virtual-time-)" + _START + _BGT, re.I),
    # the papers numbered 000-003, also as an argument value
    "paper 00x": re.compile(_PPR + r"""(?:[ _-]?|\s*=\s*["']?)00\d""", re.I),
}

#: A chapter by typed number (see the examples at the end); checked in src/,
#: tests/, the README and the book pages.
CHAPTER_NUMBER = re.compile(r"\b(?:" + _CHP + r"s?\s*|ch\.?\s+)\d+", re.I)

#: Words a reader cannot act on, checked on the book pages only.
BOOK_WORDS = {
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

#: Words about how the results were made, not what they mean: in a chapter's prose (its code
#: cells call the library, and the lab notes keep the commands and file names).
CHAPTER_PROSE_WORDS = {
    "PYTHONPATH": re.compile(r"\bPYTHONPATH\b"),
    "python -m": re.compile(r"\bpython3? -m\b"),
    "book/results": re.compile(r"\bbook/results\b"),
    "a results file name": re.compile(r"\b[\w-]+\.(?:csv|json)\b"),
    "experiments/": re.compile(r"\bexperiments/"),
    "the test suite": re.compile(r"\b(?:the )?test suite\b|\bthe tests? checks?\b", re.I),
}

#: Patterns checked in prose only: in code, ``[5, 6]`` is a list, not a citation.
PROSE_ONLY = {"numeric citation"}

_BINARY = {".png", ".jpg", ".jpeg", ".gif", ".ico", ".pdf", ".npz", ".npy", ".zip", ".gz"}


def _tracked() -> list[str]:
    """Repository-relative paths of the files in scope (text or not)."""
    try:
        out = subprocess.run(["git", "ls-files", "--", *FOLDERS, *TOP_FILES], cwd=ROOT,
                             capture_output=True, text=True, check=True, timeout=60).stdout
        paths = [p for p in out.splitlines() if p]
    except (OSError, subprocess.SubprocessError):
        paths = []
    if not paths:                           # not a git checkout: walk the folders
        paths = [str(p.relative_to(ROOT)) for f in FOLDERS for p in (ROOT / f).rglob("*")
                 if p.is_file() and "__pycache__" not in p.parts]
        paths += [f for f in TOP_FILES if (ROOT / f).is_file()]
    return sorted(paths)


def _being_replaced(rel: str) -> bool:
    return any(rel == p or (p.endswith("/") and rel.startswith(p))
               for p in BEING_REPLACED_BY_THE_EXPERIMENT_PIPELINE)


def _replaced_names() -> tuple[str, ...]:
    """Names of the files being replaced (a folder's path, each file's stem when it holds a
    process word); a line naming one of them goes with them."""
    folders = {p for p in BEING_REPLACED_BY_THE_EXPERIMENT_PIPELINE if p.endswith("/")}
    stems = {pathlib.PurePosixPath(p).stem for p in ALL_FILES if _being_replaced(p)}
    stems |= {pathlib.PurePosixPath(p).stem for p in BEING_REPLACED_BY_THE_EXPERIMENT_PIPELINE}
    return tuple(sorted(folders | {n for n in stems if PROCESS_WORDS["seed 00x"].search(n)}))


ALL_FILES = _tracked()
SCANNED = [p for p in ALL_FILES
           if not _being_replaced(p) and pathlib.PurePosixPath(p).suffix.lower() not in _BINARY]
REPLACED_NAMES = _replaced_names()


def _lines(rel: str):
    """(number, line, in_code) of a text file; nothing for a binary or missing one."""
    path = ROOT / rel
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return
    if "\0" in text:
        return
    markdown = rel.endswith(".md")
    in_code = not markdown
    for n, line in enumerate(text.splitlines(), 1):
        if markdown and line.lstrip().startswith("```"):
            in_code = not in_code
            continue
        if any(name in line for name in REPLACED_NAMES):
            continue                        # goes with the file the experiment pipeline replaces
        yield n, line, in_code


def _report(rel, n, word, line):
    return f"{rel}:{n}: {word}: {line.strip()[:100]}"


def _process_hits(rel):
    return [_report(rel, n, word, line) for n, line, _ in _lines(rel)
            for word, rx in PROCESS_WORDS.items() if rx.search(line)]


def _chapter_hits(rel):
    book_page = rel.startswith("book/") and rel.endswith(".md")
    return [_report(rel, n, "chapter by number", line) for n, line, in_code in _lines(rel)
            if not (book_page and in_code) and CHAPTER_NUMBER.search(line)]


def _book_hits(rel):
    return [_report(rel, n, word, line) for n, line, in_code in _lines(rel)
            for word, rx in BOOK_WORDS.items()
            if not (in_code and word in PROSE_ONLY) and rx.search(line)]


CHAPTER_SCOPE = [p for p in SCANNED
                 if p.startswith(("src/", "tests/")) or p == "README.md"
                 or (p.startswith("book/") and p.count("/") == 1 and p.endswith(".md"))]
PAGES = [p for p in SCANNED if p.startswith("book/") and p.count("/") == 1
         and p.endswith(".md")]


@pytest.mark.parametrize("rel", SCANNED)
def test_no_process_words(rel):
    hits = _process_hits(rel)
    assert not hits, "process words in the repository:\n" + "\n".join(hits)


def test_no_process_words_in_file_names():
    hits = [p for p in ALL_FILES if not _being_replaced(p)
            for rx in PROCESS_WORDS.values() if rx.search(p)]
    assert not hits, "process words in file names:\n" + "\n".join(hits)


@pytest.mark.parametrize("rel", CHAPTER_SCOPE)
def test_chapters_named_by_file_stem_not_number(rel):
    hits = _chapter_hits(rel)
    assert not hits, ("a chapter named by a typed number (name it by its file stem, e.g. "
                      "06_kalman, or in the book by {doc} link or title):\n" + "\n".join(hits))


@pytest.mark.parametrize("page", PAGES)
def test_no_repository_jargon_on_the_page(page):
    hits = _book_hits(page)
    assert not hits, "repository words on a reader's page:\n" + "\n".join(hits)


CHAPTERS = [p for p in PAGES if re.match(r"book/(?:\d\d_|case_stud(?:y|ies)_)", p)]


@pytest.mark.parametrize("page", CHAPTERS)
def test_chapter_prose_has_no_build_commands_or_file_names(page):
    hits = [_report(page, n, word, line) for n, line, in_code in _lines(page) if not in_code
            for word, rx in CHAPTER_PROSE_WORDS.items() if rx.search(line)]
    assert not hits, ("build commands, file names or test talk in a chapter's prose (they "
                      "belong in the lab notes):\n" + "\n".join(hits))


def test_the_scan_covers_every_folder():
    for folder in FOLDERS:
        assert any(p.startswith(folder + "/") for p in SCANNED), folder
    assert "tests/test_jargon.py" in SCANNED


def test_chapter_prose_patterns_catch_what_they_should():
    bad = ["run PYTHONPATH=src python -m trackbook", "python3 -m trackbook.evaluation",
           "see book/results/real", "the file lee2012_real.json", "claims.csv holds",
           "see experiments/lost_matrix.py", "the test suite checks it", "The tests check both"]
    good = ["the results of the benchmark", "a test of the hypothesis", "JSON is a format"]
    assert all(any(rx.search(b) for rx in CHAPTER_PROSE_WORDS.values()) for b in bad)
    assert not any(rx.search(g) for g in good for rx in CHAPTER_PROSE_WORDS.values())


def test_patterns_catch_what_they_should():
    s, p, c = _SD, _PPR, _CHP
    bad_process = [f"see {_SPC} section 4", f"({s} 002)", f"{s}000", f"{s}_001", f"{s}-002",
                   f"table_{s}000.py", f"{s.title()} 001: hsi-color-pf", f"{p} 000's",
                   f'available({p}="002")', f"{_ISU} 13", f"({_ISU.title()} 15)",
                   f"the {_ISU}'s limit", f"the {_MSN} names", f"the {_BGT} of 2400",
                   f"static_runs({_BGT}=10)", f"def test_static_{_BGT}_leaves",
                   f"_{_MSN}_knobs", f"test_{_ISU}_13"]
    good_process = ["seeded by the motion vector", "specification", "a format spec",
                    "--virtual-time-" + _BGT + "=20000", "seeds 0-9", "seed 0",
                    "paper's eq. 6", "permission denied", "issued", "kim2016"]
    for t in bad_process:
        assert any(rx.search(t) for rx in PROCESS_WORDS.values()), t
    for t in good_process:
        assert not any(rx.search(t) for rx in PROCESS_WORDS.values()), t

    for t in [f"{c} 6", f"{c.title()} 08", f"{c}s 2, 3 and 4", "ch" " 7", "Ch." " 8"]:
        assert CHAPTER_NUMBER.search(t), t
    for t in ["{doc}`06_kalman`", "eq. 6 of Kim et al.", "section 4.2", "search 7", "each 3"]:
        assert not CHAPTER_NUMBER.search(t), t

    bad_book = ["../shared/data", "on this machine", "an earlier version of",
                "the development sequences", "the baseline [20] uses", "see [3-5]"]
    good_book = ["the seven public development sequences", "[the filter](02_particle_filters.md)",
                 "x[0] + y[1]"]
    for t in bad_book:
        assert any(rx.search(t) for rx in BOOK_WORDS.values()), t
    for t in good_book:
        assert not any(rx.search(t) for rx in BOOK_WORDS.values()), t


def test_the_replaced_files_are_named_exactly():
    """The skip list holds paths that exist (or a folder), so it cannot hide a typo'd file;
    once the experiment pipeline has replaced them this fails: delete the list then."""
    for p in BEING_REPLACED_BY_THE_EXPERIMENT_PIPELINE:
        assert any(f == p or (p.endswith("/") and f.startswith(p)) for f in ALL_FILES), (
            f"{p} is gone: delete BEING_REPLACED_BY_THE_EXPERIMENT_PIPELINE and its uses")


#: A chapter's file stem as a reader would meet it in printed text: "03_hog", "(07_region_...".
_STEM = re.compile(r"\b\d\d_[a-z]+(?:_[a-z]+)*\b")


def test_departures_tables_name_chapters_by_title():
    """The departures tables print each knob's ``why`` on a reader's page: a chapter is named
    there by its title ("the HOG chapter"), never by its file stem."""
    from trackbook import trackers
    hits = [f"{name}.{d['param']}: {d['why']}" for name in trackers.available()
            for d in trackers.departures(name) if _STEM.search(str(d.get("why", "")))]
    assert not hits, "a chapter's file stem in a departures table:\n" + "\n".join(hits)
    assert _STEM.search("the book's 8 signed bins of 03_hog") and not _STEM.search("the HOG chapter")
