"""Estimation machinery: the Kalman filter (``06_kalman``), particle filters / Condensation
(``02_particle_filters``), mean-shift (``08_mean_shift``), and the tools for designing a Kalman
filter (consistency tests, smoother, IMM, sigma points, importance weights). One module per
method."""
