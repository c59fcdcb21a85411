"""The exercises of 17_kalman_filter_design: their text, defined once (see
:mod:`trackbook.exercises`), and the auto-checks of its ★★★ exercises."""

import numpy as np

STEM = "17_kalman_filter_design"

TEXT = r"""
=== 17.1 ★ pen and paper | The gain of a scaled sensor
A sensor measures $z = h\,x + v$ for a known number $h \ne 0$ (a camera that reports
positions in another unit, say), with $v$ of variance $\sigma_2^2$, independent of the prior
error (variance $\sigma_1^2$). Write the update as $\hat x^+ = \hat x^- + K(z - h\hat x^-)$,
find the error variance of $\hat x^+$ as a function of $K$, minimise it, and give the
minimum. Check that $h = 1$ gives the gain of the Kalman chapter.
--- solution
The error is $x - \hat x^+ = (1 - Kh)(x - \hat x^-) - Kv$, so its variance is
$(1 - Kh)^2\sigma_1^2 + K^2\sigma_2^2$. The derivative $-2h(1 - Kh)\sigma_1^2 + 2K\sigma_2^2$ is
zero at $K = h\sigma_1^2/(h^2\sigma_1^2 + \sigma_2^2)$: the matrix formula
$P^-H^T(HP^-H^T + R)^{-1}$ with $H = h$. There
$1 - Kh = \sigma_2^2/(h^2\sigma_1^2 + \sigma_2^2)$ and the variance is
$\sigma_1^2\sigma_2^2/(h^2\sigma_1^2 + \sigma_2^2) = (1 - Kh)\sigma_1^2$. With $h = 1$:
$K = \sigma_1^2/(\sigma_1^2 + \sigma_2^2)$.

=== 17.2 ★★ pen and paper | The Joseph form at the optimal gain
Show that $(I-KH)P^-(I-KH)^T + KRK^T = (I-KH)P^-$ when $K = P^-H^TS^{-1}$,
$S = HP^-H^T + R$. Then take the scalar case $P^- = 4$, $H = 1$, $R = 12$ and the
non-optimal gain $K = 1/2$: compute both expressions. Which one is the variance of the error
of $\hat x^+ = \hat x^- + \tfrac12(z - \hat x^-)$?
--- solution
Expand:

$$\begin{aligned}
&(I-KH)P^-(I-KH)^T + KRK^T\\
&\quad = (I-KH)P^- \\
&\quad\; - (I-KH)P^-H^TK^T + KRK^T,\\[4pt]
&-(I-KH)P^-H^TK^T + KRK^T\\
&\quad = -P^-H^TK^T \\
&\qquad + K(HP^-H^T + R)K^T \\
&\quad = -P^-H^TK^T + KSK^T .
\end{aligned}$$

At the optimal gain $KS = P^-H^T$, so $KSK^T = P^-H^TK^T$ and the two cancel. With $K = 1/2$: the
Joseph form is $\tfrac14 \cdot 4 + \tfrac14 \cdot 12 = 4$, the short form
$\tfrac12 \cdot 4 = 2$. The error is $\tfrac12$(prior error) $+ \tfrac12$(sensor error) with
variance $1 + 3 = 4$: the Joseph form is the truth; the short form claims half of it (the
optimal $K = 1/4$ gives 3 with both).

=== 17.3 ★ pen and paper | The χ² band
A four-state filter ($n_x = 4$) is run on $M = 25$ simulated tracks. The $\chi^2$ table gives
for 100 degrees of freedom the 2.5 % point 74.22 and the 97.5 % point 129.56. Compute the
95 % band of the average NEES. The average NEES at the last step is 5.6: what do you
conclude, and which of $Q$, $R$ would you change first? Without a table, the normal
approximation $\chi^2_d \approx \mathrm{N}(d, 2d)$ gives which band?
--- solution
$M\,\overline{\mathrm{NEES}} \sim \chi^2_{100}$, so the band is $[74.22/25, 129.56/25] =
[2.97, 5.18]$. 5.6 is above it: the filter is overconfident, its $P$ too small. If the NIS
(which includes $R$) is inside its band, raise $Q$ first; a NIS also too high can mean $R$ is
too small. The normal approximation gives $100 \pm 1.96\sqrt{200} = 100 \pm 27.7$, so
$[2.89, 5.11]$: close, a little too far left, because $\chi^2$ is skewed to the right.

=== 17.4 ★★★ implement | One step of the RTS smoother
Implement `rts_step(x, P, x_next_s, P_next_s, F, Q)`: from the filter's posterior $\hat x_k^+,
P_k^+$ and the smoothed $\hat x_{k+1}^s, P_{k+1}^s$, return $(\hat x_k^s, P_k^s)$ with the
chapter's equations (arrays in, arrays out; $1 \times 1$ matrices for one number). By hand
first: $F = Q = P_k^+ = 1$, $\hat x_k^+ = 0$, $\hat x_{k+1}^s = 2$, $P_{k+1}^s = 1$ gives
$P_{k+1}^- = 2$, $G_k = 1/2$, $\hat x_k^s = 1$, $P_k^s = 3/4$. The check uses that case, the
case where the smoothed future is exactly the prediction (nothing changes), and a
constant-velocity step with $Q = 0$.
--- hint
With $Q = 0$ and an invertible $F$ the gain is $G_k = F^{-1}$: the smoother runs the motion
model backwards.
--- solution
```python
def rts_step(x, P, x_next_s, P_next_s, F, Q):
    P_pred = F @ P @ F.T + Q
    G = P @ F.T @ np.linalg.inv(P_pred)
    return x + G @ (x_next_s - F @ x), P + G @ (P_next_s - P_pred) @ G.T
```
With $Q = 0$, $F = \begin{bmatrix}1 & 1\\0 & 1\end{bmatrix}$, $P_k^+ = I$: $P_{k+1}^- = FF^T$,
$G_k = F^T(FF^T)^{-1} = F^{-1}$, so $\hat x_k^s = F^{-1}\hat x_{k+1}^s$ and
$P_k^s = F^{-1}P_{k+1}^sF^{-T}$; for $\hat x_{k+1}^s = (3, 1)$ and $P_{k+1}^s = I/2$ these are
$(2, 1)$ and $\begin{bmatrix}1 & -1/2\\-1/2 & 1/2\end{bmatrix}$.

=== 17.5 ★★★ implement | The IMM's mixing probabilities
Implement `mixing(mu, Pi)` returning $(\bar c, \omega)$ with $\bar c_j = \sum_i \pi_{ij}\mu_i$
and $\omega_{ij} = \pi_{ij}\mu_i/\bar c_j$ (NumPy arrays; `omega[i, j]` is $\omega_{ij}$).
By hand first: $\mu = (0.5, 0.5)$ and $\Pi = \begin{bmatrix}0.9 & 0.1\\0.2 & 0.8\end{bmatrix}$
give $\bar c = (0.55, 0.45)$, $\omega_{11} = 0.45/0.55 = 9/11$, $\omega_{21} = 2/11$,
$\omega_{12} = 1/9$, $\omega_{22} = 8/9$. Why does each column of $\omega$ sum to 1, and what
is $\omega$ when $\mu = (1, 0)$?
--- solution
```python
def mixing(mu, Pi):
    mu, Pi = np.asarray(mu, float), np.asarray(Pi, float)
    cbar = mu @ Pi
    return cbar, Pi * mu[:, None] / cbar[None, :]
```
Column $j$ sums to $\sum_i \pi_{ij}\mu_i/\bar c_j = 1$ by the definition of $\bar c_j$: it is
the distribution of the previous mode given the current one. With $\mu = (1, 0)$ every
target came from mode 1, whatever mode it is in now: both columns are $(1, 0)$, and both
filters restart from filter 1's estimate.

=== 17.6 ★★ modify | The NIS on the ball
Run the constant-velocity filter of the IMM section (`cv`) alone on one draw of the simulated
sensor, record $\mathrm{NIS}_k$ with `nis(kf.y, kf.S)` after each update, and test the pooled
values with `consistency_test(..., 2)`. Then repeat with $Q = 0.01\,I$ and $Q = 10\,I$. Which
$Q$ does the NIS call consistent, and which frames carry most of the NIS?
--- solution
The NIS needs no ground truth, so this is the test one could run on a real tracker's
measurements. With $Q = I$ (the first draw, seed 0) the pooled NIS, about 3.2, is above the
band $[1.66, 2.37]$ of 119 values: overconfident. The bounces carry far more than their share:
about 43 % of its sum comes from the bounce frames and the four after each (13 % of the
frames); away from them its mean is about 2.1.
$Q = 0.01\,I$ is far worse (an average near 40: it lags on every arc); $Q = 10\,I$ falls
below the band (underconfident: $S$ too wide on the arcs). No single $Q$ describes both the
arcs and the bounces: the NIS says the model, not only its noise, is wrong — the case for
several models.

=== 17.7 ★★ modify | How sticky is the manoeuvre mode?
In the IMM comparison change $\pi_{22}$ (the probability that a manoeuvre continues) from
0.5 to 0.1 and to 0.9, keeping rows summing to 1, and $\pi_{12}$ from 0.05 to 0.01 and 0.2.
How do the RMSE, the window area and the mode-probability curve change?
--- solution
Over the 20 draws (rows of $\Pi$ kept summing to 1; the chapter's setting gives about 5.3 px
near the bounces and a window of about 1,700 px²): $\pi_{22} = 0.1$ pulls the manoeuvring
filter back by mixing at once, so $\mu_2$ rises for a single frame (above one half only after
the first bounce, on the first draw) and the error near the bounces grows a little (about
5.5 px) while the window shrinks (about 1,610 px²). $\pi_{22} = 0.9$ keeps $\mu_2$ near one
for several frames after every bounce: about the same error near them (5.3 px), a larger
window (about 1,930 px²). $\pi_{12} = 0.01$ holds $\mu_2$ near zero on the arcs and gives the
smallest window (about 1,500 px²) but a slower reaction (about 5.7 px near the bounces);
$\pi_{12} = 0.2$ reacts best near the bounces (about 5.1 px) but keeps $\mu_2$ well above
zero on the arcs, searches about 2,250 px² and is noisier there (RMSE about 4.5 px against
4.3). $\Pi$ moves the cost between error and search area.
"""


def _close(a, b, atol=1e-9):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and bool(np.allclose(a, b, rtol=0.0, atol=atol))


def rts_step_ok(f):
    """17.4: one RTS backward step, on cases worked out by hand."""
    one, cv = np.eye(1), np.array([[1.0, 1.0], [0.0, 1.0]])
    cases = [
        # F = Q = P = 1, x = 0: P⁻ = 2, G = 1/2, x_s = 0 + (2 - 0)/2 = 1, P_s = 1 + (1 - 2)/4
        ((np.zeros(1), one, np.full(1, 2.0), one, one, one), (np.ones(1), np.full((1, 1), 0.75))),
        # the smoothed future equals the prediction (x_next = F x, P_next = F P Fᵀ + Q):
        # nothing to correct, x_s = x and P_s = P
        ((np.array([1.0, 2.0]), np.diag([2.0, 1.0]), cv @ np.array([1.0, 2.0]),
          cv @ np.diag([2.0, 1.0]) @ cv.T + 0.5 * np.eye(2), cv, 0.5 * np.eye(2)),
         (np.array([1.0, 2.0]), np.diag([2.0, 1.0]))),
        # Q = 0, P = I: G = F⁻¹ = [[1, -1], [0, 1]]; x_s = F⁻¹(3, 1) = (2, 1);
        # P_s = F⁻¹ (I/2) F⁻ᵀ = [[1, -1/2], [-1/2, 1/2]]
        ((np.array([5.0, -4.0]), np.eye(2), np.array([3.0, 1.0]), 0.5 * np.eye(2), cv,
          np.zeros((2, 2))),
         (np.array([2.0, 1.0]), np.array([[1.0, -0.5], [-0.5, 0.5]]))),
    ]
    for args, (xs, Ps) in cases:
        got = f(*(a.copy() for a in args))
        if len(got) != 2 or not (_close(got[0], xs) and _close(got[1], Ps)):
            return False
    return True


def mixing_ok(f):
    """17.5: the IMM's predicted mode probabilities c̄ and mixing probabilities ω, by hand."""
    cases = [
        # c̄ = (0.5·0.9 + 0.5·0.2, 0.5·0.1 + 0.5·0.8) = (0.55, 0.45);
        # ω[:, 0] = (0.45, 0.10)/0.55, ω[:, 1] = (0.05, 0.40)/0.45
        (([0.5, 0.5], [[0.9, 0.1], [0.2, 0.8]]),
         ([0.55, 0.45], [[9 / 11, 1 / 9], [2 / 11, 8 / 9]])),
        # μ = (1, 0): c̄ = first row of Π; every column of ω is (1, 0)
        (([1.0, 0.0], [[0.95, 0.05], [0.5, 0.5]]), ([0.95, 0.05], [[1.0, 1.0], [0.0, 0.0]])),
        # three modes, μ = (0.2, 0.3, 0.5), Π = I: c̄ = μ, ω = I
        (([0.2, 0.3, 0.5], np.eye(3).tolist()), ([0.2, 0.3, 0.5], np.eye(3).tolist())),
    ]
    for (mu, Pi), (cbar, omega) in cases:
        got = f(np.array(mu), np.array(Pi))
        if len(got) != 2 or not (_close(got[0], cbar) and _close(got[1], omega)):
            return False
    return True


CHECKS = {"17.4": rts_step_ok, "17.5": mixing_ok}
