"""Plotting helpers for the book (cells that call them are hidden in the HTML).

The shared drawings live in :mod:`trackbook.viz.core`; chapter-specific ones in
``trackbook.viz.<concept>`` (e.g. ``viz.hog``).
"""
from .core import (CYCLE, EST_COLOR, GREY, GT_COLOR, OKABE_ITO, animate, bgr2rgb, draw_box,
                   draw_ellipse,
                   draw_particles, draw_search_window, draw_state_cv, draw_tracker_state,
                   filmstrip,
                   plot_curves, show_frame)
from ..style import label_color, tracker_color
from .tables import departures_table

__all__ = ["animate", "bgr2rgb", "departures_table", "draw_box", "draw_ellipse", "draw_particles",
           "draw_search_window", "draw_state_cv", "draw_tracker_state", "filmstrip", "plot_curves",
           "show_frame", "GT_COLOR", "EST_COLOR", "CYCLE", "GREY", "OKABE_ITO", "label_color",
           "tracker_color"]
