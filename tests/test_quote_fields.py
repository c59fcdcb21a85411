"""Every value a tracker's params record as printed has a passage of the register behind it.

The printed numbers are looked up in the passage itself (a printed 0.4 must be in the
passage), so a wrong key or a wrong number fails; values that are readings (0/1, "off",
the completion of an elided equation) are marked so and need only their passage.
"""

from __future__ import annotations

import dataclasses
import re

import pytest

from trackbook import params, quotes, trackers
from trackbook.papers import TRACKERS as PAPER_TRACKERS
from trackbook.quotes.fields import UNSUPPORTED, backing, table

FIELDS = table()


def _printed_fields():
    """The printed values of the four papers' trackers (the register holds those papers; the
    correlation filters of 10_correlation_filters cite their authors' papers and code in their
    param docs)."""
    out = []
    for name in PAPER_TRACKERS:
        cls = trackers.get(name)
        P = getattr(cls, "Params", None)
        if P is None:
            continue
        for f in dataclasses.fields(P):
            if params.has_paper(f) and f.metadata.get("paper") is not params.NOT_PRINTED:
                out.append((name, f.name, f.metadata.get("paper")))
    return out


PRINTED = _printed_fields()


def test_the_walk_found_the_papers_trackers():
    names = {t for t, _, _ in PRINTED}
    assert {"color-hog-ipca", "edge-ray-pf", "kalman-covariance",
            "condensation-mean-shift"} <= names


@pytest.mark.parametrize("tracker,field,value", PRINTED,
                         ids=[f"{t}.{f}" for t, f, _ in PRINTED])
def test_every_printed_value_has_its_passage(tracker, field, value):
    if (tracker, field) in UNSUPPORTED:
        pytest.skip(UNSUPPORTED[(tracker, field)])
    found = backing(tracker, field)
    assert found, f"{tracker}.{field} = {value!r} is recorded as printed: add its passage to " \
                  f"printed=/reading= on the param"
    key, state = found
    q = quotes.quote(key)
    assert state in ("printed", "reading")
    if state == "printed" and isinstance(value, (int, float)) and not isinstance(value, bool) \
            and value not in (0, 1):
        number = f"{value:g}"
        assert re.search(rf"(?<![\d.]){re.escape(number)}(?![\d])", q.original), (
            f"{tracker}.{field} = {number} is not in the passage {key}")


def test_every_entry_resolves_and_keeps_to_one_paper():
    for tracker, fields in FIELDS.items():
        papers = {quotes.quote(key).paper for key, _ in fields.values()}
        assert len(papers) == 1, (tracker, papers)


def test_entries_name_fields_that_exist():
    known = {(t, f) for t, f, _ in PRINTED}
    # the book's manoeuvre variant has the paper tracker's printed fields
    known |= {("kalman-covariance-manoeuvre", f) for t, f, _ in PRINTED
              if t == "kalman-covariance"}
    for tracker, fields in FIELDS.items():
        for field in fields:
            assert (tracker, field) in known, f"{tracker}.{field} is not a printed field"


def test_number_lookup_can_fail():
    # a 0.4 is not a 0.45, a 40 not a 400: the lookup is exact
    q = quotes.quote("lee2012.sigma04").original
    assert re.search(r"(?<![\d.])0\.4(?![\d])", q)
    assert not re.search(r"(?<![\d.])0\.45(?![\d])", q)
    assert not re.search(r"(?<![\d.])4(?![\d])", quotes.quote("lee2012.t40").original)
