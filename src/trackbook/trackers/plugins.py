"""Trackers defined outside the library: load a module or a ``.py`` file so its
``@trackers.register`` runs.

A minimal version of the plugin contract: :func:`load` takes a dotted module name
(``mypkg.mytracker``) or the path of a ``.py`` file and imports it once per process (loading
the same spec again returns the same module, so a tracker is never registered twice);
:func:`load_entry_points` registers the packages that declare the entry-point group
``trackbook.trackers``. The benchmark's workers call :func:`load` for the plugins a run names
(``bench.Task.plugins``), so a tracker written in a script runs in worker processes too.
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import sys
from pathlib import Path

GROUP = "trackbook.trackers"
_LOADED: dict[str, object] = {}


def load(spec: str):
    """Import the module ``spec`` (a dotted name or a ``.py`` path) and return it.

    Raises
    ------
    ValueError
        Naming the spec when it cannot be found or raises on import.
    """
    if not isinstance(spec, (str, Path)) or not str(spec).strip():
        raise ValueError(f"plugin {spec!r}: give a module name (mypkg.mytracker) or the path "
                         "of a .py file.")
    spec = str(spec)
    is_file = spec.endswith(".py") or "/" in spec or "\\" in spec
    key = str(Path(spec).resolve()) if is_file else spec
    if key in _LOADED:
        return _LOADED[key]
    try:
        if is_file:
            path = Path(key)
            if not path.is_file():
                raise FileNotFoundError(f"no such file: {path}")
            name = f"trackbook_plugin_{path.stem}_{hashlib.sha1(key.encode()).hexdigest()[:8]}"
            if name in sys.modules:
                module = sys.modules[name]
            else:
                s = importlib.util.spec_from_file_location(name, path)
                module = importlib.util.module_from_spec(s)
                sys.modules[name] = module
                try:
                    s.loader.exec_module(module)
                except BaseException:
                    del sys.modules[name]
                    raise
        else:
            module = importlib.import_module(spec)
    except Exception as e:  # noqa: BLE001  (any failure is the plugin's: name it)
        raise ValueError(f"plugin {spec!r} could not be loaded ({type(e).__name__}: {e}); "
                         "check the module name or the file's path.") from e
    _LOADED[key] = module
    return module


def load_entry_points() -> list[str]:
    """Load every module declared under the entry-point group ``trackbook.trackers``; return
    their names."""
    from importlib.metadata import entry_points

    names = []
    for ep in entry_points(group=GROUP):
        load(ep.value.split(":")[0])
        names.append(ep.name)
    return names
