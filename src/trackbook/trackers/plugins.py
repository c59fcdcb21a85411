"""User trackers: load a module or a ``.py`` file, or an installed package's entry points.

A tracker of your own is a :class:`trackbook.trackers.Tracker` subclass decorated with
``@trackers.register`` (the appendix ``appendix_own_tracker`` walks through one). Registering
happens when the module defining it is imported, so every tool that runs trackers by name
(``trackbook track --import``, ``trackbook bench --import``, the playground) first imports it:

>>> from trackbook.trackers import plugins
>>> plugins.load("my_trackers.py")            # a file path   # doctest: +SKIP
>>> plugins.load("mypackage.trackers")        # or a dotted module name   # doctest: +SKIP

A package can instead declare its trackers in its ``pyproject.toml``; they are registered the
first time ``trackers.available()`` or ``trackers.get()`` is called::

    [project.entry-points."trackbook.trackers"]
    lab-color-pf = "mypackage.trackers:LabColorPF"

An entry point may name a module (its ``@register`` decorators run when it is imported) or a
Tracker subclass (registered if its module did not register it already).
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import sys
import warnings
from pathlib import Path
from types import ModuleType

from . import registry as _registry
from .base import Tracker

#: The entry-point group installed packages declare their trackers in.
ENTRY_POINT_GROUP = "trackbook.trackers"

_loaded: dict[str, ModuleType] = {}      # resolved spec -> module, so a second load is a no-op
_entry_points_done = False


def _module_name(path: Path) -> str:
    """A stable ``sys.modules`` name for a file: its stem plus a hash of its full path (two
    files called ``my_tracker.py`` in different folders do not collide), so classes in it
    pickle by reference within the process that loaded it."""
    digest = hashlib.sha1(str(path).encode()).hexdigest()[:10]
    stem = "".join(c if c.isalnum() else "_" for c in path.stem)
    return f"trackbook_user_{stem}_{digest}"


def _is_file_spec(spec: str) -> bool:
    return spec.endswith(".py") or "/" in spec or "\\" in spec


def load(spec: str) -> ModuleType:
    """Import a dotted module name or a ``.py`` file so its ``@trackers.register`` runs.

    Loading the same spec again returns the module loaded the first time (nothing is
    registered twice).

    Parameters
    ----------
    spec : str
        ``"mypackage.trackers"`` (importable from ``sys.path``) or ``"path/to/file.py"``.

    Returns
    -------
    module

    Raises
    ------
    ValueError
        The file does not exist, the module cannot be found, or importing it fails; the
        message names the spec and the fix.

    Warns
    -----
    UserWarning
        When the module registers no new tracker (is the class decorated with
        ``@trackers.register``?).
    """
    if not isinstance(spec, str) or not spec.strip():
        raise ValueError(f"cannot load tracker module {spec!r}: pass a dotted module name "
                         "(mypackage.trackers) or a .py file path.")
    spec = spec.strip()
    if _is_file_spec(spec):
        path = Path(spec).expanduser().resolve()
        key = str(path)
        if key in _loaded:
            return _loaded[key]
        if not path.is_file():
            raise ValueError(f"cannot load tracker module {spec!r}: no such file ({path}); "
                             "give the path of a .py file that defines your tracker.")
        if path.suffix != ".py":
            raise ValueError(f"cannot load tracker module {spec!r}: not a .py file; give a "
                             ".py file or a dotted module name.")
        name = _module_name(path)
        if name in sys.modules:
            _loaded[key] = sys.modules[name]
            return sys.modules[name]
        before = set(_registry.available())
        ispec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(ispec)
        sys.modules[name] = module
        try:
            ispec.loader.exec_module(module)
        except Exception as e:  # noqa: BLE001  whatever the user's file raises, say which file
            sys.modules.pop(name, None)
            raise ValueError(f"cannot load tracker module {spec!r}: importing it raised "
                             f"{type(e).__name__}: {e}; fix the file and try again.") from e
    else:
        key = spec
        if key in _loaded:
            return _loaded[key]
        before = set(_registry.available())
        try:
            module = importlib.import_module(spec)
        except ModuleNotFoundError as e:
            raise ValueError(f"cannot load tracker module {spec!r}: no module named "
                             f"{e.name!r}; pass a .py file path, or a dotted name importable "
                             "from the current folder or an installed package.") from e
        except Exception as e:  # noqa: BLE001
            raise ValueError(f"cannot load tracker module {spec!r}: importing it raised "
                             f"{type(e).__name__}: {e}; fix the module and try again.") from e
    _loaded[key] = module
    if not set(_registry.available()) - before:
        warnings.warn(f"tracker module {spec!r} registered no new tracker; decorate your "
                      "Tracker subclass with @trackers.register (or it was already imported).",
                      stacklevel=2)
    return module


def loaded() -> list[str]:
    """The specs :func:`load` has loaded in this process (file specs as absolute paths), in
    order: what a worker process must load again to know the same trackers."""
    return list(_loaded)


def load_entry_points() -> list[str]:
    """Register the trackers installed packages declare in the ``trackbook.trackers``
    entry-point group; returns the names it registered.

    A broken entry point does not stop the others (nor ``trackers.available()``): it is
    reported in a warning naming the package and the entry point.
    """
    global _entry_points_done
    _entry_points_done = True
    from importlib.metadata import entry_points

    before = set(_registry.available())
    try:
        eps = entry_points(group=ENTRY_POINT_GROUP)
    except TypeError:   # pragma: no cover  Python < 3.10 API; kept for safety
        eps = entry_points().get(ENTRY_POINT_GROUP, [])
    seen = set()
    for ep in eps:
        if (ep.name, ep.value) in seen:   # the same distribution found twice on sys.path
            continue
        seen.add((ep.name, ep.value))
        try:
            obj = ep.load()
            if isinstance(obj, type) and issubclass(obj, Tracker):
                _registry.register(obj)
        except Exception as e:  # noqa: BLE001  one broken package must not hide the others
            dist = getattr(getattr(ep, "dist", None), "name", "?")
            warnings.warn(f"entry point {ep.name!r} = {ep.value!r} of package {dist!r} "
                          f"(group {ENTRY_POINT_GROUP}) could not be loaded: "
                          f"{type(e).__name__}: {e}", stacklevel=2)
    return [n for n in _registry.available() if n not in before]


def ensure_entry_points() -> None:
    """Call :func:`load_entry_points` once per process (on the first ``available``/``get``)."""
    if not _entry_points_done:
        load_entry_points()
