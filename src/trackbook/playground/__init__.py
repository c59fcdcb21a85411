"""The playground viewer: one JavaScript module for the Jupyter widget and the HTML book."""
from .core import Playground
from .data import VIEWER_JS

__all__ = ["Playground", "VIEWER_JS"]
