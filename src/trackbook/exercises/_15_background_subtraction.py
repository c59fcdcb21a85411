"""The exercises of 15_background_subtraction: their text, defined once (see
:mod:`trackbook.exercises`), and the auto-check of the ★★★ exercise."""

import numpy as np

STEM = "15_background_subtraction"

TEXT = r"""
=== 15.1 ★ pen and paper | When does a stopped object become background?
A pixel has seen only the floor: one component of weight 1. A box is put down on it and stays.
With the learning rate $\eta = 0.005$, $c_\mathrm{f} = 0.1$ and no complexity prior ($c_\mathrm{T} = 0$), for
how many frames, counting the frame the box arrives, is the pixel foreground? And with
$\eta = 1/500$, the rate OpenCV settles on with its default `history` of 500 frames?
--- hint
On the frame the box arrives the floor's component is scaled by $(1 - \eta)$ and the box's is
created with weight $\eta$; every later frame scales the floor's again before the background
test, which looks at the weight in front of the box's component.
--- solution
On the $k$-th frame after the arrival ($k = 0$ the arrival) the floor's weight in front of the
box's component is $(1 - \eta)^{k + 1}$, and the box's value is background once it is below
$1 - c_\mathrm{f} = 0.9$. The pixel is foreground for the frames $k$ with $(1 - \eta)^{k + 1} \ge 0.9$,
that is $k + 1 \le \ln 0.9 / \ln(1 - \eta)$. For $\eta = 0.005$:
$\ln 0.9 / \ln 0.995 = 0.10536 / 0.0050125 = 21.02$, so $k = 0, \dots, 20$: **21 frames**,
close to $c_\mathrm{f} / \eta = 20$. For $\eta = 0.002$: $0.10536 / 0.0020020 = 52.6$, **52 frames**
(about two seconds at 25 frames a second).

=== 15.2 ★ pen and paper | The match test on given numbers
One grey pixel has three components, sorted by weight: $(\pi, \mu, \sigma^2) = (0.7, 100, 16)$,
$(0.25, 125, 16)$ and $(0.05, 200, 50)$. The new value is $I_t = 120$. With $T_\mathrm{g} = 9$,
$T_\mathrm{b} = 16$, $c_\mathrm{f} = 0.1$, $c_\mathrm{T} = 0$ and $\eta = 0.01$: which component owns the value, is the
pixel background, and what are the three weights and the owner's mean and variance after the
update?
--- solution
The squared distances are $d^2 = 20^2 / 16 = 25$, $5^2 / 16 = 1.5625$ and $80^2 / 50 = 128$.
Ownership needs $d^2 < T_\mathrm{g} = 9$: the first component fails (25), the second owns the value.
The weights decay to $0.693, 0.2475, 0.0495$. The background test checks the components up
to the owner: the first is in front of nothing but $d^2 = 25 > T_\mathrm{b} = 16$; the second has
$0.693 < 0.9$ in front of it and $1.5625 < 16$: **background**. The owner gains $\eta$:
$\pi_2 = 0.2575$, so its step is $\eta / \pi_2 = 0.038835$;
$\mu_2 = 125 + 0.038835 \cdot (120 - 125) = 124.806$ and
$\sigma_2^2 = 16 + 0.038835 \cdot (\lVert \delta_2 \rVert^2 - 16)
= 16 + 0.038835 \cdot (5^2 - 16) = 16.350$. The weights $0.693, 0.2575, 0.0495$
already sum to 1, as they must with $c_\mathrm{T} = 0$.

=== 15.3 ★ pen and paper | The running average's memory
The running mean $\mu_t = (1 - \eta)\,\mu_{t-1} + \eta\, I_t$ is a weighted sum of the past
values. Write the weight of $I_{t-j}$, show that the weights sum to 1, and compute the mean
age $\sum_j j\, w_j$ of the values it averages. For values with independent noise of variance
$s^2$, the variance of $\mu_t$ is that of a plain mean of how many values? Evaluate both for
$\eta = 0.05$.
--- solution
Unrolling the recursion, $\mu_t = \sum_{j \ge 0} \eta (1 - \eta)^j I_{t-j}$: weight
$w_j = \eta (1 - \eta)^j$, and $\sum_j w_j = \eta / (1 - (1 - \eta)) = 1$. The mean age is
$\sum_j j \eta (1 - \eta)^j = (1 - \eta) / \eta$: 19 frames for $\eta = 0.05$. The variance is
$s^2 \sum_j w_j^2 = s^2 \eta^2 / (1 - (1 - \eta)^2) = s^2 \eta / (2 - \eta)$, that of a mean of
$(2 - \eta) / \eta$ values: 39 for $\eta = 0.05$. Roughly, a rate $\eta$ remembers the last
$2 / \eta$ frames.

=== 15.4 ★★★ implement | One update of one pixel's mixture
Write `mog_step(x, w, mu, var, eta)` for one grey pixel: `w`, `mu`, `var` are arrays of the
components in use, sorted by weight (heaviest first); return `(background, w, mu, var)` after
one frame, sorted by weight again. Use $T_\mathrm{g} = 9$, $T_\mathrm{b} = 16$, $c_\mathrm{f} = 0.1$, $c_\mathrm{T} = 0$, at most
$M = 5$ components, $\sigma_0^2 = 15$ for a new one and variances clamped to $[4, 75]$. The
order: decay every weight, $\pi_m \leftarrow (1 - \eta)\pi_m$; the owner is the first
component with $d_m^2 < T_\mathrm{g}$; the value is background if one of the components up to the
owner (all of them when none owns it) has $d_m^2 < T_\mathrm{b}$ and the decayed weights in front of
it sum to less than $1 - c_\mathrm{f}$; the owner gains $\eta$ and moves its mean and variance with
the step $\eta / \pi_m$ (its new weight); the weights are divided by their sum. With no owner,
a new component $(\eta, I_t, \sigma_0^2)$ is added (over the lightest when all $M$ are in use)
after the others are scaled by $(1 - \eta)$. The check uses the numbers of exercise 15.2
(owned by the second component, background), the same pixel with $I_t = 250$ (no owner, a
fourth component, foreground) and a single component that sees its own mean.
--- solution
Sort nothing until the end: the components arrive sorted, the decay keeps the order, and only
the owner's weight or a new component can change it. Compute `d2 = (x - mu) ** 2 / var`, take
the first index with `d2 < 9`, test the background on the cumulative decayed weights minus
each one's own (the weight in front of it), update the owner, normalise, append or replace,
and sort with `np.argsort(-w, kind="stable")`.

=== 15.5 ★ use | The threshold $T_\mathrm{b}$ and the false alarms
Make 60 frames of a static 60 × 80 colour image with Gaussian noise of standard deviation
$s = 3$ on every channel, run `MixtureOfGaussians(learning_rate=0.02, var_threshold=T)` for
$T$ = 4, 9, 16 and 25, and measure the share of pixels marked foreground in the last 20
frames. Compare with what a Gaussian model predicts. Careful: the variance update uses the
squared distance **summed over the three channels**, so $\sigma_m^2$ learns $3 s^2$, not $s^2$.
--- solution
With $\sigma_m^2 \approx 3 s^2$, the test $d_m^2 > T$ is $\lVert I_t - \mu_m \rVert^2 / s^2 > 3T$,
and $\lVert I_t - \mu_m \rVert^2 / s^2$ is $\chi^2_3$: the predicted share is
$P(\chi^2_3 > 3T)$, 0.0074 for $T = 4$ and below $10^{-5}$ from $T = 9$ on. The measured share at
$T = 4$ is higher in these frames (about 0.013) because the model has not settled: each mean
started at the first, noisy frame and its error shrinks only by $(1 - \eta)$ a frame, so over
the measured frames it still adds between a tenth and a quarter of $s^2$ to the variance of
$I_t - \mu_m$ on every channel, and the tail of that wider distribution is heavier. Run the
same model for 150 frames and the share over the last 20 falls to the predicted 0.007. At
$T = 9$ about four pixel-frames in $10^5$ are flagged (above the tail too, for the same
reason); from $T = 16$ on none. OpenCV's default $T_\mathrm{b} = 16$ leaves a wide margin on clean noise; real cameras add
compression artefacts and flicker, hence the floor $\sigma^2_{\min}$ on every variance.

=== 15.6 ★★ modify | The minimum area and the shadow
On the yellow ball's noisy half-size frames of the chapter (OpenCV's default rate), count the
frames after the twentieth with two detections, and the frames with exactly one box on the
ball (IoU above 0.5 with the halved ground truth), for `min_area` = 20, 40, 60 and 80. Which
value removes the shadow and keeps the ball, and what would it cost in another scene?
--- solution
The ball's component covers about 70 pixels at half size, its shadow fewer than 40. From
`min_area` = 40 the shadow is gone and the ball is still found on every frame; at 80 the ball
itself is dropped on almost every frame. The window between the two is narrow and belongs to
this scene: a smaller or more distant object, or a larger shadow, closes it. Area separates
objects from noise specks; to separate an object from its shadow, shadow detection (a pixel
darker than the background by a bounded factor, with the same colour) or the shape of the
box is the better tool.
"""


def _close(a, b, atol=1e-4):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and bool(np.allclose(a, b, rtol=0.0, atol=atol))


def mog_step_ok(f):
    """15.4: one update of one grey pixel's mixture, cases worked by hand."""
    w, mu, var = np.array([0.7, 0.25, 0.05]), np.array([100.0, 125, 200]), np.array([16.0, 16, 50])
    # I = 120: d2 = 25, 1.5625, 128; the second owns it (1.5625 < 9); decayed weights
    # 0.693, 0.2475, 0.0495; in front of the second 0.693 < 0.9 and 1.5625 < 16: background.
    # pi_2 = 0.2575, step 0.01 / 0.2575 = 0.038835; mu_2 = 125 - 5 * 0.038835 = 124.80583;
    # var_2 = 16 + 0.038835 * (25 - 16) = 16.34951; the sum is already 1.
    bg, w1, mu1, var1 = f(120.0, w.copy(), mu.copy(), var.copy(), 0.01)
    ok = bool(bg) and _close(w1, [0.693, 0.2575, 0.0495]) \
        and _close(mu1, [100, 124.80583, 200]) and _close(var1, [16, 16.34951, 50])
    # I = 250: d2 = 1406.25, 976.5625, 50: no owner, not background. Decayed and normalised weights
    # 0.7, 0.25, 0.05, scaled by 0.99, and a fourth component (0.01, 250, 15).
    bg, w2, mu2, var2 = f(250.0, w.copy(), mu.copy(), var.copy(), 0.01)
    ok = ok and not bool(bg) and _close(w2, [0.693, 0.2475, 0.0495, 0.01]) \
        and _close(mu2, [100, 125, 200, 250]) and _close(var2, [16, 16, 50, 15])
    # a single component (1, 100, 16) sees 100: weight 0.99 + 0.01 = 1, mean 100,
    # var = 16 + 0.01 * (0 - 16) = 15.84; background (0 in front, d2 = 0)
    bg, w3, mu3, var3 = f(100.0, np.array([1.0]), np.array([100.0]), np.array([16.0]), 0.01)
    return ok and bool(bg) and _close(w3, [1.0]) and _close(mu3, [100.0]) \
        and _close(var3, [15.84])


CHECKS = {"15.4": mog_step_ok}
