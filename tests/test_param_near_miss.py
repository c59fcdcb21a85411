"""An unknown param name gets the names it may have meant: close spellings and names that
share its ``_``-separated words (``sigma`` is a word of ``kernel_sigma``)."""

from __future__ import annotations

import pytest

from trackbook import trackers
from trackbook.params import near_names


def test_a_word_of_a_longer_name_is_suggested():
    with pytest.raises(ValueError, match=r"'sigma' \(did you mean 'kernel_sigma'"):
        trackers.create("kcf", sigma=3)


def test_a_longer_name_suggests_the_name_it_extends():
    with pytest.raises(ValueError, match=r"did you mean 'kernel_sigma'\?"):
        trackers.create("kcf", kernel_sigma_x=1.0)


def test_a_close_spelling_still_comes_first():
    assert near_names("n_particle", ["sigma_color", "n_particles", "particle_gain"])[0] \
        == "n_particles"


def test_words_match_whole_not_as_letters():
    # "ma" is inside "sigma" as letters, not as a word: no suggestion
    assert near_names("ma", ["kernel_sigma", "eta"]) == []
    assert near_names("sigma", ["kernel_sigma", "output_sigma_factor", "eta"]) == [
        "kernel_sigma", "output_sigma_factor"]


def test_nothing_near_says_nothing():
    with pytest.raises(ValueError) as e:
        trackers.create("kcf", zzz=1)
    assert "did you mean" not in str(e.value) and "valid names" in str(e.value)
