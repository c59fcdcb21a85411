"""OpenCV's ``TrackerMIL`` behind the trackbook contract: the reference row of every table.

It is not one of the papers' trackers: ``trackers.available()`` lists it last, after them, and
``trackers.available(reference=False)`` leaves it out; ask for it as ``trackers.create("opencv-mil")``.
"""

from __future__ import annotations

import atexit
import select
import struct
import subprocess
import sys
import weakref
from pathlib import Path

import numpy as np

from .base import Tracker
from .generic_confidence import ColourCheck

_CHILD = str(Path(__file__).with_name("_mil_child.py"))
_LIVE: "weakref.WeakSet[OpenCVMIL]" = weakref.WeakSet()

#: Limits measured with OpenCV 5.0 (each case in a fresh process with a 5 s timeout):
#: ``init`` never returns on a box of 4 x 4 px (4 x 5 and 5 x 4 work), asserts
#: (tracker_mil.cpp:80-81) on a box within 4 px of the frame's width or height
#: (316 x 236 in 320 x 240; 315 x 235 works) and on frames of 8 x 8 and 12 x 12 px (16 x 16 works).
MIN_SIDE = 6
EDGE_MARGIN = 8
MIN_FRAME = 16
#: Seconds the child may take for one frame before the run is declared lost (a safety net:
#: the limits above already keep OpenCV away from the boxes on which it hangs).
TIMEOUT_S = 60.0


def safe_box(box, shape) -> tuple[int, int, int, int]:
    """The integer box MIL is given: sides at least ``MIN_SIDE`` and at most the frame's side
    minus ``EDGE_MARGIN``, centred on ``box``'s centre and moved inside the frame.

    Raises ``ValueError`` when the frame is smaller than ``MIN_FRAME`` px on a side.
    """
    H, W = shape[:2]
    if H < MIN_FRAME or W < MIN_FRAME:
        raise ValueError(f"opencv-mil needs frames of at least {MIN_FRAME} x {MIN_FRAME} px "
                         f"(got {W} x {H}); OpenCV's MIL asserts on smaller ones. Upscale "
                         "the clip or use another tracker.")
    x, y, w, h = (float(v) for v in box)
    cx, cy = x + w / 2, y + h / 2
    w = int(round(min(max(w, MIN_SIDE), W - EDGE_MARGIN)))
    h = int(round(min(max(h, MIN_SIDE), H - EDGE_MARGIN)))
    x = int(round(min(max(cx - w / 2, 0), W - w)))
    y = int(round(min(max(cy - h / 2, 0), H - h)))
    return x, y, w, h


class OpenCVMIL(Tracker):
    """Babenko et al.'s MIL tracker as shipped by OpenCV (``cv2.TrackerMIL``), made repeatable.

    OpenCV's MIL draws its training samples from a random generator that keeps its state from
    one run to the next within a process, and ``cv2.setRNGSeed`` does not reset it (measured:
    two runs on one clip in one process differ by up to 25 px), while the n-th run of a fresh
    process is always the same. So each ``init`` starts a fresh child Python process
    (``_mil_child.py``, which imports only cv2 and numpy) that runs exactly one MIL run; frames
    go to it through a pipe. Every run is thus the *first* run of its process: the same clip
    gives the same boxes in ``evaluate``, frame by frame, in ``bench`` (fresh or resumed, any
    number of workers) and on every page of the book. The cost is the child's start (once per
    run) plus copying each frame through the pipe.

    The box is adjusted before OpenCV sees it (:func:`safe_box`): sides below ``MIN_SIDE`` px
    are grown about the centre (MIL never returns from ``init`` on a 4 x 4 box), sides within
    ``EDGE_MARGIN`` px of the frame's are shrunk (MIL asserts on them), and frames below
    ``MIN_FRAME`` px are refused with a ``ValueError``. A child that does not answer within
    ``TIMEOUT_S`` seconds is killed and the run reports ``ok=False`` from then on.

    Lost rule
    ---------
    OpenCV's MIL learns inside its own ``update`` (the classifier is trained on the box it
    has just found), which trackbook cannot split: ``_locate`` is that ``update`` and
    ``_learn`` does nothing. So the failure-detection layer can withhold ``ok`` from MIL (a
    frame judged lost keeps the last box), but it cannot stop MIL's model from learning the
    frame: a departure from the other trackers forced by OpenCV. A constant frame (all
    black, all white, one grey: grey levels spanning at most ``flat_range``) is lost and not
    shown to MIL at all (nothing to match, and MIL would learn it). MIL's own ``ok`` (False
    when OpenCV gives up, or the child process is gone) also makes the frame lost. There is
    no ``opencv-mil-redetect``: restarting MIL at a re-detected box would start a new model,
    not move the old one.

    Confidence
    ----------
    OpenCV exposes no classifier margin of MIL, so ``state().confidence`` is the failure
    layer's generic confidence, the appearance match of MIL's box against the first frame's
    (:meth:`~trackbook.trackers.generic_confidence.ColourCheck.match`): the Bhattacharyya coefficient
    rho = sum_u sqrt(h_u h_u^ref) of its kernel colour histogram (HSV 8 x 8 x 4, eq. 1 of
    Lee et al. 2012) against the first frame's, in [0, 1]; 0 when the frame computed none
    (a constant frame, or MIL's process gone).
    """

    name = "opencv-mil"

    def __init__(self, *args, seed: int | None = 0, **params):
        super().__init__(*args, seed=seed, **params)    # the base refuses a positional seed
        self._proc = None
        self._dead = False
        _LIVE.add(self)

    # -- child process ---------------------------------------------------------------------
    def _start(self):
        self.close()
        self._proc = subprocess.Popen([sys.executable, "-I", _CHILD], stdin=subprocess.PIPE,
                                      stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                      bufsize=0)
        self._dead = False

    def close(self) -> None:
        """Stop the child process (also done on ``init``, garbage collection and exit)."""
        p, self._proc = self._proc, None
        if p is None:
            return
        try:
            if p.poll() is None:
                p.stdin.write(b"Q")
                p.stdin.close()
                p.wait(timeout=2)
        except Exception:
            pass
        if p.poll() is None:
            p.kill()
            p.wait()
        for s in (p.stdout, p.stderr, p.stdin):
            try:
                s.close()
            except Exception:
                pass

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    def _ask(self, cmd: bytes, frame, box=None):
        if self._proc is None or self._dead:
            return None
        f = np.ascontiguousarray(frame, dtype=np.uint8)
        c = 1 if f.ndim == 2 else f.shape[2]
        msg = cmd + struct.pack("<iii", f.shape[0], f.shape[1], c) + f.tobytes()
        if box is not None:
            msg += struct.pack("<4i", *box)
        try:
            self._proc.stdin.write(msg)
            out = self._proc.stdout
            ready, _, _ = select.select([out], [], [], TIMEOUT_S)
            data = b""
            while ready and len(data) < 33:
                chunk = out.read(33 - len(data))
                if not chunk:
                    break
                data += chunk
            if len(data) == 33:
                return struct.unpack("<?4d", data)
        except (BrokenPipeError, OSError):
            pass
        err = b""
        if self._proc.poll() is not None:
            err = self._proc.stderr.read() or b""
        self._dead = True
        self.close()
        if cmd == b"I" and err:
            raise RuntimeError("opencv-mil failed in init: "
                               + err.decode(errors="replace").strip().splitlines()[-1])
        return None

    # -- trackbook contract ----------------------------------------------------------------
    def _init(self, frame, box):
        b = safe_box(box, frame.shape)
        self._start()
        self._ask(b"I", frame, b)
        self._colour = ColourCheck(frame, box)

    def _locate(self, frame):
        """OpenCV's ``update`` (which also trains MIL: see "Lost rule"); returns
        ``(box, colour rho, MIL's own ok)``."""
        last = np.asarray(self.bbox, dtype=float)
        if self._is_flat(frame):
            return last, 0.0, False             # not shown to MIL (see "Lost rule")
        r = self._ask(b"U", frame)
        if r is None or not r[0]:
            return last, 0.0, False
        box = np.asarray(r[1:], dtype=float)
        return box, float(self._colour.match(frame, box[None])[0]), True

    def _learn(self, frame, box):
        """Nothing: MIL has already learned inside OpenCV's ``update`` (see "Lost rule")."""


@atexit.register
def _close_all():
    for t in list(_LIVE):
        t.close()


REFERENCE = {OpenCVMIL.name: OpenCVMIL}
