"""Estimation machinery: the Kalman filter (05), particle filters / Condensation (06),
mean-shift (07). One module per chapter."""
