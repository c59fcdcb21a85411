"""Shi-Tomasi corners, pyramidal Lucas-Kanade and the forward-backward error, against OpenCV
(``cv2.goodFeaturesToTrack``, ``cv2.calcOpticalFlowPyrLK``: independent implementations of the
same definitions) and against known motions.

Agreement measures, and why:

- Corners: the two eigenvalue maps differ by float32 rounding (OpenCV's Sobel and box sums are
  float32, ours float64), so where two candidates are nearly tied the min-distance rule can keep
  the other one of the pair; we require at least 90 % of OpenCV's corners to have one of ours
  within 1 px and the reverse (measured: about 95 % identical on these images).
- Flows: OpenCV interpolates with 14-bit fixed-point weights; ours are float64. On points whose
  window stays inside the image (the two treat the border differently: OpenCV pads each
  pyramid level, we reflect at sampling) and whose smaller eigenvalue per pixel is at least
  10 grey level^2 (a well-determined 2 x 2 system), every flow agrees to 0.02 px (measured: median
  below 1e-4 px, 95th percentile below 1e-3 px); over all points, border ones included, 98 %.
  Both trackers must also be within 0.15 px of the true motion there.
- Status: identical on every corner tracked; on flat and edge-only windows (smaller eigenvalue
  0) both flag the point lost.
"""

from __future__ import annotations

import cv2
import numpy as np
import pytest
import skimage.data

from trackbook.filters import lucas_kanade as lk

WIN, LEVELS = 21, 3


def _grey(name, size=(320, 240)):
    img = getattr(skimage.data, name)()
    if img.ndim == 3:
        img = cv2.cvtColor(img, cv2.COLOR_RGB2GRAY)
    return cv2.resize(img, size, interpolation=cv2.INTER_AREA)


@pytest.mark.parametrize("name", ["astronaut", "camera", "coffee"])
def test_shi_tomasi_corners_are_opencvs(name):
    g = _grey(name)
    ref = cv2.goodFeaturesToTrack(g, 200, 0.01, 10, blockSize=3,
                                  useHarrisDetector=False).reshape(-1, 2)
    ours = lk.good_features(g, 200, 0.01, 10, block=3)
    assert abs(len(ours) - len(ref)) <= 0.05 * len(ref)
    d = np.sqrt(((ref[:, None] - ours[None]) ** 2).sum(-1))
    assert np.mean(d.min(1) <= 1.0) >= 0.9
    assert np.mean(d.min(0) <= 1.0) >= 0.9
    # the min-distance rule holds exactly
    dd = np.sqrt(((ours[:, None] - ours[None]) ** 2).sum(-1)) + np.eye(len(ours)) * 1e9
    assert dd.min() >= 10


def test_shi_tomasi_finds_the_corners_of_a_square():
    g = np.zeros((60, 60), np.uint8)
    g[20:40, 15:45] = 200
    pts = lk.good_features(g, 10, 0.3, 5)
    corners = np.array([[15, 20], [44, 20], [15, 39], [44, 39]], float)
    assert len(pts) == 4
    d = np.sqrt(((corners[:, None] - pts[None]) ** 2).sum(-1)).min(1)
    assert np.all(d <= 1.5)


def _warped(g, M):
    return cv2.warpAffine(g, M, g.shape[::-1], flags=cv2.INTER_LINEAR,
                          borderMode=cv2.BORDER_REFLECT_101)


CASES = {
    "shift": np.float32([[1, 0, 3.4], [0, 1, -2.7]]),
    "affine": np.float32([[1.02, 0.01, 3.3], [-0.01, 0.99, -2.6]]),
    "large-shift": np.float32([[1, 0, 9.3], [0, 1, 6.2]]),
}


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("name", ["astronaut", "coffee"])
def test_flows_are_opencvs_on_well_conditioned_points(name, case):
    g = _grey(name)
    M = CASES[case]
    g2 = _warped(g, M)
    pts = cv2.goodFeaturesToTrack(g, 300, 0.01, 8, useHarrisDetector=False).reshape(-1, 2)
    ref, st, _ = cv2.calcOpticalFlowPyrLK(g, g2, pts.reshape(-1, 1, 2), None,
                                          winSize=(WIN, WIN), maxLevel=LEVELS - 1)
    ref, st = ref.reshape(-1, 2).astype(float), st.ravel().astype(bool)
    ours, status = lk.track_points(g, g2, pts, win=WIN, levels=LEVELS)
    truth = pts @ M[:, :2].T + M[:, 2]
    H, W = g.shape
    margin = WIN // 2 + 2 + 12                    # the window and the motion inside the frame
    inner = ((pts[:, 0] >= margin) & (pts[:, 0] < W - margin)
             & (pts[:, 1] >= margin) & (pts[:, 1] < H - margin))
    lam = lk.min_eigenvalue_map(g, WIN)[pts[:, 1].astype(int), pts[:, 0].astype(int)] / WIN ** 2
    # the status flags are OpenCV's on every point, border and weak ones included
    np.testing.assert_array_equal(status, st)
    both = np.linalg.norm(ours - ref, axis=1)[st]
    assert np.mean(both <= 0.02) >= 0.98              # measured 99.2 % to 100 %, border ones too
    good = inner & (lam >= 10) & st
    assert good.sum() >= 50
    assert np.all(status[good])
    err = np.linalg.norm(ours - ref, axis=1)[good]
    assert err.max() <= 0.02, f"{np.sort(err)[-5:]}"
    assert np.median(np.linalg.norm(ours - truth, axis=1)[good]) <= 0.15
    assert np.median(np.linalg.norm(ref - truth, axis=1)[good]) <= 0.15


def test_status_flags_agree_on_flat_and_edge_only_windows():
    rng = np.random.default_rng(3)
    g = np.full((120, 160), 100, np.uint8)
    g[:, 100:] = 180                                          # one vertical edge, no texture
    g[:40, :60] = rng.integers(0, 255, (40, 60))              # a textured corner
    g2 = np.roll(g, 2, axis=1)
    pts = np.float32([[30, 90], [80, 60], [100, 60], [100.5, 90], [30, 20]])
    _, st, _ = cv2.calcOpticalFlowPyrLK(g, g2, pts.reshape(-1, 1, 2), None,
                                        winSize=(11, 11), maxLevel=0)
    _, status = lk.track_points(g, g2, pts, win=11, levels=1)
    np.testing.assert_array_equal(status, st.ravel().astype(bool))
    np.testing.assert_array_equal(status, [False, False, False, False, True])


def test_forward_backward_error_is_small_on_a_true_motion_and_large_on_a_wrong_one():
    g = _grey("astronaut")
    g2 = _warped(g, CASES["shift"])
    pts = cv2.goodFeaturesToTrack(g[60:180, 80:240], 10, 0.05, 10).reshape(-1, 2) + [80, 60]
    fwd, fb, status = lk.forward_backward(g, g2, pts, win=WIN, levels=LEVELS)
    assert np.all(status) and np.all(fb < 0.1)
    np.testing.assert_allclose(fwd, pts + [3.4, -2.7], atol=0.15)
    # a second frame unrelated to the first: forward and backward disagree
    other = _grey("coffee")
    _, fb2, status2 = lk.forward_backward(g, other, pts, win=WIN, levels=LEVELS)
    assert np.all((fb2 > 1.0) | ~status2)
    # by definition: the distance from each start to its back-tracked point
    back, _ = lk.track_points(g2, g, fwd, win=WIN, levels=LEVELS)
    np.testing.assert_allclose(fb, np.linalg.norm(back - pts, axis=1))


def test_bad_window_is_refused():
    g = _grey("camera")
    with pytest.raises(ValueError, match="odd"):
        lk.track_points(g, g, [[10, 10]], win=10)
