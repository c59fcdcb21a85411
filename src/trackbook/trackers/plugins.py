"""User trackers: load a module or a ``.py`` file so that its ``@trackers.register`` runs.

Minimal version (the benchmark needs :func:`load`); same signatures as the full module.
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import sys
from pathlib import Path

_LOADED: dict[str, object] = {}
_ENTRY_POINTS_DONE = False


def load(spec: str):
    """Import a dotted module name or a ``.py`` file path and return the module.

    Idempotent: the same spec (the same resolved file) is imported once per process.
    Raises ``ValueError`` naming the spec when it cannot be imported.
    """
    spec = str(spec)
    key = spec
    path = Path(spec).expanduser()
    is_file = spec.endswith(".py") or path.is_file()
    if is_file:
        key = str(path.resolve())
    if key in _LOADED:
        return _LOADED[key]
    try:
        if is_file:
            if not path.is_file():
                raise FileNotFoundError(f"no such file: {path}")
            name = "trackbook_user_" + path.stem.replace("-", "_") + "_" + \
                hashlib.sha1(key.encode()).hexdigest()[:8]
            mspec = importlib.util.spec_from_file_location(name, path)
            module = importlib.util.module_from_spec(mspec)
            sys.modules[name] = module
            try:
                mspec.loader.exec_module(module)
            except BaseException:
                sys.modules.pop(name, None)
                raise
        else:
            module = importlib.import_module(spec)
    except Exception as e:  # noqa: BLE001  one message naming the spec
        raise ValueError(f"cannot import tracker module {spec!r}: {type(e).__name__}: "
                         f"{' '.join(str(e).split())}; pass a module name importable here "
                         "or the path of a .py file.") from e
    _LOADED[key] = module
    return module


def load_entry_points() -> None:
    """Import every entry point of the group ``trackbook.trackers`` (once per process)."""
    global _ENTRY_POINTS_DONE
    if _ENTRY_POINTS_DONE:
        return
    _ENTRY_POINTS_DONE = True
    from importlib.metadata import entry_points

    for ep in entry_points(group="trackbook.trackers"):
        try:
            ep.load()
        except Exception as e:  # noqa: BLE001
            raise ValueError(f"cannot load tracker entry point {ep.name!r} ({ep.value}): "
                             f"{type(e).__name__}: {e}") from e
