"""Sphinx extension: the HTML book's playgrounds live, with no kernel and no network.

* Points ``IPYTHONDIR`` at a folder whose startup file installs :mod:`playground_export` in
  every kernel that executes a chapter (the kernels inherit the environment, the one way to
  reach them), so a :class:`trackbook.playground.Playground` or animation displayed there is
  the page :mod:`playground_export.export` writes; and sets ``TRACKBOOK_PLAYGROUND_DIR`` to
  ``<build dir>/.playground``: there the chapters' kernels write the playgrounds' run files and
  frame files (``files/``) and keep computed runs (``runs/``), so a rebuild reuses every run
  whose tracker code, clip and values did not change (:mod:`playground_export.static`). With
  ``TRACKBOOK_PLAYGROUND_BACKGROUND=1`` a page's runs are computed by a background process
  while the next pages execute (one such process at a time, two workers); the extension waits
  for them when the build ends.
* Writes, into each page, the page's path to ``_static/playground/`` (where the viewer finds
  the files), and at the end copies there every file a page names; figures get
  ``loading="lazy"`` (they load as the reader scrolls to them).
* Stops every request that would leave the machine: MyST-NB's ipywidgets loaders (require.js and
  the embed script from CDNs) and sphinx-thebe's loader (``const THEBE_JS_URL = ...``, which
  also raised a script error on some pages); any other remote script or stylesheet is dropped
  from the pages, so the book shows the same thing offline. The widget state MyST-NB embeds
  (unused: no ipywidgets manager runs on the pages) is dropped too.

Enabled in ``_config.yml`` (``sphinx.extra_extensions``).
"""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

from playground_export import add_startup
from playground_export.export import STATIC_BASE
from playground_export.static import BACKGROUND_ENV, OUT_ENV, PREFIX, wait_background
from trackbook.playground.data import VIEWER_CSS, VIEWER_JS

#: the folder of the built book that holds the playgrounds' files
STATIC_DIR = "_static/playground"
_NAME = re.compile(re.escape(PREFIX) + r"[0-9a-f]{8,40}\.(?:js|png)")
_LAZY = re.compile(r"<img (?![^>]*\bloading=)")


def _remote(name) -> bool:
    name = str(name or "")
    return name.startswith(("http://", "https://", "//"))


def _drop(asset) -> bool:
    name = getattr(asset, "filename", asset)
    attrs = getattr(asset, "attributes", {}) or {}
    body = attrs.get("body", "") or ""
    # MyST-NB embeds the kernel's widget state (a playground's model holds every frame as
    # JPEG: megabytes per page); nothing on the page reads it, the playgrounds draw themselves
    state = attrs.get("type") == "application/vnd.jupyter.widget-state+json"
    return state or _remote(name) or "thebe" in str(name or "").lower() or "THEBE" in body


def _configure(app, config):
    config.nb_ipywidgets_js = {}        # MyST-NB's default loads require.js + embed from CDNs


def _page_context(app, pagename, templatename, context, doctree):
    for key in ("script_files", "css_files"):
        if key in context:
            context[key] = [a for a in context[key] if not _drop(a)]
    # pydata-sphinx-theme logs "Got invalid theme mode" (a console error) on every page
    # when no default mode is set
    if not context.get("default_mode"):
        context["default_mode"] = "auto"
    body = context.get("body") or ""
    if STATIC_BASE in body and "pathto" in context:
        body = body.replace(STATIC_BASE, context["pathto"](STATIC_DIR + "/", 1))
    # figures load as the reader scrolls to them: a chapter's first load stays light
    context["body"] = _LAZY.sub('<img loading="lazy" ', body)


def store_dir(outdir) -> Path:
    """``<build dir>/.playground``: beside the HTML output, kept between builds."""
    return Path(outdir).parent / ".playground"


def copy_files(outdir) -> int:
    """Copy every playground file a page of ``outdir`` names into ``outdir/_static/
    playground``; returns how many. Raises ``FileNotFoundError`` naming a missing one."""
    outdir = Path(outdir)
    src = Path(os.environ.get(OUT_ENV) or store_dir(outdir)) / "files"
    dest = outdir / STATIC_DIR
    names = set()
    for page in outdir.rglob("*.html"):
        names.update(_NAME.findall(page.read_text(encoding="utf-8", errors="replace")))
    if names:
        dest.mkdir(parents=True, exist_ok=True)
    for name in sorted(names):
        if not (src / name).exists():
            raise FileNotFoundError(f"playground file {name} is named by a page but missing "
                                    f"from {src}: rebuild the book with every page executed.")
        shutil.copyfile(src / name, dest / name)
    return len(names)


def _finished(app, exception):
    if exception is None and app.builder.format == "html":
        wait_background(os.environ.get(OUT_ENV) or store_dir(app.outdir))
        copy_files(app.outdir)


def setup(app):
    # every kernel Jupyter Book starts for a chapter displays the playgrounds as pages
    os.environ["IPYTHONDIR"] = str(add_startup(store_dir(app.outdir) / "ipython"))
    os.environ.setdefault(OUT_ENV, str(store_dir(app.outdir)))
    os.environ[BACKGROUND_ENV] = "1"   # a page's runs compute while the next pages execute
    app.connect("config-inited", _configure, priority=900)
    app.connect("html-page-context", _page_context, priority=900)
    app.connect("build-finished", _finished)
    return {"parallel_read_safe": True, "parallel_write_safe": True,
            "viewer": str(VIEWER_JS), "css": str(VIEWER_CSS)}
