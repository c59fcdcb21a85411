"""The chapters that have exercises, in book order (one text module ``_<stem>.py`` each)."""

CHAPTERS = ("00_introduction", "01_kernel_histograms", "02_particle_filters", "03_hog",
            "04_incremental_svd", "05_edge_rays", "06_kalman", "07_region_covariance",
            "08_mean_shift", "09_trackers_compared", "10_correlation_filters",
            "11_knowing_you_are_lost", "12_template_matching_and_optical_flow",
            "13_camshift", "14_tracking_by_detection", "15_background_subtraction",
            "16_several_targets", "17_kalman_filter_design",
            "18_sigma_points_and_proposals", "19_evaluation_protocols",
            "20_correlation_filters_ii")
