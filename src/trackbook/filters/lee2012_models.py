"""Motion and measurement models of Lee et al. 2012's particle filter (section V).

Chapter ``02_particle_filters`` of the book. The state of a particle (eq. 8) is

    X = [x, y, w, h, x_dot, y_dot],

with (x, y) the *centre* of the box, (w, h) its size and (x_dot, y_dot) its velocity in pixels
per frame. The system model (eq. 9) is a constant-velocity model whose noise enters the size
and the velocity only:

    x_t = x_{t-1} + x_dot_{t-1},        w_t = w_{t-1} + gamma_w,     x_dot_t = x_dot_{t-1} + gamma_xdot,
    y_t = y_{t-1} + y_dot_{t-1},        h_t = h_{t-1} + gamma_h,     y_dot_t = y_dot_{t-1} + gamma_ydot,

gamma_w, gamma_h ~ U(-2.5, 2.5), gamma_xdot ~ U(-6.5, 6.5), gamma_ydot ~ U(-2.5, 2.5).

The measurement model (eq. 10-11 and 14) turns a squared distance D^2 between a particle's
feature and the reference into a likelihood and fuses colour and shape.
"""

from __future__ import annotations

import numpy as np

#: Index of each component in the state vector of eq. 8.
X, Y, W, H, VX, VY = range(6)

#: Half-widths of the uniform noises of eq. 9: (gamma_w, gamma_h, gamma_xdot, gamma_ydot).
EQ9_NOISE = (2.5, 2.5, 6.5, 2.5)

#: State transition matrix A of eq. 9.
A_EQ9 = np.array([
    [1, 0, 0, 0, 1, 0],
    [0, 1, 0, 0, 0, 1],
    [0, 0, 1, 0, 0, 0],
    [0, 0, 0, 1, 0, 0],
    [0, 0, 0, 0, 1, 0],
    [0, 0, 0, 0, 0, 1],
], dtype=float)


def box_to_state(box) -> np.ndarray:
    """(x, y, w, h) top-left box -> the eq. 8 state [cx, cy, w, h, 0, 0] at rest."""
    x, y, w, h = np.asarray(box, dtype=float).reshape(4)
    return np.array([x + w / 2, y + h / 2, w, h, 0.0, 0.0])


def states_to_boxes(states) -> np.ndarray:
    """(N, 6) eq. 8 states -> (N, 4) top-left boxes (x, y, w, h)."""
    s = np.asarray(states, dtype=float).reshape(-1, 6)
    return np.column_stack([s[:, X] - s[:, W] / 2, s[:, Y] - s[:, H] / 2, s[:, W], s[:, H]])


def predict_eq9(particles, rng: np.random.Generator, noise=EQ9_NOISE) -> np.ndarray:
    """One step of the system model of eq. 9 (Lee et al. 2012): X_t = A X_{t-1} + gamma.

    Parameters
    ----------
    particles : (N, 6) states [x, y, w, h, x_dot, y_dot].
    rng : the tracker's generator (the only source of randomness).
    noise : half-widths (a_w, a_h, a_xdot, a_ydot) of the zero-mean uniform noises.

    Returns
    -------
    (N, 6) new states (a new array).
    """
    p = np.asarray(particles, dtype=float)
    a = np.asarray(noise, dtype=float)
    gamma = np.zeros_like(p)
    gamma[:, W:] = rng.uniform(-a, a, size=(p.shape[0], 4))
    return p @ A_EQ9.T + gamma


def clamp_states(states, frame_shape, min_size: float = 4.0) -> np.ndarray:
    """Keep every particle's box a sensible size and its centre inside the frame.

    eq. 9's size noise is a random walk with no floor, so w or h would eventually go negative;
    and a box centred off-image samples nothing but replicated border. Sizes are clipped to
    [min_size, frame size] and centres to the frame, in place, and the array is returned.
    """
    Hf, Wf = frame_shape[:2]
    s = states
    s[:, W] = np.clip(s[:, W], min_size, Wf)
    s[:, H] = np.clip(s[:, H], min_size, Hf)
    s[:, X] = np.clip(s[:, X], 0.0, Wf)
    s[:, Y] = np.clip(s[:, Y], 0.0, Hf)
    return s


def similarity(d2, sigma: float) -> np.ndarray:
    """exp(-D^2 / (2 sigma^2)): 1 for a perfect match, falling with the squared distance.

    This is eq. 10-11 of Lee et al. 2012 *as corrected*: the paper prints
    exp(-(1 - D^2) / (2 sigma^2)), which grows with the distance and so rewards the particles
    that look least like the target [quote: lee2012.likelihood_eq10] -- a sign typo (Perez et al. 2002, the paper's own [20],
    use exp(-D^2 / (2 sigma^2)) = exp(-(1 - rho) / (2 sigma^2))).
    """
    d2 = np.clip(np.asarray(d2, dtype=float), 0.0, None)
    return np.exp(-d2 / (2.0 * sigma**2))


def gaussian_likelihood(d2, sigma: float) -> np.ndarray:
    """p(z|x) = exp(-D^2 / (2 sigma^2)) / sqrt(2 pi sigma^2), eq. 10-11 (corrected) and
    eq. 12-13 of Lee et al. 2012, with D^2 a squared feature distance."""
    return similarity(d2, sigma) / np.sqrt(2.0 * np.pi * sigma**2)


def fuse(p_color, p_hog, alpha: float) -> np.ndarray:
    """p(z|x) = alpha p_color + (1 - alpha) p_hog, eq. 14 of Lee et al. 2012 (alpha = 0.1)."""
    if not 0.0 <= alpha <= 1.0:
        raise ValueError(f"alpha = {alpha!r} must lie in [0, 1] (eq. 14 mixes two likelihoods).")
    return alpha * np.asarray(p_color, dtype=float) + (1.0 - alpha) * np.asarray(p_hog, dtype=float)
