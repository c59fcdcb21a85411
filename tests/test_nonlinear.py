"""The extended and unscented Kalman filters of ``06_kalman``: filterpy, numpy, calculus."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbook.filters import nonlinear as nl

filterpy = pytest.importorskip("filterpy.kalman")


def test_ekf_on_a_linear_model_is_the_kalman_filter_step_by_step():
    # With f(x) = F x and h(x) = H x the Jacobians are F and H: the EKF must be filterpy's
    # KalmanFilter, step by step.
    rng = np.random.default_rng(7)
    F, Q = nl.F_cv(), nl.Q_cv(0.3)
    H = np.array([[1.0, 0, 0, 0], [0, 1.0, 0, 0]])
    R = np.array([[2.0, 0.3], [0.3, 1.0]])
    x0, P0 = np.array([1.0, -2.0, 0.5, 0.1]), np.diag([4.0, 3.0, 1.0, 2.0])
    zs = np.cumsum(rng.normal(1.0, 1.5, (40, 2)), axis=0)
    est = nl.run_ekf(zs, x0, P0, Q, R, fx=lambda x: F @ x, FJ=lambda x: F,
                     hx=lambda x: H @ x, HJ=lambda x: H, residual=np.subtract)
    ref = filterpy.KalmanFilter(dim_x=4, dim_z=2)
    ref.x, ref.P, ref.F, ref.H, ref.Q, ref.R = x0.copy(), P0.copy(), F, H, Q, R
    for k, z in enumerate(zs):
        ref.predict(); ref.update(z)
        np.testing.assert_allclose(est.x[k], ref.x.ravel(), rtol=0, atol=1e-10)
        np.testing.assert_allclose(est.P[k], ref.P, rtol=0, atol=1e-10)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2 ** 31 - 1), st.integers(1, 4), st.integers(1, 3))
def test_unscented_transform_of_an_affine_map_is_exact(seed, n, m):
    # For g(x) = A x + b: mean A m + b and covariance A P Aᵀ, computed here with numpy alone.
    rng = np.random.default_rng(seed)
    A, b = rng.normal(size=(m, n)), rng.normal(size=m)
    L = rng.normal(size=(n, n))
    P = L @ L.T + 0.1 * np.eye(n)
    mu = rng.normal(size=n) * 10
    mean, cov, sigmas, Y = nl.unscented_transform(mu, P, lambda x: A @ x + b)
    assert sigmas.shape == (2 * n + 1, n) and Y.shape == (2 * n + 1, m)
    np.testing.assert_allclose(mean, A @ mu + b, rtol=0, atol=1e-8 * (1 + np.abs(A @ mu).max()))
    np.testing.assert_allclose(cov, A @ P @ A.T, rtol=1e-7, atol=1e-8)


def test_unscented_transform_of_a_nonlinear_map_matches_monte_carlo_better_than_linearisation():
    # Polar -> Cartesian with a vague bearing: the true mean lies inside the arc (closer to the
    # sensor); the linearised mean g(m) does not see that, the sigma points do.
    m, P = np.array([10.0, 0.0]), np.diag([0.04, 0.3 ** 2])
    g = lambda z: np.array([z[0] * np.cos(z[1]), z[0] * np.sin(z[1])])
    mean, _, _, _ = nl.unscented_transform(m, P, g)
    rng = np.random.default_rng(0)
    s = rng.multivariate_normal(m, P, 400_000)
    mc = np.column_stack([s[:, 0] * np.cos(s[:, 1]), s[:, 0] * np.sin(s[:, 1])]).mean(0)
    # E[r cos θ] = r̄ exp(-σ²/2) exactly for θ ~ N(0, σ²)
    assert mc[0] == pytest.approx(10 * np.exp(-0.045), abs=0.01)
    assert abs(mean[0] - mc[0]) < 0.05 < abs(g(m)[0] - mc[0])


@pytest.mark.parametrize("x", [[3.0, 4.0, 1.0, -1.0], [-7.0, 0.5, 0.0, 2.0], [0.2, -9.0, 3.0, 3.0]])
def test_jacobians_equal_central_finite_differences(x):
    x = np.array(x)
    sensor = (1.0, -2.0)
    eps = 1e-6
    num_H = np.column_stack([(nl.h(x + eps * e, sensor) - nl.h(x - eps * e, sensor)) / (2 * eps)
                             for e in np.eye(4)])
    num_F = np.column_stack([(nl.f(x + eps * e) - nl.f(x - eps * e)) / (2 * eps)
                             for e in np.eye(4)])
    np.testing.assert_allclose(nl.H_j(x, sensor), num_H, atol=1e-6)
    np.testing.assert_allclose(nl.F_j(x), num_F, atol=1e-6)


def test_h_by_hand_and_bearing_residual_wraps():
    np.testing.assert_allclose(nl.h([3.0, 4.0, 0, 0]), [5.0, np.arctan2(4, 3)])
    np.testing.assert_allclose(nl.h([[0.0, -2.0, 0, 0]]), [[2.0, -np.pi / 2]])
    d = nl.residual_z([1.0, np.pi - 0.1], [1.0, -np.pi + 0.1])
    np.testing.assert_allclose(d, [0.0, -0.2], atol=1e-12)
    np.testing.assert_allclose(nl.polar_to_xy([2.0, np.pi / 2], (1.0, 1.0)), [1.0, 3.0], atol=1e-12)


def test_same_seed_same_tracks_and_estimates():
    a_truth, a_z = nl.simulate(np.random.default_rng(5), n_steps=20)
    b_truth, b_z = nl.simulate(np.random.default_rng(5), n_steps=20)
    np.testing.assert_array_equal(a_truth, b_truth); np.testing.assert_array_equal(a_z, b_z)
    c_truth, _ = nl.simulate(np.random.default_rng(6), n_steps=20)
    assert not np.allclose(a_truth, c_truth)
    ea = nl.compare(a_truth, a_z, np.random.default_rng(1), n_particles=500)
    eb = nl.compare(b_truth, b_z, np.random.default_rng(1), n_particles=500)
    assert list(ea) == ["KF (converted)", "EKF", "UKF", "particle filter (N=500)"]
    for k in ea:
        np.testing.assert_array_equal(ea[k].x, eb[k].x)
        assert ea[k].x.shape == (20, 4) and ea[k].P.shape == (20, 4, 4)
        assert np.all(np.isfinite(ea[k].x))


def test_simulated_measurements_have_the_stated_noise():
    truth, zs = nl.simulate(np.random.default_rng(2), n_steps=4000, sigma_r=0.5, sigma_theta=0.02)
    d = nl.residual_z(zs, nl.h(truth))
    assert np.std(d[:, 0]) == pytest.approx(0.5, rel=0.05)
    assert np.std(d[:, 1]) == pytest.approx(0.02, rel=0.05)


def test_filters_beat_the_raw_measurements_on_the_default_scenario():
    truth, zs = nl.simulate(np.random.default_rng(0))
    raw = nl.position_rmse(nl.polar_to_xy(zs), truth)
    ests = nl.compare(truth, zs, np.random.default_rng(0), n_particles=2000)
    assert nl.position_rmse(ests["UKF"], truth) < raw


def test_position_rmse_by_hand():
    assert nl.position_rmse(np.array([[3.0, 4.0], [0.0, 0.0]]), np.zeros((2, 4))) == \
        pytest.approx(np.sqrt(12.5))


def test_bad_input_names_the_fix():
    with pytest.raises(TypeError, match="Generator"):
        nl.simulate(0)
    with pytest.raises(ValueError, match="n_steps"):
        nl.simulate(np.random.default_rng(0), n_steps=0)
    with pytest.raises(ValueError, match="resampler"):
        nl.run_particle_filter(np.zeros((1, 2)) + 1, np.ones(4), np.eye(4), np.eye(4), np.eye(2),
                               np.random.default_rng(0), resampler="nope")
