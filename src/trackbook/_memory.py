"""Keep freed memory in the process, so per-frame NumPy temporaries do not page-fault.

A particle tracker allocates the same few arrays every frame: 100 patches of 16 x 24 px are
38,400 values, about 300 kB per float64 temporary, and a frame of HOG or HSI features makes
a dozen of them. glibc's ``malloc`` serves blocks over 128 kB with ``mmap`` and hands them
back to the kernel on ``free`` (and trims the heap once more than twice that is free at its
top), so every frame the same memory is mapped again and touched page by page: those page
faults can take a large share of a particle tracker's time (compare ``trackbook bench`` on
MotorRolling with and without ``TRACKBOOK_KEEP_MEMORY=0``: same frames, same boxes).

:func:`keep_freed_memory` raises the two thresholds with ``mallopt`` so that arrays under
16 MB come from the heap and up to 64 MB of freed heap stays mapped for the next frame. The
cost is memory the process keeps rather than returns (at most the 64 MB). It is applied at
named places only: by the run loop before it makes its trackers
(:class:`trackbook.evaluation.runner.Run`, so :func:`trackbook.evaluate`, ``trackbook
track``, ``trackbook bench`` and the playground), and by whoever calls
:func:`trackbook.tune_memory` (this function) to run trackers by hand. Importing trackbook or
creating a tracker changes nothing.

It does nothing outside glibc (macOS, Windows, musl) or when the environment variable
``TRACKBOOK_KEEP_MEMORY=0`` is set.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os

#: ``mallopt`` parameters of glibc's ``<malloc.h>``.
_M_TRIM_THRESHOLD = -1
_M_MMAP_THRESHOLD = -3

#: Blocks smaller than this come from the heap, not a fresh ``mmap``.
MMAP_THRESHOLD = 16 * 2**20
#: Free memory at the top of the heap kept mapped rather than returned to the kernel.
TRIM_THRESHOLD = 64 * 2**20

#: the environment variable that turns the tuning off (``0``)
ENV = "TRACKBOOK_KEEP_MEMORY"

_state: dict = {}


def libc_mallopt():
    """glibc's ``mallopt(param, value)`` as a callable, or None outside glibc."""
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        mallopt = libc.mallopt
    except (OSError, AttributeError):       # not glibc: nothing to tune
        return None
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt.restype = ctypes.c_int
    return mallopt


def keep_freed_memory() -> bool:
    """Set glibc's mmap and trim thresholds once per process; return whether they are set.

    Public as :func:`trackbook.tune_memory`. Idempotent and silent: the first call decides,
    later calls return the same answer. ``TRACKBOOK_KEEP_MEMORY=0`` leaves ``malloc`` alone.
    """
    if "done" in _state:
        return _state["done"]
    ok = False
    if os.environ.get(ENV, "1") != "0":
        mallopt = libc_mallopt()
        if mallopt is not None:
            # mallopt returns 1 on success, 0 on error
            ok = bool(mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and \
                bool(mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD))
    _state["done"] = ok
    return ok
