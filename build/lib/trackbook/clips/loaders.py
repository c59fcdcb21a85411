"""Loading clips from disk: OTB-style folders and video files.

An OTB sequence as downloaded from the benchmark is a folder with ``img/0001.jpg ...`` and
``groundtruth_rect.txt`` (or ``groundtruth.txt``), one box per line, separated by commas,
tabs or spaces. VOT's 8-value polygons are turned into their axis-aligned bounding box.
"""

from __future__ import annotations

import math
import os
import re
from pathlib import Path

import cv2
import numpy as np

from .clip import Clip, ImageFiles, VideoFrames

IMAGE_SUFFIXES = {".jpg", ".jpeg", ".png", ".bmp"}
VIDEO_SUFFIXES = {".mp4", ".avi", ".mov", ".mkv", ".m4v", ".mpg", ".mpeg", ".webm", ".wmv"}
GT_NAMES = ("groundtruth_rect.txt", "groundtruth.txt")
_SEP = re.compile(r"[,\s]+")


def read_groundtruth(path) -> np.ndarray:
    """Read a ground-truth file into an N x 4 float array (NaN rows where unknown).

    Accepts ``x,y,w,h`` / tab / space separated lines, VOT 8-value polygons, ``NaN`` entries,
    a UTF-8 byte-order mark, and treats boxes of zero size (OTB's "target absent") as unknown.
    Infinite values and negative widths or heights are refused with the file and line: they
    are typing errors, not "target absent".
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"ground-truth file {path} does not exist; pass the path of "
                                "a text file with one x,y,w,h line per frame.")
    try:
        text = path.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError as e:
        line = path.read_bytes()[:e.start].count(b"\n") + 1
        raise ValueError(
            f"{path}, line {line}: not UTF-8 text (byte {e.object[e.start]:#04x}); save the "
            "ground truth as plain text with one x,y,w,h line per frame."
        ) from None
    rows = []
    for lineno, line in enumerate(text.splitlines(), start=1):
        line = line.strip()
        if not line:
            continue
        parts = [p for p in _SEP.split(line) if p]
        try:
            vals = [float(p) for p in parts]
        except ValueError:
            raise ValueError(
                f"{path}, line {lineno}: {line!r} is not numbers; each line must be "
                "x,y,w,h (commas, tabs or spaces) or an 8-value polygon."
            ) from None
        if any(math.isinf(v) for v in vals):
            raise ValueError(
                f"{path}, line {lineno}: {line!r} contains an infinite value; write the box "
                "in pixels, or NaN (or 0,0,0,0) where the target is not visible."
            )
        if len(vals) == 4:
            if vals[2] < 0 or vals[3] < 0:
                raise ValueError(
                    f"{path}, line {lineno}: {line!r} has a negative width or height; write "
                    "x,y,w,h with w, h >= 0 (the top-left corner and the size, not two "
                    "corners), or 0,0,0,0 where the target is not visible."
                )
            rows.append(vals)
        elif len(vals) == 8:
            xs, ys = vals[0::2], vals[1::2]
            rows.append([min(xs), min(ys), max(xs) - min(xs), max(ys) - min(ys)])
        else:
            raise ValueError(
                f"{path}, line {lineno}: {len(vals)} values; expected 4 (x, y, w, h) "
                "or 8 (a polygon)."
            )
    if not rows:
        raise ValueError(f"ground-truth file {path} is empty; it needs one x,y,w,h line per "
                         "frame.")
    gt = np.asarray(rows, dtype=float)
    with np.errstate(invalid="ignore"):
        gt[~((gt[:, 2] > 0) & (gt[:, 3] > 0))] = np.nan
    return gt


def _find_groundtruth(folder: Path) -> list[Path]:
    for name in GT_NAMES:
        if (folder / name).is_file():
            return [folder / name]
    multi = sorted(folder.glob("groundtruth_rect.*.txt"))  # OTB's Jogging, Skating2, ...
    return multi


def load_folder(folder, name: str | None = None, fps: float = 30.0, groundtruth=None) -> Clip:
    """Load an OTB-style sequence folder (``img/*.jpg`` + ``groundtruth[_rect].txt``).

    ``groundtruth`` names a ground-truth file to use instead of the folder's own.
    """
    folder = Path(folder)
    img_dir = folder / "img" if (folder / "img").is_dir() else folder
    paths = sorted(p for p in img_dir.iterdir() if p.suffix.lower() in IMAGE_SUFFIXES)
    if not paths:
        raise FileNotFoundError(
            f"no images in {img_dir}; an OTB sequence folder has img/0001.jpg, img/0002.jpg, ..."
        )
    gt_files = [Path(groundtruth)] if groundtruth is not None else _find_groundtruth(folder)
    if not gt_files:
        raise FileNotFoundError(
            f"no ground truth in {folder}; expected one of {', '.join(GT_NAMES)} "
            "(one x,y,w,h line per frame), or pass groundtruth=PATH."
        )
    targets = {}
    for f in gt_files:
        gt = read_groundtruth(f)
        if gt.shape[0] != len(paths):
            raise ValueError(
                f"{f} has {gt.shape[0]} boxes but {img_dir} has {len(paths)} images; "
                "they must match one to one (trim the images or the ground truth)."
            )
        key = "target" if len(gt_files) == 1 else f.name.split(".")[1]
        targets[key] = gt
    first = next(iter(targets.values()))
    return Clip(name or folder.name, ImageFiles(paths), first, fps=fps, targets=targets,
                source=str(folder))


def count_video_frames(path) -> int:
    """Count the decodable frames of a video (container frame counts are unreliable)."""
    cap = cv2.VideoCapture(str(path))
    if not cap.isOpened():
        raise ValueError(f"cannot open video {path}: unreadable or not a video.")
    n = 0
    while cap.grab():
        n += 1
    cap.release()
    return n


def load_video(path, groundtruth=None, name: str | None = None) -> Clip:
    """Load a video file; ground truth from ``groundtruth`` or a ``<stem>.groundtruth.txt`` beside it.

    Without ground truth every row is NaN (tracking still works; scores need ground truth).
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"video file {path} does not exist.")
    n = count_video_frames(path)
    if n == 0:
        raise ValueError(f"video {path} has no decodable frames: is it empty or corrupt?")
    cap = cv2.VideoCapture(str(path))
    fps = cap.get(cv2.CAP_PROP_FPS) or 30.0
    cap.release()
    if groundtruth is None:
        side = path.with_suffix(".groundtruth.txt")
        groundtruth = side if side.is_file() else None
    if groundtruth is None:
        gt = np.full((n, 4), np.nan)
    else:
        gt = read_groundtruth(groundtruth)
        if gt.shape[0] != n:
            raise ValueError(
                f"{groundtruth} has {gt.shape[0]} boxes but {path} has {n} frames; "
                "they must match one to one."
            )
    return Clip(name or path.stem, VideoFrames(path, n), gt, fps=float(fps), source=str(path))


def load_path(path, **kw) -> Clip:
    """Load a folder or a video file."""
    p = Path(path)
    if p.is_dir():
        return load_folder(p, **{k: v for k, v in kw.items()
                                  if k in ("name", "fps", "groundtruth")})
    if p.is_file():
        if p.suffix.lower() not in VIDEO_SUFFIXES:
            raise ValueError(
                f"{p} is not a video file (known: {', '.join(sorted(VIDEO_SUFFIXES))}) "
                "nor an OTB sequence folder."
            )
        return load_video(p, **{k: v for k, v in kw.items() if k in ("groundtruth", "name")})
    raise FileNotFoundError(f"{p} does not exist.")


def find_sequences(root=None) -> dict[str, Path]:
    """OTB-style sequence folders under ``root``, by name.

    ``root`` defaults to ``$TRACKBOOK_SEQUENCES``, else the first ``shared/data/sequences``
    found beside the current directory or one of its parents (the development data next to a
    clone). Returns an empty dict when there is none, so callers can skip cleanly.
    """
    if root is None:
        env = os.environ.get("TRACKBOOK_SEQUENCES")
        if env:
            root = Path(env)
        else:
            here = Path.cwd().resolve()
            for a in (here, *here.parents):
                cand = a / "shared" / "data" / "sequences"
                if cand.is_dir():
                    root = cand
                    break
    if root is None or not Path(root).is_dir():
        return {}
    root = Path(root)
    return {
        p.name: p for p in sorted(root.iterdir())
        if p.is_dir() and _find_groundtruth(p) and (p / "img").is_dir()
    }
