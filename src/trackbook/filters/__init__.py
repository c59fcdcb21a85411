"""Estimation machinery: the Kalman filter (``06_kalman``), particle filters / Condensation
(``02_particle_filters``), mean-shift (``08_mean_shift``), correlation filters, template
matching (SSD, NCC) and point tracking (Shi-Tomasi corners, pyramidal Lucas-Kanade, the
forward-backward error). One module per method."""
