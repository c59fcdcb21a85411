"""Animations where motion teaches, drawn by the playground's viewer (one JavaScript module).

Each function returns a displayable :class:`~trackbook.playground.animation.Animation`
(scrub, play/pause, arrow keys; live in Jupyter and in the HTML book, offline)::

    from trackbook.playground.animations import sir_cycle
    sir_cycle()                     # predict / weigh / resample of a particle filter
"""

from __future__ import annotations

import cv2
import numpy as np

from .. import clips as _clips
from ..evaluation import metrics
from ..style import OKABE_ITO
from .animation import Animation, run_entry
from .data import snapshot

ORANGE, PURPLE, SKY = OKABE_ITO["orange"], OKABE_ITO["reddish purple"], OKABE_ITO["sky blue"]


def show_run(clip, results: dict, max_frames: int = 80) -> Animation:
    """Scrub through finished runs (``{label: Result}``) of one clip; ground truth shown, the
    curve is each run's IoU per frame. At most ``max_frames`` frames (evenly spaced)."""
    clip = _clips.load(clip)
    n = min(len(r.boxes) for r in results.values())
    idx = np.unique(np.linspace(0, n - 1, min(n, max_frames)).round().astype(int))
    images = [clip.frames[i] for i in idx]
    gt = np.asarray(clip.groundtruth)[idx]
    runs = {}
    for label, r in results.items():
        s = r.scores
        iou = metrics.iou(r.boxes, clip.groundtruth[:len(r.boxes)])[idx]
        score = (f"{label} on {clip.name}: {metrics.scores_line(s, ms=False)}"
                 if "auc" in s else f"{label} on {clip.name}")
        runs[label] = run_entry(label, np.asarray(r.boxes)[idx], curve=iou,
                                curve_label="IoU with ground truth", curve_x="frame",
                                captions=[f"clip frame {i}" for i in idx], scores=score)
    return Animation(clip.name, images, runs, gt=gt,
                     note="Every frame drawn in the browser; scrub, play, or use the arrow keys.")


def sir_cycle(clip="red-cube", tracker="color-pf", frames=range(1, 9), seed=0,
              n_particles=60, zoom=4) -> Animation:
    """The SIR cycle of a particle filter, step by step: resample (drawn in proportion to
    weight: the cloud gathers on the target), predict (the particles move by the motion
    model, equal weights), weigh (each scored by the likelihood: dot size). Eq. 1-4 of
    Arulampalam et al. (2002); the trackers' loop is :class:`ParticleFilterTracker`.

    Parameters
    ----------
    zoom : int
        The frames are cut to the ``1/zoom`` of their width and height centred on the
        target (its mean ground-truth centre over ``frames``, kept inside the frame) and
        enlarged ``zoom`` times, the particles, boxes and ground truth with them: on the
        whole 320 x 240 frame of ``red-cube`` the 24 px cube and its particles are a few
        dots. ``zoom=1`` shows the whole frame.
    """
    from .. import trackers as _trackers
    from ..filters.particle import RESAMPLERS
    from ..trackers import TrackerState

    clip = _clips.load(clip)
    t = _trackers.create(tracker, seed=seed, n_particles=n_particles)
    frames = list(frames)
    zoom = int(zoom)
    if zoom < 1:
        raise ValueError(f"sir_cycle: zoom={zoom} must be a whole number >= 1.")
    fh, fw = np.asarray(clip.frames[0]).shape[:2]
    cw, ch = fw // zoom, fh // zoom                   # the crop, enlarged back to ~ fw x fh
    g = np.asarray(clip.groundtruth, dtype=float)[frames]
    mid = (g[:, :2] + g[:, 2:] / 2).mean(axis=0)
    x0 = int(np.clip(round(mid[0] - cw / 2), 0, fw - cw))
    y0 = int(np.clip(round(mid[1] - ch / 2), 0, fh - ch))
    off = np.array([x0, y0], dtype=float)

    def crop(img):
        cut = np.asarray(img)[y0:y0 + ch, x0:x0 + cw]
        return cv2.resize(cut, (cw * zoom, ch * zoom), interpolation=cv2.INTER_LINEAR)

    def box_in_crop(b):
        b = np.asarray(b, dtype=float)
        return np.concatenate([(b[:2] - off) * zoom, b[2:4] * zoom])

    def points_in_crop(p):
        q = np.array(p, dtype=float)                  # a copy: the tracker keeps its own
        q[:, :2] = (q[:, :2] - off) * zoom
        return q
    t.init(clip.frames[0], clip.groundtruth[0])
    images, index, states, boxes, captions, ess = [], [], [], [], [], []
    gts = []
    for k in range(1, max(frames) + 1):
        f = clip.frames[k]
        if k not in frames:
            t.update(f)
            continue
        images.append(crop(f))
        img = len(images) - 1
        # the tracker's own steps, reproduced one by one with its RNG (as _update does)
        idx = RESAMPLERS[t.params.resampler](t._weights, t.rng)
        resampled = t._particles[idx]
        predicted = np.asarray(t.refine(f, t.predict(resampled)), dtype=float)
        lik = np.asarray(t.likelihood(f, predicted), dtype=float)
        w = lik / lik.sum() if lik.sum() > 0 else np.full(len(lik), 1 / len(lik))
        n = len(w)
        prev = _Snap(t._particles, t._weights)
        for p, ww, cap in (
                (resampled, np.full(n, 1 / n), "resample: drawn in proportion to weight"),
                (predicted, np.full(n, 1 / n), "predict: moved by the motion model"),
                (predicted, w, "weigh: scored by the likelihood")):
            states.append(snapshot(TrackerState(particles=points_in_crop(p), weights=ww)))
            index.append(img)
            gts.append(box_in_crop(clip.groundtruth[k]))
            est = t.state_to_box(np.average(p, axis=0, weights=ww))
            boxes.append(box_in_crop(est))
            ess.append(1.0 / np.sum(ww ** 2) / n)
            captions.append(f"frame {k} \u00b7 {cap}")
        del prev
        t._particles, t._weights, t._likelihoods = predicted, w, lik
        t.estimate = np.average(predicted, axis=0, weights=w)
    run = run_entry(tracker, boxes, captions=captions, states=states, curve=ess,
                    curve_label="effective sample size / N",
                    scores=f"{tracker} on {clip.name}, {n_particles} particles: "
                           "resample \u2192 predict \u2192 weigh, frame after frame")
    where = (f" The view is enlarged {zoom} times around the target (the part "
             f"{cw} \u00d7 {ch} px of the {fw} \u00d7 {fh} frame)." if zoom > 1 else "")
    # the still picture: the middle frame's weigh step, where dot sizes differ
    still = 3 * (len(frames) // 2) + 2
    return Animation(clip.name, images, {tracker: run}, index=index, gt=gts, still=still,
                     note="Three steps per frame: resample, predict, weigh." + where)


class _Snap:
    def __init__(self, particles, weights):
        self.particles, self.weights = particles, weights


def kalman_ball(clip="yellow-ball", n_frames=40, seed=0, sensor="noisy-truth",
                qs=(0.01, 1.0, 100.0), noise_sd=4.0, **params) -> Animation:
    """The Kalman filter on the bouncing ball, two steps per frame: predict (the 3-sigma
    window of the innovation covariance S, eq. 9-10 of Lee 2015) and update (the measurement
    pulls the estimate; eq. 11-13).

    Parameters
    ----------
    sensor : {"noisy-truth", "covariance"}
        ``"noisy-truth"`` (``06_kalman``): the measurement is the ground-truth centre plus Gaussian
        noise of standard deviation ``noise_sd`` px, filtered by the constant-velocity model
        with ``R = noise_sd**2 I`` and one run per process-noise scale in ``qs`` (the viewer
        offers them as a choice). ``"covariance"`` (``case_study_lee2015``): the measurement is the best
        covariance match of the ``kalman-covariance`` tracker (``params`` go to it).
    """
    if sensor == "noisy-truth":
        return _kalman_noisy_truth(clip, n_frames, seed, qs, noise_sd)
    if sensor != "covariance":
        raise ValueError(f"sensor={sensor!r}: use 'noisy-truth' (a simulated sensor) or "
                         "'covariance' (the kalman-covariance tracker's measurements)")
    from .. import trackers as _trackers

    clip = _clips.load(clip)
    t = _trackers.create("kalman-covariance", seed=seed, **params)
    t.init(clip.frames[0], clip.groundtruth[0])
    w, h = clip.groundtruth[0][2:]
    images, index, boxes, meas, windows, captions, gts, err = [], [], [], [], [], [], [], []
    n = len(clip) if n_frames is None else min(n_frames, len(clip))
    for k in range(1, n):
        f = clip.frames[k]
        ok, box = t.update(f)
        x_pred = t.prediction[0] if not ok else None
        images.append(f)
        sw = list(t.search_window)
        # predict: the window and the predicted centre (before the measurement)
        pred_c = (sw[0] + sw[2] / 2, sw[1] + sw[3] / 2)
        pred_box = [pred_c[0] - w / 2, pred_c[1] - h / 2, w, h]
        cx = t.kalman.x[0] if hasattr(t.kalman, "x") else box[0] + w / 2
        cy = t.kalman.x[1] if hasattr(t.kalman, "x") else box[1] + h / 2
        upd_box = [cx - w / 2, cy - h / 2, w, h]
        for step in ("predict", "update"):
            index.append(len(images) - 1)
            gts.append(clip.groundtruth[k])
            windows.append({"search_window": sw})
            if step == "predict":
                boxes.append(pred_box)
                meas.append(None)
                captions.append(f"frame {k} \u00b7 predict: window from S")
            else:
                boxes.append(upd_box)
                meas.append(box if ok else None)
                captions.append(f"frame {k} \u00b7 update: measurement "
                                + ("accepted" if ok else "refused (no match)"))
            g = clip.groundtruth[k]
            b = boxes[-1]
            err.append(float(np.hypot(b[0] + b[2] / 2 - g[0] - g[2] / 2,
                                      b[1] + b[3] / 2 - g[1] - g[3] / 2)))
        del x_pred
    curve = np.minimum(np.asarray(err) / 40.0, 1.0)
    run = run_entry("kalman-covariance", boxes, captions=captions, states=windows,
                    curve=curve, curve_label="centre error / 40 px",
                    extra_boxes=[("measurement", PURPLE, meas)], est_label="Kalman estimate",
                    scores="kalman-covariance on yellow-ball: predicted window (dashed), "
                           "measurement (purple), update (vermillion)")
    return Animation(clip.name, images, {"kalman": run}, index=index, gt=gts,
                     note="Two steps per frame: predict, then update with the measurement.")


def _kalman_noisy_truth(clip, n_frames, seed, qs, noise_sd) -> Animation:
    """The view of ``06_kalman``: a simulated sensor (true centre + N(0, noise_sd^2)) and one Kalman
    run per Q scale, on the same frames and the same noisy measurements."""
    from ..filters.kalman import constant_velocity

    if noise_sd <= 0:
        raise ValueError(f"noise_sd={noise_sd}: the simulated sensor needs a positive "
                         "standard deviation in pixels (e.g. 4.0)")
    clip = _clips.load(clip)
    n = min(n_frames, len(clip))
    gt = np.asarray(clip.groundtruth[:n], dtype=float)
    centres = gt[:, :2] + gt[:, 2:] / 2
    rng = np.random.default_rng(seed)
    z = centres + rng.normal(0.0, noise_sd, size=centres.shape)
    w, h = gt[0, 2:]
    index, gts = [], []
    for k in range(1, n):
        index += [k - 1, k - 1]
        gts += [clip.groundtruth[k], clip.groundtruth[k]]
    runs = {}
    for q in qs:
        kf = constant_velocity(x0=tuple(z[0]), q=q, r=noise_sd ** 2)
        boxes, meas, windows, captions, err = [], [], [], [], []
        for k in range(1, n):
            kf.predict()
            S = kf.innovation_covariance()
            hx, hy = 3 * np.sqrt(S[0, 0]), 3 * np.sqrt(S[1, 1])
            sw = [kf.x[0] - hx, kf.x[1] - hy, 2 * hx, 2 * hy]
            pred_box = [kf.x[0] - w / 2, kf.x[1] - h / 2, w, h]
            kf.update(z[k])
            upd_box = [kf.x[0] - w / 2, kf.x[1] - h / 2, w, h]
            z_box = [z[k, 0] - w / 2, z[k, 1] - h / 2, w, h]
            for step, b in (("predict", pred_box), ("update", upd_box)):
                boxes.append(b)
                windows.append({"search_window": sw})
                meas.append(z_box if step == "update" else None)
                captions.append(f"frame {k} \u00b7 Q = {q:g}\u00b7I \u00b7 " +
                                ("predict: 3\u03c3 of S" if step == "predict"
                                 else "update with the noisy measurement"))
                err.append(float(np.hypot(b[0] + w / 2 - centres[k, 0],
                                          b[1] + h / 2 - centres[k, 1])))
        curve = np.minimum(np.asarray(err) / 40.0, 1.0)
        runs[f"Q = {q:g}\u00b7I"] = run_entry(
            f"Kalman, Q = {q:g}\u00b7I", boxes, captions=captions, states=windows, curve=curve,
            curve_label="centre error / 40 px", extra_boxes=[("measurement", PURPLE, meas)],
            est_label="Kalman estimate",
            scores=f"simulated sensor (true centre + {noise_sd:g} px noise), R = "
                   f"{noise_sd ** 2:g}\u00b7I, Q = {q:g}\u00b7I: prediction window "
                   "(dashed), measurement (purple), estimate (vermillion)")
    return Animation(clip.name, [clip.frames[k] for k in range(1, n)], runs, index=index,
                     gt=gts, note="Two steps per frame: predict, then update with the "
                                  "measurement. Choose Q to see how much the filter trusts "
                                  "its constant-velocity model.")


def mean_shift_climb(clip="occluder", frame=8, start_offset=(-25, 10), max_iter=20) -> Animation:
    """One mean-shift climb (Comaniciu et al. 2003, steps 1-6 of Cho & Kang 2005 sec. 3.3):
    the ellipse moves uphill on the Bhattacharyya surface, one iteration per step."""
    from ..filters.mean_shift import bin_image, ellipse_rho, mean_shift
    from ..trackers.condensation_mean_shift import box_to_ellipse, ellipse_to_box

    clip = _clips.load(clip)
    f0, f1 = clip.frames[0], clip.frames[frame]
    e = box_to_ellipse(clip.groundtruth[0])
    img0 = bin_image(f0, (0, 0, f0.shape[1], f0.shape[0]))
    q = ellipse_rho(img0, np.zeros(img0.n_bins), e[None, :2], e[None, 2:])[1][0]
    H, W = f1.shape[:2]
    img1 = bin_image(f1, (0, 0, W, H))
    start = e[None, :2] + np.asarray(start_offset, dtype=float)[None]
    res = mean_shift(img1, q, start, e[None, 2:], max_iter=max_iter, eps=0.5)
    traj, rho = res.trajectory[:, 0], res.rho_trajectory[:, 0]
    states = [{"ellipse": [c[0], c[1], e[2], e[3]],
               "particles": traj[:k + 1], "weights": np.ones(k + 1)}
              for k, c in enumerate(traj)]
    boxes = [ellipse_to_box(c[0], c[1], e[2], e[3]) for c in traj]
    run = run_entry("mean-shift", boxes, states=states, curve=rho,
                    curve_label="Bhattacharyya rho", curve_x="iteration",
                    captions=[f"iteration {k} \u00b7 rho {r:.3f}" for k, r in enumerate(rho)],
                    scores=f"mean-shift on frame {frame} of {clip.name}: {len(traj) - 1} "
                           f"iterations, rho {rho[0]:.3f} \u2192 {rho[-1]:.3f}")
    return Animation(clip.name, [f1], {"climb": run}, index=[0] * len(traj),
                     gt=[clip.groundtruth[frame]] * len(traj),
                     note="One climb: each step is one mean-shift iteration.")


def subspace_drift(clip="robot-corridor-day", n_frames=None, seed=0, every=3,
                   **params) -> Animation:
    """The learned colour subspace of ``color-hog-ipca`` over time (Lee et al. 2012, eq. 6-7
    and 12-13; the incremental SVD of Ross et al. 2008): beside each frame, the first frame's
    histogram (grey; its square root when the tracker learns sqrt(h)), its reconstruction
    from the current basis (orange) and the first basis vector (blue); the curve is the
    fraction of that first-frame feature the basis fails to explain, ||x - U U^T x|| / ||x||
    (empty before the basis exists, at frame T). ``n_frames=None`` plays the whole clip:
    the basis needs T frames before it exists, and more to move."""
    import cv2

    from .. import trackers as _trackers

    clip = _clips.load(clip)
    t = _trackers.create("color-hog-ipca", seed=seed, **params)
    t.init(clip.frames[0], clip.groundtruth[0])
    images, boxes, resid, captions, gts = [], [], [], [], []
    n = len(clip) if n_frames is None else min(n_frames, len(clip))
    for k in range(1, n):
        f = clip.frames[k]
        ok, box = t.update(f)
        if k % every:
            continue
        ref = t.reference.get("color")
        basis = (t.basis or {}).get("color")
        # one pixel column per bin, so all 256 colour bins are drawn
        panel = np.full((f.shape[0], 256, 3), 255, np.uint8)
        r = np.nan
        if ref is not None:
            x = np.sqrt(ref) if t._learn_root else ref
            rec = basis @ (basis.T @ x) if basis is not None else None
            r = float(np.linalg.norm(x - rec) / np.linalg.norm(x)) if rec is not None else np.nan
            _bars(panel, x, (150, 150, 150), 0)
            if rec is not None:
                _bars(panel, rec, (0, 159, 230), 1)
                _bars(panel, np.abs(basis[:, 0]), (178, 114, 0), 2)
        cv2.putText(panel, "frame 0 / recon / u1", (4, 14), cv2.FONT_HERSHEY_SIMPLEX, 0.4,
                    (0, 0, 0), 1, cv2.LINE_AA)
        images.append(np.hstack([f, panel]))
        boxes.append(box)
        gts.append(clip.groundtruth[k])
        resid.append(r)
        captions.append(f"frame {k} \u00b7 {t.n_learned} frames learned"
                        + ("" if basis is not None else " \u00b7 no basis yet"))
    run = run_entry("color-hog-ipca", boxes, captions=captions, curve=resid,
                    curve_label="frame 0's colour left unexplained",
                    curve_x="frame",
                    scores=f"color-hog-ipca on {clip.name}: the colour subspace learned online")
    return Animation(clip.name, images, {"subspace": run}, gt=gts,
                     note="Right panel: the first frame's colour feature, its "
                          "reconstruction from the learned basis, and the first basis "
                          "vector.")


def _bars(panel, v, color, row):
    """Draw vector ``v`` as a bar strip in one third of ``panel``."""
    import cv2

    v = np.asarray(v, dtype=float)
    h3 = (panel.shape[0] - 20) // 3
    top = 20 + row * h3
    m = v.max() if v.max() > 0 else 1.0
    bw = max(1, panel.shape[1] // max(len(v), 1))
    for j, x in enumerate(v[: panel.shape[1] // bw]):
        hh = int((h3 - 4) * x / m)
        cv2.rectangle(panel, (j * bw, top + h3 - hh), (j * bw + bw - 1, top + h3), color, -1)
