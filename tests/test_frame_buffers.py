"""Frames as a camera loop hands them: one buffer, refilled in place every frame.

``cv2.VideoCapture.read(image=buffer)`` and many camera APIs reuse one array; a tracker that
keeps something computed from "this frame" must not take a refilled buffer for the frame it
saw last. The same frames must give the same boxes whether they come as arrays of their own
or in one buffer, for every tracker and its re-detecting variant.
"""

from __future__ import annotations

import numpy as np
import pytest

from trackbook import trackers
from trackbook.clips.synthetic import leave_and_return

from . import _scenarios as S

NAMES = trackers.available(reference=True)


def _kept_and_refilled(name, frames, box):
    """``[(ok, box)]`` per frame from the frames as they are (each its own array, all kept
    alive, so no array's ``id`` is handed on) and from one buffer refilled with each."""
    kept, refilled = trackers.create(name, seed=0), trackers.create(name, seed=0)
    buffer = frames[0].copy()
    kept.init(frames[0], box)
    refilled.init(buffer, box)
    out = []
    for f in frames[1:]:
        buffer[...] = f
        out.append((kept.update(f), refilled.update(buffer)))
    return out


@pytest.fixture(scope="module")
def frames_and_box():
    # 12 frames in view, 18 gone, back 88 px left: locate, learn, lose and re-detect all run
    clip = leave_and_return(12, 18, 12)
    return [np.array(f) for f in clip.frames], tuple(float(v) for v in clip.groundtruth[0])


@pytest.mark.parametrize("name", NAMES)
def test_a_refilled_buffer_gives_the_boxes_of_frames_of_their_own(name, frames_and_box):
    for i, (a, b) in enumerate(_kept_and_refilled(name, *frames_and_box), start=1):
        assert a == b, (f"{name}, frame {i}: {a[0]}, {np.round(a[1], 2)} from the frame's own "
                        f"array but {b[0]}, {np.round(b[1], 2)} from the refilled buffer")


def test_the_whole_frame_search_reads_each_frame_of_a_refilled_buffer():
    """bacf's re-detection correlates its filter with the whole frame, once per frame: on the
    hand-built exit (the target leaves across the right edge and comes back at the left) a
    search that kept the first lost frame's response would never see the target return."""
    sc = S.scenario("edge-exit")
    frames = [np.array(f) for f in sc.clip.frames]
    runs = _kept_and_refilled("bacf-redetect", frames, tuple(sc.clip.groundtruth[0]))
    kept = [a for a, _ in runs]
    assert any(ok for ok, _ in kept[sc.back - 1:])          # the target is found again
    assert [b for _, b in runs] == kept
