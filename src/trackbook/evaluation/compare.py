"""Comparing trackers across clips and against the papers' own figures (``09_trackers_compared``).

Everything here works on benchmark rows (``trackbook.evaluation.bench.run`` / ``load``): dicts
with ``tracker``, ``clip``, ``auc``, ``precision20``, ``tracking_rate``, ``ms_median`` and the
trackers' own extras (``search_rate``, ...). The papers' headline figures are read from
:data:`trackbook.papers.PAPERS`; :func:`check_claims` tests each paper's central
claim on our data and says in numbers why it holds or not.
"""

from __future__ import annotations

import numpy as np

from .._markdown import table as _md_table
from ..clips.datasets import attributes as _attributes
from ..papers import PAPERS

#: Attributes of the development sequences: the OTB toolkit's table, and for the two VOT
#: sequences the same codes given by the OTB rules (see ``clips.datasets.attributes``).
SEQUENCE_ATTRIBUTES = {n: _attributes(n) for n in (
    "David", "Jogging1", "MotorRolling", "Couple", "Crossing", "Ball1", "Bag")}

#: What the attribute codes mean, for the difficulties the guide is about.
DIFFICULTIES = {
    "IV": "illumination change",
    "OCC": "occlusion",
    "FM": "fast motion",
    "BC": "distractors / clutter",
    "SV": "scale change",
    "DEF": "deformation",
}

def _mean(rows, tracker, key, clips=None):
    v = [r[key] for r in rows if r["tracker"] == tracker and r.get(key) is not None
         and (clips is None or r["clip"] in clips)]
    return float(np.mean(v)) if v else float("nan")


def table(rows, clips=None, keys=("auc", "precision20", "tracking_rate", "ms_median")) -> list[dict]:
    """One row per tracker: the mean of each score over ``clips`` (all by default);
    ``ms_median`` is the median over clips of the per-clip medians."""
    out = []
    for t in dict.fromkeys(r["tracker"] for r in rows):
        row = {"tracker": t}
        for k in keys:
            if k == "ms_median":
                v = [r[k] for r in rows if r["tracker"] == t and (clips is None or r["clip"] in clips)]
                row[k] = float(np.median(v)) if v else float("nan")
            else:
                row[k] = _mean(rows, t, k, clips)
        out.append(row)
    return out


def markdown(rows: list[dict], fmt: dict | None = None) -> str:
    """A list of dicts as a markdown table (the book has no pandas)."""
    if not rows:
        return ""
    formats = {c: (lambda v, f=f: f.format(v) if isinstance(v, float) else str(v))
               for c, f in (fmt or {}).items()}
    return _md_table(rows, list(rows[0]), formats=formats, number=".3f") + "\n"


def per_attribute(rows, attributes: dict, codes=tuple(DIFFICULTIES)) -> list[dict]:
    """Mean AUC of each tracker over the clips having each attribute, and the best tracker.

    ``attributes`` maps clip name -> attribute codes.
    """
    trackers = list(dict.fromkeys(r["tracker"] for r in rows))
    out = []
    for code in codes:
        clips = {c for c, a in attributes.items() if code in a}
        present = {r["clip"] for r in rows} & clips
        if not present:
            continue
        scores = {t: _mean(rows, t, "auc", present) for t in trackers}
        best = max(scores, key=lambda t: -1 if np.isnan(scores[t]) else scores[t])
        out.append({"difficulty": f"{DIFFICULTIES[code]} ({code})", "clips": len(present),
                    "best": best, "best AUC": scores[best], **{t: scores[t] for t in trackers}})
    return out


#: Each claim as pairwise comparisons ``(better, worse)``: "better scores higher than worse".
CLAIM_PAIRS = {
    "lee2012": [("color-hog-pf", "color-pf"), ("color-hog-ipca", "color-hog-pf")],
    "kim2016": [("hog-pf", "hsi-color-pf"), ("edge-ray-pf", "hog-pf")],
    "lee2015": [("kalman-covariance", "covariance")],
    "cho2005": [("condensation-mean-shift", "condensation"),
            ("condensation-mean-shift", "mean-shift")],
}

VERDICTS = ("holds", "fails", "inconclusive")


def paired_differences(rows, better: str, worse: str, metric: str = "auc",
                       clips=None) -> dict[str, list[float]]:
    """Per sequence, the paired differences ``score(better) - score(worse)``, one per seed.

    Rows pair when they share ``clip`` and ``seed`` (a missing ``seed`` counts as 0); a
    sequence where either tracker has no score is left out.
    """
    def key(r):
        return r["clip"], int(r.get("seed") or 0)

    def scores(name):
        return {key(r): float(r[metric]) for r in rows
                if r["tracker"] == name and r.get(metric) is not None
                and (clips is None or r["clip"] in clips) and np.isfinite(float(r[metric]))}

    b, w = scores(better), scores(worse)
    out: dict[str, list[float]] = {}
    for k in sorted(set(b) & set(w)):
        out.setdefault(k[0], []).append(b[k] - w[k])
    return out


def bootstrap_mean_difference(diffs: dict[str, list[float]], n_boot: int = 10_000,
                              level: float = 0.95, seed: int = 0) -> tuple[float, float, float]:
    """Mean paired difference and its percentile bootstrap interval, resampling *sequences*.

    Seeds of one sequence are not independent evidence (the same video, the same difficulty),
    so the bootstrap draws whole sequences with replacement (a cluster bootstrap) and averages
    every run of the drawn sequences. Returns ``(mean, low, high)``; NaNs without data.
    """
    seqs = [np.asarray(v, dtype=float) for v in diffs.values() if len(v)]
    if not seqs:
        return float("nan"), float("nan"), float("nan")
    sums = np.array([v.sum() for v in seqs])
    counts = np.array([len(v) for v in seqs], dtype=float)
    mean = float(sums.sum() / counts.sum())
    rng = np.random.default_rng(seed)
    pick = rng.integers(0, len(seqs), size=(n_boot, len(seqs)))
    boot = sums[pick].sum(axis=1) / counts[pick].sum(axis=1)
    a = (1.0 - level) / 2.0
    low, high = np.quantile(boot, [a, 1.0 - a])
    return mean, float(low), float(high)


def verdict(low: float, high: float) -> str:
    """``holds`` when the whole interval is above 0, ``fails`` when below, else ``inconclusive``."""
    if not (np.isfinite(low) and np.isfinite(high)):
        return "inconclusive"
    if low > 0:
        return "holds"
    if high < 0:
        return "fails"
    return "inconclusive"


def check_claims(rows, metric: str = "auc", clips=None, papers=PAPERS, pairs=CLAIM_PAIRS,
                 n_boot: int = 10_000, level: float = 0.95, seed: int = 0) -> list[dict]:
    """Each paper's claim, as paired comparisons with a bootstrap interval and a verdict.

    A claim "A < B < C" is the comparisons B > A and C > B. For each, the per-run differences
    of ``metric`` (paired by sequence and seed, over ``clips`` or all) are averaged, and a 95 %
    interval is bootstrapped over sequences (:func:`bootstrap_mean_difference`). The verdict is
    ``holds`` (interval above 0), ``fails`` (below 0) or ``inconclusive`` (it straddles 0).

    Returns
    -------
    rows ``{paper, comparison, metric, sequences, runs, mean_diff, ci_low, ci_high, verdict}``,
    one per comparison; a comparison whose trackers did not run has ``runs = 0`` and verdict
    ``inconclusive``.
    """
    out = []
    for key, p in papers.items():
        for better, worse in pairs.get(key, []):
            d = paired_differences(rows, better, worse, metric, clips)
            mean, low, high = bootstrap_mean_difference(d, n_boot, level, seed)
            out.append({"paper": p["label"], "comparison": f"{better} > {worse}",
                        "metric": metric, "sequences": len(d),
                        "runs": int(sum(len(v) for v in d.values())), "mean_diff": mean,
                        "ci_low": low, "ci_high": high, "verdict": verdict(low, high)})
    return out


def loso_select(scores: dict[str, dict[str, float]]) -> dict:
    """Leave-one-sequence-out choice among configurations, and the figure it earns.

    ``scores[config][sequence]`` is a configuration's score on a sequence (e.g. mean AUC over
    seeds). For each sequence in turn, the configuration with the best mean over the *other*
    sequences is chosen and scored on the held-out one. Returns ``{"cv": mean held-out score,
    "tuned": best mean over all sequences, "tuned_config": its name, "chosen": {sequence:
    config}}``. ``tuned`` is what a table reports when it picks the default on the same
    sequences it scores, and overstates what new video gives; ``cv`` does not peek.
    """
    configs = list(scores)
    seqs = sorted(set.intersection(*(set(v) for v in scores.values()))) if configs else []
    if len(seqs) < 2:
        raise ValueError("leave-one-sequence-out needs at least two sequences scored by "
                         "every configuration.")
    table = np.array([[scores[c][s] for s in seqs] for c in configs])
    chosen, held = {}, []
    for j, s in enumerate(seqs):
        rest = np.delete(table, j, axis=1).mean(axis=1)
        i = int(np.argmax(rest))
        chosen[s] = configs[i]
        held.append(table[i, j])
    means = table.mean(axis=1)
    best = int(np.argmax(means))
    return {"cv": float(np.mean(held)), "tuned": float(means[best]),
            "tuned_config": configs[best], "chosen": chosen}


def speed_ratios(rows, reference: str = "opencv-mil", papers=PAPERS) -> list[dict]:
    """Per tracker: our median ms/frame, ×MIL on the same clips, the paper's ms and paper/ours."""
    ours = {r["tracker"]: r["ms_median"] for r in table(rows, keys=("ms_median",))}
    ref = ours.get(reference, float("nan"))
    paper_ms = {t: (v, p["hardware"]) for p in papers.values() for t, v in p["ms"].items()}
    out = []
    for t, v in ours.items():
        if t == reference:
            continue
        pm, hw = paper_ms.get(t, (float("nan"), ""))
        out.append({"tracker": t, "ms/frame": v, "÷ MIL": v / ref if ref else float("nan"),
                    "paper ms": pm, "paper ÷ ours": pm / v if v else float("nan"),
                    "paper's hardware": hw or "–"})
    return out


# ------------------------------------------------------------------ Lee 2015, Table 1
#: The columns of Lee 2015's Table 1 as the book prints them, with its scores beside.
TABLE1_COLUMNS = ["tracker", "clip", "frames", "misses", "detection_rate", "search_rate", "auc",
                  "precision20", "ms_median", "ms_mean"]


def lee2015_table1_row(result, groundtruth) -> dict:
    """One row of Table 1 of Lee 2015 from a :class:`trackbook.Result` (frame 0, the
    initialisation, excluded): misses, detection rate, averaging search rate, ms/frame.

    The paper's detection rate (eq. 14) is "frames where the region was detected / all
    frames"; the book counts a frame as detected when IoU > 0.5
    (:func:`trackbook.metrics.tracking_rate`), and a miss is any other scored frame. The
    averaging search rate is the mean over frames of evaluated candidate windows / all windows
    in the frame (the trackers' ``frame_report``).
    """
    from . import metrics

    gt = np.asarray(groundtruth, dtype=float)[: len(result.boxes)]
    iou = metrics.iou(result.boxes[1:], gt[1:])
    known = np.all(np.isfinite(gt[1:]), axis=1)
    sr = result.extras.get("search_rate")
    return {
        "tracker": result.tracker,
        "clip": result.clip,
        "frames": int(known.sum()),
        "misses": int(np.sum(iou[known] <= 0.5)),
        "detection_rate": metrics.tracking_rate(result.boxes[1:], gt[1:]),
        "search_rate": float(np.nanmean(sr[1:])) if sr is not None else float("nan"),
        "auc": result.scores["auc"],
        "precision20": result.scores["precision20"],
        "ms_median": result.scores["ms_median"],
        "ms_mean": result.scores["ms_mean"],
    }


def lee2015_table1(rows) -> list[dict]:
    """Table-1 rows (as :func:`lee2015_table1_row`) from benchmark rows, e.g. the committed
    result ``lee2015_real``: ``frames`` are the scored frames, ``misses`` the scored frames
    with IoU <= 0.5 (the benchmark keeps the rate; the count follows from it)."""
    out = []
    for r in rows:
        n = int(r["frames_scored"])
        rate = float(r["tracking_rate"])
        out.append({"tracker": r["tracker"], "clip": r["clip"], "frames": n,
                    "misses": n - int(round(rate * n)), "detection_rate": rate,
                    "search_rate": float(r.get("search_rate", float("nan"))),
                    **{k: float(r[k]) for k in ("auc", "precision20", "ms_median", "ms_mean")}})
    return out


# ------------------------------------------------------------------ Cho & Kang 2005, Tables 1-2
def cho2005_single_target_table(clip_names, trackers=None, seed=0, max_frames=None) -> list[dict]:
    """Table 1 of Cho & Kang 2005 on our clips: one row per (tracker, clip) with ms_median, the
    paper's ms (``paper_ms``), auc, precision20 and the mean candidate likelihood."""
    from .. import clips as _clips
    from .runner import evaluate

    paper = PAPERS["cho2005"]
    rows = []
    for c in clip_names:
        clip = _clips.load(c)
        for t in trackers or paper["trackers"]:
            r = evaluate(t, clip, seed=seed, max_frames=max_frames)
            lik = r.extras.get("mean_likelihood")
            rows.append({"tracker": t, "clip": clip.name, "frames": len(r.boxes),
                         "auc": r.scores["auc"], "precision20": r.scores["precision20"],
                         "ms_median": r.scores["ms_median"], "ms_mean": r.scores["ms_mean"],
                         "mean_likelihood": float(np.nanmean(lik[1:])) if lik is not None
                         else float("nan"),
                         "paper_ms": paper["ms"].get(t, float("nan"))})
    return rows


def cho2005_two_target_table(clip_name="two-faces", trackers=None, seed=0,
                             max_frames=None) -> list[dict]:
    """Table 2 of Cho & Kang 2005 on a two-target clip: one row per tracker with ms per frame
    for all targets at once, the paper's ms and each target's AUC (``auc_<target>``)."""
    from .. import clips as _clips
    from . import metrics
    from .runner import evaluate

    paper = PAPERS["cho2005"]
    clip = _clips.load(clip_name)
    rows = []
    for t in trackers or paper["trackers"]:
        res = evaluate(t, clip, seed=seed, max_frames=max_frames, targets="all")
        row = {"tracker": t, "clip": clip.name, "ms_median": res.scores["ms_median"],
               "paper_ms": paper["ms_two_targets"].get(t, float("nan"))}
        for name, r in res.results.items():
            row[f"auc_{name}"] = metrics.auc(r.boxes[1:], clip.targets[name][1:len(r.boxes)])
        rows.append(row)
    return rows
