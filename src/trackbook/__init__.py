"""trackbook: classical visual object tracking, the book's library.

>>> import trackbook
>>> from trackbook import trackers, clips, metrics
>>> clip = clips.load("red-cube")                                   # doctest: +SKIP
>>> result = trackbook.evaluate("kalman-covariance", clip, seed=0)  # doctest: +SKIP
>>> result.scores["auc"]                                            # doctest: +SKIP
"""

from importlib.metadata import PackageNotFoundError, version

from . import clips, metrics, trackers
from ._memory import keep_freed_memory as tune_memory
from .evaluation.runner import MultiResult, Result, evaluate

try:
    __version__ = version("trackbook")
except PackageNotFoundError:  # running from a source tree without install
    __version__ = "0.0.0+unknown"

__all__ = ["clips", "metrics", "trackers", "evaluate", "MultiResult", "Result", "tune_memory",
           "__version__"]
