"""The exercises of 14_tracking_by_detection: their text, defined once (see :mod:`trackbook.exercises`),
and the auto-check of its ★★★ exercise."""

import numpy as np

STEM = "14_tracking_by_detection"

TEXT = r"""
=== 14.1 ★ pen and paper | The noisy-OR by hand
A positive bag holds three patches whose instance probabilities are 0.3, 0.4 and 0.5; a
negative bag holds two patches of probability 0.1 each. Compute both bag probabilities and
the bag log-likelihood $\mathrm{L}$. Then show that one negative bag of $n$ instances
contributes exactly what $n$ negative bags of one instance each contribute, so it does not
matter how the negatives are grouped.
--- solution
The positive bag: $\pi = 1 - (0.7)(0.6)(0.5) = 1 - 0.21 = 0.79$. The negative bag:
$\pi = 1 - (0.9)(0.9) = 0.19$. With the labels 1 and 0,
$\mathrm{L} = \ln 0.79 + \ln(1 - 0.19) = -0.2357 - 0.2107 = -0.4464$.

A negative bag contributes $\ln(1 - \pi_i) = \ln \prod_j (1 - \pi_{ij}) = \sum_j
\ln(1 - \pi_{ij})$, which is the sum of what each instance contributes as a bag of its own
($\ln(1 - \pi_{ij})$). The noisy-OR only changes the positive bags: for them
$\ln \pi_i = \ln\big(1 - \prod_j (1 - \pi_{ij})\big)$ does not split into a sum.

=== 14.2 ★★ pen and paper | The gradient of the bag log-likelihood
Let $\pi_{ij} = \operatorname{sig}(\Psi_{ij})$ with $\Psi_{ij} = \Psi(z_{ij})$. Show that

$$\frac{\partial \mathrm{L}}{\partial \Psi_{ij}} = \frac{\ell_i - \pi_i}{\pi_i}\,\pi_{ij}.$$

Evaluate it for the three instances of the positive bag of the chapter's hand-worked example
($\pi_{ij} = 0.5, 0.2, 0.1$; $\pi_i = 0.64$) and for an instance of a negative bag. What does
the result say about which patch of a positive bag the learner pushes up?
--- solution
Only bag $i$ depends on $\Psi_{ij}$. From $\pi_i = 1 - \prod_k (1 - \pi_{ik})$,
$\partial \pi_i / \partial \pi_{ij} = \prod_{k \ne j} (1 - \pi_{ik}) = (1 - \pi_i)/(1 - \pi_{ij})$,
and $\partial \pi_{ij}/\partial \Psi_{ij} = \pi_{ij}(1 - \pi_{ij})$ (the derivative of the
sigmoid). So $\partial \pi_i / \partial \Psi_{ij} = (1 - \pi_i)\,\pi_{ij}$. A positive bag
contributes $\ln \pi_i$, whose derivative is $(1 - \pi_i)\pi_{ij}/\pi_i$; a negative bag
contributes $\ln(1 - \pi_i)$, whose derivative is $-\pi_{ij}$. Both are
$(\ell_i - \pi_i)\pi_{ij}/\pi_i$ for $\ell_i = 1$ and $\ell_i = 0$.

For the positive bag, $(1 - 0.64)/0.64 = 0.5625$, so the three weights are $0.281$, $0.113$
and $0.056$; a negative instance gets $-\pi_{ij}$. The weight of an instance in a positive bag
is proportional to its own probability: the learner pushes up the patch it already finds most
target-like, and hardly the others. That is how MIL lets the classifier choose which patch of
the bag is the target, instead of being told (the weights are MILBoost's, Viola, Platt and
Zhang 2005).

=== 14.3 ★★ pen and paper | When the errors of the P-N experts cancel
Let $e^+(\tau)$ and $e^-(\tau)$ be the numbers of false positives and false negatives of the
detector after learning iteration $\tau$. The N-expert flags a share $\mathrm{Re}^-$ (its recall)
of the false positives and is right with precision $\mathrm{Pr}^-$; the P-expert flags a share
$\mathrm{Re}^+$ of the false negatives with precision $\mathrm{Pr}^+$. Every flagged example is relabelled and learned, and learning a
relabelled example fixes or makes exactly one error. Show that

$$\begin{pmatrix} e^+ \\ e^- \end{pmatrix}(\tau + 1) = \begin{pmatrix} 1 - \mathrm{Re}^- &
\frac{(1 - \mathrm{Pr}^+)\mathrm{Re}^+}{\mathrm{Pr}^+} \\
\frac{(1 - \mathrm{Pr}^-)\mathrm{Re}^-}{\mathrm{Pr}^-} & 1 - \mathrm{Re}^+ \end{pmatrix}
\begin{pmatrix} e^+ \\ e^- \end{pmatrix}(\tau),$$

and that both errors go to zero when the matrix's eigenvalues are smaller than one in
magnitude. Check it for $\mathrm{Pr}^+ = 0.8$, $\mathrm{Re}^+ = 0.5$, $\mathrm{Pr}^- = 0.9$,
$\mathrm{Re}^- = 0.6$. What happens with perfect experts ($\mathrm{Pr}^\pm = 1$)?
--- solution
The N-expert relabels $n^-$ examples as negative. The correct ones are false positives it
found, $\mathrm{Re}^- e^+$ of them, so $n^- = \mathrm{Re}^- e^+ / \mathrm{Pr}^-$, and the wrong
ones, $(1 - \mathrm{Pr}^-) n^-$, are true positives turned into new false negatives. Likewise the
P-expert removes $\mathrm{Re}^+ e^-$ false negatives and adds
$(1 - \mathrm{Pr}^+) \mathrm{Re}^+ e^- / \mathrm{Pr}^+$ false positives. Hence
$e^+(\tau + 1) = (1 - \mathrm{Re}^-) e^+ + (1 - \mathrm{Pr}^+)\mathrm{Re}^+ e^- / \mathrm{Pr}^+$
and $e^-(\tau + 1) = (1 - \mathrm{Re}^+) e^- + (1 - \mathrm{Pr}^-) \mathrm{Re}^- e^+ /
\mathrm{Pr}^-$: the matrix above. Call the matrix $E$. The errors are
$E^\tau$ times the first ones, and $E^\tau \to 0$ when every eigenvalue of $E$ lies inside the
unit circle. This is the analysis of Kalal, Mikolajczyk and Matas (2012): each expert makes
errors, but as long as the other one corrects more than they add, the errors cancel.

The numbers: $E = \begin{pmatrix} 0.4 & 0.125 \\ 0.0667 & 0.5 \end{pmatrix}$, trace 0.9,
determinant $0.2 - 0.00833 = 0.1917$, eigenvalues $(0.9 \pm \sqrt{0.81 - 0.7667})/2 = 0.554$
and $0.346$: both below one, the errors shrink. With $\mathrm{Pr}^\pm = 1$ the matrix is
diagonal, $\operatorname{diag}(1 - \mathrm{Re}^-, 1 - \mathrm{Re}^+)$: perfect experts never add errors and every recall above
zero removes them.

=== 14.4 ★★★ implement | The noisy-OR bag probability and the bag log-likelihood
Write `mil_likelihood(probs, bags, labels)` that returns `(bag_probs, L)`: `probs` holds the
instance probabilities $\pi_{ij}$ of all instances, `bags[k]` the bag (0, 1, …) of instance
`k`, in any order, and `labels[i]` the label $\ell_i \in \{0, 1\}$ of bag $i$. `bag_probs[i]`
is the noisy-OR $\pi_i = 1 - \prod_j (1 - \pi_{ij})$ and `L` the bag log-likelihood
$\sum_i \ell_i \ln \pi_i + (1 - \ell_i) \ln(1 - \pi_i)$. No Python loop over instances. The
check uses the chapter's hand-worked example ($\pi_i = 0.64, 0.28$ and
$\mathrm{L} = \ln 0.64 + \ln 0.72$), the same instances in another order, bags of one instance
(where $\mathrm{L}$ is the ordinary log-likelihood) and a bag with a certain instance.
--- hint
Sum $\ln(1 - \pi_{ij})$ per bag with `np.bincount(bags, weights=..., minlength=...)`; that sum
is $\ln(1 - \pi_i)$.
--- solution
With $s_i = \sum_j \ln(1 - \pi_{ij})$ (one `np.bincount`), $\pi_i = 1 - e^{s_i}$, and a negative
bag contributes $s_i$ itself, which stays exact when $\pi_i$ is tiny.

=== 14.5 ★ use | A jump inside the search radius
In `red-cube` the cube jumps by 8 to 10 px per frame at frames 138 to 142. Run
`opencv-mil` on it and plot the IoU per frame. Does MIL keep the cube through the jump? Relate
the answer to the radius of the positions OpenCV's MIL scores each frame
(`cv2.TrackerMIL_Params().samplerSearchWinSize`).
--- solution
It keeps it: the IoU stays above 0.5 through frames 135 to 150. OpenCV's MIL scores every
position within 25 px of the last one, and a step of 9 px, even several in a row, never leaves
that disc; the Haar features of the cube are the same before and after the jump. A step larger
than the radius would be lost at once, however good the classifier.

=== 14.6 ★★ modify | Which colour does MIL see?
Build a copy of the first 60 frames of `shelves` whose green and red channels are set to zero
(`clips.Clip(name, clips.ArrayFrames(frames), groundtruth)`) and run `opencv-mil` on the copy
and on the original 60 frames. Compare the boxes. Then replace the *blue* channel by the grey
level (the mean of the three channels) instead and compare again. What does OpenCV's MIL
compute its Haar features on?
--- solution
The boxes with green and red set to zero are the same as the original ones, to the pixel; the
boxes with the blue channel changed differ. OpenCV's MIL builds its integral image from the
first channel of the frame it is given, which for a BGR frame is blue: it never sees green or
red. (Each run is in a fresh process, so the comparison is exact: see the reference tracker's
documentation.) A target that differs from its surroundings only in red or green is invisible to
it; convert the frames to grey first if that matters.
"""


def mil_likelihood_ok(f):
    """14.4: noisy-OR bag probabilities and the bag log-likelihood."""
    cases = [
        # the chapter's example: 1 - 0.5*0.8*0.9 = 0.64 (positive); 1 - 0.9*0.8*1 = 0.28
        # (negative); L = ln 0.64 + ln 0.72
        (([0.5, 0.2, 0.1, 0.1, 0.2, 0.0], [0, 0, 0, 1, 1, 1], [1, 0]),
         [0.64, 0.28], np.log(0.64) + np.log(0.72)),
        # the same instances interleaved: the same answer
        (([0.5, 0.1, 0.2, 0.2, 0.1, 0.0], [0, 1, 0, 1, 0, 1], [1, 0]),
         [0.64, 0.28], np.log(0.64) + np.log(0.72)),
        # bags of one instance: the ordinary log-likelihood ln 0.8 + ln(1 - 0.3)
        (([0.8, 0.3], [0, 1], [1, 0]), [0.8, 0.3], np.log(0.8) + np.log(0.7)),
        # a positive bag with a certain instance: probability 1, contribution 0
        (([1.0, 0.0], [0, 0], [1]), [1.0], 0.0),
    ]
    for (p, b, lab), want_p, want_l in cases:
        got_p, got_l = f(np.asarray(p, float), np.asarray(b), np.asarray(lab))
        if not (np.allclose(np.asarray(got_p, float), want_p, rtol=0, atol=1e-12)
                and abs(float(got_l) - want_l) < 1e-12):
            return False
    return True


CHECKS = {"14.4": mil_likelihood_ok}
