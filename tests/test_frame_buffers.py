"""Frames as a camera loop hands them: one buffer, refilled in place every frame.

``cv2.VideoCapture.read(image=buffer)`` and many camera APIs reuse one array; a tracker that
keeps something computed from "this frame" must not take a refilled buffer for the frame it
saw last. The same frames must give the same boxes whether they come as fresh arrays or in one
buffer, for every tracker and its re-detecting variant.
"""

from __future__ import annotations

import numpy as np
import pytest

from trackbook import trackers
from trackbook.clips.synthetic import leave_and_return

NAMES = trackers.available(reference=True)


@pytest.fixture(scope="module")
def frames_and_box():
    # 12 frames in view, 18 gone, back 88 px left: locate, learn, lose and re-detect all run
    clip = leave_and_return(12, 18, 12)
    return [np.array(f) for f in clip.frames], tuple(float(v) for v in clip.groundtruth[0])


@pytest.mark.parametrize("name", NAMES)
def test_a_refilled_buffer_gives_the_boxes_of_fresh_frames(name, frames_and_box):
    frames, box = frames_and_box
    fresh, reused = trackers.create(name, seed=0), trackers.create(name, seed=0)
    fresh.init(frames[0].copy(), box)
    buffer = frames[0].copy()
    reused.init(buffer, box)
    for i, f in enumerate(frames[1:], start=1):
        ok_a, box_a = fresh.update(f.copy())
        buffer[...] = f
        ok_b, box_b = reused.update(buffer)
        assert (ok_a, box_a) == (ok_b, box_b), (
            f"{name}, frame {i}: {ok_a}, {np.round(box_a, 2)} from a fresh array but "
            f"{ok_b}, {np.round(box_b, 2)} from the refilled buffer")



def test_the_whole_frame_search_scores_the_frame_it_is_given():
    """A frame freed after use gives its ``id`` to the next one: ``bacf``'s whole-frame
    response (the re-detection layer's search) must be the new frame's, not a stale one."""
    clip = leave_and_return(12, 18, 12)
    box = tuple(float(v) for v in clip.groundtruth[0])
    t = trackers.create("bacf-redetect", seed=0)
    t.init(np.array(clip.frames[0]), box)
    boxes = np.array([box, (88.0, 40.0, box[2], box[3])])
    for i in range(1, len(clip.frames)):
        first = t._score_boxes(np.array(clip.frames[i]), boxes)       # freed at once
        fresh = trackers.create("bacf-redetect", seed=0)
        fresh.init(np.array(clip.frames[0]), box)
        expected = fresh._score_boxes(np.array(clip.frames[(i * 7) % len(clip.frames)]), boxes)
        got = t._score_boxes(np.array(clip.frames[(i * 7) % len(clip.frames)]), boxes)
        np.testing.assert_allclose(got, expected, err_msg=f"frame {i}: {first}")
