"""The exercises of 16_several_targets: their text, defined once (see :mod:`trackbook.exercises`),
and the auto-check of the ★★★ one."""

import numpy as np

STEM = "16_several_targets"

TEXT = r"""
=== 16.1 ★ pen and paper | MOTA from a count table
A tracker is scored on five frames. Per frame, the number of ground-truth targets
$\mathrm{GT}_t$, misses $\mathrm{FN}_t$, false positives $\mathrm{FP}_t$ and identity switches
$\mathrm{IDSW}_t$ are

| frame | 1 | 2 | 3 | 4 | 5 |
|---|---:|---:|---:|---:|---:|
| $\mathrm{GT}_t$ | 3 | 3 | 3 | 2 | 2 |
| $\mathrm{FN}_t$ | 0 | 1 | 0 | 0 | 1 |
| $\mathrm{FP}_t$ | 1 | 0 | 0 | 2 | 0 |
| $\mathrm{IDSW}_t$ | 0 | 0 | 1 | 0 | 0 |

Compute MOTA. How many false positives in frame 4 would make MOTA zero, the other counts
unchanged? Can MOTA be negative?
--- solution
$\sum_t \mathrm{GT}_t = 13$ and the errors add up to $\mathrm{FN} + \mathrm{FP} + \mathrm{IDSW}
= 2 + 3 + 1 = 6$, so $\mathrm{MOTA} = 1 - 6/13 = 7/13 \approx 0.538$. MOTA is zero when the
errors reach 13: seven more false positives, nine in frame 4 instead of two. Nothing bounds
the false positives, so yes: a tracker that reports more wrong boxes than there are targets
scores below zero (MOTA lies in $(-\infty, 1]$).

=== 16.2 ★ pen and paper | IDF1 from an identity assignment
A run has two targets, 1 and 2, with 10 boxes each ($n_\text{gt} = 20$), and three hypotheses a, b, c
with 8, 7 and 3 boxes ($n_\text{hyp} = 18$). The number of frames in which target $i$ and hypothesis $j$
overlap with IoU ≥ 0.5 is

| | a | b | c |
|---|---:|---:|---:|
| 1 | 6 | 2 | 0 |
| 2 | 1 | 5 | 3 |

Find the one-to-one matching of targets to hypotheses that IDF1 uses, then IDTP, IDP, IDR and
IDF1. Which pairing would a greedy choice (largest count first) give here?
--- solution
The matching maximises the matched counts: 1–a and 2–b give $6 + 5 = 11$; 1–a, 2–c give 9;
1–b, 2–a give 3; 1–b, 2–c give 5; 1–c with 2–a or 2–b gives 1 or 5. So IDTP = 11, IDFN =
$20 - 11 = 9$, IDFP = $18 - 11 = 7$, IDP = $11/18 \approx 0.611$, IDR = $11/20 = 0.55$ and
$\mathrm{IDF1} = 2 \cdot 11 / (20 + 18) = 22/38 \approx 0.579$. Greedy takes 1–a (6), then the
largest count left for target 2, 2–b (5): the same matching here. Hypothesis c is left over;
its 3 frames on target 2 count as IDFP although they are correct frame by frame.

=== 16.3 ★★ pen and paper | One SORT frame by hand
Three tracks predict boxes of height 20 at $x = 0, 20, 40$, each 20 px wide (all at $y = 0$).
The detector returns three boxes of the same height and width at $x = 5, 28, 70$. Write the
$3 \times 3$ IoU matrix (detections × tracks; boxes of one height overlap by a width $w_\mathrm{o}$ and
have IoU $w_\mathrm{o} / (2 \cdot 20 - w_\mathrm{o})$) and assign in SORT's order by hand: the matching with the
largest total IoU, then every pair below 0.3 rejected. Would gating first change the answer
here? Which track coasts, which detection starts a track? With SORT's reference defaults (a
track is deleted after more than one frame without a detection), what happens to the
coasting track if it is missed again in the next frame?
--- solution
Overlaps: $x = 5$ overlaps track 1 by 15 px (IoU $15/25 = 0.6$) and track 2 by 5 px
($5/35 \approx 0.143$); $x = 28$ overlaps track 2 by 12 px ($12/28 \approx 0.429$) and track 3
by 8 px ($8/32 = 0.25$); $x = 70$ overlaps nothing.

| | track 1 | track 2 | track 3 |
|---|---:|---:|---:|
| $x = 5$ | 0.6 | 0.143 | 0 |
| $x = 28$ | 0 | 0.429 | 0.25 |
| $x = 70$ | 0 | 0 | 0 |

The largest total IoU is $0.6 + 0.429 + 0 = 1.029$: $x = 5$ with track 1, $x = 28$ with
track 2 and $x = 70$ with track 3 (every other matching totals at most 0.85). The gate
rejects the last pair (IoU 0) and keeps the other two. Gating first gives the same: only
$(5, 1)$ and $(28, 2)$ pass the gate, in different rows and columns, so the assignment takes
both. Track 3 coasts on its prediction (its only candidate, $x = 28$,
fell below the gate); the detection at $x = 70$ starts a tentative track. The coasting track
is kept this frame (one frame without a detection, $\le$ `max_age` = 1); missed again, it
has gone two frames without one and is deleted, and if its target is detected later it
starts over under a new id.

=== 16.4 ★★ pen and paper | HOTA of a broken track
One target is present in 8 frames. A tracker follows it with hypothesis a for the first 6
frames and with hypothesis b for the last 2, every box exact (IoU 1), and reports nothing
else. Compute DetA, AssA and HOTA. Then compute MOTA and IDF1 for the same run.
--- solution
Every box is exact, so every threshold $\tau$ gives the same answer. Detection: 8 true
positives, no miss or false positive: DetA = 1. Association: each of the 6 true positives
of a has $|\mathrm{TPA}| = 6$, $|\mathrm{FNA}| = 8 - 6 = 2$ (the target's frames with b) and
$|\mathrm{FPA}| = 0$: $6/8$. Each of the 2 of b has $2/(2 + 6 + 0) = 2/8$. AssA
$= (6 \cdot 6/8 + 2 \cdot 2/8)/8 = 40/64 = 0.625$ and HOTA $= \sqrt{1 \cdot 0.625}
\approx 0.791$. MOTA: one switch, no miss, no false positive: $1 - 1/8 = 0.875$. IDF1: the
target is matched to a, IDTP = 6, $n_\text{gt} = n_\text{hyp} = 8$: $12/16 = 0.75$.

=== 16.5 ★ use | Which error costs SORT most?
Run `Sort()` (the reference defaults) on `synthetic_detections(n_targets=4, n_frames=60,
seed=1)` and score it with `clear_mot`. Of the misses, false positives and identity switches,
which takes the most from MOTA? Rerun with `min_hits=1`. Why does that change the misses so
much, and what does it cost?
--- solution
Misses dominate by far: with `min_hits=3` a track is reported only after three matches in a
row, so every target is unreported in its first frames, and after every single missed
detection its streak starts again and it stays unreported until it has been matched three
frames running again. With `min_hits=1` a
track is reported from its second detection on: the misses fall and MOTA rises, but a false
alarm that happens to be detected twice in a row is now reported too, so the false positives
can rise. The exercises appendix prints the counts below the exercise.

=== 16.6 ★★ modify | Memory against misses
With `miss_rate=0.3` (seed 0, 6 targets, 60 frames), run SORT with `max_age` 1, 3 and 6 and
tabulate identity switches, MOTA and IDF1. Which measure moves most, and why?
--- solution
With `max_age=1` a target missed in two frames running loses its track and comes back under
a new id; at a 30 % miss rate that happens often, so the switches are many. A longer memory
lets the track coast across the gap and the same id picks the target up again: the switches
fall and IDF1, which charges every frame spent under a wrong id, rises clearly. MOTA charges
each switch once, among many misses, so it moves much less.

=== 16.7 ★★★ implement | IDF1 from co-occurrence counts
Implement `idf1(together, n_truth, n_hyp)`: `together[i, j]` is the number of frames in which
target $i$ and hypothesis $j$ overlap with IoU ≥ 0.5, `n_truth` ($n_\text{gt}$) and `n_hyp` ($n_\text{hyp}$) the
numbers of ground-truth and hypothesis boxes of the run. Find the one-to-one matching of
targets to hypotheses with the largest total count (IDTP; rows or columns may be left over)
and return $2\,\mathrm{IDTP}/(n_\text{gt} + n_\text{hyp})$. By hand first: `together = [[5, 4], [4, 0]]`,
$n_\text{gt} = n_\text{hyp} = 10$: greedy would take the 5 and then be left with 0, the best matching is
$4 + 4 = 8$, so IDF1 $= 16/20 = 0.8$. The check uses that case, exercise 16.2 and the example
of the chapter.
--- hint
`scipy.optimize.linear_sum_assignment(together, maximize=True)` solves the matching, also for a
rectangular matrix.
--- solution
```python
from scipy.optimize import linear_sum_assignment

def idf1(together, n_truth, n_hyp):
    t = np.asarray(together, float)
    rows, cols = linear_sum_assignment(t, maximize=True)
    return 2 * t[rows, cols].sum() / (n_truth + n_hyp)
```
"""


def idf1_ok(f):
    """16.7: IDF1 = 2 IDTP / (n_gt + n_hyp) with IDTP the best one-to-one matching of counts."""
    cases = [
        # greedy takes 5 then 0; best 4 + 4 = 8 -> 16 / 20
        (([[5, 4], [4, 0]], 10, 10), 0.8),
        # exercise 16.2: 1-a + 2-b = 6 + 5 = 11 -> 22 / 38
        (([[6, 2, 0], [1, 5, 3]], 20, 18), 22 / 38),
        # the chapter's example: 1-a 4, 2-b 2, 2-c 1 -> 1-a + 2-b = 6, G 8, H 7 -> 12 / 15
        (([[4, 0, 0], [0, 2, 1]], 8, 7), 0.8),
        # one hypothesis for two targets: it goes to the one it covers longer, 5 -> 10 / 16
        (([[3], [5]], 8, 8), 0.625),
        # nothing ever overlaps: 0
        (([[0, 0], [0, 0]], 6, 4), 0.0),
    ]
    return all(abs(float(f(np.asarray(t, float), g, h)) - v) < 1e-12
               for (t, g, h), v in cases)


CHECKS = {"16.7": idf1_ok}
