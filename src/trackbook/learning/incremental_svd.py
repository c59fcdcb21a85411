"""Incremental SVD with a forgetting factor (eq. 6-7 of Lee et al. 2012; Ross et al. 2008).

Chapter ``04_incremental_svd`` of the book. Given the thin SVD A = U Sigma V^T of the d x n features seen so far
and m new columns B, the SVD of [A B] follows from a small (k+m) x (k+m) problem (eq. 6):

    [A B] = [U  B~] [ Sigma   U^T B  ] [ V^T  0 ]
                    [   0    B~^T B  ] [  0   I ]

where B~ is an orthonormal basis of the part of B orthogonal to U. (The paper prints B^T B
in the lower-right block [quote: lee2012.update_eq6]; it is B~^T B, the coordinates of B's residual in B~.) Calling the
middle matrix R and taking its SVD R = U~ Sigma~ V~^T gives (eq. 7)

    U' = [U  B~] U~,    Sigma' = Sigma~,

so V never has to be stored. Ross et al. 2008 (the paper's [15]) add two things used here:

- **forgetting**: Sigma is multiplied by f <= 1 before each update, so a frame seen j updates
  ago is scaled by f^j and weighs f^(2j) in A A^T, whose eigenvectors are U (a basis
  remembers about 1 / (1 - f^2) frames); the book's alternative to the paper's "remove old
  features" (section II), which ``color-hog-ipca`` reads as a window;
- **mean tracking** (``centre=True``): the subspace is fitted to mean-centred data, with the
  correction column sqrt(n m / (n + m)) (mu_B - mu_A) that makes the update exact, and the
  effective count n <- f n + m.

Lee et al. project the raw feature (z_reconst = U U^T z, eq. 12-13)
[quote: lee2012.likelihood_eq12], so the trackers use
``centre=False``; ``centre=True`` is what scikit-learn's ``IncrementalPCA`` does (without
forgetting), which the tests use as an oracle.
"""

from __future__ import annotations

import numpy as np


def _as_matrix(M, d=None, name="A") -> np.ndarray:
    M = np.asarray(M, dtype=float)
    if M.ndim == 1:
        M = M[:, None]
    if M.ndim != 2 or M.shape[1] == 0:
        raise ValueError(f"{name} must be a d x n matrix (one feature per column), got shape {M.shape}.")
    if d is not None and M.shape[0] != d:
        raise ValueError(f"{name} has {M.shape[0]} rows but the subspace lives in d = {d}; "
                         "pass features as columns of the same length as in fit().")
    if not np.all(np.isfinite(M)):
        raise ValueError(f"{name} contains NaN or infinity.")
    return M


class IncrementalSVD:
    """Truncated incremental SVD of a growing d x n feature matrix (eq. 6-7, Lee et al. 2012).

    Parameters
    ----------
    K : int
        Number of singular vectors kept (``color-hog-ipca`` defaults to 2; no K is printed in Lee et al. 2012).
    forgetting : float in (0, 1]
        f of Ross et al.: old singular values are scaled by f at every ``partial_fit``.
    centre : bool
        Track the mean and fit the centred data (Ross et al., scikit-learn) instead of the raw
        columns (the paper's eq. 12-13).
    rtol : float
        Singular values below ``rtol * max(S)`` are dropped: their directions are numerical
        noise (e.g. the orthogonal complement of a column already in span(U)) and would
        otherwise enter the projection U U^T.

    Attributes
    ----------
    U : (d, k) orthonormal basis, k <= K.
    S : (k,) singular values, descending.
    mean : (d,) mean of the data seen (zeros when ``centre=False``).
    n_seen : effective number of columns (f n + m at each update).
    """

    def __init__(self, K: int = 16, forgetting: float = 1.0, centre: bool = False,
                 rtol: float = 1e-10):
        if int(K) != K or K < 1:
            raise ValueError(f"K = {K!r} must be a positive integer (number of basis vectors).")
        if not 0.0 < forgetting <= 1.0:
            raise ValueError(f"forgetting = {forgetting!r} must lie in (0, 1] (1 = never forget).")
        self.K = int(K)
        self.forgetting = float(forgetting)
        self.centre = bool(centre)
        self.rtol = float(rtol)
        self.U = None
        self.S = None
        self.mean = None
        self.n_seen = 0.0

    @property
    def fitted(self) -> bool:
        return self.U is not None

    def _truncate(self, U, S):
        keep = min(self.K, int(np.sum(S > self.rtol * max(S[0], np.finfo(float).tiny))))
        keep = max(keep, 1)
        return U[:, :keep], S[:keep]

    def fit(self, A) -> "IncrementalSVD":
        """Start from the thin SVD A = U Sigma V^T of a d x n matrix (the T = 40 first frames)."""
        A = _as_matrix(A)
        self.mean = A.mean(axis=1) if self.centre else np.zeros(A.shape[0])
        U, S, _ = np.linalg.svd(A - self.mean[:, None], full_matrices=False)
        self.U, self.S = self._truncate(U, S)
        self.n_seen = float(A.shape[1])
        return self

    def partial_fit(self, B) -> "IncrementalSVD":
        """Add the d x m columns B (m = 1 per frame in the paper) by eq. 6-7."""
        if not self.fitted:
            return self.fit(B)
        B = _as_matrix(B, self.U.shape[0], name="B")
        m = B.shape[1]
        f = self.forgetting
        if self.centre:
            mu_B = B.mean(axis=1)
            n = self.n_seen
            # Ross et al. 2008, Sequential KL with mean update: centre the new block on its own
            # mean and add one column carrying the shift of the mean.
            B_hat = np.column_stack([B - mu_B[:, None],
                                     np.sqrt(n * m / (n + m)) * (mu_B - self.mean)])
            self.mean = (f * n * self.mean + m * mu_B) / (f * n + m)
        else:
            B_hat = B
        U, S = self.U, self.S * f
        proj = U.T @ B_hat                                   # U^T B
        resid = B_hat - U @ proj
        if resid.shape[1] == 1:
            # m = 1 (one frame): B~ is the normalised residual and B~^T B its norm; no QR call.
            r = float(np.sqrt(resid[:, 0] @ resid[:, 0]))
            B_tilde = resid / r if r > 0 else np.zeros_like(resid)
            resid_coords = np.array([[r]])
        else:
            B_tilde, resid_coords = np.linalg.qr(resid)      # B~ and B~^T B
        k, p = S.size, B_tilde.shape[1]
        R = np.zeros((k + p, k + B_hat.shape[1]))           # the middle matrix of eq. 6
        R[:k, :k] = np.diag(S)
        R[:k, k:] = proj
        R[k:, k:] = resid_coords
        U_r, S_r, _ = np.linalg.svd(R, full_matrices=False)
        U_new = np.column_stack([U, B_tilde]) @ U_r          # eq. 7
        self.U, self.S = self._truncate(U_new, S_r)
        self.n_seen = f * self.n_seen + m
        return self

    def project(self, Z) -> np.ndarray:
        """U U^T (z - mean) + mean for each column z of Z: the reconstruction of eq. 12-13."""
        Z = _as_matrix(Z, self.U.shape[0], name="Z")
        Zc = Z - self.mean[:, None]
        return self.U @ (self.U.T @ Zc) + self.mean[:, None]

    def reconstruction_error(self, Z) -> np.ndarray:
        """D = ||z - U U^T z||_2 of every column z of Z (eq. 12-13 of Lee et al. 2012, as corrected).

        The paper prints D = sqrt(sum_i z_i - z_reconst,i) [quote: lee2012.likelihood_eq12] -- a
        sum of signed differences,
        which can be negative; the intended quantity is the Euclidean norm of the residual.
        With ``centre=True`` the residual is of z - mean.
        """
        if not self.fitted:
            raise ValueError("call fit(A) before reconstruction_error(Z).")
        Z = _as_matrix(Z, self.U.shape[0], name="Z")
        Zc = Z - self.mean[:, None] if self.centre else Z
        # ||z||^2 - ||U^T z||^2 would be cheaper but cancels catastrophically for z near span(U).
        r = Zc - self.U @ (self.U.T @ Zc)
        return np.sqrt(np.einsum("ij,ij->j", r, r))
