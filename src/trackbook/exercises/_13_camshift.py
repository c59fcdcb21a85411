"""The exercises of 13_camshift: their text, defined once (see :mod:`trackbook.exercises`),
and the auto-check of its ★★★ exercise."""

import numpy as np

STEM = "13_camshift"

TEXT = r"""
=== 13.1 ★ pen and paper | The moments of a uniform rectangle
A probability image is $b = 255$ on an axis-aligned block of $w$ columns and $h$ rows of
pixels ($w > h$) and 0 elsewhere. Work out $M_{00}$, the centroid, and the normalised
central moments $\bar\mu_{20}, \bar\mu_{11}, \bar\mu_{02}$ (the sum
$\sum_{k=0}^{n-1} (k - \tfrac{n-1}{2})^2 = n(n^2 - 1)/12$ helps). What are $\theta$,
$\sigma_\mathrm{l}$ and $\sigma_\mathrm{w}$, and how long is OpenCV's rectangle of side $4\sigma_\mathrm{l}$ against the
block's $w$ when $w$ is large?
--- solution
$M_{00} = 255\,wh$ and the centroid is the block's centre. Every row is the same, so
$\bar\mu_{20}$ is the variance of the column index over $w$ equally weighted columns,
$(w^2 - 1)/12$; likewise $\bar\mu_{02} = (h^2 - 1)/12$, and $\bar\mu_{11} = 0$ because the
deviations in $x$ and $y$ are independent and each sums to zero. So $\theta = \tfrac12
\operatorname{atan2}(0, \bar\mu_{20} - \bar\mu_{02}) = 0$, $\sigma_\mathrm{l} = \sqrt{(w^2 - 1)/12}$ and
$\sigma_\mathrm{w} = \sqrt{(h^2 - 1)/12}$. For large $w$, $\sigma_\mathrm{l} \approx w/\sqrt{12}$ and
$4\sigma_\mathrm{l} \approx 4w/\sqrt{12} = 1.155\,w$: OpenCV's rectangle is 15 % longer than a uniform
block (the side of a uniform block is $\sqrt{12}\,\sigma \approx 3.46\,\sigma$, not $4\sigma$).
For $w = 30$, $h = 10$: $\bar\mu_{20} = 899/12 = 74.92$, $\bar\mu_{02} = 99/12 = 8.25$.

=== 13.2 ★ pen and paper | The orientation of a tilted rectangle
Turn the block of exercise 13.1 by an angle $\varphi$, measured from the $x$ axis towards the
$y$ axis (clockwise on screen, since $y$ points down), with $w, h$ large, so that the
variances along its own axes are $w^2/12$ and $h^2/12$. Write its normalised central
moments and show that
$\theta = \tfrac12 \operatorname{atan2}(2\bar\mu_{11}, \bar\mu_{20} - \bar\mu_{02})$ gives back $\varphi$. What happens when $w = h$?
--- solution
With $u$ along the block's long side and $v$ across it, $x = u\cos\varphi - v\sin\varphi$,
$y = u\sin\varphi + v\cos\varphi$, and $u, v$ uncorrelated with variances $\ell = w^2/12$,
$s = h^2/12$. So $\bar\mu_{20} = \ell\cos^2\varphi + s\sin^2\varphi$,
$\bar\mu_{02} = \ell\sin^2\varphi + s\cos^2\varphi$ and $\bar\mu_{11} = (\ell - s)
\sin\varphi\cos\varphi$. Then $\bar\mu_{20} - \bar\mu_{02} = (\ell - s)\cos 2\varphi$ and
$2\bar\mu_{11} = (\ell - s)\sin 2\varphi$; for $\ell > s$ the atan2 is $2\varphi$ and
$\theta = \varphi$ (modulo 180°). With $w = h$ both arguments are 0: a square (or a disc) has
no orientation, and the angle CamShift reports for it is whatever the noise makes it.

=== 13.3 ★ pen and paper | The window's side from $M_{00}$
A square target of side $d$ px sits inside the search window. (a) Every one of its pixels has
$b = 255$: what side $w_\mathrm{win} = 2\sqrt{M_{00}/256}$ does the next window get, for $d = 20$?
(b) The light changes and the target's pixels now fall in a bin of the histogram worth 128:
what side now? (c) What does (b) say about a target whose colours are only partly in the
histogram?
--- solution
(a) $M_{00} = 255\,d^2$, so $w_\mathrm{win} = 2\sqrt{255/256}\,d \approx 2d$: $w_\mathrm{win} = 39.9 \approx 40$ px for
$d = 20$, twice the target's side. (b) $M_{00} = 128\,d^2$ and $w_\mathrm{win} = 2\sqrt{128/256}\,d =
\sqrt 2\, d = 28.3$ px. (c) The rule reads $M_{00}$ as a count of "full" pixels: a target
whose back-projection is weak looks smaller than it is, and the window shrinks around it (a
target whose colours are common in the background looks larger, and the window grows).

=== 13.4 ★★★ implement | Orientation and axes from moments
Write `axes(prob)` that returns `(theta, sigma_l, sigma_w)` for a whole 2-D probability image
(pixel $(i, j)$ at $x = j$, $y = i$, $y$ pointing down): $\theta$ in degrees, the angle of the
long axis from the $x$ axis, $\tfrac12\operatorname{atan2}(2\bar\mu_{11}, \bar\mu_{20} -
\bar\mu_{02})$, and $\sigma_\mathrm{l} \ge \sigma_\mathrm{w}$ the standard deviations along and across it (the
square roots of the eigenvalues of
$\begin{pmatrix}\bar\mu_{20} & \bar\mu_{11}\\ \bar\mu_{11} & \bar\mu_{02}\end{pmatrix}$).
Use numpy only. By hand first: five pixels of 255 on the diagonal of a $5 \times 5$ image
have centroid $(2, 2)$ and $\bar\mu_{20} = \bar\mu_{02} = \bar\mu_{11} = (4 + 1 + 0 + 1 +
4)/5 = 2$, so $\theta = 45°$, $\sigma_\mathrm{l} = 2$, $\sigma_\mathrm{w} = 0$. The check uses that case, the
other diagonal ($-45°$), a row of five pixels ($0°$, $\sqrt 2$, 0) and a $2 \times 4$ block
($0°$, $\sqrt{1.25}$, $0.5$); angles are compared modulo 180°.
--- solution
The moments are sums over the pixel grid (`np.indices`); the eigenvalues of the symmetric
2 × 2 matrix are $\tfrac12(\bar\mu_{20} + \bar\mu_{02}) \pm \tfrac12\sqrt{4\bar\mu_{11}^2 +
(\bar\mu_{20} - \bar\mu_{02})^2}$, the larger along $\theta$.

=== 13.5 ★★ modify | Bradski's plain histogram
Run `camshift` with `background_weighted=False` (the plain hue histogram of
Bradski 1998) and with the default on `yellow-ball` and on `patterned-object`. On
which clip does the plain histogram fail worst, and why there?
--- solution
The plain histogram fails on both (AUC about 0.08 on `patterned-object` and 0.33 on
`yellow-ball`, against 0.84 and 0.92 with the weights). On `patterned-object` it fails at
once: the table's browns and reds have the hues of the object, the back-projection is high
all round it, and the window grows to the whole frame within a few frames. On `yellow-ball`
the lawn holds some of the ball's hues: the window settles at about 50 px a side, against
about 30 with the weights (the ball's box is 18 px), and the box, sized from $M_{00}$, is
too large on every frame, so its overlap stays low although it follows the ball. Weighing
down the hues of the ring around the first box is what keeps the window on the target in
both clips.

=== 13.6 ★ use | OpenCV's rectangle on a bar
Draw a filled bar of $60 \times 12$ pixels of value 255 in a $120 \times 160$ image, run
`cv2.CamShift` on it from a window around it, and compare the returned rectangle's long side
with 60. Explain the ratio with exercise 13.1.
--- solution
OpenCV returns sides $4\sigma$; for a uniform bar $\sigma_\mathrm{l} = \sqrt{(60^2 - 1)/12} = 17.31$,
so the long side is $69.3$ px, $1.155$ times the bar's length, and the short side
$4\sqrt{(12^2 - 1)/12} = 13.8$ px. To get the block's sides back, multiply by
$\sqrt{12}/4 = 0.866$.
"""


def _angle_close(a, b, tol=1e-6):
    """Angles in degrees equal modulo 180."""
    d = (float(a) - float(b)) % 180.0
    return min(d, 180.0 - d) < tol


def axes_ok(f):
    """13.4: theta (degrees), sigma_l, sigma_w of a probability image, on hand-worked blobs."""
    diag = np.zeros((5, 5))
    diag[np.arange(5), np.arange(5)] = 255
    # centroid (2, 2); mu20 = mu02 = mu11 = (4 + 1 + 0 + 1 + 4) / 5 = 2 -> 45 deg, 2, 0
    anti = diag[:, ::-1].copy()
    # x mirrored: mu11 = -2 -> -45 deg, 2, 0
    row = np.zeros((3, 7))
    row[1, 1:6] = 255
    # x = 1..5, variance (4 + 1 + 0 + 1 + 4) / 5 = 2; y constant -> 0 deg, sqrt 2, 0
    block = np.zeros((4, 6))
    block[1:3, 1:5] = 1.0
    # 4 columns: variance (16 - 1) / 12 = 1.25; 2 rows: (4 - 1) / 12 = 0.25 -> 0 deg, sqrt 1.25, 0.5
    cases = [(diag, 45.0, 2.0, 0.0), (anti, -45.0, 2.0, 0.0), (row, 0.0, np.sqrt(2), 0.0),
             (block, 0.0, np.sqrt(1.25), 0.5)]
    for img, theta, s_l, s_w in cases:
        t, a, b = (float(v) for v in f(img))
        if not (_angle_close(t, theta) and abs(a - s_l) < 1e-6 and abs(b - s_w) < 1e-6):
            return False
    return True


CHECKS = {"13.4": axes_ok}
