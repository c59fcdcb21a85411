"""The exercises are defined once: every chapter shows its exercises with the numbers of the
appendix, every exercise is graded, and every auto-check accepts a correct solution and
rejects a wrong one.

The correct solutions below are written from the equations (never by calling the library
function the exercise re-implements); each wrong one makes a mistake a student makes.
"""
import re
from pathlib import Path

import cv2
import numpy as np
import pytest

from trackbook import exercises
from trackbook.exercises import checks
from trackbook.quotes.attributions import unquoted

ROOT = Path(__file__).resolve().parents[1]
BOOK = ROOT / "book"
SHOW = re.compile(r"""exercises\.show\(([^)]*)\)""")
NUMBER = re.compile(r"""["'](\d+\.\d+)["']""")


def _section(text: str, heading: str) -> str:
    start = text.index(heading)
    nxt = re.search(r"^## ", text[start + len(heading):], re.M)
    return text[start:start + len(heading) + nxt.start()] if nxt else text[start:]


def _shown(text: str) -> list[str]:
    """The exercise numbers a page shows, in order; one ``show("1.8", "1.9")`` shows two."""
    return [n for args in SHOW.findall(text) for n in NUMBER.findall(args)]


def _appendix_sections():
    text = (BOOK / "appendix_exercises.md").read_text(encoding="utf-8")
    return {m.group(1): _section(text, m.group(0))
            for m in re.finditer(r"^## \d+\. .*\{doc\}`[^<]*<(\w+)>`.*$", text, re.M)}


# -- the registry -------------------------------------------------------------------------------

def test_numbers_are_consecutive_and_match_the_chapter():
    for stem in exercises.chapters():
        numbers = [e.number for e in exercises.for_chapter(stem)]
        assert numbers == [f"{int(stem[:2])}.{k}" for k in range(1, len(numbers) + 1)], stem


def test_every_exercise_is_graded_with_a_title_and_a_statement():
    for e in exercises.all_exercises():
        assert e.stars in ("★", "★★", "★★★"), e.number
        assert e.kind in exercises.KINDS and e.title and len(e.statement) > 40, e.number
        assert e.kind != "implement" or e.stars == "★★★", e.number


def test_every_chapter_from_01_has_three_pen_and_paper_exercises_with_worked_solutions():
    """A course can grade by hand: at least three derivations or hand calculations in every
    chapter after the introduction, each with a worked solution."""
    for stem in exercises.chapters():
        if stem.startswith("00_"):
            continue
        pen = [e for e in exercises.for_chapter(stem) if e.kind == "pen and paper"]
        assert len(pen) >= 3, f"{stem} has {len(pen)} pen-and-paper exercises"
        assert all(len(e.solution) > 100 for e in pen), [e.number for e in pen]


def test_every_exercise_has_a_written_solution():
    """Projects and implementations included: a model answer or a reference implementation,
    explained, so a grader knows what full marks look like."""
    missing = [e.number for e in exercises.all_exercises() if len(e.solution or "") < 40]
    assert not missing, f"exercises without a written solution: {missing}"


def test_the_correlation_filter_chapter_has_six_exercises():
    assert len(exercises.for_chapter("10_correlation_filters")) >= 6


def test_every_auto_checked_exercise_exists_and_is_an_implementation():
    for number in checks.CHECKS:
        assert exercises.get(number).stars == "★★★", number


def test_texts_cite_a_quote_wherever_they_speak_for_a_paper():
    for e in exercises.all_exercises():
        for part in (e.statement, e.hint, e.solution):
            assert not unquoted(part), (e.number, unquoted(part))


def test_markdown_renders_number_grade_and_a_folded_solution():
    md = exercises.markdown("1.6")
    assert md.startswith("**Exercise 1.6 ★ (pen and paper). ρ as a cosine.**")
    assert "{admonition} Solution to 1.6\n:class: dropdown" in md
    assert "Solution" not in exercises.markdown("1.6", solution=False)


def test_bad_numbers_and_bad_text_are_refused():
    with pytest.raises(ValueError, match="no exercise '1.99'"):
        exercises.get("1.99")
    with pytest.raises(ValueError, match="no exercises for 'zz'"):
        exercises.for_chapter("zz")
    with pytest.raises(ValueError, match="grade"):
        exercises.parse("=== 1.1 ★★★★ use | x\ntext", "t")
    with pytest.raises(ValueError, match="no auto-check"):
        exercises.autocheck("1.1", 1.0)


# -- the pages ----------------------------------------------------------------------------------

def test_every_chapter_shows_its_exercises_in_order_and_the_appendix_the_same_numbers():
    appendix = _appendix_sections()
    for stem in exercises.chapters():
        want = [e.number for e in exercises.for_chapter(stem)]
        page = (BOOK / f"{stem}.md").read_text(encoding="utf-8")
        assert _shown(_section(page, "## Exercises")) == want, stem
        assert _shown(appendix[stem]) == want, f"appendix section of {stem}"


def test_no_page_types_an_exercise_statement_of_its_own():
    """The statements come from the registry only: no bold 'N.M ★' lead-in or numbered
    '1. ★' item is typed into an exercise section."""
    typed = re.compile(r"^(\*\*(Exercise )?\d+\.\d+ ★|\d+\. ★)", re.M)
    for stem in exercises.chapters():
        page = (BOOK / f"{stem}.md").read_text(encoding="utf-8")
        assert not typed.search(_section(page, "## Exercises")), stem
    for stem, sec in _appendix_sections().items():
        assert not typed.search(sec), stem


def test_auto_checked_exercises_have_a_starter_in_the_appendix():
    appendix = "\n".join(_appendix_sections().values())
    for number in checks.CHECKS:
        assert re.search(rf"""autocheck\("{re.escape(number)}", answer_{number.replace('.', '_')}\)""",
                         appendix), number


# -- the auto-checks: a correct solution passes, a wrong one fails --------------------------------

def _inter(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    w = np.clip(np.minimum(a[:, 0] + a[:, 2], b[:, 0] + b[:, 2]) - np.maximum(a[:, 0], b[:, 0]), 0, None)
    h = np.clip(np.minimum(a[:, 1] + a[:, 3], b[:, 1] + b[:, 3]) - np.maximum(a[:, 1], b[:, 1]), 0, None)
    return w * h, a[:, 2] * a[:, 3] + b[:, 2] * b[:, 3]


def iou(a, b):
    inter, areas = _inter(a, b)
    return inter / (areas - inter)


def iou_over_sum(a, b):                              # forgets to subtract the intersection
    inter, areas = _inter(a, b)
    return inter / areas


def kernel(h, w):
    r2 = np.add.outer((np.arange(h) + 0.5 - h / 2) ** 2, (np.arange(w) + 0.5 - w / 2) ** 2)
    return 1 - r2 / r2.max()


def stratified(w, rng):
    c = np.cumsum(w)
    c[-1] = 1.0
    return np.searchsorted(c, (np.arange(len(w)) + rng.random(len(w))) / len(w))


def systematic(w, rng):
    c = np.cumsum(w)
    c[-1] = 1.0
    return np.searchsorted(c, rng.random() / len(w) + np.arange(len(w)) / len(w))


def svd_update(U, S, b):
    p = U.T @ b
    r = b - U @ p
    nr = np.linalg.norm(r)
    q = r / nr if nr > 1e-12 else np.zeros_like(r)
    R = np.block([[np.diag(S), p[:, None]], [np.zeros((1, len(S))), np.array([[nr]])]])
    Ut, St, _ = np.linalg.svd(R)
    return np.c_[U, q] @ Ut, St


def mid(d):
    return np.sort(d, axis=-1)[..., 3:5].mean(axis=-1)


def edge_weight(p, m, low=0.8, high=1.2):
    ratio = mid(p) / mid(m)
    w = np.clip(1 - np.abs(p - m).sum(axis=-1) / np.sum(m), 0, None)
    return np.where((ratio >= low) & (ratio <= high), w, 0.0)


def kf1d(zs, m, v, u, q, r):
    out = []
    for z in zs:
        m, v = m + u, v + q
        k = v / (v + r)
        m, v = m + k * (z - m), (1 - k) * v
        out.append((m, v))
    return np.array(out).T if out else (np.array([]), np.array([]))


def jacobian(x, s):
    dx, dy = x[0] - s[0], x[1] - s[1]
    r2 = dx * dx + dy * dy
    return np.array([[dx / r2 ** 0.5, dy / r2 ** 0.5, 0, 0], [-dy / r2, dx / r2, 0, 0]])


def cov_box(F, box):
    x, y, w, h = box
    f = F[y:y + h, x:x + w].reshape(-1, F.shape[2])
    return np.atleast_2d(np.cov(f.T, bias=True))


def motion(I0, I1):
    Iy, Ix = np.gradient((I0 + I1) / 2)
    It = I1 - I0
    A = np.array([[np.sum(Ix * Ix), np.sum(Ix * Iy)], [np.sum(Ix * Iy), np.sum(Iy * Iy)]])
    return np.linalg.solve(A, -np.array([np.sum(Ix * It), np.sum(Iy * It)]))


def switches(seq):
    seen = [i for i in seq if i >= 0]
    return sum(a != b for a, b in zip(seen, seen[1:]))


def loso(scores):
    seqs = sorted(set.intersection(*(set(v) for v in scores.values())))
    return float(np.mean([scores[max(scores, key=lambda c: np.mean(
        [scores[c][o] for o in seqs if o != s]))][s] for s in seqs]))


def dual(x, y, sigma, lam):
    xf = np.fft.fft(x)
    k = np.exp(-np.maximum(2 * x @ x - 2 * np.fft.ifft(xf * np.conj(xf)).real, 0)
               / (sigma ** 2 * len(x)))
    return np.fft.ifft(np.fft.fft(y) / (np.fft.fft(k) + lam)).real


def grid_step(belief, motion, likelihood, backwards=False):
    """21.7 written out cell by cell; ``backwards`` moves the target the wrong way."""
    n, predicted = len(belief), np.zeros(len(belief))
    for j in range(n):
        for move, p in motion.items():
            predicted[(j - move if backwards else j + move) % n] += p * belief[j]
    product = np.asarray(likelihood, float) * predicted
    return product / product.sum(), product.sum()


def axes(prob, half=0.5):
    """13.4 from cv2.moments (an oracle independent of the library's moments)."""
    m = cv2.moments(np.asarray(prob, np.float64))
    a, h, c = m["mu20"] / m["m00"], m["mu11"] / m["m00"], m["mu02"] / m["m00"]
    root = np.sqrt(4 * h * h + (a - c) ** 2)
    return (np.degrees(half * np.arctan2(2 * h, a - c)), np.sqrt((a + c + root) / 2),
            np.sqrt(max((a + c - root) / 2, 0.0)))


def noisy_or(p, b, lab):
    """14.4 as the appendix solves it: s_i = sum_j ln(1 - p_ij) per bag, p_i = 1 - e^(s_i)."""
    with np.errstate(divide="ignore"):        # a certain instance (p = 1): ln 0 = -inf
        s = np.bincount(b, weights=np.log1p(-p), minlength=len(lab))
        return 1 - np.exp(s), float(np.sum(np.where(lab == 1, np.log1p(-np.exp(s)), s)))


def rts_step(x, P, x_next_s, P_next_s, F, Q, transposed=False):
    """One RTS backward step written out (17.4); ``transposed`` puts F where Fᵀ belongs."""
    P_pred = F @ P @ F.T + Q
    G = (P @ F if transposed else P @ F.T) @ np.linalg.inv(P_pred)
    return x + G @ (x_next_s - F @ x), P + G @ (P_next_s - P_pred) @ G.T


def merwe(m, P, alpha, beta, kappa):
    m = np.atleast_1d(np.asarray(m, float))
    n = m.size
    lam = alpha ** 2 * (n + kappa) - n
    L = np.linalg.cholesky((n + lam) * np.atleast_2d(P))
    Wm = np.full(2 * n + 1, 0.5 / (n + lam))
    Wc = Wm.copy()
    Wm[0] = lam / (n + lam)
    Wc[0] = Wm[0] + 1 - alpha ** 2 + beta
    return np.vstack([m, m + L.T, m - L.T]), Wm, Wc


def snis(x, log_p, log_q, phi):
    lw = log_p(x) - log_q(x)
    w = np.exp(lw - lw.max())
    w = w / w.sum()
    return w @ phi(x), 1 / np.sum(w ** 2)


def snis_raw(x, log_p, log_q, phi):
    with np.errstate(invalid="ignore"):
        w = np.exp(log_p(x) - log_q(x))
        w = w / w.sum()
        return w @ phi(x), 1 / np.sum(w ** 2)


def mog_step(x, w, mu, var, eta, decay=True):
    """One grey pixel's mixture update (Zivkovic 2004 with c_T = 0, OpenCV's order)."""
    w, mu, var = (np.array(a, float) for a in (w, mu, var))
    if decay:
        w = (1 - eta) * w
    d2 = (x - mu) ** 2 / var
    owns = np.flatnonzero(d2 < 9)
    last = owns[0] if len(owns) else len(w) - 1
    background = bool(np.any(((np.cumsum(w) - w) < 0.9)[:last + 1] & (d2[:last + 1] < 16)))
    if len(owns):
        m = owns[0]
        w[m] += eta
        step, dist2 = eta / w[m], (x - mu[m]) ** 2
        mu[m] += step * (x - mu[m])
        var[m] = np.clip(var[m] + step * (dist2 - var[m]), 4, 75)
        w /= w.sum()
    else:
        w = (1 - eta) * w / w.sum()
        if len(w) == 5:
            w, mu, var = w[:-1], mu[:-1], var[:-1]
        w, mu, var = np.append(w, eta), np.append(mu, x), np.append(var, 15.0)
    order = np.argsort(-w, kind="stable")
    return background, w[order], mu[order], var[order]


def _idf1_best(together, n_truth, n_hyp):
    from scipy.optimize import linear_sum_assignment
    rows, cols = linear_sum_assignment(np.asarray(together, float), maximize=True)
    return 2 * np.asarray(together, float)[rows, cols].sum() / (n_truth + n_hyp)


def _idf1_greedy(together, n_truth, n_hyp):
    t, idtp = np.array(together, float), 0.0
    while t.size and t.max() > 0:
        i, j = np.unravel_index(t.argmax(), t.shape)
        idtp += t[i, j]
        t[i, :] = t[:, j] = -1
    return 2 * idtp / (n_truth + n_hyp)


def lk_window(I, J, x, y, r, iterations=1):
    """12.7: Lucas-Kanade for one (2r + 1)^2 window, iterated with bilinear resampling."""
    from scipy.ndimage import map_coordinates
    I, J = np.asarray(I, float), np.asarray(J, float)
    Iy, Ix = np.gradient(I)
    win = (slice(y - r, y + r + 1), slice(x - r, x + r + 1))
    rows, cols = np.mgrid[win].astype(float)
    gx, gy, T = Ix[win], Iy[win], I[win]
    Z = np.array([[np.sum(gx * gx), np.sum(gx * gy)], [np.sum(gx * gy), np.sum(gy * gy)]])
    small, large = np.linalg.eigvalsh(Z)
    if large <= 0 or small <= 1e-9 * large:
        return None
    d = np.zeros(2)
    for _ in range(iterations):
        e = T - map_coordinates(J, [rows + d[1], cols + d[0]], order=1)
        d = d + np.linalg.solve(Z, [np.sum(gx * e), np.sum(gy * e)])
    return d


def reset_count(overlaps, skip, first=1):
    """VOT's reset rule; ``first=0`` is the wrong one that also reads an initialisation frame."""
    inits, failures, start = [0], [], 0
    while True:
        fail = next((t for t in range(start + (first if inits[-1] else 1), len(overlaps))
                     if overlaps[t] == 0), None)
        if fail is None or fail + skip >= len(overlaps):
            return tuple(inits), tuple(failures + ([fail] if fail is not None else []))
        failures.append(fail)
        start = fail + skip
        inits.append(start)


def staple_merged(tmpl, beta, box, gamma):
    """20.4: (1 - γ) tmpl + γ × the box means of beta, from a zero-padded integral image."""
    h, w = box
    S = np.zeros((beta.shape[0] + 1, beta.shape[1] + 1))
    S[1:, 1:] = np.asarray(beta, float).cumsum(axis=0).cumsum(axis=1)
    means = (S[h:, w:] - S[:-h, w:] - S[h:, :-w] + S[:-h, :-w]) / (h * w)
    return (1 - gamma) * np.asarray(tmpl, float) + gamma * means


RIGHT_AND_WRONG = {
    "0.4": (iou, iou_over_sum),
    "0.5": (lambda i: np.mean([(np.asarray(i) > t).mean() for t in np.linspace(0, 1, 21)]),
            lambda i: np.mean([(np.asarray(i) >= t).mean() for t in np.linspace(0, 1, 21)])),
    "1.5": (kernel, lambda h, w: 1 - np.sqrt(1 - kernel(h, w))),           # the cone 1 - r
    "1.7": (lambda lab, k, n: np.bincount(lab.ravel(), k.ravel(), n) / k.sum(),
            lambda lab, k, n: np.bincount(lab.ravel(), minlength=n) / lab.size),  # no kernel
    "2.5": (stratified, lambda w, rng: np.searchsorted(np.cumsum(w), rng.random(len(w)))),
    "2.8": (systematic, lambda w, rng: np.searchsorted(np.cumsum(w), rng.random()
                                                       + np.arange(len(w)) / len(w)) % len(w)),
    "3.5": (lambda rc, rh, a, s: (lambda p: p / p.sum())(
                a * np.exp(-(1 - rc) / (2 * s * s)) + (1 - a) * np.exp(-(1 - rh) / (2 * s * s))),
            lambda rc, rh, a, s: (lambda p: p / p.sum())(     # D^2 = (1 - rho)^2: squared twice
                a * np.exp(-(1 - rc) ** 2 / (2 * s * s)) + (1 - a) * np.exp(-(1 - rh) ** 2 / (2 * s * s)))),
    "3.6": (lambda P: np.pad(P, ((0, 0), (1, 1)), mode="edge")[:, 2:]
            - np.pad(P, ((0, 0), (1, 1)), mode="edge")[:, :-2],
            lambda P: np.diff(P, axis=1, append=P[:, -1:])),              # forward differences
    "4.5": (svd_update, lambda U, S, b: (U, np.r_[S, np.linalg.norm(b)])),   # ignores U^T b
    "5.5": (lambda p, m: mid(p) / mid(m), lambda p, m: np.sort(p)[2:4].mean() / np.sort(m)[2:4].mean()),  # 3rd, 4th
    "5.8": (edge_weight, lambda p, m: np.clip(1 - np.abs(p - m).sum(-1) / np.sum(m), 0, None)),
    "6.5": (kf1d, lambda zs, m, v, u, q, r: kf1d(zs, m, v, u, 0.0, r)),         # forgets Q
    "6.7": (jacobian, lambda x, s: jacobian(x, (0.0, 0.0))),               # ignores the sensor
    "7.6": (cov_box, lambda F, box: cov_box(F, box) * (box[2] * box[3])
            / max(box[2] * box[3] - 1, 1)),                                # sample, not population
    "8.5": (motion, lambda I0, I1: -motion(I0, I1)),                        # I_t the wrong way
    "8.7": (switches, lambda seq: len(set(i for i in seq if i >= 0)) - 1 if seq else 0),
    "9.5": (loso, lambda scores: max(np.mean(list(v.values())) for v in scores.values())),
    "9.7": (lambda r, n: (r * n - 1) / (n - 1), lambda r, n: r),
    "10.3": (dual, lambda x, y, s, lam: y / (1 + lam)),
    # 11.4: the share of pairs with ties one half; wrong: ties counted as losses
    "11.4": (lambda on, off: float(np.mean([1.0 if a > b else 0.5 if a == b else 0.0
                                            for a in on for b in off])),
             lambda on, off: float(np.mean([a > b for a in on for b in off]))),
    "13.4": (axes, lambda p: axes(p, half=1.0)),                           # forgets the 1/2
    # 14.4: the noisy-OR by bag; wrong: the mean of the instances instead of the noisy-OR
    "14.4": (noisy_or,
             lambda p, b, lab: (lambda q: (q, float(np.sum(
                 lab * np.log(q) + (1 - lab) * np.log1p(-q)))))(
                 np.bincount(b, weights=p, minlength=len(lab)) / np.bincount(b))),
    # 17.4: the RTS step; wrong: the smoother gain with Fᵀ on the wrong side, P F (P⁻)⁻¹
    "17.4": (rts_step, lambda x, P, xs, Ps, F, Q: rts_step(x, P, xs, Ps, F, Q, transposed=True)),
    # 17.5: ω normalised over the current mode j (rows) instead of over the previous mode i
    "17.5": (lambda mu, Pi: (mu @ Pi, Pi * mu[:, None] / (mu @ Pi)[None, :]),
             lambda mu, Pi: (mu @ Pi, (Pi * mu[:, None]) / (Pi * mu[:, None]).sum(1, keepdims=True))),
    # 18.7: wrong: the covariance weight of the centre without the 1 - α² + β term
    "18.7": (merwe, lambda m, P, a, b, k: (merwe(m, P, a, b, k)[0], merwe(m, P, a, b, k)[1],
                                           merwe(m, P, a, b, k)[1])),
    # 18.8: wrong: exponentiates the raw log-weights, which underflow to 0 / 0 at -2000
    "18.8": (snis, lambda x, lp, lq, phi: snis_raw(x, lp, lq, phi)),
    # 15.4: wrong: the weights are not decayed before the owner gains eta
    "15.4": (mog_step, lambda *a: mog_step(*a, decay=False)),
    # 16.7: the best one-to-one matching of counts; wrong: greedy, largest count first
    "16.7": (_idf1_best, _idf1_greedy),
    # 12.7: one window's Lucas-Kanade; wrong: a single step, whatever `iterations` says
    "12.7": (lk_window, lambda I, J, x, y, r, iterations=1: lk_window(I, J, x, y, r, 1)),
    # 19.5: VOT's reset rule; wrong: a zero on a re-initialisation frame counted as a failure
    "19.5": (reset_count, lambda o, skip: reset_count(o, skip, first=0)),
    # 21.7: one grid step on a ring; wrong: every move taken backwards
    "21.7": (grid_step, lambda b, m, lik: grid_step(b, m, lik, backwards=True)),
    # 20.4: box means by an integral image, then the merge; wrong: the weights swapped
    "20.4": (lambda t, b, box, g: staple_merged(t, b, box, g),
             lambda t, b, box, g: staple_merged(t, b, box, 1 - g)),
}


def test_every_auto_check_has_a_right_and_a_wrong_solution_here():
    assert set(RIGHT_AND_WRONG) == set(checks.CHECKS)


@pytest.mark.parametrize("number", sorted(checks.CHECKS, key=lambda n: tuple(map(int, n.split(".")))))
def test_auto_check_accepts_the_right_solution_and_rejects_the_wrong_one(number, capsys):
    right, wrong = RIGHT_AND_WRONG[number]
    assert exercises.autocheck(number, right) is True
    assert exercises.autocheck(number, wrong) is False
    assert exercises.autocheck(number, None) is None
    out = capsys.readouterr().out
    assert f"{number}: PASS" in out and f"{number}: FAIL" in out and "not answered yet" in out


def test_grid_step_check_rejects_a_ring_that_wraps_one_way_only():
    """21.7: Python's negative indices wrap a move past cell 0, not one past the last cell."""
    def one_way(belief, motion, likelihood):
        n, predicted = len(belief), np.zeros(len(belief))
        for j in range(n):
            for move, p in motion.items():
                if j + move < n:
                    predicted[j + move] += p * belief[j]
        product = np.asarray(likelihood, float) * predicted
        return product / product.sum(), product.sum()

    assert checks.CHECKS["21.7"](one_way) is False


def test_hand_values_of_the_checks_follow_from_the_equations():
    """A few expected values of the checks, recomputed here from the equations."""
    # 2.8: pointers 0.125 + k/4 against c = cumsum(0.7, 0.1, 0.1, 0.1): smallest i, c_i >= pointer
    c, ptr = np.array([0.7, 0.8, 0.9, 1.0]), 0.125 + np.arange(4) / 4
    assert [int(np.argmax(c >= p)) for p in ptr] == [0, 0, 0, 2]
    # 6.5: the product of N(20, 4) and N(26, 12)
    assert (20 / 4 + 26 / 12) / (1 / 4 + 1 / 12) == pytest.approx(21.5)
    assert 1 / (1 / 4 + 1 / 12) == pytest.approx(3.0)
    # 9.5: the hand case
    assert loso({"p": {"a": 0.5, "b": 0.5, "c": 0.5},
                 "q": {"a": 0.4, "b": 0.4, "c": 0.9}}) == pytest.approx(1.3 / 3)
    # 10.3: (J + I) alpha = (1, 1)
    assert np.linalg.solve(np.ones((2, 2)) + np.eye(2), np.ones(2)) == pytest.approx([1 / 3] * 2)
    # 11.4: on = [2, 2, 1], absent = [2, 0]: pairs (2,2) tie, (2,0) win, twice; (1,2) loss,
    # (1,0) win -> (3 wins + 2 ties / 2) / 6
    assert (3 + 2 * 0.5) / 6 == pytest.approx(4 / 6)
    # 8.8 (pen and paper): the weighted mean inside an Epanechnikov kernel of h = 2 at 1.5
    x, w = np.array([0.0, 1, 2]), np.array([1.0, 2, 1])
    assert np.all(np.abs(x - 1.5) / 2 < 1) and (x * w).sum() / w.sum() == 1.0


def test_fixed_random_stands_in_for_a_generator():
    rng = checks.FixedRandom([0.25, 0.5, 0.75])
    assert rng.random() == 0.25 and list(rng.random(2)) == [0.25, 0.5]


def test_the_hand_out_recipe_hides_the_solutions():
    """The teaching page's recipe rewrites exercises.show("N.M") to show no solution."""
    source = 'exercises.show("6.8")'.replace('exercises.show(', 'exercises.show(solution=False, number=')
    shown = eval(source, {"exercises": exercises})
    assert "Derive the gain" in shown.data and "Solution" not in shown.data


def test_every_quote_in_the_texts_is_in_the_register():
    from trackbook import quotes
    keys = {q.key for paper in ("lee2012", "kim2016", "lee2015", "cho2005")
            for q in quotes.for_paper(paper)}
    cited = {k for e in exercises.all_exercises()
             for k in re.findall(r"\{quote\}`([^`]+)`", e.statement + e.hint + e.solution)}
    assert cited and cited <= keys, cited - keys


# -- the legend ---------------------------------------------------------------------------------

def test_every_chapter_opens_its_exercises_with_the_legend():
    """The legend a chapter prints is :data:`exercises.LEGEND`, word for word."""
    legend = " ".join(exercises.LEGEND.split())
    for stem in exercises.chapters():
        text = (BOOK / f"{stem}.md").read_text(encoding="utf-8")
        section = " ".join(_section(text, "## Exercises").split())
        assert legend in section, stem


def test_the_legend_describes_every_grade_and_kind_in_use():
    for e in exercises.all_exercises():
        assert e.stars in exercises.GRADES[e.kind], (e.number, e.stars, e.kind)
    for kind, grades in exercises.GRADES.items():
        assert f"*{kind}*" in exercises.LEGEND, kind
        assert all(g in exercises.LEGEND for g in grades), kind


def test_show_renders_several_exercises_in_order():
    md = exercises.show("1.1", "1.2").data
    assert md.index("Exercise 1.1") < md.index("Exercise 1.2")
    assert exercises.show(solution=False, number="1.6").data == exercises.markdown(
        "1.6", solution=False)
    with pytest.raises(ValueError, match="needs an exercise number"):
        exercises.show()


def test_exercise_maths_survives_markdown():
    """Markdown reads a line that starts with "+ ", "- " or "1. " as a list item and leaves
    ``$$`` inside a paragraph as text: either breaks the maths the browser then shows raw."""
    bad = []
    for e in exercises.all_exercises():
        for part in (e.statement, e.hint or "", e.solution or ""):
            lines, dollars = part.split("\n"), 0
            for i, line in enumerate(lines):
                if dollars % 2 and re.match(r"\s*(?:[+*-]|\d+\.)\s", line):
                    bad.append((e.number, "a list marker starts a line of maths", line))
                opens = sum(ln.count("$$") for ln in lines[:i]) % 2 == 0
                if (line.lstrip().startswith("$$") and opens and i
                        and lines[i - 1].strip()):
                    bad.append((e.number, "display maths without a blank line before", line))
                dollars += len(re.findall(r"(?<!\$)\$(?!\$)", line))
    assert not bad, bad
