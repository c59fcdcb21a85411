"""The Rauch–Tung–Striebel smoother over the book's Kalman filter, against filterpy's."""
import numpy as np
import pytest

from trackbook.filters.kalman import KalmanFilter, constant_velocity
from trackbook.filters.linear_gaussian import (constant_velocity_model, run_kalman_filter,
                                               simulate_linear_gaussian)
from trackbook.filters.smoother import rts_smoother

filterpy = pytest.importorskip("filterpy.kalman")


def filtered(rng_seed=5, n=60):
    rng = np.random.default_rng(rng_seed)
    F, Q, H = constant_velocity_model(0.2)
    R = np.array([[3.0, 0.5], [0.5, 2.0]])
    truth, zs = simulate_linear_gaussian(rng, F, Q, H, R, [0.0, 0.0, 2.0, -1.0], n)
    kf = KalmanFilter(4, 2)
    kf.F, kf.Q, kf.H, kf.R = F, Q, H, R
    kf.x, kf.P = np.array([1.0, -1.0, 0.0, 0.0]), np.diag([10.0, 10.0, 4.0, 4.0])
    return truth, run_kalman_filter(kf, zs), F, Q


def test_equals_filterpy_rts_smoother_on_the_same_filter_outputs():
    _, run, F, Q = filtered()
    ours = rts_smoother(run.x, run.P, F, Q)
    n = len(run.x)
    ref_fn = filterpy.rts_smoother(run.x.copy(), run.P.copy(), [F] * n, [Q] * n)
    kf = filterpy.KalmanFilter(dim_x=4, dim_z=2)
    kf.F, kf.Q = F, Q
    ref_method = kf.rts_smoother(run.x.copy(), run.P.copy())
    for ref in (ref_fn, ref_method):
        for a, b in zip(ours, ref):            # x, P, smoother gain K, predicted P
            np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9)


def test_time_varying_f_and_q_index_as_filterpys_method():
    # steps of unequal length: F[k], Q[k] take step k − 1 to step k
    rng = np.random.default_rng(8)
    dts = rng.uniform(0.5, 2.0, 30)
    Fs = np.array([constant_velocity_model(0.3, dt)[0] for dt in dts])
    Qs = np.array([constant_velocity_model(0.3, dt)[1] for dt in dts])
    kf = constant_velocity(r=2.0)
    xs, Ps = [], []
    for k, z in enumerate(np.cumsum(rng.normal(1.0, 2.0, (30, 2)), axis=0)):
        kf.F, kf.Q = Fs[k], Qs[k]
        kf.predict(); kf.update(z)
        xs.append(kf.x.copy()); Ps.append(kf.P.copy())
    xs, Ps = np.array(xs), np.array(Ps)
    ours = rts_smoother(xs, Ps, Fs, Qs)
    ref = filterpy.KalmanFilter(dim_x=4, dim_z=2).rts_smoother(xs.copy(), Ps.copy(), Fs, Qs)
    for a, b in zip(ours, ref):
        np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9)


def test_smoothing_never_widens_the_covariance_and_the_last_step_is_the_filters():
    # Pₖˢ = Pₖ − Kₖ (Pₖ₊₁⁻ − Pₖ₊₁ˢ) Kₖᵀ with Pₖ₊₁ˢ ≤ Pₖ₊₁⁻: Pₖ − Pₖˢ is positive semi-definite
    _, run, F, Q = filtered()
    xs, Ps, K, _ = rts_smoother(run.x, run.P, F, Q)
    np.testing.assert_array_equal(xs[-1], run.x[-1])
    np.testing.assert_array_equal(Ps[-1], run.P[-1])
    assert np.all(K[-1] == 0)
    assert min(np.linalg.eigvalsh(run.P[k] - Ps[k]).min() for k in range(len(Ps))) > -1e-9


def test_the_smoothed_track_is_closer_to_the_truth_than_the_filtered_one():
    errs = []
    for s in range(5):
        truth, run, F, Q = filtered(rng_seed=20 + s, n=80)
        xs = rts_smoother(run.x, run.P, F, Q)[0]
        errs.append([np.mean((run.x[:, :2] - truth[:, :2]) ** 2),
                     np.mean((xs[:, :2] - truth[:, :2]) ** 2)])
    errs = np.array(errs)
    assert np.all(errs[:, 1] < errs[:, 0])


def test_bad_shapes_name_what_is_expected():
    with pytest.raises(ValueError, match=r"F must be \(4, 4\) or \(3, 4, 4\)"):
        rts_smoother(np.zeros((3, 4)), np.tile(np.eye(4), (3, 1, 1)), np.eye(2), np.eye(4))
    with pytest.raises(ValueError, match="x must be"):
        rts_smoother(np.zeros((3, 4)), np.tile(np.eye(4), (2, 1, 1)), np.eye(4), np.eye(4))
