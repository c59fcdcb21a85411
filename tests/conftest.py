"""Shared fixtures. Tests that need the real sequences skip cleanly when they are absent."""
import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from trackbook import clips  # noqa: E402

SEQUENCES = clips.find_sequences()
needs_sequences = pytest.mark.skipif(
    not SEQUENCES, reason="../shared/data/sequences not found (set TRACKBOOK_SEQUENCES)")


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


@pytest.fixture
def textured_frame(rng):
    """A 240x320 BGR frame with smooth texture (random noise upsampled)."""
    import cv2
    small = rng.integers(0, 256, (30, 40, 3), dtype=np.uint8)
    return cv2.resize(small, (320, 240), interpolation=cv2.INTER_CUBIC)
