"""The shared pieces of the lost rules (``trackers/lost.py``), checked
against hand-worked cases and slow loops."""

from __future__ import annotations

import numpy as np
import pytest

from trackbook.trackers.lost import ColourCheck, MatchGate, visible_fraction


def test_visible_fraction_by_hand():
    shape = (100, 200, 3)
    assert visible_fraction((10, 10, 20, 20), shape) == 1.0
    assert visible_fraction((190, 10, 20, 20), shape) == 0.5        # half past the right edge
    assert visible_fraction((-10, -10, 20, 20), shape) == 0.25      # a quarter in the corner
    assert visible_fraction((200, 10, 20, 20), shape) == 0.0        # wholly outside


def test_match_gate_by_hand():
    g = MatchGate(below=0.7, k=3.0, floor=0.5)
    # five frames at D^2 = 0.05 pass and make the range: median 0.05, MAD 0 -> spread
    # max(0, 0.025) = 0.025, bound 0.05 + 3 * 0.025 = 0.125 (match 0.875)
    assert [g.lost(0.95) for _ in range(5)] == [False] * 5
    assert g.lost(0.6) is True               # below 0.7 and D^2 0.4 > 0.125
    assert g.lost(0.8) is False              # D^2 0.2 > 0.125, but the match is not below 0.7
    assert g.lost(0.45) is True              # below the floor: lost whatever the range
    assert g.lost(0.6, second_look=lambda: True) is False   # the second look keeps it
    assert g.lost(0.6, second_look=lambda: False) is True
    assert g.lost(0.4, second_look=lambda: True) is True    # no second look below the floor


def test_colour_check_finds_a_target_pasted_elsewhere():
    rng = np.random.default_rng(0)
    frame = np.zeros((120, 160, 3), np.uint8)
    frame[:] = (40, 120, 40)
    frame += rng.integers(0, 20, frame.shape, dtype=np.uint8)
    target = np.zeros((30, 24, 3), np.uint8)
    target[:15] = (30, 30, 200)
    target[15:] = (200, 180, 20)
    first = frame.copy()
    first[20:50, 30:54] = target
    check = ColourCheck(first, (30, 20, 24, 30))
    assert check.match(first, np.array([[30, 20, 24, 30]]))[0] == pytest.approx(1.0)
    later = frame.copy()
    later[70:100, 110:134] = target
    box, rho = check.search(later, max_boxes=150)
    assert rho > 0.9
    assert abs(box[0] - 110) <= 4 and abs(box[1] - 70) <= 4
    # a frame without it: the best match is poor
    _, rho_none = check.search(frame, max_boxes=150)
    assert rho_none < 0.5
    # the second look: the pasted target stands out from the plain green around it
    assert check.stands_out(later, box, rho)
