"""Generated sample clips with exact ground truth: the names a chapter or test imports.

A fresh install has no dataset, so the book tracks on clips rendered from photographs that
ship with scikit-image. The work is split in three modules, re-exported here:
:mod:`~trackbook.clips.rendering` (the compositing engine: photographs, sprites, canvas,
camera and lighting), :mod:`~trackbook.clips.sprites` (figures, balls, shadows, framed
pictures) and :mod:`~trackbook.clips.scenes` (the registered sample scenes and the
lost-and-found clip); :mod:`~trackbook.clips.samples` is their one registry.

>>> from trackbook.clips import synthetic
>>> r = synthetic.render("red-cube")
>>> r.frames.shape
(184, 240, 320, 3)
"""

from __future__ import annotations

from .rendering import (  # noqa: F401
    _PHOTO_FILES, SS, Canvas, Film, H, Placement, Rendering, Sprite, W, crop, duotone, expose,
    mask_box, noise_source, path, photo, sprite_box, steps, tile, view)
from .samples import render, render_masks  # noqa: F401
from .scenes import leave_and_return  # noqa: F401
from .sprites import (  # noqa: F401
    ball_sprite, cylinder_shading, ellipse_sprite, face, figure, planks, rect_sprite,
    shadow_sprite, walk_poses, walker)
