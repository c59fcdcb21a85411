"""The name -> tracker class registry behind ``trackers.available()`` and ``trackers.create``."""

from __future__ import annotations

from .base import Tracker

_REGISTRY: dict[str, type[Tracker]] = {}


def _redefinition(old: type, new: type) -> bool:
    """The same class defined again in the same module (a notebook cell run twice, a module
    reloaded): the new definition replaces the old one instead of being refused."""
    return old.__module__ == new.__module__ and old.__qualname__ == new.__qualname__


def register(cls: type[Tracker]) -> type[Tracker]:
    """Class decorator: make ``cls`` available under ``cls.name``."""
    if not (isinstance(cls, type) and issubclass(cls, Tracker)):
        raise TypeError("register() takes a Tracker subclass")
    old = _REGISTRY.get(cls.name)
    if old is not None and old is not cls and not _redefinition(old, cls):
        raise ValueError(f"tracker name {cls.name!r} is registered twice ({old.__module__}."
                         f"{old.__qualname__} and {cls.__module__}.{cls.__qualname__}); give "
                         "your tracker another name.")
    _REGISTRY[cls.name] = cls
    return cls


def available() -> list[str]:
    """Names of the registered trackers, in the order the book introduces them."""
    return list(_REGISTRY)


def get(name: str) -> type[Tracker]:
    """The tracker class registered as ``name``."""
    if not isinstance(name, str) or name not in _REGISTRY:
        raise ValueError(
            f"unknown tracker {name!r}; registered trackers: {', '.join(available()) or '(none)'}."
        )
    return _REGISTRY[name]
