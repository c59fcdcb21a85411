"""Checks every figure of the book as it is drawn: tracker colours and legends clear of data.

The pages draw their figures with matplotlib in a kernel; :func:`install` hooks a check into
that kernel (``execute_pages.py`` does it through IPython's startup folder, see
:func:`ipython_dir`). Before a cell's figures are shown it looks at each one and the cell
fails, naming the figure's problem, when

- a line, marker or box labelled with a registered tracker's name (``kcf``,
  ``kcf-redetect``, ``kcf (paper)``) is not drawn in that tracker's colour
  (``trackbook.style.tracker_color``): a reader who learns that ``kcf`` is vermillion in one
  figure must find it vermillion in every other;
- a legend covers a data point: a vertex of a plotted line or a scatter marker of its axes,
  inside the axes (where it is drawn), lies inside the legend's box.

:func:`problems` is the check itself, so it can be tested on figures made for the purpose.

The same hook writes a description of each figure shown (:func:`describe`: its panels' titles,
what is plotted against what, the legend's entries) where ``figure_alt.py`` finds it, so that
every figure of the built book has an alt text that says what it shows, not a file name.
"""

from __future__ import annotations

import base64
import hashlib
import os
import re
import shutil
from pathlib import Path

import numpy as np

#: The start of a label that names a tracker: "kcf", "kcf-redetect", "kcf (paper)".
_NAME = re.compile(r"^\s*([a-z][a-z0-9]*(?:-[a-z0-9]+)*)")
#: What a failing cell prints before its error.
MARK = "figure check:"


def _tracker(label: str) -> str | None:
    from trackbook.style import tracker_color
    m = _NAME.match(label or "")
    if m and tracker_color(m.group(1)) is not None:
        return m.group(1)
    return None


def _colour_of(artist):
    """The colour an artist is seen in: a line's colour, a patch's edge (or its face when the
    edge is invisible), a collection's first edge or face colour."""
    from matplotlib.collections import Collection
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    if isinstance(artist, Line2D):
        return artist.get_color()
    if isinstance(artist, Patch):
        edge = artist.get_edgecolor()
        return edge if edge[3] > 0 and artist.get_linewidth() > 0 else artist.get_facecolor()
    if isinstance(artist, Collection):
        for c in (artist.get_edgecolor(), artist.get_facecolor()):
            if len(c) and c[0][3] > 0:
                return c[0]
    return None


def _same(a, b) -> bool:
    from matplotlib.colors import to_rgb
    return np.allclose(to_rgb(a), to_rgb(b), atol=1 / 255)


def _labelled(ax):
    for artist in [*ax.lines, *ax.patches, *ax.collections]:
        label = artist.get_label()
        if label and not label.startswith("_"):
            yield label, artist
    legend = ax.get_legend()
    if legend is not None:                       # proxies drawn only in the legend
        for handle, text in zip(legend.legend_handles, legend.get_texts()):
            if handle is not None:
                yield text.get_text(), handle


def _colour_problems(fig) -> list[str]:
    from trackbook.style import tracker_color
    out = []
    for k, ax in enumerate(fig.axes):
        for label, artist in _labelled(ax):
            name = _tracker(label)
            colour = _colour_of(artist) if name else None
            if name and colour is not None and not _same(colour, tracker_color(name)):
                from matplotlib.colors import to_hex
                out.append(f"axes {k}: {label!r} is drawn in {to_hex(colour)}, not in "
                           f"{name}'s colour {tracker_color(name)} "
                           f"(trackbook.style.tracker_color)")
    return out


def _data_points(ax) -> np.ndarray:
    """Display coordinates of every line vertex and scatter marker of ``ax``."""
    pts = []
    for line in ax.lines:
        if not line.get_visible():
            continue
        xy = np.asarray(line.get_xydata(), float)
        if len(xy):
            pts.append(line.get_transform().transform(xy))
    for coll in ax.collections:
        offsets = np.asarray(coll.get_offsets(), float)
        if coll.get_visible() and offsets.ndim == 2 and len(offsets) and len(coll.get_paths()):
            pts.append(coll.get_offset_transform().transform(offsets))
    pts = [p[np.isfinite(p).all(axis=1)] for p in pts]
    return np.concatenate(pts) if pts else np.zeros((0, 2))


def _legend_problems(fig) -> list[str]:
    out = []
    renderer = fig.canvas.get_renderer()
    for k, ax in enumerate(fig.axes):
        legend = ax.get_legend()
        if legend is None or not legend.get_visible():
            continue
        box = legend.get_window_extent(renderer)
        pts = _data_points(ax)
        seen = ax.bbox                # a point outside the axes is clipped away: not seen
        inside = ((pts[:, 0] > box.x0) & (pts[:, 0] < box.x1)
                  & (pts[:, 1] > box.y0) & (pts[:, 1] < box.y1)
                  & (pts[:, 0] >= seen.x0) & (pts[:, 0] <= seen.x1)
                  & (pts[:, 1] >= seen.y0) & (pts[:, 1] <= seen.y1))
        if inside.any():
            out.append(f"axes {k}: the legend covers {int(inside.sum())} data point(s); "
                       "move it (loc=..., or outside the axes with bbox_to_anchor)")
    return out


def problems(fig) -> list[str]:
    """What is wrong with one figure (an empty list when nothing is)."""
    fig.canvas.draw()                 # legends placed with loc="best" find their place here
    return _colour_problems(fig) + _legend_problems(fig)


#: Where a kernel writes the description of each figure it shows (set by execute_pages.py):
#: ``<sha256 of the PNG>.txt``, the name MyST-NB gives the image, so ``figure_alt.py`` can put
#: the description in the page as the image's alt text.
ALTS_ENV = "TRACKBOOK_FIGURE_ALTS"


def _text(s) -> str:
    return re.sub(r"\s+", " ", re.sub(r"\$([^$]*)\$", r"\1", str(s or ""))).strip()


def describe(fig, limit: int = 400) -> str:
    """A description of a figure for readers who cannot see it, read off the figure itself:
    its title, and per panel the title, what is plotted against what, and the legend's
    entries (or that the panel is an image)."""
    panels = []
    for ax in fig.axes:
        if not ax.get_visible() or ax.get_label() == "<colorbar>":
            continue
        bits = []
        title = _text(ax.get_title())
        x, y = _text(ax.get_xlabel()), _text(ax.get_ylabel())
        if ax.images:
            bits.append("an image")
        if y and x:
            bits.append(f"{y} against {x}")
        elif y or x:
            bits.append(y or x)
        legend = ax.get_legend()
        names = ([_text(t.get_text()) for t in legend.get_texts()] if legend is not None
                 else [_text(a.get_label()) for a in [*ax.lines, *ax.collections]
                       if not str(a.get_label()).startswith("_")])
        names = [n for n in names if n]
        if names:
            bits.append("showing " + ", ".join(names))
        if title or bits:
            panels.append((f"{title}: " if title else "") + "; ".join(bits))
    head = _text(fig._suptitle.get_text()) if getattr(fig, "_suptitle", None) else ""
    n = len(panels)
    body = " | ".join(panels) if panels else "a figure"
    text = (f"{head}. " if head else "") + (f"{n} panels. " if n > 1 else "") + body
    return text if len(text) <= limit else text[:limit - 1].rstrip() + "…"


def _record_alt(fig, data) -> None:
    """Write the figure's description where the build looks for it (``ALTS_ENV``)."""
    folder = os.environ.get(ALTS_ENV)
    if not folder or data is None:
        return
    raw = base64.b64decode(data) if isinstance(data, str) else bytes(data)
    Path(folder).mkdir(parents=True, exist_ok=True)
    (Path(folder) / f"{hashlib.sha256(raw).hexdigest()}.txt").write_text(
        describe(fig), encoding="utf-8")


class FigureCheckError(AssertionError):
    """A figure of the cell breaks the book's rules (see the module's docstring)."""


def install(ip) -> None:
    """Check each figure IPython shell ``ip`` shows, and fail the cell that shows a bad one.

    Every figure a cell shows (at its end by the inline backend, by ``plt.show()`` or by
    ``display(fig)``) passes through IPython's ``print_figure``; the wrapper installed here
    checks it there, and after the cell a ``post_run_cell`` callback turns what it found into
    the cell's error (:class:`FigureCheckError`), so the page fails to execute. Must run before
    matplotlib's inline backend is set up (IPython's startup files do).
    """
    from IPython.core import pylabtools

    found: list[str] = []
    original = pylabtools.print_figure

    def print_figure(fig, *args, **kwargs):
        name = fig.get_label() or "a figure"
        try:
            seen = problems(fig)
        except Exception as exc:     # noqa: BLE001 -- a check that cannot run fails the cell:
            # raised here, IPython's display formatter would print it, drop the figure and
            # let the cell (and the page) pass
            seen = [f"the check itself failed ({type(exc).__name__}: {exc})"]
        found.extend(f"{name}: {p}" for p in seen if f"{name}: {p}" not in found)
        data = original(fig, *args, **kwargs)
        if kwargs.get("fmt", args[0] if args else "png") in ("png", "retina"):
            _record_alt(fig, data)
        return data

    def fail_cell(result):
        if found and result.error_in_exec is None and result.error_before_exec is None:
            error = FigureCheckError(MARK + " " + "; ".join(found))
            ip.showtraceback((FigureCheckError, error, None))    # the error output
            result.error_in_exec = error                          # the cell's status
        found.clear()

    pylabtools.print_figure = print_figure
    ip.events.register("post_run_cell", fail_cell)


#: The startup file IPython runs in each kernel of the book's execution.
_STARTUP = '''import sys
sys.path.insert(0, {ext!r})
import figure_check
figure_check.install(get_ipython())
'''


def ipython_dir(where: str | Path) -> Path:
    """An IPython folder under ``where`` whose startup file installs the check; point
    ``IPYTHONDIR`` at it before kernels start."""
    root = Path(where) / "ipython"
    startup = root / "profile_default" / "startup"
    shutil.rmtree(root, ignore_errors=True)
    startup.mkdir(parents=True)
    (startup / "00-figure-check.py").write_text(
        _STARTUP.format(ext=str(Path(__file__).resolve().parent)), encoding="utf-8")
    return root
