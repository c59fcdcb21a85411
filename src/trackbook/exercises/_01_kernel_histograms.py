"""The exercises of 01_kernel_histograms: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "01_kernel_histograms"

TEXT = r"""
=== 1.1 ★ use | Does the kernel help?
Resample the target's ground-truth box on frame 0 and on frame 25 of `robot-corridor-day` to
16 × 24 patches (`sample_patches(frame, box[None], (16, 24))`). Give each pixel its 8×8×4 HSV
bin (`hsv_bin_index`), and build the 256-bin histograms of both patches twice: once weighted
by the kernel $k(r^2) = 1 - r^2$ (`kernel_weights(24, 16)`), once with every weight 1. Give the
Bhattacharyya coefficient ρ between frame 0 and frame 25 for both, as
`(rho_kernel, rho_flat)`. Which of the two matches better, and why?
--- solution
$\rho \approx 0.936$ with the kernel and $0.928$ without: the kernel version matches better,
though only slightly, since most of the box is the person in both frames. The kernel gives the
border pixels, where background leaks into the box, little weight; the background behind the
person changes between the two frames, so the border pixels are the ones that change, and the
flat histogram counts them in full.

=== 1.2 ★ use | ρ by hand, and ρ ≤ 1
Compute by hand the Bhattacharyya coefficient $\rho(p, q) = \sum_u \sqrt{p_u q_u}$ of
$p = (0.5, 0.5, 0, 0)$ and $q = (0.25, 0.25, 0.25, 0.25)$, and $\rho(q, q)$. Answer
`(rho_pq, rho_qq)`. Then show numerically that $\rho \le 1$ for 1000 random pairs of 50-bin
histograms (`np.random.default_rng(0).dirichlet(np.ones(50), 1000)`), with equality only when
$p = q$. Which inequality proves it?
--- solution
$\rho(p, q) = \sqrt{0.5 \cdot 0.25} + \sqrt{0.5 \cdot 0.25} = 2\sqrt{1/8} = 1/\sqrt 2$ and
$\rho(q, q) = \sum_u q_u = 1$. The Cauchy–Schwarz inequality proves $\rho \le 1$
(exercise 1.6 works it out).

=== 1.3 ★ use | How many bins does the target use?
Count the non-empty bins of the target's kernel histogram on frame 0
(`color_histograms(frame, box[None], bins=...)`) with the book's 8×8×4 = 256 bins and with
16×16×8 = 2048 bins. Answer `(n_256, n_2048)`. What does the count mean for ρ between two
frames?
--- solution
The target fills 28 bins with the book's bins and 69 with the finer ones: its pixels spread
over more than twice as many bins, nearly half of them holding only one or two pixels. Small
shifts of colour then move mass to neighbouring bins, and ρ between the frame-0 and frame-25
targets falls (the cell below the exercise prints it for both) although it is the same person.
Fewer bins are coarser but more stable.

=== 1.4 ★★ modify | The cone kernel
Build the cone kernel $k = 1 - r$ of the case study's reading of Lee et al.'s prose (same $r$
as `kernel_weights`) and compare ρ between the frame-0 and frame-25 targets under the cone,
under $1 - r^2$ and with no kernel. Which is largest, and why is the order what it is?
--- solution
The cone gives the largest ρ, then $1 - r^2$, then the flat kernel (the cell below the exercise
prints the three; they lie within 0.02 of each other). Relative to the centre, the cone weighs
the border least of the three ($1 - r \le 1 - r^2$ for $0 \le r \le 1$) and the flat kernel not
at all less: the less the border (where the background changes) counts, the more alike the two
targets look.

=== 1.5 ★★★ implement | The kernel from scratch
Write `my_kernel(height, width)` returning the $k = 1 - r^2$ weights of a `height × width`
patch, with $r$ the distance of each pixel *centre* (pixel $(i, j)$ has centre
$(i + 0.5, j + 0.5)$) to the patch centre, divided by the largest such distance. By hand
first: a 1 × 3 patch has distances 1, 0, 1, so $k = (0, 1, 0)$. The check uses that case, a
3 × 3 patch worked by hand and the definition pixel by pixel on larger patches.
--- solution
For 3 × 3 the corners are $\sqrt 2$ from the centre, the edges 1: $k$ is 0 at the corners,
$1 - 1/2$ on the edges and 1 in the middle.

=== 1.6 ★ pen and paper | ρ as a cosine
Write ρ(p, q) as a dot product of two unit vectors, and use the
Cauchy–Schwarz inequality to show $\rho \le 1$, with equality only for $p = q$. Then compute
by hand ρ, $D = \sqrt{1 - \rho}$ and $-\ln \rho$ for $p = (\tfrac12, \tfrac12, 0)$ and
$q = (\tfrac14, \tfrac14, \tfrac12)$.
--- solution
$\rho = \sum_u \sqrt{p_u}\sqrt{q_u} = \sqrt p \cdot \sqrt q$, and
$\|\sqrt p\|^2 = \sum_u p_u = 1$, likewise for $q$: ρ is the cosine of the angle between
$\sqrt p$ and $\sqrt q$. Cauchy–Schwarz gives $\sqrt p \cdot \sqrt q \le \|\sqrt p\|\,
\|\sqrt q\| = 1$, with equality only when $\sqrt p$ and $\sqrt q$ are parallel; two unit
vectors with non-negative entries are parallel only when they are equal, so $p = q$. For the
pair: $\rho = 2\sqrt{\tfrac12 \cdot \tfrac14} = 2/\sqrt 8 = 1/\sqrt 2 \approx 0.707$ (the
third bin contributes $\sqrt{0 \cdot \tfrac12} = 0$), $D = \sqrt{1 - 0.707} \approx 0.541$ and
$-\ln \rho = \tfrac12 \ln 2 \approx 0.347$.

=== 1.7 ★★★ implement | A kernel histogram from scratch
Write `my_histogram(labels, kernel, n_bins)` that takes one patch of bin labels (an
`h × w` integer array), the `h × w` kernel weights and the number of bins, and returns the
kernel-weighted histogram normalised to sum 1 (eq. 1 of Lee et al. 2012) — with a loop over
the pixels if you like. By hand first: labels $\begin{smallmatrix}0 & 1\\ 1 & 2\end{smallmatrix}$
weighted $\begin{smallmatrix}1 & 2\\ 3 & 4\end{smallmatrix}$ give, over 4 bins,
$(1, 2 + 3, 4, 0) / 10$. The check uses that case and a one-pixel patch.
--- solution
Start from `q = np.zeros(n_bins)`; for each pixel add its kernel weight to the bin of its
label, `q[u] += k` over the pairs of `labels.ravel()` and `kernel.ravel()` (the δ of eq. 1
picks the one bin $u = b(x_i)$); then divide by `q.sum()`. Without a loop,
`np.bincount(labels.ravel(), weights=kernel.ravel(), minlength=n_bins)` is the same sum. For
the hand case the sums are $1$, $2 + 3$, $4$ and $0$, out of $10$. The exercises appendix runs
this solution through the check.

=== 1.8 ★ pen and paper | The constant C, and a two-colour patch by hand
In the kernel histogram
$\hat q_u = C \sum_{i=1}^n k(\|x_i^*\|^2)\, \delta[b(x_i^*) - u]$, show that
$C = 1 / \sum_{i=1}^n k(\|x_i^*\|^2)$ makes the $\hat q_u$ sum to 1, and that $C$ depends on
the kernel and the size of the patch but not on its colours. Then take a 3 × 3 patch with the
weights $k = 1 - r^2$ of the chapter ($r$ the distance to the centre pixel divided by the
largest such distance): 0 at the four corners, $\tfrac12$ on the four edges, 1 in the middle.
A red target two pixels wide stands on a blue background. The box sees red in its left two
columns and blue in its right one (patch A); then it slides one pixel to the right and sees
red in its left column only (patch B). Give $C$, and the two-bin (red, blue) histograms of A
and B with the kernel and with every weight 1. Compute $\rho(A, B)$ both ways: which falls
further when the box slides, and why?
--- solution
Swap the two sums:
$\sum_u \hat q_u = C \sum_{i=1}^n k(\|x_i^*\|^2) \sum_u \delta[b(x_i^*) - u]$, and the inner
sum is 1 because every pixel has exactly one bin. So $\sum_u \hat q_u = C \sum_i
k(\|x_i^*\|^2)$, which is 1 exactly when $C = 1 / \sum_i k(\|x_i^*\|^2)$. The colours enter
only through $b$, which has dropped out: $C$ is fixed by the kernel and the patch size (for
the 16 × 24 patches of the chapter it is one number for every box).

For the 3 × 3 patch, $\sum_i k = 4 \cdot 0 + 4 \cdot \tfrac12 + 1 = 3$, so $C = \tfrac13$.
Patch A: the red pixels are the left column ($0 + \tfrac12 + 0$) and the middle column
($\tfrac12 + 1 + \tfrac12$), together $\tfrac52$; the blue right column has
$0 + \tfrac12 + 0 = \tfrac12$. So $\hat q(A) = (\tfrac56, \tfrac16)$; with every weight 1,
6 of the 9 pixels are red: $(\tfrac23, \tfrac13)$. Patch B is A mirrored with the colours
swapped: $\hat q(B) = (\tfrac16, \tfrac56)$ with the kernel, $(\tfrac13, \tfrac23)$ without.

With the kernel
$\rho(A, B) = \sqrt{\tfrac56 \cdot \tfrac16} + \sqrt{\tfrac16 \cdot \tfrac56}
= \tfrac{2\sqrt 5}{6} = \tfrac{\sqrt 5}{3} \approx 0.745$; without it
$\rho(A, B) = 2\sqrt{\tfrac23 \cdot \tfrac13} = \tfrac{2\sqrt 2}{3} \approx 0.943$. The
kernel version falls further: the middle column, which turned from red to blue, carries
$\tfrac12 + 1 + \tfrac12 = 2$ of the kernel's total weight 3, but only a third of the pixels.
Weighing the centre most makes ρ fall faster as the box leaves the target, a sharper peak
for a tracker to find.

=== 1.9 ★★ pen and paper | Which distance is a metric?
Show that $0 \le \rho(p, q) \le 1$ for any two histograms (you may use $\rho \le 1$ from
exercise 1.6), with $\rho = 0$ exactly when no bin holds mass in both, and give the ranges of
$D = \sqrt{1 - \rho}$ and of $-\ln \rho$. Show that
$D^2 = \tfrac12 \sum_u (\sqrt{p_u} - \sqrt{q_u})^2$ and conclude that $D$ satisfies the
triangle inequality $D(p, r) \le D(p, q) + D(q, r)$. Show that $-\ln \rho \ge D^2$. Finally,
for $p = (0.9, 0.1)$, $q = (0.5, 0.5)$ and $r = (0.1, 0.9)$, compute ρ, $D$ and $-\ln \rho$
of the three pairs, and check the triangle inequality for both distances.
--- hint
$\ln x \le x - 1$ for every $x > 0$. For the numbers, $\sqrt{0.45} = 3\sqrt{0.05}$.
--- solution
Every term $\sqrt{p_u q_u}$ is $\ge 0$, so $\rho \ge 0$, and $\rho = 0$ only when every
product $p_u q_u$ is 0: no bin is non-empty in both. With $\rho \le 1$ (equality only for
$p = q$): $D \in [0, 1]$, 0 only for $p = q$ and 1 only for histograms with no bin in common;
$-\ln \rho \in [0, \infty]$, infinite for histograms with no bin in common.

Expanding the square, and using $\sum_u p_u = \sum_u q_u = 1$:

$$\tfrac12 \sum_u (\sqrt{p_u} - \sqrt{q_u})^2
= \tfrac12 \Bigl(\sum_u p_u + \sum_u q_u - 2 \sum_u \sqrt{p_u q_u}\Bigr)
= 1 - \rho = D^2 .$$

So $D(p, q) = \|\sqrt p - \sqrt q\| / \sqrt 2$: a fixed multiple of the Euclidean distance
between the vectors $\sqrt p$ and $\sqrt q$, which satisfies the triangle inequality, and so
does $D$. With $D \ge 0$, $D = 0$ only for $p = q$, and $D(p, q) = D(q, p)$, $D$ is a metric
(the Hellinger distance). From $\ln x \le x - 1$ with $x = \rho$:
$-\ln \rho \ge 1 - \rho = D^2$, with equality only at $\rho = 1$.

The numbers: $\rho(p, q) = \sqrt{0.45} + \sqrt{0.05} = 4\sqrt{0.05} = 2/\sqrt 5 \approx
0.894$, and $\rho(q, r)$ is the same by symmetry; $\rho(p, r) = 2\sqrt{0.09} = 0.6$. Then
$D(p, q) = D(q, r) = \sqrt{1 - 0.894} \approx 0.325$ and $D(p, r) = \sqrt{0.4} \approx 0.632
\le 0.325 + 0.325 = 0.650$: the triangle inequality holds. But
$-\ln \rho(p, q) = -\ln \rho(q, r) = \tfrac12 \ln \tfrac54 \approx 0.112$, while
$-\ln \rho(p, r) = \ln \tfrac53 \approx 0.511 > 2 \cdot \tfrac12 \ln \tfrac54 \approx 0.223$:
$-\ln \rho$ breaks the triangle inequality, by more than a factor 2 here. Both still order
the pairs the same way, and $-\ln \rho \ge D^2$ holds in each ($0.112 \ge 0.106$,
$0.511 \ge 0.4$).
"""
