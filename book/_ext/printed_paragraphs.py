"""Paragraphs a page's code prints, and the numbers in each.

A concept chapter's numbers belong in tables and figures; what a code cell prints as running
text carries at most three. A *printed paragraph* is a block of a code cell's visible text
output (a stream, or the ``text/plain`` of a result) between blank lines, or a paragraph of a
``text/markdown`` result. Not paragraphs: a table (HTML, or Markdown rows between ``|``), a
block that is an array or a matrix (every line brackets and numbers), the outputs of cells the
reader never sees (``remove-output``, ``remove-cell``), and the exercises a cell shows with
``exercises.show`` (hand-written text, as a worked example in the prose is). A *number* is a decimal numeral standing alone
(``0.583``, ``-3``, ``12 %``), not the digits inside a name (``x1``, ``precision20``).

The executed pages come from the build's execution cache (``_build/.jupyter_cache``, filled by
``execute_pages.py`` or ``jupyter-book build .``).

    python book/_ext/printed_paragraphs.py            # every concept chapter's offenders
    python book/_ext/printed_paragraphs.py book/06_kalman.md
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CACHE = ROOT / "_build" / ".jupyter_cache"
MAX_NUMBERS = 3
HIDDEN = {"remove-output", "remove-cell"}

NUMBER = re.compile(r"(?<![\w.])[-+−]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?(?![\w])")
#: a line of an array's repr: brackets, numerals, separators and nothing else
_ARRAY_LINE = re.compile(r"^[\s\[\](),.\-+−\deE]*(?:nan|inf)?[\s\[\](),.\-+−\deE]*$")
_ANSI = re.compile(r"\x1b\[[0-9;]*m")


def numbers(text: str) -> int:
    """How many stand-alone numerals ``text`` holds."""
    return len(NUMBER.findall(text))


def _is_array(block: str) -> bool:
    """An array's repr or a Markdown table: not running text."""
    lines = [ln for ln in block.splitlines() if ln.strip()]
    # an array's repr has brackets; a bare line of numbers (print(a, b, c, d)) is text
    return bool(lines) and ((all(_ARRAY_LINE.match(ln) for ln in lines) and "[" in block)
                            or all(ln.lstrip().startswith("|") for ln in lines))


def paragraphs(cell) -> list[str]:
    """The printed paragraphs of one executed code cell (a ``nbformat`` node)."""
    tags = set(cell.get("metadata", {}).get("tags", []))
    source = "".join(cell.get("source", ""))
    if tags & HIDDEN or "exercises.show(" in source:
        return []
    found, streams = [], {}
    for out in cell.get("outputs", []):
        if out.get("output_type") == "stream":
            # one text per stream: a log line on stderr between two prints must not split
            # what stdout prints into separate paragraphs
            text = out.get("text", "")
            streams[out.get("name")] = streams.get(out.get("name"), "") + (
                "".join(text) if isinstance(text, list) else text)
            continue
        elif out.get("output_type") in ("execute_result", "display_data"):
            data = out.get("data", {})
            if "text/html" in data or "image/png" in data or "image/svg+xml" in data:
                continue        # a table or a figure
            texts = [data.get("text/markdown", data.get("text/plain", ""))]
        else:
            continue
        for text in texts:
            text = _ANSI.sub("", "".join(text) if isinstance(text, list) else text)
            found += _blocks(text)
    for text in streams.values():
        found += _blocks(_ANSI.sub("", text))
    return found


def _blocks(text: str) -> list[str]:
    return [b.strip() for b in re.split(r"\n\s*\n", text) if b.strip() and not _is_array(b)]


def offenders(notebook) -> list[tuple[int, str]]:
    """``(code cell index, paragraph)`` for each printed paragraph with too many numbers."""
    hits, k = [], -1
    for cell in notebook.cells:
        if cell.cell_type != "code":
            continue
        k += 1
        hits += [(k, p) for p in paragraphs(cell) if numbers(p) > MAX_NUMBERS]
    return hits


def executed(page: Path, cache: Path = CACHE):
    """The executed notebook of ``page`` from the build's cache, or None when it has none
    (never executed, or executed before its code last changed)."""
    from jupyter_cache import get_cache
    from jupyter_cache.readers import get_reader

    if not cache.is_dir():
        return None
    store = get_cache(cache)
    nb = get_reader({"name": "myst_nb_md", "type": "plugin"})(str(page))
    try:
        _, merged = store.merge_match_into_notebook(nb)
    except KeyError:
        return None
    return merged


def main(argv: list[str]) -> int:
    pages = [Path(a).resolve() for a in argv] or sorted((ROOT / "book").glob("[0-9][0-9]_*.md"))
    total = 0
    for page in pages:
        nb = executed(page)
        if nb is None:
            print(f"{page.name}: not in the execution cache (run execute_pages.py first)")
            continue
        hits = offenders(nb)
        total += len(hits)
        print(f"{page.name}: {len(hits)}")
        for k, p in hits:
            print(f"  code cell {k}: " + p.replace("\n", " / ")[:160])
    print(f"total {total}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
