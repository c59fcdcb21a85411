"""Find sentences that say what a paper says, prints, uses or reports without citing a quote.

A sentence that speaks for a paper ("the paper prints ...", "Kim et al. (2016) use ...",
"Lee et al.'s tracker uses ...", "Cho and Kang report ...", "as printed") must itself carry a
quote reference -- in that sentence, not elsewhere in its paragraph: the book's role
``{quote}`lee2012.t40``` or, in docstrings and comments, the plain form
``[quote: lee2012.t40]``. A sentence that names one of the four (Lee et al. 2012, Kim et al.,
Lee 2015, Cho and Kang) must cite a quote of *that* paper. :func:`unquoted` lists the
sentences that break either rule. (In a param's doc -- the string literals of one call such as
``Param(..., why="...", quote="lee2012.t40")`` -- the ``quote=`` key is the citation of every
sentence of its ``why``.)

The register holds only the four papers. A sentence that speaks for another work, by name
("Bolme et al. build ...", "Henriques et al. 2015 use ...", "Comaniciu et al. (2003) stop
..."), is backed by that work's bibliographic citation instead: it passes when its author is
not Lee, Kim or Cho and its paragraph cites that author -- a ``{cite}`` role with a key of that
author (``bolme2010``) or an author-year citation ("Bolme et al. 2010") -- see
:func:`other_work_cited`. "The paper" and "the papers" always speak for the four (a chapter
that means another work names it).

Sentences end at a full stop, a question or exclamation mark followed by a space (not after
an abbreviation such as "eq." or "et al."), at a blank line, and at the start of a table row or
a list item. Paragraphs are: in Markdown, runs of non-blank lines; in Python, each docstring
paragraph and each run of comments and string literals on consecutive lines (a param's doc
split over several literals is one paragraph).

Run ``python -m trackbook.quotes.attributions FILE...`` for a ``file:line: sentence`` list.
"""

from __future__ import annotations

import io
import re
import sys
import tokenize
from dataclasses import dataclass
from pathlib import Path

from . import TEXT_REFERENCE

_VERB = (r"(?:says?|said|prints?|printed|uses?|used|reports?|reported|claims?|claimed|"
         r"measures?|measured|counts?|counted|never|states?|stated|names?|named|keeps?|kept|"
         r"gives?|gave|writes?|wrote|does\s+not|doesn't|do\s+not|don't|only|defines?|"
         r"defined|sets?|chooses?|chose|compares?|compared|runs?|ran|tests?|tested|calls?|"
         r"called|describes?|described|specif(?:y|ies|ied)|evaluates?|evaluated|tracks?|"
         r"tracked|shows?|showed|learns?|learned|adds?|added|removes?|removed|finds?|found|"
         r"achieves?|achieved|reach(?:es|ed)?|assumes?|assumed|mentions?|mentioned|"
         r"suggests?|suggested|argues?|argued|recommends?|recommended|builds?|built|"
         r"draws?|drew|plots?|plotted|lists?|listed|fixe[sd]|fix|proposes?|proposed|"
         r"applies|applied|computes?|computed|weighs?|weighted|normali[sz]es?|"
         r"normali[sz]ed|resamples?|resampled|searche[sd]|search|spreads?|ignores?|"
         r"ignored|omits?|omitted|leaves?|left|needs?|needed)")
_YEAR = r"(?:\(?\d{4}\)?,?\s+)"
_YEAR_TIGHT = r"(?:\(?\d{4}\)?\s+)"
#: Words after a citation that do not make it an attribution (a conjunction, a preposition).
_NOT_A_VERB = (r"(?!(?:is|was|are|were|be|and|or|in|on|of|for|to|with|the|a|an|as|at|by|from|"
               r"than|that|which|who|also|here|there|do|does|did|has|have|had|paper|papers|beside|"
               r"trackers?|methods?|results?|presets?|filters?|values?|settings?|equations?|"
               r"quotes?|text|data|ones?|work|variants?|baselines?|rows?|runs|"
               r"against|below|above|under|after|before|into|over|through|per|about|section|"
               r"sections|table|tables|eq|fig|figure|page|pp?)\b)")
#: After a citation with its year (no comma), any other word is taken as its verb.
_ANY_VERB = _NOT_A_VERB + r"[a-z]+\b"
_NOUN = (r"(?:measure|gain|value|values|setting|settings|criterion|choice|default|rule|"
         r"factor|figure|numbers?|rate|rates|tracking\s+rate|timings?|times|claims?|"
         r"argument|table|tables|videos?|results?|experiments?|method|preset|tracker|"
         r"equation|formula|baselines?|hardware|data)")

#: The patterns of an attribution sentence, in order: "the paper(s)" with a verb of saying
#: (also with "which" between them); an "et al." citation with a verb, or with its year
#: and any verb; a bare surname with its year and a verb; Cho and Kang with a verb; a
#: possessive of "the paper" with a noun such as measure, gain or timings; the phrases of a
#: printed value ("as" with "printed" or with "the paper"); a possessive of an author of the
#: four with a noun and a verb; "according to" one of the four.
PATTERNS = [
    re.compile(r"\bthe\s+papers?(?:'s?)?,?\s+(?:which\s+|that\s+)?(?:own\s+)?(?:text\s+)?"
               r"(?:also\s+|only\s+)?" + _VERB + r"\b", re.I),
    # "the four papers", "both papers", "neither paper", "each paper" with a verb (not a
    # possessive: "each paper's claim" names a claim, it does not make one)
    re.compile(r"\b(?:the\s+(?:four|two)|both|neither|each|all\s+four)\s+papers?,?\s+"
               r"(?:which\s+|that\s+)?(?:also\s+|only\s+)?" + _VERB + r"\b", re.I),
    re.compile(r"\bet\s+al\.?,?\s+(?:" + _YEAR + r"?" + _VERB + r"\b|" + _YEAR_TIGHT + _ANY_VERB
               + r")", re.I),
    # an "et al." without a year and any verb after it, but not after a comma (a list)
    re.compile(r"\bet\s+al\.?\s+" + _ANY_VERB, re.I),
    re.compile(r"\b(?:et\s+al\.?|Lee|Kim|Cho(?:\s+(?:and|&)\s+Kang)?),?\s*(?:\(?\d{4}\)?)?,\s+"
               r"who\s+[a-z]+"),
    re.compile(r"\b(?:Lee|Kim|Cho)\s+(?:" + _YEAR + _VERB + r"\b|" + _YEAR_TIGHT + _ANY_VERB
               + r")"),
    re.compile(r"\bCho\s+(?:and|&)\s+Kang,?\s+" + _YEAR + r"?" + _VERB + r"\b"),
    re.compile(r"\bthe\s+papers?(?:'s?|')\s+(?:own\s+)?(?:printed\s+)?" + _NOUN + r"\b",
               re.I),
    re.compile(r"\bas\s+(?:printed|in\s+the\s+papers?|the\s+papers?)\b", re.I),
    # a possessive of one of the four with a noun and a verb (their tracker, method, ... does)
    re.compile(r"\b(?:et\s+al\.?|Lee|Kim|Cho(?:\s+(?:and|&)\s+Kang)?)'s\s+" + _YEAR + r"?"
               r"(?:own\s+)?(?:[a-z\-]+\s+)?" + _NOUN + r"\s+(?:also\s+|only\s+)?" + _VERB + r"\b"),
    # "according to" one of the four, or to the paper
    re.compile(r"\baccording\s+to\s+(?:the\s+papers?\b|(?:Lee|Kim|Cho)\b)", re.I),
    # a possessive after the year, with a noun and a verb
    re.compile(r"\b(?:Lee|Kim|Cho)(?:\s+et\s+al\.?)?\s*\(?\d{4}\)?'s\s+"
               r"(?:[a-z\-]+\s+)?" + _NOUN + r"\s+" + _VERB + r"\b"),
    # "the" with an author of the four, "paper" and a verb
    re.compile(r"\b[Tt]he\s+(?:Lee|Kim|Cho)\b[^;:]{0,24}?\bpaper\s+(?:also\s+|only\s+)?"
               + _VERB + r"\b"),
    # a sentence that opens by placing itself in a paper: "In the paper, ...", "Per the
    # paper ...", "In Lee et al. (2012), ..."
    re.compile(r"(?:^|(?<=[.!?]\s)|(?<=\n))\s*(?:In|Per)\s+(?:the\s+paper\b|"
               r"(?:Lee|Kim|Cho)\b[^,]{0,30}?\d{4}\)?,)"),
]

#: In Python, a string literal that is a register key (``quote="lee2012.t40"``) cites too.
KEY_LITERAL = re.compile(r"""["'](?:lee2012|kim2016|lee2015|cho2005)\.[a-z0-9_]+["']""")


@dataclass(frozen=True)
class Attribution:
    """An attribution sentence with no quote reference in its paragraph."""

    path: str
    line: int
    sentence: str

    def __str__(self):
        return f"{self.path}:{self.line}: {self.sentence}"


#: The book's bibliographic roles: ``{cite}`key```, ``{cite:t}`a,b```, ``{cite:p}`key```.
CITE_ROLE = re.compile(r"\{cite(?::[a-z]+)?\}`([^`]*)`")
#: An author-year citation: "Henriques et al. 2015", "Nummiaro et al. (2003)", "Cho & Kang
#: 2005", "Canny (1986)", "Tuzel et al.'s (2006)"; group 1 is the first author.
AUTHOR_YEAR = re.compile(r"\b([A-Z][A-Za-z\u00c0-\u017f\-]+)(?:\s+et\s+al\.?(?:'s)?|\s+(?:and|&)\s+"
                         r"[A-Z][A-Za-z\u00c0-\u017f\-]+(?:'s)?|'s)?,?\s+\(?(?:19|20)\d\d[a-z]?\)?")
#: The first authors of the four papers.
_FOUR_AUTHORS = ("Lee", "Kim", "Cho")


def other_work_cited(paragraph: str, start: int) -> bool:
    """Whether the attribution matched at ``paragraph[start:]`` speaks for a work outside the
    register, named and cited.

    True when the attribution's subject is an author (the name before "et al." or before the
    year) who is not Lee, Kim or Cho, and ``paragraph`` cites that author: a ``{cite}`` key
    beginning with the surname (``henriques2015``) or an author-year citation of them. Such a
    work has no quote register; its citation is the evidence.
    """
    head = re.match(r"([A-Z][A-Za-z\u00c0-\u017f\-]+)\b", paragraph[start:])
    before = re.search(r"([A-Z][A-Za-z\u00c0-\u017f\-]+)\s+$", paragraph[:start])
    author = (before.group(1) if paragraph[start:start + 2].lower() == "et" and before
              else head.group(1) if head else None)
    if author is None or author in _FOUR_AUTHORS or author.lower() in ("the", "as"):
        return False
    keys = [k.strip() for m in CITE_ROLE.finditer(paragraph) for k in m.group(1).split(",")]
    if any(k.startswith(_fold(author)) for k in keys):
        return True
    return any(m.group(1) == author for m in AUTHOR_YEAR.finditer(paragraph))


def _fold(name: str) -> str:
    """A surname as a bibliography key starts: lower case, accents dropped (Pérez -> perez)."""
    import unicodedata
    return "".join(c for c in unicodedata.normalize("NFKD", name.lower())
                   if not unicodedata.combining(c))


#: The end of a sentence: a stop and a space, not after an abbreviation (eq., et al., Fig.);
#: a blank line; the start of a table row or of a list item on a new line.
_STOP = re.compile(r"(?<!\beq)(?<!\bEq)(?<!\bal)(?<!\bFig)(?<!\bfig)(?<!\be\.g)(?<!\bi\.e)"
                   r"(?<!\bvs)(?<!\bcf)(?<!\bch)(?<!\bsec)(?<!\bSec)(?<!\bno)(?<!\bp)"
                   r"(?<!\bpp)(?<!\bapprox)(?<!\beqs)(?<!\bTab)[.?!](?=\s)|\n\s*\n"
                   r"|\n(?=\s*(?:\||[-*+]\s|\d+\.\s))|(?<=\s)\|(?=\s)")


def _span(text: str, start: int, end: int) -> tuple[int, int]:
    """``(left, right)``: the sentence around ``text[start:end]``.

    A quote role right after the stop (``... eq. 9. {quote}`k```) belongs to the sentence
    before it: the role is then the first thing after the stop and cites what precedes it.
    """
    left = 0
    for m in _STOP.finditer(text, 0, start):
        left = m.end()
    m = _STOP.search(text, end)
    right = m.end() if m else len(text)
    trailing = re.match(r"\s*(?:(?:\{quote\}`[^`]*`|\[quote:[^\]]*\])[\s,;]*)+", text[right:])
    if trailing:
        right += trailing.end()
    return left, right


def _sentence(text: str, start: int, end: int) -> str:
    """The sentence around ``text[start:end]``, whitespace collapsed, at most ~200 chars."""
    left, right = _span(text, start, end)
    s = re.sub(r"\s+", " ", text[left:right]).strip()
    return s if len(s) <= 200 else s[:197] + "..."


#: The four papers by how a sentence names them: (pattern, register prefix).
_NAMED = [
    (re.compile(r"\bLee\s+et\s+al\.?(?:'s)?,?\s*\(?2012"), "lee2012"),
    (re.compile(r"\bLee\s+et\s+al\b"), "lee2012"),
    (re.compile(r"\bKim\s+et\s+al\b|\bKim\b,?\s*\(?2016"), "kim2016"),
    (re.compile(r"\bLee(?:'s)?,?\s*\(?2015|\bLee\s+\(2015\)"), "lee2015"),
    (re.compile(r"\bCho\s+(?:and|&)\s+Kang\b|\bCho\b,?\s*\(?2005"), "cho2005"),
    (re.compile(r"\bKim\b"), "kim2016"),
    (re.compile(r"\bCho\b"), "cho2005"),
]
#: A bare "Lee" (no "et al.", no year) is one of the two Lee papers, either of whose quotes
#: cites it.
_BARE_LEE = re.compile(r"\bLee\b(?!\s+et\s+al)(?![^.]{0,6}\b20(?:12|15)\b)")


#: The role as it also stands inside a Python f-string, braces doubled: ``{{quote}}`k```.
_ROLE_ANY = re.compile(r"\{\{?quote\}\}?`([^`]*)`")


def _keys(text: str) -> list[str]:
    """The quote keys a sentence cites: the role (also in an f-string), the plain-text form,
    a key literal."""
    return ([m.group(1) for m in _ROLE_ANY.finditer(text)]
            + [m.group(1) for m in TEXT_REFERENCE.finditer(text)]
            + [m.group(0).strip("\"'") for m in KEY_LITERAL.finditer(text)])


def _problem(sentence: str, extra: list[str] = ()) -> str | None:
    """Why an attribution sentence fails: no quote, or only quotes of another paper.
    ``extra``: keys that cite every sentence of its paragraph (a param's ``quote=``)."""
    keys = _keys(sentence) + list(extra)
    if not keys:
        return "cites no quote"
    named = {paper for rx, paper in _NAMED if rx.search(sentence)}
    cited = {k.split(".", 1)[0] for k in keys}
    if not named and _BARE_LEE.search(sentence) and not cited & {"lee2012", "lee2015"}:
        return f"names Lee but cites only {', '.join(sorted(cited))}"
    if named and not named & cited:
        return f"names {', '.join(sorted(named))} but cites only {', '.join(sorted(cited))}"
    return None


def _check_paragraph(text: str, first_line: int, offsets: list[int] | None = None,
                     extra: list[str] = ()):
    """``(line, sentence)`` of each attribution in one paragraph that its sentence does not
    cite. ``extra``: the keys of a param's ``quote=``, which cite every sentence of its doc.
    """
    out = []
    for rx in PATTERNS:
        for m in rx.finditer(text):
            if other_work_cited(text, m.start()):   # another work, named and cited
                continue
            left, right = _span(text, m.start(), m.end())
            if _problem(text[left:right], extra) is None:
                continue
            line = first_line + text.count("\n", 0, m.start())
            if offsets is not None:
                line = offsets[min(text.count("\n", 0, m.start()), len(offsets) - 1)]
            out.append((line, m.start(), _sentence(text, m.start(), m.end())))
    seen, result = set(), []
    for line, _, sentence in sorted(out):
        if (line, sentence) not in seen:       # two patterns on one sentence: one entry
            seen.add((line, sentence))
            result.append((line, sentence))
    return result


def _markdown_paragraphs(text: str):
    lines = text.splitlines()
    block, start = [], 1
    for n, line in enumerate(lines + [""], 1):
        if line.strip() and not line.lstrip().startswith("```"):
            if not block:
                start = n
            block.append(line)
        elif block:
            yield "\n".join(block), start
            block = []


def _python_paragraphs(text: str):
    """Paragraphs of a module's prose, each with the source line of each of its lines.

    A run of comments on consecutive lines is one paragraph; the string literals of one
    logical line (a param's doc split over several literals, its ``why``) are one; a
    docstring splits at its blank lines.
    """
    try:
        tokens = list(tokenize.generate_tokens(io.StringIO(text).readline))
    except (tokenize.TokenError, SyntaxError, IndentationError):
        for para, start in _markdown_paragraphs(text):
            yield para, list(range(start, start + para.count("\n") + 1))
        return
    groups, strings, comments = [], [], []
    for tok in tokens:
        if tok.type == tokenize.COMMENT:
            if comments and tok.start[0] > comments[-1].start[0] + 1:
                groups.append(comments)
                comments = []
            comments.append(tok)
        elif tok.type == tokenize.STRING:
            strings.append(tok)
        elif tok.type in (tokenize.NEWLINE, tokenize.ENDMARKER) and strings:
            groups.append(strings)
            strings = []
    for run in (strings, comments):
        if run:
            groups.append(run)
    for run in groups:
        pieces, lines = [], []
        for tok in run:
            s = tok.string.lstrip("#") if tok.type == tokenize.COMMENT else tok.string
            for k, part in enumerate(s.split("\n")):
                pieces.append(part)
                lines.append(tok.start[0] + k)
        block, block_lines = [], []
        for part, n in zip(pieces + [""], lines + [lines[-1]]):
            if part.strip().strip("\"'").strip():
                block.append(part)
                block_lines.append(n)
            elif block:
                yield "\n".join(block), block_lines
                block, block_lines = [], []


def unquoted(text: str, *, python: bool = False) -> list[tuple[int, str]]:
    """``(line, sentence)`` of every attribution sentence whose paragraph cites no quote.

    Parameters
    ----------
    text : str
        A Markdown page (``python=False``) or a Python module's source (``python=True``:
        only its comments, docstrings and string literals are read).
    """
    out = []
    if python:
        for para, lines in _python_paragraphs(text):
            literals = [m.group(0).strip("\"'") for m in KEY_LITERAL.finditer(para)]
            out += _check_paragraph(para, lines[0], offsets=lines, extra=literals)
    else:
        for para, start in _markdown_paragraphs(text):
            out += _check_paragraph(para, start)
    return sorted(set(out))


def scan(path, *, root=None) -> list[Attribution]:
    """The unquoted attribution sentences of one file (``.py`` or Markdown)."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such file to scan for attributions: {path}")
    text = path.read_text(encoding="utf-8")
    name = str(path.relative_to(root)) if root else str(path)
    return [Attribution(name, line, s)
            for line, s in unquoted(text, python=path.suffix == ".py")]


def main(argv=None) -> int:
    """``python -m trackbook.quotes.attributions FILE...``: list, exit 1 when any."""
    argv = sys.argv[1:] if argv is None else argv
    if not argv:
        print("usage: python -m trackbook.quotes.attributions FILE...", file=sys.stderr)
        return 2
    found = []
    for name in argv:
        try:
            found += scan(name)
        except (FileNotFoundError, UnicodeDecodeError) as e:
            print(f"error: {e}", file=sys.stderr)
            return 2
    for a in found:
        print(a)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
