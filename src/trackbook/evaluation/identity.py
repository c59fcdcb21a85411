"""Identity switches: does each target keep the same track? (``case_study_cho2005``, several targets)

Each frame, tracks are matched to ground-truth identities as the CLEAR MOT metrics do
(Bernardin & Stiefelhagen 2008): a correspondence of the previous frame is kept while its IoU
stays at or above the threshold; the remaining tracks and identities are matched by the
Hungarian assignment on IoU (pairs below the threshold never match). An **identity switch** is
a frame in which an identity is matched to a different track than the one it was last matched
to (frames where it is matched to none do not count, nor break the memory). Two tracks that
overlap one identity equally well are a tie, broken by their order.

>>> import numpy as np
>>> gt = {"a": np.array([[0, 0, 10, 10]] * 3, float), "b": np.array([[50, 0, 10, 10]] * 3, float)}
>>> identity_switches([gt["a"], gt["b"]], gt)
0
>>> swapped = [np.vstack([gt["a"][:2], gt["b"][2:]]), np.vstack([gt["b"][:2], gt["a"][2:]])]
>>> identity_switches(swapped, gt)
2
"""

from __future__ import annotations

import numpy as np

from ..trackers.association import assign, iou_matrix

__all__ = ["identity_switches", "matched_identities"]


def _as_stack(tracks) -> np.ndarray:
    """(n_tracks, N, 4) float array from a list / dict of (N, 4) box arrays."""
    if isinstance(tracks, dict):
        tracks = [v for k, v in tracks.items() if not str(k).startswith("_")]
    arr = np.asarray([np.asarray(t, dtype=float) for t in tracks], dtype=float)
    if arr.ndim != 3 or arr.shape[2] != 4:
        raise ValueError(f"tracks must be (N, 4) box arrays of one length, got shape {arr.shape}.")
    return arr


def matched_identities(tracks, truth, iou_threshold: float = 0.5) -> np.ndarray:
    """For each track and frame, the index of the identity it is matched to (−1: none).

    Parameters
    ----------
    tracks : list (or dict) of (N, 4) predicted boxes, one array per track
    truth : dict identity -> (N, 4) ground-truth boxes (NaN rows: not visible)
    iou_threshold : a track covers an identity when their IoU is at least this

    Returns
    -------
    (n_tracks, N) int array of identity indices, in the order of ``truth``
    """
    P = _as_stack(tracks)
    G = _as_stack(truth)
    if P.shape[1] != G.shape[1]:
        raise ValueError(f"tracks have {P.shape[1]} frames and the truth {G.shape[1]}; "
                         f"score them over the same frames.")
    n_frames = P.shape[1]
    out = np.full((P.shape[0], n_frames), -1, dtype=int)
    last = {}                                   # identity -> track of the previous frame
    for t in range(n_frames):
        pt = np.nan_to_num(P[:, t], nan=0.0)
        visible = np.all(np.isfinite(G[:, t]), axis=1)
        iou = iou_matrix(pt, np.nan_to_num(G[:, t], nan=0.0))
        iou[:, ~visible] = 0.0
        ok = iou >= iou_threshold
        used_tracks, used_ids = set(), set()
        for j, i in last.items():               # keep last frame's correspondences that hold
            if ok[i, j]:
                out[i, t] = j
                used_tracks.add(i); used_ids.add(j)
        ok[list(used_tracks), :] = False
        ok[:, list(used_ids)] = False
        for i, j in assign(-iou, ok):           # the rest: the largest total IoU
            out[i, t] = j
        last = {int(out[i, t]): i for i in range(P.shape[0]) if out[i, t] >= 0}
    return out


def identity_switches(tracks, truth, iou_threshold: float = 0.5) -> int:
    """The number of identity switches of ``tracks`` against ``truth`` (see the module doc)."""
    m = matched_identities(tracks, truth, iou_threshold)
    switches, previous = 0, {}
    for t in range(m.shape[1]):
        for i in np.flatnonzero(m[:, t] >= 0):
            j = int(m[i, t])
            if j in previous and previous[j] != i:
                switches += 1
            previous[j] = int(i)
    return switches
