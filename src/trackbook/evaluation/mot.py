"""Several-target measures: CLEAR-MOT's MOTA and MOTP, IDF1 and HOTA.

A *run* is one entry per frame; each entry lists the targets present in that frame with their
identity and box ``(x, y, w, h)``, in any of three spellings:

* a sequence of ``(id, box)`` pairs, e.g. ``[(1, (0, 0, 10, 10)), (2, (50, 0, 10, 10))]``;
* a dict ``{id: box}``;
* a ``(k, 5)`` array with rows ``(x, y, w, h, id)`` — what :meth:`trackbook.mot.Sort.update`
  returns and the layout of :func:`trackbook.mot.synthetic_detections`' ground truth.

Ground truth and hypotheses must cover the same frames. Ids are any hashable values and are
compared only within ground truth or within hypotheses, never across.

* :func:`clear_mot` — MOTA and MOTP (Bernardin & Stiefelhagen 2008): a frame-by-frame
  matching, counting misses, false positives and identity switches.
* :func:`identity_scores` — IDF1, IDP, IDR (Ristani et al. 2016): one global matching of whole
  trajectories, counting the frames where each identity is followed by *its* hypothesis.
* :func:`hota` — HOTA, DetA, AssA (Luiten et al. 2021): detection and association accuracy
  at every localisation threshold α = 0.05, 0.10, …, 0.95, then averaged.

>>> truth = [[(1, (0, 0, 10, 10))], [(1, (2, 0, 10, 10))]]
>>> hyps = [[("a", (0, 0, 10, 10))], [("b", (2, 0, 10, 10))]]
>>> s = clear_mot(truth, hyps)
>>> s.switches, s.mota
(1, 0.5)
>>> identity_scores(truth, hyps).idf1
0.5
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from ..trackers.association import iou_matrix

__all__ = ["ALPHAS", "ClearMot", "Hota", "IdentityScores", "clear_mot", "hota",
           "identity_scores", "mot_scores"]

#: HOTA's localisation thresholds α = 0.05, 0.10, …, 0.95 (19 values).
ALPHAS = np.arange(1, 20) / 20.0

# A pair is "at" a threshold when its IoU reaches it up to rounding: IoUs computed from the same
# boxes in a different order of operations differ in the last bit.
_EPS = np.finfo(float).eps


@dataclass(frozen=True)
class ClearMot:
    """CLEAR-MOT counts and scores of one run (see :func:`clear_mot`)."""

    mota: float
    motp: float
    matches: int
    misses: int
    false_positives: int
    switches: int
    n_truth: int


@dataclass(frozen=True)
class IdentityScores:
    """Identity measures of one run (see :func:`identity_scores`)."""

    idf1: float
    idp: float
    idr: float
    idtp: int
    idfp: int
    idfn: int


@dataclass(frozen=True)
class Hota:
    """HOTA of one run: the α-averages and the per-α curves (see :func:`hota`)."""

    hota: float
    deta: float
    assa: float
    alphas: np.ndarray
    hota_alpha: np.ndarray
    deta_alpha: np.ndarray
    assa_alpha: np.ndarray


def _frame(entry, what: str, t: int) -> tuple[list, np.ndarray]:
    """``(ids, (k, 4) boxes)`` of one frame of a run, checked."""
    if isinstance(entry, np.ndarray):
        arr = np.asarray(entry, dtype=float)
        if arr.size == 0:
            return [], np.zeros((0, 4))
        if arr.ndim != 2 or arr.shape[1] != 5:
            raise ValueError(f"{what}: frame {t} is an array of shape {arr.shape}; an array frame "
                             f"must be (k, 5) with rows (x, y, w, h, id).")
        ids, boxes = [int(i) if float(i).is_integer() else float(i) for i in arr[:, 4]], arr[:, :4]
    else:
        pairs = list(entry.items()) if isinstance(entry, dict) else list(entry)
        try:
            ids = [p[0] for p in pairs]
            boxes = np.asarray([np.asarray(p[1], dtype=float).reshape(4) for p in pairs],
                               dtype=float).reshape(-1, 4)
        except (TypeError, ValueError, IndexError) as err:
            raise ValueError(f"{what}: frame {t} must list (id, (x, y, w, h)) pairs, a dict "
                             f"{{id: box}} or a (k, 5) array ({err}).") from None
    if len(set(ids)) != len(ids):
        raise ValueError(f"{what}: frame {t} lists an id twice ({ids}); each target appears at "
                         f"most once per frame.")
    if not np.all(np.isfinite(boxes)) or np.any(boxes[:, 2:] < 0):
        raise ValueError(f"{what}: frame {t} has a box that is not finite or has a negative "
                         f"width/height; boxes are (x, y, w, h) with w, h >= 0.")
    return ids, boxes


def _frames(truth, hypotheses) -> list[tuple[list, np.ndarray, list, np.ndarray]]:
    """The two runs side by side, frame by frame: ``(gt ids, gt boxes, hyp ids, hyp boxes)``."""
    truth, hypotheses = list(truth), list(hypotheses)
    if len(truth) != len(hypotheses):
        raise ValueError(f"the runs cover different numbers of frames: {len(truth)} of ground "
                         f"truth, {len(hypotheses)} of hypotheses; give one entry per frame "
                         f"(an empty list for a frame with nothing in it).")
    out = []
    for t, (g, h) in enumerate(zip(truth, hypotheses)):
        gi, gb = _frame(g, "ground truth", t)
        hi, hb = _frame(h, "hypotheses", t)
        out.append((gi, gb, hi, hb))
    return out


def _check_threshold(threshold: float) -> float:
    threshold = float(threshold)
    if not 0.0 < threshold <= 1.0:
        raise ValueError(f"threshold must be an IoU in (0, 1], got {threshold}.")
    return threshold


def clear_mot(truth, hypotheses, threshold: float = 0.5) -> ClearMot:
    r"""MOTA and MOTP (Bernardin & Stiefelhagen 2008) with IoU matching.

    Frame by frame, ground-truth targets are matched to hypotheses:

    1. a target's last match is **kept** while it is still valid (the same two ids are
       present and their IoU is at least ``threshold``), whatever a fresh matching would say,
       so a hypothesis that keeps following its target is never re-matched. The last match
       is the one of whichever earlier frame it was made in, as in py-motmetrics; the paper
       and TrackEval keep only the previous frame's matches, so after a gap in which the
       pair was not matched they match afresh (and may count a switch this keeps out);
    2. the remaining targets and hypotheses are matched by the Hungarian method
       (``scipy.optimize.linear_sum_assignment``) on the cost 1 − IoU, pairs below
       ``threshold`` forbidden; among the matchings with the most pairs it takes one of least
       total cost.

    A target matched to a hypothesis other than the one it was last matched to (in any earlier
    frame) is an **identity switch**. Unmatched targets are misses (FN), unmatched hypotheses
    false positives (FP). Over all frames t, with g_t targets, matched pairs c_t and their IoUs,

    .. math::

        \mathrm{MOTA} = 1 - \frac{\sum_t (\mathrm{FN}_t + \mathrm{FP}_t + \mathrm{IDSW}_t)}
                                 {\sum_t g_t},
        \qquad
        \mathrm{MOTP} = \frac{\sum_{t, i} \mathrm{IoU}_{t,i}}{\sum_t c_t}.

    MOTP here is an **overlap** (mean IoU of the matched pairs, 1 is perfect), as the MOT
    Challenge reports it; the paper's MOTP is a mean *distance*, and a library fed 1 − IoU
    distances reports 1 − this value.

    Parameters
    ----------
    truth, hypotheses : runs (see the module's docstring), one entry per frame.
    threshold : float
        The least IoU of a match (0.5 by default).

    Returns
    -------
    ClearMot
        ``mota`` (−∞, 1] (nan without ground truth), ``motp`` [0, 1] (nan without a match) and
        the counts.
    """
    threshold = _check_threshold(threshold)
    last: dict = {}                                 # target id -> hypothesis id of its last match
    n_truth = matches = misses = fps = switches = 0
    iou_sum = 0.0
    for gi, gb, hi, hb in _frames(truth, hypotheses):
        n, m = len(gi), len(hi)
        n_truth += n
        pairs = []
        if n and m:
            iou = iou_matrix(gb, hb)
            valid = iou >= threshold
            used_g, used_h = np.zeros(n, bool), np.zeros(m, bool)
            column = {h: j for j, h in enumerate(hi)}
            for i, g in enumerate(gi):              # 1. keep the still-valid matches
                j = column.get(last[g]) if g in last else None
                if j is not None and not used_h[j] and valid[i, j]:
                    used_g[i] = used_h[j] = True
                    pairs.append((i, j))
            free = valid & ~used_g[:, None] & ~used_h[None, :]
            if free.any():                          # 2. Hungarian on the rest
                # a forbidden pair costs more than any r allowed ones (costs are in [0, 1]), so
                # the matching has as many pairs as possible, then the least total 1 - IoU
                cost = np.where(free, 1.0 - iou, 2.0 * min(n, m) + 1.0)
                for i, j in zip(*linear_sum_assignment(cost)):
                    if free[i, j]:
                        if gi[i] in last and last[gi[i]] != hi[j]:
                            switches += 1
                        pairs.append((i, j))
            for i, j in pairs:
                last[gi[i]] = hi[j]
                iou_sum += float(iou[i, j])
        matches += len(pairs)
        misses += n - len(pairs)
        fps += m - len(pairs)
    mota = 1.0 - (misses + fps + switches) / n_truth if n_truth else float("nan")
    motp = iou_sum / matches if matches else float("nan")
    return ClearMot(mota=mota, motp=motp, matches=matches, misses=misses, false_positives=fps,
                    switches=switches, n_truth=n_truth)


def _index(ids_per_frame) -> tuple[list[np.ndarray], int]:
    """Each frame's ids as indices 0..K-1 (first appearance order) and K."""
    table: dict = {}
    out = [np.array([table.setdefault(i, len(table)) for i in ids], dtype=int)
           for ids in ids_per_frame]
    return out, len(table)


def identity_scores(truth, hypotheses, threshold: float = 0.5) -> IdentityScores:
    r"""IDF1, IDP and IDR (Ristani et al. 2016).

    Whole trajectories are matched once, one-to-one: target i and hypothesis j *co-occur* in a
    frame where both are present with IoU ≥ ``threshold``; with n_ij such frames, the matching
    (Hungarian method) maximises the identity true positives IDTP = Σ n_ij over matched pairs —
    the same as Ristani's minimum of IDFN + IDFP, since IDFN = G − IDTP and IDFP = H − IDTP for
    the G ground-truth and H hypothesis boxes of the run. Then

    .. math::

        \mathrm{IDP} = \frac{\mathrm{IDTP}}{H}, \qquad
        \mathrm{IDR} = \frac{\mathrm{IDTP}}{G}, \qquad
        \mathrm{IDF1} = \frac{2\,\mathrm{IDTP}}{2\,\mathrm{IDTP} + \mathrm{IDFP} + \mathrm{IDFN}}
                      = \frac{2\,\mathrm{IDTP}}{G + H}.

    Parameters
    ----------
    truth, hypotheses : runs (see the module's docstring), one entry per frame.
    threshold : float
        The least IoU for a target and a hypothesis to count as together in a frame (0.5).

    Returns
    -------
    IdentityScores
        ``idf1``, ``idp``, ``idr`` (nan when their denominator is 0) and the counts.
    """
    threshold = _check_threshold(threshold)
    frames = _frames(truth, hypotheses)
    gidx, n_g = _index(f[0] for f in frames)
    hidx, n_h = _index(f[2] for f in frames)
    together = np.zeros((n_g, n_h))
    for (_, gb, _, hb), gi, hi in zip(frames, gidx, hidx):
        if len(gi) and len(hi):
            ok = iou_matrix(gb, hb) >= threshold
            r, c = np.nonzero(ok)
            np.add.at(together, (gi[r], hi[c]), 1.0)
    rows, cols = linear_sum_assignment(-together)
    idtp = int(together[rows, cols].sum())
    n_gt = sum(len(f[0]) for f in frames)
    n_hyp = sum(len(f[2]) for f in frames)
    nan = float("nan")
    return IdentityScores(
        idf1=2.0 * idtp / (n_gt + n_hyp) if n_gt + n_hyp else nan,
        idp=idtp / n_hyp if n_hyp else nan, idr=idtp / n_gt if n_gt else nan,
        idtp=idtp, idfp=n_hyp - idtp, idfn=n_gt - idtp)


def hota(truth, hypotheses) -> Hota:
    r"""HOTA, DetA and AssA (Luiten et al. 2021), averaged over α = 0.05, 0.10, …, 0.95.

    For each localisation threshold α, every frame's targets and hypotheses are matched one to
    one by the Hungarian method, maximising Σ A_ij·S_ij where S_ij is the pair's IoU and A_ij
    its whole-run alignment (below); pairs with S_ij < α are then dropped. The matched pairs
    are the true positives TP_α, the rest FN_α and FP_α, and

    .. math::

        \mathrm{DetA}_\alpha = \frac{|\mathrm{TP}_\alpha|}
            {|\mathrm{TP}_\alpha| + |\mathrm{FN}_\alpha| + |\mathrm{FP}_\alpha|},
        \qquad
        \mathrm{AssA}_\alpha = \frac{1}{|\mathrm{TP}_\alpha|} \sum_{c \in \mathrm{TP}_\alpha}
            \frac{|\mathrm{TPA}(c)|}{|\mathrm{TPA}(c)| + |\mathrm{FNA}(c)| + |\mathrm{FPA}(c)|},

    where, for a true positive c pairing target i with hypothesis j, TPA(c) are the true
    positives pairing i with j, FNA(c) the other frames of i and FPA(c) the other frames of j
    (so the denominator is n_i + n_j − |TPA(c)|, n_i the number of frames of i). Then

    .. math::

        \mathrm{HOTA}_\alpha = \sqrt{\mathrm{DetA}_\alpha \, \mathrm{AssA}_\alpha},
        \qquad \mathrm{HOTA} = \frac{1}{19} \sum_{\alpha} \mathrm{HOTA}_\alpha,

    and DetA, AssA likewise. The alignment used to choose between matchings is the soft
    version of the same ratio: A_ij = P_ij / (n_i + n_j − P_ij), with P_ij = Σ_t S_ij,t /
    (Σ_k S_ik,t + Σ_l S_lj,t − S_ij,t) summed over the frames t of the run. This is the
    reference implementation's choice (it favours pairs that stay together) and the one
    checked here.

    Parameters
    ----------
    truth, hypotheses : runs (see the module's docstring), one entry per frame.

    Returns
    -------
    Hota
        ``hota``, ``deta``, ``assa`` (the α-averages; 0 for a run with no target or no
        hypothesis) and the per-α arrays over ``alphas`` (:data:`ALPHAS`).
    """
    frames = _frames(truth, hypotheses)
    gidx, n_g = _index(f[0] for f in frames)
    hidx, n_h = _index(f[2] for f in frames)
    n_alpha = len(ALPHAS)
    tp, fn, fp = np.zeros(n_alpha), np.zeros(n_alpha), np.zeros(n_alpha)
    if n_g == 0 or n_h == 0:                        # nothing to detect, or nothing detected
        zeros = np.zeros(n_alpha)
        return Hota(0.0, 0.0, 0.0, ALPHAS.copy(), zeros, zeros.copy(), zeros.copy())
    sims = [iou_matrix(f[1], f[3]) for f in frames]

    # whole-run soft alignment A_ij
    potential = np.zeros((n_g, n_h))
    g_count, h_count = np.zeros(n_g), np.zeros(n_h)
    for s, gi, hi in zip(sims, gidx, hidx):
        denom = s.sum(0)[None, :] + s.sum(1)[:, None] - s
        soft = np.zeros_like(s)
        mask = denom > _EPS
        soft[mask] = s[mask] / denom[mask]
        potential[gi[:, None], hi[None, :]] += soft
        g_count[gi] += 1
        h_count[hi] += 1
    alignment = potential / (g_count[:, None] + h_count[None, :] - potential)

    # per-frame matching, then the per-α true positives and their identity pairs
    pair_counts = np.zeros((n_alpha, n_g, n_h))
    for s, gi, hi in zip(sims, gidx, hidx):
        if len(gi) == 0 or len(hi) == 0:
            fp += len(hi)
            fn += len(gi)
            continue
        rows, cols = linear_sum_assignment(-(alignment[gi[:, None], hi[None, :]] * s))
        kept = s[rows, cols][None, :] >= ALPHAS[:, None] - _EPS      # (n_alpha, n_pairs)
        n_kept = kept.sum(1)
        tp += n_kept
        fn += len(gi) - n_kept
        fp += len(hi) - n_kept
        a_idx, p_idx = np.nonzero(kept)
        np.add.at(pair_counts, (a_idx, gi[rows[p_idx]], hi[cols[p_idx]]), 1.0)

    # AssA_α: Σ over TP of |TPA|/(n_i + n_j − |TPA|), grouped by identity pair
    union = np.maximum(1.0, g_count[None, :, None] + h_count[None, None, :] - pair_counts)
    assa = (pair_counts * pair_counts / union).sum((1, 2)) / np.maximum(1.0, tp)
    deta = tp / np.maximum(1.0, tp + fn + fp)
    h = np.sqrt(deta * assa)
    return Hota(hota=float(h.mean()), deta=float(deta.mean()), assa=float(assa.mean()),
                alphas=ALPHAS.copy(), hota_alpha=h, deta_alpha=deta, assa_alpha=assa)


def mot_scores(truth, hypotheses, threshold: float = 0.5) -> dict[str, float]:
    """The headline numbers of one run: MOTA, MOTP, IDF1 (at ``threshold``), HOTA, DetA, AssA.

    >>> truth = [[(1, (0, 0, 10, 10))]] * 2
    >>> mot_scores(truth, truth)
    {'mota': 1.0, 'motp': 1.0, 'idf1': 1.0, 'hota': 1.0, 'deta': 1.0, 'assa': 1.0}
    """
    c = clear_mot(truth, hypotheses, threshold)
    h = hota(truth, hypotheses)
    return {"mota": c.mota, "motp": c.motp,
            "idf1": identity_scores(truth, hypotheses, threshold).idf1,
            "hota": h.hota, "deta": h.deta, "assa": h.assa}
