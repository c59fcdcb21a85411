"""The notation page holds the concept chapters to one symbol, one meaning.

What is read
------------
* **The page** (``book/appendix_notation.md``): the rows of every table whose header's first
  cell is ``symbol``. The first cell of a row holds the row's symbol(s): maths (``$…$``), or an
  upright name written as text (``AUC``). Other tables (the local uses of a letter, the papers'
  letters, the papers) are not read.
* **A chapter** (``book/[0-9][0-9]_*.md``, the concept chapters): its prose maths, i.e.
  ``$…$`` (which may wrap a line), ``$$…$$`` and ``{math}`` blocks and roles, with front
  matter, code cells, code blocks and inline code removed first (a figure label is code).
  Inline maths in a clause that says a paper *writes* it ("Isard and Blake write the samples
  $s^{(i)}$") is that paper's spelling, not the book's, and is left out; a clause ends at a
  semicolon, a bracket, a full stop or a blank line.

What a symbol is (the normalisation)
------------------------------------
A piece of maths is cut into symbols; each is a key ``(font, base, label, decoration)``:

* ``base`` is one Latin letter or one Greek letter command (``\\lambda``, ``\\Phi``, ``\\ell``;
  ``\\phi``/``\\varphi``, ``\\epsilon``/``\\varepsilon``, ``\\theta``/``\\vartheta`` are one
  letter), or, for an upright name of two or more letters (``\\mathrm{IoU}``), the name.
  A run of italic letters is one symbol per letter (``KHP`` is ``K``, ``H``, ``P``);
* ``font``: italic (``""``), ``bf`` (``\\mathbf``, ``\\boldsymbol``), ``rm`` (an upright
  letter, ``\\mathrm{P}``), ``cal``, ``bb``. ``\\mathbf{x}``, ``\\mathrm{x}``,
  ``\\mathcal{X}`` are not ``x`` (the book writes no ``\\mathcal``: its offline
  fonts have no script alphabet);
* ``label``: an **upright** subscript or superscript (``\\lambda_{\\mathrm{UT}}``,
  ``\\eta_\\text{tmpl}``, ``q^\\mathrm{O}``), or an italic one that is a word of three or more
  letters (``h_{ref}``), is part of the name: ``\\lambda_{\\mathrm{UT}}`` is not ``\\lambda``.
  Any other script is an index or an exponent: it is dropped (``x_k`` is ``x``, ``M_{00}`` is
  ``M``, ``x^{(i)}`` is ``x``), and its letters are symbols of the chapter in their turn (the
  page's own first cells do not count them). ``^T``, ``^\\top``, ``^*``, ``^H``, ``^+``, ``^-``
  and numbers are not symbols. An upright script on a bracket labels the expression
  (``p(z \\mid x)_\\mathrm{color}``) and is not a symbol;
* ``decoration``: ``\\hat``, ``\\bar``, ``\\tilde``, ``\\check``, ``\\dot``, ``\\ddot`` (with
  ``\\widehat``, ``\\overline``, ``\\widetilde``) and a prime. A decorated symbol is on the page
  if the page lists it decorated or lists its bare letter (``\\hat x_k`` is covered by ``x``);
  two rows clash when they list the same full key, decoration included.

Text inside ``\\text{…}`` at the top level (a word in a formula), environment names, tags, the
functions of ``FUNCTIONS`` and every command that is not a letter (operators, spacing,
delimiters) are not symbols.

The checks
----------
(a) no key is the symbol of two rows of the page;
(b) every symbol of a concept chapter's maths is on the page, but for the short allow-list
    ``FREE`` (running indices and counts, universal constants) and the functions of
    ``FUNCTIONS``;
(c) the checks' own checks: a hand-made page with a clash fails (a), a hand-made chapter with
    a symbol that page lacks fails (b), and the normalisation is pinned on hand-worked cases;
(d) the chapter a row names as introducing its symbol uses that symbol (or a decorated form of
    it) in its maths; that it is the *first* chapter to use it cannot be checked, since an
    earlier chapter may use the letter locally for something else;
(e) the spellings the book retired (``RETIRED``: the Kalman measurement $y_k$, the sigma points
    $\\chi_i$, the Förstner distance $d_F$ with an italic F) do not come back in the book's maths
    of a concept chapter or a case study.

What it cannot see: a letter used in a chapter with a meaning other than its row's. Those
uses are the page's table of letters with local uses, kept by hand; (e) guards the renames
that matter most against coming back.

Only text is read; nothing is executed.
"""
from __future__ import annotations

import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
BOOK = ROOT / "book"
PAGE = BOOK / "appendix_notation.md"


def chapters() -> list[pathlib.Path]:
    """The concept chapters, whose maths the page must cover.

    The case studies are not among them: they print the papers' numbered equations in the
    papers' own letters (the page's last tables give the book's letter for each), and the
    book's letters in their prose are the concept chapters'.
    """
    return sorted(BOOK.glob("[0-9][0-9]_*.md"))


#: Letters free in every chapter, with why: running indices and counts whose range the
#: sentence gives, and universal constants. The page's opening says the same in words.
FREE = {
    ("", "i", "", ""): "running index (particle, pixel, sample)",
    ("", "j", "", ""): "second running index",
    ("", "k", "", ""): "time step or running index",
    ("", "l", "", ""): "third running index",
    ("", "n", "", ""): "a count or running index, given where it is used",
    ("", "t", "", ""): "frame number, time",
    ("", "u", "", ""): "histogram bin",
    ("", "e", "", ""): "Euler's number, base of exp",
    ("", "pi", "", ""): "the constant 3.14159 (an indexed pi is a probability: the page's local letters)",
    ("rm", "d", "", ""): "differential",
    ("rm", "e", "", ""): "Euler's number, upright",
    ("rm", "i", "", ""): "the imaginary unit",
    ("", "O", "", ""): "Landau's order, O(n log n)",
}

#: Standard functions written upright, which the page need not list.
FUNCTIONS = {"atan2", "diag", "tr", "Var", "mean", "median", "DFT", "IDFT", "const", "rank"}

_GREEK = set("""alpha beta gamma delta epsilon varepsilon zeta eta theta vartheta iota kappa
lambda mu nu xi pi varpi rho varrho sigma varsigma tau upsilon phi varphi chi psi omega
Gamma Delta Theta Lambda Xi Pi Sigma Upsilon Phi Psi Omega ell""".split())
_SAME_LETTER = {"varepsilon": "epsilon", "vartheta": "theta", "varphi": "phi",
                "varrho": "rho", "varsigma": "sigma", "varpi": "pi"}
_DECORATIONS = {"hat": "hat", "widehat": "hat", "bar": "bar", "overline": "bar",
                "tilde": "tilde", "widetilde": "tilde", "check": "check", "dot": "dot",
                "ddot": "ddot"}
_FONTS = {"mathbf": "bf", "boldsymbol": "bf", "bm": "bf", "mathcal": "cal", "mathbb": "bb",
          "mathrm": "rm", "text": "rm", "textrm": "rm", "operatorname": "rm", "rm": "rm",
          "mathsf": "rm", "texttt": "rm", "mathit": ""}

Key = tuple  # (font, base, label, decoration)


def _group(s: str, i: int) -> tuple[str, int]:
    """The argument starting at ``s[i]`` (a ``{…}`` group, a command or one character)."""
    while i < len(s) and s[i] == " ":
        i += 1
    if i >= len(s):
        return "", i
    if s[i] == "{":
        depth = 0
        for j in range(i, len(s)):
            depth += {"{": 1, "}": -1}.get(s[j], 0)
            if depth == 0:
                return s[i + 1:j], j + 1
        return s[i + 1:], len(s)
    if s[i] == "\\":
        m = re.match(r"\\([A-Za-z]+|.)", s[i:])
        if m.group(1) in _FONTS:                   # \text{tmpl} as a script: keep its group
            arg, j = _group(s, i + m.end())
            return m.group(0) + "{" + arg + "}", j
        return m.group(0), i + m.end()
    return s[i], i + 1


def symbols(tex: str, scripts: bool = True) -> list[Key]:
    """Cut one piece of maths into symbol keys (see the module docstring).

    With ``scripts=False`` the letters of italic scripts (indices, exponents) are left out:
    the page's ``x_k`` lists ``x``, not ``k``.
    """
    out: list[Key] = []
    i = 0
    while i < len(tex):
        c = tex[i]
        if c == "\\":
            m = re.match(r"\\([A-Za-z]+|.)", tex[i:])
            name, i = m.group(1), i + m.end()
            if name in _DECORATIONS:
                arg, i = _group(tex, i)
                inner = symbols(arg, scripts)
                if inner:
                    f, b, lab, _ = inner[0]
                    inner[0] = (f, b, lab, _DECORATIONS[name])
                    i = _labels(tex, scripts, i, inner, 0)
                out += inner
            elif name in ("begin", "end", "tag", "label", "hspace", "vspace", "kern"):
                arg, i = _group(tex, i)            # an environment's name, a tag's number
            elif name in ("text", "textrm", "texttt", "mbox"):
                arg, i = _group(tex, i)            # words of a sentence, or code: not symbols
            elif name in _FONTS:
                arg, i = _group(tex, i)
                font = _FONTS[name]
                word = re.sub(r"\s+", "", arg)
                if font == "rm" and word in FUNCTIONS:
                    continue
                if font == "rm" and re.fullmatch(r"[A-Za-z][A-Za-z0-9]+", word):
                    key = ["rm", word, "", ""]
                    out.append(tuple(key))
                    i = _labels(tex, scripts, i, out, len(out) - 1)
                elif font == "rm" and not re.search(r"[A-Za-z]", word):
                    continue
                else:
                    inner = symbols(arg, scripts)
                    inner = [((font or f) if f == "" else f, b, lab, d)
                             for f, b, lab, d in inner]
                    start = len(out)
                    out += inner
                    if inner:
                        i = _labels(tex, scripts, i, out, start)
            elif name in _GREEK:
                out.append(("", _SAME_LETTER.get(name, name), "", ""))
                i = _labels(tex, scripts, i, out, len(out) - 1)
            # any other command (operators, spacing, unknown) is not a symbol
        elif c.isalpha():
            out.append(("", c, "", ""))
            i = _labels(tex, scripts, i + 1, out, len(out) - 1)
        elif c in "_^":
            # a script after a group or a bracket: an upright one labels the expression
            # (p(z \mid x)_\mathrm{color}), an italic one holds symbols
            arg, i = _group(tex, i + 1)
            if scripts and not re.match(r"\s*\\(mathrm|text|textrm|operatorname)\b", arg):
                out += _script_symbols(arg, c)
        else:
            i += 1
    return out


def _script_symbols(arg: str, kind: str) -> list[Key]:
    """The symbols inside an italic (index or exponent) script."""
    if kind == "^" and re.fullmatch(r"\s*(T|\\top|\\intercal|\*|\+|-|H)\s*", arg):
        return []
    return symbols(arg)


def _labels(tex: str, scripts: bool, i: int, out: list, at: int) -> int:
    """Read the scripts and primes after the symbol ``out[at]``: upright ones join its label."""
    while i < len(tex):
        while i < len(tex) and tex[i] == " ":
            i += 1
        if i < len(tex) and tex[i] == "'":
            f, b, lab, d = out[at]
            out[at] = (f, b, lab, d or "prime")
            i += 1
            continue
        if i >= len(tex) or tex[i] not in "_^":
            return i
        kind = tex[i]
        arg, i = _group(tex, i + 1)
        # an upright name at the head of a script is a label (h_{\mathrm{ref},u}: label "ref",
        # index u)
        m = re.match(r"\s*\\(mathrm|text|textrm|operatorname|rm|mathsf)\s*\{([A-Za-z0-9 ]*)\}(.*)",
                     arg, re.S) or re.match(r"()([A-Za-z]{3,})()$", arg.strip())
        if m and re.search(r"[A-Za-z]", m.group(2)):
            f, b, lab, d = out[at]
            out[at] = (f, b, lab + kind + m.group(2).replace(" ", ""), d)
            if scripts:
                out += _script_symbols(m.group(3), kind)
        elif scripts:
            out += _script_symbols(arg, kind)
    return i


_FENCE = re.compile(r"^(`{3,}|~{3,}|:{3,})(.*)$")


#: A clause ends at a semicolon, a bracket, a full stop before a space (not the one of "et al.",
#: "e.g." or "i.e.") or a blank line.
_CLAUSE = re.compile(r"[;()\[\]]|(?<!\bal)(?<!\be\.g)(?<!\bi\.e)\.\s|\n\s*\n")
#: Inline maths in a clause that says a paper (or a library) *writes* it is that paper's
#: spelling, which the book quotes beside its own symbol: "(Isard and Blake write the samples
#: $s^{(i)}$ …)". Such maths is not the book's notation. The verb needs a subject in the clause
#: that is not the book's own voice: "we write $\Gamma$", "this book writes $D$", an imperative
#: "write $e^+$ for …" and a bare "(written $z$" are the book's spelling and are read.
_PAPER_SPELLING = re.compile(r"(?P<subject>[A-Za-z}][\w.}]*)\s+(?:write|writes|wrote|spells?)\b",
                             re.I)
_BOOK_VOICE = {"we", "book", "chapter", "here", "i", "let", "us", "to", "and", "then", "also"}


def _a_paper_writes(clause: str) -> bool:
    """Whether a clause's last "write" has a subject other than the book (``_PAPER_SPELLING``)."""
    found = list(_PAPER_SPELLING.finditer(clause))
    return bool(found) and found[-1].group("subject").lower().strip(".") not in _BOOK_VOICE


def prose_maths(text: str, papers: bool = False) -> list[str]:
    """The maths of a Markdown page's prose: ``$…$``, ``$$…$$``, ``{math}`` blocks and roles.

    Code cells, code blocks and inline code are removed first; directives that hold prose
    (admonitions, notes, figures' captions) are kept. Inline maths that a clause gives as a
    paper's spelling (``_PAPER_SPELLING``) is left out unless ``papers`` is true.
    """
    lines, keep, fence, maths = text.splitlines(), [], None, []
    block: list[str] | None = None
    for line in lines:
        m = _FENCE.match(line.strip())
        if fence is None and m:
            info = m.group(2).strip()
            if info.startswith("{math}"):
                fence, block = m.group(1), []
            elif info.startswith("{") and not re.match(r"\{(code-cell|code-block|code|"
                                                       r"literalinclude|bibliography)\}", info):
                keep.append("")                    # a prose directive: its body stays
                continue
            else:
                fence = m.group(1)
                block = None
            continue
        if fence is not None:
            if line.strip() == fence:
                if block is not None:
                    maths.append("\n".join(l for l in block if not l.strip().startswith(":")))
                fence, block = None, None
            elif block is not None:
                block.append(line)
            continue
        keep.append(line)
    prose = "\n".join(keep)
    prose = re.sub(r"^---\n.*?\n---\n", "", prose, flags=re.S)      # front matter
    maths += re.findall(r"\{math\}`([^`]*)`", prose)
    prose = re.sub(r"(`+).*?\1", " ", prose, flags=re.S)            # inline code and roles
    prose = prose.replace(r"\$", " ")
    maths += re.findall(r"\$\$(.+?)\$\$", prose, flags=re.S)
    prose = re.sub(r"\$\$(.+?)\$\$", " ", prose, flags=re.S)
    for m in re.finditer(r"\$((?:[^$\n]|\n(?!\s*\n))+?)\$", prose):   # may wrap a line
        before = _CLAUSE.split(prose[max(0, m.start() - 400):m.start()])[-1]
        if papers or not _a_paper_writes(before):
            maths.append(m.group(1))
    return maths


def chapter_symbols(text: str) -> dict[Key, str]:
    """Every symbol of a page's prose maths, with the first piece of maths it occurs in."""
    found: dict[Key, str] = {}
    for tex in prose_maths(text):
        for key in symbols(tex):
            found.setdefault(key, tex.strip()[:80])
    return found


def page_rows(text: str, header: str = "symbol") -> list[tuple[int, set[Key], str]]:
    """The page's rows under a first header cell ``header``: (line number, the keys of the
    first cell, the line)."""
    rows, reading = [], False
    lines = text.splitlines()
    for n, line in enumerate(lines, 1):
        if not line.startswith("|"):
            reading = False
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if n < len(lines) and re.fullmatch(r"\|[-:| ]+\|?", lines[n].strip()):   # a header
            reading = cells[0].lower() == header
            continue
        if not reading or re.fullmatch(r"[-: ]*", cells[0]):
            continue
        first = cells[0]
        tex = re.findall(r"\$([^$]+)\$", first)
        keys = set()
        for piece in tex:
            keys |= set(symbols(piece, scripts=False))
        rest = re.sub(r"\$[^$]+\$", " ", first)
        for word in re.findall(r"[A-Za-z][A-Za-z0-9@]+", rest):
            keys.add(("rm", word, "", ""))
        rows.append((n, keys, line))
    return rows


def clashes(text: str) -> list[str]:
    """Check (a): the keys listed in more than one row of the page."""
    seen: dict[Key, int] = {}
    bad = []
    for n, keys, _line in page_rows(text):
        for key in keys:
            if key in seen:
                bad.append(f"{_show(key)} on lines {seen[key]} and {n}")
            else:
                seen[key] = n
    return bad


def missing(page: str, chapter: str) -> dict[Key, str]:
    """Check (b): a chapter's symbols that neither the page nor ``FREE`` covers."""
    listed = set().union(*(keys for _, keys, _ in page_rows(page))) if page_rows(page) else set()
    out = {}
    for key, where in chapter_symbols(chapter).items():
        bare = key[:3] + ("",)
        if key in listed or bare in listed:
            continue
        if bare in FREE:
            continue
        out[key] = where
    return out


def _show(key: Key) -> str:
    font, base, label, deco = key
    s = ("\\" + base) if len(base) > 1 and font != "rm" else base
    if font:
        s = f"\\math{font}{{{s}}}"
    if deco:
        s = f"\\{deco}{{{s}}}"
    return s + label


#: Spellings the book gave up for one symbol, one meaning, with the symbol that replaced them.
#: Each is a pattern on one piece of the book's maths (a paper's spelling is not read). The
#: Kalman filter's index is k: a y with a frame index t can be a vertical coordinate, y_t^i.
RETIRED = {
    r"(?<![\\A-Za-z])y_\{?k\b": "the Kalman measurement is z_k; y is the vertical coordinate",
    r"\\(?:chi|mathcal\{\\chi\})_": "the sigma points are a bold chi, \\boldsymbol\\chi_i; a plain chi is the chi-square",
    r"(?<![\\A-Za-z])d_\{?F\b": "the Förstner distance is d_\\mathrm{F}",
}


def retired(text: str) -> list[str]:
    """Check (e): the book's maths of a page that uses a spelling of ``RETIRED``."""
    return [f"${tex.strip()[:60]}$: {why}" for tex in prose_maths(text)
            for pattern, why in RETIRED.items() if re.search(pattern, tex)]


def not_where_named(page: str, texts: dict[str, str]) -> list[str]:
    """Check (d): rows whose introducing chapter (``{doc}`name```) does not use their symbol.

    ``texts`` maps a chapter's name to its text. Rows written as words (``AUC``) and rows
    naming a page outside ``texts`` are not checked.
    """
    used = {name: chapter_symbols(text) for name, text in texts.items()}
    bad = []
    for n, _keys, line in page_rows(page):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        named = re.findall(r"\{doc\}`([^`<>]+)`", cells[2] if len(cells) > 2 else "")
        tex = re.findall(r"\$([^$]+)\$", cells[0])
        if not named or not tex or named[0] not in used:
            continue
        keys = set().union(*(symbols(piece, scripts=False) for piece in tex))
        found = used[named[0]]
        if not any(k in found or any(f[:3] == k[:3] for f in found) for k in keys):
            bad.append(f"line {n}: {cells[0]} is not in the maths of {named[0]}")
    return bad


# --------------------------------------------------------------------------------------------
# the checks


def test_no_symbol_in_two_rows():
    assert clashes(PAGE.read_text(encoding="utf-8")) == []


@pytest.mark.parametrize("path", chapters(), ids=lambda p: p.stem)
def test_every_symbol_of_a_chapter_is_on_the_page(path):
    gaps = missing(PAGE.read_text(encoding="utf-8"), path.read_text(encoding="utf-8"))
    assert not gaps, "\n".join(f"{_show(k)}   in ${w}$" for k, w in sorted(gaps.items()))


def test_every_letter_with_local_uses_has_its_row():
    """The table of local uses names letters the page defines: no use hides behind it."""
    page = PAGE.read_text(encoding="utf-8")
    local = page_rows(page, "letter")
    rows = set().union(*(keys for _, keys, _ in page_rows(page)))
    assert local, "the page has no table of letters with local uses"
    assert [line for _, keys, line in local if not keys <= rows | set(FREE)] == []


def test_each_row_is_used_where_it_says_it_is_introduced():
    texts = {p.stem: p.read_text(encoding="utf-8") for p in chapters()}
    assert not_where_named(PAGE.read_text(encoding="utf-8"), texts) == []


@pytest.mark.parametrize("path", chapters() + sorted(BOOK.glob("case_study_*.md")),
                         ids=lambda p: p.stem)
def test_no_retired_spelling_comes_back(path):
    assert retired(path.read_text(encoding="utf-8")) == []


# --------------------------------------------------------------------------------------------
# the checks' own checks, on hand-made text

_PAGE = """\
| symbol | meaning | chapter |
|---|---|---|
| $\\mathbf{x}$ | Kalman state | Kalman |
| $x$ | a coordinate | boxes |
| $\\lambda_{\\mathrm{UT}}$ | sigma-point scaling | sigma points |
| $\\lambda$ | ridge regulariser | correlation filters |
| $\\hat y$ | DFT of the desired response | correlation filters |
| $y$ | an image point | mean shift |
| NEES | normalised estimation error squared | design |

| short name | paper |
|---|---|
| $K$ | not a symbol row |
"""


def test_normalisation_by_hand():
    assert symbols(r"x_k") == [("", "x", "", ""), ("", "k", "", "")]
    assert symbols(r"x_k", scripts=False) == [("", "x", "", "")]
    assert symbols(r"\mathbf{x}_k^-", scripts=False) == [("bf", "x", "", "")]
    assert symbols(r"\lambda_{\mathrm{UT}}") == [("", "lambda", "_UT", "")]
    assert symbols(r"\eta_\text{tmpl}") == [("", "eta", "_tmpl", "")]
    assert symbols(r"\hat x^{(i)}") == [("", "x", "", "hat"), ("", "i", "", "")]
    assert symbols(r"\mu_{\max}") == [("", "mu", "", "")]
    assert symbols(r"P^T") == [("", "P", "", "")]
    assert symbols(r"\mathrm{IoU}(B_p, B_g)") == [("rm", "IoU", "", ""), ("", "B", "", ""),
                                                   ("", "p", "", ""), ("", "B", "", ""),
                                                   ("", "g", "", "")]
    assert symbols(r"\varphi + \phi") == [("", "phi", "", "")] * 2
    assert symbols(r"\mathrm{P}") == [("rm", "P", "", "")]


def test_the_hand_made_page_is_clean():
    assert clashes(_PAGE) == []
    # the papers' table is not read: its K is not a symbol of the page
    assert ("", "K", "", "") not in set().union(*(k for _, k, _ in page_rows(_PAGE)))


def test_a_clash_is_caught():
    page = _PAGE + "\n| symbol | meaning |\n|---|---|\n| $y_k$ | Kalman measurement |\n"
    assert clashes(page) == ["y on lines 8 and 17"]
    page = _PAGE + "\n| symbol | meaning |\n|---|---|\n| $\\hat y$ | an estimate |\n"
    assert len(clashes(page)) == 1
    # a different decoration, font or upright label is a different symbol
    page = _PAGE + "\n| symbol | meaning |\n|---|---|\n| $\\mathrm{y}$, $\\lambda_\\text{r}$ | two |\n"
    assert clashes(page) == []


def test_a_missing_symbol_is_caught():
    chapter = ("# A chapter\n\nThe state $\\mathbf{x}_k$ at $\\hat y_t$ with $\\lambda$ and "
               "$\\mathrm{NEES}$ over pixels $i$.\n\n"
               "```{code-cell} ipython3\nplt.xlabel('$\\\\kappa$')\n```\n\n"
               "$$\n\\sum_i \\Gamma_i \\bar x\n$$\n")
    gaps = missing(_PAGE, chapter)
    # Gamma is on no row; the bar over x falls back to x; kappa is only in a code cell
    assert set(gaps) == {("", "Gamma", "", "")}
    # a paper's spelling, in a clause that says the paper writes it, is not the book's symbol
    assert missing(_PAGE, "The state $x$ (Lee et al. write $\\Gamma$; the book $x$).") == {}
    assert set(missing(_PAGE, "Lee et al. use it; here $\\Gamma$ is new.")) == {
        ("", "Gamma", "", "")}
    # a bold letter is not the italic one; an upright label makes a new symbol
    assert missing(_PAGE, "$\\mathbf{y}$ and $\\lambda_{\\mathrm{reg}}$") == {
        ("bf", "y", "", ""): "\\mathbf{y}",
        ("", "lambda", "_reg", ""): "\\lambda_{\\mathrm{reg}}"}
    # the book's own voice is the book's spelling: "we write", an imperative "write", "written"
    for text in ("Here we write $\\Gamma$ for the gain.", "Each expert errs; write $\\Gamma$.",
                 "The gain (written $\\Gamma$) moves it.", "This book writes $\\Gamma$."):
        assert set(missing(_PAGE, text)) == {("", "Gamma", "", "")}, text


def test_a_row_named_in_the_wrong_chapter_is_caught():
    page = ("| symbol | meaning | introduced in |\n|---|---|---|\n"
            "| $\\nu$ | innovation | {doc}`06_kalman` |\n| $S$ | its covariance | {doc}`06_kalman` |\n"
            "| AUC | a score | {doc}`00_introduction` |\n")
    texts = {"06_kalman": "The innovation $\\hat\\nu_k$ and its mean.", "00_introduction": ""}
    assert not_where_named(page, texts) == ["line 4: $S$ is not in the maths of 06_kalman"]


def test_a_retired_spelling_is_caught():
    assert retired("The measurement $y_k = Hx_k + v_k$ and $\\chi_i$, $d_F$.") == [
        "$y_k = Hx_k + v_k$: " + RETIRED[r"(?<![\\A-Za-z])y_\{?k\b"],
        "$\\chi_i$: " + RETIRED[r"\\(?:chi|mathcal\{\\chi\})_"],
        "$d_F$: " + RETIRED[r"(?<![\\A-Za-z])d_\{?F\b"]]
    # what replaced them, a y coordinate, the chi-square and a paper's own spelling, pass
    assert retired("$z_k$, $y$, $p_y$, $\\chi^2_d$, $d_\\mathrm{F}$ (Lee writes $y_k$).") == []
