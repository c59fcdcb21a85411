"""The passage behind each printed value is declared on the param itself (``printed=`` /
``reading=``), and :func:`trackbook.quotes.fields.state` reads it from there.

The oracle is the table the declarations replaced, corrected where it called a value
printed that its passage gives only for another tracker or only as a maximum: Lee et al.
(2012) print section V's values for their proposed tracker and none of the settings of the
two filters they compare with, so for ``color-pf`` and ``color-hog-pf`` those values are
readings; Kim et al. (2016) use "at most 999" particles, a maximum that the paper preset reads
as the setting. For every registered tracker and every one of its params the state read from
the declarations equals the table's.
"""

from __future__ import annotations

import dataclasses

import pytest

from trackbook import params, trackers
from trackbook.params import param
from trackbook.quotes import fields

# -- the former second table (trackbook.quotes.fields.FIELDS), as it was ---------------------
# section V's values, printed for the proposed tracker (color-hog-ipca) ...
_LEE2012_SECTION_V = {
    "n_particles": "lee2012.n100",
    "sigma_color": "lee2012.sigma04",
    "size_noise": "lee2012.motion_noise",
    "vx_noise": "lee2012.motion_noise",
    "vy_noise": "lee2012.motion_noise",
    "resampler": "lee2012.resample_cumulative",
    "init": "lee2012.init_whole_frame",
    "alpha": "lee2012.alpha01",
    "sigma_hog": "lee2012.sigma04",
}
_COLOR_FIELDS = ("n_particles", "sigma_color", "size_noise", "vx_noise", "vy_noise",
                 "resampler", "init")
# ... and read as the settings of the two baselines, which section VI compares with [14, 20]
# without printing theirs
_LEE2012_COLOR = {k: (_LEE2012_SECTION_V[k], "reading") for k in _COLOR_FIELDS}
_LEE2012_HOG = {k: (v, "reading") for k, v in _LEE2012_SECTION_V.items()}
_LEE2012_IPCA = {
    **{k: (v, "printed") for k, v in _LEE2012_SECTION_V.items()},
    "T": ("lee2012.t40", "printed"),
    "learn_threshold": ("lee2012.unfiltered_accumulation", "printed"),
    "gate_k": ("lee2012.unfiltered_accumulation", "printed"),
    "learn_every": ("lee2012.accumulate_every_frame", "printed"),
    # eq. 12-13 reconstruct z with U U^T alone: no anchor to the first frame, no mean
    # subtracted, the histogram itself as z; the garbled print makes each a reading
    # eq. 12-13 print D, not D^2, in the exponent
    "exponent": ("lee2012.likelihood_eq12", "printed"),
    # A = {I_1 ... I_n}, n = 40, m = 1, old features removed: a window of the last 40 is a
    # reading (which feature leaves is not printed)
    "window": ("lee2012.window40", "reading"),
    "anchor": ("lee2012.likelihood_eq12", "reading"),
    "centre": ("lee2012.likelihood_eq12", "reading"),
    "feature_map": ("lee2012.likelihood_eq12", "reading"),
}
_LEE2015 = {
    # eq. 2 is printed with an ellipsis after I_x: the rest of f is the book's completion
    "features": ("lee2015.features_eq2", "reading"),
}

FIELDS: dict[str, dict[str, tuple[str, str]]] = {
    "color-pf": _LEE2012_COLOR,
    "color-hog-pf": _LEE2012_HOG,
    "color-hog-ipca": _LEE2012_IPCA,
    "edge-ray-pf": {
        # "at most 999" (최대 999개): a maximum, read as the setting
        "n_particles": ("kim2016.max999", "reading"),
        "ratio_low": ("kim2016.ratio_window", "printed"),
        "ratio_high": ("kim2016.ratio_window", "printed"),
    },
    "covariance": {
        **_LEE2015,
        "fallback": ("lee2015.whole_frame_search", "printed"),
    },
    "kalman-covariance": {
        **_LEE2015,
        "q": ("lee2015.q_identity", "printed"),
        "r": ("lee2015.r_identity", "printed"),
        # the 24 x 24 region is printed for the search-rate measurement, not for a model window
        "init_size": ("lee2015.window24", "reading"),
    },
    "mean-shift": {
        "bandwidth": ("cho2005.bandwidth_eq3", "printed"),
    },
    "condensation": {
        "bandwidth": ("cho2005.bandwidth_eq3", "printed"),
        "n_particles": ("cho2005.condensation_n100", "printed"),
        "resampler": ("cho2005.condensation_sampling", "reading"),
    },
    "condensation-mean-shift": {
        "bandwidth": ("cho2005.bandwidth_eq3", "printed"),
        "n_particles": ("cho2005.proposed_n5", "printed"),
        "resampler": ("cho2005.condensation_sampling", "reading"),
        # eq. 12-13 move each candidate once (y1 = y0 + y^n); no iteration count is printed
        "max_iter": ("cho2005.likelihood_rises_eq13", "reading"),
        "use_motion": ("cho2005.motion_vector", "printed"),
        # eq. 8 is one least-squares problem over the region: one level, one solve, as read
        "flow_levels": ("cho2005.flow_eq8", "reading"),
        "flow_iterations": ("cho2005.flow_eq8", "reading"),
    },
}
# The book's manoeuvre variant of kalman-covariance has its fields (its own two are not in
# the paper); the re-detecting names are not in the table (``_oracle`` reads their algorithm's).
FIELDS["kalman-covariance-manoeuvre"] = dict(FIELDS["kalman-covariance"])


def _oracle(tracker: str, field: str) -> tuple[str, str | None]:
    # a re-detecting variant (``kcf-redetect``) has the params of the algorithm it wraps
    found = FIELDS.get(tracker.removesuffix("-redetect"), {}).get(field)
    return found[::-1] if found else ("not printed", None)


CASES = [(n, f.name) for n in trackers.available()
         if dataclasses.is_dataclass(getattr(trackers.get(n), "Params", None))
         for f in dataclasses.fields(trackers.get(n).Params)]


def test_the_walk_covers_every_tracker_of_the_table():
    assert set(FIELDS) <= {n for n, _ in CASES} and len(CASES) > 150


@pytest.mark.parametrize("tracker,field", CASES, ids=[f"{t}.{f}" for t, f in CASES])
def test_state_is_the_former_tables(tracker, field):
    assert fields.state(tracker, field) == _oracle(tracker, field)


def test_the_table_view_is_the_former_table():
    assert fields.table() == FIELDS


def test_a_param_declares_its_passage():
    @dataclasses.dataclass(frozen=True)
    class P:
        a: int = param(40, 1, 99, 1, "a", printed="lee2012.t40", paper=40)
        b: int = param(3, 1, 99, 1, "b", reading="lee2012.window40", paper=40, why="w")
        c: int = param(3, 1, 99, 1, "c", paper=params.NOT_PRINTED, why="w")
    got = [params.provenance(f) for f in dataclasses.fields(P)]
    assert got == [("printed", "lee2012.t40"), ("reading", "lee2012.window40"),
                   ("not printed", None)]


def test_a_value_is_printed_or_read_not_both():
    with pytest.raises(ValueError, match="give one key"):
        param(1, printed="lee2012.t40", reading="lee2012.t40", paper=1)
