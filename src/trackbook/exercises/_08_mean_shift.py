"""The exercises of 08_mean_shift: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "08_mean_shift"

TEXT = r"""
=== 8.1 ★ use | One candidate
Run `condensation-mean-shift` on `occluder` (random seed 0) with `n_particles=1`,
`use_motion=False`, `noise_position=0.0`, `noise_velocity=0.0`, and `mean-shift` on the same
clip. Are the two trackers' boxes the same on every frame? Answer `True` or `False`, and
explain what is left of the proposed tracker.
--- solution
One candidate, predicted without noise or motion vector and then moved only by mean-shift, is
the mean-shift tracker: same lattice, same steps, same boxes.

=== 8.2 ★ use | How many candidates?
Run `condensation-mean-shift` (seed 0) on `shelves` with 1, 5 and 20 candidates
(`n_particles=`). Answer `{1: auc, 5: auc, 20: auc}`. How does the AUC change?
--- solution
The AUC rises from 1 to 5 candidates and hardly moves from 5 to 20 (the hidden cell prints
the three values). Mean-shift pulls every candidate to a nearby mode, so a handful of
candidates already covers the few modes there are; more candidates mostly land on the same
modes.

=== 8.3 ★★ modify | Eq. 13: mean-shift never lowers ρ on average
Create the tracker (`trackers.create("condensation-mean-shift", seed=0)`), initialise it on
frame 0 of `occluder` with its ground-truth box and update it on frames 1–30. After each
update, `tracker.rho` holds the candidates' Bhattacharyya coefficients after mean-shift and
`tracker.rho_before` before it. Answer the smallest gap `mean(rho) - mean(rho_before)` over
the 30 frames. Is it ever negative?
--- solution
Never: the smallest gap is positive (the hidden cell prints it). Each candidate's climb keeps
a step only when it does not lower $\rho$ (step ⑤ halves it until it does, and a step that
still lowers $\rho$ is refused), so every candidate's $\rho$ after mean-shift is at least its
$\rho$ before, and so is the mean over the candidates: eq. 13.

=== 8.4 ★★ modify | Wider noise for Condensation
Widen Condensation's position noise (`noise_position` 0.3 and 0.6) on `occluder`.
Does it now survive the pole?
--- solution
No. With 0.3 and 0.6 the AUC stays about 0.40 and the centre error at the last frame stays
above 200 pixels: once the person is behind the pole, candidates spread a few tenths of a
half-axis a frame around a wrong estimate do not reach the person again.

=== 8.5 ★★★ implement | The motion vector of eq. 8
Write `motion_lsq(I0, I1)` that returns the least-squares $(p, q)$ minimising
$\sum (pI_x + qI_y + I_t)^2$ (eq. 8 of Cho & Kang 2005) over the whole image: $I_x, I_y$ by
central differences (`np.gradient`) of the mean of the two frames, $I_t = I_1 - I_0$, and the
2 × 2 normal equations. The check moves a smooth blob by $(0.4, -0.3)$ pixels and expects your
answer within 0.05 pixels, and $(0, 0)$ for a blob that does not move.
--- solution
Setting the derivatives in $p$ and $q$ to zero gives
$\begin{bmatrix}\sum I_x^2 & \sum I_xI_y\\ \sum I_xI_y & \sum I_y^2\end{bmatrix}
\begin{bmatrix}p\\ q\end{bmatrix} = -\begin{bmatrix}\sum I_xI_t\\ \sum I_yI_t\end{bmatrix}$.
`np.gradient` returns the derivative along rows ($I_y$) first.

=== 8.6 ★★ modify | Force a swap
On `two-faces`, force a swap by hand: exchange the two trackers (`mt.trackers.reverse()`)
after the crossing (frame 95), then *during* the overlap (frame 65) — `run_faces(faces,
name, associate, swap_at=...)` of the {doc}`case study <case_study_cho2005>`'s data-association
section does it. How many identity switches do the independent and
the associated trackers make? Look at the distance between the face centres and at the
squared distances `d2` of the gate to explain why association copes at frame 65 too.
--- solution
At both frames the independent trackers make 2 identity switches (each face changes track
once) and the associated ones none. At frame 65 the boxes overlap, but their centres are
still about 20 pixels apart, while each track's Kalman filter, steady after 65 frames of
smooth motion, predicts its own face's centre closely: each track's own box lies well inside
its gate. A box on the other face may fall inside a gate too, but the other wrong pair is far
outside, and the assignment takes the least total $d^2$, which the right pairs give (the
hidden cell prints `d2`). It would fail once both wrong pairs cost little, or when both
trackers sit on one face.

=== 8.7 ★★★ implement | Counting identity switches
For one face, `seq[t]` is the track matched to it in frame `t` (−1: none). Write
`my_switches(seq)` that counts the frames in which the face is matched to a different track
than the last one it was matched to; frames without a match neither count nor reset that
memory. By hand: `[0, 0, -1, 1, 1, -1, 1, 0]` goes 0 → 1 (one switch), stays with 1 across the
gap (none), then 1 → 0 (one): 2. The check uses that case and five more worked by hand.

=== 8.8 ★★ pen and paper | The mean-shift step from the density gradient
The weighted kernel density at $y$ is $\hat f(y) = C \sum_i w_i\, k(\lVert (y - x_i)/h\rVert^2)$
with a profile $k$ and $g = -k'$. Show that $\nabla \hat f(y) = 0$ gives the fixed point
$y = \sum_i x_i w_i g_i / \sum_i w_i g_i$ with $g_i = g(\lVert (y - x_i)/h\rVert^2)$, so that
the mean-shift step $\hat y_1 = \sum_i x_i w_i g_i / \sum_i w_i g_i$ moves towards it. Then, by
hand, in one dimension: the Epanechnikov profile, written here on the squared distance
$s = \lVert (y - x_i)/h\rVert^2$ as $k(s) = 1 - s$ for $s \le 1$ (the chapter's
$1 - r^2$ on $r$), $h = 2$,
pixels at $x = 0, 1, 2$ with weights $w = 1, 2, 1$, start $\hat y_0 = 1.5$. Where is
$\hat y_1$?
--- solution
$\nabla \hat f(y) = C \sum_i w_i\, k'(\cdot)\, 2(y - x_i)/h^2$
$= \frac{2C}{h^2} \sum_i w_i g_i (x_i - y)$
$= \frac{2C}{h^2}\left(\sum_i w_i g_i\right)
\left(\frac{\sum_i x_i w_i g_i}{\sum_i w_i g_i} - y\right)$. The last factor is the mean-shift
vector $\hat y_1 - y$: it points along the gradient, and it is zero exactly where the gradient
is. For the Epanechnikov profile $g = 1$ inside the kernel and 0 outside, so the step is the
weighted mean of the pixels inside. From $\hat y_0 = 1.5$ the distances over $h$ are 0.75,
0.25 and 0.25, so $s < 1$ for all three pixels: $\hat y_1 = (0 \cdot 1 + 1 \cdot 2 + 2 \cdot 1)/4 = 1$.
"""
