"""The committed results the book reads: ``trackbook.results.load(name)``.

Each experiment of :mod:`trackbook.evaluation.experiments` (``lee2012_real``,
``lee2012_learning``, ``kim2016_edges``, ``claims``, ``real`` ...) writes one file here,
``<name>.json``, through the benchmark: one row per (configuration, clip, seed) with the
configuration's ``label``, ``tracker``, ``preset`` and ``params``, the ``seed`` and every score
at full precision. The files ship inside the package, so ``load`` works the same in the
book's build, in exported notebooks and in a student's session, wherever the working folder
is. Regenerate a file with ``python -m trackbook.evaluation.experiments run NAME``.

This module reads files only; it imports nothing from the rest of the library.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

#: The folder of the committed result files (package data).
HERE = Path(__file__).resolve().parent


class Table:
    """The rows of one committed result, with a few helpers (the book has no pandas).

    Iterating gives the rows (dicts, all with the same keys); missing numbers are ``nan``. ``meta`` holds the file's
    description, command, clips, seeds and plugins.
    """

    def __init__(self, rows, meta=None):
        self.rows = list(rows)
        self.meta = dict(meta or {})

    def __iter__(self):
        return iter(self.rows)

    def __len__(self) -> int:
        return len(self.rows)

    def __getitem__(self, i):
        return self.rows[i]

    def __repr__(self) -> str:
        return f"Table({self.meta.get('name', '?')!r}, {len(self.rows)} rows)"

    def where(self, **equal) -> "Table":
        """The rows whose fields equal the given values (a list/tuple/set value: any of them)."""
        def ok(r):
            return all(r.get(k) in v if isinstance(v, (list, tuple, set, frozenset))
                       else r.get(k) == v for k, v in equal.items())
        return Table([r for r in self.rows if ok(r)], self.meta)

    def column(self, key: str) -> np.ndarray:
        """One field of every row, as an array."""
        return np.asarray([r.get(key) for r in self.rows])

    def unique(self, key: str) -> list:
        """The distinct values of a field, in order of first appearance."""
        return list(dict.fromkeys(r.get(key) for r in self.rows))

    def mean(self, value: str, by=("label",)) -> dict:
        """Mean of ``value`` per group of ``by`` fields (a 1-tuple key gives plain keys)."""
        by = (by,) if isinstance(by, str) else tuple(by)
        groups: dict = {}
        for r in self.rows:
            k = tuple(r.get(b) for b in by)
            groups.setdefault(k if len(by) > 1 else k[0], []).append(r[value])
        return {k: float(np.mean(v)) for k, v in groups.items()}


def available() -> list[str]:
    """Names of the committed results."""
    return sorted(p.stem for p in HERE.glob("*.json"))


def path(name: str) -> Path:
    """The file of the committed result ``name``.

    Raises
    ------
    FileNotFoundError
        Naming the result, the ones available and the command that makes it.
    """
    if not isinstance(name, str) or not name or Path(name).name != name:
        raise ValueError(f"result name {name!r}: give a name such as 'claims' "
                         f"(available: {', '.join(available())}).")
    p = HERE / f"{Path(name).stem}.json"
    if not p.is_file():
        raise FileNotFoundError(
            f"no committed result {name!r} in {HERE} (available: {', '.join(available())}); "
            f"make it with: python -m trackbook.evaluation.experiments run {name}")
    return p


def read(file) -> Table:
    """A result file (``<name>.json``, as the experiments write it) as a :class:`Table`."""
    data = json.loads(Path(file).read_text())
    raw = data.pop("rows")
    # every row gets every column (a tracker reports only its own extras): missing is nan
    cols = list(dict.fromkeys(k for r in raw for k in r))
    rows = [{k: (float("nan") if r.get(k) is None else r[k]) for k in cols} for r in raw]
    return Table(rows, data)


def load(name: str) -> Table:
    """The committed result ``name`` (see :func:`available`) as a :class:`Table` of rows."""
    return read(path(name))
