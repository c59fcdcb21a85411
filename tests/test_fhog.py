"""FHOG (Felzenszwalb et al. 2010, section 6; the toolbox code the trackers call), from its
definition: hand-made images with known answers, a hand-worked normalisation, the 180°
symmetry, and an independent pixel-by-pixel transcription of the reference's loops."""

from __future__ import annotations

import math

import numpy as np
import pytest

from trackbook.features.fhog import fhog


def _slow_fhog(image, cell, n_orient, clip):
    """A loop-per-pixel transcription of the toolbox's gradMag/gradHist/hogNormMatrix/
    hogChannels (in exact arithmetic): the oracle for the vectorised function."""
    img = np.asarray(image, dtype=np.float64)
    if img.ndim == 2:
        img = img[..., None]
    else:
        img = img[..., ::-1]                                    # BGR -> R, G, B
    h, w, d = img.shape
    ns = 2 * n_orient
    # gradients: per pixel, the channel of strictly largest squared norm (first on a tie)
    M = np.zeros((h, w)); O = np.zeros((h, w))
    for y in range(h):
        for x in range(w):
            best = (-1.0, 0.0, 0.0)
            for c in range(d):
                if x == 0:
                    gx = img[y, 1, c] - img[y, 0, c]
                elif x == w - 1:
                    gx = img[y, w - 1, c] - img[y, w - 2, c]
                else:
                    gx = 0.5 * (img[y, x + 1, c] - img[y, x - 1, c])
                if y == 0:
                    gy = img[1, x, c] - img[0, x, c]
                elif y == h - 1:
                    gy = img[h - 1, x, c] - img[h - 2, x, c]
                else:
                    gy = 0.5 * (img[y + 1, x, c] - img[y - 1, x, c])
                if gx * gx + gy * gy > best[0]:
                    best = (gx * gx + gy * gy, gx, gy)
            M[y, x] = math.sqrt(best[0])
            O[y, x] = math.atan2(best[2], best[1]) % (2 * math.pi)
    # nearest of the 2p centres; a tie (equal distances up to rounding) goes counter-clockwise
    centres = [2 * math.pi * b / ns for b in range(ns)]

    def nearest(theta):
        def key(b):
            ahead = (centres[b] - theta) % (2 * math.pi)        # angle from theta to centre b
            dist = min(ahead, 2 * math.pi - ahead)
            return (round(dist, 9), 0 if ahead <= math.pi else 1)
        return min(range(ns), key=key)

    hb, wb = h // cell, w // cell
    R1 = np.zeros((hb, wb, ns))
    for y in range(hb * cell):
        for x in range(wb * cell):
            yb = (y + 0.5) / cell - 0.5; xb = (x + 0.5) / cell - 0.5
            y0 = math.floor(yb); x0 = math.floor(xb)
            yd = yb - y0; xd = xb - x0
            o = nearest(O[y, x])
            for cy, wy in ((y0, 1 - yd), (y0 + 1, yd)):
                for cx, wx in ((x0, 1 - xd), (x0 + 1, xd)):
                    if 0 <= cy < hb and 0 <= cx < wb:
                        R1[cy, cx, o] += wy * wx * M[y, x] / cell / cell
    for cy in range(hb):
        for cx in range(wb):
            for side in (cx == 0, cy == 0, cx == wb - 1, cy == hb - 1):
                if side:
                    R1[cy, cx] *= 8.0 / 7.0
    R2 = R1[..., :n_orient] + R1[..., n_orient:]
    # hogNormMatrix: padded (hb+1) x (wb+1), energies at [i+1, j+1], in-place normalisers,
    # then the border filled in the reference's order of copies
    N = np.zeros((hb + 1, wb + 1))
    for i in range(hb):
        for j in range(wb):
            N[i + 1, j + 1] = sum(v * v for v in R2[i, j])
    eps = 1e-4 / 4 / cell ** 4
    for j in range(wb - 1):
        for i in range(hb - 1):
            s = N[i + 1, j + 1] + N[i + 2, j + 1] + N[i + 1, j + 2] + N[i + 2, j + 2]
            N[i + 1, j + 1] = 1 / math.sqrt(s + eps)
    H1, W1 = hb + 1, wb + 1
    N[0, 0] = N[1, 1]
    for i in range(H1):
        N[i, 0] = N[i, 1]
    N[H1 - 1, 0] = N[H1 - 2, 1]
    N[0, W1 - 1] = N[1, W1 - 2]
    for i in range(H1):
        N[i, W1 - 1] = N[i, W1 - 2]
    N[H1 - 1, W1 - 1] = N[H1 - 2, W1 - 2]
    for j in range(W1):
        N[0, j] = N[1, j]
    for j in range(W1):
        N[H1 - 1, j] = N[H1 - 2, j]
    F = np.zeros((hb, wb, 3 * n_orient + 4))
    for i in range(hb):
        for j in range(wb):
            norms = (N[i + 1, j + 1], N[i, j + 1], N[i + 1, j], N[i, j])
            for b in range(ns):
                for l, n in enumerate(norms):
                    t = min(R1[i, j, b] * n, clip)
                    F[i, j, b] += 0.5 * t
                    F[i, j, 3 * n_orient + l] += 0.2357 * t
            for b in range(n_orient):
                for n in norms:
                    F[i, j, ns + b] += 0.5 * min(R2[i, j, b] * n, clip)
    return F


@pytest.mark.parametrize("shape, cell, n_orient, clip", [
    ((14, 19, 3), 4, 9, 0.2),        # colour, sides not multiples of the cell
    ((13, 11), 3, 9, 0.2),           # grey, odd cell
    ((12, 16, 3), 4, 6, 0.15),       # other orientation count and clip
])
def test_agrees_with_slow_transcription(shape, cell, n_orient, clip):
    img = np.random.default_rng(7).integers(0, 256, shape).astype(np.uint8)
    got = fhog(img, cell, n_orient, clip)
    want = _slow_fhog(img, cell, n_orient, clip)
    assert got.shape == want.shape == (shape[0] // cell, shape[1] // cell, 3 * n_orient + 4)
    np.testing.assert_allclose(got, want, rtol=1e-5, atol=1e-6)


def test_vertical_step_edge_fills_only_the_horizontal_gradient_bins():
    img = np.zeros((32, 32), np.uint8); img[:, 16:] = 200      # dark left, bright right
    F = fhog(img)
    assert np.all(F[..., 0].max(axis=0)[3:5] > 0)              # cells at the edge: bin 0
    others = np.delete(np.arange(27), [0, 18])
    assert np.all(F[..., others] == 0)
    np.testing.assert_array_equal(F[..., 0], F[..., 18])       # 0 deg: insensitive bin 0
    # bright left, dark right: the gradient points at 180 deg, sensitive bin 9
    G = fhog(255 - img)
    assert np.all(np.delete(G[..., :18], 9, axis=2) == 0)
    np.testing.assert_allclose(G[..., 9], F[..., 0], rtol=1e-6)
    np.testing.assert_allclose(G[..., 18:], F[..., 18:], rtol=1e-6)


def test_horizontal_edge_tie_goes_counter_clockwise():
    # a gradient pointing straight down (90 deg) lies between the 80 and 100 deg bins; the
    # reference puts it in bin 5, pointing up (270 deg) in bin 14; both are insensitive bin 5
    img = np.zeros((24, 20), np.uint8); img[12:] = 100
    F = fhog(img); G = fhog(img[::-1])
    assert F[..., 5].max() > 0 and G[..., 14].max() > 0
    assert np.all(np.delete(F[..., :27], [5, 23], axis=2) == 0)
    assert np.all(np.delete(G[..., :27], [14, 23], axis=2) == 0)


def test_constant_image_gives_zeros():
    for img in (np.full((20, 24), 90, np.uint8), np.full((20, 24, 3), 0.3, np.float32)):
        F = fhog(img)
        assert F.dtype == np.float32 and F.shape == (5, 6, 31)
        assert np.all(F == 0)


def test_rotation_by_180_swaps_sensitive_bins_and_keeps_insensitive():
    img = np.random.default_rng(3).integers(0, 256, (24, 28, 3)).astype(np.uint8)
    F = fhog(img)
    G = fhog(img[::-1, ::-1])[::-1, ::-1]       # back in the original cell positions
    np.testing.assert_allclose(G[..., :18], np.roll(F[..., :18], 9, axis=2), rtol=1e-5,
                               atol=1e-7)
    np.testing.assert_allclose(G[..., 18:27], F[..., 18:27], rtol=1e-5, atol=1e-7)
    # the texture channels' blocks swap: below-right <-> above-left, above-right <-> below-left
    np.testing.assert_allclose(G[..., 27:], F[..., 27:][..., ::-1], rtol=1e-5, atol=1e-7)


@pytest.mark.parametrize("clip", [0.2, 0.6])
def test_hand_worked_normalisation_and_truncation(clip):
    # 8 x 8 px, cell 4: 2 x 2 cells, one block. A step of height a between columns 3 and 4
    # gives g_x = a/2 at x = 3 and 4 (0 elsewhere), all in bin 0. Along x those two pixels'
    # votes sum to 1 per cell; along y a cell receives 0.625 + 0.875 + 0.875 + 0.625 + 0.375
    # + 0.125 = 3.5 of the 8 rows' votes. So C_0 = (a/2)(3.5)/16 * (8/7)^2 = a/7 in every
    # (corner) cell, E = a^2/49, and the one block's N = (4 a^2/49 + eps)^(-1/2), eps =
    # 1e-4/(4 * 4^4). C_0 N ~ 1/2: truncated to 0.2 with clip 0.2, kept with clip 0.6.
    a = 10.0
    img = np.zeros((8, 8)); img[:, 4:] = a
    n = (4 * a * a / 49 + 1e-4 / 1024) ** -0.5
    t = min(a / 7 * n, clip)
    F = fhog(img, 4, 9, clip)
    assert F.shape == (2, 2, 31)
    np.testing.assert_allclose(F[..., 0], 0.5 * 4 * t, rtol=1e-6)
    np.testing.assert_allclose(F[..., 18], 0.5 * 4 * t, rtol=1e-6)
    np.testing.assert_allclose(F[..., 27:], 0.2357 * t, rtol=1e-6)
    assert np.all(F[..., 1:18] == 0) and np.all(F[..., 19:27] == 0)


def test_shapes_inputs_and_zero_channel():
    rng = np.random.default_rng(1)
    grey = rng.integers(0, 256, (37, 50)).astype(np.uint8)
    assert fhog(grey).shape == (9, 12, 31)
    assert fhog(grey, cell=8).shape == (4, 6, 31)
    F32 = fhog(grey, zero_channel=True)
    assert F32.shape == (9, 12, 32) and np.all(F32[..., 31] == 0)
    np.testing.assert_array_equal(F32[..., :31], fhog(grey))
    # a grey image as three equal channels, as float, or as (h, w, 1): the same features
    np.testing.assert_allclose(fhog(np.repeat(grey[..., None], 3, axis=2)), fhog(grey))
    np.testing.assert_allclose(fhog(grey.astype(np.float64)), fhog(grey))
    np.testing.assert_allclose(fhog(grey[..., None]), fhog(grey))
    for bad in (np.zeros((7, 40)), np.zeros((10, 10, 2)), np.zeros(5)):
        with pytest.raises(ValueError):
            fhog(bad)

# The float64 implementation (atan2, one bincount of float64 votes) that the float32 one
# replaced, verbatim: the fast path must reproduce it to float32 rounding.
def _prev_gradients(img: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per-pixel gradient (gx, gy) of the colour channel with the largest gradient norm.

    Central differences (I(x+1) - I(x-1)) / 2, one-sided I(1) - I(0) and I(w-1) - I(w-2) on
    the first and last column (and likewise for rows), as ``grad1`` of the reference computes
    them. ``img`` is (h, w, c) float with the channels in the reference's order (R, G, B).
    """
    gx = np.empty_like(img); gy = np.empty_like(img)
    np.subtract(img[:, 2:], img[:, :-2], out=gx[:, 1:-1]); gx[:, 1:-1] *= 0.5
    gx[:, 0] = img[:, 1] - img[:, 0]; gx[:, -1] = img[:, -1] - img[:, -2]
    np.subtract(img[2:], img[:-2], out=gy[1:-1]); gy[1:-1] *= 0.5
    gy[0] = img[1] - img[0]; gy[-1] = img[-1] - img[-2]
    if img.shape[2] == 1:
        return gx[..., 0], gy[..., 0]
    # The channel of largest squared norm wins; argmax keeps the first on a tie, as the
    # reference's strict "greater than" over channels in order does.
    best = np.argmax(gx * gx + gy * gy, axis=2)[..., None]
    return (np.take_along_axis(gx, best, axis=2)[..., 0],
            np.take_along_axis(gy, best, axis=2)[..., 0])


def _prev_spatial_votes(n: int, cell: int, cells: int) -> tuple[np.ndarray, np.ndarray]:
    """Bilinear votes of pixels 0..n-1 along one axis into ``cells`` cells.

    Pixel p sits at cell coordinate u = (p + 0.5) / cell - 0.5; it votes 1 - (u - floor u) to
    cell floor(u) and u - floor(u) to cell floor(u) + 1; votes to cells outside
    0..cells-1 are dropped. Returns (index, weight), each (n, 2), with dropped votes given
    weight 0 and a clipped index.
    """
    u = (np.arange(n) + 0.5) / cell - 0.5
    lo = np.floor(u).astype(np.int64)
    frac = u - lo
    idx = np.stack([lo, lo + 1], axis=1)
    wgt = np.stack([1.0 - frac, frac], axis=1)
    inside = (idx >= 0) & (idx < cells)
    return np.clip(idx, 0, cells - 1), np.where(inside, wgt, 0.0)


def _previous_fhog(image, cell, n_orient, clip, zero_channel=False):
    img = np.asarray(image)
    if img.ndim == 3 and img.shape[2] == 3:
        img = img[..., ::-1]                 # BGR -> RGB: the reference's channel order
    elif img.ndim == 3 and img.shape[2] == 1:
        pass
    elif img.ndim == 2:
        img = img[..., None]
    else:
        raise ValueError(f"image has shape {img.shape}; pass an (h, w) grey image or an "
                         "(h, w, 3) BGR image.")
    if int(cell) != cell or cell < 1 or int(n_orient) != n_orient or n_orient < 1:
        raise ValueError(f"cell ({cell}) and n_orient ({n_orient}) must be positive integers.")
    cell, n_orient = int(cell), int(n_orient)
    h, w = img.shape[:2]
    rows, cols = h // cell, w // cell
    if rows < 2 or cols < 2:
        raise ValueError(f"an image of {w}x{h} px holds {cols}x{rows} cells of {cell} px; "
                         "FHOG's block normalisation needs at least 2x2 cells.")
    n_sens = 2 * n_orient

    # float32 gradients are exact for 8-bit images (multiples of 1/2 below 2^8)
    gx, gy = _prev_gradients(img.astype(np.float32))
    gx, gy = gx.astype(np.float64), gy.astype(np.float64)
    mag = np.sqrt(gx * gx + gy * gy)
    theta = np.mod(np.arctan2(gy, gx), 2.0 * np.pi)
    # The 1e-9 (of a bin) makes an exact tie, which atan2 may land a rounding error either
    # side of, go to the counter-clockwise bin; distinct gradient directions of an image are
    # far further than that from a bin edge.
    obin = np.floor(theta * (n_sens / (2.0 * np.pi)) + 0.5 + 1e-9).astype(np.int64) % n_sens

    # Spatial votes of the pixels in the whole cells: one bincount over the 2 x 2 (row, column)
    # vote pairs of every pixel, into the flat (row, col, bin) histogram.
    h0, w0 = rows * cell, cols * cell
    iy, wy = _prev_spatial_votes(h0, cell, rows)
    ix, wx = _prev_spatial_votes(w0, cell, cols)
    flat = ((iy[:, :, None, None] * cols + ix[None, None, :, :]) * n_sens
            + obin[:h0, None, :w0, None])
    votes = (wy[:, :, None, None] * wx[None, None, :, :]
             * (mag[:h0, None, :w0, None] / (cell * cell)))
    C = np.bincount(flat.ravel(), weights=votes.ravel(), minlength=rows * cols * n_sens)
    C = C.reshape(rows, cols, n_sens)
    sides = np.zeros((rows, cols))
    sides[0] += 1; sides[-1] += 1; sides[:, 0] += 1; sides[:, -1] += 1
    C *= ((8.0 / 7.0) ** sides)[..., None]

    D = C[..., :n_orient] + C[..., n_orient:]
    E = np.einsum("ijb,ijb->ij", D, D)
    eps = 1e-4 / (4.0 * cell ** 4)
    N = 1.0 / np.sqrt(E[:-1, :-1] + E[1:, :-1] + E[:-1, 1:] + E[1:, 1:] + eps)
    P = np.pad(N, 1, mode="edge")            # P[i + 1, j + 1] = N(i, j)
    # (rows, cols, 4): below-right, above-right, below-left, above-left (the reference's order)
    Nl = np.stack([P[1:, 1:], P[:-1, 1:], P[1:, :-1], P[:-1, :-1]], axis=-1)

    TC = np.minimum(C[:, :, None, :] * Nl[..., None], clip)     # (rows, cols, 4, 2p)
    TD = np.minimum(D[:, :, None, :] * Nl[..., None], clip)     # (rows, cols, 4, p)
    parts = [0.5 * TC.sum(axis=2), 0.5 * TD.sum(axis=2), 0.2357 * TC.sum(axis=3)]
    if zero_channel:
        parts.append(np.zeros((rows, cols, 1)))
    return np.concatenate(parts, axis=2).astype(np.float32)


@pytest.mark.parametrize("shape, cell, n_orient", [
    ((64, 64, 3), 4, 9), ((37, 50), 3, 9), ((45, 61, 3), 5, 6), ((128, 96, 3), 8, 9),
    ((201, 199, 3), 4, 9), ((30, 30, 1), 2, 9),
])
def test_equals_previous_implementation(shape, cell, n_orient):
    rng = np.random.default_rng(11)
    for img in (rng.integers(0, 256, shape).astype(np.uint8),
                rng.random(shape).astype(np.float32)):
        want = _previous_fhog(img, cell, n_orient, 0.2)
        got = fhog(img, cell, n_orient, 0.2)
        assert got.dtype == np.float32 and got.shape == want.shape
        np.testing.assert_allclose(got, want, rtol=1e-5, atol=0)
