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
`dual(x, y, sigma, lam)` returning $\alpha$ (real, length $n$) for the Gaussian kernel
$k(x, x') = \exp(-\lVert x - x'\rVert^2 / (n\sigma^2))$. It must equal
$(K + \lambda I)^{-1} y$ with the $n \times n$ kernel matrix of all shifts written out. By
hand first: $x = 0$ makes every kernel value 1, so for $n = 2$, $y = (1, 1)$ and
$\lambda = 1$, $(J + I)\alpha = y$ gives $\alpha = (1/3, 1/3)$. The check uses that case and
the explicit solve on a random signal.
--- solution
The kernel matrix of all cyclic shifts is circulant, so the Fourier transform diagonalises
it: $\hat\alpha = \hat y / (\hat k + \lambda)$, with $k$ its first row,
$k_t = \exp(-(2\lVert x\rVert^2 - 2\,x \cdot \text{shift}_t(x)) / (n\sigma^2))$.
"""
