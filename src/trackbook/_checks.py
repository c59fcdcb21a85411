"""Input checks shared by every public entry point.

Each check either returns a clean value or raises a ``ValueError`` whose message names the
problem *and* the fix, because the people calling these are students in the middle of an
assignment.
"""

from __future__ import annotations

import datetime
import errno
import math
import os
import stat
from numbers import Real
from pathlib import Path

import numpy as np


def check_frame(frame, *, name: str = "frame") -> np.ndarray:
    """Return ``frame`` if it is an H x W x 3 ``uint8`` BGR image, else raise ``ValueError``."""
    if not isinstance(frame, np.ndarray):
        raise ValueError(
            f"{name} must be a numpy array (H x W x 3, uint8, BGR as cv2.imread returns), "
            f"got {type(frame).__name__}. Read frames with cv2.imread or trackbook.clips.load."
        )
    if frame.ndim == 2:
        raise ValueError(
            f"{name} is a grey image of shape {frame.shape}; trackers expect H x W x 3 BGR. "
            "Convert it with cv2.cvtColor(frame, cv2.COLOR_GRAY2BGR)."
        )
    if frame.ndim != 3 or frame.shape[2] not in (3,):
        if frame.ndim == 3 and frame.shape[2] == 4:
            raise ValueError(
                f"{name} has 4 channels (BGRA); trackers expect 3. "
                "Drop alpha with cv2.cvtColor(frame, cv2.COLOR_BGRA2BGR)."
            )
        raise ValueError(
            f"{name} has shape {frame.shape}; trackers expect H x W x 3 (BGR). "
            "Pass one video frame as cv2.imread returns it."
        )
    if frame.dtype != np.uint8:
        raise ValueError(f"{name} has dtype {frame.dtype}; trackers expect uint8 in 0..255. "
                         + _dtype_advice(frame))
    if frame.shape[0] == 0 or frame.shape[1] == 0:
        raise ValueError(f"{name} has shape {frame.shape}: it is empty (no pixels); pass a "
                         "real image.")
    if frame.shape[0] < 2 or frame.shape[1] < 2:
        raise ValueError(f"{name} has shape {frame.shape}: a single row or column of pixels; "
                         "a tracker needs an image at least 2 x 2 pixels (is the frame read "
                         "or reshaped the wrong way round?).")
    return frame


def _dtype_advice(frame: np.ndarray) -> str:
    """How to convert a non-uint8 frame to uint8 0..255, from its dtype and its values."""
    if frame.dtype == np.uint16:
        return ("A 16-bit frame (0..65535) keeps its top 8 bits with (frame >> 8).astype("
                "np.uint8), or scales with cv2.convertScaleAbs(frame, alpha=255 / 65535).")
    if np.issubdtype(frame.dtype, np.integer) or frame.dtype == np.bool_:
        return "Convert with np.clip(frame, 0, 255).astype(np.uint8) if it holds 0..255."
    if np.issubdtype(frame.dtype, np.floating) and frame.size:
        finite = frame[np.isfinite(frame)]
        hi = float(finite.max()) if finite.size else 0.0
        if hi > 1.0:
            return ("Its values reach {:g}, so it is already in 0..255: convert with "
                    "np.clip(frame, 0, 255).astype(np.uint8) (not frame * 255).".format(hi))
    return ("For a float image in 0..1 convert with "
            "np.clip(frame * 255, 0, 255).astype(np.uint8).")


def _fmt(box) -> str:
    """``(10, 20, 30, 0.5)``: a box in plain numbers (no ``np.float64(...)`` in messages)."""
    return "(" + ", ".join(f"{float(v):g}" for v in box) + ")"


#: What an element of each numpy dtype kind is, in a message (kinds ``i``, ``u``, ``f`` are
#: the real numbers a box accepts).
_KIND_WORDS = {"b": "a boolean", "c": "a complex value", "m": "a time span (timedelta64)",
               "M": "a date (datetime64)", "U": "text", "S": "bytes", "V": "a structured value"}
#: How to fix an element of each kind of problem.
_FIXES = {
    "a boolean": "a box is pixel numbers, not True/False",
    "a complex value": "pass the real parts (np.real(box)) if the imaginary parts are 0",
    "a time span (timedelta64)": "a box is pixel coordinates, not a time",
    "a date (datetime64)": "a box is pixel coordinates, not a date",
    "a date": "a box is pixel coordinates, not a date",
    "a time span": "a box is pixel coordinates, not a time",
    "text": "convert it first, e.g. [float(v) for v in text.split(',')]",
    "bytes": "decode and convert it first, e.g. [float(v) for v in data.decode().split(',')]",
    "a masked array": "pass a plain array: box.filled(np.nan) where the mask means "
                      "'unknown', or np.asarray(box) once nothing is masked",
    "a masked value": "pass plain numbers (NaN where a value is unknown, if the caller "
                      "allows it)",
    "an integer too large for a float": "pass pixel coordinates (at most about 1e308)",
}


def _element_problem(v) -> str | None:
    """Why scalar ``v`` is not a real number a box can hold (None: it is one)."""
    if isinstance(v, np.ndarray) and v.ndim == 0 and not isinstance(v, np.ma.MaskedArray):
        v = v[()]                   # a 0-d array: judge the numpy scalar it holds
    if isinstance(v, np.ma.core.MaskedConstant):
        return "a masked value"
    if isinstance(v, (bool, np.bool_)):
        return "a boolean"
    if isinstance(v, (str, np.str_)):
        return "text"
    if isinstance(v, (bytes, bytearray, memoryview, np.bytes_)):
        return "bytes"
    if isinstance(v, (complex, np.complexfloating)):
        return "a complex value"
    if isinstance(v, np.datetime64):
        return "a date (datetime64)"
    if isinstance(v, np.timedelta64):
        return "a time span (timedelta64)"
    if isinstance(v, (datetime.date, datetime.time)):
        return "a date"
    if isinstance(v, datetime.timedelta):
        return "a time span"
    if isinstance(v, Real):
        try:
            float(v)
        except OverflowError:        # 10**400: float() cannot hold it
            return "an integer too large for a float"
        return None
    return "None" if v is None else f"a {type(v).__name__}"


def _refuse(name: str, what: str, problem: str, value, where: str = "") -> ValueError:
    fix = _FIXES.get(problem, "pass int or float values")
    shown = " ".join(repr(value).split())
    shown = shown if len(shown) <= 60 else shown[:57] + "..."
    shown = "" if value is None else f" {shown}"
    return ValueError(f"{name} must be {what}; got {problem}{shown}{where}; {fix}.")


def _scalars(values, path=()):
    """``(index path, element)`` of every element of nested lists/tuples, in order (an array
    inside them is one element, checked by its dtype)."""
    for i, v in enumerate(values):
        if isinstance(v, (list, tuple)):
            yield from _scalars(v, (*path, i))
        else:
            yield (*path, i), v


def real_values(values, *, name: str, what: str = "numbers") -> np.ndarray:
    """``values`` (a number, a sequence or nested sequences of numbers, or an array) as a float
    array of the same shape, refusing whatever is not a real number: booleans, complex
    values, dates and time spans, text and bytes, masked arrays, objects, and integers too
    large for a float (which would otherwise raise ``OverflowError`` or be taken as 0/1, the
    real part, or a count of nanoseconds). NaN and infinity pass: callers decide.

    ``what`` says what ``values`` should be, for the message (``"four numbers (x, y, w, h),
    finite and real"``).
    """
    if isinstance(values, np.ma.MaskedArray) and not isinstance(values,
                                                                 np.ma.core.MaskedConstant):
        raise _refuse(name, what, "a masked array", values)
    if isinstance(values, (list, tuple)):
        for path, v in _scalars(values):
            if (isinstance(v, np.ndarray) and v.ndim
                    and not isinstance(v, np.ma.core.MaskedConstant)):
                real_values(v, name=name, what=what)
                continue
            problem = _element_problem(v)
            if problem is not None:
                where = (f" at position {path[0]}" if len(path) == 1
                         else " at " + "".join(f"[{k}]" for k in path))
                raise _refuse(name, what, problem, v, where)
        try:
            return np.asarray(values, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be {what}; got {values!r} (rows of different "
                             "lengths?).") from None
    if not isinstance(values, np.ndarray) or isinstance(values, np.ma.core.MaskedConstant):
        problem = _element_problem(values)      # one scalar, or an iterable of another kind
        if problem is not None and not hasattr(values, "__iter__"):
            raise _refuse(name, what, problem, values)
    arr = values if isinstance(values, np.ndarray) else np.asarray(values)
    kind = arr.dtype.kind
    if kind in "iuf":
        return arr.astype(float, copy=False)
    if kind == "O":
        for v in arr.ravel():
            if isinstance(v, np.ndarray) and v.ndim:
                real_values(v, name=name, what=what)
            elif _element_problem(v) is not None:
                raise _refuse(name, what, _element_problem(v), v)
        try:
            return arr.astype(float, copy=False)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be {what}; got {values!r}.") from None
    raise _refuse(name, what, _KIND_WORDS.get(kind, f"dtype {arr.dtype}"), values)


#: What a box is, in messages.
_BOX = "four numbers (x, y, w, h), finite and real"


def as_box(bbox, *, name: str = "bbox") -> np.ndarray:
    """Return ``bbox`` as a float array ``(x, y, w, h)`` with w, h > 0, else raise.

    Raises
    ------
    ValueError
        Not four values; a value that is not a real number (bool, complex, a date or time
        span, text, bytes, a masked array, an int beyond float range); NaN or infinity; a
        nested box; zero or negative width or height. The message names the problem and the
        fix.
    """
    if isinstance(bbox, (str, np.str_, bytes, bytearray, memoryview, np.bytes_)) or (
            isinstance(bbox, (list, tuple)) and any(isinstance(v, (str, bytes)) for v in bbox)
    ) or (isinstance(bbox, np.ndarray) and bbox.dtype.kind in "USO"
          and any(isinstance(v, (str, bytes)) for v in bbox.ravel())):
        items = (bbox if isinstance(bbox, (list, tuple)) else
                 bbox.ravel() if isinstance(bbox, np.ndarray) else [bbox])
        what = "text" if any(isinstance(v, str) for v in items) else "bytes"
        raise ValueError(f"{name} must be four numbers (x, y, w, h), got {what} {bbox!r}; "
                         f"{_FIXES[what]}.")
    if (isinstance(bbox, (list, tuple)) and any(
            isinstance(v, (list, tuple)) or (isinstance(v, np.ndarray) and v.ndim)
            for v in bbox)) or (isinstance(bbox, np.ndarray) and bbox.ndim > 1):
        raise ValueError(
            f"{name} {bbox!r} is nested; a box is four numbers (x, y, w, h) in one flat "
            "sequence. Two corners [[x1, y1], [x2, y2]] become (x1, y1, x2 - x1, y2 - y1).")
    if isinstance(bbox, (set, frozenset, dict)):
        raise ValueError(f"{name} must be {_BOX}, in order; got a {type(bbox).__name__} "
                         f"{bbox!r}, which has no order: pass a tuple or a list.")
    box = real_values(bbox, name=name, what=_BOX)
    if box.ndim > 1:
        raise ValueError(f"{name} {bbox!r} is nested; a box is four numbers (x, y, w, h) in "
                         "one flat sequence.")
    box = box.reshape(-1)
    if box.shape != (4,):
        raise ValueError(
            f"{name} must be four numbers (x, y, w, h): top-left corner, width, height; "
            f"got {box.size} values."
        )
    if not np.all(np.isfinite(box)):
        raise ValueError(f"{name} {_fmt(box)} contains NaN or infinity; pass finite numbers.")
    if box[2] <= 0 or box[3] <= 0:
        raise ValueError(
            f"{name} {_fmt(box)} has zero or negative size; width and height must be > 0 "
            "(the box is (x, y, w, h), not (x1, y1, x2, y2))."
        )
    return box


def clip_box(bbox, frame_shape) -> np.ndarray:
    """Intersect a box ``(x, y, w, h)`` with the frame; raise if nothing is left."""
    box = as_box(bbox)
    H, W = frame_shape[:2]
    if box[2] < 1 or box[3] < 1:
        raise ValueError(
            f"bbox {_fmt(box)} has a side under 1 px ({box[2]:g} x {box[3]:g}); a target box "
            "must be at least 1 x 1 pixel (x, y, w, h in pixels)."
        )
    x0, y0 = max(box[0], 0.0), max(box[1], 0.0)
    x1, y1 = min(box[0] + box[2], float(W)), min(box[1] + box[3], float(H))
    if x1 - x0 < 1 or y1 - y0 < 1:
        raise ValueError(
            f"bbox {_fmt(box)} lies outside the {W}x{H} frame; "
            "give a box inside the image (x, y are the top-left corner in pixels)."
        )
    return np.array([x0, y0, x1 - x0, y1 - y0])


def check_box_in_frame(bbox, frame_shape, *, name: str = "bbox", tol: float = 1.0) -> np.ndarray:
    """Return ``bbox`` if it lies inside the frame (within ``tol`` px), else raise."""
    box = as_box(bbox, name=name)
    H, W = frame_shape[:2]
    x, y, w, h = box
    if x + w <= 0 or y + h <= 0 or x >= W or y >= H:
        raise ValueError(
            f"{name} {_fmt(box)} lies wholly outside the {W}x{H} frame; "
            "give the target's box in pixel coordinates of this frame."
        )
    if x < -tol or y < -tol or x + w > W + tol or y + h > H + tol:
        raise ValueError(
            f"{name} {_fmt(box)} lies partly outside the {W}x{H} frame; "
            "clip it first with trackbook.trackers.clip_box(bbox, frame.shape)."
        )
    return clip_box(box, frame_shape)


def check_seed(seed) -> None:
    """Raise ``ValueError`` unless ``seed`` is None or a non-negative integer (not a bool)."""
    if seed is None:
        return
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)):
        raise ValueError(f"seed must be a non-negative int or None, got {seed!r}.")
    if seed < 0:
        raise ValueError(f"seed = {seed} is negative; pass 0 or a positive integer "
                         "(or None for a fresh random run).")


def positional_seed_error(call: str, what: str) -> TypeError:
    """The error for a seed passed by position: ``what`` (``"create()"``) takes it as a
    keyword, as in ``call`` (``"create('color-pf', seed=50)"``). A positional number after the
    name used to be taken as the seed without a word, which hid a misplaced argument."""
    return TypeError(f"{what} takes the seed as a keyword: {call}.")


#: Frames an evaluation needs: frame 0 starts the tracker, frame 1 is the first one scored.
MIN_FRAMES = 2


def check_max_frames(max_frames, *, name: str = "max_frames") -> int | None:
    """``max_frames`` as an ``int`` (``None``: the whole clip); ``ValueError`` unless it is an
    integer (not a bool) of at least :data:`MIN_FRAMES`. ``name`` is how the caller spells it
    (``"--max-frames"`` on the command line)."""
    if max_frames is None:
        return None
    if (isinstance(max_frames, (bool, np.bool_)) or not isinstance(max_frames, (int, np.integer))
            or max_frames < MIN_FRAMES):
        raise ValueError(f"{name} = {max_frames!r}: pass an integer of at least {MIN_FRAMES} "
                         "(frame 0 starts the tracker, frame 1 is the first one scored).")
    return int(max_frames)


def check_finite_number(value, *, name: str) -> None:
    """Raise ``ValueError`` if ``value`` is a number that is NaN or infinite."""
    if isinstance(value, bool):
        return
    if isinstance(value, Real) and not math.isfinite(float(value)):
        raise ValueError(f"parameter {name} = {value!r} is not finite; pass a real number.")
    if isinstance(value, (tuple, list)):
        for v in value:
            check_finite_number(v, name=name)


def check_boxes(arr, *, name: str) -> np.ndarray:
    """Return ``arr`` as an N x 4 float array, else raise ``ValueError`` (NaN rows pass:
    they mark frames without a box; values that are not real numbers are refused as in
    :func:`real_values`)."""
    a = real_values(arr, name=name, what="an N x 4 array of boxes (x, y, w, h), real numbers")
    if a.ndim == 1 and a.shape[0] == 4:
        a = a[None, :]
    if a.ndim != 2 or a.shape[1] != 4:
        raise ValueError(
            f"{name} must be an N x 4 array of boxes (x, y, w, h), got shape {a.shape}."
        )
    return a


def fs_error(e: OSError, path, what: str = "file") -> Exception:
    """The error to raise for an ``OSError`` met while reading ``path``: a
    ``PermissionError``, ``FileNotFoundError`` or ``ValueError`` whose message names the path,
    what went wrong (permission, dangling link, link loop, ...) and the fix."""
    p = Path(path)
    if isinstance(e, PermissionError) or e.errno in (errno.EACCES, errno.EPERM):
        return PermissionError(
            f"{what} {p}: permission denied; make it readable (e.g. chmod -R u+rX {p}) or "
            "copy it somewhere you can read.")
    if e.errno == errno.ELOOP:
        return ValueError(f"{what} {p} is a symbolic-link loop (a link that points back to "
                          "itself); replace the link with the real file or folder.")
    if isinstance(e, FileNotFoundError) or e.errno == errno.ENOENT:
        if os.path.islink(p):
            return FileNotFoundError(
                f"{what} {p} is a link to {os.readlink(p)}, which does not exist (a dangling "
                "link); fix the link or copy the real file there.")
        return FileNotFoundError(f"{what} {p} does not exist.")
    if e.errno == errno.EISDIR:
        return ValueError(f"{what} {p} is a folder, not a file.")
    return ValueError(f"{what} {p} cannot be read: {e.strerror or e}.")


def check_file(path, *, what: str = "file", fix: str = "") -> Path:
    """Return ``path`` as a ``Path`` if it is an existing regular file, else raise the error
    :func:`fs_error` gives (missing, dangling link, link loop, no permission, a folder); ``fix``
    is appended to the message of a missing file."""
    p = Path(path)
    try:
        st = os.stat(p)
    except OSError as e:
        err = fs_error(e, p, what)
        if fix and type(err) is FileNotFoundError:
            err = FileNotFoundError(f"{str(err).rstrip('.')}; {fix}")
        raise err from None
    if stat.S_ISDIR(st.st_mode):
        raise ValueError(f"{what} {p} is a folder, not a file.")
    return p


def list_dir(folder, *, what: str = "folder") -> list[Path]:
    """The entries of ``folder`` (``Path.iterdir``), file-system errors named as in
    :func:`fs_error`."""
    try:
        return list(Path(folder).iterdir())
    except OSError as e:
        raise fs_error(e, folder, what) from None
