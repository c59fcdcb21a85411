"""The exercises of 00_introduction: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "00_introduction"

TEXT = r"""
=== 0.1 ★ use | IoU and centre error by hand
Two boxes, $(0, 0, 20, 10)$ and $(10, 0, 20, 10)$. Compute their IoU and
centre error by hand, then with `metrics.iou` and `metrics.center_error`.
--- solution
They overlap on a 10 × 10 square: IoU = 100 / (200 + 200 − 100) = 1/3. The centres (10, 5)
and (20, 5) are 10 px apart.

=== 0.2 ★ use | A box twice too large
A tracker returns a box of the right centre but twice the width and height of
the truth in every frame. What are its precision at 20 px, its tracking rate and its AUC?
--- solution
The IoU is $400 / 1600 = 0.25$ in every frame. The centres agree, so the precision at 20 px is
1; no frame has IoU > 0.5, so the tracking rate is 0; the IoU beats the thresholds
$t = 0, 0.05, \dots, 0.2$, 5 of the 21, so the AUC is $5/21 \approx 0.238$.

=== 0.3 ★★ modify | Scores over different frames
Run MIL on `two-faces` for its first 20 frames only
(`trackbook.evaluate(..., max_frames=20)`) and compare with the whole clip in the
introduction's table. Why should scores over different numbers of frames not be compared?
--- solution
On `two-faces` MIL's AUC over the first 20 frames is higher than over the whole clip (the
introduction prints both, in the cell below this exercise). A score is an average over the
frames scored. The first frames, close to the given box, are usually the easy ones, while drift
and occlusions come later; so scores over different frames answer different questions, which is
why a playground scores the whole clip, as the introduction's table does.

=== 0.4 ★★★ implement | IoU from scratch
Write `my_iou(a, b)` for two `(n, 4)` arrays of boxes $(x, y, w, h)$, returning the `n`
overlaps (intersection area over union area). The check runs it on pairs worked out by hand:
two boxes that overlap by half, disjoint, nested, touching along an edge and identical.
--- hint
The intersection is the rectangle from the larger of the two left (top) edges to the smaller
of the two right (bottom) edges; clip its width and height at 0.
--- solution
With `a` and `b` as float arrays, the intersection runs from
`x1 = np.maximum(a[:, 0], b[:, 0])` to `x2 = np.minimum(a[:, 0] + a[:, 2], b[:, 0] + b[:, 2])`,
and likewise in $y$; its area is `np.clip(x2 - x1, 0, None) * np.clip(y2 - y1, 0, None)`, zero
for disjoint boxes and for boxes that only touch along an edge. The union is the sum of the
two areas minus the intersection, and the IoU their ratio; for the boxes of exercise 0.1 it
gives $1/3$. The exercises appendix runs this solution through the check.

=== 0.5 ★★★ implement | The AUC from scratch
Write `my_auc(ious)`: the mean, over the 21 thresholds $t = 0, 0.05, \dots, 1$, of the
fraction of frames with IoU **>** $t$. The check uses cases worked by hand: IoU 0.25 in every
frame gives $5/21$ (exercise 0.2), IoU 1 gives $20/21$ (it does not beat $t = 1$).
--- solution
With `t = np.linspace(0, 1, 21)`, the fractions are
`(np.asarray(ious)[None, :] > t[:, None]).mean(axis=1)`, one per threshold, and the AUC is
their mean. Each frame adds to the count of every threshold its IoU beats, so the AUC is also
the mean over frames of (thresholds beaten) / 21; the introduction's four-frame example
gives its $8/21$ this way. The strict $>$ matters: a frame whose IoU equals a threshold does
not count at that threshold. The exercises appendix runs this solution through the check.
"""
