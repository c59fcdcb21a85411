"""The exercises of 18_sigma_points_and_proposals: their text, defined once (see
:mod:`trackbook.exercises`), and the auto-checks of its two implementation exercises."""

import numpy as np

STEM = "18_sigma_points_and_proposals"

TEXT = r"""
=== 18.1 ★ pen and paper | Three points for a Gaussian
For $x \sim \mathrm{N}(m, \sigma^2)$ take the points $m$ and $m \pm \gamma_{\mathrm{UT}}\sigma$, with weight $w_0$ on the
centre and $w_1$ on each side point. Derive $w_0$ and $w_1$ from two requirements: the weights
sum to 1, and the weighted variance of the points is $\sigma^2$. Why does the weighted mean not
give a third equation? Then choose $\gamma_{\mathrm{UT}}$ so that the weighted fourth central moment equals the
Gaussian's, $3\sigma^4$, and give the three weights. Which $\lambda_{\mathrm{UT}}$ (for $n = 1$) and
which $\alpha_{\mathrm{UT}}$, $\kappa_{\mathrm{UT}}$ give that $\gamma_{\mathrm{UT}}$?
--- solution
Sum: $w_0 + 2 w_1 = 1$. Variance: $w_1 (\gamma_{\mathrm{UT}}\sigma)^2 + w_1 (-\gamma_{\mathrm{UT}}\sigma)^2 = 2 w_1 \gamma_{\mathrm{UT}}^2 \sigma^2 =
\sigma^2$, so $w_1 = 1/(2\gamma_{\mathrm{UT}}^2)$ and $w_0 = 1 - 1/\gamma_{\mathrm{UT}}^2$. The mean is
$w_0 m + w_1 (m + \gamma_{\mathrm{UT}}\sigma) + w_1 (m - \gamma_{\mathrm{UT}}\sigma) = (w_0 + 2w_1) m = m$ for any weights that sum
to 1: the symmetry of the points does the work. Fourth moment:
$2 w_1 (\gamma_{\mathrm{UT}}\sigma)^4 = \gamma_{\mathrm{UT}}^2 \sigma^4 = 3\sigma^4$ gives $\gamma_{\mathrm{UT}}^2 = 3$, so $w_0 = 2/3$ and
$w_1 = 1/6$. With $\gamma_{\mathrm{UT}}^2 = n + \lambda_{\mathrm{UT}}$ and $n = 1$, $\lambda_{\mathrm{UT}} = 2$; it comes
from $\alpha_{\mathrm{UT}}^2 (1 + \kappa_{\mathrm{UT}}) = 3$, e.g. $\alpha_{\mathrm{UT}} = 1$,
$\kappa_{\mathrm{UT}} = 2 = 3 - n$.

=== 18.2 ★★ pen and paper | The points carry the mean and covariance for any scaling
Show, for Van der Merwe's scaled sigma points in $n$ dimensions, that
$\sum_i W^m_i = 1$, $\sum_i W^m_i \boldsymbol{\chi}_i = m$ and
$\sum_i W^c_i (\boldsymbol{\chi}_i - m)(\boldsymbol{\chi}_i - m)^T = P$ for every $\lambda_{\mathrm{UT}} > -n$ and every
$\beta_{\mathrm{UT}}$. Why does $\beta_{\mathrm{UT}}$ not appear in the result, and why is the
transform then exact for an affine $\varphi(x) = A x + b$?
--- solution
$\sum_i W^m_i = \lambda_{\mathrm{UT}}/(n + \lambda_{\mathrm{UT}}) + 2n/(2(n + \lambda_{\mathrm{UT}}))
= (\lambda_{\mathrm{UT}} + n)/(n + \lambda_{\mathrm{UT}}) = 1$. The points $m \pm L_i$ come in
pairs with equal weights, so each pair contributes $2m/(2(n + \lambda_{\mathrm{UT}}))$ and the
weighted mean is $(W^m_0 + n/(n + \lambda_{\mathrm{UT}}))\, m = m$. In the covariance the centre
term is $W^c_0 \cdot 0$ (that is why $\beta_{\mathrm{UT}}$, which only changes $W^c_0$, drops
out); each pair gives $2 L_i L_i^T / (2(n + \lambda_{\mathrm{UT}}))$ and
$\sum_i L_i L_i^T = L L^T = (n + \lambda_{\mathrm{UT}}) P$, so the sum is $P$. For
$\varphi = Ax + b$ the images are $A\boldsymbol{\chi}_i + b$: their weighted mean is $Am + b$ and their
weighted covariance $A P A^T$ (the mean of the images is the image of the mean, so the centre
term is again zero), which are the exact moments of $Ax + b$.

=== 18.3 ★ pen and paper | The weight under the bootstrap proposal
Start from the weight update
$w_t \propto w_{t-1}\, p(z_t \mid x_t)\, p(x_t \mid x_{t-1}) / q(x_t \mid x_{t-1}, z_t)$.
(a) Show that with $q = p(x_t \mid x_{t-1})$ the weight is $w_{t-1}\, p(z_t \mid x_t)$. (b) Three
particles, resampled at $t - 1$ (equal weights), land where the likelihood is 0.2, 0.6 and
1.2: give their normalised weights. (c) Show that with
$q = p(x_t \mid x_{t-1}, z_t)$ the weight is $w_{t-1}\, p(z_t \mid x_{t-1})$, whatever $x_t$ was
drawn.
--- solution
(a) The transition in the numerator and the proposal in the denominator are the same density
and cancel. (b) Equal previous weights cancel in the normalisation: $0.2 + 0.6 + 1.2 = 2$, so
the weights are $0.1$, $0.3$ and $0.6$. (c) By Bayes' rule
$p(x_t \mid x_{t-1}, z_t) = p(z_t \mid x_t)\, p(x_t \mid x_{t-1}) / p(z_t \mid x_{t-1})$ (the
measurement depends on the past only through $x_t$); dividing the numerator by it leaves
$p(z_t \mid x_{t-1})$, which does not contain $x_t$.

=== 18.4 ★ pen and paper | The effective sample size of given weights
Compute $N_\text{eff} = 1/\sum_i w_i^2$ for the weights $(0.5, 0.25, 0.125, 0.125)$, for four
equal weights and for $(1, 0, 0, 0)$. Then show that $1 \le N_\text{eff} \le N$ for any
normalised weights, with equality exactly in the last two cases.
--- solution
$0.25 + 0.0625 + 2 \cdot 0.015625 = 0.34375$, so $N_\text{eff} = 1/0.34375 \approx 2.91$; equal
weights give $1/(4 \cdot 1/16) = 4$; one weight of 1 gives 1. Upper bound: by Cauchy–Schwarz
$1 = (\sum_i w_i)^2 \le N \sum_i w_i^2$, equality iff all $w_i$ are equal. Lower bound:
$0 \le w_i \le 1$ gives $w_i^2 \le w_i$, so $\sum_i w_i^2 \le \sum_i w_i = 1$, equality iff every
$w_i$ is 0 or 1, i.e. one particle has all the weight.

=== 18.5 ★★ pen and paper | A shifted proposal
Target $p = \mathrm{N}(0, 1)$, proposal $q = \mathrm{N}(\mu, 1)$. Show that the unnormalised weight
$\tilde w = p(x)/q(x)$ has $E_q[\tilde w] = 1$ and $E_q[\tilde w^2] = e^{\mu^2}$, and conclude
that for large $N$, $N_\text{eff} / N \to e^{-\mu^2}$. How many of 1000 samples count for
$\mu = 1$, 2 and 3? Check $\mu = 1$ with $10^6$ samples.
--- hint
$N_\text{eff} = (\sum_i \tilde w_i)^2 / \sum_i \tilde w_i^2$; divide top and bottom by $N^2$ and
let $N \to \infty$.
--- solution
$E_q[\tilde w] = \int p = 1$. $\tilde w = e^{-x^2/2 + (x - \mu)^2/2} = e^{\mu^2/2 - \mu x}$, so
$E_q[\tilde w^2] = \int p(x)^2/q(x)\, dx = e^{\mu^2} \int \mathrm{N}(x; -\mu, 1)\, dx = e^{\mu^2}$ (complete
the square: $-x^2 + (x - \mu)^2/2 = -(x + \mu)^2/2 + \mu^2$). Then
$N_\text{eff}/N = (\frac1N \sum \tilde w_i)^2 / (\frac1N \sum \tilde w_i^2) \to 1/e^{\mu^2}$. For
1000 samples: about 368, 18 and 0.1 — the last means that a single sample holds nearly all the
weight, and the variance of $\tilde w$ is so large that a run of 1000 samples rarely shows the
limit. With $10^6$ samples and $\mu = 1$ the measured ratio is close to $e^{-1} \approx 0.368$.

=== 18.6 ★★ modify | The spread of the sigma points
In the polar-conversion comparison of the chapter, run the unscented transform with
$\alpha_{\mathrm{UT}} \in \{10^{-3}, 0.3, 1\}$ ($\beta_{\mathrm{UT}} = 2$, $\kappa_{\mathrm{UT}} = 0$) at
$\sigma_\theta = 0.3$ and $0.6$ rad. Which gives the mean closest to the exact one, and which the
$y$ standard deviation closest to the Monte Carlo one? Explain the mean with a Taylor
expansion of $E[\cos(\theta - \theta_0)]$, $\theta_0 = \pi/2$ the mean bearing.
--- solution
The side points along $\theta$ lie at $\pm \gamma_{\mathrm{UT}}\sigma_\theta$ with $\gamma_{\mathrm{UT}}^2 = n + \lambda_{\mathrm{UT}} =
2\alpha_{\mathrm{UT}}^2$, and the unscented estimate of $E[\cos(\theta - \theta_0)]$ is
$1 - (1 - \cos \gamma_{\mathrm{UT}}\sigma_\theta)/\gamma_{\mathrm{UT}}^2 = 1 - \sigma_\theta^2/2 + \gamma_{\mathrm{UT}}^2\sigma_\theta^4/24 - \dots$, against
the exact $e^{-\sigma_\theta^2/2} = 1 - \sigma_\theta^2/2 + \sigma_\theta^4/8 - \dots$. A tiny
$\alpha_{\mathrm{UT}}$ keeps only the second-order term (like a second-order Taylor expansion);
$\alpha_{\mathrm{UT}} = 1$ ($\gamma_{\mathrm{UT}}^2 = 2$) gets closer to the fourth-order term, and $\gamma_{\mathrm{UT}}^2 = 3$ (the
$\kappa_{\mathrm{UT}} = 1$ setting of the chapter) matches it: larger spread, better mean here, at
both bearing noises. The covariance has no winner: $\alpha_{\mathrm{UT}} = 1$ gives the $x$
spread closest to Monte Carlo but the $y$ spread farthest (the ellipse too deep), the tiny
$\alpha_{\mathrm{UT}}$ the reverse. No setting gets every moment right, which is why the
parameters are tuning knobs and not constants.

=== 18.7 ★★★ implement | Van der Merwe's sigma points and weights
Write `sigma_points(m, P, alpha, beta, kappa)` returning `(chi, Wm, Wc)`: the $2n + 1$ points
as the rows of `chi`, in the order $\boldsymbol{\chi}_0 = m$, $\boldsymbol{\chi}_i = m + L_i$, $\boldsymbol{\chi}_{n+i} = m - L_i$
($i = 1 \dots n$, $L_i$ the $i$-th column of a matrix $L$ with $L L^T = (n + \lambda_{\mathrm{UT}})P$,
e.g. the lower Cholesky factor), and the two weight vectors. `m` is a 1-D array of length
$n$ and `P` an $n \times n$ array. By hand first: $n = 1$, $m = 5$, $P = 4$,
$\alpha_{\mathrm{UT}} = 1$, $\beta_{\mathrm{UT}} = 0$, $\kappa_{\mathrm{UT}} = 2$ gives
$\lambda_{\mathrm{UT}} = 2$, points $5$ and $5 \pm \sqrt{12}$, and $W^m = W^c = (2/3, 1/6, 1/6)$.
For $n = 2$, $m = 0$, $P = \mathrm{diag}(1, 4)$, $\alpha_{\mathrm{UT}} = 1$,
$\beta_{\mathrm{UT}} = 2$, $\kappa_{\mathrm{UT}} = 1$: $\lambda_{\mathrm{UT}} = 1$, points $(0, 0)$,
$(\sqrt3, 0)$, $(0, 2\sqrt3)$, $(-\sqrt3, 0)$, $(0, -2\sqrt3)$, $W^m_0 = 1/3$, $W^c_0 = 7/3$, all
others $1/6$. The check uses both cases, and on a random full $P$ verifies that the weighted
points reproduce $m$ and $P$.
--- solution
$\lambda_{\mathrm{UT}} = \alpha_{\mathrm{UT}}^2 (n + \kappa_{\mathrm{UT}}) - n$;
`L = np.linalg.cholesky((n + lam) * P)`; `chi = np.vstack([m, m + L.T, m - L.T])` (the rows of
$L^T$ are the columns of $L$); `Wm = np.full(2 * n + 1, 1 / (2 * (n + lam)))`, `Wc = Wm.copy()`,
`Wm[0] = lam / (n + lam)`, `Wc[0] = Wm[0] + 1 - alpha**2 + beta`.

=== 18.8 ★★★ implement | Self-normalised importance sampling
Write `snis(x, log_p, log_q, phi)` returning `(estimate, n_eff)`: `x` holds $N$ samples of the
proposal, `log_p` and `log_q` are functions giving $\log \tilde p(x)$ (the target up to a
constant) and $\log q(x)$ for an array, and `phi` the function to average. Normalise the
weights without overflow or underflow: log-weights of $-2000$ and $-2001$ must still give
weights in the ratio $e : 1$. By hand: $x = (0, 1)$ with $\log\tilde p - \log q = (\log 1,
\log 3)$ gives weights $(1/4, 3/4)$, the estimate of $E[x]$ is $3/4$ and
$N_\text{eff} = 1/(1/16 + 9/16) = 1.6$. The check uses that case, the $-2000$ case, and a case
where the target's constant must cancel.
--- solution
`lw = log_p(x) - log_q(x)`; `w = np.exp(lw - lw.max())` (the largest becomes 1, so nothing
overflows and the sum is at least 1); `w /= w.sum()`; return `w @ phi(x)` and
`1 / np.sum(w ** 2)`.
"""


def _close(a, b, atol=1e-9):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and bool(np.allclose(a, b, rtol=0.0, atol=atol))


def sigma_points_ok(f):
    """18.7: Van der Merwe's scaled sigma points and weights."""
    # n = 1, m = 5, P = 4, α = 1, β = 0, κ = 2: λ = 1·3 − 1 = 2, n + λ = 3, L = √12;
    # Wm = Wc = (2/3, 1/6, 1/6)
    chi, Wm, Wc = f(np.array([5.0]), np.array([[4.0]]), 1.0, 0.0, 2.0)
    if not (_close(np.ravel(chi), [5, 5 + 12 ** 0.5, 5 - 12 ** 0.5])
            and _close(Wm, [2 / 3, 1 / 6, 1 / 6]) and _close(Wc, [2 / 3, 1 / 6, 1 / 6])):
        return False
    # n = 2, m = 0, P = diag(1, 4), α = 1, β = 2, κ = 1: λ = 3 − 2 = 1, n + λ = 3,
    # L = diag(√3, 2√3); Wm0 = 1/3, Wc0 = 1/3 + 1 − 1 + 2 = 7/3, the rest 1/(2·3) = 1/6
    r3 = 3 ** 0.5
    chi, Wm, Wc = f(np.zeros(2), np.diag([1.0, 4.0]), 1.0, 2.0, 1.0)
    if not (_close(chi, [[0, 0], [r3, 0], [0, 2 * r3], [-r3, 0], [0, -2 * r3]])
            and _close(Wm, [1 / 3] + [1 / 6] * 4) and _close(Wc, [7 / 3] + [1 / 6] * 4)):
        return False
    # a full P, α = 0.5, β = 2, κ = 0 (n = 3: λ = −2.25, n + λ = 0.75): the points are
    # symmetric pairs about m, and the weighted mean and covariance are m and P (exercise 18.2)
    m = np.array([1.0, -2.0, 0.5])
    A = np.array([[2.0, 0.3, -0.4], [0.3, 1.0, 0.2], [-0.4, 0.2, 0.7]])
    chi, Wm, Wc = f(m, A, 0.5, 2.0, 0.0)
    d = np.asarray(chi) - m
    return (np.shape(chi) == (7, 3) and _close(chi[0], m) and _close(d[1:4], -d[4:7])
            and _close(Wm[1:], np.full(6, 1 / 1.5)) and _close(Wm[0], -3.0)
            and _close(Wm @ chi, m) and _close(d.T @ (d * np.asarray(Wc)[:, None]), A))


def snis_ok(f):
    """18.8: self-normalised importance sampling with its effective sample size."""
    # by hand: ratios 1 and 3 -> weights 1/4, 3/4; E[x] = 3/4; N_eff = 1 / (1/16 + 9/16) = 1.6
    est, n_eff = f(np.array([0.0, 1.0]), lambda x: np.log(1.0 + 2.0 * x),
                   lambda x: np.zeros_like(x), lambda x: x)
    if not (_close(est, 0.75) and _close(n_eff, 1.6)):
        return False
    # log-weights −2000 and −2001: weights e/(1 + e) and 1/(1 + e), in the ratio e : 1
    e = np.e
    est, n_eff = f(np.array([0.0, 1.0]), lambda x: -2000.0 - x, lambda x: np.zeros_like(x),
                   lambda x: x)
    if not (_close(est, 1 / (1 + e)) and _close(n_eff, (1 + e) ** 2 / (e ** 2 + 1))):
        return False
    # the target's constant cancels: log p̃ = log p + 50 for p = N(0, 1), q = N(0, 2²) at
    # x = (−2, 0, 2); ratios p/q ∝ exp(−x²/2 + x²/8) = (e^−1.5, 1, e^−1.5);
    # E[x²] estimate = 2·4·e^−1.5 / (1 + 2 e^−1.5)
    x = np.array([-2.0, 0.0, 2.0])
    est, _ = f(x, lambda x: -x ** 2 / 2 + 50.0, lambda x: -x ** 2 / 8 - np.log(2.0),
               lambda x: x ** 2)
    r = np.exp(-1.5)
    return _close(est, 8 * r / (1 + 2 * r))


CHECKS = {"18.7": sigma_points_ok, "18.8": snis_ok}
