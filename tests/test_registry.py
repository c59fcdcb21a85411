"""The one tracker registry: ``available`` names everything ``create`` accepts, the seed is a
keyword, and a user's module that raises or calls ``sys.exit`` while loaded is reported as a
``PluginError`` naming their file and line."""

from __future__ import annotations

import importlib
import sys
import textwrap
import warnings

import pytest

from trackbook import trackers
from trackbook.evaluation.experiments import Experiment
from trackbook.trackers import plugins, registry
from trackbook.trackers.plugins import PluginError
from trackbook.trackers.reference import REFERENCE

# The library's own trackers by paper, the papers in the book's order (one chapter after
# another): written out here, not read from the registry under test.
BOOK_GROUPS = [["color-pf", "color-pf-redetect", "color-hog-pf",               # lee2012
                "color-hog-pf-redetect", "color-hog-ipca", "color-hog-ipca-redetect"],
               ["hsi-color-pf", "hsi-color-pf-redetect", "hog-pf", "hog-pf-redetect",  # kim2016
                "edge-ray-pf", "edge-ray-pf-redetect"],
               ["covariance", "covariance-redetect", "kalman-covariance",       # lee2015
                "kalman-covariance-redetect", "kalman-covariance-manoeuvre",
                "kalman-covariance-manoeuvre-redetect"],
               ["condensation", "condensation-redetect", "mean-shift",          # cho2005
                "mean-shift-redetect", "condensation-mean-shift",
                "condensation-mean-shift-redetect"],
               ["camshift", "camshift-redetect"],                               # bradski1998
               ["mosse", "mosse-redetect", "kcf", "kcf-redetect"],              # correlation
               ["dsst", "dsst-redetect"],                                       # danelljan2014
               ["staple", "staple-redetect"],                                   # bertinetto2016
               ["bacf", "bacf-redetect"],                                       # kianigaloogahi2017
               ["median-flow", "median-flow-redetect"]]                         # kalal2010
BOOK_ORDER = [n for g in BOOK_GROUPS for n in g]


# -- available() ------------------------------------------------------------------------------

def test_available_names_everything_create_accepts_in_the_books_order():
    names = trackers.available()
    own = [n for n in names if trackers.get(n).__module__.startswith("trackbook.")]
    assert sorted(own) == sorted(BOOK_ORDER + ["opencv-mil"])
    group = {n: k for k, g in enumerate(BOOK_GROUPS) for n in g}
    ranks = [group[n] for n in own[:-1]]
    assert ranks == sorted(ranks)                    # paper after paper, as the book goes
    assert names[-1] == "opencv-mil"                 # the reference row comes last
    assert len(names) == len(set(names))
    for n in names:                                  # each name is one create() accepts
        assert isinstance(trackers.get(n), type)
    assert "opencv-mil" in names                     # what the README creates
    assert isinstance(trackers.create("opencv-mil", seed=0), trackers.Tracker)


def test_available_reference_false_is_the_librarys_own():
    own = trackers.available(reference=False)
    assert "opencv-mil" not in own
    assert own == [n for n in trackers.available() if n not in REFERENCE]


def test_experiment_grid_runs_mil_once():
    """The grid takes the library's trackers and adds MIL itself when asked: MIL in
    available() must not make it appear twice (nor at all without ``reference``)."""
    with_ref = [c.tracker for c in Experiment("x", "d", reference=True).grid()]
    assert with_ref.count("opencv-mil") == 1
    without = [c.tracker for c in Experiment("x", "d").grid()]
    assert "opencv-mil" not in without
    assert set(BOOK_ORDER) <= set(without)


def test_public_api_is_one_module():
    for name in ("available", "create", "get", "register", "departures", "PRESETS"):
        assert getattr(trackers, name) is getattr(registry, name)
    assert trackers.plugins is plugins
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("trackbook.trackers.factory")


def test_a_tracker_may_not_take_the_references_name(clean_registry):
    class Fake(trackers.Tracker):
        name = "opencv-mil"
    with pytest.raises(ValueError, match="reference"):
        trackers.register(Fake)


# -- the seed is a keyword --------------------------------------------------------------------

def test_create_refuses_a_positional_seed():
    with pytest.raises(TypeError) as e:
        trackers.create("color-pf", 50)
    assert "create('color-pf', seed=50)" in str(e.value)
    assert trackers.create("color-pf", seed=50).seed == 50


def test_tracker_refuses_a_positional_seed():
    cls = trackers.get("mean-shift")
    with pytest.raises(TypeError, match=r"seed=7"):
        cls(7)
    assert cls(seed=7).seed == 7
    with pytest.raises(TypeError, match=r"OpenCVMIL\(seed=3\)"):
        REFERENCE["opencv-mil"](3)


def test_multi_tracker_refuses_a_positional_seed():
    with pytest.raises(TypeError) as e:
        trackers.MultiTracker("mean-shift", 5)
    assert "MultiTracker('mean-shift', seed=5)" in str(e.value)
    assert trackers.MultiTracker("mean-shift", seed=5).seed == 5


# -- user modules that fail while loaded --------------------------------------------------------

def _line_of(text: str, needle: str) -> int:
    return next(i for i, ln in enumerate(text.splitlines(), 1) if needle in ln)


def test_a_file_calling_sys_exit_is_a_plugin_error_with_file_and_line(tmp_path, clean_registry):
    src = textwrap.dedent("""\
        import sys

        def main():
            sys.exit(3)

        main()
    """)
    f = tmp_path / "exits.py"
    f.write_text(src)
    with pytest.raises(PluginError) as e:
        plugins.load(str(f))
    msg = str(e.value)
    assert f"{f}, line {_line_of(src, 'sys.exit(3)')}" in msg
    assert "sys.exit(3)" in msg
    assert isinstance(e.value.__cause__, SystemExit)
    assert isinstance(e.value, RuntimeError)
    assert not any(k.startswith("trackbook_user_exits") for k in sys.modules)


def test_a_file_raising_names_the_deepest_line_in_it(tmp_path, clean_registry):
    src = "x = 1\n\ndef f():\n    return {}['missing']\n\nf()\n"
    f = tmp_path / "raises.py"
    f.write_text(src)
    with pytest.raises(PluginError) as e:
        plugins.load(str(f))
    assert f"{f}, line 4: KeyError" in str(e.value)
    assert isinstance(e.value.__cause__, KeyError)


def test_a_syntax_error_names_file_and_line(tmp_path, clean_registry):
    f = tmp_path / "bad_syntax.py"
    f.write_text("x = 1\ny = (\n")
    with pytest.raises(PluginError, match=r"bad_syntax\.py, line 2"):
        plugins.load(str(f))


def test_a_dotted_module_exiting_in_a_file_it_imports_names_that_file(tmp_path, clean_registry,
                                                                monkeypatch):
    pkg = tmp_path / "exiting_pkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "gpu_setup.py").write_text("import sys\n\n\ndef setup():\n    sys.exit('no GPU')\n")
    (pkg / "trk.py").write_text("from exiting_pkg.gpu_setup import setup\nsetup()\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        with pytest.raises(PluginError) as e:
            plugins.load("exiting_pkg.trk")
        assert f"{pkg / 'gpu_setup.py'}, line 5" in str(e.value)
        assert isinstance(e.value.__cause__, SystemExit)
    finally:
        for k in [k for k in sys.modules if k.startswith("exiting_pkg")]:
            del sys.modules[k]


def test_a_module_importing_a_missing_package_is_the_users_error(tmp_path, clean_registry,
                                                                 monkeypatch):
    """The module exists; a package it imports does not: that is their line, not 'no module
    named <their module>'."""
    (tmp_path / "needs_missing.py").write_text("import os\nimport no_such_pkg_qq\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        with pytest.raises(PluginError) as e:
            plugins.load("needs_missing")
        assert f"{tmp_path / 'needs_missing.py'}, line 2" in str(e.value)
        assert "no_such_pkg_qq" in str(e.value)
    finally:
        sys.modules.pop("needs_missing", None)


def test_an_entry_point_calling_sys_exit_warns_with_file_and_line(tmp_path, clean_registry,
                                                                  monkeypatch):
    """One broken package must not end the program (exit 0, nothing done) nor hide the
    others: it is a warning carrying the PluginError's words."""
    (tmp_path / "ep_exits.py").write_text("import sys\nsys.exit(0)\n")
    info = tmp_path / "ep_exits-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: ep_exits\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text("[trackbook.trackers]\nexits = ep_exits:X\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            plugins.load_entry_points()
        msgs = [str(x.message) for x in w]
        assert any(f"{tmp_path / 'ep_exits.py'}, line 2" in m and "sys.exit(0)" in m
                   and "ep_exits" in m for m in msgs), msgs
    finally:
        sys.modules.pop("ep_exits", None)
