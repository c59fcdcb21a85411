"""The book's colours, in one place for the figures, the playground viewer and the videos.

Dependency-free (no numpy, no matplotlib), so any layer may import it. Colours are ``#RRGGBB``
strings; :func:`bgr` turns one into the ``(B, G, R)`` tuple OpenCV draws with.
"""

from __future__ import annotations


class Palette(list):
    """A list of colours that can also be indexed by name: ``p[5] == p["blue"]``."""

    def __init__(self, named: dict):
        super().__init__(named.values())
        self.names = dict(named)

    def __getitem__(self, key):
        return self.names[key] if isinstance(key, str) else super().__getitem__(key)


#: The book's one palette: Okabe & Ito's eight colours, distinguishable with the common
#: colour-vision deficiencies; index it by position or by name.
OKABE_ITO = Palette({"black": "#000000", "orange": "#E69F00", "sky blue": "#56B4E9",
                     "bluish green": "#009E73", "yellow": "#F0E442", "blue": "#0072B2",
                     "vermillion": "#D55E00", "reddish purple": "#CC79A7"})
#: Ground truth bluish green, the estimate vermillion, everything else from the palette;
#: trackers that a comparison plot is not about are drawn in GREY.
GT_COLOR = OKABE_ITO["bluish green"]
EST_COLOR = OKABE_ITO["vermillion"]
GREY = "#BBBBBB"
#: The order in which several trackers of one plot take their colours.
CYCLE = [OKABE_ITO[k] for k in ("vermillion", "blue", "orange", "reddish purple", "sky blue",
                                "black", "bluish green", "yellow")]
#: Each registered tracker's colour, the same in every figure of the book: one colour per
#: tracker (its re-detecting variant ``<name>-redetect`` shares it and is told apart by a dashed
#: line), distinct within the groups the book shows together (the correlation filters; the
#: particle filters of Lee et al. and Kim et al.; the covariance trackers; Condensation and
#: mean-shift), none of them the ground truth's colour. :func:`tracker_color` looks it up.
TRACKER_COLORS = {
    # correlation filters
    "kcf": OKABE_ITO["vermillion"], "mosse": OKABE_ITO["sky blue"],
    "dsst": OKABE_ITO["orange"], "staple": OKABE_ITO["reddish purple"],
    "bacf": OKABE_ITO["blue"],
    # particle filters on colour, gradients, subspaces and edges
    "color-pf": "#882255", "color-hog-pf": "#332288", "color-hog-ipca": "#44AA99",
    "hsi-color-pf": "#999933", "hog-pf": "#AA4499", "edge-ray-pf": OKABE_ITO["black"],
    # region covariance
    "covariance": "#CC6677", "kalman-covariance": "#6699CC",
    "kalman-covariance-manoeuvre": "#8C564B",
    # Condensation and mean-shift
    "condensation": "#BBCC33", "mean-shift": "#004488", "condensation-mean-shift": "#EE3377",
    "camshift": "#EE7733",
    # point tracking and tracking by detection
    "median-flow": "#555555", "opencv-mil": "#997700",
}


def tracker_color(name: str, default: str | None = None) -> str | None:
    """The colour tracker ``name`` is drawn in in every figure (:data:`TRACKER_COLORS`).

    A re-detecting variant (``kcf-redetect``) has its tracker's colour. A name the book does
    not register (a student's own tracker) gets ``default``.
    """
    base = name[: -len("-redetect")] if name.endswith("-redetect") else name
    return TRACKER_COLORS.get(base, default)


def _tracker_of(label: str) -> str | None:
    """The colour of the tracker a plot label starts with ("kcf", "kcf-redetect [0.583]",
    "kcf (ours)"), or None."""
    return tracker_color(label.strip().split(" ", 1)[0].rstrip(",:;")) if label else None


def label_color(label: str, i: int = 0) -> str:
    """The colour of a plotted series labelled ``label``, ``i``-th in its plot: its tracker's
    colour when the label starts with a tracker's name, otherwise the ``i``-th colour of
    :data:`CYCLE` (:func:`label_colors` also keeps clear of the plot's trackers' colours)."""
    return _tracker_of(label) or CYCLE[i % len(CYCLE)]


def label_colors(labels) -> list[str]:
    """The colours of the series ``labels`` of one plot, in order: a tracker's label in its
    tracker's colour, every other label in the next colour of :data:`CYCLE` that no tracker
    of this plot is drawn in (so a student's tracker beside ``kcf`` is not drawn in
    ``kcf``'s vermillion)."""
    own = [_tracker_of(label) for label in labels]
    taken = {c.lower() for c in own if c}
    free = [c for c in CYCLE if c.lower() not in taken] or CYCLE
    out, k = [], 0
    for c in own:
        if c is None:
            c, k = free[k % len(free)], k + 1
        out.append(c)
    return out


#: What the playground viewer draws each element in (sent to ``viewer.js`` with its config).
VIEWER = {"gt": GT_COLOR, "est": EST_COLOR, "particle": OKABE_ITO["blue"],
          "window": OKABE_ITO["orange"], "ellipse": OKABE_ITO["reddish purple"],
          "cand": "#8c8c8c", "ray": OKABE_ITO["sky blue"], "curve": EST_COLOR,
          "grid": "#dddddd", "conf": OKABE_ITO["blue"], "lost": OKABE_ITO["vermillion"],
          "response": OKABE_ITO["sky blue"]}


def bgr(colour: str) -> tuple:
    """``"#RRGGBB"`` as the ``(B, G, R)`` integer tuple OpenCV draws with."""
    h = colour.lstrip("#")
    if len(h) != 6:
        raise ValueError(f"colour {colour!r} is not '#RRGGBB'.")
    r, g, b = (int(h[i:i + 2], 16) for i in (0, 2, 4))
    return (b, g, r)
