"""trackbook._memory: glibc's thresholds are raised at named places (the run loop, and
``trackbook.tune_memory()``), never by importing trackbook or creating a tracker, and
``TRACKBOOK_KEEP_MEMORY=0`` turns them off."""

import os
import platform
import subprocess
import sys

import pytest

import trackbook
from trackbook import _memory

GLIBC = platform.system() == "Linux" and platform.libc_ver()[0] == "glibc"
#: what one tuning asks of mallopt, from glibc's <malloc.h> (M_MMAP_THRESHOLD -3,
#: M_TRIM_THRESHOLD -1) and the thresholds the module documents (16 MB, 64 MB)
TUNED = [(-3, 16 * 2**20), (-1, 64 * 2**20)]


@pytest.fixture
def calls(monkeypatch):
    """A fresh process state and a recording mallopt in place of glibc's."""
    seen = []

    def mallopt(param, value):
        seen.append((param, value))
        return 1
    monkeypatch.setattr(_memory, "_state", {})
    monkeypatch.setattr(_memory, "libc_mallopt", lambda: mallopt)
    monkeypatch.delenv(_memory.ENV, raising=False)
    return seen


def test_creating_a_tracker_leaves_malloc_alone(calls):
    trackbook.trackers.create("color-pf")
    trackbook.trackers.create("hog-pf", seed=3)
    assert calls == [] and "done" not in _memory._state


def test_evaluate_tunes_malloc_once(calls):
    trackbook.evaluate("mean-shift", "red-cube", max_frames=3)
    trackbook.evaluate("mean-shift", "red-cube", max_frames=3)
    assert calls == TUNED


def test_tune_memory_is_the_public_switch(calls):
    assert trackbook.tune_memory() is True and calls == TUNED


def test_the_environment_variable_turns_it_off(calls, monkeypatch):
    monkeypatch.setenv("TRACKBOOK_KEEP_MEMORY", "0")
    trackbook.evaluate("mean-shift", "red-cube", max_frames=3)
    assert calls == [] and trackbook.tune_memory() is False


def test_import_and_a_tracker_change_nothing_in_a_fresh_process():
    code = ("import trackbook, trackbook._memory as m; trackbook.trackers.create('color-pf'); "
            "a = 'done' in m._state; trackbook.evaluate('mean-shift', 'red-cube', "
            "max_frames=3); print(a, m._state.get('done'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=os.environ, check=True)
    assert out.stdout.strip() == f"False {GLIBC}"
