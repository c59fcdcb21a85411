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

Whatever a user's module raises while it is imported, ``sys.exit()`` included, comes back as
a :class:`PluginError` naming the user's file and line (the original exception is its
``__cause__``): an error in their code is theirs to fix, and it must not end the program
silently. This module has its own reason to change (how user code is found, imported and
blamed); the names themselves live in :mod:`trackbook.trackers.registry`.
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import sys
import traceback
import warnings
from pathlib import Path
from types import ModuleType

from . import registry as _registry
from .base import Tracker

#: The entry-point group installed packages declare their trackers in.
ENTRY_POINT_GROUP = "trackbook.trackers"

_loaded: dict[str, ModuleType] = {}      # resolved spec -> module, so a second load is a no-op
_entry_points_done = False


class PluginError(RuntimeError, ValueError):
    """A user's tracker module failed while it was being imported (it raised, or called
    ``sys.exit``). The message names the user's file and line; ``__cause__`` is the original
    exception. It is also a ``ValueError``, which :func:`load` raised for this before."""


def _module_name(path: Path) -> str:
    """A stable ``sys.modules`` name for a file: its stem plus a hash of its full path (two
    files called ``my_tracker.py`` in different folders do not collide), so classes in it
    pickle by reference within the process that loaded it."""
    digest = hashlib.sha1(str(path).encode()).hexdigest()[:10]
    stem = "".join(c if c.isalnum() else "_" for c in path.stem)
    return f"trackbook_user_{stem}_{digest}"


def _is_file_spec(spec: str) -> bool:
    return spec.endswith(".py") or "/" in spec or "\\" in spec


def _module_roots(module: str) -> list[Path]:
    """Where the code of dotted ``module`` lives: its top-level package's folder, or the
    file of a top-level module (found without importing anything)."""
    try:
        spec = importlib.util.find_spec(module.split(".")[0])
    except (ImportError, ValueError):
        return []
    if spec is None:
        return []
    if spec.submodule_search_locations:
        return [Path(p).resolve() for p in spec.submodule_search_locations]
    return [Path(spec.origin).resolve()] if spec.origin and spec.has_location else []


def _inside(filename: str, roots: list[Path]) -> bool:
    if filename.startswith("<"):
        return False
    f = Path(filename).resolve()
    return any(f == r or r in f.parents for r in roots)


def _where(exc: BaseException, roots: list[Path]) -> str:
    """``"file.py, line 3"`` of the deepest frame of ``exc``'s traceback in the user's code
    (under ``roots``); a ``SyntaxError`` gives its own file and line."""
    if isinstance(exc, SyntaxError) and exc.filename and exc.lineno:
        return f"{exc.filename}, line {exc.lineno}"
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if _inside(f.filename, roots)]
    if frames:
        return f"{frames[-1].filename}, line {frames[-1].lineno}"
    return ", ".join(str(r) for r in roots) or "(file unknown)"


def _plugin_error(what: str, exc: BaseException, roots: list[Path]) -> PluginError:
    """The :class:`PluginError` for ``exc`` raised while importing ``what`` (to raise ``from
    exc``)."""
    where = _where(exc, roots)
    if isinstance(exc, SystemExit):
        return PluginError(
            f"{what} called sys.exit({exc.code!r}) at {where} while being imported; a tracker "
            "module must not exit: put script code under if __name__ == '__main__':.")
    return PluginError(f"{what} failed at {where}: {type(exc).__name__}: {exc}; fix your "
                       "code and load it again.")


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
        The file does not exist, is not a ``.py`` file, or the module cannot be found; the
        message names the spec and the fix.
    PluginError
        Importing the module raised, or called ``sys.exit``: the message names the user's
        file and line, ``__cause__`` is the original exception. A ``ValueError`` too.

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
        before = set(_registry.registered())
        ispec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(ispec)
        sys.modules[name] = module
        try:
            ispec.loader.exec_module(module)
        except (Exception, SystemExit) as e:  # whatever the user's file does
            sys.modules.pop(name, None)
            raise _plugin_error(f"tracker module {spec!r}", e, [path]) from e
    else:
        key = spec
        if key in _loaded:
            return _loaded[key]
        before = set(_registry.registered())
        try:
            module = importlib.import_module(spec)
        except ModuleNotFoundError as e:
            if e.name and (spec == e.name or spec.startswith(e.name + ".")):
                raise ValueError(f"cannot load tracker module {spec!r}: no module named "
                                 f"{e.name!r}; pass a .py file path, or a dotted name "
                                 "importable from the current folder or an installed "
                                 "package.") from e
            # the module exists but imports one that does not: an error in the user's code
            raise _plugin_error(f"tracker module {spec!r}", e, _module_roots(spec)) from e
        except (Exception, SystemExit) as e:
            raise _plugin_error(f"tracker module {spec!r}", e, _module_roots(spec)) from e
    _loaded[key] = module
    if not set(_registry.registered()) - before:
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

    A broken entry point (one that raises, or calls ``sys.exit``, while being imported) does
    not stop the others (nor ``trackers.available()``): it is reported in a warning with the
    message of its :class:`PluginError`, naming the package, the entry point and the file and
    line that failed.
    """
    global _entry_points_done
    _entry_points_done = True
    from importlib.metadata import entry_points

    before = set(_registry.registered())
    try:
        eps = entry_points(group=ENTRY_POINT_GROUP)
    except TypeError:   # pragma: no cover  Python < 3.10 API; kept for safety
        eps = entry_points().get(ENTRY_POINT_GROUP, [])
    seen = set()
    for ep in eps:
        if (ep.name, ep.value) in seen:   # the same distribution found twice on sys.path
            continue
        seen.add((ep.name, ep.value))
        dist = getattr(getattr(ep, "dist", None), "name", "?")
        what = (f"entry point {ep.name!r} = {ep.value!r} of package {dist!r} "
                f"(group {ENTRY_POINT_GROUP})")
        try:
            obj = ep.load()
            if isinstance(obj, type) and issubclass(obj, Tracker):
                _registry.register(obj)
        except (Exception, SystemExit) as e:  # one broken package must not hide the others
            err = _plugin_error(what, e, _module_roots(ep.value.split(":")[0].strip()))
            warnings.warn(str(err), stacklevel=2)
    return [n for n in _registry.registered() if n not in before]


def ensure_entry_points() -> None:
    """Call :func:`load_entry_points` once per process (on the first ``available``/``get``)."""
    if not _entry_points_done:
        load_entry_points()


_registry._before_lookup(ensure_entry_points)
