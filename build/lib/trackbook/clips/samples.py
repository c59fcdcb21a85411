"""The registry of generated sample clips (SPEC section 3).

A scenario is a function ``make() -> Clip`` registered with :func:`sample`. Clips are built on
first use and kept in memory, so a chapter that loads the same clip twice pays once.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable

from .clip import Clip


@dataclasses.dataclass(frozen=True)
class SampleInfo:
    name: str
    paper: str          # which seed's experiment it stands in for ("000".."003")
    description: str
    make: Callable[[], Clip]


_SAMPLES: dict[str, SampleInfo] = {}


def sample(name: str, paper: str, description: str):
    """Decorator registering a scenario function as the sample clip ``name``."""
    def deco(fn):
        if name in _SAMPLES:
            raise ValueError(f"sample clip {name!r} registered twice")
        _SAMPLES[name] = SampleInfo(name, paper, description, fn)
        return fn
    return deco


def names(paper: str | None = None) -> list[str]:
    return [n for n, s in _SAMPLES.items() if paper is None or s.paper == paper]


def info(name: str) -> SampleInfo:
    return _SAMPLES[name]


@functools.lru_cache(maxsize=None)
def build(name: str) -> Clip:
    return _SAMPLES[name].make()
