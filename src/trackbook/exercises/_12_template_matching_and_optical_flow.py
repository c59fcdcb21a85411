"""The exercises of 12_template_matching_and_optical_flow: their text, defined once (see
:mod:`trackbook.exercises`), and the auto-check of the ★★★ one."""

from __future__ import annotations

import numpy as np

STEM = "12_template_matching_and_optical_flow"

TEXT = r"""
=== 12.1 ★ pen and paper | One Lucas–Kanade step by hand
Take $I(x) = x^2$ and the same row moved by $p = 0.5$, $J(x) = (x - 0.5)^2$, with the exact
derivative $I_x = 2x$. Compute the one-step estimate
$\sum I_x (I - J) / \sum I_x^2$ on the window $x = -1, 0, 1$, then on $x = 0, 1, 2$. Show that
for this $I$ and any window the step is $p - p^2 \sum x / (2 \sum x^2)$, and say when one step
is exact.
--- solution
On $x = -1, 0, 1$: $I - J = -1.25, -0.25, 0.75$ and $I_x = -2, 0, 2$, so
$\sum I_x (I - J) = 2.5 + 0 + 1.5 = 4$ and $\sum I_x^2 = 8$: the step is exactly $0.5$.
On $x = 0, 1, 2$ (the chapter's example) it is $8.5 / 20 = 0.425$. In general
$I - J = x^2 - (x - p)^2 = 2px - p^2$, so
$\sum 2x (2px - p^2) / \sum 4x^2 = p - p^2 \sum x / (2\sum x^2)$. One step is exact when the
window is symmetric about the vertex ($\sum x = 0$); otherwise the second-order term the
Taylor step drops biases it by $p^2 \sum x / (2 \sum x^2)$, which iterating removes.

=== 12.2 ★ pen and paper | What NCC does not see
Show that zero-mean NCC is unchanged when the window's grey levels are replaced by
$a I + b$ with $a > 0$, and that it changes sign when $a < 0$. By how much does the SSD of a
perfect match change when the window is brightened by $b = 20$ grey levels, for an
$h \times w$ template? And what happens to NCC on a window of constant grey level?
--- solution
The window's mean becomes $a \bar I + b$, so $I' \mapsto a I'$: the offset disappears with the
mean. The numerator $\sum T' I'$ becomes $a \sum T' I'$ and the denominator
$\sqrt{\sum T'^2 \sum I'^2}$ becomes $|a|$ times itself, so NCC is multiplied by
$a / |a| = \operatorname{sign}(a)$: unchanged for $a > 0$, negated for $a < 0$ (an inverted
image is a perfect *anti*-match). The SSD of the perfect match goes from 0 to
$\sum 20^2 = 400\, h w$. On a constant window $I' = 0$ and NCC is $0/0$: undefined (the
library returns 0 there, no evidence either way).

=== 12.3 ★★ pen and paper | Eigenvalues of an edge and of a corner
In a window, $n_1$ pixels have the gradient $m\,\mathbf u_1$ and $n_2$ pixels the gradient
$m\,\mathbf u_2$, with unit vectors $\mathbf u_1, \mathbf u_2$ at an angle $\varphi$; all
other pixels have gradient 0. Write the structure tensor $Z$ as a sum of outer products and
find its eigenvalues (a) for an edge ($n_2 = 0$), whatever its direction, (b) for a right-angled
corner ($\varphi = 90°$), (c) for $n_1 = n_2 = n$ and any $\varphi$. Which corners are the best
to track? (d) Give $(\lambda_{\min}, \lambda_{\max})$ for $n = 5$, $m = 2$ and $\varphi = 60°$.
--- solution
$Z = m^2 (n_1 \mathbf u_1 \mathbf u_1^T + n_2 \mathbf u_2 \mathbf u_2^T)$.
(a) $Z = n_1 m^2\, \mathbf u_1 \mathbf u_1^T$ has rank 1: eigenvalues $n_1 m^2$ (along
$\mathbf u_1$) and 0 (along the edge), for any direction, so turning an edge does not help:
the motion along it is never determined. (b) With $\mathbf u_1 \perp \mathbf u_2$ the two outer
products share the eigenvectors: eigenvalues $n_1 m^2$ and $n_2 m^2$, and
$\lambda_{\min} = m^2 \min(n_1, n_2)$: a corner is as good as its *shorter* edge.
(c) The trace is $2nm^2$ and the determinant $n^2 m^4 (1 - \cos^2\varphi)$, so the eigenvalues
are $n m^2 (1 \pm \cos\varphi)$ and $\lambda_{\min} = n m^2 (1 - |\cos\varphi|)$. The best
corners are right-angled, with two long, contrasted edges; a sharp or a flat angle is nearly
an edge. (d) $n m^2 = 20$ and $\cos 60° = 1/2$: $(\lambda_{\min}, \lambda_{\max}) = (10, 30)$.

=== 12.4 ★★ pen and paper | How many pyramid levels
Suppose the Lucas–Kanade iteration converges when the motion it has to find on a level is at
most 2 px. How many levels does a motion of 20 px need? What is the motion on each level,
and what does an error of 0.1 px left on the coarsest level become on the next? With a
21 × 21 window, how much of the original frame does the window cover on the coarsest level,
and why is that a problem for a 30 × 30 target?
--- solution
On level $\ell$ (0 is the frame itself) the motion is $20 / 2^\ell$: 20, 10, 5, 2.5, 1.25 px.
It is at most 2 px from $\ell = 4$ on, so five levels are needed. The coarse estimate is
doubled on the way down, so an error of 0.1 px becomes 0.2 px on the next level, which that
level corrects: each level only has to find its own doubled residual, well within 2 px. On
level 4 one pixel is $2^4 = 16$ pixels of the frame, so the window covers $21 \times 16 = 336$
pixels on a side, more than a 320 × 240 frame: a 30 × 30 target is a small part of it, and
the coarse estimate is the motion of the background. Use as few levels as the motion needs.

=== 12.5 ★ use | Template matching as a tracker
Match the first frame's patch of `occluder` against every fifth frame (0, 5, 10, …) with
`tm.ncc_map`, and plot, for each, the best NCC value and the IoU of the best window with the
ground truth. List the frames whose best window misses the person (IoU below 0.5). What
happens while the person is behind the tree, and after? Compare with Median Flow on the same
clip.
--- solution
While the person is visible the best NCC is mostly between 0.8 and 0.96 and the best window
is on the person. Behind the tree (frames 65 to 85, the five frames the list holds) the peak falls to about
0.4 and the window is elsewhere; from about frame 90 on it is back on the person. A whole-frame search with a fixed
template finds the target again, and its peak value says "not here" while the target is
hidden, where Median Flow's FB error stayed small and its box stayed behind on the
background.

=== 12.6 ★★ modify | The pyramid on a fast target
Run `median-flow` on the first 60 frames of `yellow-ball` with `levels` 1, 2 and 3 (the
default), as a dict {levels: AUC}. Compare the AUCs, and explain with the pyramid why.
--- solution
With one or two levels the AUC is low (about 0.2 to 0.3) and with three it is above 0.8. The
ball moves several pixels per frame, more than an 11 × 11 window's local search can reach on
one level; each extra level halves the motion the coarsest level has to find.

=== 12.7 ★★★ implement | Lucas–Kanade for one window
Write `lk_window(I, J, x, y, r, iterations)` for two grey images (2-D float arrays): the
displacement $(p, q)$ of the $(2r + 1) \times (2r + 1)$ window centred on pixel $(x, y)$
(column $x$, row $y$) of $I$. Take $I_x, I_y$ by central differences of $I$ (`np.gradient`),
build $Z$, and repeat `iterations` times: sample $J$ bilinearly at the window's pixels moved
by the current $(p, q)$ (`scipy.ndimage.map_coordinates` with `order=1`), solve
$Z\,\delta = \sum \nabla I\,(I - J_\text{moved})$ and add $\delta$. Return `None` when $Z$ is
singular (its smaller eigenvalue at most $10^{-9}$ times the larger). The check uses a bowl
$I = (x - 20)^2 + (y - 20)^2$: moved by $(0.5, -0.25)$, one step from its centre is exact
(exercise 12.1 in two dimensions); moved by $(2, -1)$, 30 iterations on an off-centre window
must reach $(2, -1)$; a ramp $I = 10x$ must give `None`; $J = I$ must give $(0, 0)$.
--- solution
`Iy, Ix = np.gradient(I)`; take the window's rows and columns, $Z$ from the three sums, and in
each iteration `Jw = map_coordinates(J, [rows + q, cols + p], order=1)`,
`e = I_window - Jw`, `delta = np.linalg.solve(Z, [sum(Ix * e), sum(Iy * e)])`. Why the bowl
cases are exact: central differences are exact on a quadratic, and on a window symmetric
about the vertex the cross sums vanish, so $Z = \operatorname{diag}(4\sum u^2, 4\sum v^2)$
and the right-hand side is $(4p\sum u^2, 4q\sum v^2)$. At the integer shift $(2, -1)$ the
moved window samples $J$ at whole pixels, where it equals $I$ exactly: the residual and the
step are 0, so that is where the iteration stops.
"""


def _bowl(px=0.0, py=0.0, n=41, c=20.0):
    """(x - c - px)^2 + (y - c - py)^2 on an n x n grid: the bowl centred at c, moved by
    (px, py)."""
    yy, xx = np.mgrid[0:n, 0:n].astype(float)
    return (xx - c - px) ** 2 + (yy - c - py) ** 2


def lk_window_ok(f) -> bool:
    """12.7: one window's Lucas-Kanade on cases worked out by hand (see the exercise)."""
    def close(got, want, atol):
        return got is not None and np.allclose(np.asarray(got, float), want, atol=atol)

    I = _bowl()
    # one step from the vertex, window symmetric: exact (0.5, -0.25) (exercise 12.1 in 2-D)
    if not close(f(I, _bowl(0.5, -0.25), 20, 20, 5, 1), [0.5, -0.25], 1e-9):
        return False
    # off-centre window, integer shift: the fixed point is exactly (2, -1); 30 iterations
    # of bilinear Gauss-Newton reach it (a reference solution is within 1e-7 after 8)
    if not close(f(I, _bowl(2.0, -1.0), 14, 25, 4, 30), [2.0, -1.0], 0.01):
        return False
    # no motion: the residual is 0 at (0, 0)
    if not close(f(I, I.copy(), 12, 27, 3, 5), [0.0, 0.0], 1e-12):
        return False
    # a ramp in x: Iy = 0 everywhere, Z = diag(a, 0) is singular (the aperture problem)
    ramp = 10.0 * np.mgrid[0:41, 0:41][1].astype(float)
    return f(ramp, ramp + 5.0, 20, 20, 5, 3) is None


CHECKS = {"12.7": lk_window_ok}
