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
from 0, the chapter's $D_u$ from 1), of the signed angle
$\tilde\theta = \operatorname{atan2}(g_y, g_x) \in [0, 2\pi)$. Which bin `u` does a
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

=== 3.4 ★★ modify | How much colour? | after case_study_lee2012
Run `color-hog-pf` on the night clip with $\alpha$ = 0, 0.02, 0.1 and 0.5
(seeds 0–2). How does the mean AUC move, and how does that fit the measurement of the two
features at night in the {doc}`case study <case_study_lee2012>`?
--- solution
The mean AUC falls as $\alpha$ grows, and most of the fall comes with the first, small weights
on colour, below $\alpha = 0.1$; beyond it little more is lost. That fits the measurement: at night
HOG's likelihood varies less across the candidates than colour's, so even a small weight on
colour lets colour, the feature more often off target at night, carry most of the spread of
the fused weights and decide.

=== 3.5 ★★★ implement | Fusing the two likelihoods | after case_study_lee2012
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
Write `gx_loop(P)`: the horizontal gradient of the chapter (central differences
$I(x+1, y) - I(x-1, y)$, with the border replicated: $I(-1, y) = I(0, y)$,
$I(w, y) = I(w - 1, y)$) of a 2-D patch `P`, as a plain Python loop over pixels. By hand
first: the row $(0, 1, 4, 9)$ gives $(1 - 0, 4 - 0, 9 - 1, 9 - 4) = (1, 4, 8, 5)$. The check
uses that row and a constant one.
--- solution
```python
def gx_loop(P):
    h, w = P.shape
    out = np.zeros((h, w))
    for y in range(h):
        for x in range(w):
            # the replicated border:
            # I(-1, y) = I(0, y), I(w, y) = I(w - 1, y)
            right, left = P[y, min(x + 1, w - 1)], P[y, max(x - 1, 0)]
            out[y, x] = right - left
    return out
```
The central difference takes, at every pixel, the right neighbour minus the left one. Inside
the patch both exist; at the borders the replicated pixel stands in for the missing one, which
is the same as clamping the column index into $0, \dots, w - 1$ (`min`, `max`). So the first
column gets the one-sided difference $I(1, y) - I(0, y)$ and the last $I(w-1, y) - I(w-2, y)$,
taken over one pixel instead of two: a border pixel still sees the edge it sits on, and
nothing outside the box enters. By hand, the row $(0, 1, 4, 9)$: at $x = 0$, $1 - 0 = 1$; at
$x = 1$, $4 - 0 = 4$; at $x = 2$, $9 - 1 = 8$; at $x = 3$, $9 - 4 = 5$. A constant row has
every difference 0, borders included: no edge, no vote. The library's `gradients` computes the
same with array slices for many patches at once (the chapter compares the two on a random
patch); the exercises appendix runs this solution through the check.

=== 3.7 ★★ pen and paper | Why HOG ignores brightness and contrast
Let $I' = cI + b$ with $c > 0$. Show from the chapter's steps (central differences,
magnitude and signed angle, the cell histogram $D_u$) that every pixel's orientation bin is
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

=== 3.8 ★★ pen and paper | One pixel's gradient and its vote
Take the 3 × 3 grey patch (no blur; $x$ along the columns, $y$ down the rows)

$$I = \begin{bmatrix} 20 & 10 & 70 \\ 60 & 35 & 30 \\ 90 & 50 & 40 \end{bmatrix}.$$

For its centre pixel compute the central differences $g_x$ and $g_y$, the magnitude $m$ and
the signed angle $\tilde\theta \in [0, 2\pi)$ (mind the quadrant: use
$\operatorname{atan2}(g_y, g_x)$), and the bin $u$ (counted from 0)
of the chapter's 8 signed bins $[u\,\pi/4, (u+1)\,\pi/4)$. Dalal and Triggs' unsigned
descriptor instead folds the angle into $[0°, 180°)$ and has 9 bins of 20°, bin $k$ centred
at $20k + 10°$ ($k = 0, \dots, 8$); it splits the magnitude linearly between the two bins
whose centres are nearest, each getting $m \cdot (1 - d/20°)$ with $d$ the angle's distance
to that bin's centre. Which two bins get how much? Then invert the contrast, $255 - I$: what
happens to $g_x$, $g_y$, $m$, $\tilde\theta$, the signed bin and the unsigned votes?
--- solution
The central differences at the centre: $g_x = I(x+1, y) - I(x-1, y) = 30 - 60 = -30$ and
$g_y = I(x, y+1) - I(x, y-1) = 50 - 10 = 40$ (the corners do not enter). Then
$m = \sqrt{(-30)^2 + 40^2} = 50$. With $g_x < 0$ and $g_y > 0$ the gradient lies in the second
quadrant: $\theta = \operatorname{atan2}(40, -30) = 180° - \arctan(40/30) = 180° - 53.13°
= 126.87°$ (2.214 rad). A plain $\tan^{-1}(g_y / g_x) = \tan^{-1}(-4/3) = -53.13°$ would name
the opposite direction. As $\theta \ge 0$, it is kept: $\tilde\theta = 126.87°$, and
$u = \lfloor 126.87 / 45 \rfloor = 2$, the bin $[90°, 135°)$ (bin 3 when counted from 1, as
$D_u$ counts). The image gets brighter towards the left ($g_x < 0$) and down ($g_y > 0$, as
$y$ grows downwards).

Unsigned: $126.87°$ is already in $[0°, 180°)$. The nearest centres are $130°$ ($k = 6$, at
$d = 3.13°$) and $110°$ ($k = 5$, at $d = 16.87°$): bin 6 gets
$50 \cdot (1 - 3.13/20) \approx 42.2$ and bin 5 gets $50 \cdot (1 - 16.87/20) \approx 7.8$,
together $m = 50$.

Inverted contrast: the 255 cancels in the differences and their signs flip, $g_x = 30$,
$g_y = -40$, $m = 50$ unchanged. $\theta = \operatorname{atan2}(-40, 30) = -53.13° < 0$, so
$360°$ is added: $\tilde\theta = 306.87°$, bin $\lfloor 306.87/45 \rfloor = 6 = 2 + 4$: the
signed descriptor moves the vote to the opposite bin. Folded into $[0°, 180°)$,
$306.87° - 180° = 126.87°$, the same angle as before: the unsigned votes are again 42.2 in bin
6 and 7.8 in bin 5, and the unsigned descriptor cannot tell the two contrasts apart
(exercise 3.3 measures this on the target).

=== 3.9 ★★ pen and paper | Block normalisation: L2-Hys against a plain sum
A 36-value block of Dalal and Triggs' descriptor (2 × 2 cells of 9 bins) holds one strong
edge and weak texture: one value 4, sixteen values 1 and nineteen values 0. Normalise it with
L2-Hys, taking $\varepsilon = 0$: $v \leftarrow v / \lVert v \rVert_2$, clip every value at
0.2, then $v \leftarrow v / \lVert v \rVert_2$ once more. Give the strong value and a weak
value after each step, and the ratio of the strong to a weak value at the start and at the
end. Is every value at most 0.2 at the end? Then normalise the same 36 values the way the
chapter's descriptor is normalised, dividing by their sum ($f$ in the chapter's $D_u$, taken
over the whole descriptor): values and ratio? What does the clipping buy?
--- solution
$\lVert v \rVert_2^2 = 4^2 + 16 \cdot 1^2 = 32$, $\lVert v \rVert_2 = 4\sqrt 2 \approx 5.657$:
the strong value becomes $4 / (4\sqrt 2) = 1/\sqrt 2 \approx 0.707$ and a weak one
$1 / (4\sqrt 2) \approx 0.177$. The ratio is still 4: dividing by a norm scales every value by
the same factor. Clipping at 0.2 turns 0.707 into 0.2 and leaves the weak values
($0.177 < 0.2$) and the zeros alone. The new norm is
$\sqrt{0.2^2 + 16 \cdot \tfrac1{32}} = \sqrt{0.04 + 0.5} = \sqrt{0.54} \approx 0.735$, so the
final values are $0.2 / 0.735 \approx 0.272$ and $0.177 / 0.735 \approx 0.241$: ratio
$0.2 \cdot 4\sqrt 2 = 0.8\sqrt 2 \approx 1.13$ instead of 4. Not every value is at most 0.2 at
the end: the second normalisation lifts all seventeen non-zero values above it. The recipe
clips once and normalises once more; it does not repeat until the bound holds. Dividing by the
sum, $4 + 16 = 20$, gives 0.2 and 0.05: the ratio stays 4, as for any division by one
number. Only the clipping changes the ratio: it caps what one strong edge can contribute, so
the block says more about which directions occur and less about how strong the strongest one
is, and a single high-contrast edge (a sharp shadow, a bright border) cannot swamp the rest.
The chapter's descriptor has no such cap: there every edge counts in proportion to its
magnitude, however strong.
"""
