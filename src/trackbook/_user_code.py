"""Whose code raised an exception: trackbook's, or the user's (a ``--import`` file, a plugin).

The command line reports an error raised in a user's own tracker as theirs, with their file
and line, instead of as a usage error or a bug in trackbook. "User code" is the deepest frame
of the traceback whose file is neither in the trackbook package nor in the Python
installation's library folders (the standard library and site-packages, from
:mod:`sysconfig`, and the other site-packages folders :mod:`site` names). Benchmark worker processes describe the exception where it happened
(:func:`portable`), since a traceback does not survive the trip back to the parent.
"""

from __future__ import annotations

import contextlib
import os
import site
import sysconfig
import traceback
from pathlib import Path

_PACKAGE = str(Path(__file__).resolve().parent)


def _library_dirs() -> list[str]:
    paths = sysconfig.get_paths()
    dirs = [paths[k] for k in ("stdlib", "platstdlib", "purelib", "platlib") if paths.get(k)]
    # packages installed elsewhere on the path Python searches (pip install --user, a
    # distribution's dist-packages) are libraries too, not the user's own code
    with contextlib.suppress(AttributeError):   # site without these (an embedded Python)
        dirs += [*site.getsitepackages(), site.getusersitepackages()]
    return sorted({os.path.realpath(d) for d in dirs})


_LIBRARY = _library_dirs()


def _inside(path: str, folder: str) -> bool:
    return path == folder or path.startswith(folder.rstrip(os.sep) + os.sep)


def is_user_file(filename: str) -> bool:
    """True for a real file outside the trackbook package and the Python library folders."""
    if not filename or filename.startswith("<"):     # <frozen ...>, <string>
        return False
    path = os.path.realpath(filename)
    return not (_inside(path, _PACKAGE) or any(_inside(path, d) for d in _LIBRARY))


def user_frame(exc: BaseException):
    """``(exception, FrameSummary)`` of the deepest user frame in ``exc``'s traceback, looking
    through its causes (a wrapper raised by trackbook around the user's error); else None."""
    seen = set()
    e = exc
    while e is not None and id(e) not in seen:
        seen.add(id(e))
        frames = [f for f in traceback.extract_tb(e.__traceback__) if is_user_file(f.filename)]
        if frames:
            return e, frames[-1]
        e = e.__cause__ or e.__context__
    return None


class UserCodeError(Exception):
    """An exception raised inside a user's own code, described in one line.

    ``where`` is ``file:line, in function``; ``kind`` and ``text`` the exception's type and
    message; ``details`` the whole formatted traceback (printed by ``--traceback``).
    """

    def __init__(self, where: str, kind: str, text: str, details: str = ""):
        super().__init__(where, kind, text, details)
        self.where, self.kind, self.text, self.details = where, kind, text, details

    def __str__(self) -> str:
        return f"error in your code ({self.where}): {self.kind}: {self.text}"


def describe(exc: BaseException) -> UserCodeError | None:
    """``exc`` as a :class:`UserCodeError` when a user frame raised it, else None."""
    if isinstance(exc, UserCodeError):
        return exc
    found = user_frame(exc)
    if found is None:
        return None
    e, f = found
    text = " ".join(str(e).split())
    if isinstance(e, KeyError) and e.args:
        text = repr(e.args[0])           # str(KeyError) is the key alone; say it is a key
    if isinstance(e, SystemExit):
        text = (f"sys.exit({e.code!r}) was called while trackbook loaded or ran your code; "
                "raise an exception instead")
    details = "".join(traceback.format_exception(type(exc), exc, exc.__traceback__))
    return UserCodeError(f"{os.path.basename(f.filename)}:{f.lineno}, in {f.name}",
                         type(e).__name__, text, details)
