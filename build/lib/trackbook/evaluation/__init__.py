"""Scoring runs: OTB metrics, the ``evaluate`` runner and the benchmark."""
from . import metrics
from .runner import Result, evaluate

__all__ = ["metrics", "evaluate", "Result"]
