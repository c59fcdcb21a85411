"""The exercises of 04_incremental_svd: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "04_incremental_svd"

TEXT = r"""
=== 4.1 ★ use | Forgetting is a weight on the columns
Fit an `IncrementalSVD(K=12, forgetting=0.8)` on the first 4 columns of a 12 × 9 matrix `A4`
(`np.random.default_rng(1).normal(size=(12, 9))`) with `fit`, then add the remaining 5
columns one at a time with `partial_fit`. Show that its singular values `S` equal those of
`A4` with column $j$ multiplied by $f^{\text{age}_j}$, and answer the vector of the 9 ages.
--- solution
Every `partial_fit` multiplies what is already learned by $f$ once: scaling $\Sigma$ by $f$
before adding a column scales every older column of $AV$ by $f$, so the SVD of $[fA, b]$ has
the singular values of $f\Sigma$ augmented by $b$, and so on recursively. The first 4 columns
saw 5 updates after the fit; column 4 saw 4, …, the last column 0: ages
$(5, 5, 5, 5, 4, 3, 2, 1, 0)$.

=== 4.2 ★ use | Which setting costs most?
Which of the paper preset's settings costs most on the day clip? Start from
`preset="paper"` and change one of `sigma_color`/`sigma_hog` (to 0.2), `feature_map` (to
`"sqrt"`) or `init` (to `"box"`) at a time.

=== 4.3 ★★ modify | Raw or square-rooted histograms?
Run `color-hog-ipca` (seed 0) on the first 80 frames of `robot-corridor-day` with `anchor=0.0`
(after the learning phase of $T = 40$ frames, the likelihood is the subspace's reconstruction
error alone), once with `feature_map="sqrt"` and once with `feature_map="raw"`. Compare the
mean effective sample size after frame $T$ (`result.extras["ess"][41:]`, the effective sample
size of the {doc}`particle-filter chapter <02_particle_filters>`; 100 particles). Which feature
map leaves the weights nearly uniform? Answer `"sqrt"` or `"raw"`, and say why.
--- solution
`"raw"`. Raw histograms sum to 1 over hundreds of bins, so their Euclidean norm is far below
1 (0.1–0.4 on the sample clips' targets) and every particle's reconstruction error is at most
that norm: $\exp(-D^2 / 2\sigma^2)$ differs little between the particles and the weights are
nearly uniform (ESS close to $N$): the likelihood no longer tells the particles apart. The
square root has norm 1, and its errors spread over a range that σ can resolve.

=== 4.4 ★★ pen and paper | Twice the distance
With a single learned appearance $u = \sqrt{h_{ref}}$, show that
$\lVert z - uu^Tz\rVert^2 = 1 - \rho^2$ for any $z = \sqrt h$, with $\rho = u^Tz$. What σ after
frame $T$ gives the same weights as σ = 0.2 before it, for $\rho$ near 1? Then check the
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
Write `my_update(U, S, b)`: one step of eq. 6–7 with $m = 1$, no forgetting and no truncation.
Return `(U_new, S_new)`. By hand first: $U = e_1$ (3 × 1), $\Sigma = 2$ and $b = 3e_2$ make
$[U\Sigma,\ b]$ the matrix with columns $2e_1$ and $3e_2$, whose singular values are 3 and 2
with the basis $e_2, e_1$. The check uses that case and a $b$ inside span$(U)$, which adds a
zero singular value.
--- solution
The residual $r = b - UU^Tb$ gives the new direction $\tilde b = r / \lVert r\rVert$; the
middle matrix of eq. 6 is $\begin{bmatrix}\Sigma & U^Tb\\ 0 & \tilde b^Tb\end{bmatrix}$, and
eq. 7 rotates $[U, \tilde b]$ by the left singular vectors of that small matrix. In the hand
case $U^Tb = 0$ and $\tilde b^Tb = 3$: the middle matrix is diag(2, 3).

=== 4.6 ★★★ project | Learn with a different K and measure it
Lee et al. (2012) print no
$K$ (their matrices have $n = 40$ columns {quote}`lee2012.window40`, but no number of basis
vectors is given). Run `color-hog-ipca` with $K$ = 1, 2, 4, 8 and 16 on both sample clips, with the anchor
(the default) and without it (`anchor=0`). Report AUC and tracking rate; then repeat on a few
of the public sequences with three seeds (`trackbook.evaluate(name, folder, seed=s, K=k)`) and
say whether the differences exceed the seed-to-seed noise reported in the lab notes. A starting
point (sample clips, seed 0, with the anchor):
"""
