"""The exercises of 03_hog: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "03_hog"

TEXT = r"""
=== 3.1 ★ use | Halve the light
Darken the first frame of `robot-corridor-day` by half (`frame0 // 2`). Compute the
Bhattacharyya coefficient between the target's descriptor on the dark frame and on the
original, for the colour histogram (`color_histograms`) and for the HOG (`hog_descriptors`),
both on the ground-truth box of frame 0. Answer `(rho_colour, rho_hog)`. Which feature is
nearly blind to the change, and why?
--- solution
Halving the intensities halves every gradient: the orientations stay, the magnitudes scale by
the same factor, and the normalised HOG hardly moves (rounding of the uint8 halving is all
that is left). The V channel of HSV halves too, so pixels move to other value bins and the
colour ρ drops.

=== 3.2 ★ use | Which bin is "up"?
The 8 orientation bins are $[u\,\pi/4, (u+1)\,\pi/4)$, $u = 0, \dots, 7$ (the library counts
from 0, eq. 5 from 1), of the angle
$\tilde\theta = \operatorname{atan2}(g_y, g_x) \in [0, 2\pi)$ (eq. 3–4). Which bin `u` does a
gradient pointing straight *up* the image fall into? Why is it not bin 2?
--- solution
Image rows grow downwards, so "up" is $g_x = 0$, $g_y < 0$:
$\tilde\theta = \operatorname{atan2}(-1, 0) + 2\pi = 3\pi/2$, which is bin 6. Bin 2 ($\pi/2$)
holds gradients pointing down the image.

=== 3.3 ★★ modify | An unsigned descriptor
Make the descriptor unsigned like Dalal and Triggs': fold bins $u$ and
$u + 4$ of `hog_of_patch(patch)` together. Compare the HOG ρ of the target with a copy of
itself with inverted contrast (`255 - patch`), signed and unsigned.
--- solution
Inverting the contrast turns every gradient by 180°: the unsigned descriptor cannot tell the
two apart (ρ = 1), the signed one can.

=== 3.4 ★★ modify | How much colour?
Run `color-hog-pf` on the night clip with $\alpha$ = 0, 0.02, 0.1 and 0.5
(seeds 0–2). How does the mean AUC move, and how does that fit the measurement of the two
features at night in the {doc}`case study <case_study_lee2012>`?
--- solution
The mean AUC falls as $\alpha$ grows, and most of the fall comes with the first, small weights
on colour, below $\alpha = 0.1$; beyond it little more is lost. That fits the measurement: at night
HOG's likelihood varies less across the candidates than colour's, so even a small weight on
colour lets colour, the feature more often off target at night, carry most of the spread of
the fused weights and decide.

=== 3.5 ★★★ implement | Fusing the two likelihoods
Write `my_fuse(rho_c, rho_h, alpha, sigma)`: the normalised particle weights of eq. 14 from
the colour and HOG Bhattacharyya coefficients of each particle, with the corrected likelihood
of eq. 10–11, $p \propto \exp(-(1 - \rho)/2\sigma^2)$. By hand first: with
$\sigma^2 = 0.05$, $\alpha = 1/2$, $\rho_c = (1, 0.9)$ and $\rho_h = (1, 1)$ the two particles
get $1$ and $\tfrac12(e^{-1} + 1)$ before normalising. The check uses that case and
$\alpha = 1$ (colour alone).
--- solution
$(1 - 0.9) / (2 \cdot 0.05) = 1$, so the second particle's colour term is $e^{-1}$; its HOG
term is $e^0 = 1$. The constant $1/\sqrt{2\pi\sigma^2}$ cancels in the normalisation. The
HOG term here is flat: with colour alone ($\alpha = 1$) the first particle gets
$1/(1 + e^{-1}) \approx 0.73$ of the weight, with the flat HOG term at $\alpha = 1/2$ only
$1/(1 + \tfrac12(e^{-1} + 1)) \approx 0.59$. Same order, pulled towards uniform.

=== 3.6 ★★★ implement | The gradient as a loop
Write `gx_loop(P)`: the horizontal gradient of eq. 2 (central differences
$I(x+1, y) - I(x-1, y)$, with the border replicated: $I(-1, y) = I(0, y)$,
$I(w, y) = I(w - 1, y)$) of a 2-D patch `P`, as a plain Python loop over pixels. By hand
first: the row $(0, 1, 4, 9)$ gives $(1 - 0, 4 - 0, 9 - 1, 9 - 4) = (1, 4, 8, 5)$. The check
uses that row and a constant one.

=== 3.7 ★★ pen and paper | Why HOG ignores brightness and contrast
Let $I' = cI + b$ with $c > 0$. Show from eq. 2–5 that every pixel's orientation bin is
unchanged, that every magnitude is multiplied by $c$, and hence that a normalised cell
histogram is unchanged. What happens for $c < 0$ (inverted contrast), and what does the
clipping of a `uint8` frame at 0 and 255 change in the argument?
--- solution
The central differences of $I'$ are $g'_x = c\,g_x$ and $g'_y = c\,g_y$: the offset $b$
cancels. For $c > 0$, $\operatorname{atan2}(c g_y, c g_x) = \operatorname{atan2}(g_y, g_x)$,
so every pixel keeps its bin, and $\sqrt{g_x'^2 + g_y'^2} = c\sqrt{g_x^2 + g_y^2}$. Every bin of
a cell's histogram is a sum of magnitudes, so the whole histogram is multiplied by $c$, and
dividing by its norm removes $c$. For $c < 0$ the angle turns by $\pi$: bin $u$ becomes bin
$u + 4 \pmod 8$, which is why a signed descriptor tells inverted contrast apart (exercise 3.3).
Clipping breaks the linear relation where pixels saturate, so there the gradients no longer
scale. Exercise 3.1 halves the frame ($c = 1/2$, $b = 0$), which cannot saturate a pixel:
what is left there is the rounding of the integer halving alone (on a float copy of the frame
the two descriptors are identical).
"""
