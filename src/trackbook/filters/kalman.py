"""The linear Kalman filter of ``06_kalman`` (eq. 7–13 of Lee 2015).

Names follow filterpy (``x``, ``P``, ``F``, ``H``, ``Q``, ``R``, ``K``, ``y``, ``S``;
``predict()`` / ``update(z)``) so the book can put this code and
``filterpy.kalman.KalmanFilter`` side by side; the tests check both agree to 1e-9.

>>> from trackbook.filters.kalman import constant_velocity
>>> kf = constant_velocity(x0=(10.0, 20.0))
>>> kf.predict(); kf.update((11.0, 21.0))
>>> kf.x.round(3).tolist()
[10.75, 20.75, 0.25, 0.25]
"""

from __future__ import annotations

import numpy as np


class KalmanFilter:
    """A linear Kalman filter x_{k+1} = F x_k + w, y_k = H x_k + v (eq. 7–8 of Lee 2015).

    Parameters
    ----------
    dim_x, dim_z : sizes of the state and of the measurement.

    Attributes
    ----------
    x : (dim_x,) state estimate (x̂⁺ after ``update``, x̂⁻ after ``predict``)
    P : (dim_x, dim_x) its error covariance
    F, H, Q, R : the model matrices of eq. 7–8 (w ~ N(0, Q), v ~ N(0, R))
    K, y, S : gain, innovation and innovation covariance of the last ``update``
    """

    def __init__(self, dim_x: int, dim_z: int):
        self.dim_x, self.dim_z = int(dim_x), int(dim_z)
        self.x = np.zeros(dim_x)
        self.P = np.eye(dim_x)
        self.F = np.eye(dim_x)
        self.H = np.zeros((dim_z, dim_x))
        self.Q = np.eye(dim_x)
        self.R = np.eye(dim_z)
        self.K = np.zeros((dim_x, dim_z))
        self.y = np.zeros(dim_z)
        self.S = np.eye(dim_z)

    def predict(self) -> None:
        """x̂⁻ = F x̂⁺ (eq. 9); P⁻ = F P⁺ Fᵀ + Q (eq. 10)."""
        self.x = self.F @ self.x
        self.P = self.F @ self.P @ self.F.T + self.Q

    def update(self, z) -> None:
        """Fold in the measurement z (eq. 11–13).

        K = P⁻Hᵀ(HP⁻Hᵀ + R)⁻¹ (eq. 11); x̂⁺ = x̂⁻ + K(z − Hx̂⁻) (eq. 12); P⁺ = (I − KH)P⁻ (eq. 13).
        """
        z = np.asarray(z, dtype=float).reshape(self.dim_z)
        self.y = z - self.H @ self.x
        self.S = self.H @ self.P @ self.H.T + self.R
        # Solve rather than invert S; same K as eq. 11.
        self.K = np.linalg.solve(self.S.T, (self.P @ self.H.T).T).T
        self.x = self.x + self.K @ self.y
        # filterpy uses the Joseph form (I−KH)P(I−KH)ᵀ + KRKᵀ; equal to eq. 13 for the optimal
        # K, and it keeps P symmetric, so we use it too.
        I_KH = np.eye(self.dim_x) - self.K @ self.H
        self.P = I_KH @ self.P @ I_KH.T + self.K @ self.R @ self.K.T

    def innovation_covariance(self) -> np.ndarray:
        """S = H P Hᵀ + R for the current P (after ``predict``: the gate of the next measurement)."""
        return self.H @ self.P @ self.H.T + self.R


def constant_velocity(x0=(0.0, 0.0), v0=(0.0, 0.0), q: float = 1.0, r: float = 1.0,
                      p0: float = 1.0) -> KalmanFilter:
    """The constant-velocity model printed in Lee 2015 (section 2.2).

    State [x, y, ẋ, ẏ]; F advances position by velocity per frame; H picks the position;
    Q = q·I₄ and R = r·I₂ (the paper prints Q = I and R = I [quote: lee2015.q_identity]
    [quote: lee2015.r_identity], q = r = 1); P₀ = p0·I₄.
    """
    kf = KalmanFilter(4, 2)
    kf.F = np.array([[1.0, 0, 1, 0], [0, 1, 0, 1], [0, 0, 1, 0], [0, 0, 0, 1]])
    kf.H = np.array([[1.0, 0, 0, 0], [0, 1, 0, 0]])
    kf.Q = q * np.eye(4)
    kf.R = r * np.eye(2)
    kf.P = p0 * np.eye(4)
    kf.x = np.array([x0[0], x0[1], v0[0], v0[1]], dtype=float)
    return kf


__all__ = ["KalmanFilter", "constant_velocity"]
