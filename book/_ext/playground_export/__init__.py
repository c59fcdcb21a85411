"""The HTML book's playgrounds and animations: pages that run with no kernel and no network.

The library's :class:`~trackbook.playground.Playground` and
:class:`~trackbook.playground.animation.Animation` are Jupyter widgets and know nothing of the
book. In the book's build every chapter's kernel displays them as page fragments instead:
:func:`install` registers this package's pages with the kernel's IPython display formatter,
and :func:`add_startup` writes the IPython startup file that calls it, so every kernel the
build starts (``execute_pages.py``, or Jupyter Book itself through ``sphinx_playground``)
has it before the chapter's first cell.

* :mod:`playground_export.export`: the page fragment of a playground (its knobs' values as
  the page offers them) and of an animation;
* :mod:`playground_export.static`: every clip x tracker's runs, precomputed over several
  seeds, written as small files the page loads when the reader picks them.

The chapters themselves import from ``trackbook`` only: the same cells show the live widget in
Jupyter and the page in the HTML book.
"""

from __future__ import annotations

from pathlib import Path

#: The startup file IPython runs in each kernel of the book's build.
_STARTUP = '''import sys
if {ext!r} not in sys.path:
    sys.path.insert(0, {ext!r})
import playground_export
playground_export.install(get_ipython())
'''
#: its name in the profile's startup folder (after ``figure_check``'s ``00-``)
STARTUP_NAME = "10-playground-export.py"


def page_bundle(obj) -> tuple[dict, dict]:
    """The display of a playground or an animation in the book: ``(data, metadata)`` with
    the page fragment as ``text/html`` (its runs and frames written as files,
    :func:`playground_export.static.store`)."""
    from trackbook.playground import Playground

    from .export import animation_html, static_html

    if isinstance(obj, Playground):
        return ({"text/plain": f"Playground({obj.tracker} on {obj.clip})",
                 "text/html": static_html(obj, files=True)}, {})
    return {"text/plain": "Animation", "text/html": animation_html(obj, files=True)}, {}


def install(ip) -> None:
    """Display every :class:`~trackbook.playground.Playground` and
    :class:`~trackbook.playground.animation.Animation` of IPython shell ``ip`` as the HTML
    book's page (:func:`page_bundle`) instead of the live widget. A printer registered for a
    type comes before the object's own ``_repr_mimebundle_``, so the widgets stay as they are."""
    from trackbook.playground import Playground
    from trackbook.playground.animation import Animation

    formatter = ip.display_formatter.mimebundle_formatter
    for cls in (Playground, Animation):
        formatter.for_type(cls, page_bundle)


def add_startup(ipython_dir: str | Path) -> Path:
    """Write the startup file that runs :func:`install` into ``ipython_dir``'s default profile
    (made if missing; its other startup files are kept); point ``IPYTHONDIR`` at it before
    kernels start. Returns ``ipython_dir``."""
    root = Path(ipython_dir)
    startup = root / "profile_default" / "startup"
    startup.mkdir(parents=True, exist_ok=True)
    (startup / STARTUP_NAME).write_text(
        _STARTUP.format(ext=str(Path(__file__).resolve().parents[1])), encoding="utf-8")
    return root
