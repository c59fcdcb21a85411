"""What the ``trackbook`` commands write, and where: annotated frames, the video codec, the
output file names, the ``--out`` folder, and files written only when complete
(:func:`staged`) and never over an existing one unless asked (:func:`refuse_existing`).

Kept apart from :mod:`trackbook.cli` (argument parsing and messages) so both stay short.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import re
import tempfile
from pathlib import Path

import cv2
import numpy as np

from ._cli_errors import os_problem

#: Box colours (BGR) an estimate may be drawn in: red, blue, orange, purple, cyan, magenta,
#: yellow, white. Ground truth is always green (``GT_COLOR``); :func:`estimate_colors` orders
#: the rest by how far they are from the target's own colours.
PALETTE = ((40, 39, 214), (180, 119, 31), (14, 127, 255), (189, 103, 148),
           (255, 255, 0), (255, 0, 255), (0, 230, 255), (255, 255, 255))
GT_COLOR = (44, 160, 44)


def _lab(bgr) -> np.ndarray:
    """CIE-Lab (L in 0..100, a and b around 0) of BGR uint8 colours, rows of 3."""
    lab = cv2.cvtColor(np.asarray(bgr, np.uint8).reshape(1, -1, 3), cv2.COLOR_BGR2LAB)
    lab = lab.reshape(-1, 3).astype(float)
    return np.column_stack([lab[:, 0] * 100 / 255, lab[:, 1] - 128, lab[:, 2] - 128])


def estimate_colors(frame, boxes) -> list[tuple]:
    """The palette sorted from the colour that stands out most on the targets to the least.

    For each palette colour the Lab distance to every pixel inside the target boxes (and a
    margin of half a box around them, where the box's outline is drawn) is taken; its 10th
    percentile says how far the colour is from the bulk of what it is drawn over, so one odd
    pixel does not decide. The ground truth's green is never chosen.
    """
    frame = np.asarray(frame)
    H, W = frame.shape[:2]
    pix = []
    for b in boxes:
        if b is None or not np.all(np.isfinite(b)):
            continue
        x, y, w, h = (float(v) for v in b)
        x0, y0 = int(max(0, x - w / 2)), int(max(0, y - h / 2))
        x1, y1 = int(min(W, x + 1.5 * w)), int(min(H, y + 1.5 * h))
        if x1 > x0 and y1 > y0:
            pix.append(frame[y0:y1, x0:x1].reshape(-1, 3))
    if not pix:
        return list(PALETTE)
    pix = np.concatenate(pix)
    if len(pix) > 4000:     # a subsample keeps this instant on a large box
        pix = pix[np.linspace(0, len(pix) - 1, 4000).astype(int)]
    lab_pix = _lab(pix)
    lab_pal = _lab(PALETTE)
    d = np.linalg.norm(lab_pal[:, None, :] - lab_pix[None, :, :], axis=2)
    score = np.percentile(d, 10, axis=1)
    return [PALETTE[i] for i in np.argsort(-score, kind="stable")]


def annotate(frame, boxes: dict, gt=None, colors=None):
    """Draw boxes on a copy of a BGR frame (OpenCV drawing, for videos).

    Each estimate is drawn in its colour (``colors``, default the palette in order) over a
    1-px black outline on both sides, so it stays visible whatever it crosses.
    """
    img = frame.copy()
    colors = list(colors or PALETTE)
    if gt is not None and np.all(np.isfinite(gt)):
        x, y, w, h = (int(round(v)) for v in gt)
        cv2.rectangle(img, (x, y), (x + w, y + h), GT_COLOR, 1, cv2.LINE_AA)
    for i, (label, b) in enumerate(boxes.items()):
        if b is None or not np.all(np.isfinite(b)):
            continue
        x, y, w, h = (int(round(v)) for v in b)
        c = tuple(int(v) for v in colors[i % len(colors)])
        cv2.rectangle(img, (x, y), (x + w, y + h), (0, 0, 0), 4, cv2.LINE_AA)
        cv2.rectangle(img, (x, y), (x + w, y + h), c, 2, cv2.LINE_AA)
        org = (x, max(y - 4, 10))
        cv2.putText(img, label, org, cv2.FONT_HERSHEY_SIMPLEX, 0.4, (0, 0, 0), 3, cv2.LINE_AA)
        cv2.putText(img, label, org, cv2.FONT_HERSHEY_SIMPLEX, 0.4, c, 1, cv2.LINE_AA)
    return img


@contextlib.contextmanager
def _quiet_stderr():
    """Silence C-level stderr (OpenCV's and FFmpeg's logs while a codec is probed)."""
    try:
        fd = os.dup(2)
    except OSError:         # no stderr to silence
        yield
        return
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 2)
            yield
    finally:
        os.dup2(fd, 2)
        os.close(fd)


_CODEC: list = []


def video_codec() -> str:
    """``"avc1"`` (H.264, plays in browsers) when this OpenCV build can write it, else
    ``"mp4v"`` (MPEG-4 part 2: plays in VLC or mpv, not in browsers). Probed once."""
    if not _CODEC:
        with tempfile.TemporaryDirectory() as d, _quiet_stderr():
            w = cv2.VideoWriter(str(Path(d) / "probe.mp4"), cv2.VideoWriter_fourcc(*"avc1"),
                                10, (64, 48))
            ok = w.isOpened()
            if ok:
                w.write(np.zeros((48, 64, 3), np.uint8))
            w.release()
        _CODEC.append("avc1" if ok else "mp4v")
    return _CODEC[0]


CODEC_NOTE = {"avc1": "H.264, plays in browsers and every player",
              "mp4v": "MPEG-4 part 2: this OpenCV has no H.264 encoder; play it in VLC or mpv "
                      "(browsers do not play it)"}


def open_video(path, fps, size):
    """A ``cv2.VideoWriter`` with :func:`video_codec`; returns ``(writer, codec)``."""
    codec = video_codec()
    with _quiet_stderr():
        w = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*codec), float(fps or 25), size)
    if not w.isOpened():
        raise ValueError(f"cannot write the video {path}; pass a writable --out folder.")
    return w, codec


def write_video_as(write_video, path, tmp, frames, fps, size, codec) -> None:
    """``write_video`` into the temporary ``tmp`` of ``path``; its error (which names the file
    and the fix) names ``path``. The writer is released either way, also on SIGTERM."""
    try:
        write_video(tmp, frames, fps, size, fourcc=codec)
    except ValueError as e:
        raise ValueError(str(e).replace(str(tmp), str(path))) from None


def settings_hash(settings: dict) -> str:
    """Six hex digits of the SHA-1 of the run's settings (tracker, seed, params, ...)."""
    text = json.dumps(settings, sort_keys=True, default=repr)
    return hashlib.sha1(text.encode()).hexdigest()[:6]


def output_stem(tracker: str, clip: str, settings: dict, default_settings: dict) -> str:
    """``tracker_clip`` for a run with the default settings, else ``tracker_clip_<hash>``: a
    run with other params, seed, preset, starting box, ``--max-frames`` or ground truth gets
    its own files instead of being refused as another run's (or overwriting it)."""
    from .evaluation.runs import safe_name  # a clip name from a file may hold anything

    stem = f"{tracker}_{safe_name(clip)}"
    if settings_hash(settings) == settings_hash(default_settings):
        return stem
    return f"{stem}_{settings_hash(settings)}"


def csv_text(rows) -> str:
    """``rows`` as CSV text (write it with ``newline=""``)."""
    import csv
    import io

    buf = io.StringIO()
    csv.writer(buf).writerows(rows)
    return buf.getvalue()


@contextlib.contextmanager
def staged(paths):
    """Write a command's outputs through temporary files beside them.

    Yields ``{final path: temporary path}`` (the temporary keeps the final suffix, which
    OpenCV's video writer goes by). When the block ends normally each temporary replaces its
    final file (``os.replace``: a reader sees the old file or the new one, never half of one);
    when it raises (an error, Ctrl-C, SIGTERM) every temporary is removed, so an interrupted
    run leaves no half-written video or CSV and the earlier files as they were.
    """
    mask = os.umask(0)
    os.umask(mask)
    temps: dict = {}
    try:
        for p in map(Path, paths):
            try:
                fd, tmp = tempfile.mkstemp(dir=p.parent, prefix=f".{p.stem}.",
                                           suffix=f".partial{p.suffix}")
            except OSError as e:    # name the file the user asked for, not the temporary
                raise OSError(e.errno, e.strerror, str(p)) from None
            os.close(fd)
            os.chmod(tmp, 0o666 & ~mask)     # an ordinary file's mode, not mkstemp's 0600
            temps[p] = Path(tmp)
        yield temps
        for p, tmp in temps.items():
            os.replace(tmp, p)
    finally:
        for tmp in temps.values():
            with contextlib.suppress(OSError):
                tmp.unlink(missing_ok=True)


# --------------------------------------------------------------------------- --out
def check_out_dir(path) -> Path:
    """``--out`` checked before any work (a file in the way is named in the error); the
    folder itself is made by :func:`out_dir` once there is something to write, so a failing
    command leaves no empty folder behind."""
    out = Path(path)
    try:
        for p in (out, *out.parents):
            if p.exists() and not p.is_dir():
                raise ValueError(f"--out {path}: {p} is a file, not a folder; pass a folder "
                                 "name (it is created if missing).")
    except OSError as e:       # a name the OS refuses (too long), a folder it cannot search
        raise ValueError(f"--out {path}: {os_problem(e)}") from None
    return out


def out_dir(path) -> Path:
    """``--out``: an existing folder or a new one; a file in the way is named in the error."""
    out = check_out_dir(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise ValueError(f"--out {path}: cannot create the folder: {os_problem(e)}") from None
    return out


def refuse_existing(paths, force: bool) -> None:
    """Outputs are never replaced unless asked: an existing one is an error naming ``--force``."""
    if force:
        return
    for p in paths:
        if Path(p).exists():
            raise ValueError(f"{p} exists (an earlier run's); pass --force to replace it, or "
                             "another --out.")


def made_folders(path) -> list[Path]:
    """The folders of ``path`` that do not exist yet (deepest last)."""
    if path is None:
        return []
    p, missing = Path(path), []
    while not p.exists() and p != p.parent:
        missing.append(p)
        p = p.parent
    return missing[::-1]


def remove_if_empty(folders) -> None:
    """After a failed command: remove the ``--out`` folders it created if they are empty."""
    for d in reversed(folders):
        # only succeeds on an empty folder; a name the OS refused (too long) was never made,
        # so its parent is still tried
        with contextlib.suppress(OSError):
            d.rmdir()


def plain_doc(doc: str, name: str = "") -> str:
    """A docstring's first paragraph as a terminal shows it: the reST backticks, the
    quote markers of the register (the book shows the passage; a terminal cannot) and a leading
    repetition of the tracker's name dropped, white space folded."""
    text = " ".join((doc or "").strip().split("\n\n")[0].split())
    text = re.sub(r"\s*\[quote: [^\]]*\]", "", text)
    text = re.sub(r"``([^`]*)``", r"\1", text)
    text = re.sub(r":\w+:`~?([^`]*)`", r"\1", text)
    return text.removeprefix(f"{name}:").strip() if name else text
