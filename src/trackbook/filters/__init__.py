"""Estimation machinery: the Kalman filter (``06_kalman``), particle filters / Condensation
(``02_particle_filters``), mean-shift (``08_mean_shift``) and CamShift, correlation filters,
template matching (SSD, NCC), point tracking (Shi-Tomasi corners, pyramidal Lucas-Kanade, the
forward-backward error), background subtraction, and the tools for designing a Kalman filter
(consistency tests, smoother, IMM, sigma points, importance weights). One module per method."""
