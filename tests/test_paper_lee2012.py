"""``color-hog-pf`` and ``color-hog-ipca`` against the values Lee et al. (2012) print.

Expected numbers are copied from the paper (the text has no page numbers, so comments name
the section and passage), not from the code: a default that differs from
the paper fails here unless its field says why.
"""
import pytest

from trackbook import trackers
from trackbook.features.color import HSV_BINS
from trackbook.params import NOT_PRINTED
from trackbook.trackers import color_pf

from ._paper import fields

PRINTED = {
    "color-hog-pf": {
        "n_particles": 100,    # "N = 100", section V, the sentence after the pseudocode
        "sigma_color": 0.4,    # "all sigma_color and sigma_hog ... 0.4", section V, after eq. 12-13
        "sigma_hog": 0.4,      # same sentence
        "alpha": 0.1,          # "alpha = 0.1", section V, after eq. 14
        "size_noise": 2.5,     # gamma_w, gamma_h ~ U(-2.5, 2.5), section V, after eq. 9
        "vx_noise": 6.5,       # gamma_xdot ~ U(-6.5, 6.5), after eq. 9
        "vy_noise": 2.5,       # gamma_ydot ~ U(-2.5, 2.5), after eq. 9
    },
}
PRINTED["color-hog-ipca"] = dict(PRINTED["color-hog-pf"], T=40)  # "T = 40", end of section II; n = 40 in section IV
# The paper gives no number of basis vectors (its 16 is the patch width) and no forgetting.
NOT_PRINTED_IPCA = {"K", "forgetting", "gate_on", "gate_window", "min_size"}


@pytest.mark.parametrize("name", sorted(PRINTED))
def test_printed_values_are_pinned(name):
    f = fields(name)
    for key, value in PRINTED[name].items():
        assert f[key].metadata["paper"] == value, key


def test_section_v_is_printed_for_the_proposed_tracker_only():
    # section V describes "the proposed algorithm"; section VI compares it with [14, 20]
    # without their settings: a reading for color-hog-pf, printed for color-hog-ipca
    from trackbook.quotes import fields
    for key in PRINTED["color-hog-pf"]:
        assert fields.state("color-hog-pf", key)[0] == "reading", key
        assert fields.state("color-hog-ipca", key)[0] == "printed", key


def test_no_K_is_credited_to_the_paper():
    f = fields("color-hog-ipca")
    for key in NOT_PRINTED_IPCA:
        assert f[key].metadata["paper"] is NOT_PRINTED, key
    assert "16" not in f["K"].metadata["doc"]


def test_patch_and_bins_are_the_papers():
    # ROI resized to 16 x 24 px: section II; 8 x 8 x 4 HSV bins: section III (after eq. 1).
    assert color_pf.PATCH_SIZE == (16, 24)
    assert tuple(HSV_BINS) == (8, 8, 4)


def test_paper_preset_learns_like_the_paper():
    p = trackers.create("color-hog-ipca", preset="paper").params
    for key, value in PRINTED["color-hog-ipca"].items():
        assert getattr(p, key) == value, key
    # eq. 12-13 on the raw histograms, every frame, no anchor, no gate, no forgetting printed
    assert (p.anchor, p.gate_k, p.learn_threshold, p.learn_every) == (0.0, 0.0, 0.0, 1)
    assert p.feature_map == "raw" and p.forgetting == 1.0 and p.init == "frame"
