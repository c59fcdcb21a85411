"""Tunable parameters as dataclasses.

Every tracker declares its knobs as a frozen dataclass whose fields are made with
:func:`param`. The metadata (range, step, one-line doc) is what the widgets turn into sliders,
so a new knob shows up in the book's playground without touching the widget code.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from ._checks import check_finite_number


def param(default: Any, lo: float | None = None, hi: float | None = None,
          step: float | None = None, doc: str = "", choices: tuple | None = None):
    """A dataclass field with a default and the metadata widgets need.

    Parameters
    ----------
    default : the paper's value.
    lo, hi, step : slider range for the widgets (and the valid range checked on creation).
    doc : one line naming the symbol and the equation it belongs to.
    choices : for string parameters, the allowed values.
    """
    meta = {"lo": lo, "hi": hi, "step": step, "doc": doc, "choices": choices}
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
    """Rows ``{name, default, lo, hi, step, doc, choices}`` for tables and widgets."""
    rows = []
    for f in dataclasses.fields(cls):
        rows.append({"name": f.name, "default": f.default, **f.metadata})
    return rows
