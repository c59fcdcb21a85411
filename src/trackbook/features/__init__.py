"""Appearance features of a region: colour histograms (``01_kernel_histograms``),
HOG (``03_hog``), edge rays (``05_edge_rays``), region covariance (``07_region_covariance``),
Felzenszwalb's 31-channel HOG for the correlation-filter trackers (``fhog``).
One module per feature."""
