"""Comparing trackers across clips and against the papers' own figures (chapter 09).

Everything here works on benchmark rows (``trackbook.evaluation.bench.run`` / ``load``): dicts
with ``tracker``, ``clip``, ``auc``, ``precision20``, ``tracking_rate``, ``ms_median`` and the
trackers' own extras (``search_rate``, ...). The papers' headline figures live in
:data:`PAPERS`, transcribed from their tables; :func:`check_claims` tests each paper's central
claim on our data and says in numbers why it holds or not.
"""

from __future__ import annotations

import numpy as np

#: Attributes of the development sequences (OTB codes from the benchmark's annotation; the two
#: VOT sequences annotated by the same rules from their SOURCE.txt descriptions).
SEQUENCE_ATTRIBUTES = {
    "David": ("IV", "OPR", "SV", "OCC", "DEF", "MB", "IPR"),
    "Jogging1": ("OPR", "OCC", "DEF"),
    "MotorRolling": ("IV", "SV", "MB", "FM", "IPR", "BC", "LR"),
    "Couple": ("OPR", "SV", "DEF", "FM", "BC"),
    "Crossing": ("SV", "DEF", "BC"),
    "Ball1": ("FM", "BC", "LR"),
    "Bag": ("DEF", "IPR", "SV", "BC"),
}

#: What the attribute codes mean, for the difficulties the guide is about.
DIFFICULTIES = {
    "IV": "illumination change",
    "OCC": "occlusion",
    "FM": "fast motion",
    "BC": "distractors / clutter",
    "SV": "scale change",
    "DEF": "deformation",
}

#: The papers' headline figures (their tables), and the hardware they were measured on.
PAPERS = {
    "000": {
        "paper": "Lee et al. 2012, Table 3",
        "trackers": ["color-pf", "color-hog-pf", "color-hog-ipca"],
        "tracking_rate": {"color-pf": 0.711, "color-hog-pf": 0.903, "color-hog-ipca": 0.924},
        "ms": {"color-pf": 7.0, "color-hog-pf": 13.0, "color-hog-ipca": 55.0},
        "hardware": "Intel Core 2 Quad Q6600, C++, 640x480",
        "claim": "tracking rate: Color < Color+HOG < Proposed",
        "kind": "rate_order",
    },
    "001": {
        "paper": "Kim, Kim & Choi 2016, Table 3",
        "trackers": ["hsi-color-pf", "hog-pf", "edge-ray-pf"],
        "tracking_rate": {"hsi-color-pf": 0.623, "hog-pf": 0.704, "edge-ray-pf": 0.898},
        "ms": {},
        "hardware": "not reported",
        "claim": "tracking rate: HSI < HOG < edge rays",
        "kind": "rate_order",
    },
    "002": {
        "paper": "Lee 2015, Table 1 (RedCube, 164 frames)",
        "trackers": ["covariance", "kalman-covariance"],
        "tracking_rate": {"covariance": 0.871, "kalman-covariance": 0.963},
        "search_rate": {"covariance": 0.00134, "kalman-covariance": 0.00043},
        "ms": {},
        "hardware": "Intel Pentium G2120 3.1 GHz, 320x240",
        "claim": "the Kalman window detects more and searches less than covariance alone",
        "kind": "kalman",
    },
    "003": {
        "paper": "Cho & Kang 2005, Table 1 (single target)",
        "trackers": ["condensation", "mean-shift", "condensation-mean-shift"],
        "tracking_rate": {},
        "ms": {"condensation": 84.0, "mean-shift": 7.0, "condensation-mean-shift": 35.0},
        "hardware": "Pentium 4 1.5 GHz, 320x240",
        "claim": "5 candidates + mean-shift are faster than Condensation and more accurate "
                 "than both",
        "kind": "speed_accuracy",
    },
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
    fmt = fmt or {}
    cols = list(rows[0])
    lines = ["| " + " | ".join(cols) + " |", "|" + "|".join("---" for _ in cols) + "|"]
    for r in rows:
        cells = []
        for c in cols:
            v = r[c]
            if isinstance(v, float):
                cells.append("–" if not np.isfinite(v) else fmt.get(c, "{:.3f}").format(v))
            else:
                cells.append(str(v))
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


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


def check_claims(rows, clips, papers=PAPERS) -> list[dict]:
    """Each paper's central claim tested on ``rows`` restricted to ``clips``.

    Returns rows ``{paper, claim, paper's figures, ours, holds}``, ``holds`` being
    ``"yes"``, ``"no"`` or ``"n/a"`` (trackers missing from the rows).
    """
    out = []
    names = {r["tracker"] for r in rows}
    for key, p in papers.items():
        ts = p["trackers"]
        if not set(ts) <= names:
            out.append({"paper": p["paper"], "claim": p["claim"], "paper's figures": "",
                        "ours": "trackers not run", "holds": "n/a"})
            continue
        rate = {t: _mean(rows, t, "tracking_rate", clips) for t in ts}
        auc = {t: _mean(rows, t, "auc", clips) for t in ts}
        ms = {t: _mean(rows, t, "ms_median", clips) for t in ts}
        if p["kind"] == "rate_order":
            holds = all(rate[a] < rate[b] for a, b in zip(ts, ts[1:]))
            theirs = " < ".join(f"{100 * p['tracking_rate'][t]:.1f} %" for t in ts)
            ours = " , ".join(f"{t} {100 * rate[t]:.1f} %" for t in ts)
        elif p["kind"] == "kalman":
            sr = {t: _mean(rows, t, "search_rate", clips) for t in ts}
            holds = rate[ts[1]] >= rate[ts[0]] and sr[ts[1]] < sr[ts[0]]
            theirs = (f"{100 * p['tracking_rate'][ts[0]]:.1f} % / {100 * p['search_rate'][ts[0]]:.3f} % "
                      f"→ {100 * p['tracking_rate'][ts[1]]:.1f} % / {100 * p['search_rate'][ts[1]]:.3f} %")
            ours = (f"{100 * rate[ts[0]]:.1f} % / {100 * sr[ts[0]]:.3f} % → "
                    f"{100 * rate[ts[1]]:.1f} % / {100 * sr[ts[1]]:.3f} %")
        else:  # speed_accuracy
            c, m, pr = ts
            holds = ms[pr] < ms[c] and auc[pr] >= max(auc[c], auc[m])
            theirs = " / ".join(f"{p['ms'][t]:.0f} ms" for t in ts)
            ours = (" / ".join(f"{ms[t]:.2f} ms" for t in ts) + "; AUC "
                    + " / ".join(f"{auc[t]:.3f}" for t in ts))
        out.append({"paper": p["paper"], "claim": p["claim"], "paper's figures": theirs,
                    "ours": ours, "holds": "yes" if holds else "no"})
    return out


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
