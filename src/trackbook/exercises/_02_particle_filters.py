"""The exercises of 02_particle_filters: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "02_particle_filters"

TEXT = r"""
=== 2.1 ★★ modify | Copies under multinomial resampling
Multinomial resampling draws $N$ particles independently with probabilities $w_i$. How many
copies of a particle of weight $w_i$ do you expect, and with what variance? Write
`moments(w, N)` returning the expected number of copies of each particle and its variance (two
arrays), and compare them with 2000 seeded resamplings of a 20-particle set with one heavy
particle ($w = 0.4$).
--- solution
The copies of particle $i$ count successes in $N$ independent draws of probability $w_i$:
they are Binomial$(N, w_i)$, with mean $N w_i$ and variance $N w_i (1 - w_i)$.

=== 2.2 ★ use | How many particles?
Run `color-pf` (seed 0) on `robot-corridor-day` with 20, 100 and 400 particles
(`n_particles=`). Answer a dict `{20: auc, 100: auc, 400: auc}`. How does the AUC move, and what
does `scores["ms_median"]` do at the same time? (Timings depend on the machine.)
--- solution
More particles cover the posterior better: the AUC rises, with diminishing returns. The time
per frame rises too, because every particle needs its own histogram (by how much depends on
the machine and on what else runs on it).

=== 2.3 ★★ modify | Which departure matters more?
`color-pf` departs from its paper in σ and in the start (two of the departures of the
{doc}`case study <case_study_lee2012>`): the paper preset weighs with
$\sigma_\mathrm{color} = 0.4$ and spreads the first particles over the whole frame, the book's
defaults weigh with $\sigma_\mathrm{color} = 0.2$ and start them around the given box.
Which of the two matters more on the day clip? The departures are the filter's, so leave
the failure layer out: run the paper preset,
`trackers.create("color-pf", preset="paper", seed=0, failure=False)`, then the paper preset
with only `sigma_color=0.2`, then with only `init="box"`, each through
`evaluate(tracker, "robot-corridor-day")`, and give the two changes as
`{"sigma": ..., "init": ...}` (each run's AUC minus the paper preset's).
--- solution
σ. With the paper preset's other settings, σ = 0.2 lifts the AUC of seed 0 on the day clip
several times as much as starting the particles around the given box does (the exercises
appendix prints the three AUCs below the exercise): at σ = 0.4 the weights hardly separate
good particles from poor ones. With the failure layer on, the comparison blurs: the layer
holds the paper preset's box through the dim frames where its own estimate drifts, which
rescues it more than either departure. One clip and one seed are a hint, not a measurement;
the case study's mean over seven sequences and three seeds puts the book's defaults ahead of
each section V value.

=== 2.4 ★★ modify | A look-alike close by
In the 1-D corridor example of {doc}`the Bayes filter <21_bayes_filter>`, move the look-alike
to 45 m (as strong as before, 0.6 of the target). How many peaks does the grid posterior have now, where, and how do
its mean and spread compare with the look-alike at 60 m? How far from the target must the
look-alike be (same prediction) before the posterior has a second peak?
--- solution
At 45 m the two likelihood bumps (width 3 m each, 5 m apart) overlap so much that their sum
has a single peak: two Gaussians of equal width σ apart by less than 2σ add up to one hump.
The prediction then multiplies one hump by another, and the posterior has **one** peak, just
below 40 m, not two (the exercises appendix prints the peaks, means and spreads below the
exercise). The look-alike is not vetoed but absorbed: it pulls
the mean a little towards 45 m and widens the posterior compared with the look-alike at 60 m,
whose bump the prediction suppresses (only a faint second maximum is left of it). A single
Gaussian describes the 45 m posterior well; the belief a Gaussian cannot hold is the one with
two separated peaks, which needs the look-alike farther away: on the grid, in steps of 0.5 m,
a second peak appears first with the look-alike at 54 m, 14 m from the target. That is where
particles, which keep every hump, pay off.

=== 2.5 ★★★ implement | Stratified resampling from scratch
Write `my_stratified(w, rng)`: stratified resampling with one pointer $(k + u_k)/N$ in each
stratum $k = 0, \dots, N-1$, the $u_k$ drawn by **one** call `rng.random(N)`, and for each
pointer the smallest $i$ with $c_i \ge$ pointer, $c$ the cumulative weights (set $c_N = 1$
exactly, against round-off). By hand first: $w = (0.1, 0.2, 0.3, 0.4)$ has
$c = (0.1, 0.3, 0.6, 1)$; with every $u_k = 0.5$ the pointers are 0.125, 0.375, 0.625 and
0.875, and the indices $(1, 2, 3, 3)$. The check hands your function a stand-in for `rng`
whose `random` returns chosen $u_k$, and compares with indices worked out by hand.
--- solution
Each stratum $[k/N, (k+1)/N)$ gets exactly one pointer. Particle $i$ owns the interval
$(c_{i-1}, c_i]$ of length $w_i$. Every stratum lying wholly inside that interval gives it
exactly one copy; the at most two strata its ends cut into give it one copy each or none, by
chance, independently. An interval of length $w_i$ holds at least $\lfloor N w_i \rfloor - 1$
whole strata and touches at most $\lceil N w_i \rceil + 1$, so the particle gets between
$\max(0, \lfloor N w_i \rfloor - 1)$ and $\lceil N w_i \rceil + 1$ copies: always less than
2 away from $N w_i$, and both ends occur for some positions of the interval. For
$N w_i = 1.5$ that is 0 to 3 copies: with the interval at $(0.3/N, 1.8/N]$ no pointer lands
in it with probability $0.3 \cdot 0.2 = 0.06$, and with it at $(0.9/N, 2.4/N]$ three do with
probability $0.1 \cdot 0.4 = 0.04$. The count's variance is that of at most two coin flips,
at most $1/2$ whatever $N w_i$, where multinomial resampling's $N w_i (1 - w_i)$ grows with
$N w_i$; but it is not held to $\lfloor N w_i \rfloor$ or $\lceil N w_i \rceil$ as systematic
resampling's is, whose pointers move together. With
$u = (0.2, 0.9, 0.1, 0)$ the pointers are 0.05, 0.475, 0.525 and 0.75: indices
$(0, 2, 2, 3)$.

=== 2.6 ★★ pen and paper | Importance weights under a proposal
Factored sampling draws its samples from the prior $p(x)$. Suppose
they come from another density, a *proposal* $q(x)$, instead. Show that the weights

$$w^{(i)} \propto \frac{p(z \mid x^{(i)})\, p(x^{(i)})}{q(x^{(i)})}$$

make the weighted set stand for the posterior, and that they reduce to factored sampling's weights when $q = p$. Then, by hand:
prior $\mathrm{N}(0, 1)$, proposal $\mathrm{N}(1, 1)$, a likelihood that is the same everywhere, and the two
samples $x^{(1)} = 0$, $x^{(2)} = 1$. What are their normalised weights?
--- solution
For any function $\varphi$,

$$\begin{aligned} & E_{p(x \mid z)}[\varphi] \\
&\quad = \int \varphi(x)\, \frac{p(z \mid x)\, p(x)}{p(z)}\, dx \\
&\quad = \int \varphi(x)\, \frac{p(z \mid x)\, p(x)}{p(z)\, q(x)}\, q(x)\, dx \\
&\quad = \frac{1}{p(z)}\, E_q\!\left[\varphi(x)\, \frac{p(z \mid x)\, p(x)}{q(x)}\right], \end{aligned}$$

so averaging $\varphi$ over samples of $q$ with weights proportional to $p(z \mid x) p(x) / q(x)$,
normalised to sum 1, estimates the posterior average (the weights' mean before normalising
estimates $p(z)$). With $q = p$ the ratio
$p/q$ is 1 and the weight is the likelihood alone, $w^{(i)} \propto p(z \mid x^{(i)})$. In the
hand case the likelihood cancels in the normalisation and
$p(x)/q(x) = e^{-x^2/2} / e^{-(x-1)^2/2}$ $= e^{1/2 - x}$: $e^{1/2}$ for $x^{(1)}$, $e^{-1/2}$ for $x^{(2)}$, so the
normalised weights are $1/(1 + e^{-1}) \approx 0.731$ and $e^{-1}/(1 + e^{-1}) \approx 0.269$.
The sample the proposal over-produces ($x = 1$, its mean) is weighed down.

=== 2.7 ★★ modify | Systematic resampling is tight
Systematic resampling uses one random offset $u \sim \mathrm{U}[0, 1/N)$ and the $N$ evenly spaced
pointers $u + k/N$. Write `bounds(w, N)` returning, for each particle, the smallest and the
largest number of copies it can get (two integer arrays), and verify on 300 random weight
vectors that the copies of `systematic_resample` always lie within your bounds and that the
bounds are at most 1 apart.
--- solution
Particle $i$ owns an interval of length $w_i$ of the cumulative weights; pointers $1/N$ apart
hit it $\lfloor N w_i \rfloor$ or $\lceil N w_i \rceil$ times, whatever the offset (exactly
$N w_i$ times when that is a whole number). Multinomial resampling can give any number from 0
to $N$: systematic resampling adds far less noise. One caution for checks: where $N w_i$ is a
whole number, the floating-point cumulative sum may be off by a hair and hand the particle one
copy fewer or more; random weights (as in the check) never land there.

=== 2.8 ★★★ implement | Systematic resampling from scratch
Write `my_systematic(w, rng)`: draw one offset with a single call `u = rng.random() / N`, form
the pointers $u + k/N$ for $k = 0, \dots, N-1$, and return for each pointer the smallest index
$i$ with $c_i \ge$ pointer, $c$ the cumulative weights (set $c_N = 1$ exactly). By hand:
$w = (0.7, 0.1, 0.1, 0.1)$, `rng.random()` = 0.5, so $u = 0.125$: pointers 0.125, 0.375, 0.625,
0.875 against $c = (0.7, 0.8, 0.9, 1)$, indices $(0, 0, 0, 2)$. The check uses that case and three more worked by hand.
--- solution
```python
def my_systematic(w, rng):
    n = len(w)
    c = np.cumsum(w)
    c[-1] = 1.0             # round-off must not leave c_N below 1
    pointers = rng.random() / n + np.arange(n) / n
    return np.searchsorted(c, pointers, side="left")
```
The cumulative weights $c_i$ lay the particles side by side on $[0, 1]$: particle $i$ owns
$(c_{i-1}, c_i]$, of length $w_i$. Setting the last one to 1 exactly matters because round-off
can leave the sum of the weights a hair below 1, and a pointer above it would find no
particle. The single call `rng.random() / N` gives the offset $u \in [0, 1/N)$, and
$u + k/N$, $k = 0, \dots, N-1$, are the $N$ pointers, $1/N$ apart and all below 1.
`np.searchsorted(c, pointers, side="left")` returns, for each pointer, the first $i$ with
$c_i \ge$ pointer, the rule of the statement; since the pointers are sorted, a loop that walks
$i$ forward once through the particles does the same. By hand, with
$w = (0.7, 0.1, 0.1, 0.1)$ and $u = 0.125$: the pointers 0.125, 0.375 and 0.625 are all
$\le c_0 = 0.7$ and pick particle 0; 0.875 is above $c_1 = 0.8$ but not above $c_2 = 0.9$ and
picks particle 2: indices $(0, 0, 0, 2)$. Particle 0 gets 3 copies for $N w_0 = 2.8$,
particle 2 one for $N w_2 = 0.4$, particles 1 and 3 none for 0.4 each: every count is
$\lfloor N w_i \rfloor$ or $\lceil N w_i \rceil$, as exercise 2.7 shows it must be. The
exercises appendix runs this solution through the check.

=== 2.9 ★ pen and paper | The effective sample size and its bounds
The effective sample size of normalised weights ($w^{(i)} \ge 0$,
$\sum_{i=1}^N w^{(i)} = 1$) is $N_{\mathrm{eff}} = 1 / \sum_{i=1}^N (w^{(i)})^2$. Show that
$1 \le N_{\mathrm{eff}} \le N$, that $N_{\mathrm{eff}} = 1$ only when one particle has all
the weight and $N_{\mathrm{eff}} = N$ only when all weights are equal, and that $k$ particles
sharing the weight equally (the others at 0) give $N_{\mathrm{eff}} = k$. Then compute
$N_{\mathrm{eff}}$ of $w = (\tfrac12, \tfrac14, \tfrac18, \tfrac18)$.
--- hint
For the upper bound, apply the Cauchy–Schwarz inequality to the vectors
$(w^{(1)}, \dots, w^{(N)})$ and $(1, \dots, 1)$.
--- solution
Lower bound: every $w^{(i)} \le 1$, so $(w^{(i)})^2 \le w^{(i)}$ and
$\sum_i (w^{(i)})^2 \le \sum_i w^{(i)} = 1$: $N_{\mathrm{eff}} \ge 1$. Equality needs
$(w^{(i)})^2 = w^{(i)}$ for every $i$, so every weight is 0 or 1: one particle has weight 1,
the others 0. Upper bound: by Cauchy–Schwarz,

$$1 = \Bigl(\sum_i w^{(i)} \cdot 1\Bigr)^2 \le \sum_i (w^{(i)})^2 \cdot \sum_i 1^2
= N \sum_i (w^{(i)})^2,$$

so $N_{\mathrm{eff}} \le N$, with equality only when $w$ is parallel to $(1, \dots, 1)$:
every $w^{(i)} = 1/N$. With $k$ weights $1/k$ and the rest 0,
$\sum_i (w^{(i)})^2 = k / k^2 = 1/k$ and $N_{\mathrm{eff}} = k$: $N_{\mathrm{eff}}$ reads as
the number of equally weighted particles the set is worth. For the vector,
$\sum_i (w^{(i)})^2 = \tfrac14 + \tfrac1{16} + \tfrac1{64} + \tfrac1{64}
= \tfrac{16 + 4 + 1 + 1}{64} = \tfrac{11}{32}$, so $N_{\mathrm{eff}} = \tfrac{32}{11}
\approx 2.91$ of 4: more than the 2 of two equal particles, less than the 4 of four.

=== 2.10 ★★ pen and paper | Weigh and resample four particles by hand
Four particles have the squared Bhattacharyya distances $D^2 = (0, 0.08, 0.16, 0.24)$ to the
reference histogram. (a) With the likelihood of eq. 10 and $\sigma_\mathrm{color} = 0.2$, give their
normalised weights $w^{(i)}$ and $N_{\mathrm{eff}}$; why does the factor
$1/\sqrt{2\pi\sigma_\mathrm{color}^2}$ not matter? (b) Resample them systematically with the offset
$u = 0.05$: the pointers are $u + k/4$, $k = 0, \dots, 3$, and each picks the smallest $i$
with $c_i \ge$ pointer, $c_i$ the cumulative weights (particles counted from 0). How many
copies does each particle get, and does each count lie between $\lfloor N w^{(i)} \rfloor$
and $\lceil N w^{(i)} \rceil$? (c) Repeat (a) and (b) with $\sigma_\mathrm{color} = 0.4$. What does
the larger σ do to the weights and to the copies? (Use a calculator for the exponentials.)
--- solution
(a) The factor $1/\sqrt{2\pi\sigma_\mathrm{color}^2}$ is the same for every particle and cancels when
the weights are divided by their sum. With $2\sigma_\mathrm{color}^2 = 0.08$ the exponents
$D^2 / 2\sigma_\mathrm{color}^2$ are $(0, 1, 2, 3)$, so the likelihoods are proportional to
$(1, e^{-1}, e^{-2}, e^{-3}) \approx (1, 0.368, 0.135, 0.050)$, of sum $\approx 1.553$:
$w \approx (0.644, 0.237, 0.087, 0.032)$. Then
$\sum_i (w^{(i)})^2 \approx 0.4146 + 0.0561 + 0.0076 + 0.0010 \approx 0.479$ and
$N_{\mathrm{eff}} \approx 2.09$.

(b) The cumulative weights are $c \approx (0.644, 0.881, 0.968, 1)$ and the pointers 0.05,
0.30, 0.55 and 0.80. The first three are $\le c_0$ and pick particle 0; 0.80 lies above
$c_0$ and below $c_1$ and picks particle 1: indices $(0, 0, 0, 1)$, copies $(3, 1, 0, 0)$.
$N w \approx (2.58, 0.95, 0.35, 0.13)$, so every count is the floor or the ceiling of its
$N w^{(i)}$, as systematic resampling guarantees (exercise 2.7).

(c) With $2\sigma_\mathrm{color}^2 = 0.32$ the exponents are $(0, 0.25, 0.5, 0.75)$ and the
likelihoods are proportional to $(1, 0.779, 0.607, 0.472)$, of sum $\approx 2.858$:
$w \approx (0.350, 0.273, 0.212, 0.165)$, $\sum_i (w^{(i)})^2 \approx 0.269$ and
$N_{\mathrm{eff}} \approx 3.72$. Now $c \approx (0.350, 0.622, 0.835, 1)$: 0.05 and 0.30 pick
particle 0, 0.55 particle 1 and 0.80 particle 2, copies $(2, 1, 1, 0)$, again floor or ceiling
of $N w \approx (1.40, 1.09, 0.85, 0.66)$. The larger σ flattens the weights: $N_{\mathrm{eff}}$
is close to 4, the worst particle keeps about a sixth of the weight, and three particles
survive the resampling instead of two. With σ = 0.2 the best particle takes three of the four
copies. Flat weights let the estimate drift with the cloud; too sharp ones collapse it onto
a single particle.
"""
