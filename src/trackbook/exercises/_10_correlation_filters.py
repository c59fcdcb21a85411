"""The exercises of 10_correlation_filters: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "10_correlation_filters"

TEXT = r"""
=== 10.1 ★ use | The PSR by hand
Compute by hand the PSR of a 15 × 15 response that is 0 everywhere except 6 at the peak
(7, 7) and 1 at (0, 14). Check with `cf.psr`.
--- solution
The sidelobe leaves out the 11 × 11 window around the peak: $225 - 121 = 104$ values, one 1
and 103 zeros. Their mean is $1/104$ and their standard deviation
$\sqrt{1/104 - 1/104^2} \approx 0.0976$, so the PSR is $(6 - 1/104)/0.0976 \approx 61.4$.

=== 10.2 ★★ modify | The learning rate
Run `kcf` on `red-cube` with the learning rate `eta` at 0, 0.02 (the paper's) and 0.2.
Which scores best, and what does $\eta = 0$ mean for the model?
--- solution
$\eta = 0$ keeps the first frame's model and learns nothing after it; the red cube changes
little, so here it scores best, ahead of 0.02. With $\eta = 0.2$ a frame's weight falls to
$0.8^{10} \approx 0.1$ ten frames later, so the model soon holds mostly the latest windows,
background included, and scores lowest. On a target that changes its appearance a fixed model
fails instead.

=== 10.3 ★★★ implement | Kernel ridge regression in the Fourier domain
Implement the 1-D kernel ridge regression over all cyclic shifts in the Fourier domain:
`dual(x, g, sigma, lam)` returning $\alpha$ (real, length $n$) for the Gaussian kernel
$\kappa(x, x') = \exp(-\lVert x - x'\rVert^2 / (n\sigma^2))$. It must equal
$(\mathbf{K} + \lambda_\mathrm{r} I)^{-1} g$ with the $n \times n$ kernel matrix of all shifts written out. By
hand first: $x = 0$ makes every kernel value 1, so for $n = 2$, $g = (1, 1)$ and
$\lambda_\mathrm{r} = 1$, $(J + I)\alpha = g$ gives $\alpha = (1/3, 1/3)$. The check uses that case and
the explicit solve on a random signal.
--- solution
The kernel matrix of all cyclic shifts is circulant, so the Fourier transform diagonalises
it: $\hat\alpha = \hat g / (\hat{\boldsymbol{\kappa}} + \lambda_\mathrm{r})$, with $\boldsymbol{\kappa}$ its first row,
$\boldsymbol{\kappa}_t = \exp(-(2\lVert x\rVert^2 - 2\,x \cdot \text{shift}_t(x)) / (n\sigma^2))$.
=== 10.4 ★★ pen and paper | The MOSSE filter from its squared error
MOSSE trains on patches $x_i$ with desired responses $g_i$; $\hat x_i$, $\hat g_i$ and $\hat h$ are their
DFTs and the filter's, and the filter's response on $x_i$ has the DFT $\hat x_i \odot \hat h^*$. The
filter minimises the output sum of squared error plus a penalty on its size,

$$\mathsf{E} = \sum_i \sum_\omega \lvert \hat x_i(\omega) \hat h^*(\omega) - \hat g_i(\omega) \rvert^2 +
\lambda_\mathrm{r} \sum_\omega \lvert \hat h(\omega) \rvert^2 ,$$

with $\omega$ running over the frequencies and $\lambda_\mathrm{r} > 0$.
(a) Show that $\mathsf{E}$ splits into one term per frequency, and minimise each term over the
complex number $\hat h^*(\omega)$ to obtain
$\hat h^* = \sum_i \hat g_i \odot \hat x_i^* / (\sum_i \hat x_i \odot \hat x_i^* + \lambda_\mathrm{r})$. Why is the stationary
point a minimum? (b) At one frequency, two training patches have $\hat x_1 = 2$ and $\hat x_2 = i$
(the imaginary unit), with $\hat g_1 = \hat g_2 = 1$ and $\lambda_\mathrm{r} = 1$. Compute $\hat h^*$ there. What is
$\hat h^*$ at a frequency where every $\hat x_i$ is 0, and what would it be without $\lambda_\mathrm{r}$?
--- hint
Perturb $q = \hat h^*(\omega)$ to $q + \varepsilon$ and expand $\lvert a + b \rvert^2 =
\lvert a \rvert^2 + 2\operatorname{Re}(a b^*) + \lvert b \rvert^2$.
--- solution
(a) Each summand holds one frequency's $\hat h(\omega)$ and no other, so $\mathsf{E}$ is a sum of terms
that can be minimised one at a time. At one frequency write $q = \hat h^*(\omega)$ (then
$\lvert \hat h(\omega) \rvert^2 = \lvert q \rvert^2$) and
$\mathsf{E}_\omega(q) = \sum_i \lvert \hat x_i q - \hat g_i \rvert^2 + \lambda_\mathrm{r} \lvert q \rvert^2$. Expanding
with $a = \hat x_i q - \hat g_i$, $b = \hat x_i \varepsilon$:

$$\begin{aligned}
\mathsf{E}_\omega(q + \varepsilon) = \mathsf{E}_\omega(q) &+ 2 \operatorname{Re}\Big[\varepsilon^*
\Big(\sum_i \hat x_i^* (\hat x_i q - \hat g_i) + \lambda_\mathrm{r} q\Big)\Big] \\
&+ \Big(\sum_i \hat x_i \hat x_i^* + \lambda_\mathrm{r}\Big) \lvert \varepsilon \rvert^2 .
\end{aligned}$$

The linear term vanishes for every $\varepsilon$ (real and imaginary) only if
$\sum_i \hat x_i^* (\hat x_i q - \hat g_i) + \lambda_\mathrm{r} q = 0$, that is
$q \,(\sum_i \hat x_i \hat x_i^* + \lambda_\mathrm{r}) = \sum_i \hat g_i \hat x_i^*$, so
$\hat h^*(\omega) = \sum_i \hat g_i \hat x_i^* / (\sum_i \hat x_i \hat x_i^* + \lambda_\mathrm{r})$: at every frequency, the
element-wise formula. At this $q$, $\mathsf{E}_\omega(q + \varepsilon) - \mathsf{E}_\omega(q) =
(\sum_i \lvert \hat x_i \rvert^2 + \lambda_\mathrm{r}) \lvert \varepsilon \rvert^2 > 0$ for every
$\varepsilon \ne 0$, since $\lambda_\mathrm{r} > 0$: the stationary point is the unique minimum. Each
$\hat h(\omega)$ was free here; for real patches and labels $\hat x_i(-\omega) = \hat x_i(\omega)^*$ and
$\hat g_i(-\omega) = \hat g_i(\omega)^*$ give $\hat h^*(-\omega) = \hat h^*(\omega)^*$, so the filter
$h = \operatorname{DFT}^{-1}(\hat h)$ is real: the best of all filters is a real one. (By
Parseval, with $n$ the number of pixels and $r_i$ the filter's response on $x_i$,
$\mathsf{E} = n\,(\sum_i \lVert r_i - g_i \rVert^2 + \lambda_\mathrm{r}
\lVert h \rVert^2)$: the same minimiser as the least squares on the patches themselves.)

(b) $\sum_i \hat g_i \hat x_i^* = 1 \cdot 2 + 1 \cdot (-i) = 2 - i$ and
$\sum_i \hat x_i \hat x_i^* + \lambda_\mathrm{r} = 4 + 1 + 1 = 6$, so $\hat h^* = (2 - i)/6 \approx 0.333 - 0.167i$.
Where every $\hat x_i$ is 0 the numerator is 0 and the denominator $\lambda_\mathrm{r}$: $\hat h^* = 0$. Without
$\lambda_\mathrm{r}$ it would be $0/0$, undefined: $\lambda_\mathrm{r}$ keeps the filter defined where the
training patches have no energy, and damps it where they have little, where dividing by a
tiny $\sum_i \hat x_i \hat x_i^*$ would amplify noise.

=== 10.5 ★★ pen and paper | Correlation as a product of spectra
In the one-dimensional setting of this chapter, row $t$ of the circulant matrix $X$ is the
signal $x$ shifted by $-t$ (`np.roll(x, -t)` in the chapter's code), so the filter $w$
answers at shift $t$ with
$(Xw)_t = \sum_m x_{(m+t) \bmod n}\, w_m$. The DFT is
$\hat x_k = \sum_m x_m e^{-2\pi i k m / n}$.
(a) Show that the DFT of $Xw$ is $\hat x \odot \hat w^*$ for a real $w$. (b) For $n = 4$,
$x = (2, 1, 0, 1)$ and $w = (1, 0, 0, 1)$, compute $Xw$ directly, then $\hat x$, $\hat w$
and $\hat x \odot \hat w^*$ (for $n = 4$, $e^{-2\pi i k m / 4} = (-i)^{km}$), and check
that the last is the DFT of $Xw$. (c) The circular convolution
$(x * w)_t = \sum_m x_{(t-m) \bmod n}\, w_m$ has the DFT $\hat x \odot \hat w$. Compute it
for the same $x$ and $w$: how does it differ from $Xw$? (d) With $\lambda_\mathrm{r} = 0$, at which
frequency $k$ is the filter $\hat w^* = \hat g \odot \hat x^* / (\hat x \odot \hat x^* +
\lambda_\mathrm{r})$ undefined for this $x$, and which part of a label $g$ can no filter reproduce?
--- solution
(a) $\widehat{Xw}_k = \sum_t \sum_m x_{m+t}\, w_m\, e^{-2\pi i k t/n}$. Put $s = m + t$
(mod $n$, which the exponential does not see, being $n$-periodic), so $t = s - m$ and
$e^{-2\pi i k t/n} = e^{-2\pi i k s/n} e^{+2\pi i k m/n}$:
$\widehat{Xw}_k = \big(\sum_s x_s e^{-2\pi i k s/n}\big)\big(\sum_m w_m e^{+2\pi i k m/n}\big)
= \hat x_k \, \hat w_k^*$, the second factor being the conjugate of $\hat w_k$ because $w$
is real.

(b) $(Xw)_t = x_t + x_{(t+3) \bmod 4}$: $Xw = (2 + 1, 1 + 2, 0 + 1, 1 + 0) = (3, 3, 1, 1)$.
$\hat x_k = 2 + (-i)^k + (-i)^{3k}$: $\hat x = (4, 2, 0, 2)$.
$\hat w_k = 1 + (-i)^{3k}$: $\hat w = (2, 1 + i, 0, 1 - i)$, so
$\hat w^* = (2, 1 - i, 0, 1 + i)$ and $\hat x \odot \hat w^* = (8, 2 - 2i, 0, 2 + 2i)$.
The DFT of $(3, 3, 1, 1)$: $k = 0$: 8; $k = 1$: $3 - 3i - 1 + i = 2 - 2i$; $k = 2$:
$3 - 3 + 1 - 1 = 0$; $k = 3$: $3 + 3i - 1 - i = 2 + 2i$. The same.

(c) $(x * w)_t = x_t + x_{(t-3) \bmod 4} = x_t + x_{(t+1) \bmod 4}$: $x * w = (3, 1, 1, 3)$,
with DFT $\hat x \odot \hat w = (8, 2 + 2i, 0, 2 - 2i)$. It differs from $Xw = (3, 3, 1, 1)$:
the convolution flips the filter. Correlating with $w$ is convolving with
$w_{(-m) \bmod 4} = (1, 1, 0, 0)$, whose DFT is $\hat w^*$.

(d) At $k = 2$: $\hat x_2 = 0$, so numerator and denominator are both 0. There
$\widehat{Xw}_2 = \hat x_2 \hat w_2^* = 0$ whatever the filter: the part of a label at
frequency 2, the alternating part $\tfrac14 \hat g_2\,(1, -1, 1, -1)$ with
$\hat g_2 = g_0 - g_1 + g_2 - g_3$, is out of reach. With $\lambda_\mathrm{r} > 0$ the filter is 0
there, and at every other frequency the response $\hat x_k \hat w_k^* = \hat g_k \lvert
\hat x_k \rvert^2 / (\lvert \hat x_k \rvert^2 + \lambda_\mathrm{r})$ is the label's, shrunk by that
factor, below 1 (a little where $\lambda_\mathrm{r}$ is small beside $\lvert \hat x_k \rvert^2$).

=== 10.6 ★★ pen and paper | KCF's solution on a circulant kernel matrix
KCF's kernel ridge regression over all shifts $x_j$ of the training patch $x$ (the rows of
$X$: $x_j$ is $x$ shifted by $-j$, $(x_j)_m = x_{(m+j) \bmod n}$) solves
$(\mathbf{K} + \lambda_\mathrm{r} I)\alpha = g$ with $\mathbf{K}_{ij} = \kappa(x_i, x_j)$. The kernel treats every shift
alike: $\kappa$ of two signals does not change when both are shifted by the same amount,
and $\kappa(a, b) = \kappa(b, a)$. As in the chapter, $\boldsymbol{\kappa}^{xx}_t = \kappa(x, x \text{ shifted
by } t)$, where $x$ shifted by $t$ has the entries $x_{(m-t) \bmod n}$ (`np.roll(x, t)`).
A fact you may use: for sequences $u$ and $v$ with $v$ real, the sequence
$\sum_m v_m u_{(m+t) \bmod n}$ has the DFT $\hat u \odot \hat v^*$.
(a) Show that $\boldsymbol{\kappa}^{xx}_{-t} = \boldsymbol{\kappa}^{xx}_t$ (so $\hat{\boldsymbol{\kappa}}^{xx}$ is real), that
$\mathbf{K}_{ij} = \boldsymbol{\kappa}^{xx}_{(j-i) \bmod n}$, and that $\hat\alpha = \hat g / (\hat{\boldsymbol{\kappa}}^{xx} + \lambda_\mathrm{r})$.
(b) By hand, for $n = 4$, the linear kernel $\kappa(a, b) = a^T b$, the patch
$x = (1, 1, 0, 0)/\sqrt 2$, labels $g = (1, 0, 0, 0)$ and $\lambda_\mathrm{r} = 1$: compute
$\boldsymbol{\kappa}^{xx}$, $\hat{\boldsymbol{\kappa}}^{xx}$, $\hat\alpha$ and $\alpha$, and check $(\mathbf{K} + \lambda_\mathrm{r} I)\alpha = g$
with $\mathbf{K}$ written out. (c) What goes wrong with $\lambda_\mathrm{r} = 0$ here?
--- solution
(a) Shifting both signals by $t$ does not change $\kappa$, so with the symmetry
$\boldsymbol{\kappa}^{xx}_{-t} = \kappa(x, x \text{ shifted by } -t) = \kappa(x \text{ shifted by } t, x) =
\kappa(x, x \text{ shifted by } t) = \boldsymbol{\kappa}^{xx}_t$; an even real sequence has a real DFT
($\hat{\boldsymbol{\kappa}}^{*}_k = \sum_t \boldsymbol{\kappa}_t e^{2\pi i k t/n} = \sum_t \boldsymbol{\kappa}_{-t} e^{-2\pi i k t/n} = \hat{\boldsymbol{\kappa}}_k$).
$x_i$ and $x_j$ are $x$ shifted by $-i$ and by $-j$; shifting both by $i$ gives
$\mathbf{K}_{ij} = \kappa(x, x \text{ shifted by } i - j) = \boldsymbol{\kappa}^{xx}_{(i-j) \bmod n} =
\boldsymbol{\kappa}^{xx}_{(j-i) \bmod n}$: $\mathbf{K}$ is circulant, its first row $\boldsymbol{\kappa}^{xx}$. Then
$(\mathbf{K}\alpha)_i = \sum_j \boldsymbol{\kappa}^{xx}_{j-i} \alpha_j = \sum_m \boldsymbol{\kappa}^{xx}_m \alpha_{m+i}$, which by the
fact has the DFT
$\hat\alpha \odot \hat{\boldsymbol{\kappa}}^{xx*} = \hat\alpha \odot \hat{\boldsymbol{\kappa}}^{xx}$. The system becomes
$(\hat{\boldsymbol{\kappa}}^{xx} + \lambda_\mathrm{r}) \odot \hat\alpha = \hat g$, one division per frequency:
$\hat\alpha = \hat g / (\hat{\boldsymbol{\kappa}}^{xx} + \lambda_\mathrm{r})$, $n$ divisions in place of an $n \times n$
solve.

(b) $x$ shifted by $t = 0, 1, 2, 3$ is $(1,1,0,0)$, $(0,1,1,0)$, $(0,0,1,1)$, $(1,0,0,1)$, each
over $\sqrt 2$, so $\boldsymbol{\kappa}^{xx} = (1, 1/2, 0, 1/2)$. $\hat{\boldsymbol{\kappa}}^{xx}_k = 1 + \tfrac12 (-i)^k +
\tfrac12 i^k$: $\hat{\boldsymbol{\kappa}}^{xx} = (2, 1, 0, 1)$. $\hat g = (1, 1, 1, 1)$, so
$\hat\alpha = (1/3, 1/2, 1, 1/2)$, and
$\alpha_t = \tfrac14 \sum_k \hat\alpha_k\, i^{kt}$:
$\alpha = (7/12, -1/6, 1/12, -1/6)$. With $\mathbf{K} + I$ the circulant of rows
$(2, \tfrac12, 0, \tfrac12)$, $(\tfrac12, 2, \tfrac12, 0)$, $(0, \tfrac12, 2, \tfrac12)$,
$(\tfrac12, 0, \tfrac12, 2)$: row $i = 0$ gives
$\tfrac{14}{12} - \tfrac1{12} - \tfrac1{12} = 1$, row 1
$\tfrac7{24} - \tfrac8{24} + \tfrac1{24} = 0$, row 2
$-\tfrac1{12} + \tfrac2{12} - \tfrac1{12} = 0$, row 3 $\tfrac7{24} + \tfrac1{24} -
\tfrac8{24} = 0$: $g$.

(c) $\hat{\boldsymbol{\kappa}}^{xx}_2 = 0$: $\mathbf{K}$ is singular ($\mathbf{K} (1, -1, 1, -1)^T = 0$), and $\hat\alpha_2 =
\hat g_2 / 0$ with $\hat g_2 = 1$: $\mathbf{K}\alpha = g$ has no solution. $\lambda_\mathrm{r} > 0$ makes every
$\hat{\boldsymbol{\kappa}}^{xx} + \lambda_\mathrm{r}$ positive ($\hat{\boldsymbol{\kappa}}^{xx}$ holds the eigenvalues of $\mathbf{K}$, never negative
for a positive semi-definite kernel such as the linear or the Gaussian one), so the system
always has exactly one solution.
"""
