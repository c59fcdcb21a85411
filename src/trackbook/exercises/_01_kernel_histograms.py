"""The exercises of 01_kernel_histograms: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "01_kernel_histograms"

TEXT = r"""
=== 1.1 ★ use | Does the kernel help?
Resample the target's ground-truth box on frame 0 and on frame 25 of `robot-corridor-day` to
16 × 24 patches (`sample_patches(frame, box[None], (16, 24))`). Give each pixel its 8×8×4 HSV
bin (`hsv_bin_index`), and build the 256-bin histograms of both patches twice: once weighted
by the kernel $k(r) = 1 - r^2$ (`kernel_weights(24, 16)`), once with every weight 1. Give the
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
picks the one bin $u = c(x_i)$); then divide by `q.sum()`. Without a loop,
`np.bincount(labels.ravel(), weights=kernel.ravel(), minlength=n_bins)` is the same sum. For
the hand case the sums are $1$, $2 + 3$, $4$ and $0$, out of $10$. The exercises appendix runs
this solution through the check.
"""
