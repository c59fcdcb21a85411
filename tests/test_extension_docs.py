"""The extension points a student's tracker uses are documented where ``help()`` shows them."""
from __future__ import annotations

import importlib
import inspect
import pkgutil
import pydoc

import pytest

import trackbook.trackers as trackers_pkg
from trackbook.trackers.base import Tracker
from trackbook.trackers.particle_filter import ParticleFilterTracker


def _all_tracker_modules():
    for m in pkgutil.iter_modules(trackers_pkg.__path__):
        importlib.import_module(f"trackbook.trackers.{m.name}")


def _subclasses(cls):
    for s in cls.__subclasses__():
        yield s
        yield from _subclasses(s)


def _overridden_hooks() -> set[str]:
    """Names of the methods that the library's particle trackers override and that the
    particle-filter base (or the tracker base under it) defines."""
    _all_tracker_modules()
    names = set()
    for cls in _subclasses(ParticleFilterTracker):
        if not cls.__module__.startswith("trackbook.trackers."):
            continue                  # a tracker defined by another test
        for k, v in vars(cls).items():
            if inspect.isfunction(v) and k != "__init__" and hasattr(ParticleFilterTracker, k):
                names.add(k)
    return names


def test_help_of_tracker_shows_the_subclass_contract():
    text = pydoc.render_doc(Tracker, renderer=pydoc.plaintext)
    # pydoc hides underscore methods, so the class docstring must name them
    for word in ("_init(frame, box)", "_update(frame) -> (ok, box)", "_drawn", "Params",
                 "flat_range", "state()", "self.rng", "register"):
        assert word in text, word


def test_the_overridden_hooks_are_found():
    hooks = _overridden_hooks()
    # the hooks every particle tracker of the book fills in, and a few optional ones
    assert {"model", "initial_particles", "predict", "likelihood", "box_to_state",
            "state_to_box", "respread", "refine", "_locate", "_learn", "_init"} <= hooks


@pytest.mark.parametrize("name", sorted(_overridden_hooks()))
def test_every_overridden_hook_has_a_numpydoc_docstring(name):
    fn = getattr(ParticleFilterTracker, name)
    doc = inspect.getdoc(fn)
    assert doc, f"ParticleFilterTracker.{name} has no docstring"
    params = [p for p in inspect.signature(fn).parameters if p != "self"]
    if params:
        assert "Parameters\n----------" in doc, name
        section = doc.split("Parameters\n----------", 1)[1]
        for p in params:
            assert f"\n{p} :" in "\n" + section, f"{name}: parameter {p!r} not described"
    assert "Returns\n-------" in doc, name


def test_learn_is_called_only_on_frames_judged_on_target():
    from trackbook import clips
    from trackbook.trackers.color_pf import ColorPF

    class Counting(ColorPF):              # not registered: only this test uses it
        def _learn(self, frame, box):
            calls.append(tuple(box))
            super()._learn(frame, box)

    calls = []
    clip = clips.load("red-cube")
    t = Counting(seed=0)
    t.init(clip.frames[0], clip.groundtruth[0])
    ok, box = t.update(clip.frames[1])
    assert ok and calls == [box]                      # a tracked frame: learned, that box
    before = tuple(t.estimate)
    ok, box = t.update(clip.frames[2] * 0)            # a black frame: lost
    assert not ok and len(calls) == 1                 # not learned
    assert tuple(t.estimate) == before                # the estimate stays
    assert box == calls[0]                            # and so does the box
