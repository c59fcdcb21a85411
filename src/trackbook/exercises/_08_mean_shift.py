"""The exercises of 08_mean_shift: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "08_mean_shift"

TEXT = r"""
=== 8.1 ★ use | One candidate | after case_study_cho2005
Run `condensation-mean-shift` on `occluder` (random seed 0) with `n_particles=1`,
`use_motion=False`, `noise_position=0.0`, `noise_velocity=0.0`, and `mean-shift` on the same
clip. Are the two trackers' boxes the same on every frame? Answer `True` or `False`, and
explain what is left of the proposed tracker.
--- solution
One candidate, predicted without noise or motion vector and then moved only by mean-shift, is
the mean-shift tracker: same lattice, same steps, same boxes.

=== 8.2 ★ use | How many candidates? | after case_study_cho2005
Run `condensation-mean-shift` (seed 0) on `shelves` with 1, 5 and 20 candidates
(`n_particles=`). Answer `{1: auc, 5: auc, 20: auc}`. How does the AUC change?
--- solution
The AUC rises from 1 to 5 candidates and hardly moves from 5 to 20 (the hidden cell shows
the three values). Mean-shift pulls every candidate to a nearby mode, so a handful of
candidates already covers the few modes there are; more candidates mostly land on the same
modes.

=== 8.3 ★★ modify | Eq. 13: mean-shift never lowers ρ on average | after case_study_cho2005
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

=== 8.4 ★★ modify | Wider noise for Condensation | after case_study_cho2005
Widen Condensation's position noise (`noise_position` 0.3 and 0.6) on `occluder`.
Does it now survive the tree trunk?
--- solution
No. With 0.3 and 0.6 the AUC stays about 0.40 and the centre error at the last frame stays
above 200 pixels: once the person is behind the tree trunk, candidates spread a few tenths of a
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

=== 8.6 ★★ modify | Force a swap | after case_study_cho2005
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
--- solution
Keep `last`, the track the face was last matched to (none before its first match), and walk
through the frames: a frame without a match ($-1$) is skipped, so it neither counts nor
forgets `last`; a match to a track other than `last` counts one switch; every match then
becomes the new `last`.

```python
def my_switches(seq):
    last, n = None, 0
    for i in seq:
        if i < 0:               # no match: no switch, and last is kept
            continue
        if last is not None and i != last:
            n += 1
        last = i
    return n
```

The same count without a loop: drop the $-1$ entries and count the neighbours that differ,
`m = np.asarray(seq); m = m[m >= 0]; int(np.count_nonzero(m[1:] != m[:-1]))`. The check's
other cases, by hand: `[-1, -1]` is never matched, 0; `[2, 2, 2]` keeps its track, 0;
`[0, 1, 0, 1]` changes three times, 3 (going back to an earlier track is a switch too);
`[-1, 3, -1, 3]` finds the same track after each gap, 0; `[]` has nothing to count, 0.
`identity_switches` does this for every face, after matching the tracks to the faces by IoU,
and adds up the faces' counts.

=== 8.8 ★★ pen and paper | The mean-shift step from the density gradient
The weighted kernel density at $\mathbf y$ is $\hat f(\mathbf y) = C \sum_i w_i\, k(\lVert (\mathbf y - \mathbf x_i)/h\rVert^2)$
with a profile $k$ and $g = -k'$. Show that $\nabla \hat f(\mathbf y) = 0$ gives the fixed point
$\mathbf y = \sum_i \mathbf x_i w_i g_i / \sum_i w_i g_i$ with $g_i = g(\lVert (\mathbf y - \mathbf x_i)/h\rVert^2)$, so that
the mean-shift step $\hat{\mathbf y}_1 = \sum_i \mathbf x_i w_i g_i / \sum_i w_i g_i$ moves towards it. Then, by
hand, in one dimension: the Epanechnikov profile, written here on the squared distance
$s = \lVert (\mathbf y - \mathbf x_i)/h\rVert^2$ as $k(s) = 1 - s$ for $s \le 1$ (the chapter's
$k(r^2) = 1 - r^2$ with $s = r^2$), $h = 2$,
pixels at $x = 0, 1, 2$ with weights $w = 1, 2, 1$, start $\hat{\mathbf y}_0 = 1.5$. Where is
$\hat{\mathbf y}_1$?
--- solution
$\nabla \hat f(\mathbf y) = C \sum_i w_i\, k'(\cdot)\, 2(\mathbf y - \mathbf x_i)/h^2$
$= \frac{2C}{h^2} \sum_i w_i g_i (\mathbf x_i - \mathbf y)$
$= \frac{2C}{h^2}\left(\sum_i w_i g_i\right)
\left(\frac{\sum_i \mathbf x_i w_i g_i}{\sum_i w_i g_i} - \mathbf y\right)$. The last factor is the mean-shift
vector $\hat{\mathbf y}_1 - \mathbf y$: it points along the gradient, and it is zero exactly where the gradient
is. For the Epanechnikov profile $g = 1$ inside the kernel and 0 outside, so the step is the
weighted mean of the pixels inside. From $\hat{\mathbf y}_0 = 1.5$ the distances over $h$ are 0.75,
0.25 and 0.25, so $s < 1$ for all three pixels: $\hat{\mathbf y}_1 = (0 \cdot 1 + 1 \cdot 2 + 2 \cdot 1)/4 = 1$.

=== 8.9 ★★ pen and paper | Where the weights of step ② come from
A candidate at $\hat{\mathbf y}_0$ has the colour histogram $p(\hat{\mathbf y}_0)$, with $p_u(\hat{\mathbf y}_0) > 0$
in every bin, the model is $q$, and $\rho(\mathbf y) = \sum_u \sqrt{p_u(\mathbf y)\, q_u}$. (a) Expand each
term $\sqrt{p_u(\mathbf y)\, q_u}$ to first order in $p_u(\mathbf y)$ around $p_u(\hat{\mathbf y}_0)$ and show that
$\rho(\mathbf y) \approx \frac12 \sum_u \sqrt{p_u(\hat{\mathbf y}_0)\, q_u} +
\frac12 \sum_u p_u(\mathbf y) \sqrt{q_u / p_u(\hat{\mathbf y}_0)}$. (b) Insert the candidate's
kernel-weighted histogram $p_u(\mathbf y) = C \sum_i k(r_i^2)\, \delta[b(\mathbf x_i) - u]$ ($b(\mathbf x_i)$ the bin
of pixel $\mathbf x_i$, $r_i$ its normalised distance from $\mathbf y$) and show that the second term is
$\frac C2 \sum_i w_i\, k(r_i^2)$ with $w_i = \sum_u \sqrt{q_u / p_u(\hat{\mathbf y}_0)}\,
\delta[b(\mathbf x_i) - u]$, the weights of step ②. What does it mean for the climb that the first
term does not depend on $\mathbf y$? (c) Two bins, $q = (0.36, 0.64)$ and
$p(\hat{\mathbf y}_0) = (0.64, 0.36)$. Compute $\rho_0 = \rho(\hat{\mathbf y}_0)$ and the weight of a pixel of
each bin: which pixels pull the window? For a candidate $\mathbf y$ with $p(\mathbf y) = (0.5, 0.5)$,
compute the linearised $\rho$ of (a) and the true $\rho$. Why can the linearised value never
be below the true one?
--- solution
(a) $\frac{d}{dp}\sqrt{p\, q_u} = \frac12 \sqrt{q_u / p}$, so
$\sqrt{p_u(\mathbf y)\, q_u} \approx \sqrt{p_u(\hat{\mathbf y}_0)\, q_u} +
\frac12 \big(p_u(\mathbf y) - p_u(\hat{\mathbf y}_0)\big) \sqrt{q_u / p_u(\hat{\mathbf y}_0)}$. Summed over $u$, the
part with $-p_u(\hat{\mathbf y}_0)$ is $-\frac12 \sum_u p_u(\hat{\mathbf y}_0) \sqrt{q_u / p_u(\hat{\mathbf y}_0)}
= -\frac12 \sum_u \sqrt{p_u(\hat{\mathbf y}_0)\, q_u} = -\frac12 \rho_0$, which leaves
$\rho(\mathbf y) \approx \frac12 \rho_0 + \frac12 \sum_u p_u(\mathbf y) \sqrt{q_u / p_u(\hat{\mathbf y}_0)}$.

(b)

$$\begin{aligned}
&\frac12 \sum_u \sqrt{q_u / p_u(\hat{\mathbf y}_0)}\; C \sum_i k(r_i^2)\, \delta[b(\mathbf x_i) - u] \\
&\quad = \frac C2 \sum_i k(r_i^2) \sum_u \sqrt{q_u / p_u(\hat{\mathbf y}_0)}\, \delta[b(\mathbf x_i) - u] \\
&\quad = \frac C2 \sum_i w_i\, k(r_i^2) :
\end{aligned}$$

each pixel lies in exactly one bin, so the inner sum picks
that bin's $\sqrt{q_u / p_u(\hat{\mathbf y}_0)}$. The first term, $\rho_0 / 2$, is a constant, and so,
nearly, is the normalising constant $C$ (on the pixel lattice the sum of the kernel's
values hardly changes as the ellipse moves). Raising the linearised $\rho$ therefore means
raising the weighted kernel density $\sum_i w_i\, k(r_i^2)$ of the pixel positions (the chapter's
$\text{const} + \frac C2 \sum_i w_i\, k(\cdot)$), and that density is what the
mean-shift step climbs (exercise 8.8). Only $k(r_i^2)$ moves with $\mathbf y$; the weights are frozen
at $\hat{\mathbf y}_0$, which is why step ② computes them again at every iteration.

(c) $\rho_0 = \sqrt{0.64 \cdot 0.36} + \sqrt{0.36 \cdot 0.64} = 0.48 + 0.48 = 0.96$. A pixel
of bin 1 weighs $\sqrt{0.36 / 0.64} = 0.75$, a pixel of bin 2 weighs
$\sqrt{0.64 / 0.36} = 4/3 \approx 1.33$: the bin the candidate has too little of counts
more, and its pixels pull the window towards them. At $p(\mathbf y) = (0.5, 0.5)$ the linearised
$\rho$ is $0.48 + \frac12 (0.5 \cdot 0.75 + 0.5 \cdot \frac43) = 0.48 + \frac{25}{48}
\approx 1.001$ and the true one $\sqrt{0.18} + \sqrt{0.32} = 0.7 \sqrt 2 \approx 0.990$.
Both are above $\rho_0$ (the move is uphill), but the linearised value even exceeds 1,
which no Bhattacharyya coefficient can. $\rho$ is a sum of $\sqrt{q_u}\sqrt{p_u}$, a concave
function of $p$, and a concave function lies below each of its tangent planes: the
linearisation can only promise too much. That is why step ④ computes the true $\rho_1$ and
step ⑤ halves the step when $\rho$ fell.

=== 8.10 ★★ pen and paper | A climb by hand, and why it never goes down
As in exercise 8.8, $\hat f(\mathbf y) = C \sum_i w_i\, k(s_i)$ with
$s_i = ((\mathbf y - \mathbf x_i)/h)^2$ and the Epanechnikov profile $k(s) = 1 - s$ for $s \le 1$ and 0
beyond, so $g = -k'$ is 1 for $s_i < 1$ and 0 for $s_i > 1$, and the mean-shift step
$\mathbf y \mapsto \sum_i \mathbf x_i w_i g_i / \sum_i w_i g_i$ is the weighted mean of the pixels closer
than $h$ to $\mathbf y$ (no pixel falls exactly on the border in this exercise). Four pixels lie
at $x = 0, 2, 4, 7$ with weights $w = 3, 1, 1, 1$, and $h = 4$. (a) Start at
$\hat{\mathbf y}_0 = 9$ and iterate until the step is zero; list the iterates. (b) Compute
$\hat f / C$ at each iterate. (c) Show that a step from $\mathbf y$ to the weighted mean $\mathbf y'$ raises
the density by at least $\frac{C}{h^2} \big(\sum_i w_i g_i\big) (\mathbf y' - \mathbf y)^2$, using that $k$
is convex: $k(s') \ge k(s) - g(s)(s' - s)$. Check the bound on your steps. (d) Start again
at $\hat{\mathbf y}_0 = 1$. Where does the climb stop, and which of the two end points has the
higher density? What does this say about a tracker whose climb starts where the target was?
--- solution
(a) From 9 only the pixel at 7 is closer than 4: $\hat{\mathbf y}_1 = 7$. From 7 the pixels at 4
and 7 are inside (2 is 5 away): $\hat{\mathbf y}_2 = (4 + 7)/2 = 5.5$. From 5.5 the pixels at 2, 4
and 7 are inside (0 is 5.5 away): $\hat{\mathbf y}_3 = 13/3 \approx 4.33$. From $13/3$ the same three
pixels are inside (0 is 4.33 away), their mean is $13/3$ again, and the step is zero: the
climb stops at $13/3$.

(b) At 9: $1 - (2/4)^2 = 3/4$. At 7: $(1 - 9/16) + 1 = 23/16 \approx 1.44$. At 5.5:
$(1 - 12.25/16) + 2\,(1 - 2.25/16) = 125/64 \approx 1.95$. At $13/3$:
$(1 - 49/144) + (1 - 1/144) + (1 - 64/144) = 53/24 \approx 2.21$. It rises at every step.

(c) Convexity gives $k(s_i') - k(s_i) \ge g_i (s_i - s_i')$ for every pixel ($k$ is the
larger of the two straight lines $1 - s$ and 0). Multiply by $C w_i \ge 0$ (the weights here
are positive, and those of step ② are never negative), insert
$s_i - s_i' = [(\mathbf y - \mathbf x_i)^2 - (\mathbf y' - \mathbf x_i)^2]/h^2$ and sum over the pixels:

$$\begin{aligned}
\hat f(\mathbf y') - \hat f(\mathbf y) &\ge \frac{C}{h^2} \sum_i w_i g_i \big[(\mathbf y - \mathbf x_i)^2 - (\mathbf y' - \mathbf x_i)^2\big]
\\
&= \frac{C}{h^2} \sum_i w_i g_i\, (\mathbf y - \mathbf y')(\mathbf y + \mathbf y' - 2 \mathbf x_i) .
\end{aligned}$$

With $G = \sum_i w_i g_i$ and
$\sum_i w_i g_i \mathbf x_i = G \mathbf y'$ (the definition of $\mathbf y'$) the sum is
$(\mathbf y - \mathbf y')(G \mathbf y + G \mathbf y' - 2 G \mathbf y') = G (\mathbf y' - \mathbf y)^2$. $G > 0$ whenever the step is defined (its
denominator is $G$), so every step that moves raises $\hat f$. On the climb of (a), divided by
$C$: $9 \to 7$, bound $1 \cdot 4/16 = 0.25$, rise $11/16 \approx 0.69$; $7 \to 5.5$, bound
$2 \cdot 2.25/16 \approx 0.28$, rise $33/64 \approx 0.52$; $5.5 \to 13/3$, bound
$3 \cdot (7/6)^2/16 \approx 0.255$ and the rise is exactly that: no pixel enters or leaves
the kernel over this step (2, 4 and 7 stay inside, 0 outside), so $\hat f$ is one parabola
there and the inequality holds with equality for every pixel.

(d) From 1 the pixels at 0, 2 and 4 are inside (7 is 6 away):
$\hat{\mathbf y}_1 = (0 \cdot 3 + 2 + 4)/5 = 1.2$, and from 1.2 the same pixels give 1.2 again: the
climb stops there. $\hat f(1.2)/C = 3\,(1 - 1.44/16) + (1 - 0.64/16) + (1 - 7.84/16) = 4.2$,
nearly twice the $53/24 \approx 2.21$ at $13/3$. Each climb ends on top of the hill it
starts on; the one from 9 never sees the higher hill at 1.2. A mean-shift tracker starts
its climb where the target was in the last frame and ends on the top of the hill it starts on: the
target's if it is still the nearest peak, a distractor's if the target moved away or a
distractor's hill is closer. The nearest peak, not the best.
"""
