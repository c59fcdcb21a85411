"""The auto-checks of the ★★★ exercises: each one runs the student's function on cases whose
answer is known from the equation or worked out by hand, never on the library function the
student re-implements.

``CHECKS[number]`` is a predicate ``answer -> bool``; :func:`trackbook.exercises.autocheck`
prints its verdict. Each case's expected value is written out in the comment beside it.
A chapter's text module may hold its own checks in a ``CHECKS`` dict of the same form (so a
chapter's exercises and their checks change together); they are gathered here.
"""

from __future__ import annotations

import numpy as np

__all__ = ["CHECKS", "FixedRandom"]


class FixedRandom:
    """A stand-in for ``numpy.random.Generator`` whose ``random`` returns given numbers, so a
    resampler's result can be worked out by hand for a known offset."""

    def __init__(self, values):
        self.values = np.asarray(values, dtype=float)

    def random(self, size=None):
        if size is None:
            return float(self.values.ravel()[0])
        return self.values[:size].copy()


def _close(a, b, atol=1e-9):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and bool(np.allclose(a, b, rtol=0.0, atol=atol))


def iou_ok(f):
    """0.4: IoU of boxes (x, y, w, h), worked by hand."""
    a = np.array([[0, 0, 20, 10], [0, 0, 10, 10], [0, 0, 20, 20], [0, 0, 10, 10],
                  [5, 5, 4, 6]], dtype=float)
    b = np.array([[10, 0, 20, 10], [20, 20, 5, 5], [0, 0, 10, 10], [10, 0, 10, 10],
                  [5, 5, 4, 6]], dtype=float)
    # 10 x 10 overlap of two 200 px boxes: 100 / 300; disjoint: 0; nested: 100 / 400;
    # touching along an edge: 0; identical: 1
    return _close(f(a, b), [1 / 3, 0.0, 0.25, 0.0, 1.0])


def auc_ok(f):
    """0.5: mean over t = 0, 0.05, ..., 1 of the fraction of frames with IoU > t."""
    # IoU 0.25 beats t = 0, ..., 0.2: 5 of 21 thresholds; IoU 1 beats all but t = 1: 20/21;
    # IoU 0 beats none; [0.5, 0] -> 0.5 beats 10 thresholds in one frame of two: 5/21
    cases = [([0.25] * 4, 5 / 21), ([1.0], 20 / 21), ([0.0, 0.0], 0.0), ([0.5, 0.0], 5 / 21)]
    return all(abs(float(f(np.array(i))) - e) < 1e-9 for i, e in cases)


def _kernel_by_definition(h, w):
    """k = 1 - r^2, r the distance of pixel centre (i + 1/2, j + 1/2) to the patch centre over
    the largest such distance, pixel by pixel."""
    d2 = np.array([[(i + 0.5 - h / 2) ** 2 + (j + 0.5 - w / 2) ** 2 for j in range(w)]
                   for i in range(h)])
    return 1 - d2 / d2.max() if d2.max() > 0 else np.ones((h, w))


def kernel_ok(f):
    """1.5: the kernel 1 - r^2 of a patch."""
    # by hand: 1 x 3 -> distances 1, 0, 1 -> (0, 1, 0); 3 x 3 -> corners 0, edges 1/2, centre 1
    if not (_close(f(1, 3), [[0, 1, 0]])
            and _close(f(3, 3), [[0, 0.5, 0], [0.5, 1, 0.5], [0, 0.5, 0]])):
        return False
    return all(_close(f(h, w), _kernel_by_definition(h, w)) for h, w in [(24, 16), (5, 7)])


def histogram_ok(f):
    """1.7: the kernel-weighted histogram (eq. 1 of Lee et al. 2012 [quote: lee2012.kernel_eq1]),
    normalised to sum 1."""
    # labels 0 1 / 1 2 weighted 1 2 / 3 4: bin 0 gets 1, bin 1 gets 2 + 3, bin 2 gets 4; / 10
    labels, kernel = np.array([[0, 1], [1, 2]]), np.array([[1.0, 2.0], [3.0, 4.0]])
    if not _close(f(labels, kernel, 4), [0.1, 0.5, 0.4, 0.0]):
        return False
    # one pixel: all the mass in its bin
    return _close(f(np.array([[3]]), np.array([[0.7]]), 5), [0, 0, 0, 1, 0])


# w = (0.1, 0.2, 0.3, 0.4): cumulative weights c = (0.1, 0.3, 0.6, 1.0)
_W = np.array([0.1, 0.2, 0.3, 0.4])


def stratified_ok(f):
    """2.5: stratified resampling, pointers (k + u_k) / N, smallest i with c_i >= pointer."""
    cases = [  # (weights, the u_k rng.random(N) returns, indices worked by hand)
        (_W, [0.5] * 4, [1, 2, 3, 3]),               # pointers .125 .375 .625 .875
        (_W, [0.0] * 4, [0, 1, 2, 3]),               # pointers 0 .25 .5 .75
        (_W, [0.2, 0.9, 0.1, 0.0], [0, 2, 2, 3]),    # pointers .05 .475 .525 .75
        (np.array([0.5, 0, 0, 0.5]), [0.5] * 4, [0, 0, 3, 3]),  # empty particles get none
    ]
    return all(np.array_equal(np.asarray(f(w, FixedRandom(u))), i) for w, u, i in cases)


def systematic_ok(f):
    """2.8: systematic resampling, one offset u = rng.random() / N and pointers u + k/N."""
    cases = [(_W, 0.5, [1, 2, 3, 3]),                # u = 0.125: pointers .125 .375 .625 .875
             (_W, 0.0, [0, 1, 2, 3]),                # u = 0: pointers 0 .25 .5 .75
             (_W, 0.9, [1, 2, 3, 3]),                # u = .225: .225 .475 .725 .975
             (np.array([0.7, 0.1, 0.1, 0.1]), 0.5, [0, 0, 0, 2])]   # .875 -> c = .9
    return all(np.array_equal(np.asarray(f(w, FixedRandom([u]))), i) for w, u, i in cases)


def fuse_ok(f):
    """3.5: weights of eq. 14 from the likelihood exp(-(1 - rho) / 2 sigma^2) of eq. 10-11."""
    # sigma^2 = 0.05: (1 - rho) / (2 sigma^2) = 1 for rho = 0.9, 0 for rho = 1.
    # alpha = 0.5: p = 0.5 (e^0 + e^0) = 1 and 0.5 (e^-1 + e^0); normalised
    p = np.array([1.0, 0.5 * (np.exp(-1) + 1)])
    ok = _close(f(np.array([1.0, 0.9]), np.array([1.0, 1.0]), 0.5, np.sqrt(0.05)), p / p.sum())
    # alpha = 1: colour only; rho_c = (1, 0.9) -> (1, e^-1) normalised
    q = np.array([1.0, np.exp(-1)])
    return ok and _close(f(np.array([1.0, 0.9]), np.array([0.2, 1.0]), 1.0, np.sqrt(0.05)),
                         q / q.sum())


def gradient_ok(f):
    """3.6: central differences I(x+1) - I(x-1) with the border replicated."""
    # row 0 1 4 9: (1-0, 4-0, 9-1, 9-4); row 2 2 2 2: zeros
    return _close(f(np.array([[0.0, 1, 4, 9], [2, 2, 2, 2]])), [[1, 4, 8, 5], [0, 0, 0, 0]])


def svd_update_ok(f):
    """4.5: one incremental step of eq. 6-7 must give the SVD of [U Sigma, b]."""
    # U = e1, Sigma = 2, b = 3 e2: [U Sigma, b] = [[2, 0], [0, 3], [0, 0]]: singular values
    # 3 and 2, basis e2 and e1 (up to sign)
    U2, S2 = (np.asarray(x, dtype=float) for x in f(np.eye(3)[:, :1], np.array([2.0]),
                                                     np.array([0.0, 3.0, 0.0])))
    if not (_close(S2, [3.0, 2.0]) and _close(np.abs(U2), [[0, 1], [1, 0], [0, 0]])):
        return False
    # b inside span(U) adds no direction: [[2, 1], [0, 0], [0, 0]] has singular value sqrt 5
    U3, S3 = (np.asarray(x, dtype=float) for x in f(np.eye(3)[:, :1], np.array([2.0]),
                                                     np.array([1.0, 0.0, 0.0])))
    return abs(S3[0] - np.sqrt(5)) < 1e-9 and np.all(np.abs(S3[1:]) < 1e-9)


# the rays of 05_edge_rays' exercise 5.1
_M = np.array([5, 9, 2, 7, 6, 3, 8, 4.0])
_P = np.array([6, 10, 2, 7, 6, 3, 9, 5.0])


def ratio_ok(f):
    """5.5: the Ratio of eq. 5, the mean of the 4th and 5th sorted lengths of p over m's."""
    # sorted M: 2 3 4 [5 6] 7 8 9 -> 5.5; sorted p: 2 3 5 [6 6] 7 9 10 -> 6; 6 / 5.5
    return (abs(float(f(_P, _M)) - 6 / 5.5) < 1e-9 and abs(float(f(_M, _M)) - 1) < 1e-9
            and abs(float(f(2 * _M, _M)) - 2) < 1e-9
            and abs(float(f(np.roll(_P, 3), _M)) - 6 / 5.5) < 1e-9)   # order does not matter


def edge_weight_ok(f):
    """5.8: eq. 6, 1 - sum |p - m| / sum m inside the Ratio window, clipped at 0, else 0."""
    ones = np.ones(8)
    cases = [(_P, _M, 1 - 4 / 44),                   # 5.1 by hand: Ratio 1.09 inside
             (_M, _M, 1.0),                          # the model itself
             (1.3 * _M, _M, 0.0),                    # Ratio 1.3 outside, though 1 - 0.3 > 0
             (np.r_[ones[:7], 17.0], ones, 0.0)]     # Ratio 1 but 1 - 16 / 8 < 0: clipped
    got = [float(np.ravel(f(np.atleast_2d(p), m))[0]) for p, m, _ in cases]
    return np.allclose(got, [e for _, _, e in cases], rtol=0.0, atol=1e-9)


def kalman_1d_ok(f):
    """6.5: 1-D Kalman filter, predict m + u, v + q; update K = v / (v + r)."""
    cases = [  # (zs, mu0, var0, u, var_q, var_r) -> (means, variances), by hand
        (([26.0], 20, 4, 0, 0, 12), ([21.5], [3.0])),                 # K = 1/4
        (([26.0, 21.5], 20, 4, 0, 0, 12), ([21.5, 21.5], [3.0, 2.4])),  # then K = 3/15
        (([11.0], 0, 3, 5, 1, 12), ([6.5], [3.0])),                   # predict (5, 4), K = 1/4
    ]
    for args, (mus, vs) in cases:
        m, v = f(*args)
        if not (_close(m, mus) and _close(v, vs)):
            return False
    return True


def _range_bearing(x, s):
    return np.array([np.hypot(x[0] - s[0], x[1] - s[1]), np.arctan2(x[1] - s[1], x[0] - s[0])])


def jacobian_ok(f):
    """6.7: the Jacobian of range and bearing, by hand at (3, 4) and by finite differences."""
    # r = 5, dr/dp = (3/5, 4/5), dtheta/dp = (-4/25, 3/25), velocity columns 0
    if not _close(f(np.array([3.0, 4.0, 1.0, -2.0]), (0.0, 0.0)),
                  [[0.6, 0.8, 0, 0], [-0.16, 0.12, 0, 0]]):
        return False
    x, s, eps = np.array([-2.0, 7.0, 0.3, 0.1]), (1.0, -1.0), 1e-6
    numeric = np.column_stack([(_range_bearing(x + eps * e, s) - _range_bearing(x - eps * e, s))
                               / (2 * eps) for e in np.eye(4)])
    return _close(f(x, s), numeric, atol=1e-6)


def covariance_ok(f):
    """7.6: eq. 4, the population covariance of the features inside a box."""
    # one feature 1 2 / 3 4 over the whole 2 x 2 image: mean 2.5, variance 1.25
    F = np.array([[1.0, 2.0], [3.0, 4.0]])[..., None]
    if not _close(f(F, (0, 0, 2, 2)), [[1.25]]):
        return False
    # the right column only (2, 4): variance 1; two features x and 2x: [[1, 2], [2, 4]]
    G = np.concatenate([F, 2 * F], axis=2)
    return _close(f(G, (1, 0, 1, 2)), [[1.0, 2.0], [2.0, 4.0]])


def motion_ok(f):
    """8.5: the least-squares motion of eq. 8 on a smooth blob moved by (0.4, -0.3) px."""
    yy, xx = np.mgrid[0:64, 0:64].astype(float)

    def blob(cx, cy):
        return 200 * np.exp(-((xx - cx) ** 2 + (yy - cy) ** 2) / (2 * 6.0 ** 2))

    # the blob is moved by construction; a sub-pixel move keeps the linearisation accurate
    return (_close(f(blob(32, 32), blob(32.4, 31.7)), [0.4, -0.3], atol=0.05)
            and _close(f(blob(32, 32), blob(32, 32)), [0.0, 0.0], atol=1e-9))


def switches_ok(f):
    """8.7: identity switches of one face, counted by hand."""
    cases = [([0, 0, -1, 1, 1, -1, 1, 0], 2),   # 0 -> 1, held across the gaps, 1 -> 0
             ([-1, -1], 0), ([2, 2, 2], 0), ([0, 1, 0, 1], 3), ([-1, 3, -1, 3], 0), ([], 0)]
    return all(int(f(s)) == n for s, n in cases)


def loso_ok(f):
    """9.5: leave one sequence out, by hand."""
    # holding out a or b, q has the better mean on the others (0.65 vs 0.5) and scores 0.4
    # there; holding out c, p is better (0.5 vs 0.4) and scores 0.5: (0.4 + 0.4 + 0.5) / 3
    case = {"p": {"a": 0.5, "b": 0.5, "c": 0.5}, "q": {"a": 0.4, "b": 0.4, "c": 0.9}}
    one = {"only": {"a": 0.2, "b": 0.6}}                 # one configuration: its mean
    return abs(float(f(case)) - 1.3 / 3) < 1e-12 and abs(float(f(one)) - 0.4) < 1e-12


def without_first_ok(f):
    """9.7: the rate over frames 2..N from the toolkit's rate over frames 1..N."""
    # 6/11 with frame 1 a success: 5 of 10; r = 1 stays 1; only frame 1: 0
    return (abs(f(6 / 11, 11) - 0.5) < 1e-12 and abs(f(1.0, 471) - 1.0) < 1e-12
            and abs(f(1 / 120, 120)) < 1e-12)


def _dual_by_definition(x, y, sigma, lam):
    """Kernel ridge regression over all cyclic shifts with the n x n kernel matrix written out."""
    n = len(x)
    S = np.array([np.roll(x, -t) for t in range(n)])
    K = np.array([[np.exp(-np.sum((S[i] - S[j]) ** 2) / (n * sigma ** 2)) for j in range(n)]
                  for i in range(n)])
    return np.linalg.solve(K + lam * np.eye(n), y)


def dual_ok(f):
    """10.3: alpha of kernel ridge regression in the Fourier domain equals the explicit solve."""
    # by hand: x = 0 makes every kernel value 1, K = all-ones; y = (1, 1) and lam = 1:
    # (J + I) alpha = y -> alpha = y / 3
    if not _close(f(np.zeros(2), np.ones(2), 1.0, 1.0), [1 / 3, 1 / 3]):
        return False
    rng = np.random.default_rng(0)
    x, y = rng.normal(size=16), np.exp(-0.5 * (np.arange(16) - 8.0) ** 2)
    return _close(f(x, y, 0.5, 1e-3), _dual_by_definition(x, y, 0.5, 1e-3), atol=1e-8)


def grid_step_ok(f):
    """21.7: one step of a grid Bayes filter on a ring, predict by the moves, update, normalise."""
    cases = [  # (belief, motion, likelihood) -> (posterior, normaliser), by hand
        # the chapter's ten cells: predicted (0, 0, .025, .25, .45, .25, .025, 0, 0, 0)
        ([0, .25, .5, .25, 0, 0, 0, 0, 0, 0], {1: .1, 2: .8, 3: .1},
         [.1, .1, .1, .1, .1, .7, .1, .1, .7, .1],
         ([0, 0, .01, .1, .18, .7, .01, 0, 0, 0], .25)),
        # exercise 21.1: predicted (.125, .5, .375, 0, 0), product (.025, .1, .225, 0, 0)
        ([.5, .5, 0, 0, 0], {0: .25, 1: .75}, [.2, .2, .6, .2, .6],
         ([1 / 14, 4 / 14, 9 / 14, 0, 0], .35)),
        # round the ring: the move -1 from cell 0 comes in at cell 3; predicted
        # (0, .5, 0, .5), product (0, .5, 0, .1)
        ([1, 0, 0, 0], {-1: .5, 1: .5}, [1, 1, 1, .2], ([0, 5 / 6, 0, 1 / 6], .6)),
        # round the ring the other way: the move +1 from cell 3 comes in at cell 0;
        # predicted (.5, 0, 0, .5), product (.1, 0, 0, .5)
        ([0, 0, 0, 1], {0: .5, 1: .5}, [.2, 1, 1, 1], ([1 / 6, 0, 0, 5 / 6], .6)),
    ]
    for belief, motion, likelihood, (posterior, normaliser) in cases:
        got, z = f(np.array(belief, float), motion, np.array(likelihood, float))
        if not (_close(got, posterior) and abs(float(z) - normaliser) < 1e-9):
            return False
    return True


def roc_count_ok(f):
    """11.4: the ROC area as a share of pairs, ties one half."""
    cases = [(([2, 2, 1], [2, 0]), 4 / 6), (([3, 2], [1]), 1.0), (([1], [1]), 0.5),
             (([1, 3], [2]), 0.5), (([0.1, 0.2], [0.3, 0.4, 0.5]), 0.0)]
    return all(abs(float(f(np.asarray(a, float), np.asarray(b, float))) - v) < 1e-12
               for (a, b), v in cases)


#: exercise number -> predicate on the student's answer
CHECKS = {
    "0.4": iou_ok, "0.5": auc_ok, "1.5": kernel_ok, "1.7": histogram_ok,
    "2.5": stratified_ok, "2.8": systematic_ok, "3.5": fuse_ok, "3.6": gradient_ok,
    "4.5": svd_update_ok, "5.5": ratio_ok, "5.8": edge_weight_ok, "6.5": kalman_1d_ok,
    "6.7": jacobian_ok, "7.6": covariance_ok, "8.5": motion_ok, "8.7": switches_ok,
    "9.5": loso_ok, "9.7": without_first_ok, "10.3": dual_ok, "11.4": roc_count_ok,
    "21.7": grid_step_ok,
}


def _gather_chapter_checks() -> None:
    """Add the ``CHECKS`` of every chapter text module that defines some."""
    import importlib

    from ._chapters import CHAPTERS
    for stem in CHAPTERS:
        own = getattr(importlib.import_module(f"{__package__}._{stem}"), "CHECKS", {})
        clash = set(own) & set(CHECKS)
        if clash:
            raise ValueError(f"{stem}: exercise checks defined twice: {sorted(clash)}")
        CHECKS.update(own)


_gather_chapter_checks()

