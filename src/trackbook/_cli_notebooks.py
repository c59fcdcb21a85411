"""``trackbook notebooks``: the book's pages exported as notebooks for class use (the command
line's one subject that reads the book rather than runs a tracker)."""

from __future__ import annotations

from pathlib import Path

from . import _cli_output as _out
from ._cli_errors import CLIError


def _chapters(book: Path) -> list[Path]:
    # every page: the numbered chapters, the case studies, the unnumbered ones (where_next),
    # appendices, lab notes
    parts = [sorted(book.glob(g)) for g in ("[0-9][0-9]_*.md", "case_study_*.md",
                                            "appendix_*.md", "lab_notes_*.md")]
    rest = [p for p in sorted(book.glob("*.md")) if not any(p in q for q in parts)]
    return parts[0] + parts[1] + rest + parts[2] + parts[3]


def find_book(book=None) -> Path:
    """The folder of the book's chapters: ``--book`` if given; else ``./book``; else the
    chapters installed with the package (``trackbook/_book``, where an installed copy holds
    the repository's ``book/``, or that ``book/`` itself beside ``src/`` in an editable
    install)."""
    if book is not None:
        return Path(book)
    here = Path(__file__).resolve().parent
    for cand in (Path("book"), here / "_book", here.parents[1] / "book"):
        if _chapters(cand):
            return cand
    return here / "_book"


def cmd_notebooks(args) -> int:
    try:
        import jupytext
    except ImportError:
        raise CLIError("trackbook notebooks needs jupytext, which the book extra installs: "
                       "pip install 'trackbook[book]' (or pip install jupytext).") from None
    book = find_book(args.book)
    chapters = _chapters(book)
    if not chapters:
        raise ValueError(f"no chapters in {book}; pass --book FOLDER (the book/ folder of the "
                         "repository).")
    out = _out.check_out_dir(args.out)
    files = {md: out / (md.stem + ".ipynb") for md in chapters}
    # a notebook a student has edited is never replaced unless asked
    _out.refuse_existing(files.values(), args.force)
    _out.out_dir(out)
    for md, path in files.items():
        text = jupytext.writes(jupytext.read(md), fmt="ipynb")
        with _out.staged([path]) as tmp:
            tmp[path].write_text(text, encoding="utf-8")
        print(path)
    return 0
