"""Every tracker records the paper's value of every knob, and says why where the book differs.

The per-paper tests (``test_paper_<author><year>.py``) pin the printed values with the page of
the paper; this file checks the mechanism for all eleven trackers at once: ``preset="paper"``
builds, every field has a ``paper=``, and every departure has a ``why``.
"""
import dataclasses

import numpy as np
import pytest

from trackbook import params as P
from trackbook import trackers

NAMES = trackers.available(reference=False)


@pytest.mark.parametrize("name", NAMES)
def test_every_field_records_the_papers_value(name):
    cls = trackers.get(name).Params
    missing = [f.name for f in dataclasses.fields(cls) if not P.has_paper(f)]
    assert not missing, f"{name}: fields without paper=: {missing}"


@pytest.mark.parametrize("name", NAMES)
def test_every_departure_says_why(name):
    rows = trackers.departures(name)
    # a why is a reason, not a word: at least five words
    silent = [r["param"] for r in rows if len(r["why"].split()) < 5]
    assert not silent, f"{name}: defaults that differ from the paper without a why: {silent}"
    for r in rows:
        assert set(r) == {"param", "paper", "book", "why"}


@pytest.mark.parametrize("name", NAMES)
def test_paper_preset_builds_the_printed_method_and_runs(name):
    cls = trackers.get(name).Params
    t = trackers.create(name, seed=0, preset="paper")
    for f in dataclasses.fields(cls):
        assert getattr(t.params, f.name) == P.paper_value(f), f.name
    frame = np.full((60, 80, 3), 90, np.uint8)
    frame[20:40, 30:50] = (40, 60, 200)
    t.init(frame, (30, 20, 20, 20))
    ok, box = t.update(frame)
    assert np.all(np.isfinite(box))


def test_keyword_params_override_the_preset():
    name = NAMES[0]
    field = dataclasses.fields(trackers.get(name).Params)[0]
    lo = field.metadata.get("lo")
    value = field.default if lo is None else type(field.default)(lo)
    t = trackers.create(name, preset="paper", **{field.name: value})
    assert getattr(t.params, field.name) == value


def test_unknown_preset_is_refused_with_the_choices():
    with pytest.raises(ValueError, match="book, paper"):
        trackers.create(NAMES[0], preset="printed")


def test_departures_mechanism_by_hand():
    @dataclasses.dataclass(frozen=True)
    class Knobs:
        a: int = P.param(100, 1, 1000, paper=100)
        b: float = P.param(0.2, 0, 1, paper=0.4, why="measured on the sample clips")
        c: str = P.param("box", choices=("box", "frame"), paper=P.NOT_PRINTED,
                         why="the paper's pseudocode spreads particles over the frame")
        d: float = P.param(0.5, 0, 1, paper=P.NOT_PRINTED, paper_value=0.0,
                           why="the book's addition; 0 switches it off")
        e: bool = P.param(True, paper=1)

    rows = {r["param"]: r for r in P.departures(Knobs)}
    assert set(rows) == {"b", "c", "d", "e"}          # a agrees; True is not the number 1
    assert rows["b"] == {"param": "b", "paper": 0.4, "book": 0.2,
                         "why": "measured on the sample clips"}
    assert rows["c"]["paper"] == "not printed"
    assert P.paper_values(Knobs) == {"a": 100, "b": 0.4, "c": "box", "d": 0.0, "e": 1}
