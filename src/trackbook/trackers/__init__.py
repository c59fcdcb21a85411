"""Trackers: the registry, the shared base class and the papers' trackers.

>>> from trackbook import trackers
>>> trackers.available()          # every name create accepts, opencv-mil last  # doctest: +SKIP
>>> t = trackers.create("color-hog-ipca", seed=0, n_particles=100)  # doctest: +SKIP
>>> t.init(frame, (x, y, w, h)); ok, box = t.update(next_frame)     # doctest: +SKIP

The papers' trackers register themselves when their module is imported below; each module
matches one chapter of the book.
"""

from __future__ import annotations

from .._checks import clip_box
from . import plugins
from .base import Tracker, TrackerState, redetecting
from .registry import PRESETS, available, create, departures, get, register
from .multi import MultiTracker
from .reference import REFERENCE

# The papers' trackers (each import registers its names) -------------------------------
# (one line per paper module; the order is the book's)
from . import color_pf  # noqa: E402,F401  lee2012: color-pf (02_particle_filters)
from . import color_hog_pf  # noqa: E402,F401  lee2012: color-hog-pf (03_hog)
from . import color_hog_ipca  # noqa: E402,F401  lee2012: color-hog-ipca (04_incremental_svd)
from . import hsi_color_pf  # noqa: E402,F401  kim2016: hsi-color-pf
from . import hog_pf  # noqa: E402,F401  kim2016: hog-pf
from . import edge_ray  # noqa: E402,F401  kim2016: edge-ray-pf
from . import covariance  # noqa: E402,F401  lee2015: covariance, kalman-covariance
from . import covariance_manoeuvre  # noqa: E402,F401  the book's variant: kalman-covariance-manoeuvre
from . import condensation_mean_shift  # noqa: E402,F401  cho2005: condensation, mean-shift, condensation-mean-shift
from . import camshift  # noqa: E402,F401  bradski1998: camshift
from . import correlation  # noqa: E402,F401  bolme2010, henriques2015: mosse, kcf (10_correlation_filters)
from . import dsst  # noqa: E402,F401  danelljan2014: dsst
from . import staple  # noqa: E402,F401  bertinetto2016: staple
from . import bacf  # noqa: E402,F401  kianigaloogahi2017: bacf (background-aware correlation filters)
from . import median_flow  # noqa: E402,F401  kalal2010: median-flow


__all__ = ["MultiTracker", "PRESETS", "REFERENCE", "Tracker", "TrackerState", "available",
           "clip_box", "create", "departures", "get", "plugins", "redetecting", "register"]
