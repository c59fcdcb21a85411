"""The child side of :class:`trackbook.trackers.reference.OpenCVMIL` (run as ``python -c``).

Kept free of trackbook imports so the child starts in the time it takes to import cv2 and numpy.
Protocol on stdin/stdout, little-endian: a command byte (``I`` init, ``U`` update, ``Q`` quit),
then for ``I``/``U`` a frame header ``<iii`` (h, w, channels) and its uint8 bytes; ``I`` adds the
box ``<4i``. The answer is ``<?4d`` (ok, x, y, w, h).
"""

import os
import struct
import sys

import cv2
import numpy as np

# A bench worker asks its MIL child for one OpenCV thread (see evaluation.parallel).
if os.environ.get("TRACKBOOK_CV_THREADS"):
    cv2.setNumThreads(int(os.environ["TRACKBOOK_CV_THREADS"]))


def _read(f, n):
    b = f.read(n)
    if len(b) != n:
        raise EOFError
    return b


def main():
    fin, fout = sys.stdin.buffer, sys.stdout.buffer
    tracker = None
    while True:
        try:
            cmd = _read(fin, 1)
        except EOFError:
            return
        if cmd == b"Q":
            return
        h, w, c = struct.unpack("<iii", _read(fin, 12))
        frame = np.frombuffer(_read(fin, h * w * c), np.uint8).reshape((h, w, c) if c > 1 else (h, w))
        if cmd == b"I":
            box = struct.unpack("<4i", _read(fin, 16))
            tracker = cv2.TrackerMIL_create()
            tracker.init(frame, box)
            ok, out = True, box
        else:
            ok, out = tracker.update(frame)
        fout.write(struct.pack("<?4d", bool(ok), *(float(v) for v in out)))
        fout.flush()


if __name__ == "__main__":
    main()
