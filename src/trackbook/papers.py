"""What is printed in the four papers: their headline tables, timings, hardware and citations.

One dictionary, :data:`PAPERS`, keyed by paper (``lee2012``, ``kim2016``, ``lee2015``,
``cho2005``; the keys are also the entries of ``book/references.bib``). Chapters, the lab
notes and :mod:`trackbook.evaluation.compare` read the printed figures from here, so each is
typed once. A figure a paper does not print is absent (not zero, not guessed).

This module is data only and imports nothing from the library.

Fields of each entry
--------------------
label : short citation ("Lee et al. 2012")
citation : the full reference (as in ``book/references.bib``)
table : which table the headline figures come from
trackers : the registered trackers standing for the paper's methods (proposed and
    baselines), in its order
tracking_rate : printed tracking (detection) rate per tracker, as fractions
ms : printed milliseconds per frame, single target
hardware : the machine (and image size) the paper timed on
claim : the central claim of the paper, in words
kind : how :func:`trackbook.evaluation.compare.check_claims` reads the claim

and, where printed: ``search_rate`` and ``table1`` (Lee 2015's Table 1 on RedCube: misses,
frames, detection rate, averaging search rate), ``ms_two_targets`` (Cho & Kang's Table 2).
"""

from __future__ import annotations

PAPERS = {
    "lee2012": {
        "label": "Lee et al. 2012",
        "citation": "Lee, Cui, Kim, Ma, Lee and Kim (2012), Robust Object Tracking in Mobile "
                    "Robots using Object Features and On-line Learning based Particle Filter, "
                    "Journal of Institute of Control, Robotics and Systems",
        "table": "Lee et al. 2012, Table 3",
        "trackers": ["color-pf", "color-hog-pf", "color-hog-ipca"],
        "tracking_rate": {"color-pf": 0.711, "color-hog-pf": 0.903, "color-hog-ipca": 0.924},
        "ms": {"color-pf": 7.0, "color-hog-pf": 13.0, "color-hog-ipca": 55.0},
        "hardware": "Intel Core 2 Quad Q6600 2.4 GHz, Visual Studio 2008 / OpenCV 2.1, 640x480",
        "claim": "tracking rate: Color < Color+HOG < Proposed",
        "kind": "rate_order",
    },
    "kim2016": {
        "label": "Kim et al. 2016",
        "citation": "Kim, Kim and Choi (2016), Tracking moving objects using particle filter and "
                    "edge observation model, Journal of Korean Society for Internet Information",
        "table": "Kim, Kim & Choi 2016, Table 3",
        "trackers": ["hsi-color-pf", "hog-pf", "edge-ray-pf"],
        "tracking_rate": {"hsi-color-pf": 0.623, "hog-pf": 0.704, "edge-ray-pf": 0.898},
        "ms": {},
        "hardware": "not reported",
        "claim": "tracking rate: HSI < HOG < edge rays",
        "kind": "rate_order",
    },
    "lee2015": {
        "label": "Lee 2015",
        "citation": ("Lee (2015), A Fast Moving Object Tracking Method by the Combination of "
                     "Covariance Matrix and Kalman Filter Algorithm, Journal of the Korea "
                     "Institute of Information and Communication Engineering"),
        "table": "Lee 2015, Table 1 (RedCube, 164 frames)",
        "trackers": ["covariance", "kalman-covariance"],
        "tracking_rate": {"covariance": 0.871, "kalman-covariance": 0.963},
        "search_rate": {"covariance": 0.00134, "kalman-covariance": 0.00043},
        #: Table 1 [quote: lee2015.table1] (RedCube; 164 frames in the table, 184 in the text
        #: [quote: lee2015.frames184]).
        "table1": {
            "covariance": {"misses": 21, "frames": 164, "detection_rate": 0.871,
                           "search_rate": 0.00134},
            "kalman-covariance": {"misses": 6, "frames": 164, "detection_rate": 0.963,
                                  "search_rate": 0.00043},
        },
        "ms": {},
        "hardware": "Intel Pentium G2120 3.1 GHz, 320x240",
        "claim": "the Kalman window detects more and searches less than covariance alone",
        "kind": "kalman",
    },
    "cho2005": {
        "label": "Cho & Kang 2005",
        "citation": ("Cho and Kang (2005), Integration of Condensation and Mean-shift algorithms "
                     "for real-time object tracking, The KIPS Transactions: Part B"),
        "table": "Cho & Kang 2005, Table 1 (single target)",
        "trackers": ["condensation", "mean-shift", "condensation-mean-shift"],
        "tracking_rate": {},
        #: Table 1 (single target), ms per frame.
        "ms": {"condensation": 84.0, "mean-shift": 7.0, "condensation-mean-shift": 35.0},
        #: Table 2 (two targets), ms per frame.
        "ms_two_targets": {"condensation": 248.0, "mean-shift": 17.0,
                           "condensation-mean-shift": 86.0},
        "hardware": "Pentium 4 1.5 GHz, 320x240",
        "claim": "5 candidates + mean-shift are faster than Condensation and more accurate "
                 "than both",
        "kind": "speed_accuracy",
    },
}

#: The trackers of the four papers (baselines and proposed), paper by paper: what the
#: comparisons of ``09_trackers_compared`` are about (``mosse`` and ``kcf`` come after it).
TRACKERS = tuple(t for p in PAPERS.values() for t in p["trackers"])
