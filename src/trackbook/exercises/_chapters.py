"""The chapters that have exercises, in the book's order (one text module ``_<stem>.py`` each).

The order is the table of contents' (a test holds the two together); the number in a stem is
the chapter's fixed identifier, which its exercises carry, not its place.
"""

CHAPTERS = ("00_introduction",
            # appearance models
            "01_kernel_histograms", "03_hog", "05_edge_rays", "07_region_covariance",
            "04_incremental_svd",
            # search
            "08_mean_shift", "13_camshift", "10_correlation_filters",
            "12_template_matching_and_optical_flow", "20_correlation_filters_ii",
            # Bayesian filtering
            "21_bayes_filter", "06_kalman", "17_kalman_filter_design",
            "02_particle_filters", "18_sigma_points_and_proposals",
            # comparing trackers, failure and re-detection
            "09_trackers_compared", "19_evaluation_protocols", "11_knowing_you_are_lost",
            "14_tracking_by_detection",
            # several targets
            "15_background_subtraction", "16_several_targets")
