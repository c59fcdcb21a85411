"""trackbook._memory: glibc's thresholds are raised once, by creating a tracker, and can be
turned off."""

import os
import platform
import subprocess
import sys

import pytest

import trackbook
from trackbook import _memory

GLIBC = platform.system() == "Linux" and platform.libc_ver()[0] == "glibc"


def _run(code, **env):
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env={**os.environ, **env}, check=True)
    return out.stdout.strip()


def test_import_changes_nothing_and_a_tracker_sets_the_thresholds():
    code = ("import trackbook, trackbook._memory as m; a = 'done' in m._state; "
            "trackbook.trackers.create('color-pf'); print(a, m._state.get('done'))")
    assert _run(code) == f"False {GLIBC}"


def test_opt_out_by_environment():
    code = ("import trackbook, trackbook._memory as m; trackbook.trackers.create('color-pf'); "
            "print(m._state.get('done'))")
    assert _run(code, TRACKBOOK_KEEP_MEMORY="0") == "False"


@pytest.mark.skipif(not GLIBC, reason="mallopt is glibc's")
def test_idempotent_on_glibc():
    trackbook.trackers.create("color-pf")
    assert _memory.keep_freed_memory() is True
    assert _memory.keep_freed_memory() is True
