"""The book's table of contents as the tests read it: ``_toc.yml``'s pages and parts.

One reader for every test that needs the order (the table of contents is the teaching order):
the pages in order (root first, sections after their chapter) and each page's part caption.
"""
import re
from pathlib import Path

TOC = Path(__file__).resolve().parents[1] / "_toc.yml"
_CAPTION = re.compile(r'^\s*- caption:\s*"?(.+?)"?\s*$')
_FILE = re.compile(r"^\s*(?:root|- file):\s*(\S+)\s*$")


def files() -> list[str]:
    """Every page of ``_toc.yml`` in order, as written there (``book/03_hog``)."""
    return [m.group(1) for line in TOC.read_text().splitlines() if (m := _FILE.match(line))]


def stems() -> list[str]:
    """Every page's file stem in order (``03_hog``)."""
    return [f.split("/")[-1] for f in files()]


def captions() -> list[str]:
    """The parts' captions in order."""
    return [m.group(1) for line in TOC.read_text().splitlines() if (m := _CAPTION.match(line))]


def parts() -> dict[str, str]:
    """page stem -> the caption of its part (the root page, in no part, is left out)."""
    out, cur = {}, None
    for line in TOC.read_text().splitlines():
        if m := _CAPTION.match(line):
            cur = m.group(1)
        elif (m := _FILE.match(line)) and cur is not None:
            out[m.group(1).split("/")[-1]] = cur
    return out
