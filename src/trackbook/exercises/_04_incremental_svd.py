"""The exercises of 04_incremental_svd: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "04_incremental_svd"

TEXT = r"""
=== 4.1 ★ use | Forgetting is a weight on the columns
Fit an `IncrementalSVD(K=12, forgetting=0.8)` on the first 4 columns of a 12 × 9 matrix `A4`
(`np.random.default_rng(1).normal(size=(12, 9))`) with `fit`, then add the remaining 5
columns one at a time with `partial_fit`. Show that its singular values `S` equal those of
`A4` with column $j$ multiplied by $\xi^{\text{age}_j}$, and answer the vector of the 9 ages.
--- solution
Every `partial_fit` multiplies what is already learned by $\xi$ once: scaling $\Sigma$ by $\xi$
before adding a column scales every older column of $AV$ by $\xi$, so the SVD of $[\xi A, b]$ has
the singular values of $\xi\Sigma$ augmented by $b$, and so on recursively. The first 4 columns
saw 5 updates after the fit; column 4 saw 4, …, the last column 0: ages
$(5, 5, 5, 5, 4, 3, 2, 1, 0)$.

=== 4.2 ★ use | Which setting costs most? | after case_study_lee2012
Which of the paper preset's settings costs most on the day clip? Start from
`preset="paper"` and change one setting at a time: σ (both `sigma_color` and `sigma_hog`,
to 0.2), `feature_map` (to `"sqrt"`) or `init` (to `"box"`), and compare the AUC of seed 0 over the first 80
frames: `evaluate(trackers.create("color-hog-ipca", preset="paper", seed=0, **change), clip,
max_frames=80)`, with `change` the one setting changed (`{}` for the preset itself).
--- solution
σ, only just ahead of the start. Over the first 80 frames σ = 0.2 for both features lifts the
preset's AUC the most, the start around the box almost as much and the square-root feature
map least, so the preset's wide σ = 0.4 costs most. The mean IoU with the ground truth, frames
0–39 and 40–79, says where each setting acts:

| run | AUC | mean IoU, frames 0–39 | mean IoU, frames 40–79 |
|---|---|---|---|
| `preset="paper"` | 0.545 | 0.588 | 0.520 |
| σ = 0.2 | 0.692 | 0.796 | 0.612 |
| `feature_map="sqrt"` | 0.562 | 0.588 | 0.556 |
| `init="box"` | 0.685 | 0.795 | 0.593 |

In all four runs the failure layer judges the frames from 34, where the lights dim, to 59
lost, and a lost frame is not learned: the subspaces are complete only at frame 65, not at
frame $T$. σ acts on every frame: before the subspaces exist it sharpens the weights of the
colour and HOG likelihoods (eq. 10–11 of the {doc}`case study <case_study_lee2012>`), after,
those of the subspace. The start around the box also acts from the first frame, and both lift
the first 40 frames well above the preset. The feature map acts only once the subspaces exist:
its boxes up to that frame are exactly the preset's, and in the frames after it the square
root keeps more of the target than the raw histograms (exercise 4.3 explains why raw
histograms leave the weights nearly uniform).

A good answer adds that this is one seed and 80 frames, of which only the last 14 are weighed
by the subspaces, and that σ and the start are nearly tied. Over the whole clip (150 frames),
averaged over seeds 0–2, the order changes: the square root lifts the mean AUC most, σ = 0.2
less, and the start around the box hardly at all:

| run | mean AUC, whole clip, seeds 0–2 |
|---|---|
| `preset="paper"` | 0.399 |
| `feature_map="sqrt"` | 0.483 |
| σ = 0.2 | 0.458 |
| `init="box"` | 0.401 |

=== 4.3 ★★ modify | Raw or square-rooted histograms? | after 02_particle_filters
Run `color-hog-ipca` (seed 0) on the first 80 frames of `robot-corridor-day` with `anchor=0.0`
(once the subspaces are learned, the likelihood is their reconstruction error alone), once
with `feature_map="sqrt"` and once with `feature_map="raw"`. The subspaces are built from the
first $T = 40$ frames the tracker learns, and a frame judged lost is not learned, so they need
not exist by frame $T$: `result.extras["learning"]` turns 1 on the frame that completes them.
Compare the mean effective sample size over the frames after that one
(`start = np.flatnonzero(result.extras["learning"] == 1)[0] + 1`, then
`result.extras["ess"][start:]`; the effective sample size of the
{doc}`particle-filter chapter <02_particle_filters>`; 100 particles). Which feature map leaves
the weights nearly uniform? Answer `"sqrt"` or `"raw"`, and say why.
--- solution
`"raw"`. Raw histograms sum to 1 over hundreds of bins, so their Euclidean norm is far below
1 (0.1–0.4 on the sample clips' targets) and every particle's reconstruction error is at most
that norm: $\exp(-D^2 / 2\sigma^2)$ differs little between the particles and the weights are
nearly uniform (ESS close to $N$): the likelihood no longer tells the particles apart. The
square root has norm 1, and its errors spread over a range that σ can resolve.
On this clip the failure layer judges the frames from 34, where the lights dim, to 59 lost,
so the subspaces are complete only at frame 65; a mean from frame $T$ on would mix in frames
weighed before learning, the same in both runs.

=== 4.4 ★★ pen and paper | Twice the distance
With a single learned appearance $u = \sqrt{h_{ref}}$, show that
$\lVert z - uu^Tz\rVert^2 = 1 - \rho^2$ for any $z = \sqrt h$, with $\rho = u^Tz$. A tracker
scores a candidate by $\exp(-D^2/2\sigma^2)$, before frame $T$ with $D^2 = 1 - \rho$ and from
frame $T$ on, once it has learned $u$, with $D^2 = \lVert z - uu^Tz\rVert^2$. What σ after
frame $T$ gives the same scores as σ = 0.2 before it, for $\rho$ near 1? Then check the
identity on the target's colour histograms of frames 0 and 30 of `robot-corridor-day`
(`color_histograms` on the ground-truth boxes): compute
$\lVert z - uu^Tz\rVert^2 / (1 - \rho)$ and compare it with $1 + \rho$.
--- solution
$\lVert z \rVert = \lVert u \rVert = 1$ and $u^Tz = \sum_i \sqrt{h_i h_{ref,i}} = \rho$, so
$\lVert z - uu^Tz\rVert^2 = \lVert z\rVert^2 - (u^Tz)^2 = 1 - \rho^2 = (1-\rho)(1+\rho)
\approx 2(1 - \rho)$. To keep $\exp(-2(1-\rho)/2\sigma'^2) = \exp(-(1-\rho)/2\sigma^2)$ we need
$\sigma' = \sqrt2\,\sigma \approx 0.28$. The ratio of the two distances is $1 + \rho$, near 2
for similar histograms.

=== 4.5 ★★★ implement | One incremental step
Write `my_update(U, S, b)`: one step of the chapter's update with $m = 1$, no forgetting and
no truncation. Return `(U_new, S_new)`. By hand first: $U = e_1$ (3 × 1), $\Sigma = 2$ and
$b = 3e_2$ make $[U\Sigma,\ b]$ the matrix with columns $2e_1$ and $3e_2$, whose singular
values are 3 and 2 with the basis $e_2, e_1$. The check uses that case and a $b$ inside
span$(U)$, which adds a zero singular value.
--- solution
The residual $r = b - UU^Tb$ gives the new direction $\tilde b = r / \lVert r\rVert$; the
middle matrix $R$ is $\begin{bmatrix}\Sigma & U^Tb\\ 0 & \tilde b^Tb\end{bmatrix}$, and
$U' = [U\ \tilde b]\,\tilde U$ rotates $[U, \tilde b]$ by the left singular vectors of that
small matrix. In the hand case $U^Tb = 0$ and $\tilde b^Tb = 3$: the middle matrix is
diag(2, 3).

=== 4.6 ★★★ project | Learn with a different number of basis vectors and measure it | after case_study_lee2012
Lee et al. (2012) print no
$n_\mathrm{b}$ (their matrices have $n = 40$ columns {quote}`lee2012.window40`, but no number of basis
vectors is given). Run `color-hog-ipca` with $n_\mathrm{b}$ = 1, 2, 4, 8 and 16 on both sample clips, with the anchor
(the default) and without it (`anchor=0`). Report AUC and tracking rate; then repeat on a few
of the public sequences with three seeds (`trackbook.evaluate(name, folder, seed=s, K=k)`) and
say whether the differences exceed the seed-to-seed noise reported in the lab notes. A starting
point (sample clips, seed 0, with the anchor):
--- solution
A good answer has three parts: a table of AUC and tracking rate for every $n_\mathrm{b}$, with and
without the anchor, on both clips; a measure of the seed-to-seed noise of the same runs; and a
verdict for each comparison that weighs a difference against that noise.

The sample clips, seed 0. With the anchor every $n_\mathrm{b}$ tracks nearly the whole day
clip (tracking rate at least 0.97). The lowest and highest AUC over the five $n_\mathrm{b}$:

| clip | anchor | lowest AUC ($n_\mathrm{b}$) | highest AUC ($n_\mathrm{b}$) |
|---|---|---|---|
| day | 0.7 | 0.662 (16) | 0.731 (4) |
| night | 0.7 | 0.287 (4) | 0.345 (2) |
| day | 0 | 0.544 (1) | 0.729 (2) |
| night | 0 | 0.287 (4) | 0.561 (8) |

Without the anchor the runs swing further, on both clips.

The noise. Seeds 1 and 2 move one configuration as far as $n_\mathrm{b}$ does: at night with
the anchor and $n_\mathrm{b} = 4$ the AUC of seeds 0–2 ranges over 0.163, wider than the range
over all five $n_\mathrm{b}$ at seed 0 (0.058); without the anchor the same $n_\mathrm{b}$ at
night ranges over 0.240.

The public sequences. The committed runs of the {doc}`lab notes <lab_notes_lee2012>` (seven
sequences, seeds 0–2) hold two of these comparisons, paired by sequence and seed:

| comparison | mean AUC difference | 95 % interval |
|---|---|---|
| $n_\mathrm{b} = 4$ minus $n_\mathrm{b} = 2$, with the anchor | −0.026 | [−0.087, +0.011] |
| $n_\mathrm{b} = 16$ minus $n_\mathrm{b} = 2$, learning unchecked | −0.017 | [−0.083, +0.026] |

Both intervals straddle 0: inconclusive. One sequence's AUC moves by up to 0.44 between seeds
(Jogging1, with the library's default: anchor 0.7, $n_\mathrm{b} = 2$).

The verdict: no $n_\mathrm{b}$ from 1 to 16 is established better than another. The two comparisons
with a confidence interval are both inconclusive, and $n_\mathrm{b}$ = 1 and 8 were run on the sample
clips with one seed only, so nothing here shows a better $n_\mathrm{b}$ than the library's $n_\mathrm{b} = 2$, which
is also cheaper than the larger ones; nor does it show $n_\mathrm{b} = 2$ is the best. A good answer also says why more
basis vectors need not help. For one set of learned frames the first $n_\mathrm{b} + 1$ singular vectors
span the first $n_\mathrm{b}$ and one more, so a particle's reconstruction error can only fall as $n_\mathrm{b}$
grows: the background's as well as the target's, and the subspace term tells them apart less.
Fewer vectors forget more of how the target varied. Where the balance lies depends on the
clip, and the runs above cannot resolve it.

=== 4.7 ★ pen and paper | A reconstruction error by hand
Four-bin histograms, fed to the subspace as $z = \sqrt h$. The tracker has learned two
appearances, $u_1 = (0.8, 0.6, 0, 0)^T$ and $u_2 = (0, 0, 0.6, 0.8)^T$, and
$U = [u_1\ u_2]$. A candidate's histogram is $h = (0.25, 0.25, 0.25, 0.25)$.
(a) Check that $U$ has orthonormal columns. (b) Compute $U^Tz$, the reconstruction $UU^Tz$,
the residual $z - UU^Tz$ and $D^2 = \lVert z - UU^Tz\rVert^2$. (c) Show that
$D^2 = \lVert z\rVert^2 - \lVert U^Tz\rVert^2$ for any $z$ and any $U$ with orthonormal
columns, and use it to check (b). (d) What is $D^2$ with $n_\mathrm{b} = 1$ ($U = u_1$ alone)?
(e) Compare the two likelihood factors $\exp(-D^2/2\sigma^2)$ for $\sigma = 0.2$.
--- solution
(a) $u_1^Tu_1 = 0.64 + 0.36 = 1$, $u_2^Tu_2 = 0.36 + 0.64 = 1$, and $u_1^Tu_2 = 0$ (no bin is
non-zero in both).

(b) $z = \sqrt h = (0.5, 0.5, 0.5, 0.5)^T$, so $U^Tz = (0.5 \cdot 1.4,\ 0.5 \cdot 1.4)^T =
(0.7, 0.7)^T$ and

$$UU^Tz = 0.7\,u_1 + 0.7\,u_2 = (0.56, 0.42, 0.42, 0.56)^T,$$

$$z - UU^Tz = (-0.06, 0.08, 0.08, -0.06)^T,$$

$D^2 = 0.0036 + 0.0064 + 0.0064 + 0.0036 = 0.02$.

(c) $UU^T$ is an orthogonal projection ($U^TU = I$, so $(UU^T)^2 = UU^T$ and
$(UU^T)^T = UU^T$): the residual $z - UU^Tz$ is orthogonal to $UU^Tz$, and by Pythagoras
$\lVert z\rVert^2 = \lVert UU^Tz\rVert^2 + D^2$. Moreover
$\lVert UU^Tz\rVert^2 = z^TUU^TUU^Tz = z^TUU^Tz = \lVert U^Tz\rVert^2$. Here
$\lVert z\rVert^2 = 4 \cdot 0.25 = 1$ and $\lVert U^Tz\rVert^2 = 0.49 + 0.49 = 0.98$:
$D^2 = 0.02$, as in (b).

(d) With $u_1$ alone, $D^2 = 1 - 0.7^2 = 0.51$: half of this candidate's appearance lies in
the two bins that $u_1$ cannot explain. A second basis vector can only lower the error, never
raise it.

(e) $2\sigma^2 = 0.08$: $e^{-0.02/0.08} = e^{-0.25} \approx 0.78$ with $n_\mathrm{b} = 2$ and
$e^{-0.51/0.08} = e^{-6.375} \approx 0.0017$ with $n_\mathrm{b} = 1$. The same candidate is a good match
for the two-vector subspace and a poor one for the one-vector subspace.

=== 4.8 ★★ pen and paper | Why the small matrix is enough
(a) With $A = U\Sigma V^T$ (thin SVD, $V^TV = I$) and one new column $b$, show that
$[A\ b][A\ b]^T = [U\Sigma\ \ b][U\Sigma\ \ b]^T$, and conclude that $[A\ b]$ and
$[U\Sigma\ \ b]$ have the same non-zero singular values and their left singular vectors, so
$V$ is never needed; say what changes with the forgetting factor $\xi$. (b) Show that
$[U\Sigma\ \ b] = [U\ \tilde b]\,R$ with $\tilde b$ the normalised residual of $b$ and $R$ the
middle matrix of the update, and why the SVD of $R$ gives an SVD of $[U\Sigma\ \ b]$.
(c) By hand, in two dimensions: the tracker holds $U = (0.6, 0.8)^T$ and $\Sigma = 5$ and
forgets with $\xi = 0.8$; the new column is $b = (6.8, 2.4)^T$. Compute $U^Tb$, the residual,
$\tilde b$, $R$, $\Sigma'$ and $U'$. By how much does the first basis vector turn?
--- solution
(a)

$$\begin{aligned}
[A\ b][A\ b]^T &= AA^T + bb^T = U\Sigma V^TV\Sigma U^T + bb^T \\
&= U\Sigma^2U^T + bb^T = [U\Sigma\ \ b][U\Sigma\ \ b]^T .
\end{aligned}$$

The left singular vectors of a matrix $M$ are the
eigenvectors of $MM^T$ and its singular values the square roots of the eigenvalues, so two
matrices with the same $MM^T$ have the same of both (for the non-zero singular values; the
wider matrix $[A\ b]$ merely has more zero ones). $V$ has dropped out. With forgetting the
old columns enter as $\xi A$, whose SVD is $U(\xi\Sigma)V^T$: use $[\xi U\Sigma\ \ b]$.

(b) Split $b = UU^Tb + r$ with the residual $r = b - UU^Tb$ and $\tilde b = r / \lVert r\rVert$,
so $b = U(U^Tb) + \tilde b(\tilde b^Tb)$ with $\tilde b^Tb = \lVert r\rVert$. Then

$$[U\Sigma\ \ b] = [U\ \tilde b]\begin{bmatrix}\Sigma & U^Tb\\ 0 & \tilde b^Tb\end{bmatrix}
= [U\ \tilde b]\,R .$$

With $R = \tilde U\tilde\Sigma\tilde V^T$, $[U\Sigma\ \ b] = ([U\ \tilde b]\tilde U)\,
\tilde\Sigma\,\tilde V^T$. $[U\ \tilde b]$ has orthonormal columns ($\tilde b \perp U$) and
$\tilde U$ is orthogonal, so $U' = [U\ \tilde b]\tilde U$ has orthonormal columns: this is an
SVD, with $\Sigma' = \tilde\Sigma$.

(c) $\xi\Sigma = 4$. $U^Tb = 0.6 \cdot 6.8 + 0.8 \cdot 2.4 = 4.08 + 1.92 = 6$; the residual is
$b - 6U = (6.8 - 3.6,\ 2.4 - 4.8)^T = (3.2, -2.4)^T$ with norm 4, so
$\tilde b = (0.8, -0.6)^T$ and $\tilde b^Tb = 4$:

$$R = \begin{bmatrix} 4 & 6\\ 0 & 4\end{bmatrix}, \qquad
RR^T = \begin{bmatrix} 52 & 24\\ 24 & 16\end{bmatrix}.$$

The trace is 68 and the determinant $832 - 576 = 256$, so the eigenvalues solve
$\lambda^2 - 68\lambda + 256 = 0$: $\lambda = 64$ and 4, and $\Sigma' = (8, 2)$. The
eigenvectors of $RR^T$ are $(2, 1)^T/\sqrt5$ (for 64: $52 \cdot 2 + 24 = 128 = 64 \cdot 2$) and
$(1, -2)^T/\sqrt5$. Rotating:

$$u'_1 = \frac{2U + \tilde b}{\sqrt5} = \frac{(2, 1)^T}{\sqrt5}, \qquad
u'_2 = \frac{U - 2\tilde b}{\sqrt5} = \frac{(-1, 2)^T}{\sqrt5}$$

(each up to its sign). The first basis vector turns from $U$ towards $b$ by
$\arccos(U^Tu'_1) = \arccos(2/\sqrt5) \approx 26.6°$. Check: $\sigma_1'^2 + \sigma_2'^2 = 68 =
(\xi\Sigma)^2 + \lVert b\rVert^2 = 16 + 52$, the squared Frobenius norm, as it must be.
"""
