"""The tracker playground (kept here so ``from trackbook.widgets import Playground`` works).

The implementation lives in :mod:`trackbook.playground`: one JavaScript module draws the panel
in Jupyter (an anywidget) and in the HTML book (runs precomputed at build time).
"""
from .playground import Playground
from .playground.data import knob_spec, sample_values

__all__ = ["Playground", "knob_spec", "sample_values"]
