"""The exercises of 20_correlation_filters_ii: their text, defined once (see
:mod:`trackbook.exercises`), and the auto-check of its ★★★ exercise."""

import numpy as np

STEM = "20_correlation_filters_ii"

TEXT = r"""
=== 20.1 ★ pen and paper | The scale filter from its ridge regression
The scale filter sees one training sample: $n_\mathrm{c}$ feature channels $x^c$, each a signal of $n_\mathrm{s}$
values over the scales, and the desired output $g$ over the scales. Its filter $h$ minimises
$\mathsf{E}(h) = \lVert \sum_c h^c \star x^c - g \rVert^2 + \lambda_\mathrm{r} \sum_c \lVert h^c \rVert^2$
over all cyclic shifts along the scale axis. Show that, frequency by frequency,
$\hat h^c = \hat g^* \hat x^c / (\sum_k \hat x^{k*} \hat x^k + \lambda_\mathrm{r})$. Then: with DSST's $n_\mathrm{s} = 33$ and
$a = 1.02$, what are the smallest and largest relative sizes one frame can test?
--- hint
By Parseval, $\mathsf{E}(h)$ splits into one small problem per frequency. In each, the data are
the single row $\hat{\mathbf x} = (\hat x^1, \dots, \hat x^{n_\mathrm{c}})$; invert $\hat{\mathbf x}^H \hat{\mathbf x} + \lambda_\mathrm{r} I$ with
Sherman–Morrison.
--- solution
The correlation $h^c \star x^c$ has the DFT $\hat h^{c*} \hat x^c$, so by Parseval (unnormalised
DFTs, a factor $1/n_\mathrm{s}$ on both terms, which does not move the minimiser) each frequency
contributes $|\sum_c \hat h^{c*} \hat x^c - \hat g|^2 + \lambda_\mathrm{r} \sum_c |\hat h^c|^2$ on its own. Write
$\hat{\mathbf h}^* = (\hat h^{1*}, \dots, \hat h^{n_\mathrm{c}*})^T$ and $\hat{\mathbf x} = (\hat x^1, \dots, \hat x^{n_\mathrm{c}})$, a row: the term
is $|\hat{\mathbf x} \hat{\mathbf h}^* - \hat g|^2 + \lambda_\mathrm{r} \lVert \hat{\mathbf h}^* \rVert^2$, a ridge regression with
one equation, whose minimiser solves $(\hat{\mathbf x}^H \hat{\mathbf x} + \lambda_\mathrm{r} I)\hat{\mathbf h}^* =
\hat{\mathbf x}^H \hat g$. Sherman–Morrison gives $(\hat{\mathbf x}^H \hat{\mathbf x} + \lambda_\mathrm{r} I)^{-1}\hat{\mathbf x}^H =
\hat{\mathbf x}^H / (\hat{\mathbf x} \hat{\mathbf x}^H + \lambda_\mathrm{r})$, so $\hat h^{c*} = \hat x^{c*} \hat g / (\sum_k |\hat x^k|^2 +
\lambda_\mathrm{r})$; conjugating, $\hat h^c = \hat g^* \hat x^c / (\sum_k \hat x^{k*} \hat x^k + \lambda_\mathrm{r})$. One division per
frequency and channel, and one denominator shared by all channels.

The exponents run from $-16$ to $16$: the sizes are $1.02^{-16} \approx 0.728$ to
$1.02^{16} \approx 1.373$ times the current one.

=== 20.2 ★ pen and paper | Merging two responses by hand
Along one row of the search area, Staple's template response is
$g_\text{tmpl} = (0.2, 0.9, 0.4, 0.1)$ and its histogram response
$g_\text{hist} = (0.3, 0.4, 0.8, 0.9)$. Where is the peak of the merged response
$(1 - \gamma_\text{hist}) g_\text{tmpl} + \gamma_\text{hist} g_\text{hist}$ for Staple's
$\gamma_\text{hist} = 0.3$? For which values of $\gamma_\text{hist}$ does each position hold
the peak?
--- solution
With $\gamma_\text{hist} = 0.3$: $(0.23, 0.75, 0.52, 0.34)$, the peak is at position 1 (counting
from 0), the template's. In general the four values are $0.2 + 0.1\gamma$, $0.9 - 0.5\gamma$,
$0.4 + 0.4\gamma$ and $0.1 + 0.8\gamma$ ($\gamma = \gamma_\text{hist}$); position 0 never wins.
Position 1 beats position 2 while $0.9 - 0.5\gamma > 0.4 + 0.4\gamma$, $\gamma < 5/9$, and beats
position 3 while $\gamma < 8/13$; position 2 beats position 3 while $\gamma < 3/4$. So the
peak is at 1 for $\gamma < 5/9 \approx 0.556$, at 2 for $5/9 < \gamma < 3/4$ and at 3 for
$\gamma > 3/4$. In between, the merge picks position 2, which neither learner ranks first: a
compromise, where both scores are fairly high.

=== 20.3 ★ pen and paper | One Sherman–Morrison step
BACF's $\hat h_\mathrm{pad}$-step solves, at each frequency ($n$ the window's cells), $(\mathbf x \mathbf x^H + n\mu I)\,\mathbf h_\mathrm{pad} =
\mathbf b$ for an $n_\mathrm{c}$-vector $\mathbf h_\mathrm{pad}$. Show that $\mathbf h_\mathrm{pad} = \bigl(\mathbf b - \mathbf x\,
(\mathbf x^H \mathbf b)/(n\mu + \mathbf x^H \mathbf x)\bigr)/(n\mu)$. Then compute $\mathbf h_\mathrm{pad}$
for $n_\mathrm{c} = 2$, $\mathbf x = (1, 2)^T$, $n\mu = 1$ and $\mathbf b = (1, 0)^T$, once by this formula
and once by inverting the $2 \times 2$ matrix.
--- solution
Sherman–Morrison: $(A + \mathbf u \mathbf v^H)^{-1} = A^{-1} - A^{-1}\mathbf u \mathbf v^H
A^{-1} / (1 + \mathbf v^H A^{-1} \mathbf u)$. With $A = n\mu I$ and $\mathbf u = \mathbf v =
\mathbf x$: $(\mathbf x \mathbf x^H + n\mu I)^{-1} = \frac{1}{n\mu}\bigl(I - \mathbf x
\mathbf x^H / (n\mu + \mathbf x^H \mathbf x)\bigr)$; apply it to $\mathbf b$. Here
$\mathbf x^H \mathbf b = 1$ and $\mathbf x^H \mathbf x = 5$, so $\mathbf h_\mathrm{pad} = (1, 0) -
(1, 2)/6 = (5/6, -1/3)$. Directly: $\mathbf x \mathbf x^T + I = \begin{pmatrix} 2 & 2 \\ 2 & 5
\end{pmatrix}$, whose inverse is $\frac16 \begin{pmatrix} 5 & -2 \\ -2 & 2 \end{pmatrix}$; its
first column is $(5/6, -1/3)$. The formula costs $O(n_\mathrm{c})$ per frequency instead of an $n_\mathrm{c} \times n_\mathrm{c}$
solve.

=== 20.4 ★★★ implement | Staple's histogram response and the merge
Write `merged(tmpl, beta, box, gamma)`. `beta` is an $H \times W$ map of per-pixel object
scores, `box = (h, w)` the target's size in pixels, `tmpl` the template response on the
$(H - h + 1) \times (W - w + 1)$ placements of the box. Return
$(1 - \gamma_\text{hist})\,g_\text{tmpl} + \gamma_\text{hist}\, g_\text{hist}$, where $g_\text{hist}[i, j]$ is the mean of
`beta` over rows $i \dots i + h - 1$ and columns $j \dots j + w - 1$, computed from an integral
image (no loop over placements). Worked by hand: for `beta` the $3 \times 3$ identity,
`box = (2, 2)`, `tmpl = [[0, 1], [0, 0]]` and $\gamma_\text{hist} = 0.5$ the box means are
$\begin{pmatrix} 0.5 & 0.25 \\ 0.25 & 0.5 \end{pmatrix}$ and the answer is
`[[0.25, 0.625], [0.125, 0.25]]`.
--- hint
With $\mathrm{II}$ the cumulative sum over rows and columns, padded by a zero row and
column, the sum over a box is $\mathrm{II}[i + h, j + w] - \mathrm{II}[i, j + w] -
\mathrm{II}[i + h, j] + \mathrm{II}[i, j]$; slicing $\mathrm{II}$ four times gives every
placement at once.
--- solution
Pad the cumulative sums with a zero row and column, take the four shifted slices, divide by
$h w$, then merge: four array slices and two products, whatever the number of placements.

=== 20.5 ★ use | The scale step
Run `dsst` on `patterned-object` (the target grows to about 1.4 times its first size and
shrinks again) with `scale_step` 1.005, 1.02 (DSST's) and 1.08, and compare the AUC and how
closely the box's size follows the ground truth's (for example the mean of
$|\ln(\text{size}/\text{true size})|$ over the frames, the size being $\sqrt{wh}$). Why do
both a smaller and a larger step do worse?
--- solution
The step 1.02 scores best and follows the size most closely (AUC about 0.81 against 0.76 for
1.005 and 0.79 for 1.08). With 1.005 the 33 scales span only $1.005^{\pm 16} \approx 0.92$ to
$1.08$, so a frame can test at most 8 % of growth, and neighbouring samples look almost alike:
the size lags behind the target's. With 1.08 the samples are 8 % apart, so the answer moves in
coarse steps; a reading of why that hurts: the HOG vectors of two resized patches that differ by
less than a step are hard to tell apart, and the size waits until the change is a whole step.
The scale step sets both the range one frame can test and the resolution of the answer.

=== 20.6 ★★ modify | The merge factor
Run `staple` on `occluder` and `shelves` with `gamma` 0 (template only), 0.3 (Staple's) and 1
(colour only). Compare with what the chapter measured on `two-faces` and `yellow-ball`, and
say, for each clip, which learner carries the tracking.
--- solution
On both clips the template alone scores close to the merge, and colour alone lower: a little
lower on `shelves`, much lower on `occluder`. So the template carries the tracking there, as on
`two-faces` (where colour alone fails on the second face of the same colours), while on
`yellow-ball` it is the other way round. The merge at 0.3 scores highest of the three on both
clips: it follows the template and borrows from the colour score only as much as $\gamma$
allows.
"""


def _box_means_by_definition(beta, h, w):
    """The mean over every h x w placement, one placement at a time (the definition)."""
    H, W = beta.shape
    return np.array([[beta[i:i + h, j:j + w].mean() for j in range(W - w + 1)]
                     for i in range(H - h + 1)])


def merged_ok(f):
    """20.4: the histogram response by box means, merged with the template response."""
    eye = np.eye(3)
    tmpl = np.array([[0.0, 1.0], [0.0, 0.0]])
    # worked by hand: box means [[0.5, 0.25], [0.25, 0.5]]; 0.5 tmpl + 0.5 means
    if not np.allclose(f(tmpl, eye, (2, 2), 0.5), [[0.25, 0.625], [0.125, 0.25]], atol=1e-12):
        return False
    # gamma = 0: the template alone; gamma = 1: the box means alone
    if not np.allclose(f(tmpl, eye, (2, 2), 0.0), tmpl, atol=1e-12):
        return False
    if not np.allclose(f(tmpl, eye, (2, 2), 1.0), [[0.5, 0.25], [0.25, 0.5]], atol=1e-12):
        return False
    # a 1 x 1 box: the box means are beta itself; 0.7 * 1 + 0.3 * beta
    beta = np.arange(6.0).reshape(2, 3) / 5
    if not np.allclose(f(np.ones((2, 3)), beta, (1, 1), 0.3), 0.7 + 0.3 * beta, atol=1e-12):
        return False
    # a random map and a non-square box against the one-placement-at-a-time definition
    rng = np.random.default_rng(4)
    beta = rng.random((9, 12))
    tmpl = rng.normal(size=(9 - 4 + 1, 12 - 3 + 1))
    want = 0.8 * tmpl + 0.2 * _box_means_by_definition(beta, 4, 3)
    return bool(np.allclose(f(tmpl, beta, (4, 3), 0.2), want, atol=1e-12))


CHECKS = {"20.4": merged_ok}
