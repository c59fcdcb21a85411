"""The exercises of 09_trackers_compared: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "09_trackers_compared"

TEXT = r"""
=== 9.1 ★ use | Another measure | after case_studies_compared
Run `compare.check_claims(rows, metric="precision20")` on the book
defaults (`rows = [r for r in results.load("claims") if
r["preset"] == "book"]`). Which verdicts change compared with the AUC's (on the page
{doc}`The four papers' claims, checked <case_studies_compared>`)? In what is the
precision at 20 px closer to the AUC than to the tracking rate?
--- solution
Two of the seven change, both inconclusive by the AUC: Cho and Kang's
`condensation-mean-shift > condensation` (its AUC interval's lower bound is −0.0002) holds by
precision at 20 px, and Kim et al.'s `hog-pf > hsi-color-pf` (upper bound +0.012) fails by
it. How near the AUC interval comes to 0 is not what decides: three of the other five cross
0 by less than 0.01, nearer than `hog-pf > hsi-color-pf` does, and stay inconclusive by both,
as do the remaining two. Precision at 20 px, like the
AUC, credits a tracker that stays near the target with a loose box: it only asks whether the
centre is within 20 px, not whether the box is tight; the tracking rate asks for an overlap
above 0.5.

=== 9.2 ★ use | Where MIL wins | after 14_tracking_by_detection
Load the committed benchmark of the real sequences (`results.load("real")`) and compute the
mean AUC per difficulty with `compare.per_attribute(rows, compare.SEQUENCE_ATTRIBUTES)`. For
which difficulty is OpenCV's MIL (`opencv-mil`) the best tracker? Answer its code (`"IV"`,
`"OCC"`, `"FM"`, `"BC"`, `"SV"` or `"DEF"`; the first in the table if there are several), then
explain from what MIL learns on-line why it wins there.
--- solution
MIL retrains its classifier (Haar-like features of the grey image, target against the
background around it) at every frame, so its model follows the target's appearance as the
light changes. The papers' trackers keep the first frame's colour/HOG model (or learn it only
under a gate), and a colour histogram is exactly what an illumination change alters.

=== 9.3 ★★ modify | One seed is not enough
Run `condensation` and `condensation-mean-shift` on `shelves` with seeds 0, 1, 2, 3 and 4. In
how many of the five seeds does `condensation-mean-shift` have the higher AUC, and what is the
spread (max − min) of `condensation`'s AUC over the seeds? Answer `(wins, spread)`. Compare the
spread with the gap between the two trackers: what does it say about comparing two particle
filters on one seed?
--- solution
The gap between the two trackers is of the order of the seed-to-seed spread of either: the
ranking can flip with the seed. Compare particle filters over several seeds (and clips), and
report the spread, before calling one better.

=== 9.4 ★★ modify | Which interval? | after case_studies_compared
Re-run the claims check of {doc}`The four papers' claims, checked <case_studies_compared>`
with a 90 % and a 99 % interval
(`level=0.90`, `level=0.99`). Which verdicts move? Why is a wider interval "more cautious"?
--- solution
With the book's defaults and the AUC none of the seven has a verdict at 95 %. At 90 % three
move: Kim et al.'s `hog-pf > hsi-color-pf` fails, and Lee et al.'s `color-hog-pf > color-pf`
and Cho and Kang's `condensation-mean-shift > condensation` hold; at 99 % all seven are
inconclusive. A wider
interval is harder to push wholly above or below 0, so fewer claims get a verdict: it trades
missed effects for fewer false verdicts.

=== 9.5 ★★★ implement | Leave one sequence out, yourself
Write `loso(scores)`: `scores[config][sequence]` is a configuration's score on a sequence. For
each sequence in turn, choose the configuration with the best mean over the *other* sequences
and take its score on the held-out one; return the mean of those held-out scores. By hand
first: `{"p": {"a": 0.5, "b": 0.5, "c": 0.5}, "q": {"a": 0.4, "b": 0.4, "c": 0.9}}`. Holding out
`a` (or `b`), `q` has the better mean on the others (0.65 against 0.5) and scores 0.4 on it;
holding out `c`, `p` is better (0.5 against 0.4) and scores 0.5: the answer is
$(0.4 + 0.4 + 0.5)/3 \approx 0.433$, below the mean of either configuration over all three
(0.5 and 0.567). The check uses that
case and a single configuration (its plain mean). Then run it on both presets of every tracker
(`results.load("claims")`, mean AUC over seeds) and compare with `compare.loso_select`.
--- solution
Choosing on the same sequences one reports on overstates: in the hand case the best
configuration by its mean over all three sequences is `q` (0.567), but chosen without the
sequence it is scored on it earns only 0.433.

=== 9.6 ★★ modify | One algorithm, two implementations
In the table beside the published results, MIL
appears twice: the authors' code (published) and OpenCV's `TrackerMIL` run by the book. On
which of the five sequences is the gap largest, and name two things that differ between the
two runs besides the code (settings, initialisation, the run itself)?
--- solution
The gap is largest on Crossing, where the published MIL succeeds on almost every frame and
the book's run of OpenCV's MIL on about a third of them. Besides the code, the largest
difference is the book's failure layer: on the frames it judges lost the run reports MIL's
last box judged on target (without the layer the same run succeeds on about a quarter of the
frames). Then: the parameters (search radius, number of features, learning rate), the
initial box the toolkit hands over, and the run itself (MIL samples its features at random).

=== 9.7 ★★★ implement | From the toolkit's count to the book's frames
The published success rate $r$
counts frames 1 to $N$, and frame 1 is the given box, always a success; the book scores frames
2 to $N$. Write `without_first(r, N)` returning the rate over frames 2 to $N$. By hand: on a
sequence of $N = 11$ frames, $r = 6/11$ is 6 successes, frame 1 among them; over frames 2 to
11 that is 5 of 10, 0.5. The check uses that case, $r = 1$ (stays 1) and $r = 1/N$ (only frame 1: 0).
--- solution
$rN$ frames are successes, one of them frame 1: $(rN - 1)/(N - 1)$.

=== 9.8 ★★★ project | A benchmark of your own | after case_studies_compared
Download a handful of OTB sequences, point the
library at them (`clips.load_dataset`), run the trackers of
one paper with both presets over three seeds, and write up its claim with intervals as
{doc}`The four papers' claims, checked <case_studies_compared>` does. Does it hold on
sequences neither the paper nor this book was tuned on?
--- solution
No single number is right here: the answer depends on the sequences chosen. A good write-up
has five parts; the model below takes the claim the book tests for Lee et al. (2012),
`color-pf` < `color-hog-pf` < `color-hog-ipca`, and any of the four claims is worked the same
way.

1. **The sequences, chosen before any run.** OTB-100 sequences outside the seven this book was
   tuned on, with the reason for each (the claim's setting: for a colour model against
   colour + HOG, illumination variation and background clutter, OTB's IV and BC), and none
   that shares its frames with a development sequence: `Jogging.2` is the other target of the
   video of Jogging-1. Ten or so: the width of the interval falls roughly as one over the
   square root of the number of sequences, so ten instead of seven narrows it only by about
   $1 - \sqrt{7/10} \approx 16\,\%$, and halving it takes four times as many, 28.
2. **The runs.** `ds = clips.load_dataset("~/data/OTB100")` (read `ds.skipped`), keep the
   chosen sequences, and run
   `bench.run(["color-pf", "color-hog-pf", "color-hog-ipca"], chosen, out, seeds="0-2",
   preset=p, reference=False)` once with `p = "paper"` and once with `p = "book"`: with
   ten sequences $3 \times 10 \times 3 \times 2 = 180$ runs, and each comparison pairs
   $10 \times 3 = 30$ runs per preset.
3. **The verdicts.** `compare.check_claims(rows, metric=m,
   papers={"lee2012": PAPERS["lee2012"]})` for each preset and each measure (`"auc"`,
   `"tracking_rate"`): a table of the mean paired difference, its 95 % interval over
   sequences and the verdict, as on that page, with the per-sequence paired differences
   drawn (one dot per seed) so that a reader sees whether one sequence makes the mean.
4. **The comparison with the development sequences.** There, `color-hog-pf > color-pf` by AUC
   is $+0.082$ $[-0.004, +0.176]$, inconclusive, with the book's defaults and $-0.087$
   $[-0.149, -0.029]$, fails, with the paper preset. A good answer states both beside its
   own and says which moved. The book's defaults were chosen on the development sequences
   (the leave-one-sequence-out section), so new sequences are their honest test: if the
   defaults do better than the paper preset on the development sequences and by less on the
   new ones, that is what that section predicts.
5. **The conclusion, no further than the interval.** "Holds" only if the interval lies above
   0; "inconclusive" says these sequences cannot separate the trackers, not that the paper
   was wrong; and the verdict is about these ten sequences, their one set of ground-truth
   boxes and three seeds: not about the trackers in general. The limits go in too: one benchmark's
   boxes, the book's choices wherever a setting is not printed, and video of other sizes and
   frame rates.

=== 9.9 ★ pen and paper | Three measures, two rankings
Two trackers run on the same five frames. Their overlaps (IoU) with the true box are
$A$: 0.46, 0.48, 0.47, 0.49, 0.44 and $B$: 0.78, 0.72, 0.66, 0, 0; their centre errors, in
pixels, are $A$: 6, 9, 4, 12, 8 and $B$: 2, 3, 5, 140, 95. The success rate at a threshold
$t$ is the share of frames with IoU $> t$, and the AUC is the mean of the success rates over
the 21 thresholds $t = 0, 0.05, \dots, 1$; the tracking rate is the share of frames with
IoU $> 0.5$, and the precision at 20 px the share with a centre error $\le 20$ px.
(a) Compute each tracker's success rates and AUC. (b) Compute each one's tracking rate and
precision at 20 px; which tracker does each of the three measures put first?
(c) Swap the two sums of the AUC to show that it is the mean over frames of $c(u)/21$, where
$c(u)$ is the number of thresholds below the frame's IoU $u$, and that it lies within $1/21$
of the mean IoU.
--- solution
(a) $A$'s overlaps all lie between 0.44 and 0.49: all five exceed $t$ for the nine
thresholds $t = 0, \dots, 0.40$ (rate 1), four exceed $t = 0.45$ (0.44 does not: rate 0.8),
and none exceeds $t \ge 0.5$. AUC $= (9 \times 1 + 0.8)/21 = 9.8/21 \approx 0.467$. $B$'s
two frames of IoU 0 fail at every threshold, even $t = 0$ (the test is $>$); its other three
exceed $t$ for the fourteen thresholds $t = 0, \dots, 0.65$ (rate 0.6), two exceed $0.70$
(0.4), one exceeds $0.75$ (0.2), none $t \ge 0.80$. AUC $= (14 \times 0.6 + 0.4 + 0.2)/21 =
9/21 \approx 0.429$.

(b) Tracking rate: $A$ 0 (no overlap above 0.5), $B$ 3/5 = 0.6. Precision at 20 px: $A$ 1
(every centre within 20 px), $B$ 3/5 = 0.6. The AUC and the precision put $A$ first, the
tracking rate $B$: $A$ follows the target loosely in every frame, $B$ is tight or lost.

(c) With $u_i$ the IoU of frame $i$ and $\mathbf 1$ the indicator,
$\text{AUC} = \frac{1}{21}\sum_t \frac15 \sum_i \mathbf 1[u_i > t] = \frac15 \sum_i
\frac{1}{21} \sum_t \mathbf 1[u_i > t] = \frac15 \sum_i c(u_i)/21$. Here $c = 10, 10, 10,
10, 9$ for $A$ (sum 49, $49/105 = 9.8/21$) and $16, 15, 14, 0, 0$ for $B$ (sum 45,
$45/105 = 9/21$). The thresholds below $u$ are $0.05k$ for $k = 0, 1, \dots$ with $k < 20u$,
so $c(u) = \lceil 20u \rceil$ and $20u \le c(u) < 20u + 1$ for every $u$ in $[0, 1]$. Then
$-u/21 \le c(u)/21 - u < (1 - u)/21$, so each frame's term lies within $1/21 \approx 0.048$
of its IoU, and their mean, the AUC, within $1/21$ of the mean IoU: $A$'s mean IoU is 0.468
(AUC 0.467), $B$'s 0.432 (AUC 0.429).

=== 9.10 ★★ pen and paper | Why pair: four sequences by hand
Trackers $A$ and $B$ each ran once on four sequences, with AUCs

| sequence | 1 | 2 | 3 | 4 |
|---|---|---|---|---|
| $A$ | 0.70 | 0.40 | 0.55 | 0.25 |
| $B$ | 0.66 | 0.35 | 0.52 | 0.27 |

Write $a$ and $b$ for a sequence's AUCs of $A$ and $B$. (a) Compute the paired differences
$d = a - b$ and their mean $\bar d$. (b) With $S_{aa} = \sum (a - \bar a)^2$,
$S_{bb} = \sum (b - \bar b)^2$ and $S_{ab} = \sum (a - \bar a)(b - \bar b)$ over the four
sequences, show that
$\sum (d - \bar d)^2 = S_{aa} + S_{bb} - 2 S_{ab}$, and compute the three sums. Compare the
standard error of $\bar d$ from the paired differences, $s_d / \sqrt 4$ (with
$s_d^2 = \sum (d - \bar d)^2 / 3$), with the one that treats $A$'s and $B$'s scores as two
unrelated samples, $\sqrt{(s_a^2 + s_b^2)/4}$ (with $s_a^2 = S_{aa}/3$ and
$s_b^2 = S_{bb}/3$). Why are they so different? (c) The bootstrap
draws four sequences with replacement and averages their differences; each of the
$4^4 = 256$ ordered draws is equally likely. How many draws have a mean $\le 0$? The ends of
the 95 % percentile interval lie at rank $256 \times 0.025 = 6.4$ from each end of the 256
sorted means: find them and give the verdict. (d) What does the interval say, and what does
it not say?
--- solution
(a) $d = (0.04, 0.05, 0.03, -0.02)$, $\bar d = 0.10/4 = 0.025$.

(b) $d - \bar d = (a - \bar a) - (b - \bar b)$, since $\bar d = \bar a - \bar b$; squaring and
summing gives $S_{aa} + S_{bb} - 2S_{ab}$. With $\bar a = 0.475$ and $\bar b = 0.45$:
$a - \bar a = (0.225, -0.075, 0.075, -0.225)$, $S_{aa} = 0.1125$;
$b - \bar b = (0.21, -0.10, 0.07, -0.18)$, $S_{bb} = 0.0914$;
$S_{ab} = 0.04725 + 0.0075 + 0.00525 + 0.0405 = 0.1005$. So
$\sum (d - \bar d)^2 = 0.1125 + 0.0914 - 0.2010 = 0.0029$, as from
$d - \bar d = (0.015, 0.025, 0.005, -0.045)$ directly. Paired: $s_d^2 = 0.0029/3$,
$s_d \approx 0.0311$, standard error $\approx 0.0155$. Unpaired:
$\sqrt{(0.1125 + 0.0914)/(3 \times 4)} \approx 0.130$, about 8.4 times larger. The
scores are strongly correlated ($S_{ab}/\sqrt{S_{aa} S_{bb}} \approx 0.99$): a sequence
hard for $A$ is hard for $B$. The unpaired error counts that shared difficulty as noise;
the term $-2S_{ab}$ removes it, which is what pairing does.

(c) A draw's mean is $\le 0$ only if it holds sequence 4 three or four times. Four times:
1 draw, mean $-0.02$. Three times and one other sequence (4 places for it): the sums are
$-0.06 + 0.03$, $-0.06 + 0.04$, $-0.06 + 0.05$, means $-0.0075$, $-0.005$, $-0.0025$, 4
draws each. Twice already gives $-0.04$ plus at least $0.06$, above 0. So $1 + 12 = 13$
draws, 5.1 %. Sorted, the 6th to 9th smallest means are $-0.005$: the lower end is
$-0.005$. At the top, the largest is $0.05$ (sequence 2 four times, 1 draw), then $0.0475$
(three 2s and a 1, 4 draws), then $0.045$ (three 2s and a 3, 4 draws, or two 2s and two
1s, 6 draws): the 6th to 15th largest are $0.045$, the upper end. (Every reading of
"rank 6.4" lands in these runs of equal means: the library's `np.quantile` interpolates
between the 7th and the 8th from each end.) The interval $[-0.005, 0.045]$ contains 0:
**inconclusive**.

(d) It says how far the mean difference would move if another four sequences like these
were drawn: a range of plausible mean differences over sequences of this kind. It does not
give the probability that $A$ is better, and "inconclusive" is not evidence that the two
are equal: three of the four sequences favour $A$, but with four sequences one that
favours $B$ is enough to keep 0 in the interval.

=== 9.11 ★ pen and paper | The sign test
Over seven sequences (each score the mean over its seeds), tracker $B$ beats tracker $A$ on
six and loses on one. The sign test asks: if the two were equally good, each sequence would
be a fair coin, independently of the others; how likely is a result this lopsided?
(a) Compute the one-sided p-value $P(\text{at least 6 wins of 7})$ and the two-sided one
(either tracker that lopsided). Is the difference significant at 5 %? (b) Which results of
seven sequences are significant at 5 %, two-sided? (c) With the five OTB sequences of this
chapter alone, can any result be significant at 5 %, two-sided? (d) What does the sign
test ignore that the bootstrap uses? Why count seven sequences and not the 21 runs of
three seeds each?
--- solution
(a) $P(\ge 6) = \left[\binom76 + \binom77\right] / 2^7 = 8/128 = 0.0625$ one-sided, and twice
that, $0.125$, two-sided: not significant at 5 %.

(b) Only 7 of 7 (or 0 of 7): $2 \times 1/128 \approx 0.0156$. Six of seven is already 0.125.

(c) No: the most lopsided result, 5 of 5, has $2 \times 1/32 = 0.0625 > 0.05$.

(d) The sizes of the differences: a win by 0.001 counts as much as one by 0.3. That makes
the test blind to how much better a tracker is, but robust to one sequence with a huge
difference. The seeds of one sequence replay the same video, so they are not independent
coins: counting 21 runs would treat three replays of one difficulty as three pieces of
evidence and make the p-value too small. The unit of evidence is the sequence, as in the
chapter's bootstrap.
"""
