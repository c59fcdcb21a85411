"""The exercises of 09_trackers_compared: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "09_trackers_compared"

TEXT = r"""
=== 9.1 ★ use | Another measure
Run `compare.check_claims(rows, metric="precision20")` on the book
defaults (`rows = [r for r in results.load("claims") if
r["preset"] == "book"]`). Which verdicts change compared with the AUC? In what is the
precision at 20 px closer to the AUC than to the tracking rate?
--- solution
Two of the seven change, both from inconclusive: Kim et al.'s `hog-pf > hsi-color-pf` fails and
Cho and Kang's `condensation-mean-shift > condensation` holds. Precision at 20 px, like the
AUC, credits a tracker that stays near the target with a loose box: it only asks whether the
centre is within 20 px, not whether the box is tight; the tracking rate asks for an overlap
above 0.5.

=== 9.2 ★ use | Where MIL wins
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

=== 9.4 ★★ modify | Which interval?
Re-run the claims check with a 90 % and a 99 % interval
(`level=0.90`, `level=0.99`). Which verdicts move? Why is a wider interval "more cautious"?
--- solution
With the book's defaults and the AUC all seven verdicts are inconclusive at 95 %. At 90 % two
move: Kim et al.'s `hog-pf > hsi-color-pf` fails and Cho and Kang's
`condensation-mean-shift > condensation` holds; at 99 % all stay inconclusive. A wider
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
the book's run of OpenCV's MIL on fewer than a third of them. Besides the code: the parameters (search radius, number of features, learning rate), the
initial box the toolkit hands over, and the run itself (MIL samples its features at random).

=== 9.7 ★★★ implement | From the toolkit's count to the book's frames
The published success rate $r$
counts frames 1 to $N$, and frame 1 is the given box, always a success; the book scores frames
2 to $N$. Write `without_first(r, N)` returning the rate over frames 2 to $N$. By hand: on a
sequence of $N = 11$ frames, $r = 6/11$ is 6 successes, frame 1 among them; over frames 2 to
11 that is 5 of 10, 0.5. The check uses that case, $r = 1$ (stays 1) and $r = 1/N$ (only frame 1: 0).
--- solution
$rN$ frames are successes, one of them frame 1: $(rN - 1)/(N - 1)$.

=== 9.8 ★★★ project | A benchmark of your own
Download a handful of OTB sequences, point the
library at them (`clips.load_dataset`), run the trackers of
one paper with both presets over three seeds, and write up its claim with intervals as
this chapter does. Does it hold on sequences neither the paper nor this book was tuned on?
"""
