"""Which passage backs each value a tracker's ``paper=`` records, and whether it is printed.

A value of the paper preset is in one of three states (:data:`STATES`, :func:`state`):
``"printed"`` (the passage states it, quoted), ``"reading"`` (the passage is ambiguous or
elided and the value is the book's reading of it, quoted) or ``"not printed"`` (no passage: the
field records ``paper=NOT_PRINTED`` and the preset uses the book's stated setting).

The passage is declared on the param itself, ``param(..., printed="lee2012.t40", paper=40)``
or ``reading=`` (:func:`trackbook.params.provenance`); this module reads the declarations of
the registered trackers. ``UNSUPPORTED`` lists the ``paper=`` values that no passage backs,
with the reason; the params that record them are to be corrected.
"""

from __future__ import annotations

import dataclasses

from .. import params as _params
from .. import trackers as _trackers

#: ``(tracker, field)``: ``paper=`` values that no passage backs.
UNSUPPORTED: dict[tuple[str, str], str] = {}

#: The three honest states of a value of the paper preset.
STATES = ("printed", "reading", "not printed")


def _field(tracker: str, field: str) -> dataclasses.Field | None:
    P = getattr(_trackers.get(tracker), "Params", None)
    if not dataclasses.is_dataclass(P):
        return None
    return next((f for f in dataclasses.fields(P) if f.name == field), None)


def state(tracker: str, field: str) -> tuple[str, str | None]:
    """``(state, quote key)`` of ``tracker``'s ``field`` in the paper preset: ``("printed",
    key)``, ``("reading", key)`` or ``("not printed", None)`` (see :data:`STATES`)."""
    f = _field(tracker, field)
    return ("not printed", None) if f is None else _params.provenance(f)


def backing(tracker: str, field: str) -> tuple[str, str] | None:
    """``(quote key, "printed" | "reading")`` behind ``tracker``'s ``field``, or None."""
    st, key = state(tracker, field)
    return None if key is None else (key, st)


def table() -> dict[str, dict[str, tuple[str, str]]]:
    """``{tracker: {field: (quote key, state)}}`` of every registered tracker's backed
    fields (trackers with none are left out; a re-detecting variant, ``<name>-redetect``, has
    the fields of ``<name>`` and is not listed again)."""
    out = {}
    for name in _trackers.available():
        if name.endswith("-redetect"):
            continue
        P = getattr(_trackers.get(name), "Params", None)
        if not dataclasses.is_dataclass(P):
            continue
        found = {f.name: backing(name, f.name) for f in dataclasses.fields(P)}
        found = {k: v for k, v in found.items() if v is not None}
        if found:
            out[name] = found
    return out
