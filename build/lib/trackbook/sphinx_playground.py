"""Sphinx extension: the HTML book's playgrounds live, with no kernel and no network.

* Sets ``TRACKBOOK_BOOK_BUILD=1`` before the chapters execute (the kernels inherit the
  environment), so :class:`trackbook.playground.Playground` displays its static page: the runs
  for a few values of each knob precomputed and embedded with the viewer module, which works
  from ``file://`` and over http.
* Stops every request that would leave the machine: MyST-NB's ipywidgets loaders (require.js and
  the embed script from CDNs) and sphinx-thebe's loader (``const THEBE_JS_URL = ...``, which
  also raised a script error on some pages); any other remote script or stylesheet is dropped
  from the pages, so the book shows the same thing offline.

Enabled in ``_config.yml`` (``sphinx.extra_extensions``).
"""

from __future__ import annotations

import os

from .playground.core import BOOK_ENV, VIEWER_CSS, VIEWER_JS


def _remote(name) -> bool:
    name = str(name or "")
    return name.startswith(("http://", "https://", "//"))


def _drop(asset) -> bool:
    name = getattr(asset, "filename", asset)
    body = (getattr(asset, "attributes", {}) or {}).get("body", "") or ""
    return _remote(name) or "thebe" in str(name or "").lower() or "THEBE" in body


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


def setup(app):
    os.environ[BOOK_ENV] = "1"
    app.connect("config-inited", _configure, priority=900)
    app.connect("html-page-context", _page_context, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True,
            "viewer": str(VIEWER_JS), "css": str(VIEWER_CSS)}
