"""The one registry of generated sample clips.

A scene registers with :func:`sample`: a function ``render(n) -> Rendering`` (see
:mod:`trackbook.clips.scenes`) plus what a listing needs, so :func:`names` and :func:`info`
answer without rendering a frame. Clips are rendered on first use and kept in memory, so a
chapter that loads the same clip twice pays once.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable

import numpy as np

from .clip import ArrayFrames, Clip
from .rendering import H, W, Rendering

#: The papers the sample clips stand in for, by key.
PAPERS = ("lee2012", "kim2016", "lee2015", "cho2005")


@dataclasses.dataclass(frozen=True)
class SampleInfo:
    """What a sample clip is, known without rendering it.

    Attributes
    ----------
    name : str
    paper : str
        Key of the paper whose experiment the clip stands in for (one of :data:`PAPERS`).
    frames : int
        Number of frames.
    size : tuple of int
        ``(width, height)`` in pixels.
    fps : float
    attributes : tuple of str
        OTB challenge codes (``"FM"`` fast motion, ``"OCC"`` occlusion, ...).
    description : str
        One paragraph on what the clip shows.
    render : callable
        ``render(frames) -> Rendering``, the scene.
    """

    name: str
    paper: str
    frames: int
    size: tuple
    fps: float
    attributes: tuple
    description: str
    render: Callable[[int], Rendering] = dataclasses.field(repr=False)


_SAMPLES: dict[str, SampleInfo] = {}


def sample(name: str, paper: str, *, frames: int, fps: float, attributes: tuple,
           description: str, size: tuple = (W, H)):
    """Decorator registering ``render(n) -> Rendering`` as the sample clip ``name``."""
    check_paper(paper)
    if name in _SAMPLES:
        raise ValueError(f"sample clip {name!r} registered twice")

    def deco(render_fn):
        _SAMPLES[name] = SampleInfo(name, paper, int(frames), tuple(size), float(fps),
                                    tuple(attributes), " ".join(description.split()),
                                    render_fn)
        return render_fn
    return deco


def check_paper(paper) -> str:
    """``paper`` if it is a paper key, else a ``ValueError`` naming the keys."""
    if paper in PAPERS:
        return paper
    old = {"000": "lee2012", "001": "kim2016", "002": "lee2015", "003": "cho2005"}
    hint = (f"; the papers are named by key now: paper={old[str(paper)]!r}"
            if str(paper) in old else "")
    raise ValueError(f"unknown paper {paper!r}{hint}; pass one of {', '.join(PAPERS)}.")


def names(paper: str | None = None) -> list[str]:
    """Names of the registered sample clips, all or those of one paper key."""
    if paper is not None:
        check_paper(paper)
    return [n for n, s in _SAMPLES.items() if paper is None or s.paper == paper]


def info(name: str) -> SampleInfo:
    """The registry entry of sample clip ``name``."""
    return _SAMPLES[name]


def render(name: str) -> Rendering:
    """Render sample clip ``name`` with its target masks (not cached; see :func:`build`)."""
    if name not in _SAMPLES:
        raise ValueError(f"unknown generated clip {name!r}; known: {', '.join(_SAMPLES)}")
    s = _SAMPLES[name]
    return s.render(s.frames)


def render_masks(name: str, visible: bool = False) -> np.ndarray:
    """N x H x W bool masks of the primary target of clip ``name``.

    ``visible=False`` gives the sprite's full support (its box is the ground truth, also
    while occluded); ``visible=True`` only the pixels nothing is drawn over.
    """
    r = render(name)
    return r.visible if visible else r.support


@functools.lru_cache(maxsize=None)
def in_view(name: str, share: float = 0.5) -> np.ndarray:
    """Per frame of sample clip ``name``: whether its target shows at least ``share`` of its
    pixels (an N-long bool array).

    A target mostly hidden behind something drawn over it (a tree, the other face) keeps its
    whole box as ground truth, yet a tracker that reports it lost there is right, whatever
    its box's overlap: this is the mask the failure contract's false-loss count uses.
    """
    r = render(name)          # once: a benchmark records every run of a clip with it
    out = r.visible.sum(axis=(1, 2)) >= share * np.maximum(r.support.sum(axis=(1, 2)), 1)
    out.setflags(write=False)
    return out


@functools.lru_cache(maxsize=None)
def build(name: str) -> Clip:
    """The sample clip ``name`` as a read-only :class:`Clip` (rendered once per process)."""
    s = _SAMPLES[name]
    r = render(name)
    r.frames.setflags(write=False)
    return Clip(name, ArrayFrames(r.frames), next(iter(r.targets.values())), fps=s.fps,
                targets=r.targets, description=s.description, attributes=s.attributes,
                source="sample")
