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
from .lost import ColourCheck, MatchGate, visible_fraction

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
    OpenCV's MIL answers ``ok=True`` on almost every frame, and its classifier's response is
    not exposed, so the wrapper applies the rules of the book's trackers to the box MIL
    returns: a constant frame (all black, all white, one grey: grey levels spanning at most
    ``flat_range``) is lost and not shown to MIL (it would learn it); a box with less than
    ``min_visible`` of its area in the frame is lost; a box whose kernel colour histogram
    (HSV 8 x 8 x 4, eq. 1 of Lee et al. 2012), at best over shifts of a quarter box
    (:meth:`~trackbook.trackers.lost.ColourCheck.match_near`: MIL does not place its box by
    colour), matches the first frame's poorly is lost (rho
    below 0.5, or below 0.7 and far outside its recent range,
    :class:`~trackbook.trackers.lost.MatchGate`, unless it stands out from the boxes around
    it: a sudden change of light). While lost, the whole frame is searched by
    colour (:meth:`~trackbook.trackers.lost.ColourCheck.search`, at most 325 histograms a
    frame, paid only while lost); a box that passes the gate restarts MIL there (a fresh child process, as ``init``) and is reported ``ok=True``.

    Confidence
    ----------
    OpenCV exposes no classifier margin of MIL, so ``state().confidence`` is the generic
    appearance match of the lost rule, not MIL's own: the Bhattacharyya coefficient
    rho = sum_u sqrt(h_u h_u^ref) of a kernel colour histogram against the first frame's,
    of MIL's box (best over the nine quarter-box shifts), or of the whole-frame search's best
    box on a frame that searched; in [0, 1]; 0 when the frame computed none (a constant
    frame, or MIL's process gone).
    """

    name = "opencv-mil"
    #: Less than this fraction of the box in the frame: the target is leaving (lost).
    min_visible = 0.5

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
        self._gate = MatchGate()
        self._lost = False
        self._rho = 0.0

    def _update(self, frame):
        last = np.asarray(self.bbox, dtype=float)
        self._rho = 0.0
        if self._is_flat(frame):
            self._lost = True
            return False, last                  # nothing to match (see "Lost rule")
        r = self._ask(b"U", frame)
        ok = r is not None and bool(r[0])
        box = np.asarray(r[1:], dtype=float) if ok else last
        if ok and visible_fraction(box, frame.shape) < self.min_visible:
            ok = False
        if ok:
            rho, near = self._colour.match_near(frame, box)
            self._rho = rho
            ok = not self._gate.lost(rho, lambda: self._colour.stands_out(frame, near, rho))
        if not ok and not self._dead:
            found, rho = self._colour.search(frame, max_boxes=300)
            self._rho = rho
            if visible_fraction(found, frame.shape) >= self.min_visible \
                    and not self._gate.lost(rho):
                b = safe_box(found, frame.shape)
                self._start()                   # MIL learned the wrong box: restart it there
                self._ask(b"I", frame, b)
                ok, box = True, np.asarray(b, dtype=float)
        self._lost = not ok
        return ok, (box if ok else last)

    def _last_confidence(self) -> float:
        """The last frame's colour rho (see "Confidence"): generic, not MIL's own."""
        return float(self._rho)


@atexit.register
def _close_all():
    for t in list(_LIVE):
        t.close()


REFERENCE = {OpenCVMIL.name: OpenCVMIL}
