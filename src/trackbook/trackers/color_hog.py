"""Lee et al. 2012: particle filters on a kernel colour histogram, HOG, and IPCA learning.

Three registered trackers share one class, :class:`ColorHogParticleFilter`, and differ only
in which parts of the measurement model they switch on:

========================  =========================================================  =====
name                      measurement                                                paper
========================  =========================================================  =====
``color-pf``              HSV 8x8x4 kernel histogram vs. the first frame (eq. 1, 10)  base
``color-hog-pf``          colour + HOG, fused by eq. 14, fixed references            base
``color-hog-ipca``        as above for T frames, then reconstruction error against   prop.
                          incrementally learned subspaces (eq. 6-7, 12-13)
========================  =========================================================  =====

From the paper: state and motion of eq. 8-9, N = 100 particles, SIR selection by cumulative
weights (multinomial), estimate = weighted mean of the states. The paper spreads the t = 0
particles over the whole frame; the book starts them around the given box (``init``; the paper
preset uses ``"frame"``). ``trackers.departures(name)`` lists every departure with its why.

Decisions where the paper is silent or wrong (chapters 2-4 of the book discuss them):

- eq. 10-11 print exp(-(1 - D^2) / 2 sigma^2), which rewards *dissimilar* particles; we use
  exp(-D^2 / 2 sigma^2).
- eq. 12-13 print D = sqrt(sum_i z_i - z_reconst,i); we use the residual norm
  D = ||z - U U^T z||_2.
- The learned feature is z = sqrt(h) (the Hellinger map of the histogram h). Then ||z|| = 1 and
  ||sqrt(h) - sqrt(h_ref)||^2 = 2 (1 - rho). The reconstruction error ||z - U U^T z||^2 is
  therefore about 2 (1 - rho), twice the D^2 = 1 - rho of eq. 10-11 (chapter 4 measures the
  ratio): the same sigma is effectively sqrt(2) narrower after frame T, and beta = 0.7 weighs
  the reference and subspace terms about 0.7 : 0.6, not 0.7 : 0.3. On raw histograms (sum 1, norm ~0.1) every reconstruction error is ~0.01 and
  exp(-D^2 / 0.32) ~ 1 for every particle: the weights would carry no information.
  ``feature_map="raw"`` keeps the raw histograms for comparison.
- Sizes are kept in [min_size, frame size] and centres inside the frame (eq. 9 has no floor).
- Checked learning (beyond the paper, whose conclusion blames unchecked accumulation):

  * **anchor** (default beta = 0.7): after T the squared distance of a feature is
    beta (1 - rho(h, h_ref)) + (1 - beta) ||z - U U^T z||^2, so the first frame -- the one box
    known to be the target -- keeps pulling the particles back when the subspace has learned
    a drifted estimate (Matthews, Ishikawa & Baker 2004's drift correction, in a subspace
    tracker). ``anchor=0`` is the paper's eq. 12-13.
  * **relative gate** (``gate_k > 0``): a frame joins the subspace only if the energy
    -log(alpha s_color + (1 - alpha) s_hog) of its estimate, s = exp(-D^2 / 2 sigma^2), is
    within median + k MAD of the recently learned frames; ``learn_threshold`` is the older
    absolute version (s >= threshold); ``learn_every`` learns every k-th frame only.

  The lab notes on Lee et al. (2012) list every configuration tried and its AUC
  (``evaluation.table_seed000``).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..features.color import (HSV_BINS, bhattacharyya_coefficient, hsv_bin_index_u8,
                              kernel_weights, weighted_histograms)
from ..features.hog import gray_patches, hog_of_patches
from ..features.patches import sample_patches
from ..filters.motion import (VX, VY, W, H, box_to_state, clamp_states, fuse, gaussian_likelihood,
                              predict_eq9, similarity, states_to_boxes)
from ..filters.particle import RESAMPLERS, effective_sample_size
from .particle_filter import ParticleFilterTracker, lost_below_param, lost_k_param
from ..learning.incremental_svd import IncrementalSVD
from ..params import NOT_PRINTED, param
from .registry import register

#: Patch every box is resized to before its features are taken (section II).
PATCH_SIZE = (16, 24)
_KERNEL = kernel_weights(PATCH_SIZE[1], PATCH_SIZE[0])     # k = 1 - r^2 of eq. 1
_N_COLOR = int(np.prod(HSV_BINS))


@dataclasses.dataclass(frozen=True)
class ColorPFParams:
    """Knobs of ``color-pf``: the colour-only particle filter that Lee et al. (2012) compare
    against (Pérez et al. 2002), with the state, motion and likelihood of their section V.

    Chapter 2 of the book builds it step by step. ``paper=`` is the value Lee et al. print
    (section V; the comment names the passage); ``trackers.departures("color-pf")`` lists
    the fields whose default is the book's choice, with ``why``.
    """

    # N = 100: section V, the sentence after the pseudocode.
    n_particles: int = param(100, 10, 1000, 10, "N, number of particles (section V)",
                             paper=100)
    # sigma_color = 0.4: section V, the sentence after eq. 12-13 ("all sigma ... 0.4").
    sigma_color: float = param(0.2, 0.02, 1.0, 0.02, "sigma_color of eq. 10 (and 12): width of "
                               "the colour likelihood", paper=0.4,
                               why="at 0.4 a perfect match and a poor one (D^2 = 0.3) differ by "
                               "a factor 0.4 only: the weights are nearly flat; 0.2 scored best "
                               "of 0.1, 0.2, 0.4 on the seven public sequences we tuned on "
                               "(chapter 2)")
    # gamma_width, gamma_height ~ U(-2.5, 2.5): section V, the paragraph after eq. 9.
    size_noise: float = param(2.5, 0.0, 10.0, 0.5, "gamma_w, gamma_h ~ U(-a, a) of eq. 9 (px)",
                              paper=2.5)
    # gamma_xdot ~ U(-6.5, 6.5): section V, the paragraph after eq. 9.
    vx_noise: float = param(6.5, 0.0, 20.0, 0.5, "gamma_xdot ~ U(-a, a) of eq. 9 (px/frame)",
                            paper=6.5)
    # gamma_ydot ~ U(-2.5, 2.5): section V, the paragraph after eq. 9.
    vy_noise: float = param(2.5, 0.0, 20.0, 0.5, "gamma_ydot ~ U(-a, a) of eq. 9 (px/frame)",
                            paper=2.5)
    # Pseudocode of section V: one r ~ U[0, 1] per particle, smallest i with c_i >= r.
    resampler: str = param("multinomial", doc="SIR selection step (the pseudocode's is "
                           "multinomial: one uniform draw per particle)",
                           choices=tuple(RESAMPLERS), paper="multinomial")
    # Pseudocode, t = 0 (and section II): particles spread uniformly over the whole image.
    init: str = param("box", doc="t = 0 particles: 'box' within a quarter box of the given "
                      "box; 'frame' uniform over the frame with the given box size (the paper)",
                      choices=("frame", "box"), paper="frame",
                      why="the tracker is given the first box; a whole-frame start throws it "
                      "away and lets look-alikes win the first frames; 'box' scored higher on "
                      "the seven public sequences we tuned on (chapter 2)")
    # Not in the paper: eq. 9 lets w and h drift without bound.
    min_size: float = param(4.0, 1.0, 50.0, 1.0, "smallest box side a particle may have (px)",
                            paper=NOT_PRINTED,
                            why="eq. 9 has no floor, but a box must cover pixels to have a "
                            "histogram: every side stays >= 4 px (in the paper preset too)")
    # Not in the paper, which never reports a lost target: the book's distance gate (ch. 2).
    lost_below: float = lost_below_param()
    lost_k: float = lost_k_param()


@dataclasses.dataclass(frozen=True)
class ColorHogPFParams(ColorPFParams):
    """Knobs of ``color-hog-pf``: colour + HOG fused by eq. 14 against fixed first-frame
    references (Lee et al. 2012 compare it as a baseline, after Jin et al. 2010).

    Chapter 3 of the book builds it. ``paper=`` is the value Lee et al. print (section V; the
    comment names the passage); ``trackers.departures("color-hog-pf")`` lists the book's choices.
    """

    # alpha = 0.1: section V, the sentence after eq. 14 ("alpha = 0.1").
    alpha: float = param(0.1, 0.0, 1.0, 0.05, "alpha of eq. 14: weight of colour vs HOG",
                         paper=0.1)
    # sigma_hog = 0.4: section V, after eq. 12-13 ("all sigma ... 0.4").
    sigma_hog: float = param(0.2, 0.02, 1.0, 0.02, "sigma_hog of eq. 11 and 13",
                             paper=0.4,
                             why="same reason as sigma_color: at 0.4 the HOG weights are nearly "
                             "flat; 0.2 scored higher on the seven public sequences we tuned on "
                             "(chapter 3)")


@dataclasses.dataclass(frozen=True)
class ColorHogIPCAParams(ColorHogPFParams):
    """Knobs of ``color-hog-ipca`` (the tracker Lee et al. 2012 propose).

    Chapter 4 of the book builds it. Lee et al. print T = 40 and the sigmas; they print no
    number of basis vectors K (their "16" is the patch width, 16 x 24 px) and no forgetting
    factor: those are the book's choices (``paper=NOT_PRINTED`` with the setting
    ``preset="paper"`` uses). The gates, the anchor and the feature map are additions of the
    book, switched off (or set to the printed raw features) in the paper preset.
    """

    # T = 40: end of section II ("T = 40"), n = 40 in section IV.
    T: int = param(40, 2, 200, 1, "frames collected before the first SVD (section II, V)",
                   paper=40)
    # Not printed: the paper names no number of basis vectors.
    K: int = param(2, 1, 64, 1, "basis vectors kept by the incremental SVD (eq. 6-7)",
                   paper=NOT_PRINTED, paper_value=2,
                   why="Lee et al. give no K (their 16 is the patch width); 2 scored higher "
                   "than 4 with the anchor and than 16 without it, on the seven public "
                   "sequences we tuned on (lab notes)")
    # Not printed: eq. 6-7 follow Ross et al. 2008, whose forgetting factor the paper omits.
    forgetting: float = param(0.95, 0.5, 1.0, 0.01,
                              "forgetting factor f (old singular values x f, Ross et al. 2008)",
                              paper=NOT_PRINTED, paper_value=1.0,
                              why="the paper says old features are removed (section II) but "
                              "prints no rule or factor (paper preset: 1.0); with the anchor 0.95 "
                              "scored higher than 0.99 and 1.0 on the seven public sequences we "
                              "tuned on (lab notes; without the anchor 1.0 is better)")
    learn_threshold: float = param(0.0, 0.0, 1.0, 0.05,
                                   "gated learning: learn a frame only if its similarity >= this "
                                   "(0 = every frame, as the paper)", paper=0.0)
    anchor: float = param(0.7, 0.0, 1.0, 0.05,
                          "beta: after T the distance is beta D^2(h, h_ref) + (1 - beta) "
                          "D^2_subspace (0 = subspace only, the paper's eq. 12-13)",
                          paper=0.0,
                          why="the book's addition: the first frame keeps pulling drifted "
                          "subspaces back; 0.7 chosen on the seven public sequences we tuned "
                          "on (chapter 4, lab notes)")
    gate_k: float = param(0.0, 0.0, 10.0, 0.5,
                          "relative gate: learn a frame only if its energy -log(similarity) is "
                          "<= median + k * MAD of the last accepted frames (0 = off, as the paper)",
                          paper=0.0)
    gate_on: str = param("model", doc="what the relative gate measures: 'model' = the fused "
                         "similarity under the current likelihood, 'reference' = the fused "
                         "Bhattacharyya similarity to the first frame", choices=("model", "reference"),
                         paper=NOT_PRINTED, paper_value="model",
                         why="the book's addition; only used when gate_k > 0 (off in the paper "
                         "preset)")
    gate_window: int = param(20, 3, 200, 1, "accepted frames the relative gate remembers",
                             paper=NOT_PRINTED, paper_value=20,
                             why="the book's addition; only used when gate_k > 0 (off in the "
                             "paper preset)")
    learn_every: int = param(1, 1, 20, 1, "learn every k-th frame only (1 = every frame)",
                             paper=1)
    centre: bool = param(False, doc="learn mean-centred features (Ross et al.) instead of the "
                         "raw z of eq. 12-13 (the paper)", paper=False)
    # The paper learns the histograms themselves (section IV, eq. 12-13 of section V).
    feature_map: str = param("sqrt", doc="learned feature z: 'sqrt' = sqrt(histogram) "
                             "(unit norm), 'raw' = the histogram itself", choices=("sqrt", "raw"),
                             paper="raw",
                             why="on raw histograms (norm ~0.1) every reconstruction error is "
                             "~0.01 and every particle weighs the same; sqrt(h) has unit norm "
                             "(chapter 4)")


class ColorHogParticleFilter(ParticleFilterTracker):
    """Lee et al. 2012's SIR particle filter on colour, optionally HOG and IPCA learning.

    Subclasses switch parts on with ``use_hog`` and ``learns``.

    Attributes
    ----------
    particles : (N, 6) states [cx, cy, w, h, x_dot, y_dot] (eq. 8) after the last update.
    weights : (N,) normalised weights of the last update.
    likelihoods : (N,) the fused p(z|x) of eq. 14 of the last update.
    similarities : dict of (N,) arrays ``exp(-D^2 / 2 sigma^2)`` per feature ("color", "hog").
    reference : dict of the reference features ("color": (256,), "hog": (192,)).
    basis : dict of learned bases ("color": (256, k), "hog": (192, k)) or None before T.
    learning : bool, whether the likelihood uses the learned subspaces.
    n_learned : number of frames added to the subspaces (or collected before T).
    n_rejected : number of frames the relative gate refused.

    Lost rule: that of ``ParticleFilterTracker`` (flat frames, the distance gate with its
    second look, the scatter while lost); the gate's match is the colour term 1 - D^2_color.
    """

    use_hog: bool = False
    learns: bool = False

    # -- model ---------------------------------------------------------------------------
    def _features(self, frame, boxes) -> dict:
        """Colour histogram (eq. 1) and HOG (eq. 2-5) of every box, from ONE resampling of
        the boxes to 16 x 24 px: the same as ``color_histograms`` and ``hog_descriptors``,
        with a single ``cv2.remap`` for both."""
        patches = sample_patches(frame, boxes, PATCH_SIZE)
        feats = {"color": weighted_histograms(hsv_bin_index_u8(patches, HSV_BINS), _KERNEL, _N_COLOR)}
        if self.use_hog:
            feats["hog"] = hog_of_patches(gray_patches(patches))
        return feats

    def _z(self, h):
        """The learned feature of a histogram (rows): sqrt(h) or h (see module docstring)."""
        return np.sqrt(h) if getattr(self.params, "feature_map", "sqrt") == "sqrt" else h

    def _model(self, frame, box):
        self._reference = {k: v[0] for k, v in self._features(frame, box[None]).items()}
        self._root_reference = {k: np.sqrt(v) for k, v in self._reference.items()}
        self._learn_root = getattr(self.params, "feature_map", "sqrt") == "sqrt"
        self._subspaces = None
        self._collected = [] if self.learns else None
        self._n_learned = 0
        self._similarities = {}
        self._gate_history = []
        self._n_rejected = 0
        self._n_frames_seen = 0
        if self.learns:
            self._collected.append({k: self._z(v) for k, v in self._reference.items()})
            self._n_learned = 1

    def _initial_particles(self, frame, box):
        p = self.params
        n = p.n_particles
        s0 = box_to_state(box)
        states = np.tile(s0, (n, 1))
        Hf, Wf = frame.shape[:2]
        if p.init == "frame":
            # Pseudocode, t = 0: N particles spread uniformly and independently over the image,
            # each with the initial box size.
            w, h = s0[W], s0[H]
            states[:, 0] = self.rng.uniform(min(w / 2, Wf / 2), max(Wf - w / 2, Wf / 2), n)
            states[:, 1] = self.rng.uniform(min(h / 2, Hf / 2), max(Hf - h / 2, Hf / 2), n)
        else:
            states[:, 0] += self.rng.uniform(-s0[W] / 4, s0[W] / 4, n)
            states[:, 1] += self.rng.uniform(-s0[H] / 4, s0[H] / 4, n)
        return clamp_states(states, frame.shape, p.min_size)

    def _predict(self, particles):
        p = self.params
        new = predict_eq9(particles, self.rng, (p.size_noise, p.size_noise, p.vx_noise, p.vy_noise))
        return clamp_states(new, self._shape, p.min_size)

    def _distances2(self, feats) -> dict:
        """D^2 per feature: Bhattacharyya (eq. 10-11) before learning, reconstruction error
        (eq. 12-13) after, mixed with the first-frame Bhattacharyya term when ``anchor > 0``."""
        beta = getattr(self.params, "anchor", 0.0)
        d2 = {}
        for k, h in feats.items():
            root = np.sqrt(h)
            d2_ref = None
            if self._subspaces is None or beta > 0:
                # 1 - rho with rho = sum sqrt(h h_ref) = sqrt(h) . sqrt(h_ref)  (eq. 10-11)
                d2_ref = np.clip(1.0 - root @ self._root_reference[k], 0.0, None)
            if self._subspaces is None:
                d2[k] = d2_ref
                continue
            z = root if self._learn_root else h
            d2_sub = self._subspaces[k].reconstruction_error(z.T) ** 2
            d2[k] = d2_sub if beta == 0 else beta * d2_ref + (1.0 - beta) * d2_sub
        return d2

    def _likelihood(self, frame, particles):
        p = self.params
        feats = self._features(frame, states_to_boxes(particles))
        d2 = self._distances2(feats)
        self._similarities = {"color": similarity(d2["color"], p.sigma_color)}
        p_color = gaussian_likelihood(d2["color"], p.sigma_color)
        # the match 1 - D^2 of the lost gate is the colour term alone: whether the target is
        # there at all; HOG's match swings with small misalignments and on small boxes
        self._match = np.clip(1.0 - d2["color"], 0.0, 1.0)
        if not self.use_hog:
            return p_color
        self._similarities["hog"] = similarity(d2["hog"], p.sigma_hog)
        return fuse(p_color, gaussian_likelihood(d2["hog"], p.sigma_hog), p.alpha)   # eq. 14

    def _box_to_state(self, box):
        return box_to_state(box)

    def _state_to_box(self, state):
        return states_to_boxes(state)[0]

    def _on_lost(self):
        # Nothing looked like the target: forget the velocities, which are what carried the
        # particles away.
        self._particles[:, VX:VY + 1] = 0.0

    # -- learning ------------------------------------------------------------------------
    def _update(self, frame):
        ok, box = super()._update(frame)
        if self.learns and ok:
            self._learn(frame, box)
        return ok, box

    def _fused_similarity(self, d2) -> float:
        p = self.params
        s_c = float(similarity(d2["color"], p.sigma_color)[0])
        s_h = float(similarity(d2["hog"], p.sigma_hog)[0])
        return p.alpha * s_c + (1 - p.alpha) * s_h

    def _estimate_similarity(self, feats) -> float:
        """alpha s_color + (1 - alpha) s_hog of the estimate, s = exp(-D^2 / 2 sigma^2), under
        the current model (``gate_on="model"``) or against the first frame (``"reference"``)."""
        if getattr(self.params, "gate_on", "model") == "reference":
            return self._fused_similarity({k: 1.0 - bhattacharyya_coefficient(v, self._reference[k])
                                           for k, v in feats.items()})  # eq. 10-11
        return self._fused_similarity(self._distances2(feats))

    def _gate(self, feats) -> bool:
        """Whether the estimate's features may join the model (beyond the paper).

        Absolute gate: similarity s >= ``learn_threshold``. Relative gate (``gate_k > 0``): the
        frame's energy e = -log s (about D^2 / 2 sigma^2) must lie within the typical range of
        the frames learned recently, e <= median + k * 1.4826 * MAD (the MAD scaled to a
        Gaussian's sigma); a frame far above it is an occlusion, a look-alike or drift, and
        learning it would teach the model its own mistake. The range is taken on e, not on s:
        s is squeezed against 0 for every poor frame, e keeps them apart. The first five
        frames always pass (there is no range yet).
        """
        p = self.params
        if p.learn_threshold <= 0 and p.gate_k <= 0:
            return True
        s = self._estimate_similarity(feats)
        if p.learn_threshold > 0 and s < p.learn_threshold:
            return False
        if p.gate_k <= 0:
            return True
        e = -np.log(max(s, 1e-300))
        hist = self._gate_history
        if len(hist) >= 5:
            v = np.asarray(hist)
            med = float(np.median(v))
            mad = 1.4826 * float(np.median(np.abs(v - med)))
            if e > med + p.gate_k * mad:
                self._n_rejected += 1
                return False
        hist.append(e)
        del hist[:-p.gate_window]
        return True

    def _learn(self, frame, box):
        """Collect the features at the estimated state; SVD at T, incremental updates after."""
        p = self.params
        self._n_frames_seen += 1
        if self._n_frames_seen % p.learn_every:
            return                                   # not a learning frame: no features needed
        feats = self._features(frame, np.asarray(box)[None])
        if not self._gate(feats):
            return
        z = {k: self._z(v[0]) for k, v in feats.items()}
        if self._subspaces is None:
            self._collected.append(z)
            if len(self._collected) >= p.T:
                self._subspaces = {}
                for k in z:
                    A = np.column_stack([c[k] for c in self._collected])   # d x T
                    self._subspaces[k] = IncrementalSVD(p.K, p.forgetting, centre=p.centre).fit(A)
                self._collected = []
                if p.gate_on == "model":
                    self._gate_history = []       # the similarity changes meaning at T
        else:
            for k, v in z.items():
                self._subspaces[k].partial_fit(v)                          # m = 1 (eq. 6-7)
        self._n_learned += 1

    # -- read-only views for the book ------------------------------------------------------
    @property
    def similarities(self) -> dict:
        return {k: v.copy() for k, v in self._similarities.items()}

    @property
    def reference(self) -> dict:
        return {k: v.copy() for k, v in self._reference.items()}

    @property
    def basis(self):
        if not self.learns or self._subspaces is None:
            return None
        return {k: s.U.copy() for k, s in self._subspaces.items()}

    @property
    def singular_values(self):
        if not self.learns or self._subspaces is None:
            return None
        return {k: s.S.copy() for k, s in self._subspaces.items()}

    @property
    def learning(self) -> bool:
        return self.learns and self._subspaces is not None

    @property
    def n_learned(self) -> int:
        return self._n_learned

    @property
    def n_rejected(self) -> int:
        """Frames the relative gate (``gate_k > 0``) refused to learn."""
        return self._n_rejected

    def frame_report(self) -> dict:
        """Per-frame numbers collected by ``trackbook.evaluate``: the mean likelihood of the
        particles, the effective sample size (before the next resampling) and, for the
        learning tracker, whether the learned subspaces were in use."""
        rep = {"mean_likelihood": float(np.mean(self._likelihoods)),
               "ess": effective_sample_size(self._weights)}
        if self.learns:
            rep["learning"] = float(self.learning)
        return rep


@register
class ColorPF(ColorHogParticleFilter):
    """``color-pf``: the colour-only particle filter Lee et al. 2012 compare against
    (Pérez et al. 2002), with their state (eq. 8), motion (eq. 9), colour likelihood (eq. 10,
    sign corrected) and N = 100. The first whole tracker of the book (chapter 2)."""

    name = "color-pf"
    Params = ColorPFParams


@register
class ColorHogPF(ColorHogParticleFilter):
    """``color-hog-pf``: colour + HOG fused by eq. 14, no learning ([14], Jin et al. 2010)."""

    name = "color-hog-pf"
    Params = ColorHogPFParams
    use_hog = True


@register
class ColorHogIPCA(ColorHogParticleFilter):
    """``color-hog-ipca``: Lee et al. 2012's proposed tracker (colour + HOG + IPCA learning)."""

    name = "color-hog-ipca"
    Params = ColorHogIPCAParams
    use_hog = True
    learns = True
