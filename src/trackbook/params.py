"""Tunable parameters as dataclasses.

Every tracker declares its knobs as a frozen dataclass whose fields are made with
:func:`param`. The metadata (range, step, one-line doc) is what the widgets turn into sliders,
so a new knob shows up in the book's playground without touching the widget code.

Each field also records what the paper printed (``paper=``) and, where the book's default is
not that value, why (``why=``). From these :func:`paper_values` builds the printed method
(``trackers.create(name, preset="paper")``) and :func:`departures` lists the book's departures
(``trackers.departures(name)``): the chapters' departure tables are generated from them, so
they cannot drift from the code.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from ._checks import check_finite_number


class _NotPrinted:
    """Marker for a value the paper does not print (the book had to choose one)."""

    def __repr__(self) -> str:
        return "not printed"

    def __reduce__(self):
        return "NOT_PRINTED"


#: ``paper=NOT_PRINTED``: the paper gives no value; ``why=`` says what the book chose and why.
NOT_PRINTED = _NotPrinted()
#: A knob the paper's method does not have (an addition of the book) is also ``NOT_PRINTED``,
#: with ``paper_value=`` the setting that switches the addition off.
_UNSET = object()


def param(default: Any, lo: float | None = None, hi: float | None = None,
          step: float | None = None, doc: str = "", choices: tuple | None = None, *,
          paper: Any = _UNSET, why: str = "", paper_value: Any = _UNSET):
    """A dataclass field with a default and the metadata widgets need.

    Parameters
    ----------
    default : the book's default.
    lo, hi, step : slider range for the widgets (and the valid range checked on creation).
    doc : one line naming the symbol and the equation it belongs to.
    choices : for string parameters, the allowed values.
    paper : the value the paper prints, or :data:`NOT_PRINTED` when it prints none.
    why : required when ``default != paper`` or the paper prints nothing: one line on why the
        book's default is what it is, and where that was measured.
    paper_value : the setting ``preset="paper"`` uses when ``paper`` is not a usable value
        (for :data:`NOT_PRINTED`, or a knob the paper's method does not have, e.g. ``0`` for
        "off"); defaults to ``paper``, or to ``default`` when the paper prints nothing.
    """
    meta = {"lo": lo, "hi": hi, "step": step, "doc": doc, "choices": choices,
            "paper": paper, "why": why, "paper_value": paper_value}
    if isinstance(default, (list, dict, set)):
        raise TypeError("use tuples for sequence defaults so params stay immutable")
    return dataclasses.field(default=default, metadata=meta)


def validate(params) -> None:
    """Check a params dataclass instance: finite numbers, values in range, valid choices."""
    for f in dataclasses.fields(params):
        value = getattr(params, f.name)
        check_finite_number(value, name=f.name)
        lo, hi = f.metadata.get("lo"), f.metadata.get("hi")
        choices = f.metadata.get("choices")
        if choices is not None and value not in choices:
            raise ValueError(f"parameter {f.name} = {value!r} is not one of {choices}.")
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            if lo is not None and value < lo:
                raise ValueError(f"parameter {f.name} = {value!r} is below its minimum {lo}.")
            if hi is not None and value > hi:
                raise ValueError(f"parameter {f.name} = {value!r} is above its maximum {hi}.")


def make_params(cls, values: dict):
    """Build ``cls(**values)`` with a clear error for unknown names, then validate it."""
    names = [f.name for f in dataclasses.fields(cls)]
    unknown = sorted(set(values) - set(names))
    if unknown:
        raise ValueError(
            f"unknown parameter(s) {unknown} for {cls.__qualname__}; valid names: {names}."
        )
    p = cls(**values)
    validate(p)
    return p


def describe(cls) -> list[dict]:
    """Rows ``{name, default, lo, hi, step, doc, choices, paper, why}`` for tables and widgets."""
    rows = []
    for f in dataclasses.fields(cls):
        rows.append({"name": f.name, "default": f.default, **f.metadata})
    return rows


def has_paper(field: dataclasses.Field) -> bool:
    """Whether the field records the paper's value (every field of every tracker must)."""
    return field.metadata.get("paper", _UNSET) is not _UNSET


def paper_value(field: dataclasses.Field) -> Any:
    """The value ``preset="paper"`` gives this field: the printed value, or the stated setting."""
    m = field.metadata
    if m.get("paper_value", _UNSET) is not _UNSET:
        return m["paper_value"]
    paper = m.get("paper", _UNSET)
    if paper is _UNSET or paper is NOT_PRINTED:
        return field.default
    return paper


def paper_values(cls) -> dict:
    """``{name: value}`` of the printed method, for ``trackers.create(name, preset="paper")``."""
    return {f.name: paper_value(f) for f in dataclasses.fields(cls)}


def is_departure(field: dataclasses.Field) -> bool:
    """The book's default is not the printed value, or the paper prints none."""
    paper = field.metadata.get("paper", _UNSET)
    if paper is _UNSET:
        return False
    return paper is NOT_PRINTED or not _same(field.default, paper_value(field))


def _same(a, b) -> bool:
    """Equal values of the same kind (``True`` is not the number 1 here)."""
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    return bool(a == b)


def departures(cls) -> list[dict]:
    """Rows ``{param, paper, book, why}``: every field whose default is the book's choice."""
    rows = []
    for f in dataclasses.fields(cls):
        if is_departure(f):
            paper = f.metadata["paper"]
            rows.append({"param": f.name,
                         "paper": "not printed" if paper is NOT_PRINTED else paper,
                         "book": f.default, "why": f.metadata.get("why", "")})
    return rows
