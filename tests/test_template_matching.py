"""SSD and zero-mean NCC response maps against ``cv2.matchTemplate`` (an independent oracle),
plus cases worked by hand.

Tolerances: OpenCV computes in float32 (its own DFT correlation and integral images), our maps
in float64, so the difference is OpenCV's rounding. For SSD each value is a sum of terms of
size up to sum T^2 + sum_window I^2, so the rounding is a few float32 ulps of that scale:
|ours - cv2| <= 16 eps32 (sum T^2 + sum_window I^2) (measured up to about 2.4 eps32). For NCC
the window variance is a difference of sums, sum I^2 - (sum I)^2 / n, whose rounding is
amplified by the cancellation factor c_I = sum I^2 / var_I (and likewise c_T for the
template): |ours - cv2| <= 32 eps32 c_I c_T (measured up to about 14 eps32 c_I c_T on the
camera photograph, whose flat sky gives c_I in the thousands).
"""

from __future__ import annotations

import cv2
import numpy as np
import pytest
import skimage.data

from trackbook.filters import template_matching as tm

EPS32 = float(np.finfo(np.float32).eps)


def _cases():
    rng = np.random.default_rng(7)
    out = []
    for k in range(3):
        I = rng.integers(0, 256, (70, 90)).astype(np.float32)
        T = I[15 + k:36 + k, 20:47].copy()
        T += rng.normal(0, 6, T.shape).astype(np.float32)     # not an exact copy
        out.append((f"random-{k}", I, T))
    cam = skimage.data.camera()[::2, ::2].astype(np.float32)
    out.append(("camera", cam, cam[100:130, 120:160].copy()))
    coins = skimage.data.coins().astype(np.float32)
    out.append(("coins-other-frame", coins, coins[150:171, 200:231] * 0.9 + 7))
    return out


CASES = _cases()


def _sums(I, T):
    h, w = T.shape
    I = I.astype(np.float64)
    T = T.astype(np.float64)
    s1 = tm.window_sums(I, h, w)
    s2 = tm.window_sums(I * I, h, w)
    return T, s1, s2, h * w


@pytest.mark.parametrize("name,I,T", CASES, ids=[c[0] for c in CASES])
def test_ssd_is_cv2_tm_sqdiff(name, I, T):
    ours = tm.ssd_map(I, T)
    ref = cv2.matchTemplate(I, T, cv2.TM_SQDIFF).astype(np.float64)
    assert ours.shape == ref.shape
    T64, _, s2, _ = _sums(I, T)
    scale = np.sum(T64 * T64) + s2
    assert np.all(np.abs(ours - ref) <= 16 * EPS32 * scale)
    assert tm.best_match(ours, "ssd") == tm.best_match(ref, "ssd")


@pytest.mark.parametrize("name,I,T", CASES, ids=[c[0] for c in CASES])
def test_ncc_is_cv2_tm_ccoeff_normed(name, I, T):
    ours = tm.ncc_map(I, T)
    ref = cv2.matchTemplate(I, T, cv2.TM_CCOEFF_NORMED).astype(np.float64)
    T64, s1, s2, n = _sums(I, T)
    var_i = s2 - s1 * s1 / n
    assert var_i.min() > 0          # the cases have no constant window: NCC defined everywhere
    Tz = T64 - T64.mean()
    cond = (s2 / var_i) * (np.sum(T64 * T64) / np.sum(Tz * Tz))
    assert np.all(np.abs(ours - ref) <= 32 * EPS32 * cond)
    assert tm.best_match(ours, "ncc") == tm.best_match(ref, "ncc")


def test_hand_worked_maps():
    # a 1 x 2 template [1, 3] over the row [0, 1, 3, 2]: windows [0,1], [1,3], [3,2]
    I = np.array([[0.0, 1.0, 3.0, 2.0]])
    T = np.array([[1.0, 3.0]])
    np.testing.assert_allclose(tm.ssd_map(I, T), [[1 + 4, 0, 4 + 1]], atol=1e-9)
    # zero-mean: T' = [-1, 1]; windows' I' = [-.5, .5], [-1, 1], [.5, -.5] -> NCC 1, 1, -1
    np.testing.assert_allclose(tm.ncc_map(I, T), [[1.0, 1.0, -1.0]], atol=1e-9)
    assert tm.best_match(tm.ssd_map(I, T), "ssd") == (1, 0)


def test_ncc_ignores_gain_and_offset_and_is_zero_on_flat_windows():
    rng = np.random.default_rng(1)
    I = rng.uniform(0, 255, (30, 40))
    I[:, 30:] = 50.0                                      # a constant strip
    T = I[5:15, 8:18]
    r = tm.ncc_map(I, 2.5 * T + 40)
    assert r[5, 8] == pytest.approx(1.0, abs=1e-9)
    assert np.all(r[:, 30:] == 0.0)                       # windows inside the constant strip


def test_patch_ncc_matches_the_map_at_the_same_window():
    rng = np.random.default_rng(2)
    I = rng.uniform(0, 255, (40, 50))
    T = rng.uniform(0, 255, (9, 11))
    r = tm.ncc_map(I, T)
    ys, xs = np.array([0, 7, 31]), np.array([0, 20, 39])
    windows = np.stack([I[y:y + 9, x:x + 11] for y, x in zip(ys, xs)])
    got = tm.patch_ncc(windows, np.repeat(T[None], 3, 0))
    np.testing.assert_allclose(got, r[ys, xs], atol=1e-9)
    assert tm.patch_ncc(np.ones((1, 3, 3)), windows[:1, :3, :3])[0] == 0.0


def test_bad_input_is_refused_by_name():
    with pytest.raises(ValueError, match="does not fit"):
        tm.ssd_map(np.zeros((5, 5)), np.zeros((6, 2)))
    with pytest.raises(ValueError, match="2-D grey"):
        tm.ncc_map(np.zeros((5, 5, 3)), np.zeros((2, 2)))
    with pytest.raises(ValueError, match="'ssd'"):
        tm.best_match(np.zeros((2, 2)), "sad")
