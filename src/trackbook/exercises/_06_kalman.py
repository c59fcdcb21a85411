"""The exercises of 06_kalman: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "06_kalman"

TEXT = r"""
=== 6.1 ★ use | The product of two Gaussians
The prior is $\mathrm{N}(20, 4)$ (mean 20 px, variance 4), the measurement $z = 26$ px with noise
variance 12. Compute by hand the Kalman gain $K$, the posterior mean and the posterior
variance, and check them on a grid. Answer `(K, mean, variance)`.
--- solution
$K = 4 / (4 + 12) = 1/4$; mean $= 20 + K(26 - 20) = 21.5$; variance $= (1 - K) \cdot 4 = 3$.

=== 6.2 ★ use | One step by hand
The constant-velocity model of the chapter has state $(x, y, \dot x, \dot y)$, $F$ adding the
velocity to the position, $H$ picking the position, $Q = I_4$, $R = I_2$, $P_0 = I_4$. Compute
by hand the predicted position variance $(P_1^-)_{xx}$, the innovation variance $S_{xx}$ and
the gains $K_{x,x}$ (position) and $K_{\dot x, x}$ (velocity) of the first update, then check
with `constant_velocity().predict()` and `.update(...)`. Answer `(P_xx, S_xx, K_pos, K_vel)`.
--- solution
$P_1^- = F P_0 F^T + Q$: per axis $\begin{bmatrix}1 & 1\\ 0 & 1\end{bmatrix}
\begin{bmatrix}1 & 1\\ 0 & 1\end{bmatrix}^T = \begin{bmatrix}2 & 1\\ 1 & 1\end{bmatrix}$, plus
$I$: position variance 3, $\operatorname{cov}(x, \dot x) = 1$, velocity variance 2.
$S = H P_1^- H^T + R = 3 + 1 = 4$ and $K = P_1^- H^T S^{-1} = (3/4, 1/4)$ per axis.

=== 6.3 ★★ modify | Flying blind
Run `constant_velocity()` (Q = R = I) for 50 frames with a measurement at (0, 0) every frame
(`predict()` then `update((0.0, 0.0))`), so that it reaches its steady state. Then predict 5
frames without any measurement. What is the 3σ half-size of the window in x,
$3\sqrt{S_{xx}}$ (`innovation_covariance()`), after those 5 blind frames? How fast does the
position's spread grow with the number $t$ of blind frames, and why not linearly?
--- solution
After the 5 blind frames the half-size is about 28.4 px (from about 7.1 px at the steady
state). With no update the velocity is a random walk (its variance grows like $t$) and the position,
its sum, has a variance growing like $t^3/3$: the half-size $3\sqrt S$ grows like $t^{1.5}$,
not linearly ($R$ and the steady-state $P$ add lower powers, so the fitted exponent approaches
1.5 as $t$ grows; over blind frames 10 to 20 it is about 1.4).

=== 6.4 ★★ modify | The wrong sensor noise
On the chapter's simulated sensor (the bouncing ball), keep $Q = I$ but tell the filter the
wrong sensor noise: $R = I$ (too confident in the sensor) and $R = 100\,I$ (too sceptical).
Which gives the larger mean error, and how many surprises does each report?
--- solution
$R = 100\,I$ gives the larger mean error, about 7.8 px, and reports one surprise; $R = I$
reports 60 surprises in 119 frames, with a mean error of about 4.5 px. $R = I$ claims the
sensor is far better than it is: $S$ is too small, so the honest 4 px noise lands outside 3σ
of $S$ again and again (false surprises). Its mean error is nevertheless the smallest, below
even that of the true $R = 16\,I$: the ball is not a constant-velocity object (gravity,
bounces), and trusting the measurements more hides that model error. $R = 100\,I$ smooths so
hard that it lags behind every arc. A filter's $R$ is a statement about the sensor and a knob against model mismatch.

=== 6.5 ★★★ implement | A 1-D Kalman filter from scratch
Write `kf1d(zs, mu0, var0, u, var_q, var_r)` returning two arrays, the posterior means and
variances after each measurement in `zs`: predict by adding the known motion `u` to the mean
and `var_q` to the variance (the convolution of two Gaussians), update by the product of two
Gaussians (gain $K = v / (v + \text{var}_r)$). Use plain NumPy, not `KalmanFilter`. The check
uses exercise 6.1 (one measurement: mean 21.5, variance 3), a second measurement after it
($K = 3/15$, variance 2.4) and a case with motion: from $\mathrm{N}(0, 3)$ with $u = 5$ and
$\text{var}_q = 1$ the prediction is $\mathrm{N}(5, 4)$, and $z = 11$ with variance 12 gives mean 6.5
and variance 3.
--- solution
One loop over the measurements, two lines per step:

```python
def kf1d(zs, mu0, var0, u, var_q, var_r):
    m, v, means, variances = mu0, var0, [], []
    for z in zs:
        m, v = m + u, v + var_q        # predict: add means, variances
        K = v / (v + var_r)            # gain
        m, v = m + K * (z - m), (1 - K) * v    # update: product
        means.append(m)
        variances.append(v)
    return np.array(means), np.array(variances)
```

The cases by hand: from $\mathrm{N}(20, 4)$ with $u = 0$, $\text{var}_q = 0$ and $z = 26$ (variance
12), $K = 1/4$, mean 21.5, variance 3 (exercise 6.1). A second measurement with the same
variance has $K = 3/(3 + 12) = 1/5$, so the variance becomes $(4/5) \cdot 3 = 2.4$. With motion,
$\mathrm{N}(0, 3)$ predicts to $\mathrm{N}(0 + 5, 3 + 1) = \mathrm{N}(5, 4)$; then $K = 4/16 = 1/4$, mean
$5 + (11 - 5)/4 = 6.5$ and variance $(3/4) \cdot 4 = 3$.

=== 6.6 ★★ modify | A precise bearing or a good start
In the chapter's range-bearing section, make the bearing ten times more precise
(`sigma_theta=0.02` in both `nl.simulate` and `nl.compare`), then instead start the filters
at the truth (`x0_error=(0, 0, 0, 0)`, `p0=(1, 1, 1, 1)`) with the vague bearing. In which
case does the EKF catch up with the UKF, and why not in the other?
--- solution
Started at the truth, the EKF comes close to the UKF: $h$ is linearised at the right place
from the first step. With a precise bearing it still trails the others: the measurement is now
precise, but the first tangents are taken at the wrong guess, 28 units off, and a confident
update at the wrong tangent takes many steps to undo. The converted-measurement KF linearises,
in effect, at the measurement itself, which is now close to the truth: it does best.

=== 6.7 ★★★ implement | The Jacobian of range and bearing
A sensor at $s$ measures a target at $p = (p_x, p_y)$ by its range $r = \lVert p - s \rVert$
and bearing $\theta = \operatorname{atan2}(p_y - s_y, p_x - s_x)$. Write `my_H_j(x, sensor)`
returning the 2 × 4 Jacobian $\partial h / \partial x$ for the state
$x = [p_x, p_y, v_x, v_y]$. By hand first: with the sensor at the origin and the target at
$(3, 4)$, $r = 5$, $\partial r/\partial p = (3/5, 4/5)$,
$\partial \theta / \partial p = (-4/25, 3/25)$ and the velocity columns are zero. The check
uses that case and finite differences of $h$ at another point.
--- solution
$\partial r / \partial p = (p - s)/r$ and $\partial\theta/\partial p = (-(p_y - s_y),
p_x - s_x)/r^2$; the measurement does not depend on the velocity.

=== 6.8 ★★ pen and paper | Derive the gain
Write the updated estimate as $\mu = \mu_1 + K(z - \mu_1)$
for an unknown $K$. With independent prior error (variance $\sigma_1^2$) and sensor error
(variance $\sigma_2^2$), show that the error variance of $\mu$ is
$(1 - K)^2 \sigma_1^2 + K^2 \sigma_2^2$, find the $K$ that minimises it, and show that the
minimum is $(1 - K)\sigma_1^2$ — the gain and the variance of the product of two Gaussians.
--- solution
The error is $\mu - x = (1 - K)(\mu_1 - x) + K(z - x)$, a sum of two independent errors, so its
variance is $(1-K)^2\sigma_1^2 + K^2\sigma_2^2$. The derivative in $K$ is
$-2(1-K)\sigma_1^2 + 2K\sigma_2^2$; it is zero at $K = \sigma_1^2/(\sigma_1^2 + \sigma_2^2)$.
There $1 - K = \sigma_2^2/(\sigma_1^2 + \sigma_2^2)$, and the variance is
$\frac{\sigma_2^4\sigma_1^2 + \sigma_1^4\sigma_2^2}{(\sigma_1^2 + \sigma_2^2)^2}
= \frac{\sigma_1^2\sigma_2^2}{\sigma_1^2 + \sigma_2^2} = (1 - K)\sigma_1^2$.

=== 6.9 ★★ pen and paper | The multivariate gain from the trace
Exercise 6.8 in matrices. The prior error $e^- = x_k - \hat x_k^-$ has covariance $P_k^-$,
the sensor noise $v_k$ of eq. 2 has covariance $R$ and is independent of it, and the update is
eq. 6 with an unknown gain $K$. (a) Show that the posterior error covariance is
$P_k^+ = (I - KH)P_k^-(I - KH)^T + KRK^T$. (b) Minimise its trace (the sum of the error
variances of all the state's entries) over $K$ and show that the minimiser is eq. 5,
$K_k = P_k^- H^T (H P_k^- H^T + R)^{-1}$. Use $\partial \operatorname{tr}(KA)/\partial K = A^T$
and $\partial \operatorname{tr}(KBK^T)/\partial K = 2KB$ for symmetric $B$. (c) Show that at
this gain $P_k^+ = (I - K_kH)P_k^-$, eq. 7. (d) Check on exercise 6.2's first update, one
axis: $P_k^- = \begin{bmatrix}3 & 1\\ 1 & 2\end{bmatrix}$, $H = [1\ \ 0]$, $R = 1$. Compute
$K_k$ and $\operatorname{tr} P_k^+$, and compare with the gain $K = (1, 0)^T$ that takes the
measurement as the position and leaves the velocity alone.
--- solution
(a) With $z_k = Hx_k + v_k$ and eq. 6, $x_k - \hat x_k^+ = e^- - K(Hx_k + v_k - H\hat x_k^-)
= (I - KH)e^- - Kv_k$. The two terms are independent with zero mean, so their covariances
add: $P_k^+ = (I - KH)P_k^-(I - KH)^T + KRK^T$ (the Joseph form of the chapter, true for any
$K$).

(b) Multiply out, with $S = HP_k^-H^T + R$ (symmetric):
$P_k^+ = P_k^- - KHP_k^- - P_k^-H^TK^T + KSK^T$. A matrix and its transpose have the same
trace, so $\operatorname{tr}P_k^+ = \operatorname{tr}P_k^- - 2\operatorname{tr}(KHP_k^-) +
\operatorname{tr}(KSK^T)$, and its derivative in $K$ is
$-2(HP_k^-)^T + 2KS = -2P_k^-H^T + 2KS$. It vanishes at $K = P_k^-H^TS^{-1}$, eq. 5. This is
the minimum: $S$ is positive definite, so $\operatorname{tr}(KSK^T)$ is a convex quadratic in
$K$, and the trace is convex.

(c) At this gain $KSK^T = P_k^-H^TS^{-1}SK^T = P_k^-H^TK^T$, which cancels the third term:
$P_k^+ = P_k^- - KHP_k^- = (I - K_kH)P_k^-$.

(d) $S = 3 + 1 = 4$ and $K_k = (3, 1)^T/4 = (0.75, 0.25)^T$, as in exercise 6.2. Then
$I - K_kH = \begin{bmatrix}0.25 & 0\\ -0.25 & 1\end{bmatrix}$ and
$P_k^+ = \begin{bmatrix}0.75 & 0.25\\ 0.25 & 1.75\end{bmatrix}$: trace 2.5. With
$K = (1, 0)^T$, $I - KH = \begin{bmatrix}0 & 0\\ 0 & 1\end{bmatrix}$, the first term is
$\begin{bmatrix}0 & 0\\ 0 & 2\end{bmatrix}$ and $KRK^T = \begin{bmatrix}1 & 0\\ 0 &
0\end{bmatrix}$: trace 3, larger. The optimal gain believes only three quarters of the
innovation in the position (the prior is worth something) and, through the covariance 1 of
position and velocity, also corrects the velocity by a quarter of the innovation
($P_{21}/S = 1/4$, with the prior's covariance $P_{21} = 1$), which $K = (1, 0)^T$ leaves alone.

=== 6.10 ★ pen and paper | The steady state of a random walk
A target does a random walk on a line: predict adds $u = 0$ to the mean and $\sigma_q^2 = 1$
to the variance; each frame a sensor measures its position with noise variance
$\sigma_2^2 = 2$. The filter starts from a known position (posterior variance $v_0 = 0$).
(a) Run three steps by hand: for $k = 1, 2, 3$ the predicted variance $p_k = v_{k-1} +
\sigma_q^2$, the gain $K_k = p_k / (p_k + \sigma_2^2)$ and the posterior variance
$v_k = (1 - K_k)p_k$, as fractions. (b) In the steady state $p_k$ stops changing: write the
equation it satisfies (a scalar Riccati equation) and solve it. What are the steady-state
predicted variance, gain and posterior variance? (c) Show that the steady-state posterior
variance is $\bigl(-\sigma_q^2 + \sqrt{\sigma_q^4 + 4\sigma_q^2\sigma_2^2}\bigr)/2$ in general.
(d) With the steady gain, what does the update do to the mean?
--- solution
(a) $p_1 = 0 + 1 = 1$, $K_1 = 1/3$, $v_1 = (2/3) \cdot 1 = 2/3$. $p_2 = 5/3$,
$K_2 = (5/3)/(11/3) = 5/11$, $v_2 = (6/11)(5/3) = 10/11 \approx 0.909$. $p_3 = 21/11$,
$K_3 = (21/11)/(43/11) = 21/43$, $v_3 = (22/43)(21/11) = 42/43 \approx 0.977$. The variance
rises from the known start towards a limit.

(b) $v = (1 - K)p = p\,\sigma_2^2/(p + \sigma_2^2)$ and $p = v + \sigma_q^2$, so
$p = p\,\sigma_2^2/(p + \sigma_2^2) + \sigma_q^2$. Multiplying by $p + \sigma_2^2$:
$p^2 - \sigma_q^2\,p - \sigma_q^2\sigma_2^2 = 0$, here $p^2 - p - 2 = (p - 2)(p + 1) = 0$. The
variance is positive: $p = 2$. Then $K = 2/(2 + 2) = 1/2$ and $v = (1 - 1/2) \cdot 2 = 1$;
check: $v + \sigma_q^2 = 2 = p$.

(c) The positive root is $p = \bigl(\sigma_q^2 + \sqrt{\sigma_q^4 +
4\sigma_q^2\sigma_2^2}\bigr)/2$, and $v = p - \sigma_q^2 = \bigl(-\sigma_q^2 +
\sqrt{\sigma_q^4 + 4\sigma_q^2\sigma_2^2}\bigr)/2$; here $(-1 + \sqrt{1 + 8})/2 = 1$. Only
the ratio of $\sigma_q^2$ to $\sigma_2^2$ sets the steady gain; scaling both by $c$ scales
$p$ and $v$ by $c$.

(d) $\mu_k = \mu_k^- + \tfrac12(z_k - \mu_k^-) = \tfrac12\mu_{k-1} + \tfrac12 z_k$ (for a
random walk $\mu_k^- = \mu_{k-1}$): in its steady state the Kalman filter is an exponential
moving average of the measurements, with weight $K = 1/2$ on the newest one.
"""
