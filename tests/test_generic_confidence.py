"""The failure layer's generic confidence (``trackers/generic_confidence.py``): the colour
match of a box against the first frame, checked on hand-made frames and a slow loop."""

from __future__ import annotations

import numpy as np
import pytest

from trackbook.trackers.generic_confidence import ColourCheck


def _scene():
    rng = np.random.default_rng(0)
    frame = np.zeros((120, 160, 3), np.uint8)
    frame[:] = (40, 120, 40)
    frame += rng.integers(0, 20, frame.shape, dtype=np.uint8)
    target = np.zeros((30, 24, 3), np.uint8)
    target[:15] = (30, 30, 200)
    target[15:] = (200, 180, 20)
    return frame, target


def test_the_target_matches_itself_and_a_copy_elsewhere_but_not_the_background():
    frame, target = _scene()
    first = frame.copy()
    first[20:50, 30:54] = target
    check = ColourCheck(first, (30, 20, 24, 30))
    assert check.match(first, np.array([[30, 20, 24, 30]]))[0] == pytest.approx(1.0)
    later = frame.copy()
    later[70:100, 110:134] = target
    rho = check.match(later, np.array([[110, 70, 24, 30], [30, 20, 24, 30]]))
    assert rho[0] == pytest.approx(1.0, abs=0.02)       # the same pixels, moved
    assert rho[1] < 0.5                                  # plain green where it was


def test_match_is_the_bhattacharyya_coefficient_of_the_histograms():
    frame, target = _scene()
    frame[20:50, 30:54] = target
    check = ColourCheck(frame, (30, 20, 24, 30))
    boxes = np.array([[30, 20, 24, 30], [60, 40, 24, 30], [35, 25, 24, 30]], float)
    h = check.histograms(frame, boxes)
    assert np.allclose(h.sum(axis=1), 1.0)
    slow = [sum(np.sqrt(p * q) for p, q in zip(row, check.reference)) for row in h]
    assert np.allclose(check.match(frame, boxes), slow, atol=1e-12)
