"""Scoring runs: OTB metrics, the ``evaluate`` runner and the benchmark."""
from . import metrics
from .runner import MultiResult, Result, evaluate

__all__ = ["metrics", "evaluate", "MultiResult", "Result"]
