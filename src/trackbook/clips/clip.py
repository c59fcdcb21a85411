"""A clip: frames (BGR uint8, sized, indexable, iterable), ground truth, and a frame rate."""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Sequence
from pathlib import Path

import cv2
import numpy as np

from .._checks import fs_error, real_values


class CorruptFrameWarning(UserWarning):
    """A frame that decodes only in part (a truncated JPEG, a video cut short): the warning
    names the file and the frame."""


def _truncated(data: bytes, suffix: str) -> bool:
    """True when an image file's bytes end before the format's end marker (JPEG's EOI
    ``FF D9``, PNG's ``IEND`` chunk): the decoder would fill the rest with grey."""
    tail = data[-4096:]
    if suffix in (".jpg", ".jpeg"):
        return b"\xff\xd9" not in tail
    if suffix == ".png":
        return b"IEND" not in tail
    return False


class FrameSequence(Sequence):
    """Base of the lazy frame containers: ``len``, ``[i]``, ``[a:b]`` and iteration."""

    def _get(self, i: int) -> np.ndarray:  # pragma: no cover
        raise NotImplementedError

    def __getitem__(self, i):
        n = len(self)
        if isinstance(i, slice):
            return _Slice(self, range(*i.indices(n)))
        i = int(i)
        if i < 0:
            i += n
        if not 0 <= i < n:
            raise IndexError(f"frame index {i} out of range for a clip of {n} frames")
        return self._get(i)

    def __iter__(self):
        for i in range(len(self)):
            yield self._get(i)

    @property
    def shape(self) -> tuple[int, int, int]:
        """Shape ``(H, W, 3)`` of one frame."""
        return self[0].shape


class _Slice(FrameSequence):
    def __init__(self, base: FrameSequence, idx: range):
        self._base, self._idx = base, idx

    def __len__(self):
        return len(self._idx)

    def _get(self, i):
        return self._base._get(self._idx[i])


class ArrayFrames(FrameSequence):
    """Frames held in one N x H x W x 3 array (the generated sample clips)."""

    def __init__(self, array: np.ndarray):
        array = np.asarray(array)
        if array.ndim != 4 or array.shape[3] != 3 or array.dtype != np.uint8:
            raise ValueError("ArrayFrames needs an N x H x W x 3 uint8 array")
        array.setflags(write=False)  # shared between callers through the cache
        self.array = array

    def __len__(self):
        return self.array.shape[0]

    def _get(self, i):
        return self.array[i]

    def __iter__(self):
        return iter(self.array)


class ImageFiles(FrameSequence):
    """Frames read from image files on access (an OTB ``img/`` folder)."""

    def __init__(self, paths):
        self.paths = [Path(p) for p in paths]

    def __len__(self):
        return len(self.paths)

    def _get(self, i):
        path = self.paths[i]
        img = cv2.imread(str(path), cv2.IMREAD_COLOR)
        if img is None:     # say which: missing, unreadable, a link loop, empty, not an image
            try:
                data = path.read_bytes()
            except OSError as e:
                raise fs_error(e, path, f"frame {i}: image") from None
            if not data:
                raise ValueError(f"frame {i}: image {path} is an empty file (0 bytes); the "
                                 "download or copy did not finish.")
            raise ValueError(f"frame {i}: image {path} ({len(data)} bytes) cannot be decoded: "
                             "it is corrupt or not an image (JPEG, PNG or BMP).")
        if _truncated(_tail(path), path.suffix.lower()):
            warnings.warn(f"frame {i}: image {path} is truncated (no end marker); the part "
                          "after the cut decodes as grey. Re-download or re-export it.",
                          CorruptFrameWarning, stacklevel=3)
        return img


def _tail(path: Path, n: int = 4096) -> bytes:
    """The last ``n`` bytes of a file (where an image format's end marker is)."""
    with open(path, "rb") as f:
        f.seek(0, 2)
        f.seek(max(f.tell() - n, 0))
        return f.read()


class VideoFrames(FrameSequence):
    """Frames decoded from a video file; sequential reads stream, random access seeks."""

    def __init__(self, path, n_frames: int):
        self.path = Path(path)
        self._n = n_frames
        self._cap = None
        self._next = 0

    def __len__(self):
        return self._n

    def _open(self):
        self._cap = cv2.VideoCapture(str(self.path))
        self._next = 0

    def _get(self, i):
        if self._cap is None or i < self._next:
            self._open()
        if i > self._next:
            self._cap.set(cv2.CAP_PROP_POS_FRAMES, i)
            self._next = i
        ok, img = self._cap.read()
        if not ok:
            raise ValueError(f"cannot decode frame {i} of {self.path}")
        self._next = i + 1
        return img

    def __iter__(self):
        cap = cv2.VideoCapture(str(self.path))
        try:
            for i in range(self._n):
                ok, img = cap.read()
                if not ok:
                    raise ValueError(f"cannot decode frame {i} of {self.path} (of "
                                     f"{self._n} counted when loaded); was the file changed?")
                yield img
        finally:
            cap.release()


@dataclasses.dataclass
class Clip:
    """A clip to track on.

    Attributes
    ----------
    name : str
    frames : FrameSequence
        BGR ``uint8`` frames: ``len(frames)``, ``frames[i]``, ``for f in frames``.
    groundtruth : ndarray, N x 4
        Boxes ``(x, y, w, h)``; rows of NaN where the target's box is unknown.
    fps : float
    targets : dict of str -> N x 4 ndarray
        Every annotated target (multi-target clips have several); ``groundtruth`` is the first.
    description : str
    attributes : tuple of str
        What makes it hard (OTB attribute codes such as ``IV``, ``OCC``, ``FM``).
    source : str
        ``"sample"`` or the path it was loaded from.
    """

    name: str
    frames: FrameSequence
    groundtruth: np.ndarray
    fps: float = 30.0
    targets: dict = dataclasses.field(default_factory=dict)
    description: str = ""
    attributes: tuple = ()
    source: str = ""

    def __post_init__(self):
        # a bool, complex, date or text array would otherwise become 0/1, its real part or
        # nanoseconds without a word
        gt = real_values(self.groundtruth, name=f"clip {self.name!r}: ground truth",
                         what="one (x, y, w, h) row of real numbers per frame (NaN: no box)")
        if gt.ndim != 2 or gt.shape[1] != 4 or gt.shape[0] != len(self.frames):
            raise ValueError(
                f"clip {self.name!r}: ground truth has shape {gt.shape} but there are "
                f"{len(self.frames)} frames; need one (x, y, w, h) row per frame."
            )
        gt.setflags(write=False)
        self.groundtruth = gt
        if not self.targets:
            self.targets = {"target": gt}
        else:
            self.targets = {k: real_values(v, name=f"clip {self.name!r}: target {k!r}",
                                           what="one (x, y, w, h) row of real numbers per "
                                                "frame (NaN: no box)")
                            for k, v in self.targets.items()}

    def __len__(self) -> int:
        return len(self.frames)

    @property
    def size(self) -> tuple[int, int]:
        """Frame size ``(width, height)``."""
        h, w = self.frames.shape[:2]
        return w, h

    def __repr__(self) -> str:
        w, h = self.size
        return f"Clip({self.name!r}, {len(self)} frames, {w}x{h}, fps={self.fps:g})"
