"""Importance weights with a proposal: the bootstrap case, and the optimal proposal of a 1-D
linear-Gaussian model against the Kalman posterior."""
import numpy as np
import pytest
from scipy.stats import multivariate_normal, norm

from trackbook.filters.importance_sampling import (bootstrap_weights, gaussian_log_density,
                                                   importance_weights, normalize_log_weights,
                                                   optimal_gaussian_proposal)
from trackbook.filters.particle import effective_sample_size


def test_with_the_transition_as_proposal_the_weights_are_the_normalised_likelihoods():
    rng = np.random.default_rng(31)
    N = 500
    F = np.array([[1.0, 1.0], [0.0, 1.0]])
    Q = np.array([[0.5, 0.1], [0.1, 0.3]])
    x_prev = rng.normal(size=(N, 2))
    x = x_prev @ F.T + rng.multivariate_normal(np.zeros(2), Q, N)        # drawn from q = p(x|x_prev)
    z = 0.8
    lik = norm.pdf(z, loc=x[:, 0], scale=0.7)                            # p(z|x), z = x₀ + v
    log_trans = np.array([multivariate_normal(F @ a, Q).logpdf(b) for a, b in zip(x_prev, x)])
    w = importance_weights(norm.logpdf(z, x[:, 0], 0.7), log_trans, log_trans)
    np.testing.assert_allclose(w, lik / lik.sum(), rtol=1e-10)
    np.testing.assert_allclose(bootstrap_weights(np.log(lik)), lik / lik.sum(), rtol=1e-10)
    # earlier weights multiply in
    w_prev = rng.uniform(0.1, 1.0, N)
    np.testing.assert_allclose(bootstrap_weights(np.log(lik), w_prev),
                               w_prev * lik / np.sum(w_prev * lik), rtol=1e-10)


def test_weights_by_hand_and_far_off_particles_do_not_underflow():
    # p(z|x) = (1, 2), p(x|x_prev) = (1, 1), q = (2, 1): w ∝ (0.5, 2) -> (0.2, 0.8)
    w = importance_weights(np.log([1.0, 2.0]), np.log([1.0, 1.0]), np.log([2.0, 1.0]))
    np.testing.assert_allclose(w, [0.2, 0.8])
    # log-weights of −2000 and −2001 would be 0 and 0 as densities; their ratio is e
    np.testing.assert_allclose(normalize_log_weights([-2000.0, -2001.0]),
                               [1 / (1 + np.exp(-1)), np.exp(-1) / (1 + np.exp(-1))])


def test_gaussian_log_density_equals_scipy():
    rng = np.random.default_rng(2)
    x, m = rng.normal(size=(50, 3)), rng.normal(size=(50, 3))
    C = np.array([[2.0, 0.3, 0.0], [0.3, 1.0, 0.2], [0.0, 0.2, 0.5]])
    ref = [multivariate_normal(mi, C).logpdf(xi) for xi, mi in zip(x, m)]
    np.testing.assert_allclose(gaussian_log_density(x, m, C), ref, rtol=1e-12)
    np.testing.assert_allclose(gaussian_log_density(x[:, 0], 0.5, 2.0),
                               norm.logpdf(x[:, 0], 0.5, np.sqrt(2.0)), rtol=1e-12)


# the 1-D model: x_k = F x_{k-1} + w, w ~ N(0, Q); z = H x_k + v, v ~ N(0, R);
# prior x_{k-1} ~ N(m0, P0); one measurement z
F, Q, H, R, M0, P0, Z = 0.9, 0.5, 1.0, 0.25, 1.0, 2.0, 3.0


def kalman_posterior():
    """The Kalman filter's x̂⁺ and P⁺ for the model above, written out."""
    x_prior, P_prior = F * M0, F * F * P0 + Q
    K = P_prior * H / (H * P_prior * H + R)
    return x_prior + K * (Z - H * x_prior), (1 - K * H) * P_prior


def weighted_particles(rng, n, proposal):
    x_prev = rng.normal(M0, np.sqrt(P0), n)
    log_trans = lambda x: norm.logpdf(x, F * x_prev, np.sqrt(Q))
    log_lik = lambda x: norm.logpdf(Z, H * x, np.sqrt(R))
    if proposal == "optimal":
        mean, cov, S = optimal_gaussian_proposal(x_prev[:, None], [Z], F, Q, H, R)
        x = mean[:, 0] + np.sqrt(cov[0, 0]) * rng.standard_normal(n)
        w = importance_weights(log_lik(x), log_trans(x), norm.logpdf(x, mean[:, 0],
                                                                     np.sqrt(cov[0, 0])))
    else:
        x = F * x_prev + np.sqrt(Q) * rng.standard_normal(n)
        w = bootstrap_weights(log_lik(x))
    return x_prev, x, w


def test_optimal_proposal_weighted_mean_is_the_kalman_posterior_mean():
    # N = 200 000 particles from np.random.default_rng(41). The self-normalised estimator
    # μ̂ = Σ wᵢ xᵢ has standard error √(Σ wᵢ² (xᵢ − μ̂)²) (delta method), computed here; the
    # Kalman mean must lie within 4 of them.
    m_post, P_post = kalman_posterior()
    x_prev, x, w = weighted_particles(np.random.default_rng(41), 200_000, "optimal")
    mu_hat = w @ x
    se = np.sqrt(np.sum(w ** 2 * (x - mu_hat) ** 2))
    assert se < 0.01 * np.sqrt(P_post)                       # the check has teeth
    assert abs(mu_hat - m_post) < 4 * se
    # the optimal proposal's weight does not depend on x: it is p(z | x_prev) = N(z; HF x_prev, S)
    S = H * Q * H + R
    ref = norm.pdf(Z, H * F * x_prev, np.sqrt(S))
    np.testing.assert_allclose(w, ref / ref.sum(), rtol=1e-9)


def test_the_optimal_proposal_wastes_fewer_particles_than_the_bootstrap():
    n = 20_000
    _, _, w_opt = weighted_particles(np.random.default_rng(42), n, "optimal")
    _, _, w_boot = weighted_particles(np.random.default_rng(42), n, "bootstrap")
    assert effective_sample_size(w_opt) > effective_sample_size(w_boot)


def test_optimal_proposal_is_the_kalman_update_of_the_point_prediction():
    # mean = F x_prev + K (z − H F x_prev), cov = (1 − K H) Q with K = Q H / (H Q H + R),
    # which is also (1/Q + H²/R)⁻¹ (information form)
    mean, cov, S = optimal_gaussian_proposal(np.array([[2.0]]), [Z], F, Q, H, R)
    K = Q * H / (H * Q * H + R)
    assert mean[0, 0] == pytest.approx(F * 2.0 + K * (Z - H * F * 2.0))
    assert cov[0, 0] == pytest.approx(1 / (1 / Q + H * H / R))
    assert S[0, 0] == pytest.approx(H * Q * H + R)


def test_optimal_proposal_in_two_dimensions_equals_filterpys_kalman_update():
    # the optimal proposal of each particle is filterpy's Kalman update of the prediction
    # F x_prev with prior covariance Q, and the weight it leaves, log N(z; H F x_prev, S),
    # is filterpy's log-likelihood of that update
    kalman = pytest.importorskip("filterpy.kalman")
    F = np.array([[1.0, 1.0], [0.0, 1.0]])
    Q = np.array([[0.5, 0.1], [0.1, 0.3]])
    H = np.array([[1.0, 0.0], [0.3, 1.0]])
    R = np.array([[0.2, 0.05], [0.05, 0.4]])
    x_prev = np.random.default_rng(43).normal(size=(4, 2))
    z = np.array([2.5, -0.5])
    mean, cov, S = optimal_gaussian_proposal(x_prev, z, F, Q, H, R)
    for i, x in enumerate(x_prev):
        kf = kalman.KalmanFilter(dim_x=2, dim_z=2)
        kf.x, kf.P, kf.H, kf.R = F @ x, Q.copy(), H, R
        kf.update(z)
        np.testing.assert_allclose(mean[i], kf.x, rtol=1e-12)
        np.testing.assert_allclose(cov, kf.P, rtol=1e-12)
        np.testing.assert_allclose(S, kf.S, rtol=1e-12)
        assert gaussian_log_density(z[None, :], H @ F @ x, S)[0] == pytest.approx(
            kf.log_likelihood, rel=1e-12)


def test_bad_input_names_the_problem():
    with pytest.raises(ValueError, match="one value per particle"):
        importance_weights(np.zeros(3), np.zeros(3), np.zeros(2))
    with pytest.raises(ValueError, match="zero weight"):
        bootstrap_weights([-np.inf, -np.inf])
    with pytest.raises(ValueError, match="NaN"):
        bootstrap_weights([0.0, np.nan])
    with pytest.raises(ValueError, match="weights_prev"):
        bootstrap_weights([0.0, 0.0], weights_prev=[1.0, -1.0])
