"""Van der Merwe's scaled sigma points: by hand, against filterpy, and the book's UKF uses them."""
import numpy as np
import pytest

from trackbook.filters import nonlinear as nl
from trackbook.filters.sigma_points import (merwe_scaled_lambda, merwe_scaled_sigma_points,
                                            merwe_scaled_weights)

filterpy = pytest.importorskip("filterpy.kalman")


def random_spd(rng, n):
    L = rng.normal(size=(n, n))
    return L @ L.T + 0.1 * np.eye(n)


def test_one_dimension_by_hand():
    # n = 1, α = 1, β = 0, κ = 2: λ = 1·3 − 1 = 2, n + λ = 3; points x, x ± √(3P);
    # Wm₀ = 2/3, Wc₀ = 2/3 + 1 − 1 + 0 = 2/3, the others 1/6
    sigmas, Wm, Wc = merwe_scaled_sigma_points(5.0, 4.0, alpha=1.0, beta=0.0, kappa=2.0)
    np.testing.assert_allclose(sigmas.ravel(), [5.0, 5.0 + np.sqrt(12.0), 5.0 - np.sqrt(12.0)])
    np.testing.assert_allclose(Wm, [2 / 3, 1 / 6, 1 / 6])
    np.testing.assert_allclose(Wc, [2 / 3, 1 / 6, 1 / 6])
    # n = 2, α = 0.5, β = 2, κ = 1: λ = 0.25·3 − 2 = −1.25, n + λ = 0.75
    # Wm₀ = −1.25/0.75 = −5/3, Wc₀ = −5/3 + 1 − 0.25 + 2 = 13/12, Wᵢ = 1/1.5 = 2/3
    assert merwe_scaled_lambda(2, 0.5, 1.0) == pytest.approx(-1.25)
    Wm, Wc = merwe_scaled_weights(2, alpha=0.5, beta=2.0, kappa=1.0)
    np.testing.assert_allclose(Wm, [-5 / 3] + [2 / 3] * 4)
    np.testing.assert_allclose(Wc, [13 / 12] + [2 / 3] * 4)


@pytest.mark.parametrize("n, alpha, beta, kappa", [(1, 0.1, 2.0, 0.0), (2, 0.3, 2.0, 0.0),
                                                   (4, 1e-3, 2.0, 0.0), (3, 1.0, 0.0, 0.0),
                                                   (5, 0.5, 1.0, -2.0), (4, 0.8, 2.0, 3 - 4)])
def test_equals_filterpy_merwe_scaled_sigma_points(n, alpha, beta, kappa):
    rng = np.random.default_rng(100 + n)
    x, P = rng.normal(size=n) * 10, random_spd(rng, n)
    sigmas, Wm, Wc = merwe_scaled_sigma_points(x, P, alpha, beta, kappa)
    ref = filterpy.MerweScaledSigmaPoints(n, alpha=alpha, beta=beta, kappa=kappa)
    np.testing.assert_allclose(sigmas, ref.sigma_points(x, P), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(Wm, ref.Wm, rtol=1e-12, atol=0)
    np.testing.assert_allclose(Wc, ref.Wc, rtol=1e-12, atol=0)


@pytest.mark.parametrize("n, alpha, kappa", [(1, 0.5, 0.0), (3, 0.3, 0.0), (4, 1.0, 1.0)])
def test_the_points_carry_the_mean_and_covariance(n, alpha, kappa):
    # Σ Wmᵢ χᵢ = x and Σ Wcᵢ (χᵢ − x)(χᵢ − x)ᵀ = P (χ₀ − x = 0, so β does not matter);
    # Wm sums to 1 and Wc to 2 − α² + β
    rng = np.random.default_rng(n)
    x, P = rng.normal(size=n), random_spd(rng, n)
    sigmas, Wm, Wc = merwe_scaled_sigma_points(x, P, alpha, 2.0, kappa)
    d = sigmas - x
    np.testing.assert_allclose(Wm @ sigmas, x, atol=1e-9)
    np.testing.assert_allclose(d.T @ (d * Wc[:, None]), P, atol=1e-9)
    assert Wm.sum() == pytest.approx(1.0) and Wc.sum() == pytest.approx(2 - alpha ** 2 + 2.0)


def test_the_books_ukf_uses_these_points_and_weights():
    # nonlinear.unscented_transform and run_ukf take filterpy's MerweScaledSigmaPoints with
    # α = 0.3, β = 2, κ = 0: the same points, and a mean and covariance weighted by our Wm, Wc
    m, P = np.array([10.0, 0.2]), np.diag([0.04, 0.09])
    g = lambda z: np.array([z[0] * np.cos(z[1]), z[0] * np.sin(z[1])])
    mean, cov, sigmas_nl, Y = nl.unscented_transform(m, P, g)
    sigmas, Wm, Wc = merwe_scaled_sigma_points(m, P, alpha=0.3, beta=2.0, kappa=0.0)
    np.testing.assert_allclose(sigmas_nl, sigmas, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(mean, Wm @ Y, rtol=1e-12)
    d = Y - Wm @ Y
    np.testing.assert_allclose(cov, d.T @ (d * Wc[:, None]), rtol=1e-9, atol=1e-12)


def test_bad_input_names_the_fix():
    with pytest.raises(ValueError, match="kappa"):
        merwe_scaled_weights(3, alpha=0.5, beta=2.0, kappa=-3.0)
    with pytest.raises(ValueError, match="alpha must be positive"):
        merwe_scaled_weights(3, alpha=0.0, beta=2.0, kappa=0.0)
    with pytest.raises(ValueError, match=r"P must be \(2, 2\)"):
        merwe_scaled_sigma_points([0.0, 0.0], np.eye(3), 0.5, 2.0, 0.0)
    with pytest.raises(ValueError, match="positive definite"):
        merwe_scaled_sigma_points([0.0, 0.0], -np.eye(2), 0.5, 2.0, 0.0)
