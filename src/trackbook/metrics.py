"""OTB scores (the OTB conventions, Wu et al. 2013): ``from trackbook import metrics``.

The implementation lives in :mod:`trackbook.evaluation.metrics`; this module is the short name
assignments use.
"""
from .evaluation.metrics import *  # noqa: F401,F403
from .evaluation.metrics import __all__  # noqa: F401
