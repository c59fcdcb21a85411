"""The one parameter parser (``trackbook.params.parse``) behind the API and the CLI.

One regression test per class of bad input found by a hostile probe of the parser, plus a
hypothesis fuzz: whatever a user passes, the parser returns a valid value or raises a
``ValueError`` that names the parameter.

Decision documented here: a string from the API (``n_particles='100'``) is converted with the
field's type, exactly as ``--param n_particles=100`` on the command line is, so the two entry
points agree; a string that is not a valid value is refused with the parameter's name.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbook import cli, trackers
from trackbook.params import parse


def _P(name):
    return trackers.get(name).Params


def test_string_from_api_is_converted_with_the_field_type():
    t = trackers.create("color-pf", n_particles="100")
    assert t.params.n_particles == 100 and isinstance(t.params.n_particles, int)
    with pytest.raises(ValueError, match="n_particles"):
        trackers.create("color-pf", n_particles="a hundred")


def test_covariance_stride_string_and_none():
    assert trackers.create("covariance", stride="4").params.stride == 4
    with pytest.raises(ValueError, match="stride"):
        trackers.create("covariance", stride="100")      # above 8, as a string too
    with pytest.raises(ValueError, match="n_particles"):
        trackers.create("hsi-color-pf", n_particles=None)


@pytest.mark.parametrize("value", [np.int64(200_000), np.int32(200_000), 200_000,
                                   np.float64(200_000.0)])
def test_numpy_scalars_are_range_checked(value):
    with pytest.raises(ValueError, match="n_particles.*maximum"):
        trackers.create("color-pf", n_particles=value)


def test_numpy_stride_above_range_refused():
    with pytest.raises(ValueError, match="stride"):
        trackers.create("covariance", stride=np.int64(100))
    assert trackers.create("covariance", stride=np.int64(4)).params.stride == 4


@pytest.mark.parametrize("value", [True, False, np.bool_(True), 50.5, "50.5", [100]])
def test_bools_fractions_and_lists_refused_for_ints(value):
    with pytest.raises(ValueError, match="n_particles"):
        trackers.create("color-pf", n_particles=value)


def test_whole_float_accepted_for_int():
    assert parse(_P("color-pf"), "n_particles", 50.0) == 50


@pytest.mark.parametrize("value", ["nan", "NaN", " nan ", "inf", "-Infinity", float("nan"),
                                   np.float32("inf"), np.nan])
def test_nan_and_inf_refused_however_spelled(value):
    with pytest.raises(ValueError, match="eps"):
        parse(_P("mean-shift"), "eps", value)


@pytest.mark.parametrize("text,expected", [("false", False), ("False", False), ("no", False),
                                           ("0", False), ("true", True), ("yes", True),
                                           ("1", True)])
def test_bool_words(text, expected):
    assert parse(_P("mean-shift"), "scale_adapt", text) is expected
    assert trackers.create("mean-shift", scale_adapt=text).params.scale_adapt is expected


def test_bool_garbage_refused():
    with pytest.raises(ValueError, match="scale_adapt"):
        parse(_P("mean-shift"), "scale_adapt", "maybe")


def test_unknown_name_suggests_near_miss():
    with pytest.raises(ValueError, match="did you mean 'n_particles'"):
        parse(_P("color-pf"), "n_particle", 100)


def test_cli_track_param_goes_through_the_parser(tmp_path, capsys):
    """``--param scale_adapt=false`` must turn adaptation off; ``eps=nan`` must be refused."""
    assert cli._bench_param("mean-shift", "scale_adapt=false", flag="--param") == \
        {"scale_adapt": False}
    rc = cli.main(["track", "mean-shift", "red-cube", "--param", "eps=nan",
                   "--out", str(tmp_path / "o"), "--max-frames", "2"])
    err = capsys.readouterr().err
    assert rc != 0 and "eps" in err and "Traceback" not in err


# --- fuzz -------------------------------------------------------------------------------------

_FIELDS = [(n, f) for n in trackers.available(reference=False) for f in dataclasses.fields(_P(n))]

_values = st.one_of(
    st.text(max_size=12),
    st.booleans(),
    st.none(),
    st.integers(-10**6, 10**6),
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(-10**6, 10**6).map(np.int64),
    st.floats(width=32, allow_nan=True, allow_infinity=True).map(np.float32),
    st.floats(allow_nan=True, allow_infinity=True).map(np.float64),
    st.booleans().map(np.bool_),
    st.sampled_from(["1", "0", "true", "no", "nan", "-inf", "1e9", "3.5", "0.8,1.2", "(1,2)",
                     "", " ", "100", "10", "0.5"]),
)


@settings(max_examples=300, deadline=None)
@given(field=st.sampled_from(_FIELDS), value=_values)
def test_fuzz_parser_valid_value_or_named_error(field, value):
    tracker, f = field
    cls = _P(tracker)
    try:
        out = parse(cls, f.name, value)
    except ValueError as e:
        assert f.name in str(e)
        return
    lo, hi, choices = f.metadata["lo"], f.metadata["hi"], f.metadata["choices"]
    if isinstance(f.default, bool):
        assert isinstance(out, bool)
    elif isinstance(f.default, int):
        assert type(out) is int
    elif isinstance(f.default, float):
        assert type(out) is float and math.isfinite(out)
    if isinstance(out, (int, float)) and not isinstance(out, bool):
        assert (lo is None or out >= lo) and (hi is None or out <= hi)
    if choices is not None:
        assert out in choices
    # the value is one the tracker accepts
    trackers.create(tracker, **{f.name: out})


def test_unknown_tracker_and_clip_names_suggest_near_misses(capsys, tmp_path):
    with pytest.raises(ValueError, match="did you mean 'color-pf'"):
        trackers.get("color-pff")
    rc = cli.main(["track", "color-pf", "red-cub", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert rc != 0 and "did you mean 'red-cube'" in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_slider_range_is_not_the_allowed_range():
    """The slider of color-pf's N stops at 1000, but 2000 particles are a valid setting."""
    from trackbook.widgets import knob_spec
    t = trackers.create("color-pf", n_particles=2000)
    assert t.params.n_particles == 2000
    spec = knob_spec(trackers.get("color-pf"), "n_particles")
    assert (spec["lo"], spec["hi"]) == (10, 1000)
    with pytest.raises(ValueError, match="n_particles.*maximum"):
        trackers.create("color-pf", n_particles=10**6)


def test_slider_outside_allowed_range_refused():
    from trackbook.params import param
    with pytest.raises(ValueError, match="slider"):
        param(5, 1, 10, 1, "x", slider=(0, 10))
    with pytest.raises(ValueError, match="slider"):
        param(5, 1, 10, 1, "x", slider=(3, 2))


@pytest.mark.parametrize("name", trackers.available(reference=False))
def test_describe_prints_no_sentinel_objects(name):
    """Unprinted values read "not printed", never ``<object object at 0x...>``."""
    from trackbook import params
    rows = params.describe(trackers.get(name).Params)
    assert rows
    for row in rows:
        for key, value in row.items():
            assert "object at 0x" not in repr(value), (name, row["name"], key)
    paper = {r["name"]: r["paper"] for r in rows}
    if name == "color-hog-ipca":
        assert paper["K"] == "not printed" and paper["T"] == 40     # section II prints T = 40
