"""The exercises of 05_edge_rays: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "05_edge_rays"

TEXT = r"""
=== 5.1 ★ use | Eq. 5 and 6 by hand
The model's eight ray lengths are $M = (5, 9, 2, 7, 6, 3, 8, 4)$ and a candidate's are
$p = (6, 10, 2, 7, 6, 3, 9, 5)$. Work out by hand the Ratio of eq. 5 (pAvg / mAvg, each the
mean of the 4th and 5th sorted lengths) and the weight of eq. 6,
$w = 1 - \sum_j |p_j - m_j| / \sum_j m_j$ (zero when the Ratio is outside [0.8, 1.2]), then
check with `er.ratio` and `er.edge_weight`. Answer `(ratio, weight)`.
--- solution
Sorted $M$: 2, 3, 4, [5, 6], 7, 8, 9, so mAvg = 5.5; sorted $p$: 2, 3, 5, [6, 6], 7, 9, 10, so
pAvg = 6; Ratio = 6 / 5.5 ≈ 1.09, inside the window. $\sum_j |p_j - m_j| = 1 + 1 + 0 + 0 + 0 +
0 + 1 + 1 = 4$ and $\sum_j m_j = 44$: $w = 1 - 4/44 = 10/11 \approx 0.909$.

=== 5.2 ★ use | How selective is the Ratio test?
On frame 0 of `patterned-object`, take the model $M$ as the rays of the ground-truth box's
centre pixel (`maps = er.ray_distance_maps(er.edge_image(frame0))`, centre $c_0$ = box corner
+ half the size, `M = er.rays_at(maps, [np.floor(c0)])[0]`). Which fraction of all the frame's
pixels has a Ratio (`er.ratio`) inside the paper's window [0.8, 1.2]
({quote}`kim2016.ratio_window`), and which inside
[0.9, 1.1]? Answer `(fraction_08_12, fraction_09_11)`.
--- solution
The Ratio test alone rejects most of the pixels: only places whose median ray length matches
the target's survive. The narrower window is a sharper test, but it also zeroes candidates
that sit on the target at a slightly wrong scale (the tracker's `ratio_low` / `ratio_high`
params over a few seeds show no clear gain on this clip).

=== 5.3 ★★ modify | A frame without edges | after 02_particle_filters
Initialise `edge-ray-pf` (seed 0) on frame 0 of `patterned-object` with its ground-truth box,
then update it with a flat grey frame (`np.full_like(frame0, 128)`). What are the rays of the
centre pixel of the flat frame, and what `ok` does `update` return? Explain from the rays.
--- solution
Without edges every ray runs to the frame's border, far longer than the model's rays: every
particle's Ratio falls outside [0.8, 1.2], every weight is 0, and the tracker reports
`ok = False` and keeps its last estimate instead of raising or returning NaN.

=== 5.4 ★★ modify | The sorted reading
Eq. 6 compares rays direction by direction. Write the *sorted* reading (sort both ray
sets before differencing): which reading gives the higher weight to the model's own rays
turned by 180° (`np.roll(M, 4)`), and why?
--- solution
The sorted reading: the turned rays have the same sorted values, so the Ratio is 1 and the
sorted weight 1, the highest possible. Direction by direction they differ, so eq. 6 as the
book reads it scores them lower. With exercise 5.1's $M$ the turned rays are
$(6, 3, 8, 4, 5, 9, 2, 7)$, $\sum_j |p_j - m_j| = 1 + 6 + 6 + 3 + 1 + 6 + 6 + 3 = 32$ and
$w = 1 - 32/44 = 3/11 \approx 0.27$: a pattern of edges turned upside down about the
point (each ray's length moved to the opposite direction) looks perfect to the sorted
reading.

=== 5.5 ★★★ implement | The Ratio of eq. 5
Implement eq. 5 yourself (`my_ratio(p, m)`: sort, mean of the 4th and 5th, divide) without
`trackbook`. The check uses exercise 5.1's rays (Ratio $6/5.5$), a ray set against itself
(1), a ray set twice as long (2) and reordered rays (the Ratio does not see the order).
--- solution
Sort each ray set, take the mean of its two middle values, divide:

```python
def my_ratio(p, m):
    def mid(d):  # mean of the 4th and 5th of the 8 sorted lengths
        d = np.sort(np.asarray(d, float), axis=-1)
        return d[..., 3:5].mean(axis=-1)
    return mid(p) / mid(m)
```

NumPy counts from 0, so the 4th and 5th sorted values are at indices 3 and 4, the slice
`3:5`; `[2:4]` would take the 3rd and 4th, a common slip (on exercise 5.1's rays it gives
$5.5/4.5$ instead of $6/5.5$). Sorting along the last axis lets the same function take one
ray set of shape `(8,)` or `N` candidates' of shape `(N, 8)`. The check's cases follow from the
definition: exercise 5.1's rays give $6/5.5 \approx 1.09$ (worked there); a ray set against
itself gives 1; doubling every ray doubles both middle values, so the Ratio is 2; and sorting
forgets the directions, so reordered rays have the same middle pair and the same Ratio.

=== 5.6 ★★★ project | Add scale to the edge-ray tracker | after case_study_kim2016
Run `edge-ray-pf` with `adapt_scale=True` on the sample clip and on one real sequence, compare
its AUC with the default over three seeds, and explain the result with what the Ratio
measures.
--- solution
`trackbook.evaluate("edge-ray-pf", clip, seed=s, adapt_scale=True)` for s = 0, 1, 2 against the
same call without the option. Expect no gain: the Ratio mixes size with edge density (section
"The median pair and the Ratio" of the case study of Kim et al. 2016), so the box drifts with
texture changes. The lab notes report the same on the seven sequences.

=== 5.7 ★ pen and paper | Condensation's contour likelihood
Condensation's likelihood with $\sigma = 3$ and the cap $\nu_{\max} = 10$: hypothesis A has four
normals, three with the nearest edge at 1, 2 and 4 px and one with no edge within $\nu_{\max}$;
hypothesis B has all four at 3 px. Compute both log-likelihoods (up to the common constant).
Which is more likely, and what would A's missing edge do without the cap $\nu_{\max}$?
--- solution
A: $-(1 + 4 + 16 + 100)/18 = -121/18 \approx -6.72$; B: $-(4 \cdot 9)/18 = -2$. B is
$e^{85/18} \approx e^{4.7}$, about 110 times more likely: one missing edge costs A more than its three close
edges earn. Without the cap the missing edge has no finite distance, so A's likelihood would
be 0: one normal without an edge would veto the hypothesis.

=== 5.8 ★★★ implement | Eq. 6 from scratch
Write `my_weight(p, m, low=0.8, high=1.2)` for ray sets of shape `(N, 8)` and `(8,)`: 0 where
the Ratio of eq. 5 is outside `[low, high]`, otherwise $1 - \sum_j |p_j - m_j| / \sum_j m_j$
compared direction by direction and clipped at 0 (the book's reading of Kim et al. 2016). Use
only NumPy. The check uses exercise 5.1 ($10/11$), the model itself (1), rays 1.3 times as
long (Ratio 1.3: 0) and a set whose Ratio is 1 but whose differences exceed $\sum_j m_j$ (clipped: 0).
--- solution
The Ratio of eq. 5 is the gate, eq. 6 the score inside it:

```python
def my_weight(p, m, low=0.8, high=1.2):
    p, m = np.atleast_2d(np.asarray(p, float)), np.asarray(m, float)
    mid = lambda d: np.sort(d, axis=-1)[..., 3:5].mean(axis=-1)
    ratio = mid(p) / mid(m)                                   # eq. 5
    w = 1 - np.abs(p - m).sum(axis=-1) / m.sum()              # eq. 6
    inside = (ratio >= low) & (ratio <= high)
    return np.where(inside, np.clip(w, 0, None), 0.0)
```

Three points. The differences are taken direction by direction, `p - m` on the unsorted rays
(the sort is only for the Ratio). The sums run over the last axis, so one call weighs all $N$
candidates, and `np.atleast_2d` lets a single ray set through as one candidate. And both
cut-offs are needed: the window zeroes a candidate of the wrong typical size even when eq. 6
would be positive, and the clip at 0 zeroes a candidate inside the window whose differences
exceed the model's total length. The check's cases by hand: exercise 5.1 gives
$1 - 4/44 = 10/11$; the model against itself has no difference, weight 1; rays 1.3 times as
long have Ratio 1.3, outside the window, so weight 0 although eq. 6 would give
$1 - 0.3 = 0.7$; seven rays of 1 and one of 17 against eight rays of 1 have middle pair 1 and
Ratio 1, but $\sum_j |p_j - m_j| = 16$ against $\sum_j m_j = 8$, so eq. 6 gives
$1 - 2 = -1$, clipped to 0.

=== 5.9 ★ pen and paper | Where a ray stops
Edge detection in one dimension, as Canny's detector does it across an edge: along a ray, the
gradient is the central difference $g_k = (I_{k+1} - I_{k-1})/2$, and step $k$ is an edge
pixel where $|g_k| \ge 20$ and $|g_k|$ is not smaller than either neighbour's (non-maximum
suppression). From a candidate's pixel ($k = 0$) the brightness along its NE ray is

$$I = (50, 52, 51, 53, 120, 190, 192, 191, 190), \qquad k = 0, \dots, 8 .$$

(a) Compute $g_1, \dots, g_7$ and find the edge pixels. (b) What is this ray's length $d_j$,
with the chapter's conventions (a ray starts at the neighbouring pixel; $k$ steps along a
diagonal are $k\sqrt2$ pixels)? What would it be if the same profile lay along the E ray?
(c) Without non-maximum suppression the ray would stop at the first step with
$|g_k| \ge 20$: what length would it report, and how far off is that?
--- solution
(a) $g_1 = (51 - 50)/2 = 0.5$, $g_2 = (53 - 52)/2 = 0.5$, $g_3 = (120 - 51)/2 = 34.5$,
$g_4 = (190 - 53)/2 = 68.5$, $g_5 = (192 - 120)/2 = 36$, $g_6 = (191 - 190)/2 = 0.5$,
$g_7 = (190 - 192)/2 = -1$. Steps 3, 4 and 5 pass the threshold, but only step 4 is a local
maximum of $|g_k|$ ($68.5 \ge 34.5$ and $68.5 \ge 36$): one edge pixel, at $k = 4$, in the
middle of the ramp from 53 to 190.

(b) Four diagonal steps: $d_j = 4\sqrt2 \approx 5.66$ px. Along the E ray the same profile
gives $d_j = 4$ px.

(c) The ray would stop at $k = 3$: $3\sqrt2 \approx 4.24$ px, one diagonal step
($\sqrt2 \approx 1.41$ px) short. Without thinning a ray stops at the near side of a thick
edge, so two rays that meet the same edge from its two sides end at different pixels; thinned
to one pixel at the steepest point, the edge ends both where the brightness changes fastest.

=== 5.10 ★★ pen and paper | Sliding a contour along its normals
Condensation's likelihood, $\log p(z \mid x) = -\frac{1}{2\sigma^2}\sum_{m=1}^{M}
\min(\nu_m^2, \nu_{\max}^2) + \text{const}$, with $\sigma = 3$ and $\nu_{\max} = 10$. A box-shaped contour
has $M = 4$ points on its left and right sides, whose normals are horizontal; the hypothesis
$x$ is the box shifted sideways by $d$ pixels, which moves every point by $d$ along its normal.
Measured from the unshifted points, the nearest edge on each normal lies at the offsets
$e = (1, 2, -1, 2)$ px, and for every shift considered ($|d| \le 3$) it stays the nearest edge
and within $\nu_{\max}$, so $\nu_m = |e_m - d|$. (a) Write $\log p(z \mid x)$ as a function of $d$
and show that it is largest at the mean offset $\bar e$. (b) Show that $p(z \mid x)$, as a
function of $d$, is a Gaussian bell with variance $\sigma^2/M$: what are its centre and its
standard deviation? (c) Three candidates sit at $d = 0, 1, 2$: compute their weights, the
likelihoods normalised to sum 1. (d) If the third normal had no edge within $\nu_{\max}$ of
any of these shifts, where would the likelihood peak, and how wide would it be?
--- solution
(a) $\log p = -\frac{1}{18}\sum_m (e_m - d)^2 + \text{const}$. Writing
$e_m - d = (e_m - \bar e) + (\bar e - d)$ and using $\sum_m (e_m - \bar e) = 0$,

$$\sum_m (e_m - d)^2 = \sum_m (e_m - \bar e)^2 + M(d - \bar e)^2,$$

so the log-likelihood is largest at $d = \bar e = (1 + 2 - 1 + 2)/4 = 1$: the least-squares
fit of the shift to the edges. Here $\sum_m (e_m - \bar e)^2 = 0 + 1 + 4 + 1 = 6$ and
$\log p = -(6 + 4(d - 1)^2)/18 + \text{const}$.

(b) $p \propto \exp\bigl(-M(d - \bar e)^2/2\sigma^2\bigr) =
\exp\bigl(-(d - \bar e)^2/2(\sigma^2/M)\bigr)$: a Gaussian bell centred at $\bar e = 1$ px
with variance $\sigma^2/M = 9/4$, standard deviation 1.5 px. Four normals pin the shift down
twice as well as one ($\sigma/\sqrt M$).

(c) $\log p = -10/18$, $-6/18$, $-10/18$ (up to the constant) for $d = 0, 1, 2$. Dividing by
the largest, the weights are proportional to $e^{-4/18} \approx 0.801$, 1 and 0.801, and
normalised $0.801/2.601 \approx 0.308$, $1/2.601 \approx 0.384$ and 0.308. The weighted mean
of the three is $d = 1$ by symmetry.

(d) The third normal contributes $\min(\nu_3^2, \nu_{\max}^2) = \nu_{\max}^2 = 100$ for every $d$: a
constant factor $e^{-100/18}$ that lowers every hypothesis alike and drops out of the normalised
weights. The other three normals decide: the peak moves to their mean, $(1 + 2 + 2)/3 = 5/3
\approx 1.67$ px, and the variance grows to $\sigma^2/3 = 3$ (standard deviation
$\sqrt3 \approx 1.73$ px). The cap turns a missing edge into a loss of information, not a
veto.
"""
