"""OpenCV's ``TrackerMIL`` behind the trackbook contract: the reference row of every table.

It is not one of the papers' trackers, so it is not in ``trackers.available()``; ask for it as
``trackers.create("opencv-mil")`` or list it with ``trackers.available(reference=True)``.
"""

from __future__ import annotations

import cv2
import numpy as np

from .base import Tracker


class OpenCVMIL(Tracker):
    """Babenko et al.'s MIL tracker as shipped by OpenCV (``cv2.TrackerMIL``).

    It takes integer boxes; the wrapper rounds the initial box and returns floats like every
    other trackbook tracker.

    Unlike trackbook's trackers, MIL is *not* repeatable within one Python process: it draws
    its training samples from a random generator inside OpenCV that keeps its state from one
    run to the next and that ``cv2.setRNGSeed`` does not reset (measured: two runs on Crossing
    in one process differ by up to 25 px; the n-th run of a fresh process is always the same).
    Its scores therefore vary a little with what ran before; the benchmark reports the first run.
    """

    name = "opencv-mil"

    def _init(self, frame, box):
        self._cv = cv2.TrackerMIL_create()
        x, y, w, h = (int(round(v)) for v in box)
        self._cv.init(frame, (x, y, max(w, 1), max(h, 1)))

    def _update(self, frame):
        ok, box = self._cv.update(frame)
        if not ok:
            return False, np.asarray(self.bbox, dtype=float)
        return True, np.asarray(box, dtype=float)


REFERENCE = {OpenCVMIL.name: OpenCVMIL}
