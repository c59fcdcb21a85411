"""Sphinx extension: serve MathJax from the built book instead of a CDN, and load nothing else
from one (sphinx-thebe's scripts are dropped).

The HTML book must show its equations on a machine without internet (a classroom behind a
firewall, CI). MathJax 2.7 ships inside the ``jupyter-server-mathjax`` package on PyPI; this
extension points Sphinx at a copy under ``_static/mathjax`` and copies it there after the
build. Enabled in ``_config.yml`` (``sphinx.extra_extensions``).
"""

from __future__ import annotations

import shutil
from pathlib import Path

MATHJAX_PATH = "mathjax/MathJax.js?config=TeX-AMS-MML_HTMLorMML-full"


def mathjax_source() -> Path:
    """The folder holding ``MathJax.js`` in the installed ``jupyter-server-mathjax``."""
    import jupyter_server_mathjax

    return Path(jupyter_server_mathjax.__file__).parent / "static"


def _configure(app, config):
    config.mathjax_path = MATHJAX_PATH
    # MathJax 2 reads its configuration from this block; process what Sphinx marks as maths.
    config.mathjax2_config = {
        # Sphinx writes \( \) and \[ \]; the quoted passages of the papers ({quote} role) keep
        # the seeds' $ $ and $$ $$ verbatim, typeset where they are marked mathjax_process
        "tex2jax": {"inlineMath": [["\\(", "\\)"], ["$", "$"]],
                    "displayMath": [["\\[", "\\]"], ["$$", "$$"]],
                    "processEscapes": True, "processEnvironments": True,
                    "processClass": "tex2jax_process|mathjax_process|math|output_area",
                    "ignoreClass": "tex2jax_ignore|mathjax_ignore|document"},
        "TeX": {"extensions": ["AMSmath.js", "AMSsymbols.js"]},
        # the package ships the STIX-Web fonts only (not MathJax's TeX fonts)
        # MathJax 2 probes web fonts against a "MathJax_Blank" face whose src is
        # url('about:blank'): from file:// Chromium refuses it (a CORS console error on every
        # page); local() asks for no file at all and falls back the same way
        "HTML-CSS": {"availableFonts": [], "preferredFont": None, "webFont": "STIX-Web",
                     "imageFont": None,
                     "styles": {"@font-face": {"font-family": "MathJax_Blank",
                                               "src": "local('MathJax_Blank')"}}},
        "SVG": {"font": "STIX-Web"},
        "showMathMenu": False,
        "messageStyle": "none",
    }
    config.mathjax3_config = None
    # MyST would add a MathJax 3 ``window.MathJax`` block, which MathJax 2 takes as its whole
    # configuration; the block above already does that job.
    if "myst_update_mathjax" in config:
        config.myst_update_mathjax = False


def _copy(app, exception):
    if exception is None and app.builder.format == "html":
        shutil.copytree(mathjax_source(), Path(app.outdir) / "_static" / "mathjax",
                        dirs_exist_ok=True)


def _drop_thebe(app, pagename, templatename, context, doctree):
    """Remove sphinx-thebe's scripts from every page.

    Jupyter Book always loads sphinx-thebe, which adds an inline ``const THEBE_JS_URL`` block
    (twice: a script error on the second) pointing at a CDN. The book has no live-code
    buttons, so the scripts are dropped rather than repaired.
    """
    scripts = context.get("script_files")
    if not scripts:
        return
    keep = [js for js in scripts
            if "thebe" not in str(getattr(js, "filename", js) or "").lower()
            and "THEBE" not in str(getattr(js, "attributes", {}).get("body", ""))]
    scripts[:] = keep


def setup(app):
    app.connect("config-inited", _configure, priority=900)
    app.connect("html-page-context", _drop_thebe)
    app.connect("build-finished", _copy)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
