"""User trackers: ``trackers.plugins.load`` (a file or a module) and installed entry points."""

from __future__ import annotations

import sys
import textwrap
import warnings

import numpy as np
import pytest

from trackbook import trackers
from trackbook.trackers import plugins
from trackbook.trackers import registry as _registry

# A tiny tracker: the box never moves. Its name carries a per-test suffix so tests do not
# collide in one process.
TRACKER_SRC = textwrap.dedent("""
    from trackbook import trackers

    @trackers.register
    class Still(trackers.Tracker):
        name = {name!r}

        def _init(self, frame, box):
            self._box = tuple(float(v) for v in box)

        def _update(self, frame):
            return True, self._box
""")


def test_load_file_registers_once(tmp_path, clean_registry):
    f = tmp_path / "still_tracker.py"
    f.write_text(TRACKER_SRC.format(name="still-file"))
    assert "still-file" not in trackers.available()
    m1 = plugins.load(str(f))
    assert "still-file" in trackers.available()
    cls = trackers.get("still-file")
    # loading the same file again (also through another spelling of its path) is a no-op
    m2 = plugins.load(str(tmp_path / "." / "still_tracker.py"))
    assert m1 is m2
    assert trackers.available().count("still-file") == 1
    assert trackers.get("still-file") is cls
    # and the tracker runs through the public API
    frame = np.zeros((40, 50, 3), np.uint8)
    frame[10:20, 10:20] = 200
    t = trackers.create("still-file")
    t.init(frame, (10, 10, 10, 10))
    assert t.update(frame) == (True, (10.0, 10.0, 10.0, 10.0))


def test_load_dotted_module(tmp_path, clean_registry, monkeypatch):
    pkg = tmp_path / "my_student_pkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "trk.py").write_text(TRACKER_SRC.format(name="still-module"))
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        plugins.load("my_student_pkg.trk")
        assert "still-module" in trackers.available()
        plugins.load("my_student_pkg.trk")              # idempotent
        assert trackers.available().count("still-module") == 1
    finally:
        for k in [k for k in sys.modules if k.startswith("my_student_pkg")]:
            del sys.modules[k]


@pytest.mark.parametrize("spec, words", [
    ("no/such/file.py", ["no/such/file.py", "no such file"]),
    ("no_such_module_xyz.trk", ["no_such_module_xyz", "no module named"]),
    ("", ["dotted module name"]),
])
def test_load_errors_name_the_spec(spec, words, clean_registry):
    with pytest.raises(ValueError) as e:
        plugins.load(spec)
    for w in words:
        assert w in str(e.value)


def test_load_file_that_raises(tmp_path, clean_registry):
    f = tmp_path / "broken.py"
    f.write_text("raise RuntimeError('boom')\n")
    with pytest.raises(ValueError, match=r"broken\.py.*RuntimeError: boom"):
        plugins.load(str(f))
    # after fixing the file it loads (the failed attempt was not remembered)
    f.write_text(TRACKER_SRC.format(name="still-fixed"))
    plugins.load(str(f))
    assert "still-fixed" in trackers.available()


def test_load_file_registering_nothing_warns(tmp_path, clean_registry):
    f = tmp_path / "empty.py"
    f.write_text("X = 1\n")
    with pytest.warns(UserWarning, match="registered no new tracker"):
        plugins.load(str(f))


def _fake_distribution(root, dist, module, value, tracker_name):
    """A package 'installed' into ``root``: its module and a ``.dist-info`` folder with the
    entry point, which is all ``importlib.metadata`` reads (no pip involved)."""
    (root / f"{module}.py").write_text(TRACKER_SRC.format(name=tracker_name))
    info = root / f"{dist}-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text(
        f"[trackbook.trackers]\n{tracker_name} = {value}\n")


def test_entry_point_registers(tmp_path, clean_registry, monkeypatch):
    _fake_distribution(tmp_path, "fake_trk_dist", "fake_trk_mod", "fake_trk_mod:Still",
                       "still-entry")
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        assert "still-entry" not in _registry.registered()
        # the first trackers.available() of a process loads the entry points
        monkeypatch.setattr(plugins, "_entry_points_done", False)
        assert "still-entry" in trackers.available()
        assert trackers.get("still-entry").__module__ == "fake_trk_mod"
        # once per process: a second call does not import again
        assert plugins.load_entry_points() == []
    finally:
        sys.modules.pop("fake_trk_mod", None)


def test_entry_point_naming_a_module(tmp_path, clean_registry, monkeypatch):
    _fake_distribution(tmp_path, "fake_trk_dist2", "fake_trk_mod2", "fake_trk_mod2",
                       "still-entry-module")
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        assert plugins.load_entry_points() == ["still-entry-module"]
    finally:
        sys.modules.pop("fake_trk_mod2", None)


def test_broken_entry_point_warns_and_others_still_load(tmp_path, clean_registry,
                                                        monkeypatch):
    _fake_distribution(tmp_path, "fake_good", "fake_good_mod", "fake_good_mod:Still",
                       "still-good")
    info = tmp_path / "fake_bad-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: fake_bad\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text("[trackbook.trackers]\nbad = no_such_mod_abc:X\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            new = plugins.load_entry_points()
        assert "still-good" in new
        assert any("no_such_mod_abc" in str(x.message) for x in w)
    finally:
        sys.modules.pop("fake_good_mod", None)


def test_a_class_defined_again_replaces_itself(clean_registry):
    """A notebook cell run twice defines the class twice: the second replaces the first; a
    different class under a taken name is still refused."""
    ns1, ns2 = {"__name__": "nb_cell"}, {"__name__": "nb_cell"}
    exec(TRACKER_SRC.format(name="still-twice"), ns1)
    exec(TRACKER_SRC.format(name="still-twice"), ns2)
    assert trackers.get("still-twice") is ns2["Still"]
    with pytest.raises(ValueError, match="registered twice"):
        exec(TRACKER_SRC.format(name="still-twice"), {"__name__": "another_module"})
