"""The exercises of 05_edge_rays: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "05_edge_rays"

TEXT = r"""
=== 5.1 ★ use | Eq. 5 and 6 by hand
The model's eight ray lengths are $M = (5, 9, 2, 7, 6, 3, 8, 4)$ and a particle's are
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
the target's survive. The narrower window is a sharper test, but it also zeroes particles that
sit on the target at a slightly wrong scale (the tracker's `ratio_low` / `ratio_high` params
over a few seeds show no clear gain on this clip).

=== 5.3 ★★ modify | A frame without edges
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
particle (each ray's length moved to the opposite direction) looks perfect to the sorted
reading.

=== 5.5 ★★★ implement | The Ratio of eq. 5
Implement eq. 5 yourself (`my_ratio(p, m)`: sort, mean of the 4th and 5th, divide) without
`trackbook`. The check uses exercise 5.1's rays (Ratio $6/5.5$), a ray set against itself
(1), a ray set twice as long (2) and reordered rays (the Ratio does not see the order).

=== 5.6 ★★★ project | Add scale to the edge-ray tracker
Run `edge-ray-pf` with `adapt_scale=True` on the sample clip and on one real sequence, compare
its AUC with the default over three seeds, and explain the result with what the Ratio
measures.
--- solution
`trackbook.evaluate("edge-ray-pf", clip, seed=s, adapt_scale=True)` for s = 0, 1, 2 against the
same call without the option. Expect no gain: the Ratio mixes size with edge density (section
"The median pair and the Ratio" of the case study of Kim et al. 2016), so the box drifts with
texture changes. The lab notes report the same on the seven sequences.

=== 5.7 ★ pen and paper | Condensation's contour likelihood
Condensation's likelihood with $\sigma = 3$ and the cap $\mu = 10$: hypothesis A has four
normals, three with the nearest edge at 1, 2 and 4 px and one with no edge within $\mu$;
hypothesis B has all four at 3 px. Compute both log-likelihoods (up to the common constant).
Which is more likely, and what would A's missing edge do without the cap $\mu$?
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
"""
