"""Trackers: the registry, the shared base class and the papers' trackers.

>>> from trackbook import trackers
>>> trackers.available()          # the eleven registered names (SPEC section 2)  # doctest: +SKIP
>>> t = trackers.create("color-hog-ipca", seed=0, n_particles=100)  # doctest: +SKIP
>>> t.init(frame, (x, y, w, h)); ok, box = t.update(next_frame)     # doctest: +SKIP

The papers' trackers register themselves when their module is imported below; each module
matches one chapter of the book.
"""

from __future__ import annotations

import difflib

from .. import params as _params
from .._checks import clip_box
from . import registry as _registry
from .base import Tracker
from .multi import MultiTracker
from .reference import REFERENCE

# The papers' trackers (each import registers its names) -------------------------------
# (one line per paper module; the order is the book's)
from . import color_hog  # noqa: E402,F401  seed 000: color-pf, color-hog-pf, color-hog-ipca
from . import hsi_hog_pf  # noqa: E402,F401  seed 001: hsi-color-pf, hog-pf
from . import edge_ray  # noqa: E402,F401  seed 001: edge-ray-pf
from . import covariance  # noqa: E402,F401  seed 002: covariance, kalman-covariance
from . import condensation_mean_shift  # noqa: E402,F401  seed 003: condensation, mean-shift, condensation-mean-shift
from . import correlation  # noqa: E402,F401  bolme2010, henriques2015: mosse, kcf


def available(reference: bool = False) -> list[str]:
    """Registered tracker names; with ``reference=True`` also OpenCV's ``opencv-mil``."""
    names = _registry.available()
    return names + list(REFERENCE) if reference else names


def get(name: str) -> type[Tracker]:
    """The tracker class for a registered (or reference) name."""
    if name in REFERENCE:
        return REFERENCE[name]
    try:
        return _registry.get(name)
    except ValueError:
        near = difflib.get_close_matches(str(name), available(reference=True), n=1)
        hint = f" (did you mean {near[0]!r}?)" if near else ""
        raise ValueError(
            f"unknown tracker {name!r}{hint}; registered trackers: "
            f"{', '.join(available()) or '(none)'}; reference: {', '.join(REFERENCE)}."
        ) from None


PRESETS = ("book", "paper")


def create(name: str, seed: int | None = 0, preset: str = "book", **params) -> Tracker:
    """Create the tracker called ``name`` with a seed and keyword params (its ``Params`` fields).

    ``preset="book"`` (the default) starts from the book's defaults; ``preset="paper"`` starts
    from the values the paper prints (see :func:`departures` for where the two differ). Keyword
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

    Rows ``{param, paper, book, why}``: the paper's value (or ``"not printed"``), the book's
    default and one line on why. Each chapter's departures table is generated from this.
    """
    return _params.departures(get(name).Params)


register = _registry.register

__all__ = ["MultiTracker", "Tracker", "available", "create", "departures", "get", "register",
           "clip_box"]
