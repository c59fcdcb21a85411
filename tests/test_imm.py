"""The interacting multiple model estimator: by hand, against filterpy's IMMEstimator, and on a
target that turns."""
import numpy as np
import pytest

from trackbook.filters.imm import (InteractingMultipleModel, combine_estimates,
                                   gaussian_likelihood, imm_versus_constant_velocity,
                                   mix_estimates, mixing_probabilities, mode_probability_update,
                                   run_imm, simulate_turning_target)
from trackbook.filters.kalman import KalmanFilter
from trackbook.filters.linear_gaussian import constant_velocity_model

filterpy = pytest.importorskip("filterpy.kalman")


def test_mixing_probabilities_by_hand():
    # μ = (0.5, 0.5), M = [[0.9, 0.1], [0.2, 0.8]]:
    # c̄₁ = 0.9·0.5 + 0.2·0.5 = 0.55, c̄₂ = 0.1·0.5 + 0.8·0.5 = 0.45
    # ω[0, 0] = 0.45/0.55, ω[1, 0] = 0.10/0.55, ω[0, 1] = 0.05/0.45, ω[1, 1] = 0.40/0.45
    cbar, omega = mixing_probabilities([0.5, 0.5], [[0.9, 0.1], [0.2, 0.8]])
    np.testing.assert_allclose(cbar, [0.55, 0.45])
    np.testing.assert_allclose(omega, [[0.45 / 0.55, 0.05 / 0.45], [0.10 / 0.55, 0.40 / 0.45]])


def test_mixing_and_combination_by_hand():
    # two 1-D modes at 0 and 2, variance 1 each, equal weight: mean 1, variance 1 + 1 = 2
    x, P = combine_estimates([[0.0], [2.0]], [[[1.0]], [[1.0]]], [0.5, 0.5])
    assert x.tolist() == [1.0] and P.tolist() == [[2.0]]
    # mixing with ω = [[1, 0.25], [0, 0.75]]: filter 1 keeps its own, filter 2 gets
    # 0.25·0 + 0.75·2 = 1.5 and 0.25(1 + 1.5²) + 0.75(1 + 0.5²) = 1.75
    x0, P0 = mix_estimates([[0.0], [2.0]], [[[1.0]], [[1.0]]], [[1.0, 0.25], [0.0, 0.75]])
    np.testing.assert_allclose(x0, [[0.0], [1.5]])
    np.testing.assert_allclose(P0, [[[1.0]], [[1.75]]])
    # mode probabilities: c̄ = (0.5, 0.5), Λ = (1, 3) -> (0.25, 0.75)
    np.testing.assert_allclose(mode_probability_update([0.5, 0.5], [1.0, 3.0]), [0.25, 0.75])


def test_gaussian_likelihood_equals_scipy():
    from scipy.stats import multivariate_normal
    y, S = np.array([0.7, -1.2]), np.array([[2.0, 0.4], [0.4, 1.5]])
    assert gaussian_likelihood(y, S) == pytest.approx(multivariate_normal(cov=S).pdf(y),
                                                      rel=1e-12)
    assert gaussian_likelihood([1e3], [[1e-3]]) > 0          # underflow floored, not zero


def mode_matrices():
    """Three modes on [p_x, p_y, v_x, v_y]: quiet CV, manoeuvring CV, and a halting model
    (velocity decays) — with a transition matrix that is not symmetric, so that reading it
    transposed would show."""
    F1, Q1, H = constant_velocity_model(0.01)
    F2, Q2, _ = constant_velocity_model(3.0)
    F3 = F1.copy()
    F3[2, 2] = F3[3, 3] = 0.5
    Q3 = np.diag([0.5, 0.5, 0.2, 0.2])
    R = np.array([[4.0, 0.5], [0.5, 3.0]])
    M = np.array([[0.90, 0.07, 0.03], [0.15, 0.80, 0.05], [0.20, 0.10, 0.70]])
    return [(F1, Q1), (F2, Q2), (F3, Q3)], H, R, M


def test_equals_filterpy_imm_estimator_over_a_manoeuvre():
    truth, zs = simulate_turning_target(np.random.default_rng(4), n_straight=20, n_turn=10,
                                        n_after=20)
    models, H, R, M = mode_matrices()
    mu0 = np.array([0.6, 0.3, 0.1])
    x0, P0 = np.array([0.0, 0.0, 4.0, 0.5]), np.diag([9.0, 9.0, 4.0, 4.0])
    ours, ref = [], []
    for F, Q in models:
        a = KalmanFilter(4, 2)
        b = filterpy.KalmanFilter(dim_x=4, dim_z=2)
        for kf in (a, b):
            kf.F, kf.Q, kf.H, kf.R = F.copy(), Q.copy(), H.copy(), R.copy()
            kf.x, kf.P = x0.copy(), P0.copy()
        ours.append(a); ref.append(b)
    imm = InteractingMultipleModel(ours, mu0, M)
    oracle = filterpy.IMMEstimator(ref, mu0.copy(), M.copy())
    close = dict(rtol=1e-9, atol=1e-9)
    turn_mu = []
    for z in zs:
        imm.predict(); oracle.predict()
        np.testing.assert_allclose(imm.x, oracle.x, **close)          # combined prior
        np.testing.assert_allclose(imm.P, oracle.P, **close)
        imm.update(z); oracle.update(z)
        np.testing.assert_allclose(imm.x, oracle.x, **close)
        np.testing.assert_allclose(imm.P, oracle.P, **close)
        np.testing.assert_allclose(imm.mu, oracle.mu, **close)
        np.testing.assert_allclose(imm.likelihood, oracle.likelihood, rtol=1e-9, atol=0)
        np.testing.assert_allclose(imm.omega, oracle.omega, **close)
        for a, b in zip(imm.filters, oracle.filters):
            np.testing.assert_allclose(a.x, b.x, **close)
            np.testing.assert_allclose(a.P, b.P, **close)
        turn_mu.append(imm.mu[1])
    # the run did switch modes: the manoeuvring model won somewhere and lost somewhere
    assert max(turn_mu) > 0.5 > min(turn_mu)


def test_run_imm_records_the_posterior_each_step():
    truth, zs = simulate_turning_target(np.random.default_rng(1), 5, 3, 5)
    models, H, R, M = mode_matrices()

    def bank():
        out = []
        for F, Q in models:
            kf = KalmanFilter(4, 2)
            kf.F, kf.Q, kf.H, kf.R = F, Q, H, R
            kf.x = truth[0].copy()
            out.append(kf)
        return out

    run = run_imm(InteractingMultipleModel(bank(), [1, 1, 1], M), zs)
    imm = InteractingMultipleModel(bank(), [1, 1, 1], M)
    for k, z in enumerate(zs):
        imm.predict(); imm.update(z)
        np.testing.assert_array_equal(run.x[k], imm.x)
        np.testing.assert_array_equal(run.mu[k], imm.mu)
    assert run.P.shape == (13, 4, 4) and np.allclose(run.mu.sum(axis=1), 1.0)


@pytest.mark.parametrize("rng_seed", [0, 1, 2, 3])
def test_imm_beats_a_constant_velocity_filter_tuned_for_the_straight_part(rng_seed):
    # 40 straight steps at 5 px/step, a 0.3 rad/step turn for 10 steps (172°), 30 straight;
    # measurement noise σ = 2 px. The single CV filter has q = 0.01 (right for the straight
    # part); the IMM holds that filter and one with q = 2.
    truth, zs = simulate_turning_target(np.random.default_rng(rng_seed))
    out = imm_versus_constant_velocity(truth, zs)
    assert out["rmse_imm"] < out["rmse_cv"]
    # and the IMM knows when: the manoeuvre mode is likelier in the turn than on the straight
    mu_turn = out["imm"].mu[:, 1]
    assert mu_turn[42:52].mean() > mu_turn[10:38].mean()


def test_simulated_turn_keeps_the_speed_and_turns_by_the_rate():
    truth, zs = simulate_turning_target(np.random.default_rng(0), 3, 4, 2, speed=5.0,
                                        turn_rate=0.25, sigma_z=0.0)
    np.testing.assert_allclose(np.hypot(truth[:, 2], truth[:, 3]), 5.0)
    heading = np.unwrap(np.arctan2(truth[:, 3], truth[:, 2]))
    np.testing.assert_allclose(np.diff(heading), [0, 0, 0.25, 0.25, 0.25, 0.25, 0, 0], atol=1e-12)
    np.testing.assert_allclose(np.diff(truth[:, :2], axis=0), truth[:-1, 2:], atol=1e-12)
    np.testing.assert_array_equal(zs, truth[:, :2])


def test_bad_input_names_the_fix():
    with pytest.raises(ValueError, match="sum to 1"):
        mixing_probabilities([0.5, 0.5], [[0.9, 0.2], [0.2, 0.8]])
    with pytest.raises(ValueError, match=r"must be \(2, 2\)"):
        mixing_probabilities([0.5, 0.5], np.eye(3))
    with pytest.raises(TypeError, match="KalmanFilter"):
        InteractingMultipleModel([KalmanFilter(4, 2)], [1.0], [[1.0]])
    with pytest.raises(ValueError, match="same state size"):
        InteractingMultipleModel([KalmanFilter(4, 2), KalmanFilter(2, 1)], [1, 1], np.eye(2))
