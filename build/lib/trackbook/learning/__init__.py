"""On-line appearance learning: incremental SVD (chapter 08)."""
