"""Loading clips from disk: OTB-style folders and video files.

An OTB sequence as downloaded from the benchmark is a folder with ``img/0001.jpg ...`` and
``groundtruth_rect.txt`` (or ``groundtruth.txt``), one box per line, separated by commas,
tabs or spaces. VOT's 8-value polygons are turned into their axis-aligned bounding box.
Image folders are read in natural (numeric) order: ``2.jpg`` comes before ``10.jpg``
(see :func:`frame_order`).
"""

from __future__ import annotations

import math
import os
import re
import warnings
from pathlib import Path

import cv2
import numpy as np

from .._checks import check_file, fs_error, list_dir
from .clip import Clip, CorruptFrameWarning, ImageFiles, VideoFrames

IMAGE_SUFFIXES = {".jpg", ".jpeg", ".png", ".bmp"}
VIDEO_SUFFIXES = {".mp4", ".avi", ".mov", ".mkv", ".m4v", ".mpg", ".mpeg", ".webm", ".wmv"}
GT_NAMES = ("groundtruth_rect.txt", "groundtruth.txt")
_SEP = re.compile(r"[,\s]+")
#: a number written with a decimal comma (``10,5``) inside a whitespace-separated line
_DECIMAL_COMMA = re.compile(r"\d,\d")
#: the numbers a ground-truth file may hold: ASCII decimal digits with an optional sign,
#: fraction and exponent (``12``, ``-3.5``, ``.5``, ``1e3``)
_NUMBER = re.compile(r"[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?")
#: "not known": ``nan`` in any case, with an optional sign (C's printf writes ``-nan``)
_NAN = re.compile(r"[+-]?nan", re.IGNORECASE)
_INF = re.compile(r"[+-]?inf(inity)?", re.IGNORECASE)
#: the runs of ASCII digits that number the frames of an image folder
_FRAME_NUMBER = re.compile(r"([0-9]+)")


def _value(word: str) -> float:
    """One ground-truth value, or ``ValueError`` whose message says what is wrong with it
    (Python's ``float`` would take ``١٢``, ``１２`` and ``1_000`` without a word)."""
    if _NUMBER.fullmatch(word) or _NAN.fullmatch(word) or _INF.fullmatch(word):
        return float(word)
    if any(c.isdigit() and not "0" <= c <= "9" for c in word):
        raise ValueError(f"{word!r} has digits other than 0-9 (Arabic-Indic, fullwidth, ...); "
                         "write the numbers with the digits 0-9")
    if "_" in word and _float_or_none(word) is not None:
        raise ValueError(f"{word!r} groups digits with '_'; write it without "
                         f"({word.replace('_', '')})")
    if re.fullmatch(r"[+-]?0[xX][0-9a-fA-F]+", word):
        raise ValueError(f"{word!r} is hexadecimal; write decimal numbers ({int(word, 16)})")
    raise ValueError(f"{word!r} is not a number")


def _float_or_none(word: str):
    """``float(word)``, or None when Python cannot read it either."""
    try:
        return float(word)
    except ValueError:
        return None


def _pattern(stem: str) -> str:
    """A frame name with its numbers hidden: ``img0001`` -> ``img#``."""
    return _FRAME_NUMBER.sub("#", stem)


def _natural_key(stem: str) -> tuple:
    """``"img10"`` -> ``("img", 10, "")``: text and numbers alternate, numbers by value."""
    parts = _FRAME_NUMBER.split(stem)
    return tuple(int(p) if i % 2 else p for i, p in enumerate(parts))


def frame_order(paths, folder) -> list[Path]:
    """The image files of ``folder`` in natural (numeric) order: ``1.jpg, 2.jpg, ..., 10.jpg``.

    Zero-padded names (``0001.jpg``) keep their order. Names are compared by their runs of
    the digits 0-9 as numbers and by the text between them, so every frame must follow one
    pattern: the same text, different numbers (``img0001.jpg``, ``img0002.jpg``, ...).

    Raises
    ------
    ValueError
        Two files with one frame number (``1.jpg`` and ``01.jpg``, or ``1.jpg`` and ``1.png``),
        or names of several patterns (``a1.jpg`` and ``b1.jpg``, or a stray ``cover.jpg``)
        whose order cannot be told; the message names the files.
    """
    paths = list(paths)
    patterns: dict[str, list[Path]] = {}
    for p in sorted(paths):
        patterns.setdefault(_pattern(p.stem), []).append(p)
    if len(patterns) > 1:
        shown = ", ".join(f"{ps[0].name} ({len(ps)} like it)" if len(ps) > 1 else ps[0].name
                          for ps in list(patterns.values())[:4])
        raise ValueError(
            f"image folder {folder}: the frames' names follow {len(patterns)} patterns "
            f"({shown}), so their order is ambiguous; name every frame with one pattern and "
            "its number (0001.jpg, 0002.jpg, ...) or move the other files out.")
    frames: dict[tuple, Path] = {}
    for p in sorted(paths):
        key = _natural_key(p.stem)
        if key in frames:
            raise ValueError(
                f"image folder {folder}: {frames[key].name} and {p.name} have the same frame "
                "number, so their order is ambiguous; keep one of them (move or rename the "
                "other).")
        frames[key] = p
    return [frames[k] for k in sorted(frames)]


def read_groundtruth(path) -> np.ndarray:
    """Read a ground-truth file into an N x 4 float array (NaN rows where unknown).

    Accepts ``x,y,w,h`` / tab / space separated lines, VOT 8-value polygons, ``NaN`` entries,
    a UTF-8 byte-order mark, and treats boxes of zero size (OTB's "target absent") as unknown.
    Infinite values and negative widths or heights are refused with the file and line: they
    are typing errors, not "target absent".

    A value is a decimal number in the ASCII digits 0-9 with an optional sign, fraction and
    exponent (``12``, ``-3.5``, ``.5``, ``1e3``), or ``nan`` in any case with an optional sign
    (``NaN``, ``-nan``: unknown). Anything else is refused with the file, the line and what is
    wrong, although Python's ``float`` reads some of it: other scripts' digits (``١٢``,
    fullwidth ``１２``), digit groups (``1_000``), hexadecimal (``0x10``), and words such as
    ``None`` or ``null``.
    """
    path = check_file(path, what="ground-truth file",
                      fix="pass the path of a text file with one x,y,w,h line per frame.")
    try:
        data = path.read_bytes()
    except OSError as e:
        raise fs_error(e, path, "ground-truth file") from None
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        line = data[:e.start].count(b"\n") + 1
        raise ValueError(
            f"{path}, line {line}: not UTF-8 text (byte {e.object[e.start]:#04x}); save the "
            "ground truth as plain text with one x,y,w,h line per frame."
        ) from None
    rows = []
    for lineno, line in enumerate(text.splitlines(), start=1):
        line = line.strip()
        if not line:
            continue
        words = line.split()
        if len(words) > 1 and any(_DECIMAL_COMMA.search(w) for w in words):
            # "10,5<TAB>12,25": commas inside whitespace-separated numbers are decimal commas,
            # which would otherwise read as twice as many values (a false 8-value polygon)
            raise ValueError(
                f"{path}, line {lineno}: {line!r} uses decimal commas; write decimal points "
                "(10.5 not 10,5), e.g. with sed 's/,/./g' when the fields are tab-separated.")
        parts = [p for p in _SEP.split(line) if p]
        try:
            vals = [_value(p) for p in parts]
        except ValueError as e:
            raise ValueError(
                f"{path}, line {lineno}: {line!r} is not numbers: {e}; each line must be "
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
        # a dangling or looping link is found too, so that reading it says what is wrong
        if (folder / name).is_file() or (folder / name).is_symlink():
            return [folder / name]
    multi = sorted(folder.glob("groundtruth_rect.*.txt"))  # OTB's Jogging, Skating2, ...
    return multi


def load_folder(folder, name: str | None = None, fps: float = 30.0, groundtruth=None) -> Clip:
    """Load an OTB-style sequence folder (``img/*.jpg`` + ``groundtruth[_rect].txt``).

    The images are read in natural (numeric) order, ``1.jpg, 2.jpg, ..., 10.jpg`` (zero-padded
    names such as ``0001.jpg`` keep theirs), and line *i* of the ground truth is frame *i*.
    Names that cannot be ordered unambiguously (``a1.jpg`` beside ``b1.jpg``, ``1.jpg``
    beside ``01.jpg``) raise ``ValueError`` naming the files (see :func:`frame_order`).
    ``groundtruth`` names a ground-truth file to use instead of the folder's own.
    """
    folder = Path(folder)
    img_dir = folder / "img" if (folder / "img").is_dir() else folder
    paths = frame_order((p for p in list_dir(img_dir, what="image folder")
                         if p.suffix.lower() in IMAGE_SUFFIXES), img_dir)
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
    return _count_frames(path)[0]


def _count_frames(path) -> tuple[int, int]:
    """(decodable frames, frames the container lists or -1)."""
    cap = cv2.VideoCapture(str(path))
    if not cap.isOpened():
        raise ValueError(f"cannot open video {path}: unreadable or not a video.")
    listed = int(cap.get(cv2.CAP_PROP_FRAME_COUNT) or -1)
    n = 0
    while cap.grab():
        n += 1
    cap.release()
    return n, listed


def write_video(path, frames, fps: float, size, fourcc: str = "mp4v") -> int:
    """Write BGR ``frames`` of ``size`` (width, height) to ``path`` with the codec ``fourcc``
    (``"mp4v"``, or ``"avc1"`` where OpenCV has H.264); return the count.

    Raises ``ValueError`` naming the file when OpenCV's writer cannot open it (a codec that
    refuses the size, e.g. a 2 x 20000 clip, or a folder that cannot be written) or when the
    written file does not hold the frames: a failed write is never reported as written.
    """
    path = Path(path)
    w, h = (int(v) for v in size)
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*fourcc), float(fps or 25),
                             (w, h))
    if not writer.isOpened():
        raise ValueError(f"cannot write video {path}: OpenCV's {fourcc} writer refused a {w}x{h} "
                         "video (MPEG-4 needs sides of 16..8190 px and a writable folder); "
                         "the CSV beside it holds the boxes.")
    n = 0
    try:
        for frame in frames:
            writer.write(frame)
            n += 1
    finally:
        writer.release()
    written = -1
    if path.is_file() and path.stat().st_size > 0:
        cap = cv2.VideoCapture(str(path))
        written = int(cap.get(cv2.CAP_PROP_FRAME_COUNT)) if cap.isOpened() else -1
        cap.release()
    if n and written < 1:
        raise ValueError(f"writing video {path} failed: {n} frames were given but the file "
                         "holds none (disk full, or a codec that refused the frames).")
    return n


def load_video(path, groundtruth=None, name: str | None = None) -> Clip:
    """Load a video file; ground truth from ``groundtruth`` or a ``<stem>.groundtruth.txt`` beside it.

    Without ground truth every row is NaN (tracking still works; scores need ground truth).
    """
    path = check_file(path, what="video file")
    n, listed = _count_frames(path)
    if n == 0:
        raise ValueError(f"video {path} has no decodable frames: is it empty or corrupt?")
    if listed > n:      # a frame the decoder cannot read ends the stream early: say which
        msg = (f"video {path}: frame {n} (counting from 0) cannot be decoded; the file lists "
               f"{listed} frames, so it is truncated or corrupt from there")
        if n < 2:
            raise ValueError(msg + "; re-encode or re-download it "
                             "(e.g. ffmpeg -i in.avi -c:v libx264 out.mp4).")
        warnings.warn(msg + f"; only frames 0..{n - 1} are used.", CorruptFrameWarning,
                      stacklevel=2)
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


#: the environment variable naming the folder of sequences loadable by name
SEQUENCES_ENV = "TRACKBOOK_SEQUENCES"


def sequences_root() -> Path | None:
    """The folder :func:`find_sequences` reads by default, by one rule: ``$TRACKBOOK_SEQUENCES``
    if set, else ``../shared/data/sequences`` beside the source checkout trackbook runs from
    (the folder holding ``pyproject.toml`` above the package: the development data next to a
    clone); None for an installed copy with no checkout around it. The working directory plays
    no part."""
    env = os.environ.get(SEQUENCES_ENV)
    if env:
        return Path(env).expanduser()
    package = Path(__file__).resolve().parents[1]
    for repo in (package.parent, package.parent.parent):    # flat or src layout
        if (repo / "pyproject.toml").is_file():
            return repo.parent / "shared" / "data" / "sequences"
    return None


def find_sequences(root=None) -> dict[str, Path]:
    """OTB-style sequence folders under ``root``, by name.

    ``root`` defaults to :func:`sequences_root` (``$TRACKBOOK_SEQUENCES``, else
    ``../shared/data/sequences`` beside the source checkout). Returns an empty dict when there
    is none, so callers can skip cleanly.
    """
    if root is None:
        root = sequences_root()
    if root is None or not Path(root).is_dir():
        return {}
    root = Path(root)
    return {
        p.name: p for p in sorted(list_dir(root, what="sequences folder"))
        if p.is_dir() and _find_groundtruth(p) and (p / "img").is_dir()
    }
