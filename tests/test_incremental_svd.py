"""Incremental SVD (eq. 6-7 of Lee et al. 2012 / Ross et al. 2008) against full SVD and
scikit-learn's IncrementalPCA."""

import numpy as np
import pytest
from scipy.linalg import subspace_angles

from trackbook.learning.incremental_svd import IncrementalSVD


def low_rank(rng, d=30, n=60, r=6, noise=0.0):
    return rng.normal(size=(d, r)) @ rng.normal(size=(r, n)) + noise * rng.normal(size=(d, n))


@pytest.mark.parametrize("m", [1, 3])
def test_equals_full_svd_without_forgetting_or_truncation(m):
    rng = np.random.default_rng(0)
    A = low_rank(rng, d=30, n=50, r=8, noise=0.01)        # full rank 30 with noise
    isvd = IncrementalSVD(K=30, forgetting=1.0).fit(A[:, :10])
    for j in range(10, 50, m):
        isvd.partial_fit(A[:, j:j + m])
    U, S, _ = np.linalg.svd(A, full_matrices=False)
    np.testing.assert_allclose(isvd.S, S[:isvd.S.size], rtol=1e-9)
    assert isvd.S.size == 30
    assert np.max(subspace_angles(isvd.U, U)) < 1e-8


def test_rank_deficient_drops_noise_directions():
    rng = np.random.default_rng(1)
    A = low_rank(rng, d=20, n=30, r=4)
    isvd = IncrementalSVD(K=16).fit(A[:, :5])
    for j in range(5, 30):
        isvd.partial_fit(A[:, j])
    assert isvd.U.shape[1] == 4
    U, S, _ = np.linalg.svd(A, full_matrices=False)
    np.testing.assert_allclose(isvd.S, S[:4], rtol=1e-9)
    # every column of A lies in the learned span: zero reconstruction error
    assert np.max(isvd.reconstruction_error(A)) < 1e-9 * np.linalg.norm(A, axis=0).max()


def test_forgetting_equals_svd_of_weighted_columns():
    """With f < 1 and m = 1, after fit(A) and j updates the result is the SVD of the matrix
    whose old columns are scaled by f^(updates since they arrived)."""
    rng = np.random.default_rng(2)
    A = rng.normal(size=(12, 9))
    f = 0.8
    isvd = IncrementalSVD(K=12, forgetting=f).fit(A[:, :4])
    for j in range(4, 9):
        isvd.partial_fit(A[:, j])
    ages = np.r_[np.full(4, 5), np.arange(4, -1, -1)]
    U, S, _ = np.linalg.svd(A * f**ages, full_matrices=False)
    np.testing.assert_allclose(isvd.S, S, rtol=1e-9)
    assert np.max(subspace_angles(isvd.U, U)) < 1e-8


@pytest.mark.parametrize("batch", [1, 5])
def test_centred_agrees_with_sklearn_incremental_pca(batch):
    """Same data, same batches, same truncation K: the same algorithm (Ross et al. with the
    mean update, f = 1), so the subspaces coincide (principal angles ~ 0)."""
    from sklearn.decomposition import IncrementalPCA
    rng = np.random.default_rng(3)
    A = low_rank(rng, d=25, n=80, r=10, noise=0.05) + rng.normal(size=(25, 1)) * 3
    K = 5
    ipca = IncrementalPCA(n_components=K).partial_fit(A[:, :20].T)
    isvd = IncrementalSVD(K=K, forgetting=1.0, centre=True).fit(A[:, :20])
    for j in range(20, 80, batch):
        ipca.partial_fit(A[:, j:j + batch].T)
        isvd.partial_fit(A[:, j:j + batch])
    assert np.max(subspace_angles(isvd.U, ipca.components_.T)) < 1e-8
    np.testing.assert_allclose(isvd.S, ipca.singular_values_, rtol=1e-8)
    np.testing.assert_allclose(isvd.mean, A.mean(axis=1), rtol=1e-10, atol=1e-10)


def test_centred_without_truncation_equals_pca():
    rng = np.random.default_rng(5)
    A = low_rank(rng, d=15, n=40, r=15, noise=0.0) + 2.0
    isvd = IncrementalSVD(K=15, centre=True).fit(A[:, :3])
    for j in range(3, 40):
        isvd.partial_fit(A[:, j])
    Uc, Sc, _ = np.linalg.svd(A - A.mean(axis=1, keepdims=True), full_matrices=False)
    np.testing.assert_allclose(isvd.S, Sc[:isvd.S.size], rtol=1e-8)
    assert np.max(subspace_angles(isvd.U, Uc[:, :isvd.S.size])) < 1e-7


def test_reconstruction_error_hand_case():
    isvd = IncrementalSVD(K=1).fit(np.array([[1.0], [0.0], [0.0]]))
    z = np.array([[3.0, 0.0], [4.0, 0.0], [0.0, 2.0]])
    np.testing.assert_allclose(isvd.reconstruction_error(z), [4.0, 2.0])


def test_truncation_keeps_K():
    rng = np.random.default_rng(4)
    isvd = IncrementalSVD(K=3, forgetting=0.95).fit(rng.normal(size=(10, 6)))
    for _ in range(10):
        isvd.partial_fit(rng.normal(size=10))
    assert isvd.U.shape == (10, 3)
    np.testing.assert_allclose(isvd.U.T @ isvd.U, np.eye(3), atol=1e-10)
    assert np.all(np.diff(isvd.S) <= 0)


def test_bad_input():
    with pytest.raises(ValueError, match="forgetting"):
        IncrementalSVD(K=3, forgetting=0)
    with pytest.raises(ValueError, match="K"):
        IncrementalSVD(K=0)
    isvd = IncrementalSVD(K=2).fit(np.eye(4))
    with pytest.raises(ValueError, match="rows"):
        isvd.partial_fit(np.ones(5))
    with pytest.raises(ValueError, match="NaN"):
        isvd.partial_fit(np.full(4, np.nan))
    with pytest.raises(ValueError, match="fit"):
        IncrementalSVD(K=2).reconstruction_error(np.ones(4))


def test_reconstruction_error_is_one_plus_rho_times_the_bhattacharyya_distance():
    """With z = sqrt(h) and one learned appearance u = sqrt(h_ref), eq. 12-13 (book's reading)
    give ||z - u u^T z||^2 = (1 - rho)(1 + rho): about twice eq. 10's D^2 = 1 - rho, so the
    same sigma is narrower after learning (04_incremental_svd). Hand-worked identity, checked on
    random histograms."""
    import numpy as np
    from trackbook.learning.incremental_svd import IncrementalSVD
    rng = np.random.default_rng(0)
    h_ref = rng.dirichlet(np.ones(256))
    m = IncrementalSVD(K=1).fit(np.sqrt(h_ref)[:, None])
    for _ in range(20):
        h = 0.8 * h_ref + 0.2 * rng.dirichlet(np.ones(256))
        rho = np.sum(np.sqrt(h * h_ref))
        err2 = m.reconstruction_error(np.sqrt(h)[:, None])[0] ** 2
        assert err2 == pytest.approx((1 - rho) * (1 + rho), rel=1e-9)
        assert 1.9 < err2 / (1 - rho) <= 2.0
