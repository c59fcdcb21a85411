"""The exercises of 19_evaluation_protocols: their text, defined once (see
:mod:`trackbook.exercises`), and the auto-check of its ★★★ exercise."""

STEM = "19_evaluation_protocols"

TEXT = r"""
=== 19.1 ★ pen and paper | Accuracy and robustness of a reset run by hand
A tracker runs through the reset protocol on a 16-frame clip with re-initialisation 5 frames
after a failure and a burn-in of 2 frames (short, for a short clip). Its overlap on the frames
it tracks is

| frame | 1 | 2 | 3 | 4 | 5 | 6 | 7 | 8 | 9 | 10 | 11 | 12 | 13 | 14 | 15 |
|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|
| overlap | 0.8 | 0.7 | 0.6 | 0.5 | 0 | | | | | | 0.9 | 0.6 | 0.5 | 0.7 | 0.8 |

(frame 0 and frame 10 are initialisations; frames 6–9 are skipped). Which frames does the
accuracy average? Give the accuracy, the number of failures and the failures per 100 frames.
--- solution
The failure is frame 5 (overlap 0), so the tracker is re-initialised on frame 5 + 5 = 10.
The burn-in drops frames 1–2 after the first initialisation and 11–12 after the second; the
failure frame is counted by robustness, not accuracy. The accuracy averages frames 3, 4, 13,
14 and 15: $(0.6 + 0.5 + 0.5 + 0.7 + 0.8)/5 = 3.1/5 = 0.62$. One failure on 16 frames is
$100 \cdot 1/16 = 6.25$ failures per 100 frames.

=== 19.2 ★ pen and paper | A point of the expected-average-overlap curve
Reset runs on two clips give three fragments (only a run's last fragment can reach the end
of its clip). On the first clip, fragment a failed after the overlaps $(0.8, 0.6, 0)$ and
fragment b, after the re-initialisation, reached the end after $(0.9, 0.9, 0.9, 0.9, 0.9)$;
on the second clip, fragment c reached the end after $(0.5, 0.5)$. Compute $\langle\Phi_T\rangle$ for $T = 2$ and $T = 4$.
--- solution
$T = 2$: every fragment has two frames, $\Phi_2 = 0.7, 0.9, 0.5$, mean $2.1/3 = 0.7$.
$T = 4$: fragment a failed, so its overlaps are padded with zeros,
$\Phi_4 = (0.8 + 0.6 + 0 + 0)/4 = 0.35$; fragment b has $\Phi_4 = 0.9$; fragment c ended after
two frames without failing, so it says nothing about four-frame sequences and is left out.
$\langle\Phi_4\rangle = (0.35 + 0.9)/2 = 0.625$.

=== 19.3 ★ pen and paper | The SRE boxes of a given box
Write the 12 initial boxes of the spatial robustness evaluation for the first box
$(x, y, w, h) = (40, 30, 20, 10)$: four centre shifts, four corner shifts, four scalings.
Check with `protocols.sre_boxes`.
--- solution
$\delta_x = 0.1 w = 2$, $\delta_y = 0.1 h = 1$, centre $(50, 35)$. Centre shifts: left
$(38, 30, 20, 10)$, right $(42, 30, 20, 10)$, up $(40, 29, 20, 10)$, down $(40, 31, 20, 10)$.
Corner shifts move one corner out and keep the opposite one, so the box grows to $22 \times 11$:
top-left $(38, 29, 22, 11)$, top-right $(40, 29, 22, 11)$, bottom-left $(38, 30, 22, 11)$,
bottom-right $(40, 30, 22, 11)$. Scalings keep the centre: 0.8 gives $(42, 31, 16, 8)$, 0.9
gives $(41, 30.5, 18, 9)$, 1.1 gives $(39, 29.5, 22, 11)$, 1.2 gives $(38, 29, 24, 12)$.

=== 19.4 ★ pen and paper | Where TRE starts
A clip has $T_\mathrm{clip} = 50$ frames, every ground-truth box known. With $M = 5$ starts and segments of
at least 20 frames, which frames does TRE start on? Use the rule of `protocols.tre_starts`
and check your answer with it.
--- solution
A start must leave 20 frames, $50 - i \ge 20$, so the candidates are frames 0–30, positions
1–31, and $E = 31$. The positions are $1 + \lfloor kE/(M-1) \rfloor$ while
$1 + kE/4 \le 31$: $k = 0, 1, 2, 3$ gives 1, 8, 16, 24 ($k = 4$ would give 32), then $E$:
positions 1, 8, 16, 24, 31, that is frames 0, 7, 15, 23 and 30.

=== 19.5 ★★★ implement | Counting failures the VOT way
Write `reset_count(overlaps, skip)` for VOT's reset rule. `overlaps[i]` is the overlap the
tracker has on frame `i` whenever it is tracking there (entry 0 is never used: frame 0 is the
first initialisation). A tracked frame with overlap 0 is a failure; after a failure at `f` the
tracker is re-initialised on frame `f + skip` (nothing happens if that is past the end), and
the initialisation frame itself is never scored. Return `(inits, failures)`, two tuples of
frame numbers. Worked by hand: for `[1, .5, 0, .5, .5, .5, .5, .5, .5, .5]` and skip 5 the
answer is `((0, 7), (2,))`; for `[1, 0, 0, 0, 0, 0, 0, 0]` and skip 5 it is `((0, 6), (1, 7))`;
for `[1, .3, .3, 0, .3, .3, .3, .3, 0, .3]` and skip 5 it is `((0, 8), (3,))`, since frame 8
is an initialisation and its 0 is never read.
--- solution
Walk the frames once: after each initialisation at `s`, look at `s + 1, s + 2, ...` for the
first zero; record it as a failure and jump to `f + skip`; stop at the end of the clip.

=== 19.6 ★★ modify | How long to wait before re-initialising
Run `protocols.evaluate_reset("mosse", "yellow-ball")` with `skip=5` (VOT's) and with
`skip=1`. Compare the failure counts, and explain why VOT does not re-initialise on the very
next frame. Why is the accuracy `nan` in both runs?
--- solution
`mosse` cannot follow the fast ball: after every initialisation it loses it again within a
few frames. With `skip=5` it fails 14 times in the 120 frames; with `skip=1` it is put back
on the target the frame after each failure, while the cause (the fast motion) is still there,
and fails 25 times. The count then says more about how often the benchmark restarted the
tracker than about how often it lost the target: the same difficulty is counted again and
again. Waiting five frames lets the cause pass and counts it fewer times; the frames skipped
are scored by neither accuracy nor robustness. The accuracy is `nan` because every failure
comes within ten frames of the initialisation before it: each tracked frame is either in a
burn-in or a failure, so no frame is left to average (`run.valid.sum()` is 0).

=== 19.7 ★ use | TRE from the command line
Run `trackbook bench --trackers kcf --clips red-cube --protocol tre:5 --max-frames 60
--out tre-kcf` and then the same bench with `--protocol ope --out ope-kcf`. Read both
`table.md` files. Why do the two AUCs differ, and which one weighs the end of the clip more?
--- solution
(Each table also has a row for `opencv-mil`, which `bench` always adds as a reference.) The
TRE table pools five runs that start on frames 0, 10, 20, 30 and 40 of the 60 frames: the
last frames are tracked by every run, the first ones by one run only, so TRE weighs the end
of the clip more than the one-pass evaluation does: a tracker that does well early in the
clip (where OPE starts it) gains less from it under TRE, and one that does well late gains
more. The AUCs differ for a second reason too: every later run starts again from the ground
truth, so a drift that OPE carries to the end of the clip is undone at each start.
"""


def reset_count_ok(f):
    """19.5: VOT's reset rule on scripted overlap series (answers worked by hand)."""
    cases = [
        # init 0, fails at 2, re-init at 7, frames 8, 9 tracked
        (([1, .5, 0, .5, .5, .5, .5, .5, .5, .5], 5), ((0, 7), (2,))),
        # never fails
        (([1, .2, .3, .4], 5), ((0,), ())),
        # fails at 1, re-init at 6, fails at 7, the next init (12) is past the end
        (([1, 0, 0, 0, 0, 0, 0, 0], 5), ((0, 6), (1, 7))),
        # fails at 3, re-init at 8: frame 8's own 0 is never read, 9 is tracked
        (([1, .3, .3, 0, .3, .3, .3, .3, 0, .3], 5), ((0, 8), (3,))),
        # skip 1: fail 1, init 2, fail 3, init 4 (the last frame)
        (([1, 0, .5, 0, .5], 1), ((0, 2, 4), (1, 3))),
        # a failure on the last frame: no re-initialisation follows
        (([1, .5, .5, 0], 5), ((0,), (3,))),
    ]
    for (o, skip), (inits, fails) in cases:
        got = f(list(o), skip)
        if tuple(int(v) for v in got[0]) != inits or tuple(int(v) for v in got[1]) != fails:
            return False
    return True


CHECKS = {"19.5": reset_count_ok}
