"""Sphinx: every figure a page's code draws gets an alt text that describes it.

MyST-NB names each image output by the SHA-256 of its PNG and leaves its ``alt`` empty, so
the HTML shows the file's path to a screen reader. While the pages execute, the book's
figure hook (``figure_check.py``) writes a description of each figure it shows to
``_build/.figure_alts/<sha256>.txt``; this extension puts that text on the image.

Enabled in ``_config.yml`` under ``sphinx: local_extensions``.
"""

from __future__ import annotations

from pathlib import Path

from docutils import nodes

#: Where the kernels of ``execute_pages.py`` write the descriptions (beside the build's
#: execution cache, so both come from the same execution).
ALTS = Path(__file__).resolve().parents[2] / "_build" / ".figure_alts"


def set_alt_texts(app, doctree, docname) -> None:
    """Give each image of ``doctree`` without an alt text the description of its figure."""
    for image in doctree.findall(nodes.image):
        if image.get("alt"):
            continue
        stem = Path(str(image.get("uri", ""))).stem
        described = ALTS / f"{stem}.txt"
        if described.is_file():
            image["alt"] = described.read_text(encoding="utf-8").strip()


def setup(app):
    app.connect("doctree-resolved", set_alt_texts)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
