"""Estimation machinery: the Kalman filter (``06_kalman``), particle filters / Condensation
(``02_particle_filters``), mean-shift (``08_mean_shift``). One module per method."""
