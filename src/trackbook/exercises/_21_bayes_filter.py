"""The exercises of 21_bayes_filter: their text, defined once (see :mod:`trackbook.exercises`)."""

STEM = "21_bayes_filter"

TEXT = r"""
=== 21.1 ★ pen and paper | One predict and one update by hand
A corridor of five cells, numbered 0 to 4. At frame $t-1$ the belief is $(0.5, 0.5, 0, 0, 0)$.
Between frames the target stays in its cell with probability 0.25 and moves one cell on with
probability 0.75. Then the camera fires in cell 2 and, just as strongly, in cell 4: the
likelihood is $(0.2, 0.2, 0.6, 0.2, 0.6)$. By hand, give the predicted belief, the product of
the prediction and the likelihood, the normaliser $p(z_t \mid z_{1:t-1})$ and the posterior
(as fractions). Why does cell 4 get nothing, although its likelihood is as high as cell 2's?
--- solution
Predict: cell 0 keeps $0.5 \cdot 0.25 = 0.125$; cell 1 receives $0.5 \cdot 0.75$ from cell 0
and keeps $0.5 \cdot 0.25$ of its own, $0.5$ in all; cell 2 receives $0.5 \cdot 0.75 = 0.375$
from cell 1; cells 3 and 4 receive nothing. The predicted belief is
$(0.125, 0.5, 0.375, 0, 0)$, which still adds up to 1.

Update: the product is $(0.125 \cdot 0.2,\ 0.5 \cdot 0.2,\ 0.375 \cdot 0.6,\ 0,\ 0)
= (0.025, 0.1, 0.225, 0, 0)$, whose sum, the normaliser, is $0.35$. Dividing by it gives the
posterior $(1, 4, 9, 0, 0)/14 \approx (0.071, 0.286, 0.643, 0, 0)$.

Cell 4 gets nothing because the prediction gives it probability zero: from cells 0 and 1 no
move of at most one cell reaches it. Zero times any likelihood is zero. The second detection
is a look-alike in a place the target cannot have reached.

=== 21.2 ★★ pen and paper | Predict adds the means and the variances
Let the motion add a move $s$ to the position, $x_t = x_{t-1} + s$, with $s$ drawn from the
motion's probabilities independently of $x_{t-1}$. (a) Show that the predicted belief is the
sum of the chapter, $p(x_t = i \mid z_{1:t-1}) = \sum_j p(s = i - j)\,
p(x_{t-1} = j \mid z_{1:t-1})$. (b) Show that the predicted mean is the old mean plus the mean
move, and the predicted variance the old variance plus the variance of the move. (c) Check (b)
on the chapter's ten cells. (d) The corridor in metres: the belief at $t-1$ is a Gaussian of
mean 30 m and standard deviation 4 m, and the move is Gaussian, 8 m give or take 3 m (standard
deviation). What are the mean and the standard deviation of the prediction? Why can the update
not be summarised as simply?
--- solution
(a) The target is in cell $i$ at frame $t$ if it was in some cell $j$ and then moved $i - j$.
The events "was in $j$" are disjoint, and the move is independent of where the target was, so
the probability of each path is the product, and $p(x_t = i \mid z_{1:t-1})$ is their sum over
$j$. This is a convolution of the belief with the motion's probabilities.

(b) The mean of a sum is the sum of the means: $E[x_t] = E[x_{t-1}] + E[s]$. For the variance,

$$\operatorname{Var}(x_{t-1} + s) = \operatorname{Var}(x_{t-1}) + \operatorname{Var}(s)
+ 2\operatorname{Cov}(x_{t-1}, s),$$

and the covariance is zero because $s$ is independent of $x_{t-1}$. So predicting always
widens the belief, by the motion's own variance, whatever the belief's shape.

(c) Before: mean 2, variance $0.25 \cdot 1 + 0.5 \cdot 0 + 0.25 \cdot 1 = 0.5$. The move: mean
$0.1 \cdot 1 + 0.8 \cdot 2 + 0.1 \cdot 3 = 2$, variance $0.1 \cdot 1 + 0.8 \cdot 0 + 0.1 \cdot 1
= 0.2$. Predicted: mean 4 and variance 0.7, as the chapter's table gives.

(d) Mean $30 + 8 = 38$ m, variance $4^2 + 3^2 = 25$, so a standard deviation of 5 m (and the
sum of two independent Gaussians is again Gaussian). The prediction depends only on the motion
model; the update depends on the measurement and on the shape of the likelihood, and with a
look-alike the posterior is not even one bump. When both belief and likelihood are Gaussian the
update has a closed form too: that is {doc}`the Kalman filter <06_kalman>`, the next chapter.

=== 21.3 ★ pen and paper | Odds: the target against the look-alike
(a) Show that for two cells $a$ and $b$ the posterior odds are the predicted odds times the
likelihood ratio,

$$\frac{p(x_t = a \mid z_{1:t})}{p(x_t = b \mid z_{1:t})}
= \frac{p(x_t = a \mid z_{1:t-1})}{p(x_t = b \mid z_{1:t-1})}
\cdot \frac{p(z_t \mid x_t = a)}{p(z_t \mid x_t = b)},$$

and that the normaliser is not needed. (b) In the chapter's ten cells, give the posterior odds
of cell 5 against cell 4 from the predicted belief and the likelihood alone, and check them
against the posterior. (c) Move the look-alike from cell 8 to cell 6 (likelihood 0.7 in cells
5 and 6, 0.1 elsewhere). What are the posterior odds of cell 5 against cell 6? How many times
more probable than the target's would the look-alike's image have to be, as a likelihood ratio,
for cell 6 to be as probable as cell 5?
--- solution
(a) Write Bayes' rule for both cells and divide: the normaliser $p(z_t \mid z_{1:t-1})$ is the
same for every cell and cancels, leaving the prediction times the likelihood for each.

(b) Predicted odds $0.25 / 0.45 = 5/9$, likelihood ratio $0.7 / 0.1 = 7$: posterior odds
$35/9 \approx 3.9$. The chapter's posterior gives $0.7 / 0.18 = 35/9$.

(c) Predicted odds $0.25 / 0.025 = 10$, likelihood ratio $0.7 / 0.7 = 1$: posterior odds 10,
so the target's cell is ten times as probable as the look-alike's. The look-alike's image
would need a likelihood ten times the target's to draw level. In cell 8, where the prediction
is zero, no likelihood ratio makes it win: the predicted odds are infinite.

=== 21.4 ★★ pen and paper | The normaliser is the probability of the measurement
(a) Show that the normaliser $p(z_t \mid z_{1:t-1}) = \sum_i p(z_t \mid x_t = i)\,
p(x_t = i \mid z_{1:t-1})$ lies between the smallest and the largest value of the likelihood.
(b) In the chapter's ten cells it is 0.25. Compute it for a motion model that says the target
stands still (it stays with probability 0.8, moves one cell either way with 0.1 each), with the
same belief at $t-1$ and the same likelihood. (c) Under which motion model was the image more
probable, and by what factor? (d) Show that the probability of all the images,
$p(z_{1:T})$, is the product of the normalisers of the frames $t = 1, \dots, T$, and say how a
tracker could use it to choose between two motion models.
--- solution
(a) The predicted probabilities are at least 0 and add up to 1, so the normaliser is a weighted
average of the likelihood's values: no smaller than the smallest and no larger than the
largest.

(b) Standing still spreads the belief $(0.25, 0.5, 0.25)$ in cells 1 to 3 over cells 0 to 4:
$(0.025, 0.25, 0.45, 0.25, 0.025)$. All five cells have likelihood 0.1, so the normaliser is
$0.1 \cdot 1 = 0.1$: the smallest value of the likelihood, since the prediction puts no
probability where something target-like was seen.

(c) Under the walking model: $0.25 / 0.1 = 2.5$ times as probable. The walking model had
predicted where the camera fired; the standing model had not.

(d) By the chain rule of probability,
$p(z_{1:T}) = p(z_1)\, p(z_2 \mid z_1) \cdots p(z_T \mid z_{1:T-1})$, and each factor is the
normaliser of its frame. A tracker can run one filter per motion model on the same images and
compare the products of their normalisers (in practice the sums of their logarithms): the model
under which the images were more probable explains them better. The multiple-model filter of
the {doc}`Kalman-design chapter <17_kalman_filter_design>` weighs its models frame by frame in
this way.

=== 21.5 ★ use | How strong must a look-alike be?
In the chapter's corridor in metres the look-alike at 60 m is 0.6 times as strong as the target
at 40 m, and less than 0.1 % of the posterior lies beyond 50 m. Make it 1, 100, 1000 and
10 000 times as strong as the target (the factor in front of `gauss(x, 60, 3)`), keeping the
prediction. What share of the posterior lies beyond 50 m each time? Answer a dict
`{1: share, 100: share, 1000: share, 10000: share}`. About how strong must the look-alike be
to take half of the belief?
--- solution
The shares are about 0.001, 0.07, 0.44 and 0.85 (the exercises appendix prints them below
the exercise): the look-alike must be about a thousand times as strong as the target to take
half of the belief. The reason: the predicted belief is a Gaussian of mean 38 m and standard
deviation 5 m (exercise 21.2). The probability that each likelihood bump collects is the
integral of the prediction times the bump, which for two Gaussians is a Gaussian in the
distance between their centres, with the two variances added, $5^2 + 3^2 = 34$ m². The
target's bump is 2 m from the prediction, the look-alike's 22 m, so the look-alike collects
$e^{-(22^2 - 2^2)/(2 \cdot 34)} = e^{-480/68} \approx 1/1160$ as much per unit of strength. A
look-alike 1160 times as strong as the target collects as much as the target, so half of the
belief (a look-alike 100 times as strong gets $100/1260$ of it, and so on). The share beyond
50 m is a little smaller: the prediction pulls the look-alike's posterior bump towards 38 m, to
about 54 m, and a little of it falls short of 50 m, so on the grid half lies beyond 50 m at a
strength of about 1300. A motion model that says "about 38 m" turns a 20 m jump into odds of
a thousand to one.

=== 21.6 ★★ modify | A look-alike that walks a little slower
In the chapter's frame-after-frame run, let the look-alike start 20 m behind the target and
never stop, walking 7, 6 or 4 m per frame while the target walks 8: at 7 m per frame its
position in frame $k$ is $8 + 7\,(k - 1)$ m, and likewise at 6 and 4. Run 9 frames for each
pace. What share of the belief lies near the look-alike (within 8 m, the chapter's
`share_near`) in frame 9? Answer a dict `{7: share, 6: share, 4: share}`. Why does a
look-alike 1 m per frame slower than the target keep so much of the belief, when one that
stops loses almost all of it in three frames?
--- solution
In frame 9 the look-alike keeps about 0.41 of the belief at 7 m per frame, about 0.18 at 6 m
and well under 1 % at 4 m (the exercises appendix prints the shares below the exercise). The
motion model knows no velocity: it asks only that every step be about 8 m, give or take 3 m. A
walker 1 m per frame slower stays well within that give-or-take, and each frame the prediction
puts its peak only a little ahead of where the camera then sees it; the likelihood there is
still close to its maximum, and the peak loses only a few per cent of its weight a frame. The
loss grows like a Gaussian of the gap between prediction and measurement: twice the gap costs
four times as much in the exponent, so a walker 4 m per frame slower fades within a few frames
and one that stops (a gap of 8 m) faster still. A tighter motion model (a smaller
give-or-take) would veto a slow look-alike sooner, and would also lose a target that really
changes its pace: the motion model's spread is a trade.

=== 21.7 ★★★ implement | One step of a grid Bayes filter
Write `grid_step(belief, motion, likelihood)` returning `(posterior, normaliser)`: `belief` and
`likelihood` are arrays over the same $n$ cells, and `motion` maps a move (in cells, possibly
0 or negative) to its probability, as in the chapter. Predict by handing each cell's
probability on along every move, update by multiplying by the likelihood, and return the
normalised posterior and the normaliser $p(z_t \mid z_{1:t-1})$. The cells form a ring (a
circular track): a move past the last cell comes back in at the first. By hand first: the
chapter's ten cells give the posterior $(0, 0, 0.01, 0.1, 0.18, 0.7, 0.01, 0, 0, 0)$ and the
normaliser 0.25. The check uses that case, exercise 21.1 and two where the belief wraps round
the ring, one each way.
--- solution
```python
def grid_step(belief, motion, likelihood):
    belief = np.asarray(belief, dtype=float)
    predicted = np.zeros_like(belief)
    for move, p_move in motion.items():
        predicted += p_move * np.roll(belief, move)   # cell j -> j + move
    product = np.asarray(likelihood, dtype=float) * predicted
    normaliser = product.sum()
    return product / normaliser, normaliser
```
`np.roll(belief, move)` moves the probability of every cell $j$ to cell $j + \text{move}$,
wrapping round the ring, which is the sum
$\sum_j p(\text{move} = i - j)\, p(x_{t-1} = j)$ one move at a time. The direction matters:
rolling by `-move` walks the target backwards. The product with the likelihood is the
numerator of Bayes' rule and its sum the normaliser. The wrap-round case: a belief $(1, 0, 0, 0)$
with moves $-1$ and $+1$ of probability one half each predicts $(0, 0.5, 0, 0.5)$ (the move
$-1$ from cell 0 comes in at cell 3); the likelihood $(1, 1, 1, 0.2)$ gives the product
$(0, 0.5, 0, 0.1)$, the normaliser 0.6 and the posterior $(0, 5/6, 0, 1/6)$. The other way
round: a belief $(0, 0, 0, 1)$ that stays or moves $+1$ with probability one half each
predicts $(0.5, 0, 0, 0.5)$ (the move $+1$ from cell 3 comes in at cell 0); the likelihood
$(0.2, 1, 1, 1)$ gives the product $(0.1, 0, 0, 0.5)$, the normaliser 0.6 and the posterior
$(1/6, 0, 0, 5/6)$. A function that wraps only one way, say by Python's negative indices, fails
this case. The exercises appendix runs this solution through the check.
"""
