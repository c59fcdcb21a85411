"""The exercises of 11_knowing_you_are_lost: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "11_knowing_you_are_lost"

TEXT = r"""
=== 11.1 ★ pen and paper | The rule by hand
The reference of a tracker holds the confidences $0.80, 0.84, 0.82, 0.90, 0.82$. Compute its
median $r$ and scaled MAD $s$. With $k_\text{lost} = 3$, is a frame of confidence 0.72 lost?
And one of 0.75? After the frame of 0.72, with $k_\text{found} = 1$ and $m = 2$, which of the
next frames $0.79, 0.81, 0.80$ is the first judged on target again? Last, with the spread
test off and the ratio test on instead ($\phi_\text{lost} = 0.9$): are 0.72 and 0.75 lost?
--- solution
Sorted: $0.80, 0.82, 0.82, 0.84, 0.90$, so $r = 0.82$. The absolute deviations are
$0.02, 0.02, 0, 0.08, 0$; sorted $0, 0, 0.02, 0.02, 0.08$, median $0.02$, so
$s = 1.4826 \times 0.02 = 0.0297$. The loss threshold is $0.82 - 3 \times 0.0297 = 0.731$:
0.72 is below it (**lost**), 0.75 above it (on target). While lost, $r$ and $s$ are frozen and
the found threshold is $0.82 - 0.0297 = 0.7903$: 0.79 falls just short, 0.81 and 0.80 clear
it, so 0.80, the second in a row, is the first frame judged on target again. Check:
`FailureDetector(FailureParams(k_lost=3, k_found=1, m=2, warmup=5))` stepped through the five
reference values and then 0.72, 0.79, 0.81, 0.80 returns five True, three False, one True.
With the ratio test the threshold is $0.9 \times 0.82 = 0.738$: 0.72 is lost and 0.75 is not,
the same verdicts from a threshold that does not use the spread at all.

=== 11.2 ★★ pen and paper | Units do not matter
Show that the spread test gives the same verdicts for a confidence series $c_t$ and for
$a c_t + b$ with $a > 0$. Which step fails for $a < 0$, and why is that the right answer? Which
maps $c \mapsto a c + b$ leave the ratio test's verdicts unchanged?
--- solution
The median commutes with an increasing affine map: $\operatorname{median}(a c + b) = a\,r + b$
(for an even count too: the mean of the two middle values maps the same way).
The deviations become $|a c_j + b - (a r + b)| = a |c_j - r|$, so the MAD (and the
mean absolute deviation of the fallback) is multiplied by $a$: $s \to a s$. Each test
$c_t < r - k s$ becomes $a c_t + b < a r + b - k a s$, which is the same inequality
multiplied by $a > 0$ and shifted by $b$: the same truth value, frame by frame, so the
same frames enter the reference and the same verdicts follow by induction. For $a < 0$
the spread becomes $|a| s$ and the loss test becomes $c_t > r + k s$: the rule would call a
rise a loss. That is right, because $-c$ is no longer a confidence ("larger is surer" is part
of the rule's contract). The ratio test $c_t < \phi r_t$ becomes $a c_t < \phi a r_t$ under
$c \to a c$: the same inequality, so scaling leaves its verdicts alone. A shift does not:
$c_t + b < \phi (r_t + b)$ is $c_t < \phi r_t - (1 - \phi) b$, another threshold. The ratio
test measures the drop from the confidence's own zero, and a shift moves the zero.

=== 11.3 ★★ modify | The price of a looser threshold
Run `kcf` on the second camera-cut scene of `calibration_set(seed=1, per_kind=2)` with
`failure=FailureParams(...)`:
its calibrated thresholds, but the ratio test's $\phi_\text{lost}$ at 0.2, 0.5 and 0.8 (and
$\phi_\text{found}$ at least as high). How does the share of absent frames flagged change,
and what would you expect to happen to the false losses on the sample clips?
--- solution
A larger $\phi_\text{lost}$ puts the threshold closer to the median, so more absent frames
fall below it: the share flagged rises (or stays at 100 %). The same closeness catches the
ordinary dips of a tracker on target (a fast motion, a change of light), so the false losses
on the sample clips rise too. A smaller $\phi_\text{lost}$ does the reverse. That trade-off
is the ROC curve read one point at a time; calibration picks the point with at most 1 % false
losses.

=== 11.4 ★★★ implement | The ROC area as a count
Implement `auc(on, absent)`: the area under the ROC curve of confidences `on` (positives) and
`absent` (negatives), as the share of pairs $(i, j)$ with $c^\text{on}_i > c^\text{absent}_j$,
ties counting one half. By hand first: `on = [2, 2, 1]`, `absent = [2, 0]` has six pairs, two
ties, three wins and one loss: $4/6$. The check uses that case and a few more.
--- solution
Compare every pair at once with broadcasting:
`d = np.subtract.outer(on, absent); return ((d > 0).sum() + 0.5 * (d == 0).sum()) / d.size`.
For long series this costs $n_\text{on} \times n_\text{absent}$ comparisons; the library's
`roc_auc` gets the same number from ranks (the Mann–Whitney statistic) in
$O(n \log n)$.

=== 11.5 ★★ pen and paper | Why stop learning?
A correlation filter updates its model with a learning rate $\eta$ (KCF's is 0.02):
$\hat\alpha_t = (1 - \eta)\hat\alpha_{t-1} + \eta\,\hat\alpha(\text{this frame})$. The target
is gone for $n$ frames and the tracker keeps learning. What share of the model is still the
target's after $n$ frames, for $\eta = 0.02$ and $n = 35$? What does that mean for the
confidence while the target is gone, and when it returns?
--- solution
Each frame keeps $(1 - \eta)$ of the model, so after $n$ frames the target's share is
$(1 - \eta)^n = 0.98^{35} \approx 0.49$: half of the model is background. While the target is
gone, the model comes to match the background, so the confidence creeps back up and a rule on
the confidence is fooled into "found"; when the target returns, half of the model no longer
matches it. A tracker judged lost that stops learning keeps $(1 - \eta)^0 = 1$ of its model.

=== 11.6 ★ pen and paper | A box that has left the frame
The layer calls a frame lost, whatever the confidence says, when less than half of the
tracker's box $b$ lies inside the frame $F$. Show that such a box has
$\operatorname{IoU}(b, g) < 1/2$ with every box $g$ inside the frame: the box the tracker
found is never on target (IoU > 0.5). Is the bound tight? And which exit does the rule not
catch?
--- solution
The union contains $b$, and $b \cap g \subseteq b \cap F$ because $g \subseteq F$, so
$\operatorname{IoU}(b, g) = |b \cap g| / |b \cup g| \le |b \cap g| / |b| \le |b \cap F| / |b|
< 1/2$. Tight, as a limit: with $g = b \cap F$ both inequalities are equalities, so IoU
equals the share in view. $b = (-10.5, 0, 20, 10)$ in a frame that starts at $x = 0$ has
$9.5 \times 10 = 95$ of its 200 px$^2$ in view; with $g = (0, 0, 9.5, 10)$,
$|b \cap g| = 95$, $|b \cup g| = 200$, IoU $= 0.475$. At $b = (-10, 0, 20, 10)$ with
$g = b \cap F = (0, 0, 10, 10)$ both reach $1/2$; that box is exactly half in view, which
the rule does not flag. The rule misses a box that stops at the border with
most of it inside (a tracker that keeps its box in the frame never triggers it): there the
box scores the background beside the border, and only the confidence can say the target has
gone.

=== 11.7 ★★ modify | Stricter at the frame's edge
A tracker whose box rests across the frame's edge on the background, after the target has
left, can keep its confidence between the lost and the found thresholds, and so stay "on
target". One remedy: judge a frame whose located box reaches past an edge against the found
thresholds, with no hysteresis band. Write it for `condensation`: subclass its class,
`type(trackers.create("condensation"))`, and override `_locate` so that, after the layer's
warm-up and while the layer says on target, a box past an edge whose confidence is below
`threshold(r, s, k_found, ratio_found)` comes back as `(box, conf, False)`: the optional
third value of `_locate` is the algorithm's own verdict, `False` for lost (`condensation`'s
`_locate` returns only the first two). The layer is `self._detector` (a `FailureDetector`;
`None` with `failure=False`): `self._detector.lost` says whether it is lost, and
`self._detector.reference` is the reference $(r, s)$ the coming frame is judged against; the
thresholds are `self.failure_params`, and `threshold` comes from `trackbook.trackers.failure`.
For the warm-up, `self.frame_index > self.failure_params.warmup` will do (it is exact while
every frame of the warm-up has a confidence). Run it and `condensation` with
`trackbook.evaluate` on the second exit scene of `calibration_set(seed=1, per_kind=2)` (the
share of absent frames flagged lost) and on the sample clip `robot-corridor-day` (the false
losses, `metrics.false_losses(r.ok, r.boxes, clip.groundtruth, samples.in_view(clip.name))`).
Would you make it the library's rule?
--- solution
```python
def strict_at_the_edge(name):
    Base = type(trackers.create(name))

    class Strict(Base):
        def _locate(self, frame):
            box, conf, *rest = super()._locate(frame)
            ok = bool(rest[0]) if rest else True
            d, p = self._detector, self.failure_params
            x, y, w, h = box
            H, W = frame.shape[:2]
            out = x < 0 or y < 0 or x + w > W or y + h > H
            if out and not d.lost and self.frame_index > p.warmup:
                r, s = d.reference
                found = threshold(r, s, p.k_found, p.ratio_found)
                ok = ok and conf >= found
            return box, conf, ok

    return Strict(seed=0)
```
`condensation` uses the ratio test alone: lost below $\phi_\text{lost} = 0.3$ of the
reference, found at $\phi_\text{found} = 0.8$ of it, $m = 3$ frames in a row. On the exit
scene the stricter rule flags every absent frame, where `condensation` flags none. It fires
once, on frame 23, six frames after the box first crossed the edge behind the leaving target:
the box is half in view and $\rho$ has dropped into the band between the two thresholds. The
reference frozen at that loss keeps the tracker lost to the clip's end. Without the loss,
$\rho$ on the absent frames lies between 0.41 and 0.70 of the reference: under the found
level, but above the lost one, so each of them passes as on target. (The library keeps the
confidence of a box past the edge out of the reference: the box rests across the edge from
frame 17 to 33, and the reference stays near 0.99 to the last absent frame, 41. From frame
34 the box lies wholly inside the frame, on the background, and its confidences enter; after
the target's return the reference sinks to them, 0.69 by frame 50. The absent frames pass
all the same: 0.41–0.70 of the reference lies inside the band between 0.3 and 0.8.)

On `robot-corridor-day` the rule costs 5 false losses of the 129 frames with the box on the
target (none of 138 without): 3.9 %, over the contract's 1 %. With the lights dimmed, the box
slides down the target until, at frame 37, it reaches 1 px past the bottom edge with $\rho$
at 0.53 of its reference. That loss is not itself false (the box found there, and the box
reported, overlap the target with IoU under 0.5), but the found threshold is not met for $m$
frames in a row until the lights come back, and the box reported meanwhile, the last judged
on target, still overlaps the target by more than half on 5 of those frames.

The rule gives up the band that lets a tracker ride through a dip wherever the box touches
the edge, and a single pixel is enough: the box at frame 37 is 99 % in view. Before making it
the library's, measure it over every tracker and scene, calibrate again (the found thresholds
would judge these frames too), and consider asking for a real share out of view instead.
"""
