"""Clips to track on: generated sample clips, OTB sequence folders and video files.

>>> from trackbook import clips
>>> clips.available()                      # the embedded sample clips   # doctest: +SKIP
>>> clip = clips.load("red-cube")          # a sample by name             # doctest: +SKIP
>>> clip = clips.load("~/otb/Basketball")  # a downloaded OTB folder      # doctest: +SKIP
>>> clip = clips.load("walk.mp4", groundtruth="walk.txt")                 # doctest: +SKIP
"""

from __future__ import annotations

import difflib
from pathlib import Path

import cv2
import numpy as np

from . import samples as _samples
from . import scenes as _scenes  # noqa: F401  (registers the sample clips)
from .clip import ArrayFrames, Clip, FrameSequence, ImageFiles, VideoFrames
from .loaders import find_sequences, load_folder, load_path, load_video, read_groundtruth


def available(paper: str | None = None) -> list[str]:
    """Names of the sample clips: all, or those standing in for one paper.

    Parameters
    ----------
    paper : str, optional
        A paper key: ``"lee2012"``, ``"kim2016"``, ``"lee2015"`` or ``"cho2005"``.
    """
    return _samples.names(paper)


def catalogue(paper: str | None = None) -> list[_samples.SampleInfo]:
    """What each sample clip is, from the registry, without rendering a frame.

    One :class:`~trackbook.clips.samples.SampleInfo` per clip (name, paper key, frames,
    size, fps, OTB attributes, description), in the order of :func:`available`.
    """
    return [_samples.info(n) for n in _samples.names(paper)]


def describe(name: str) -> str:
    """One paragraph on what a sample clip shows and which paper it stands in for."""
    if not isinstance(name, str) or name not in _samples._SAMPLES:
        raise ValueError(f"unknown sample clip {name!r}{_near(name, available())}; sample "
                         f"clips: {', '.join(available())}.")
    s = _samples.info(name)
    return f"{s.name} ({s.paper}): {s.description}"


def _near(name, names) -> str:
    """`` (did you mean 'red-cube'?)`` for a near-miss name, else ``""``."""
    m = difflib.get_close_matches(str(name), list(names), n=1, cutoff=0.6)
    return f" (did you mean {m[0]!r}?)" if m else ""


def load(name_or_path, groundtruth=None) -> Clip:
    """A clip by sample name, OTB-style folder, or video file (with optional ground truth).

    Raises
    ------
    ValueError
        For an unknown name (the message lists the samples) or unreadable files.
    FileNotFoundError
        For a path that does not exist or a folder without images / ground truth.
    """
    if isinstance(name_or_path, Clip):
        return name_or_path
    if not isinstance(name_or_path, (str, Path)) or not str(name_or_path).strip():
        raise ValueError(
            f"clips.load({name_or_path!r}): pass a sample name (one of "
            f"{', '.join(available())}), an OTB sequence folder or a video file.")
    if isinstance(name_or_path, str) and name_or_path in _samples._SAMPLES:
        return _samples.build(name_or_path)
    p = Path(str(name_or_path)).expanduser()
    if p.exists():
        return load_path(p, groundtruth=groundtruth)
    if isinstance(name_or_path, str) and "/" not in name_or_path and "\\" not in name_or_path \
            and p.suffix == "":
        seq = find_sequences()
        if name_or_path in seq:
            return load_folder(seq[name_or_path], groundtruth=groundtruth)
        raise ValueError(
            f"unknown clip {name_or_path!r}{_near(name_or_path, [*available(), *seq])}; "
            f"sample clips: {', '.join(available())}"
            + (f"; sequences found: {', '.join(seq)}" if seq else "")
            + ". Or pass a path to an OTB sequence folder or a video file."
        )
    raise FileNotFoundError(f"{p} does not exist; pass a sample name, a folder or a video "
                            f"file{_near(name_or_path, available())}.")


def export(clip, path, fourcc: str = "mp4v") -> tuple[Path, Path]:
    """Write a clip as a video plus ``<stem>.groundtruth.txt``; returns both paths.

    ``clips.load(video_path)`` reads the pair back.
    """
    clip = load(clip)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    w, h = clip.size
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*fourcc), clip.fps, (w, h))
    if not writer.isOpened():
        raise ValueError(f"cannot write video {path}; use a .mp4 (mp4v) or .avi (MJPG) name.")
    for f in clip.frames:
        writer.write(np.ascontiguousarray(f))
    writer.release()
    gt_path = path.with_suffix(".groundtruth.txt")
    np.savetxt(gt_path, clip.groundtruth, fmt="%.3f", delimiter=",")
    return path, gt_path


__all__ = [
    "Clip", "FrameSequence", "ArrayFrames", "ImageFiles", "VideoFrames", "available",
    "catalogue", "describe", "load", "export", "find_sequences", "load_folder", "load_video",
    "read_groundtruth",
]


from . import datasets  # noqa: E402,F401  (after load(): datasets builds clips with the loaders)
from .datasets import load_dataset  # noqa: E402,F401
from .failure_scenes import calibration_set, failure_scene  # noqa: E402,F401
