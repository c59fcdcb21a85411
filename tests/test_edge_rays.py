"""The 8-ray edge model of Kim, Kim & Choi 2016: fast per-pixel maps against a slow walk,
and eq. 5-6 against hand-worked cases."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from trackbook.features import edge_rays as er


def slow_rays(edges, x, y, max_length=None):
    """Reference: walk each ray one pixel at a time from (x, y) (module conventions)."""
    H, W = edges.shape
    out = np.zeros(8)
    for j, (dx, dy) in enumerate(er.DIRECTIONS):
        k = 1
        while True:
            xx, yy = x + k * dx, y + k * dy
            if not (0 <= xx < W and 0 <= yy < H) or edges[yy, xx]:
                break
            k += 1
        d = k * np.hypot(dx, dy)
        out[j] = min(d, max_length) if max_length else d
    return out


def slow_maps(edges, max_length=None):
    H, W = edges.shape
    out = np.zeros((8, H, W))
    for y in range(H):
        for x in range(W):
            out[:, y, x] = slow_rays(edges, x, y, max_length)
    return out


edge_maps = st.tuples(st.integers(1, 14), st.integers(1, 14), st.floats(0.0, 0.6)).flatmap(
    lambda hwp: arrays(bool, (hwp[0], hwp[1]),
                       elements=st.booleans() if hwp[2] > 0.3 else st.sampled_from([False]*4 + [True])))


@settings(max_examples=60, deadline=None)
@given(edges=edge_maps, max_length=st.one_of(st.none(), st.floats(1.0, 12.0)))
def test_fast_maps_equal_slow_walk(edges, max_length):
    fast = er.ray_distance_maps(edges, max_length)
    assert fast.shape == (8,) + edges.shape
    np.testing.assert_allclose(fast, slow_maps(edges, max_length), rtol=1e-6)


@settings(max_examples=80, deadline=None)
@given(edges=edge_maps, data=st.data(), max_length=st.one_of(st.none(), st.floats(1.0, 12.0)))
def test_rays_along_particle_lines_equal_slow_walk_and_full_maps(edges, data, max_length):
    # The fast path of the tracker (only the rows, columns and diagonals through the points)
    # must give the slow walk's numbers and the whole-frame maps' numbers exactly, also for
    # repeated points and points on the border.
    H, W = edges.shape
    pts = data.draw(st.lists(st.tuples(st.integers(0, W - 1), st.integers(0, H - 1)),
                             min_size=1, max_size=25))
    x, y = np.array(pts).T
    steps = er.ray_steps_at(edges, x, y)
    np.testing.assert_array_equal(steps, er.ray_steps(edges)[:, y, x].T)
    got = er.rays_at_points(edges, np.column_stack([x, y]), max_length)
    want = np.array([slow_rays(edges, xi, yi, max_length) for xi, yi in zip(x, y)])
    np.testing.assert_allclose(got, want, rtol=1e-6)


def test_rays_at_points_rounds_and_clips_like_the_maps():
    rng = np.random.default_rng(5)
    e = rng.random((40, 60)) < 0.08
    xy = rng.uniform(-10, 70, size=(200, 2))   # continuous, some outside the frame
    np.testing.assert_allclose(er.rays_at_points(e, xy, 20.0),
                               er.rays_at(er.ray_distance_maps(e, 20.0), xy))


def test_empty_frame_rays_reach_the_border():
    # No edge at all: every ray ends at the first step outside the frame.
    e = np.zeros((5, 7), bool)
    d = er.ray_distance_maps(e)
    # pixel (x=2, y=1): E needs 5 steps to leave (x=7), N 2 steps, NE min(5, 2) = 2 diagonal steps
    assert d[:, 1, 2].tolist() == pytest.approx(
        [5, 2 * np.sqrt(2), 2, 2 * np.sqrt(2), 3, 3 * np.sqrt(2), 4, 4 * np.sqrt(2)])


def test_point_is_not_its_own_edge_and_crops_with_offset():
    e = np.zeros((9, 9), bool)
    e[4, 4] = True
    e[4, 7] = True
    d = er.ray_distance_maps(e)
    assert d[0, 4, 4] == 3                # E from the edge pixel itself finds the next edge
    steps = er.ray_steps(e[2:8, 3:9])
    got = er.rays_at(steps, [(4, 4)], offset=(3, 2))[0]
    np.testing.assert_allclose(got[0], 3)  # same E distance through a crop with an offset


def test_median_pair_ratio_and_weight_hand_worked():
    # Model M (E, NE, N, NW, W, SW, S, SE): sorted 2, 3, 4, [5, 6], 7, 8, 9 -> mAvg = 5.5
    m = np.array([5, 9, 2, 7, 6, 3, 8, 4], float)
    # Particle p: sorted 2, 3, 5, [6, 6], 7, 9, 10 -> pAvg = 6; Ratio = 6 / 5.5 = 1.0909 (inside)
    p = np.array([6, 10, 2, 7, 6, 3, 9, 5], float)
    assert er.median_pair_mean(m) == 5.5
    assert er.ratio(p, m) == pytest.approx(6 / 5.5)
    # eq. 6 direction by direction: |1|+|1|+0+0+0+0+|1|+|1| = 4; sum m = 44; w = 1 - 4/44
    assert er.edge_weight(p, m) == pytest.approx(1 - 4 / 44)
    # Twice as far everywhere: Ratio = 2 -> outside [0.8, 1.2] -> weight 0 even though eq. 6
    # alone would give 1 - 44/44 = 0 anyway; use 1.3x to show the window decides:
    q = 1.3 * m                             # Ratio 1.3, eq. 6 alone: 1 - 0.3 = 0.7
    assert er.ratio(q, m) == pytest.approx(1.3)
    assert er.edge_weight(q, m) == 0.0
    assert er.edge_weight(q, m, window=(0.8, 1.4)) == pytest.approx(0.7)
    # Far off on two rays above the median: NE 9 -> 40, S 8 -> 30. Sorted 2,3,4,[5,6],7,30,40:
    # Ratio = 5.5 / 5.5 = 1 (inside), but sum |p - m| = 31 + 22 = 53 > 44: eq. 6 gives
    # 1 - 53/44 < 0, clipped to 0.
    r = m.copy()
    r[[1, 6]] = [40, 30]
    assert er.ratio(r, m) == 1.0
    assert er.edge_weight(r, m) == 0.0


def test_weight_map_is_eq6_at_every_pixel():
    rng = np.random.default_rng(3)
    e = rng.random((20, 30)) < 0.15
    maps = er.ray_distance_maps(e)
    m = slow_rays(e, 12, 9)
    wm = er.weight_map(maps, m)
    assert wm[9, 12] == pytest.approx(1.0)  # the model's own point matches itself exactly
    for (x, y) in [(0, 0), (29, 19), (5, 14), (20, 3)]:
        assert wm[y, x] == pytest.approx(er.edge_weight(slow_rays(e, x, y), m))
    assert ((wm >= 0) & (wm <= 1)).all()


def test_bad_window_and_shapes_raise():
    with pytest.raises(ValueError, match="low <= high"):
        er.edge_weight(np.ones(8), np.ones(8), window=(1.2, 0.8))
    with pytest.raises(ValueError, match="bool map"):
        er.ray_steps(np.zeros((2, 3, 4), bool))
    with pytest.raises(ValueError, match="max_length"):
        er.ray_distance_maps(np.zeros((3, 3), bool), max_length=0.5)
    with pytest.raises(ValueError, match="inside the"):
        er.ray_steps_at(np.zeros((3, 3), bool), [3], [0])
    with pytest.raises(ValueError, match="same length"):
        er.ray_steps_at(np.zeros((3, 3), bool), [1, 2], [0])
