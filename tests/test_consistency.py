"""NEES and NIS consistency tests (Bar-Shalom, Li and Kirubarajan 2001), by hand, from χ² tables,
and on Monte-Carlo runs of the book's Kalman filter on a constant-velocity target."""
import numpy as np
import pytest

from trackbook.filters.consistency import (average_over_runs, chi2_acceptance_interval,
                                           consistency_test, is_consistent, nees, nis)
from trackbook.filters.kalman import KalmanFilter
from trackbook.filters.linear_gaussian import (constant_velocity_model, run_kalman_filter,
                                               simulate_linear_gaussian, sqrt_psd)


def test_nees_and_nis_by_hand():
    # e = (1, 2), P = diag(1, 4): 1²/1 + 2²/4 = 2
    assert float(nees([1.0, 2.0], [0.0, 0.0], np.diag([1.0, 4.0]))) == pytest.approx(2.0)
    # y = (1, 1), S = [[2, 1], [1, 2]]: S⁻¹ = [[2, −1], [−1, 2]] / 3, yᵀS⁻¹y = 2/3
    assert float(nis([1.0, 1.0], [[2.0, 1.0], [1.0, 2.0]])) == pytest.approx(2 / 3)
    # a stack (2 runs × 3 steps) keeps its leading shape; the error x − x̂ is what counts
    x = np.zeros((2, 3, 2))
    x_hat = np.ones((2, 3, 2))
    P = np.broadcast_to(np.diag([1.0, 0.5]), (2, 3, 2, 2))
    np.testing.assert_allclose(nees(x, x_hat, P), np.full((2, 3), 3.0))


def test_chi2_acceptance_interval_matches_the_printed_tables():
    # χ²₁: 2.5 % point 0.000982, 97.5 % point 5.024 (any χ² table)
    lo, hi = chi2_acceptance_interval(1, 1, 0.95)
    assert lo == pytest.approx(0.000982, abs=1e-6) and hi == pytest.approx(5.024, abs=1e-3)
    # Bar-Shalom's Monte-Carlo example: n_x = 2, N = 50 runs -> χ²₁₀₀ points 74.2 and 129.6,
    # divided by 50: [1.5, 2.6]
    lo, hi = chi2_acceptance_interval(2, 50, 0.95)
    assert lo == pytest.approx(74.222 / 50, abs=1e-3) and hi == pytest.approx(129.561 / 50, abs=1e-3)
    # χ²₁₀ at 5 % and 95 %: 3.940 and 18.307 (a 90 % interval)
    lo, hi = chi2_acceptance_interval(5, 2, 0.90)
    assert lo == pytest.approx(3.940 / 2, abs=1e-3) and hi == pytest.approx(18.307 / 2, abs=1e-3)


def test_verdicts_from_the_interval():
    lo, hi = chi2_acceptance_interval(2, 4)
    assert consistency_test([2.0] * 4, 2).verdict == "consistent"
    assert consistency_test([hi + 0.01] * 4, 2).verdict == "overconfident"
    assert consistency_test([lo - 0.01] * 4, 2).verdict == "underconfident"
    assert is_consistent([2.0] * 4, 2) and not is_consistent([hi + 0.01] * 4, 2)
    t = consistency_test(np.array([[1.0, 3.0], [2.0, 2.0]]), 2)
    assert (t.average, t.n_samples, t.lower, t.upper) == (2.0, 4, lo, hi)
    np.testing.assert_allclose(average_over_runs([[1.0, 4.0], [3.0, 0.0]]), [2.0, 2.0])


def test_bad_input_names_the_problem():
    with pytest.raises(ValueError, match="confidence"):
        chi2_acceptance_interval(2, 10, 95)
    with pytest.raises(ValueError, match="covariances of shape"):
        nees(np.zeros(3), np.zeros(3), np.eye(2))
    with pytest.raises(ValueError, match="finite"):
        consistency_test([1.0, np.nan], 2)
    with pytest.raises(ValueError, match="runs, steps"):
        average_over_runs([1.0, 2.0])


# --------------------------------------------------------------------------- Monte Carlo

M_RUNS, N_STEPS, Q_TRUE, R_TRUE = 100, 40, 0.1, 4.0
M0, P0 = np.array([0.0, 0.0, 3.0, 1.0]), np.diag([4.0, 4.0, 1.0, 1.0])


def monte_carlo(q_filter: float, rng_seed: int = 11):
    """NEES (M, K) and NIS (M, K) of the Kalman filter with Q = q_filter·G Gᵀ on M_RUNS
    simulated constant-velocity tracks with Q = Q_TRUE·G Gᵀ and R = R_TRUE·I.

    Every run draws its initial state from N(M0, P0), the belief the filter starts with, so a
    filter with the true Q and R is consistent from the first step on."""
    rng = np.random.default_rng(rng_seed)
    F, Q, H = constant_velocity_model(Q_TRUE)
    R = R_TRUE * np.eye(2)
    eps_x, eps_z = [], []
    for _ in range(M_RUNS):
        x0 = M0 + sqrt_psd(P0) @ rng.standard_normal(4)
        truth, zs = simulate_linear_gaussian(rng, F, Q, H, R, x0, N_STEPS)
        kf = KalmanFilter(4, 2)
        kf.F, kf.H, kf.R = F, H, R
        kf.Q = constant_velocity_model(q_filter)[1]
        kf.x, kf.P = M0.copy(), P0.copy()
        run = run_kalman_filter(kf, zs)
        eps_x.append(nees(truth, run.x, run.P))
        eps_z.append(nis(run.y, run.S))
    return np.array(eps_x), np.array(eps_z)


@pytest.fixture(scope="module")
def true_model():
    return monte_carlo(Q_TRUE)


def test_with_the_true_q_and_r_the_averaged_nees_lies_inside_the_95_interval(true_model):
    # M = 100 runs from np.random.default_rng(11); 40 steps. At each step the average over the
    # runs is 1/M χ²(4M) if the filter is consistent: inside [r1, r2] with probability 0.95.
    eps_x, _ = true_model
    lo, hi = chi2_acceptance_interval(4, M_RUNS)
    avg = average_over_runs(eps_x)
    assert lo <= avg[-1] <= hi                                  # at the last step
    assert np.mean((avg >= lo) & (avg <= hi)) >= 0.9            # and at nearly every step
    assert is_consistent(eps_x[:, -1], 4)
    assert avg.mean() == pytest.approx(4.0, rel=0.1)            # E[NEES] = n_x


def test_with_the_true_q_and_r_the_nis_lies_inside_the_95_interval(true_model):
    # the residuals of a consistent filter are white: all M × K values pool
    _, eps_z = true_model
    t = consistency_test(eps_z, 2)
    assert t.n_samples == M_RUNS * N_STEPS and t.verdict == "consistent"
    # Bar-Shalom's single-run test: each run's time-averaged NIS against χ²(K n_z)/K; a
    # consistent filter passes it in about 95 % of the runs
    passed = [is_consistent(run, 2) for run in eps_z]
    assert 0.9 <= np.mean(passed) < 1.0


def test_with_q_ten_times_too_small_the_filter_is_overconfident():
    eps_x, eps_z = monte_carlo(Q_TRUE / 10)
    lo, hi = chi2_acceptance_interval(4, M_RUNS)
    avg = average_over_runs(eps_x)
    assert avg[-1] > hi
    assert consistency_test(eps_x[:, -1], 4).verdict == "overconfident"
    assert consistency_test(eps_z, 2).verdict == "overconfident"
    assert np.mean([is_consistent(run, 2) for run in eps_z]) < 0.5     # most single runs fail


def test_with_q_ten_times_too_large_the_filter_is_underconfident():
    eps_x, _ = monte_carlo(Q_TRUE * 10)
    assert consistency_test(eps_x[:, -1], 4).verdict == "underconfident"
