"""The helpers that replaced repeated code: the scores line and the viewer's JPEG frames."""

from __future__ import annotations

import base64

import cv2
import numpy as np

from trackbook.evaluation.metrics import scores_line
from trackbook.playground import data as D


def test_the_scores_line():
    s = {"auc": 0.51249, "precision20": 0.6, "tracking_rate": 0.5804, "ms_median": 4.214}
    assert scores_line(s) == ("AUC 0.512 \u00b7 precision@20px 0.600 \u00b7 tracking rate "
                              "58.0% \u00b7 4.21 ms/frame")
    assert scores_line(s, ms=False, sep=", ") == ("AUC 0.512, precision@20px 0.600, "
                                                  "tracking rate 58.0%")
    assert scores_line({"ms_median": 2.0}) == "no ground truth \u00b7 2.00 ms/frame"


def test_jpeg_frames_decode_to_the_image():
    rng = np.random.default_rng(0)
    img = cv2.GaussianBlur(rng.integers(0, 255, (48, 64, 3), dtype=np.uint8), (0, 0), 2)
    buf = np.frombuffer(base64.b64decode(D.jpeg(img, quality=95)), np.uint8)
    back = cv2.imdecode(buf, cv2.IMREAD_COLOR)
    assert back.shape == img.shape
    assert np.abs(back.astype(int) - img).mean() < 3      # lossy, but the same picture, BGR
