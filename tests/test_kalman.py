"""The Kalman filter of 06_kalman (eq. 7-13 of Lee 2015) against filterpy and by hand."""
import numpy as np
import pytest

from trackbook.filters.kalman import constant_velocity

filterpy = pytest.importorskip("filterpy.kalman")


def test_matches_filterpy_step_by_step():
    # Same F, H, Q = I, R = I (sec. 2.2 of Lee 2015), P0 = I, random measurements.
    rng = np.random.default_rng(3)
    kf = constant_velocity((10.0, 20.0), q=1.0, r=1.0, p0=1.0)
    ref = filterpy.KalmanFilter(dim_x=4, dim_z=2)
    ref.x = kf.x.copy()
    ref.F, ref.H, ref.Q, ref.R, ref.P = (kf.F.copy(), kf.H.copy(), kf.Q.copy(), kf.R.copy(),
                                         kf.P.copy())
    for k in range(30):
        z = np.array([10.0 + 2 * k, 20.0 - k]) + rng.normal(0, 1, 2)
        kf.predict(); ref.predict()
        assert kf.P == pytest.approx(ref.P, rel=1e-12, abs=1e-12)
        kf.update(z); ref.update(z)
        assert kf.x == pytest.approx(ref.x.ravel(), rel=1e-12, abs=1e-12)
        assert kf.P == pytest.approx(ref.P, rel=1e-12, abs=1e-12)


def test_position_spread_grows_as_t_to_the_1_5_without_measurements():
    # With Q = I and no update, var(x) follows t^3/3 + lower terms (the velocity is a random
    # walk, the position its sum), so its standard deviation grows as t^1.5, not t^2.
    kf = constant_velocity((0.0, 0.0), q=1.0, r=1.0, p0=1.0)
    var = []
    for _ in range(400):
        kf.predict()
        var.append(kf.P[0, 0])
    t = np.arange(1, 401)
    slope = np.polyfit(np.log(t[200:]), np.log(np.sqrt(var[200:])), 1)[0]
    assert slope == pytest.approx(1.5, abs=0.02)
    assert var[-1] / (400 ** 3 / 3) == pytest.approx(1.0, rel=0.02)
