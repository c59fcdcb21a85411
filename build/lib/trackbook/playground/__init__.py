"""The playground viewer: one JavaScript module for the Jupyter widget and the HTML book."""
from .core import BOOK_ENV, VIEWER_JS, Playground

__all__ = ["Playground", "VIEWER_JS", "BOOK_ENV"]
