"""Non-linear filtering for ``06_kalman``: a target seen by range and bearing.

A point target moves with constant velocity (plus white-noise acceleration) in the plane; a
sensor at ``s = (s_x, s_y)`` measures its range and bearing. The motion is linear, the
measurement is not:

    x_k = f(x_{k-1}) + w_k,   f(x) = F x,                       w_k ~ N(0, Q)
    z_k = h(x_k) + v_k,       h(x) = [‖p − s‖, atan2(p_y − s_y, p_x − s_x)],  v_k ~ N(0, R)

with x = [p_x, p_y, v_x, v_y] and p = (p_x, p_y). Four filters estimate x from z:

* :func:`run_kf` — the linear Kalman filter of :mod:`trackbook.filters.kalman` on the
  *converted* measurement s + r (cos θ, sin θ), with one fixed measurement covariance;
* :func:`run_ekf` — filterpy's ``ExtendedKalmanFilter``: h linearised at the prediction by its
  Jacobian H_j (any f, h: the tests run it on a linear model against ``KalmanFilter``);
* :func:`run_ukf` — filterpy's ``UnscentedKalmanFilter`` with ``MerweScaledSigmaPoints``;
* :func:`run_particle_filter` — a bootstrap (SIR) particle filter built from
  :mod:`trackbook.filters.particle`.

Every runner returns an :class:`Estimate` (the posterior means and covariances per step);
:func:`position_rmse` scores it against the simulated truth of :func:`simulate`.

>>> import numpy as np
>>> truth, zs = simulate(np.random.default_rng(0), n_steps=5)
>>> truth.shape, zs.shape
((5, 4), (5, 2))
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .kalman import KalmanFilter
from .particle import RESAMPLERS, effective_sample_size, normalize_weights, weighted_mean

__all__ = ["Estimate", "F_cv", "F_j", "H_j", "Q_cv", "compare", "f", "h", "polar_to_xy",
           "position_rmse", "residual_z", "run_ekf", "run_kf", "run_particle_filter",
           "run_ukf", "simulate", "unscented_transform", "wrap_angle"]

#: The default scenario: the target passes 10 units from the sensor, so the bearing sweeps
#: through most of 180 degrees; the range is precise and the bearing vague (σ_r = 0.2,
#: σ_θ = 0.2 rad), so the likelihood of one measurement is a thin arc, far from an ellipse.
X0 = (-60.0, 10.0, 2.0, 0.0)
SENSOR = (0.0, 0.0)


# --------------------------------------------------------------------------- the model

def F_cv(dt: float = 1.0) -> np.ndarray:
    """The constant-velocity transition matrix F for x = [p_x, p_y, v_x, v_y]."""
    F = np.eye(4)
    F[0, 2] = F[1, 3] = dt
    return F


def Q_cv(q: float, dt: float = 1.0) -> np.ndarray:
    """Q = q G Gᵀ: white acceleration of variance q held over one step, G = [dt²/2 I; dt I]."""
    G = np.vstack([0.5 * dt ** 2 * np.eye(2), dt * np.eye(2)])
    return q * G @ G.T


def f(x, dt: float = 1.0) -> np.ndarray:
    """The motion model f(x) = F x, for one state (4,) or a stack of states (N, 4)."""
    return np.asarray(x, dtype=float) @ F_cv(dt).T


def F_j(x, dt: float = 1.0) -> np.ndarray:
    """The Jacobian ∂f/∂x at x: F itself, since f is linear."""
    return F_cv(dt)


def wrap_angle(a):
    """Angles mapped into [−π, π): a bearing difference of 359° is one of −1°."""
    return (np.asarray(a, dtype=float) + np.pi) % (2 * np.pi) - np.pi


def h(x, sensor=SENSOR) -> np.ndarray:
    """The measurement model: range and bearing of the target from the sensor.

    h(x) = [‖p − s‖, atan2(p_y − s_y, p_x − s_x)] for one state (4,) -> (2,), or a stack
    (N, 4) -> (N, 2).
    """
    x = np.asarray(x, dtype=float)
    dx, dy = x[..., 0] - sensor[0], x[..., 1] - sensor[1]
    return np.stack([np.hypot(dx, dy), np.arctan2(dy, dx)], axis=-1)


def H_j(x, sensor=SENSOR) -> np.ndarray:
    """The Jacobian H_j = ∂h/∂x at one state x (2 × 4).

    With (d_x, d_y) = p − s and r = ‖p − s‖: ∂r/∂p = (d_x, d_y)/r, ∂θ/∂p = (−d_y, d_x)/r²;
    neither depends on the velocity.
    """
    x = np.asarray(x, dtype=float)
    dx, dy = x[0] - sensor[0], x[1] - sensor[1]
    r2 = dx * dx + dy * dy
    r = np.sqrt(r2)
    return np.array([[dx / r, dy / r, 0.0, 0.0], [-dy / r2, dx / r2, 0.0, 0.0]])


def residual_z(a, b) -> np.ndarray:
    """a − b for measurements [r, θ], the bearing difference wrapped into [−π, π)."""
    d = np.asarray(a, dtype=float) - np.asarray(b, dtype=float)
    d[..., 1] = wrap_angle(d[..., 1])
    return d


def polar_to_xy(z, sensor=SENSOR) -> np.ndarray:
    """The converted measurement s + r (cos θ, sin θ) of a range-bearing z (2,) or (N, 2)."""
    z = np.asarray(z, dtype=float)
    return np.stack([sensor[0] + z[..., 0] * np.cos(z[..., 1]),
                     sensor[1] + z[..., 0] * np.sin(z[..., 1])], axis=-1)


def simulate(rng: np.random.Generator, n_steps: int = 60, x0=X0, q: float = 0.01,
             sigma_r: float = 0.2, sigma_theta: float = 0.2, sensor=SENSOR, dt: float = 1.0):
    """A true track and its range-bearing measurements.

    Parameters
    ----------
    rng : ``numpy.random.Generator`` (same generator state -> same track and measurements)
    n_steps : number of steps; x0 : the state before the first step
    q : variance of the white acceleration (see :func:`Q_cv`)
    sigma_r, sigma_theta : standard deviations of the range and of the bearing (radians)

    Returns
    -------
    truth : (n_steps, 4) states x_1 … x_n; zs : (n_steps, 2) measurements [r, θ] of them
    """
    if not isinstance(rng, np.random.Generator):
        raise TypeError("simulate needs a numpy.random.Generator, e.g. np.random.default_rng(0).")
    n_steps = int(n_steps)
    if n_steps < 1:
        raise ValueError(f"n_steps must be at least 1, got {n_steps}.")
    G = np.vstack([0.5 * dt ** 2 * np.eye(2), dt * np.eye(2)])
    x = np.asarray(x0, dtype=float)
    truth = np.empty((n_steps, 4))
    for k in range(n_steps):
        x = f(x, dt) + G @ rng.normal(0.0, np.sqrt(q), 2)
        truth[k] = x
    noise = rng.normal(0.0, 1.0, (n_steps, 2)) * [sigma_r, sigma_theta]
    zs = h(truth, sensor) + noise
    zs[:, 1] = wrap_angle(zs[:, 1])
    return truth, zs


# --------------------------------------------------------------------------- the filters

@dataclass
class Estimate:
    """What a filter believed after each measurement.

    Attributes
    ----------
    name : the filter's name
    x : (n, dim_x) posterior means x̂_k⁺; P : (n, dim_x, dim_x) posterior covariances P_k⁺
    """

    name: str
    x: np.ndarray
    P: np.ndarray


def position_rmse(estimate, truth) -> float:
    """Root-mean-square position error sqrt(mean ‖p̂_k − p_k‖²) of an Estimate or (n, ≥2) array."""
    x = estimate.x if isinstance(estimate, Estimate) else np.asarray(estimate, dtype=float)
    d = x[:, :2] - np.asarray(truth, dtype=float)[:, :2]
    return float(np.sqrt(np.mean(np.sum(d * d, axis=1))))


def run_kf(zs, x0, P0, Q, sigma_r: float = 0.2, sigma_theta: float = 0.2, sensor=SENSOR,
           dt: float = 1.0) -> Estimate:
    """The linear Kalman filter on the converted measurements s + r (cos θ, sin θ).

    A linear filter needs z = H x + v with fixed H and R. Converting each range-bearing
    measurement to a position gives the H of ``06_kalman``; its noise, however, is stretched
    across the line of sight (σ_θ r wide, σ_r deep) and turns with the bearing. The filter
    keeps the one R it is given: R_c = J R Jᵀ at the first measurement (J the Jacobian of the
    conversion), so it is right at the start and wrong as the bearing turns.
    """
    zs = np.asarray(zs, dtype=float)
    kf = KalmanFilter(4, 2)
    kf.x, kf.P = np.asarray(x0, dtype=float).copy(), np.asarray(P0, dtype=float).copy()
    kf.F, kf.Q = F_cv(dt), np.asarray(Q, dtype=float)
    kf.H = np.eye(2, 4)
    r, th = zs[0]
    J = np.array([[np.cos(th), -r * np.sin(th)], [np.sin(th), r * np.cos(th)]])
    kf.R = J @ np.diag([sigma_r ** 2, sigma_theta ** 2]) @ J.T
    xs, Ps = [], []
    for zc in polar_to_xy(zs, sensor):
        kf.predict()
        kf.update(zc)
        xs.append(kf.x.copy()); Ps.append(kf.P.copy())
    return Estimate("KF (converted)", np.array(xs), np.array(Ps))


def run_ekf(zs, x0, P0, Q, R, fx=f, FJ=F_j, hx=h, HJ=H_j, residual=residual_z) -> Estimate:
    """filterpy's ``ExtendedKalmanFilter`` over the measurements zs.

    Predict: x̂⁻ = f(x̂⁺), P⁻ = F_j P⁺ F_jᵀ + Q with F_j = ∂f/∂x at x̂⁺. Update: the Kalman
    update of ``06_kalman`` with H replaced by H_j = ∂h/∂x at x̂⁻ and the innovation z − h(x̂⁻)
    (``residual``; wrapped for bearings). With linear f and h it *is* the Kalman filter.

    Parameters
    ----------
    zs : (n, dim_z) measurements; x0, P0 : initial mean and covariance; Q, R : noise covariances
    fx, FJ, hx, HJ : the model and its Jacobians (default: the range-bearing model)
    residual : z − h(x) for this measurement space
    """
    from filterpy.kalman import ExtendedKalmanFilter

    x0 = np.asarray(x0, dtype=float)
    zs = np.asarray(zs, dtype=float)
    ekf = ExtendedKalmanFilter(dim_x=x0.size, dim_z=zs.shape[1])
    ekf.x, ekf.P = x0.copy(), np.asarray(P0, dtype=float).copy()
    ekf.Q, ekf.R = np.asarray(Q, dtype=float), np.asarray(R, dtype=float)
    xs, Ps = [], []
    for z in zs:
        x_prev = ekf.x.copy()
        ekf.F = FJ(x_prev)
        ekf.predict()                 # P⁻ = F_j P Fᵀ_j + Q (and x = F_j x, replaced next line)
        ekf.x = fx(x_prev)            # x̂⁻ = f(x̂⁺): the non-linear prediction
        ekf.update(z, HJ, hx, residual=residual)
        xs.append(np.asarray(ekf.x, dtype=float).ravel().copy()); Ps.append(ekf.P.copy())
    return Estimate("EKF", np.array(xs), np.array(Ps))


def _mean_z(sigmas, Wm):
    """Weighted mean of range-bearing sigma points: the bearing as a circular mean."""
    r = Wm @ sigmas[:, 0]
    th = np.arctan2(Wm @ np.sin(sigmas[:, 1]), Wm @ np.cos(sigmas[:, 1]))
    return np.array([r, th])


def run_ukf(zs, x0, P0, Q, R, fx=f, hx=h, alpha: float = 0.3, beta: float = 2.0,
            kappa: float = 0.0, residual=residual_z, z_mean=_mean_z) -> Estimate:
    """filterpy's ``UnscentedKalmanFilter`` with ``MerweScaledSigmaPoints(alpha, beta, kappa)``.

    No Jacobians: 2n + 1 sigma points of the belief are pushed through f (predict) and h
    (update) and a Gaussian is refitted to them (:func:`unscented_transform`).
    """
    from filterpy.kalman import MerweScaledSigmaPoints, UnscentedKalmanFilter

    x0 = np.asarray(x0, dtype=float)
    zs = np.asarray(zs, dtype=float)
    points = MerweScaledSigmaPoints(x0.size, alpha=alpha, beta=beta, kappa=kappa)
    # fx carries its own time step, so filterpy's dt is only passed through
    ukf = UnscentedKalmanFilter(dim_x=x0.size, dim_z=zs.shape[1], dt=1.0,
                                fx=lambda x, dt: fx(x), hx=hx, points=points,
                                z_mean_fn=z_mean, residual_z=residual)
    ukf.x, ukf.P = x0.copy(), np.asarray(P0, dtype=float).copy()
    ukf.Q, ukf.R = np.asarray(Q, dtype=float), np.asarray(R, dtype=float)
    xs, Ps = [], []
    for z in zs:
        ukf.predict()
        ukf.update(z)
        xs.append(ukf.x.copy()); Ps.append(ukf.P.copy())
    return Estimate("UKF", np.array(xs), np.array(Ps))


def unscented_transform(m, P, g, alpha: float = 0.3, beta: float = 2.0, kappa: float = 0.0):
    """Mean and covariance of g(x) for x ~ N(m, P), by the scaled sigma points (Van der Merwe).

    Returns ``(mean, cov, sigmas, Y)``: the 2n + 1 sigma points ``sigmas`` (filterpy's
    ``MerweScaledSigmaPoints``), their images ``Y = g(sigmas)``, and the weighted mean and
    covariance of the images (filterpy's ``unscented_transform``). Exact for an affine g.
    """
    from filterpy.kalman import MerweScaledSigmaPoints
    from filterpy.kalman import unscented_transform as ut

    m = np.atleast_1d(np.asarray(m, dtype=float))
    points = MerweScaledSigmaPoints(m.size, alpha=alpha, beta=beta, kappa=kappa)
    sigmas = points.sigma_points(m, np.atleast_2d(np.asarray(P, dtype=float)))
    Y = np.array([np.atleast_1d(g(s)) for s in sigmas], dtype=float)
    mean, cov = ut(Y, points.Wm, points.Wc)
    return mean, cov, sigmas, Y


def _sqrt_psd(A) -> np.ndarray:
    """L with L Lᵀ = A for a symmetric positive semi-definite A (Q of :func:`Q_cv` is singular)."""
    lam, V = np.linalg.eigh(np.asarray(A, dtype=float))
    return V * np.sqrt(np.clip(lam, 0.0, None))


def run_particle_filter(zs, x0, P0, Q, R, rng: np.random.Generator, n_particles: int = 2000,
                        fx=f, hx=h, residual=residual_z, resampler: str = "systematic",
                        ess_fraction: float = 0.5) -> Estimate:
    """A bootstrap particle filter (chapter ``02_particle_filters``) on the same model.

    Particles start from N(x0, P0); each step they move by f plus a draw of N(0, Q), are
    weighted by the Gaussian likelihood N(z; h(x), R) of the measurement, and are resampled
    (``trackbook.filters.particle.RESAMPLERS[resampler]``) when the effective sample size falls
    below ``ess_fraction`` · N. The estimate is the weighted mean and covariance.
    """
    if not isinstance(rng, np.random.Generator):
        raise TypeError("run_particle_filter needs a numpy.random.Generator.")
    if resampler not in RESAMPLERS:
        raise ValueError(f"unknown resampler {resampler!r}; choose one of {sorted(RESAMPLERS)}.")
    x0 = np.asarray(x0, dtype=float)
    n = int(n_particles)
    L0, Lq = _sqrt_psd(P0), _sqrt_psd(Q)
    R_inv = np.linalg.inv(np.asarray(R, dtype=float))
    X = x0 + rng.standard_normal((n, x0.size)) @ L0.T
    w = np.full(n, 1.0 / n)
    xs, Ps = [], []
    for z in np.asarray(zs, dtype=float):
        X = fx(X) + rng.standard_normal(X.shape) @ Lq.T                      # predict
        d = residual(z, hx(X))                                              # (n, dim_z)
        loglik = -0.5 * np.einsum("ni,ij,nj->n", d, R_inv, d)
        w, informative = normalize_weights(w * np.exp(loglik - loglik.max()))  # update
        mean = weighted_mean(X, w)
        xs.append(mean)
        Ps.append((X - mean).T @ ((X - mean) * w[:, None]))
        if not informative or effective_sample_size(w) < ess_fraction * n:
            X = X[RESAMPLERS[resampler](w, rng)]
            w = np.full(n, 1.0 / n)
    return Estimate(f"particle filter (N={n})", np.array(xs), np.array(Ps))


def compare(truth, zs, rng: np.random.Generator, q: float = 0.01, sigma_r: float = 0.2,
            sigma_theta: float = 0.2, x0_error=(20.0, 20.0, 0.5, 0.5), p0=(400.0, 400.0, 1.0, 1.0),
            n_particles=10000, sensor=SENSOR) -> dict:
    """The four filters on one simulated track, all started from the same wrong guess.

    Every filter starts at the true initial state plus ``x0_error``, with P0 = diag(p0), and
    knows the true Q and R. ``n_particles`` may be a list: one particle filter per size, run
    one after the other from ``rng``. Returns ``{name: Estimate}`` in the order KF, EKF, UKF,
    particle filter(s); score them with :func:`position_rmse`.
    """
    truth = np.asarray(truth, dtype=float)
    Q, R = Q_cv(q), np.diag([sigma_r ** 2, sigma_theta ** 2])
    # the guess for the state before the first step: one step back from the first true state
    x0 = np.linalg.solve(F_cv(), truth[0]) + np.asarray(x0_error, dtype=float)
    P0 = np.diag(np.asarray(p0, dtype=float))
    hs = lambda x: h(x, sensor)
    runs = [run_kf(zs, x0, P0, Q, sigma_r, sigma_theta, sensor),
            run_ekf(zs, x0, P0, Q, R, hx=hs, HJ=lambda x: H_j(x, sensor)),
            run_ukf(zs, x0, P0, Q, R, hx=hs)]
    runs += [run_particle_filter(zs, x0, P0, Q, R, rng, n_particles=int(n), hx=hs)
             for n in np.atleast_1d(n_particles)]
    return {e.name: e for e in runs}
