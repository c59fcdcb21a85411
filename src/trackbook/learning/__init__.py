"""On-line appearance learning: incremental SVD (``04_incremental_svd``)."""
