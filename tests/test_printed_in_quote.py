"""A preset value marked "printed" is in its quoted passage, and the passage is about that
tracker.

Every registered tracker's params are walked (re-detecting and variant names too). A field
whose provenance is ``printed=KEY`` passes only if

- the quote ``KEY`` is itself of kind "printed";
- the value is in the passage's original text: a number as it is spelled (``0.4`` is not
  ``0.45``, ``40`` not ``400``), or, for a value the paper states in words (a choice, a
  switch, "without filtering" for a gate that is off), the words listed for it below, which
  must stand in the original;
- the passage is about that tracker: ``ABOUT`` names, from the papers' texts, the trackers
  each passage gives values for. A setting printed for a paper's proposed tracker is not
  printed for the trackers it is compared with (Lee et al. 2012, section V, describe the
  proposed algorithm, "제안된 알고리즘의 Pseudo Code", and section VI compares it with [14, 20]
  without their settings).

The oracle is the two tables below, written from the papers' texts in ``../shared/seeds``, not
from the params.
"""

from __future__ import annotations

import dataclasses
import re

import pytest

from trackbook import params, quotes, trackers

#: The registered trackers each passage gives values for.
ABOUT = {
    # Lee et al. 2012: sections II, IV, V and VII describe the proposed algorithm ("제안된
    # 알고리즘"; the pseudocode of section V is "제안된 알고리즘의 Pseudo Code").
    "lee2012.n100": {"color-hog-ipca"},
    "lee2012.sigma04": {"color-hog-ipca"},
    "lee2012.motion_noise": {"color-hog-ipca"},
    "lee2012.resample_cumulative": {"color-hog-ipca"},
    "lee2012.init_whole_frame": {"color-hog-ipca"},
    "lee2012.alpha01": {"color-hog-ipca"},
    "lee2012.t40": {"color-hog-ipca"},
    "lee2012.likelihood_eq12": {"color-hog-ipca"},
    "lee2012.unfiltered_accumulation": {"color-hog-ipca"},
    "lee2012.accumulate_every_frame": {"color-hog-ipca"},
    # Kim et al. 2016, section 3.2: the Ratio window of the proposed edge model.
    "kim2016.ratio_window": {"edge-ray-pf"},
    # Lee 2015: Q and R of the proposed Kalman filter (section 2.2); the whole-frame search
    # of the covariance tracker alone (section 3, frame 160).
    "lee2015.q_identity": {"kalman-covariance"},
    "lee2015.r_identity": {"kalman-covariance"},
    "lee2015.whole_frame_search": {"covariance"},
    # Cho & Kang 2005: section 3.1 defines the object (an ellipse, eq. 3) for the algorithms
    # of section 3 and the proposed one; section 5.1 gives each system its candidates.
    "cho2005.bandwidth_eq3": {"condensation", "mean-shift", "condensation-mean-shift"},
    "cho2005.condensation_n100": {"condensation"},
    "cho2005.proposed_n5": {"condensation-mean-shift"},
    "cho2005.motion_vector": {"condensation-mean-shift"},
}

#: ``(quote key, value)``: the words of the original that state a value printed in words.
WORDS = {
    ("lee2012.resample_cumulative", "multinomial"):
        r"균일 분포의 난수 $r \in [0, 1]$ 생성하기 2. $c_{t-1}^{(i)} \geq r$ 인 가장 작은",
    ("lee2012.init_whole_frame", "frame"): "영상 전체에 분포된 파티클",
    ("lee2012.likelihood_eq12", "D"): r"\exp\left(-\frac{D(z_x^{color}",
    ("lee2012.unfiltered_accumulation", 0.0): "여과 없이 누적",
    ("lee2012.accumulate_every_frame", 1): "매 프레임 동안 누적",
    ("lee2015.whole_frame_search", "frame"): "전 영역을 후보 영역으로 탐색",
    ("cho2005.bandwidth_eq3", "diagonal"): r"a 는 $\sqrt{H_x^2 + H_y^2}$",
    ("cho2005.motion_vector", True): "모션 벡터(Motion vector)를 이용한다",
}

#: The book's variants, whose printed fields are those of the paper's tracker they extend.
VARIANT_OF = {"kalman-covariance-manoeuvre": "kalman-covariance"}


def _paper_tracker(name: str) -> str:
    name = name.removesuffix("-redetect")
    return VARIANT_OF.get(name, name)


def _printed():
    out = []
    for name in trackers.available():
        P = getattr(trackers.get(name), "Params", None)
        if not dataclasses.is_dataclass(P):
            continue
        for f in dataclasses.fields(P):
            state, key = params.provenance(f)
            if state == "printed":
                out.append((name, f.name, key, f.metadata["paper"]))
    return out


PRINTED = _printed()


def _spelled(value, text: str) -> bool:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    number = f"{value:g}"
    return re.search(rf"(?<![\d.]){re.escape(number)}(?![\d]|\.\d)", text) is not None


def test_the_walk_finds_the_printed_values_of_the_four_papers():
    keys = {key.split(".")[0] for _, _, key, _ in PRINTED}
    assert keys == set(quotes.PAPERS)
    assert len(PRINTED) > 15


@pytest.mark.parametrize("tracker,field,key,value", PRINTED,
                         ids=[f"{t}.{f}" for t, f, _, _ in PRINTED])
def test_a_printed_value_is_in_its_passage_about_its_tracker(tracker, field, key, value):
    q = quotes.quote(key)
    assert q.kind == "printed", f"{tracker}.{field}: {key} is a reading, not a printed passage"
    words = WORDS.get((key, value))
    if words is not None:
        assert words in q.original, f"{tracker}.{field}: {words!r} is not in {key}"
    else:
        assert _spelled(value, q.original), (
            f"{tracker}.{field} = {value!r} is marked printed but is not in the passage {key}")
    about = ABOUT.get(key, set())
    assert _paper_tracker(tracker) in about, (
        f"{tracker}.{field} = {value!r} is marked printed by {key}, a passage about "
        f"{sorted(about) or 'no registered tracker'}: mark it a reading or not printed")


def test_the_lookup_can_fail():
    """By hand: the spelling is exact, the words must be in the passage, and a passage about
    the proposed tracker does not print the baselines' settings."""
    sigma = quotes.quote("lee2012.sigma04").original
    assert _spelled(0.4, sigma) and not _spelled(0.45, sigma) and not _spelled(4, sigma)
    assert not _spelled(4, quotes.quote("lee2012.t40").original)
    assert _spelled(40, quotes.quote("lee2012.t40").original)
    assert not _spelled(True, quotes.quote("cho2005.motion_vector").original)
    assert "color-pf" not in ABOUT["lee2012.n100"]
    assert "hsi-color-pf" not in ABOUT["kim2016.ratio_window"]
    # Kim et al. 2016 give "at most 999" particles: a maximum, not a printed setting
    assert "kim2016.max999" not in ABOUT


def test_the_tables_name_registered_trackers_and_quotes():
    names = set(trackers.available())
    for key, about in ABOUT.items():
        assert quotes.quote(key).kind == "printed", key
        assert about <= names, (key, about - names)
    for (key, _), words in WORDS.items():
        assert words in quotes.quote(key).original, key
