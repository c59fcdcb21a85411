"""Trackers by name: the one registry behind ``trackers.register``, ``available``, ``get``,
``create``, ``departures`` and ``PRESETS`` (re-exported by :mod:`trackbook.trackers`).

It maps names to :class:`~trackbook.trackers.base.Tracker` subclasses: the papers' trackers
register themselves when their modules are imported, OpenCV's MIL is added as the reference
(:data:`~trackbook.trackers.reference.REFERENCE`), and a user's trackers join once their
module is loaded. *Loading* user code (files, dotted modules, installed packages' entry
points) is :mod:`trackbook.trackers.plugins`' job: it imports this module, never the other way
round, and hands it the entry-point loader through :func:`_before_lookup` so the first
``available`` or ``get`` of a process sees installed packages' trackers too.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable

from .. import params as _params
from .._checks import positional_seed_error
from .base import Tracker
from .reference import REFERENCE

_REGISTRY: dict[str, type[Tracker]] = {}
#: Called before every lookup (``available``, ``get``): plugins' entry-point loader, which
#: runs once per process.
_LOOKUP_HOOKS: list[Callable[[], None]] = []

#: The starting points ``create(..., preset=)`` accepts.
PRESETS = ("book", "paper")


def _before_lookup(hook: Callable[[], None]) -> None:
    """Run ``hook()`` before every ``available``/``get`` (it must be cheap after its first
    call); used by :mod:`~trackbook.trackers.plugins` for installed packages' entry points."""
    if hook not in _LOOKUP_HOOKS:
        _LOOKUP_HOOKS.append(hook)


def _lookup() -> None:
    for hook in _LOOKUP_HOOKS:
        hook()


def _redefinition(old: type, new: type) -> bool:
    """The same class defined again in the same module (a notebook cell run twice, a module
    reloaded): the new definition replaces the old one instead of being refused."""
    return old.__module__ == new.__module__ and old.__qualname__ == new.__qualname__


def register(cls: type[Tracker]) -> type[Tracker]:
    """Class decorator: make ``cls`` available under ``cls.name``.

    Raises
    ------
    TypeError
        ``cls`` is not a :class:`Tracker` subclass.
    ValueError
        Another class is registered under the same name, or the name is the reference's.
    """
    if not (isinstance(cls, type) and issubclass(cls, Tracker)):
        raise TypeError("register() takes a Tracker subclass")
    if cls.name in REFERENCE and cls is not REFERENCE[cls.name]:
        raise ValueError(f"tracker name {cls.name!r} is the OpenCV reference's; give your "
                         "tracker another name.")
    old = _REGISTRY.get(cls.name)
    if old is not None and old is not cls and not _redefinition(old, cls):
        raise ValueError(f"tracker name {cls.name!r} is registered twice ({old.__module__}."
                         f"{old.__qualname__} and {cls.__module__}.{cls.__qualname__}); give "
                         "your tracker another name.")
    _REGISTRY[cls.name] = cls
    return cls


def registered() -> list[str]:
    """The names registered so far, in registration order, without the reference and without
    loading installed packages' entry points (what a loader compares before and after)."""
    return list(_REGISTRY)


def available(reference: bool = True) -> list[str]:
    """Every name :func:`create` accepts, in the order the book introduces them.

    Parameters
    ----------
    reference : bool, default True
        Include OpenCV's ``opencv-mil`` (last: the reference row of the book's tables).
        ``reference=False`` gives the library's own trackers and the registered ones only.

    Returns
    -------
    list of str

    Notes
    -----
    The first call of a process also registers the trackers of installed packages
    (entry-point group ``trackbook.trackers``, see :mod:`trackbook.trackers.plugins`).
    """
    _lookup()
    return registered() + list(REFERENCE) if reference else registered()


def get(name: str) -> type[Tracker]:
    """The tracker class for a registered (or reference) name.

    Raises
    ------
    ValueError
        Unknown name; the message suggests the nearest one and lists them all.
    """
    _lookup()
    if isinstance(name, str) and name in REFERENCE:
        return REFERENCE[name]
    if isinstance(name, str) and name in _REGISTRY:
        return _REGISTRY[name]
    near = difflib.get_close_matches(str(name), available(), n=1)
    if not near and str(name).lower().replace("_", "-") in ("mil", "trackermil", "cv-mil"):
        near = ["opencv-mil"]           # OpenCV's name for it
    hint = f" (did you mean {near[0]!r}?)" if near else ""
    raise ValueError(
        f"unknown tracker {name!r}{hint}; registered trackers: "
        f"{', '.join(registered()) or '(none)'}; reference: {', '.join(REFERENCE)}; a "
        "tracker of your own is known once its module is loaded (--import my_tracker.py, "
        "or trackbook.trackers.plugins.load)."
    )


def create(name: str, *args, seed: int | None = 0, preset: str = "book",
           **params) -> Tracker:
    """Create the tracker called ``name``.

    Parameters
    ----------
    name : str
        One of :func:`available`.
    seed : int or None, keyword only
        Seed of the tracker's random generator (same seed, same frames: same boxes).
    preset : {"book", "paper"}, keyword only
        ``"book"`` (the default) starts from the book's defaults; ``"paper"`` from the printed
        values (see :func:`departures` for where the two differ).
    **params
        Fields of the tracker's ``Params``; they override either preset.

    Raises
    ------
    TypeError
        A positional argument after ``name`` (``create("color-pf", 50)``): the seed is given
        as ``seed=50``.
    ValueError
        Unknown name, unknown preset, or a param that is unknown or out of range.
    """
    if args:
        raise positional_seed_error(f"create({name!r}, seed={args[0]!r})", "create()")
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
