"""Trackers by name: ``available``, ``get``, ``create`` and ``departures`` over the registry
and the OpenCV reference (re-exported by :mod:`trackbook.trackers`)."""

from __future__ import annotations

import difflib

from .. import params as _params
from . import plugins
from . import registry as _registry
from .base import Tracker
from .reference import REFERENCE


def available(reference: bool = False) -> list[str]:
    """Registered tracker names; with ``reference=True`` also OpenCV's ``opencv-mil``.

    The first call also registers the trackers of installed packages (entry-point group
    ``trackbook.trackers``, see :mod:`trackbook.trackers.plugins`)."""
    plugins.ensure_entry_points()
    names = _registry.available()
    return names + list(REFERENCE) if reference else names


def get(name: str) -> type[Tracker]:
    """The tracker class for a registered (or reference) name."""
    plugins.ensure_entry_points()
    if name in REFERENCE:
        return REFERENCE[name]
    try:
        return _registry.get(name)
    except ValueError:
        near = difflib.get_close_matches(str(name), available(reference=True), n=1)
        if not near and str(name).lower().replace("_", "-") in ("mil", "trackermil", "cv-mil"):
            near = ["opencv-mil"]           # OpenCV's name for it
        hint = f" (did you mean {near[0]!r}?)" if near else ""
        raise ValueError(
            f"unknown tracker {name!r}{hint}; registered trackers: "
            f"{', '.join(available()) or '(none)'}; reference: {', '.join(REFERENCE)}; a "
            "tracker of your own is known once its module is loaded (--import my_tracker.py, "
            "or trackbook.trackers.plugins.load)."
        ) from None


PRESETS = ("book", "paper")


def create(name: str, seed: int | None = 0, preset: str = "book", **params) -> Tracker:
    """Create the tracker called ``name`` with a seed and keyword params (its ``Params`` fields).

    ``preset="book"`` (the default) starts from the book's defaults; ``preset="paper"`` starts
    from the printed values (see :func:`departures` for where the two differ). Keyword
    params override either preset.
    """
    if preset not in PRESETS:
        raise ValueError(f"unknown preset {preset!r}; use one of {', '.join(PRESETS)}.")
    cls = get(name)
    if preset == "paper":
        params = {**_params.paper_values(cls.Params), **params}
    return cls(seed=seed, **params)


def departures(name: str) -> list[dict]:
    """Where the book's defaults for ``name`` are not the printed method.

    Rows ``{param, paper, book, why}``: the printed value (or ``"not printed"``), the book's
    default and one line on why. Each chapter's departures table is generated from this.
    """
    return _params.departures(get(name).Params)
