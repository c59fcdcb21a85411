"""Appearance features of a region: colour histograms (01), HOG (02), edge rays (03),
region covariance (04). One module per chapter."""
