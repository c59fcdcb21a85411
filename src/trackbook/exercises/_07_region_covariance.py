"""The exercises of 07_region_covariance: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "07_region_covariance"

TEXT = r"""
=== 7.1 ★ use | Förstner's distance by hand
Compute $d_\mathrm{F}(C_1, C_2) = \sqrt{\sum_i \ln^2 \lambda_i(C_1, C_2)}$ (eq. 5 of Lee 2015) for
$C_1 = \mathrm{diag}(1, 4)$ and $C_2 = \mathrm{diag}(4, 1)$, where $\lambda_i$ are the
generalised eigenvalues ($\det(\lambda C_1 - C_2) = 0$, eq. 6), then check it with
`forstner_distance`. Answer the number.
--- solution
$C_1^{-1} C_2 = \mathrm{diag}(4, 1/4)$: $\lambda = 4$ and $1/4$, $\ln^2\lambda = (\ln 4)^2$
twice, so $d_\mathrm{F} = \sqrt 2 \ln 4 \approx 1.96$.

=== 7.2 ★ use | Counting windows
How many 24 × 24 windows does a 320 × 240 frame hold at stride 1, and at stride 4 (windows
fully inside the frame, starting at the top-left corner)? Work it out by hand, then check with
`trackbook.trackers.covariance.n_windows`. Answer `(n_stride1, n_stride4)`.
--- solution
Stride 1: $(320 - 24 + 1)(240 - 24 + 1) = 297 \cdot 217 = 64\,449$. Stride 4:
$(\lfloor 296/4 \rfloor + 1)(\lfloor 216/4 \rfloor + 1) = 75 \cdot 55 = 4125$.

=== 7.3 ★★ modify | Brightness and contrast
Convert frame 0 of `red-cube` to grey floats
(`cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY).astype(float)`, no clipping at 255) and take the
covariance of the ground-truth box (`covariance_of_box(g, box)`, features
$x, y, I, |I_x|, |I_y|$). Give $d_\mathrm{F}$ (`forstner_distance(..., eps=0)`) between it and the same
box after a brightness shift $I \mapsto I + 40$, and after a contrast change
$I \mapsto 1.5\,I$. Answer `(d_shift, d_contrast)`. Why is one of them 0 and the other not,
although $d_\mathrm{F}$ is invariant to any congruence $C \mapsto A C A^T$? What happens with real uint8
frames, where bright pixels clip at 255?
--- hint
Which matrix $A$ turns $C$ into the contrast-changed covariance $A C A^T$? What does the
congruence invariance of $d_\mathrm{F}$ say, and what does it not say?
--- solution
The shift cancels in the covariance (eq. 4 subtracts the mean) and the gradients do not see
it: $d_\mathrm{F} = 0$. The contrast change multiplies $I, |I_x|, |I_y|$ by 1.5, i.e.
$C \mapsto ACA^T$ with $A = \mathrm{diag}(1, 1, 1.5, 1.5, 1.5)$. $d_\mathrm{F}$ is invariant when both
matrices get the same $A$ (two windows of the same changed frame keep their distance,
exercise 7.8), but $d_\mathrm{F}(C, ACA^T)$ is not 0: a model stored before the change does not match
the changed target exactly, because the $x, y$ rows did not scale while the others did. With
uint8 frames the pixels that clip at 255 do not move with the rest: the shift no longer
cancels (on this box $d_\mathrm{F}$ is about 0.3 instead of 0), and a contrast change is no longer a
congruence, so two windows of the changed frame no longer keep their distance.

=== 7.4 ★★ modify | Small q or large q? | after 06_kalman
Run the book's variant `kalman-covariance-manoeuvre` (from the
{doc}`case study <case_study_lee2015>`) on the first 146 frames of `red-cube`
(`evaluate(..., seed=0, q=..., max_frames=146)`) with `q=0.01` and with `q=100`; the cube
accelerates suddenly at frames 139–142. One of the two needs its second, larger search (the
manoeuvre window, `tracker.manoeuvre`, readable in an `on_frame` callback), and why? The other
never does, but pays in every frame: how many candidate windows does it evaluate per frame
(`result.extras["candidates"]`; its window is ±48 px at stride 1, so you can also work it out
by hand)? Answer `(q, first_frame, candidates)`.
--- solution
$q = 0.01$: a tiny window (±4 px, 81 candidates) and a confident velocity; the acceleration at
frame 139 leaves it, $d_\mathrm{F}$ jumps, and the manoeuvre window is searched. $q = 100$: a ±48 px
window in every frame, $(2 \cdot 48 + 1)^2 = 9409$ candidates, never a second search.

=== 7.5 ★★ modify | The manoeuvre window | after 06_kalman
Starting from the steady state (Q = R = I, a measurement every
frame), add σ_v² = 64 to the velocity block of $P^+$ and predict. What is the 3σ half-size
of the window now, and what are the position and velocity gains of the update? On
`yellow-ball`, at which frames does `kalman-covariance-manoeuvre` use the manoeuvre window
(`tracker.manoeuvre`, readable in an `on_frame` callback)? Compare with the frames where the
true ball turns from falling to rising. Answer `(half_size, k_position, k_velocity, frames)`.
--- hint
Iterate predict and update with $F$ of the constant-velocity model, $Q = I_4$, $R = I_2$ until
$P^+$ stops changing; then $P^- = F(P^+ + \sigma_v^2 D)F^T + Q$ with $D = \mathrm{diag}(0, 0, 1, 1)$,
$S = P^-_{xx} + 1$, and the gains are $P^-_{xx}/S$ and $P^-_{\dot x x}/S$.
--- solution
In the steady state $P^+$ has position variance 0.822, position-velocity covariance 0.422
and velocity variance 1.947 per axis (the window is then $3\sqrt{S} \approx 7.1$ px). With
64 added to the velocity variance, $P^-_{xx} = 0.822 + 2 \cdot 0.422 + 65.947 + 1 = 68.61$
and $P^-_{\dot x x} = 0.422 + 65.947 = 66.37$; $S = 69.61$, so the 3σ half-size is
$3\sqrt{69.61} \approx 25.0$ px, the position gain $68.61/69.61 \approx 0.986$ and the
velocity gain $66.37/69.61 \approx 0.953$: the update moves the velocity estimate almost all
the way to what the measurement implies. On `yellow-ball` the tracker uses the manoeuvre
window at frames 24, 66 and 105, once per bounce, one or two frames after the true ball turns
(23, 64 and 103). The second window is searched only when the best $d_\mathrm{F}$ of the ordinary
window exceeds three times its recent median; after the second and third turns the first
frame predicted into the ground stays just under that gate, and the jump comes a frame later.

=== 7.6 ★★★ implement | Eq. 4 from integral images
Write `cov_from_sums(F, box)`: for the rectangle `box = (x, y, w, h)` of a feature image `F`
(H × W × d), take the sums $\mathbf s = \sum_k \mathbf f_k$ and $V = \sum_k \mathbf f_k \mathbf f_k^T$ over the rectangle from
summed-area tables (four look-ups each) and return $\frac{1}{MN}\big(V - \mathbf s \mathbf s^T/MN\big)$, the
population covariance of eq. 4. By hand first: one feature with values 1, 2, 3, 4 over a
2 × 2 image has mean 2.5 and variance $(2.25 + 0.25 + 0.25 + 2.25)/4 = 1.25$. The check uses
that case and a box of two features, the second twice the first, whose covariance is
$\begin{bmatrix}v & 2v\\ 2v & 4v\end{bmatrix}$ ($v$ the first one's variance).
--- solution
Build one summed-area table of the $d$ features and one of their products $\mathbf f \mathbf f^T$ (pad a
zero row and column first), read $\mathbf s$ and $V$ with the four look-ups
$S[y+h, x+w] - S[y, x+w] - S[y+h, x] + S[y, x]$, and return $(V - \mathbf s \mathbf s^T/MN)/MN$ with
$MN = wh$. Centre the features first (subtract the image's mean): the covariance does not
change, and $V - \mathbf s \mathbf s^T/MN$ then does not lose precision to the subtraction of two large
numbers. The appendix's solution cell writes it out.

=== 7.7 ★★★ project | Add scale to the covariance tracker
Neither covariance tracker changes the size of its window; David and MotorRolling, the two
public sequences on which both score lowest (the {doc}`case study <case_study_lee2015>`),
are annotated with scale variation (among much else). Around each frame's best window,
evaluate the same centre at scales 0.9, 1.0 and 1.1 and keep the smallest $d_\mathrm{F}$. Beware: the
$x, y$ features are pixel coordinates, so a larger window has a larger $x$-variance even for
the same object — divide the $x, y$ rows and columns of $C$ by the scale (a congruence
$A C A^T$ with $A = \mathrm{diag}(1/s, 1/s, 1, 1, 1)$) before comparing. Measure the IoU with
and without the scale step on `red-cube` and `yellow-ball`, and say where it helps.
--- solution
A post-hoc step is enough for a first measurement: run `covariance` with an `on_frame`
callback that, around the tracker's centre, scores the three scaled windows against the
first frame's model (each candidate's covariance normalised with its $A$) and keeps the
best; carry the chosen size to the next frame. Measured on the sample clips, it helps on
neither: the targets there keep their size, and a free choice in every frame lets the size
drift (each choice starts from the last one). On `red-cube` the mean IoU falls from about
0.92 to below 0.6, on `yellow-ball` it stays close to its fixed-size value (about 0.83). A
useful version needs a prior that keeps the size (penalise changes, or accept a new scale
only when $d_\mathrm{F}$ improves clearly) and sequences that do change scale, such as David; the
chapter's hidden solution cell is the code.

=== 7.8 ★★ pen and paper | Why the Förstner distance ignores a common change of coordinates
Show that $d_\mathrm{F}(AC_1A^T, AC_2A^T) = d_\mathrm{F}(C_1, C_2)$ for every invertible $A$, from the
definition of the generalised eigenvalues (eq. 6). Then say why it does not follow that
$d_\mathrm{F}(C, ACA^T) = 0$, and compute $d_\mathrm{F}(C, ACA^T)$ by hand for $C = I_2$ and
$A = \mathrm{diag}(1, 2)$.
--- solution
$\det(\lambda AC_1A^T - AC_2A^T)$ $= \det(A)\det(\lambda C_1 - C_2)\det(A^T)$
$= \det(A)^2\det(\lambda C_1 - C_2)$, and $\det(A) \ne 0$: both matrix pairs have the same
generalised eigenvalues, hence the same $d_\mathrm{F}$. The invariance needs the same $A$ on both
sides; $d_\mathrm{F}(C, ACA^T)$ compares $C$ with a changed copy of itself. For $C = I_2$,
$ACA^T = \mathrm{diag}(1, 4)$: eigenvalues 1 and 4, $d_\mathrm{F} = \sqrt{0 + \ln^2 4} = \ln 4 \approx
1.39$.

=== 7.9 ★★ pen and paper | A window's covariance from four look-ups
A 3 × 3 grey image has rows $y = 0, 1, 2$ from the top and columns $x = 0, 1, 2$:

$$I = \begin{bmatrix} 1 & 2 & 0\\ 3 & 5 & 1\\ 2 & 4 & 6 \end{bmatrix}.$$

Each pixel has the $d = 2$ features $\mathbf f = (x, I)$. The zero-padded summed-area table of a
channel $g$ is the 4 × 4 array $S_g[r, c] = \sum_{y < r,\, x < c} g(x, y)$ (row 0 and
column 0 are zeros), and the sum of $g$ over the rectangle `box = (x, y, w, h)` is
$S_g[y+h, x+w] - S_g[y, x+w] - S_g[y+h, x] + S_g[y, x]$. (a) Write out $S_I$ and say why
the four look-ups give the rectangle's sum. (b) For the window $(1, 1, 2, 2)$, the
bottom-right 2 × 2 pixels, read $s_I = \sum I$ from $S_I$. (c) Read $s_x$, $V_{xx}$,
$V_{xI}$ and $V_{II}$ the same way from the tables of $x$, $x^2$, $xI$ and $I^2$ (only
their entries $[3, 3]$, $[1, 3]$, $[3, 1]$ and $[1, 1]$ are needed) and compute
$C_R = \frac{1}{MN}\big(V - \frac{1}{MN}\mathbf s \mathbf s^T\big)$. (d) Check $C_R$ against eq. 4 on the
four pixels directly. How many tables do the five features $x, y, I, |I_x|, |I_y|$ need,
and how many look-ups does one window cost?
--- solution
(a) Cumulative sums down the columns and along the rows, with a zero row and column in
front:

$$S_I = \begin{bmatrix} 0 & 0 & 0 & 0\\ 0 & 1 & 3 & 3\\ 0 & 4 & 11 & 12\\
0 & 6 & 17 & 24 \end{bmatrix}.$$

$S[y+h, x+w]$ sums everything above and to the left of the rectangle's far corner.
Subtracting $S[y, x+w]$ (the strip above the rectangle) and $S[y+h, x]$ (the strip to its
left) removes the block above and to the left twice, and $+S[y, x]$ adds it back once
(inclusion–exclusion): what is left is the rectangle.

(b) $s_I = S_I[3, 3] - S_I[1, 3] - S_I[3, 1] + S_I[1, 1] = 24 - 3 - 6 + 1 = 16$, and indeed
$5 + 1 + 4 + 6 = 16$.

(c) The four entries $[3, 3], [1, 3], [3, 1], [1, 1]$ of each table: $x$: 9, 3, 0, 0, so
$s_x = 6$; $x^2$: 15, 5, 0, 0, so $V_{xx} = 10$; $xI$: 25, 2, 0, 0, so $V_{xI} = 23$;
$I^2$: 96, 5, 14, 1, so $V_{II} = 78$. With $MN = 4$ and $\mathbf s = (6, 16)$,

$$V - \tfrac14 \mathbf s \mathbf s^T = \begin{bmatrix} 10 - 9 & 23 - 24\\ 23 - 24 & 78 - 64 \end{bmatrix}
= \begin{bmatrix} 1 & -1\\ -1 & 14 \end{bmatrix},$$

$$C_R = \begin{bmatrix} 0.25 & -0.25\\ -0.25 & 3.5 \end{bmatrix}.$$

(d) The four pixels are $(x, I) = (1, 5), (2, 1), (1, 4), (2, 6)$ with mean $(1.5, 4)$; the
deviations are $x$: $-0.5, 0.5, -0.5, 0.5$ and $I$: $1, -3, 0, 2$. Eq. 4 gives the
$x$-variance $4 \cdot 0.25/4 = 0.25$, the $I$-variance $(1 + 9 + 0 + 4)/4 = 3.5$ and the
covariance $(-0.5 - 1.5 + 0 + 1)/4 = -0.25$: the same matrix. The negative entry says
"darker to the right" (the left column averages 4.5, the right one 3.5). Five features need
5 tables of the features and $5 \cdot 6/2 = 15$ of their products, 20 in all, and a window
costs $4 \cdot 20 = 80$ look-ups, whatever its size.

=== 7.10 ★★ pen and paper | Symmetric, and zero only for equal matrices
Let $C_i$ and $C_j$ be symmetric positive definite $d \times d$ matrices and $\lambda_k$ the
generalised eigenvalues of eq. 6, $\lambda_k C_i x_k = C_j x_k$; eq. 5 is
$d_\mathrm{F}(C_i, C_j) = \sqrt{\sum_k \ln^2 \lambda_k}$. (a) Show that the $\lambda_k$ are the
eigenvalues of the whitened matrix $\tilde C = C_i^{-1/2} C_j C_i^{-1/2}$, and hence real
and positive, so that the logarithms exist. (b) Show that $d_\mathrm{F}(C_j, C_i) = d_\mathrm{F}(C_i, C_j)$.
(c) Show that $d_\mathrm{F}(C_i, C_j) = 0$ only when $C_i = C_j$. (d) By hand: $d_\mathrm{F}(I_2, C)$ for
$C = \begin{bmatrix} 2 & 1\\ 1 & 2 \end{bmatrix}$, and $d_\mathrm{F}(C, sC)$ for any symmetric
positive definite $C$ of size $d$ and any $s > 0$; give the number for $d = 5$, $s = 2$.
--- solution
(a) $C_i = Q_i \Lambda_i Q_i^T$ with $Q_i$ orthogonal and the eigenvalues in $\Lambda_i$
positive, so $C_i^{-1/2} = Q_i \Lambda_i^{-1/2} Q_i^T$ exists, is symmetric and invertible.
Write $x_k = C_i^{-1/2} z_k$ ($z_k \ne 0$ exactly when $x_k \ne 0$) and multiply eq. 6 on the
left by $C_i^{-1/2}$: $\lambda_k z_k = C_i^{-1/2} C_j C_i^{-1/2} z_k = \tilde C z_k$. The steps
run backwards too, so the generalised eigenvalues are exactly the eigenvalues of
$\tilde C$. $\tilde C$ is symmetric, so its eigenvalues are real, and
$z^T \tilde C z = (C_i^{-1/2} z)^T C_j (C_i^{-1/2} z) > 0$ for every $z \ne 0$; for an
eigenvector this reads $\lambda_k \lVert z_k \rVert^2 > 0$, so they are positive. (This
whitening is how `forstner_distance` computes them.)

(b) $\lambda C_i x = C_j x$ is the same equation as $\frac1\lambda C_j x = C_i x$:
swapping the two matrices turns every $\lambda_k$ into $1/\lambda_k$, with the same
eigenvector $x_k$. The $d$ vectors $x_k = C_i^{-1/2} z_k$, with $z_k$ the orthonormal
eigenvectors of $\tilde C$, are linearly independent, so the $1/\lambda_k$ are all $d$
eigenvalues of the swapped pair. $\ln^2(1/\lambda_k) = (-\ln \lambda_k)^2 = \ln^2 \lambda_k$:
the sum of eq. 5 does not change.

(c) $d_\mathrm{F} = 0$ forces every $\ln \lambda_k = 0$, that is every $\lambda_k = 1$. The symmetric
$\tilde C$ is $Q \Lambda Q^T$ with $Q$ orthogonal and $\Lambda$ the diagonal of its
eigenvalues; $\Lambda = I$ gives $\tilde C = QQ^T = I$, and then
$C_j = C_i^{1/2} \tilde C C_i^{1/2} = C_i$. Conversely $C_i = C_j$ gives $\tilde C = I$, all
$\lambda_k = 1$ and $d_\mathrm{F} = 0$.

(d) With $C_i = I_2$, $\tilde C = C$: $\det(\lambda I - C) = (\lambda - 2)^2 - 1 = 0$ gives
$\lambda = 1$ and $\lambda = 3$, so $d_\mathrm{F} = \sqrt{0 + \ln^2 3} = \ln 3 \approx 1.10$. For
$sC$: $\lambda C x = s C x$ gives $\lambda = s$, $d$ times, so
$d_\mathrm{F}(C, sC) = \sqrt{d}\,|\ln s|$ whatever $C$ is; for $d = 5$, $s = 2$ that is
$\sqrt 5 \ln 2 \approx 1.55$, and $d_\mathrm{F}(C, C/2)$ is the same. The Frobenius distance
$\lVert C - sC \rVert_\mathrm{F} = |1 - s|\,\lVert C \rVert_\mathrm{F}$ instead grows with the size of $C$'s
entries.
"""
