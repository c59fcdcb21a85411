"""The HOG descriptor of Lee et al. 2012 (section III.2, eq. 2-5), batched over boxes.

A variant of Dalal & Triggs (2005): signed angles (8 bins of 45 degrees over 360), small 4 x 4 px
cells and one normalisation of the whole descriptor instead of overlapping blocks.

Chapter ``03_hog`` of the book. The recipe, on a grey patch resized to 16 wide x 24 high:

1. smooth with a 5 x 5 Gaussian;
2. central differences (eq. 2)::

       g_x(x, y) = I(x+1, y) - I(x-1, y),     g_y(x, y) = I(x, y+1) - I(x, y-1);

3. magnitude m = sqrt(g_x^2 + g_y^2) and angle theta = atan(g_y / g_x) (eq. 3);
4. make the angle *signed*, in [0, 2 pi): theta + 2 pi where theta < 0 (eq. 4);
5. cut the patch into 6 x 4 non-overlapping cells of 4 x 4 px and let every pixel vote its
   magnitude into one of 8 orientation bins of 45 degrees (eq. 5); normalise.

Decisions not printed (the book states them):

- **Order of operations.** The paper resizes the ROI to 16 x 24 *first* (Fig. 1): the BGR box
  is resampled, converted to grey, and the blur and the gradients are taken on that patch,
  not on the frame.
- **Borders.** Both the blur and the differences repeat the patch's edge pixels
  (``BORDER_REPLICATE``): on the first column g_x = I(1, y) - I(0, y), a one-sided difference,
  so a border pixel still votes for the edge it sits on and nothing outside the box leaks in.
- **The Gaussian.** OpenCV's ``GaussianBlur(ksize=5, sigma=0)`` kernel, which for a 5-tap
  window is the binomial [1, 4, 6, 4, 1] / 16 (sigma ~ 1.1), applied separably.
- **Axes.** x runs along columns, y down the rows (image coordinates), so an angle of pi/2 is a
  gradient pointing *down* the image. atan2 gives the quadrant eq. 3's atan cannot.
- **Normalisation.** A reading: eq. 5 normalises per cell, and the text then says "all the
  6x4 descriptors are normalised" [quote: lee2012.hog_cells_normalise], which may mean each
  cell or the whole; the book takes 1/f over all 192 values so that the descriptor sums to 1
  and two descriptors compare with the Bhattacharyya coefficient (eq. 11). A flat patch (no
  gradient anywhere) gets the uniform descriptor 1/192, never NaN.
- **Layout.** Values are ordered (cell row, cell column, orientation bin): index
  ``(r * 4 + c) * 8 + b``.

Neither ``skimage.feature.hog`` (unsigned angles, block normalisation) nor OpenCV 5 (no
HOGDescriptor) computes this descriptor, hence this module.
"""

from __future__ import annotations

import functools

import cv2
import numpy as np

from .patches import sample_patches

#: Patch size (width, height) of Lee et al. 2012.
HOG_PATCH_SIZE = (16, 24)
#: Cell side in pixels (4 x 4 px cells).
HOG_CELL = 4
#: Orientation bins over [0, 2 pi): 8 bins of 45 degrees.
HOG_BINS = 8
#: Length of the descriptor of a 16 x 24 patch: (24/4) x (16/4) cells x 8 bins = 6 x 4 x 8.
HOG_DIM = (HOG_PATCH_SIZE[1] // HOG_CELL) * (HOG_PATCH_SIZE[0] // HOG_CELL) * HOG_BINS

#: The 5-tap Gaussian of step 1 (OpenCV's fixed kernel for ksize=5, sigma=0).
GAUSS5 = np.array([1.0, 4.0, 6.0, 4.0, 1.0]) / 16.0


def to_gray(frame: np.ndarray) -> np.ndarray:
    """A float32 grey image (0..255) of a BGR or grey frame."""
    frame = np.asarray(frame)
    if frame.ndim == 3 and frame.shape[2] == 3:
        frame = cv2.cvtColor(np.ascontiguousarray(frame), cv2.COLOR_BGR2GRAY)
    elif frame.ndim != 2:
        raise ValueError(
            f"frame has shape {frame.shape}; pass an H x W x 3 BGR image or an H x W grey image."
        )
    return frame.astype(np.float32)


def gray_patches(bgr_patches: np.ndarray) -> np.ndarray:
    """(N, h, w, 3) BGR patches -> (N, h, w) uint8 grey patches (OpenCV's BGR2GRAY weights).

    Converting the small resampled patches is cheaper than converting the whole frame, and it
    is the paper's order (resize the ROI, then compute its features).
    """
    p = np.ascontiguousarray(bgr_patches)
    n, h, w = p.shape[:3]
    if n == 0:
        return np.zeros((0, h, w), np.uint8)
    # one row per patch: OpenCV's per-row cost makes n * h short rows several times slower
    g = cv2.cvtColor(p.reshape(n, h * w, 3), cv2.COLOR_BGR2GRAY)
    return g.reshape(n, h, w)


def _pad_edges(patches: np.ndarray, k: int) -> np.ndarray:
    """(N, h, w) patches padded by ``k`` pixels repeating each patch's own edge pixels
    (``np.pad(mode="edge")``, written as five slice copies, which is faster)."""
    n, h, w = patches.shape
    out = np.empty((n, h + 2 * k, w + 2 * k), dtype=patches.dtype)
    out[:, k:-k, k:-k] = patches
    out[:, k:-k, :k] = patches[:, :, :1]
    out[:, k:-k, -k:] = patches[:, :, -1:]
    out[:, :k] = out[:, k:k + 1]
    out[:, -k:] = out[:, -k - 1:-k]
    return out


def _blur(patches: np.ndarray) -> np.ndarray:
    """Step 1: separable 5 x 5 Gaussian of (N, h, w) patches with replicated borders.

    Each patch is padded with its own edge pixels, the padded patches are stacked into one
    tall image and blurred by one ``cv2.sepFilter2D`` call; the 2-px padding keeps a patch's
    blur from ever reaching its neighbour in the stack.
    """
    n, h, w = patches.shape
    patches = np.asarray(patches)
    if patches.dtype not in (np.uint8, np.float32, np.float64):
        patches = patches.astype(np.float64)
    # pad before converting: copying uint8 is cheaper, and OpenCV widens to float64 itself
    # (exactly: the kernel's weights k / 16 are binary fractions)
    tall = _pad_edges(patches, 2).reshape(n * (h + 4), w + 4)
    out = cv2.sepFilter2D(tall, cv2.CV_64F, GAUSS5, GAUSS5, borderType=cv2.BORDER_REPLICATE)
    return out.reshape(n, h + 4, w + 4)[:, 2:-2, 2:-2]


def gradients(patches: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Central differences of eq. 2 of Lee et al. 2012 on (N, h, w) patches, replicated borders.

    Returns
    -------
    gx, gy : (N, h, w) arrays, ``gx = I(x+1, y) - I(x-1, y)``, ``gy = I(x, y+1) - I(x, y-1)``.
    """
    I = np.asarray(patches, dtype=np.float64)
    gx = np.empty_like(I)
    gy = np.empty_like(I)
    np.subtract(I[:, :, 2:], I[:, :, :-2], out=gx[:, :, 1:-1])
    np.subtract(I[:, :, 1], I[:, :, 0], out=gx[:, :, 0])     # replicated border: I(-1, y) = I(0, y)
    np.subtract(I[:, :, -1], I[:, :, -2], out=gx[:, :, -1])
    np.subtract(I[:, 2:], I[:, :-2], out=gy[:, 1:-1])
    np.subtract(I[:, 1], I[:, 0], out=gy[:, 0])
    np.subtract(I[:, -1], I[:, -2], out=gy[:, -1])
    return gx, gy


def magnitude_angle(gx: np.ndarray, gy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Magnitude (eq. 3) and signed angle in [0, 2 pi) (eq. 3-4 of Lee et al. 2012)."""
    m = np.sqrt(gx * gx + gy * gy)
    theta = np.arctan2(gy, gx)                              # (-pi, pi], quadrant-aware eq. 3
    theta = np.where(theta < 0, theta + 2 * np.pi, theta)   # eq. 4
    return m, theta


#: The bin of eq. 4's angle for 8 bins, by octant: key 9 sign(g_y) + 3 sign(g_x) +
#: sign(|g_y| - |g_x|) + 13. The octants' edges are the bins' edges (multiples of 45 degrees),
#: so signs and the diagonal decide the bin exactly; an edge starts its bin (0 deg -> 0,
#: 45 -> 1, 90 -> 2, ..., 315 -> 7). Keys no (g_x, g_y) can give (e.g. both signs 0 and
#: |g_y| > |g_x|) hold 0. atan2(0, 0) = 0, so a zero gradient is in bin 0, as np.arctan2 says.
_OCTANT_BIN = np.zeros(27, dtype=np.intp)
for _sy, _sx, _d, _b in [(0, 0, 0, 0), (0, 1, -1, 0), (0, -1, -1, 4), (1, 0, 1, 2),
                         (-1, 0, 1, 6), (1, 1, -1, 0), (1, 1, 0, 1), (1, 1, 1, 1),
                         (1, -1, 1, 2), (1, -1, 0, 3), (1, -1, -1, 3), (-1, -1, -1, 4),
                         (-1, -1, 0, 5), (-1, -1, 1, 5), (-1, 1, 1, 6), (-1, 1, 0, 7),
                         (-1, 1, -1, 7)]:
    _OCTANT_BIN[9 * _sy + 3 * _sx + _d + 13] = _b


def _sign_i8(a: np.ndarray) -> np.ndarray:
    # -1, 0, 1 as int8 (a quarter of the memory traffic of np.sign's float64)
    return (a > 0).view(np.int8) - (a < 0).view(np.int8)


def orientation_bin(gx: np.ndarray, gy: np.ndarray, bins: int = HOG_BINS) -> np.ndarray:
    """Index u of the bin [u 2pi/bins, (u+1) 2pi/bins) holding eq. 4's angle (Lee et al. 2012).

    For the paper's 8 bins of 45 degrees the bin is the octant of (g_x, g_y): the signs of
    g_x and g_y and whether |g_y| exceeds |g_x| (``_OCTANT_BIN``). That is exact, with no
    arctangent and no rounding at the edges, and faster than
    ``np.arctan2`` (which was the HOG trackers' largest single cost per frame). For other bin counts it is floor(atan2(g_y, g_x) * bins / 2pi + bins) mod
    bins, the same bin as eq. 4's theta + 2pi: the shift by ``bins`` (not 2pi) makes every
    value positive, so the floor is a plain integer cast, and an angle just below 0 lands in
    the last bin and never in a bin ``bins``. (The two agree on every (g_x, g_y) except
    (-0.0, -0.0), which np.arctan2 puts at -pi; a zero gradient votes nothing, so its bin
    never matters. ``tests/test_hog.py`` compares them on random and edge angles.)
    """
    gx = np.asarray(gx)
    gy = np.asarray(gy)
    if bins == 8:
        ax, ay = np.abs(gx), np.abs(gy)
        key = _sign_i8(gy) * np.int8(9)
        key += _sign_i8(gx) * np.int8(3)
        key += (ay > ax).view(np.int8)
        key -= (ay < ax).view(np.int8)
        key += np.int8(13)
        return _OCTANT_BIN[key]
    t = np.arctan2(gy, gx)
    t *= bins / (2 * np.pi)
    t += bins                                   # (-pi, pi] -> (bins / 2, 3 bins / 2]
    b = t.astype(np.intp)                       # floor, as t > 0
    if bins & (bins - 1) == 0:
        b &= bins - 1                           # mod for a power of two, much cheaper than %
    else:
        np.mod(b, bins, out=b)
    return b


@functools.lru_cache(maxsize=16)
def _vote_offsets(n: int, h: int, w: int, cell: int, bins: int) -> np.ndarray:
    """Where pixel (y, x) of patch i votes: (i * cells + its cell) * bins, cached per shape
    because a tracker asks for the same N x h x w every frame."""
    cols = w // cell
    cell_of_pixel = (np.arange(h)[:, None] // cell) * cols + np.arange(w)[None, :] // cell
    dim = (h // cell) * cols * bins
    out = cell_of_pixel[None] * bins + (np.arange(n) * dim)[:, None, None]
    out.flags.writeable = False
    return out


def hog_of_patches(gray_patches: np.ndarray, cell: int = HOG_CELL,
                   bins: int = HOG_BINS) -> np.ndarray:
    """HOG descriptors of a stack of grey patches (eq. 2-5 of Lee et al. 2012), vectorised.

    Parameters
    ----------
    gray_patches : (N, h, w) array; h and w must be multiples of ``cell``.
    cell : cell side in pixels (4).
    bins : orientation bins over [0, 2 pi) (8).

    Returns
    -------
    (N, (h / cell) * (w / cell) * bins) float array, rows sum to 1 (uniform for a flat patch).
    """
    g = np.asarray(gray_patches)
    if g.ndim != 3:
        raise ValueError(f"gray_patches must be an (N, h, w) array, got shape {g.shape}.")
    n, h, w = g.shape
    if h % cell or w % cell:
        raise ValueError(
            f"patch size {w}x{h} is not a multiple of the {cell}px cell; "
            f"resize patches to e.g. {HOG_PATCH_SIZE[0]}x{HOG_PATCH_SIZE[1]}."
        )
    rows, cols = h // cell, w // cell
    dim = rows * cols * bins
    if n == 0:
        return np.zeros((0, dim))
    gx, gy = gradients(_blur(g))                                       # eq. 2
    # in-place arithmetic: 100 patches make ~300 kB per temporary, and fewer temporaries
    # stay in cache
    index = orientation_bin(gx, gy, bins)                              # eq. 3-4
    index += _vote_offsets(n, h, w, cell, bins)
    m = np.multiply(gx, gx, out=gx)
    m += np.multiply(gy, gy, out=gy)
    np.sqrt(m, out=m)                                                  # eq. 3
    hist = np.bincount(index.ravel(), weights=m.ravel(), minlength=n * dim).reshape(n, dim)
    total = hist.sum(axis=1, keepdims=True)
    # eq. 5's 1/f over the whole descriptor; a patch with no gradient has no shape: uniform.
    flat = total <= 1e-9
    return np.where(flat, 1.0 / dim, hist / np.where(flat, 1.0, total))


def hog_of_patch(gray_patch: np.ndarray) -> np.ndarray:
    """The HOG descriptor of one grey patch (24 x 16 in the paper -> ``HOG_DIM`` = 192 values).

    eq. 2-5 of Lee et al. 2012; see the module docstring for the border and blur decisions.
    """
    p = np.asarray(gray_patch)
    if p.ndim != 2:
        raise ValueError(
            f"gray_patch must be a 2-D grey patch (height x width), got shape {p.shape}; "
            "convert colour with trackbook.features.hog.to_gray."
        )
    return hog_of_patches(p[None])[0]


def hog_descriptors(frame: np.ndarray, boxes, size=HOG_PATCH_SIZE) -> np.ndarray:
    """HOG descriptors of every box of a frame, batched (section III.2 of Lee et al. 2012).

    All boxes are resampled to ``size = (width, height)`` in one ``cv2.remap`` call
    (:func:`~trackbook.features.patches.sample_patches`), converted to grey (the paper's order:
    resize the ROI first, Fig. 1), then blurred, differentiated and binned together (eq. 2-5).

    Parameters
    ----------
    frame : H x W x 3 BGR (or H x W grey) image.
    boxes : (N, 4) array of ``(x, y, w, h)``; parts outside the frame repeat the border.
    size : patch ``(width, height)``, multiples of 4; (16, 24) gives ``HOG_DIM`` = 192 values.

    Returns
    -------
    (N, D) float array whose rows sum to 1; D = 192 for the default size.
    """
    frame = np.asarray(frame)
    if frame.ndim == 3 and frame.shape[2] == 3:
        return hog_of_patches(gray_patches(sample_patches(frame, boxes, size)))
    return hog_of_patches(sample_patches(to_gray(frame), boxes, size))
