"""Tunable parameters as dataclasses.

Every tracker declares its knobs one way: a frozen dataclass (``@dataclasses.dataclass(
frozen=True)``, subclassing another tracker's params to extend them) whose fields are made with
:func:`param` or a helper that returns one (``resampler_param`` ...).
The metadata (allowed range, slider range, step, one-line doc) is what the widgets turn into
sliders, so a new knob shows up in the book's playground without touching the widget code.

Each field also records the printed value (``paper=``), where the book's default is not that
value, why (``why=``), and the passage of the quote register behind a printed value: ``printed=``
its key when the passage states the value, ``reading=`` when the value is the book's reading of
an ambiguous or elided passage (:func:`provenance`; a value with no passage is
``NOT_PRINTED``). From these :func:`paper_values` builds the printed method
(``trackers.create(name, preset="paper")``) and :func:`departures` lists the book's departures
(``trackers.departures(name)``): the chapters' departure tables are generated from them, so
they cannot drift from the code.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
from numbers import Integral, Real
from typing import Any

import numpy as np

from ._checks import check_finite_number


class _NotPrinted:
    """Marker for a value with no printed source (the book had to choose one)."""

    def __repr__(self) -> str:
        return "not printed"

    def __reduce__(self):
        return "NOT_PRINTED"


#: ``paper=NOT_PRINTED``: no value is printed; ``why=`` says what the book chose and why.
NOT_PRINTED = _NotPrinted()
#: A knob missing from the printed method (an addition of the book) is also ``NOT_PRINTED``,
#: with ``paper_value=`` the setting that switches the addition off.
_UNSET = object()


def param(default: Any, lo: float | None = None, hi: float | None = None,
          step: float | None = None, doc: str = "", choices=None, *,
          paper: Any = _UNSET, why: str = "", paper_value: Any = _UNSET,
          slider: tuple | None = None, printed: str | None = None, reading: str | None = None):
    """A dataclass field with a default and the metadata widgets need.

    Parameters
    ----------
    default : the book's default.
    lo, hi : the range a value may take (checked by :func:`parse` on creation; None = open).
    step : the widgets' slider step.
    doc : one line naming the symbol and the equation it belongs to.
    choices : for string parameters, the allowed values: a tuple, or a sequence read each
        time a value is checked (a live view of a registry that grows, e.g.
        ``filters.particle.RESAMPLER_NAMES``), or a function returning them.
    slider : ``(a, b)``, the range the widgets' sliders span when it is narrower than the
        allowed range (e.g. up to 1000 particles on a slider, any number by keyword);
        defaults to ``(lo, hi)``.
    paper : the printed value, or :data:`NOT_PRINTED` when none is printed.
    why : required when ``default != paper`` or nothing is printed: one line on why the
        book's default is what it is, and where that was measured.
    paper_value : the setting ``preset="paper"`` uses when ``paper`` is not a usable value
        (for :data:`NOT_PRINTED`, or a knob missing from the printed method, e.g. ``0`` for
        "off"); defaults to ``paper``, or to ``default`` when nothing is printed.
    printed : the key of the quote (:mod:`trackbook.quotes`) that states the ``paper`` value.
    reading : the key of the quote whose ambiguous or elided passage the ``paper`` value
        reads (at most one of ``printed`` and ``reading``).
    """
    if printed is not None and reading is not None:
        raise ValueError(f"printed={printed!r} and reading={reading!r}: a value is either "
                         "stated by its passage or read from it; give one key.")
    if slider is not None:
        if len(slider) != 2 or not slider[0] <= slider[1]:
            raise ValueError(f"slider={slider!r} must be a pair (a, b) with a <= b.")
        if (lo is not None and slider[0] < lo) or (hi is not None and slider[1] > hi):
            raise ValueError(f"slider={slider!r} must lie within the allowed range {lo}..{hi}.")
    meta = {"lo": lo, "hi": hi, "step": step, "doc": doc, "choices": choices,
            "paper": paper, "why": why, "paper_value": paper_value,
            "slider": tuple(slider) if slider is not None else (lo, hi),
            "quote": printed if printed is not None else reading,
            "quote_state": "printed" if printed is not None else
            "reading" if reading is not None else None}
    if isinstance(default, (list, dict, set)):
        raise TypeError("use tuples for sequence defaults so params stay immutable")
    return dataclasses.field(default=default, metadata=meta)


def restate(cls, name: str, *, paper: Any = _UNSET, why: str = "",
            paper_value: Any = _UNSET, printed: str | None = None,
            reading: str | None = None):
    """The field ``name`` of the params dataclass ``cls`` again, with a new provenance.

    Default, range, slider, step, doc and choices stay those of ``cls``; ``paper``, ``why``,
    ``paper_value``, ``printed`` and ``reading`` are given anew (as for :func:`param`). A
    subclass uses it when a value its base class can only read is printed for the subclass's
    tracker: Lee et al. (2012) print N = 100 for their proposed tracker [quote: lee2012.n100],
    which extends the class of a baseline whose settings they do not print
    [quote: lee2012.baselines].

    Examples
    --------
    >>> import dataclasses
    >>> @dataclasses.dataclass(frozen=True)
    ... class Base:
    ...     n: int = param(100, 1, 1000, 1, "N", reading="lee2012.n100", paper=100)
    >>> @dataclasses.dataclass(frozen=True)
    ... class Proposed(Base):
    ...     n: int = restate(Base, "n", printed="lee2012.n100", paper=100)
    >>> [provenance(f) for f in dataclasses.fields(Proposed)]
    [('printed', 'lee2012.n100')]
    """
    f = _field(cls, name)
    m = f.metadata
    slider = m["slider"] if tuple(m["slider"]) != (m["lo"], m["hi"]) else None
    return param(f.default, m["lo"], m["hi"], m["step"], m["doc"], m["choices"],
                 paper=paper, why=why, paper_value=paper_value, slider=slider,
                 printed=printed, reading=reading)


def provenance(field: dataclasses.Field) -> tuple[str, str | None]:
    """``(state, quote key)`` of the field's printed value: ``("printed", key)`` (its passage
    states it), ``("reading", key)`` (the book's reading of its passage) or
    ``("not printed", None)`` (no passage backs it)."""
    key = field.metadata.get("quote")
    return (field.metadata["quote_state"], key) if key else ("not printed", None)


def choices_of(field: dataclasses.Field):
    """The allowed values of a field now, as a tuple (a live sequence is read, a ``choices``
    function called), or None."""
    c = field.metadata.get("choices")
    if c is None:
        return None
    return tuple(c()) if callable(c) else tuple(c)


def slider_of(field: dataclasses.Field) -> tuple:
    """``(a, b)``: the range the widgets' slider spans (within the allowed ``lo..hi``)."""
    m = field.metadata
    return tuple(m.get("slider") or (m.get("lo"), m.get("hi")))


_TRUE = ("true", "yes", "1", "on")
_FALSE = ("false", "no", "0", "off")


def _kind(field: dataclasses.Field):
    """The Python type of a field: its annotation, else the type of its default."""
    t = field.type
    if isinstance(t, str):
        t = {"int": int, "float": float, "bool": bool, "str": str}.get(t.split("|")[0].strip(),
                                                                        None)
    if t in (int, float, bool, str):
        return t
    if isinstance(field.default, tuple):
        return tuple
    return type(field.default)


def near_names(name: str, names) -> list[str]:
    """The names a mistyped ``name`` may have meant, best first: close spellings
    (:func:`difflib.get_close_matches`), then names sharing a run of its ``_``-separated words
    (``sigma`` -> ``kernel_sigma``, ``kernel_sigma_x`` -> ``kernel_sigma``)."""
    names = [str(n) for n in names]
    out = difflib.get_close_matches(name, names, n=3)
    words = [w for w in name.lower().split("_") if w]

    def inside(a, b):       # a's words a contiguous run of b's
        return bool(a) and any(b[i:i + len(a)] == a for i in range(len(b) - len(a) + 1))
    for n in names:
        other = [w for w in n.lower().split("_") if w]
        if n not in out and (inside(words, other) or inside(other, words)):
            out.append(n)
    return out[:3]


def _did_you_mean(name: str, names) -> str:
    near = near_names(name, names)
    if not near:
        return ""
    return " (did you mean " + " or ".join(repr(n) for n in near) + "?)"


def _field(cls, name: str) -> dataclasses.Field:
    fields = {f.name: f for f in dataclasses.fields(cls)}
    if name not in fields:
        names = list(fields)
        hint = _did_you_mean(str(name), names)
        raise ValueError(f"unknown parameter {name!r}{hint} for {cls.__qualname__}; "
                         f"valid names: {', '.join(names)}.")
    return fields[name]


def _number(name: str, value, kind):
    """An int or float from a Python/numpy number or a string, refusing bools and NaN/inf."""
    what = "an integer" if kind is int else "a number"
    if isinstance(value, str):
        text = value.strip()
        try:
            value = int(text) if kind is int else float(text)
        except ValueError:
            if kind is int:
                try:
                    f = float(text)
                except ValueError:
                    f = None
                if f is not None and math.isfinite(f):
                    value = f     # "50.5": fall through to the whole-number check below
                else:
                    raise ValueError(
                        f"parameter {name} = {text!r} is not {what}; pass e.g. "
                        f"{name}=100.") from None
            else:
                raise ValueError(f"parameter {name} = {text!r} is not {what}; pass a finite "
                                 f"decimal number, e.g. {name}=0.5.") from None
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (Integral, Real)):
        raise ValueError(f"parameter {name} = {value!r} ({type(value).__name__}) is not {what}; "
                         f"pass {what}" + (" (True/False are not numbers here)."
                                           if isinstance(value, (bool, np.bool_)) else "."))
    f = float(value)
    if not math.isfinite(f):
        raise ValueError(f"parameter {name} = {value!r} is not finite; pass a real number.")
    if kind is int:
        if isinstance(value, Integral):
            return int(value)
        if f != int(f):
            raise ValueError(f"parameter {name} = {value!r} is not a whole number; pass an "
                             f"integer such as {int(f)}.")
        return int(f)
    return f


def _bool(name: str, value):
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (Integral,)) and int(value) in (0, 1):
        return bool(int(value))
    if isinstance(value, str) and value.strip().lower() in _TRUE + _FALSE:
        return value.strip().lower() in _TRUE
    raise ValueError(f"parameter {name} = {value!r} is not a yes/no value; pass True or False "
                     "(on the command line: true/false, yes/no or 1/0).")


def _tuple(name: str, value, default: tuple):
    if isinstance(value, str):
        text = value.strip().strip("()[]")
        value = tuple(v for v in (t.strip() for t in text.split(",")) if v)
    if not isinstance(value, (tuple, list, np.ndarray)):
        raise ValueError(f"parameter {name} = {value!r} is not a tuple; pass "
                         f"{len(default)} values like {default!r}.")
    value = tuple(value)
    if default and len(value) != len(default):
        raise ValueError(f"parameter {name} = {value!r} has {len(value)} values; it needs "
                         f"{len(default)}, like {default!r}.")
    kinds = [int if isinstance(d, Integral) and not isinstance(d, bool) else float
             for d in default] or [float] * len(value)
    return tuple(_number(name, v, k) for v, k in zip(value, kinds))


def parse(cls, name: str, value):
    """Convert ``value`` for the field ``name`` of the params dataclass ``cls``, or raise.

    The one parser behind ``trackers.create(name, **params)`` and the CLI's
    ``--param NAME=VALUE``: ints and floats accept Python and numpy numbers (and, from the
    command line, their decimal spelling); bools are not numbers; a float is not an int unless
    whole; NaN and infinity are refused however spelled; ``true/false/yes/no/1/0`` for bools;
    tuples from ``(a, b)`` or ``a,b``; the range ``lo..hi`` and the choices are checked for
    every kind of number. Returns the converted value; raises ``ValueError`` naming the
    parameter and the fix.
    """
    f = _field(cls, name)
    kind = _kind(f)
    meta = f.metadata
    if value is None:
        raise ValueError(f"parameter {name} = None; pass a value like its default "
                         f"{f.default!r} (or leave it out for the default).")
    if kind is bool:
        out = _bool(name, value)
    elif kind in (int, float):
        out = _number(name, value, kind)
    elif kind is tuple:
        out = _tuple(name, value, f.default)
    elif kind is str:
        if not isinstance(value, str):
            raise ValueError(f"parameter {name} = {value!r} is not a string; pass one of "
                             f"{choices_of(f) or 'the documented values'}.")
        out = value.strip()
    else:
        out = value
    choices = choices_of(f)
    if choices is not None and out not in choices:
        near = difflib.get_close_matches(str(out), [str(c) for c in choices], n=1)
        hint = f" (did you mean {near[0]!r}?)" if near else ""
        raise ValueError(f"parameter {name} = {out!r} is not one of "
                         f"{', '.join(map(str, choices))}{hint}.")
    lo, hi = meta.get("lo"), meta.get("hi")
    for v in (out if isinstance(out, tuple) else (out,)):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            continue
        if lo is not None and v < lo:
            raise ValueError(f"parameter {name} = {value!r} is below its minimum {lo}; "
                             f"pass a value in {lo}..{hi}.")
        if hi is not None and v > hi:
            raise ValueError(f"parameter {name} = {value!r} is above its maximum {hi}; "
                             f"pass a value in {lo}..{hi}.")
    return out


def validate(params) -> None:
    """Check a params dataclass instance: every field as :func:`parse` would accept it."""
    for f in dataclasses.fields(params):
        value = getattr(params, f.name)
        check_finite_number(value, name=f.name)
        parse(type(params), f.name, value)


def make_params(cls, values: dict):
    """Build ``cls(**values)`` with every value through :func:`parse`, then validate it."""
    names = [f.name for f in dataclasses.fields(cls)]
    unknown = sorted(set(values) - set(names))
    if len(unknown) == 1:
        _field(cls, unknown[0])         # one unknown name: the parser's own message
    if unknown:
        hints = [repr(u) + _did_you_mean(str(u), names) for u in unknown]
        raise ValueError(
            f"unknown parameter(s) {', '.join(hints)} for {cls.__qualname__}; "
            f"valid names: {names}."
        )
    p = cls(**{k: parse(cls, k, v) for k, v in values.items()})
    validate(p)
    return p


def describe(cls) -> list[dict]:
    """Rows ``{name, default, lo, hi, step, slider, doc, choices, paper, why, paper_value,
    quote, quote_state}`` for
    tables and widgets: ``choices`` as they are now, and ``"not printed"`` where no value is
    printed (or where no ``paper_value`` is stated: ``preset="paper"`` then uses the
    one :func:`paper_value` gives)."""
    rows = []
    for f in dataclasses.fields(cls):
        m = dict(f.metadata)
        m["choices"] = choices_of(f)
        m["paper_value"] = paper_value(f) if has_paper(f) else "not printed"
        if m.get("paper", _UNSET) is _UNSET or m.get("paper") is NOT_PRINTED:
            m["paper"] = "not printed"
        rows.append({"name": f.name, "default": f.default, **m})
    return rows


def has_paper(field: dataclasses.Field) -> bool:
    """Whether the field records its printed value or NOT_PRINTED (every field of every
    tracker must)."""
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
    """The book's default is not the printed value, or none is printed."""
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
