"""The playground viewer: one JavaScript module for the Jupyter widget and the HTML book."""
from .core import Playground
from .data import VIEWER_JS
from .export import BOOK_ENV

__all__ = ["Playground", "VIEWER_JS", "BOOK_ENV"]
