"""The printed options the paper presets run: Lee et al. 2012's 40-frame learning window and
the exponent D of eq. 12-13, Cho & Kang 2005's kernel bandwidth a = sqrt(Hx^2 + Hy^2).

Expected values come from the equations: the window's subspace from numpy's SVD of the last 40
feature vectors, the exponents and kernel weights worked by hand, the colour distribution of
eq. 3 from a slow loop over the ellipse's pixels.
"""
import numpy as np
import pytest
import skimage.data

from trackbook import trackers
from trackbook.filters.mean_shift import BinImage, ellipse_rho, kernel_weights
from trackbook.quotes import fields
from trackbook.trackers.color_hog_ipca import subspace_exponent


def _clip(n=100, W=160, H=120):
    """A textured patch (the astronaut's face) moving on noise, with its boxes."""
    rng = np.random.default_rng(3)
    patch = skimage.data.astronaut()[30:130, 170:250, ::-1]
    patch = np.ascontiguousarray(patch[::4, ::4])                        # 25 x 20
    frames, boxes = [], []
    for t in range(n):
        f = rng.integers(0, 255, (H, W, 3), dtype=np.uint8)
        x, y = 40 + int(30 * np.sin(t / 15)), 40 + int(20 * np.cos(t / 20))
        f[y:y + 25, x:x + 20] = patch
        frames.append(f)
        boxes.append((x, y, 20, 25))
    return frames, boxes


def test_paper_preset_runs_the_printed_options():
    ipca = trackers.create("color-hog-ipca", preset="paper").params
    assert (ipca.window, ipca.exponent) == (40, "D")
    for name in ("condensation", "mean-shift", "condensation-mean-shift"):
        assert trackers.create(name, preset="paper").params.bandwidth == "diagonal"
    book = trackers.create("color-hog-ipca").params
    assert (book.window, book.exponent) == (0, "D2")
    assert trackers.create("condensation-mean-shift").params.bandwidth == "ellipse"


def test_a_40_frame_window_keeps_exactly_the_last_40_feature_vectors():
    frames, boxes = _clip()
    # the window's arithmetic, on every frame: without the failure layer (which, on this clip
    # of a face on noise, rightly calls the tracker lost and stops its learning) every
    # estimate is learned
    t = trackers.create("color-hog-ipca", seed=0, preset="paper", failure=False)
    t.init(frames[0], boxes[0])
    estimates = [t.update(f)[1] for f in frames[1:]]
    assert t.learning and t.n_learned == len(frames)
    # A = [I_1 ... I_40]: the raw features (feature_map 'raw' in the paper preset) at the
    # estimates of the last 40 frames, recomputed here and decomposed by numpy
    last = list(zip(frames[1:], estimates))[-40:]
    for k in ("color", "hog"):
        A = np.column_stack([t.features(f, np.asarray(b)[None])[k][0] for f, b in last])
        U, S, _ = np.linalg.svd(A, full_matrices=False)
        K = t.basis[k].shape[1]
        assert K == t.params.K
        np.testing.assert_allclose(t.singular_values[k], S[:K], rtol=1e-9)
        # the same subspace: equal projectors (the signs of singular vectors are free)
        np.testing.assert_allclose(t.basis[k] @ t.basis[k].T, U[:, :K] @ U[:, :K].T,
                                   atol=1e-9)
    assert len(t._window["color"]) == 40      # the 41st-to-last frame was removed


def test_without_a_window_every_frame_stays_in_the_subspace():
    frames, boxes = _clip(60)
    t = trackers.create("color-hog-ipca", seed=0, preset="paper", window=0, T=10)
    t.init(frames[0], boxes[0])
    for f in frames[1:]:
        t.update(f)
    assert t.learning and t._window is None


def test_eq12_exponent_d_not_d_squared_by_hand():
    D = np.array([0.0, 0.3, 2.0])
    np.testing.assert_allclose(subspace_exponent(D, "D"), [0.0, 0.3, 2.0])
    np.testing.assert_allclose(subspace_exponent(D, "D2"), [0.0, 0.09, 4.0])
    with pytest.raises(ValueError, match="exponent"):
        subspace_exponent(D, "D3")


def test_the_ipca_likelihood_puts_d_in_the_exponent():
    """After T, anchor 0: p = exp(-D / 2 sigma^2) with D = ||z - U U^T z|| (eq. 12-13)."""
    frames, boxes = _clip(50)
    t = trackers.create("color-hog-ipca", seed=0, preset="paper", T=10)
    t.init(frames[0], boxes[0])
    for f in frames[1:]:
        t.update(f)
    assert t.learning
    feats = t.features(frames[-1], np.array([boxes[-1], (5.0, 5.0, 20.0, 25.0)]))
    got = t._distances2(feats)
    for k, h in feats.items():
        U = t.basis[k]
        D = np.linalg.norm(h - (h @ U) @ U.T, axis=1)          # raw z = h in the paper preset
        np.testing.assert_allclose(got[k], D, rtol=1e-9)       # D, not D^2
        assert not np.allclose(D, D * D)


def test_kernel_bandwidth_by_hand():
    """Hx = 4, Hy = 3: a = sqrt(16 + 9) = 5 (eq. 3 and 10 of Cho & Kang 2005)."""
    dx = np.array([0.0, 3.0, 0.0, 0.0, 4.0, 2.0])
    dy = np.array([0.0, 0.0, 2.0, 3.0, 1.0, 2.0])
    ellipse = [1.0, 1 - 9 / 16, 1 - 4 / 9, 0.0, 0.0, 1 - 4 / 16 - 4 / 9]
    diagonal = [1.0, 1 - 9 / 25, 1 - 4 / 25, 0.0, 0.0, 1 - 8 / 25]    # (0, 3), (4, 1): outside
    np.testing.assert_allclose(kernel_weights(dx, dy, 4.0, 3.0, "ellipse"), ellipse)
    np.testing.assert_allclose(kernel_weights(dx, dy, 4.0, 3.0, "diagonal"), diagonal)
    with pytest.raises(ValueError, match="bandwidth"):
        kernel_weights(dx, dy, 4.0, 3.0, "circle")


@pytest.mark.parametrize("bandwidth", ["ellipse", "diagonal"])
def test_eq3_colour_distribution_against_a_slow_loop(bandwidth):
    rng = np.random.default_rng(0)
    m = 6
    labels = rng.integers(0, m, (30, 40))
    img = BinImage(labels, np.array([0.5, 0.5]), 1, m)
    Hx, Hy, j0, i0 = 7.0, 4.0, 20, 15
    a2 = Hx ** 2 + Hy ** 2
    p = np.zeros(m)
    for i in range(labels.shape[0]):
        for j in range(labels.shape[1]):
            dx, dy = j - j0, i - i0
            if (dx / Hx) ** 2 + (dy / Hy) ** 2 >= 1:
                continue                                        # only the I pixels inside
            r2 = (dx / Hx) ** 2 + (dy / Hy) ** 2 if bandwidth == "ellipse" else (
                dx * dx + dy * dy) / a2
            p[labels[i, j]] += 1 - r2                           # k(r) = 1 - r^2 (eq. 2)
    p /= p.sum()                                                # f
    _, got, _ = ellipse_rho(img, np.ones(m) / m, [[j0 + 0.5, i0 + 0.5]], [[Hx, Hy]],
                            bandwidth=bandwidth)
    np.testing.assert_allclose(got[0], p, rtol=1e-12)


def test_fields_record_the_printed_options():
    assert fields.backing("color-hog-ipca", "exponent") == ("lee2012.likelihood_eq12", "printed")
    assert fields.backing("color-hog-ipca", "window") == ("lee2012.window40", "reading")
    for name in ("condensation", "mean-shift", "condensation-mean-shift"):
        assert fields.backing(name, "bandwidth") == ("cho2005.bandwidth_eq3", "printed")


def test_three_states_of_a_preset_value():
    assert fields.state("color-hog-ipca", "exponent") == ("printed", "lee2012.likelihood_eq12")
    assert fields.state("color-hog-ipca", "window") == ("reading", "lee2012.window40")
    assert fields.state("color-hog-ipca", "forgetting") == ("not printed", None)
    assert {fields.state(t, f)[0] for t, fs in fields.table().items() for f in fs} <= set(
        fields.STATES)


def test_departures_table_shows_the_window_as_a_reading_and_d_as_printed():
    from trackbook import viz
    rows = {line.split("|")[1].strip(): line.split("|")[2].strip()
            for line in viz.departures_table("color-hog-ipca").splitlines()[2:]}
    assert rows["window"] == "40 (a reading)"
    assert rows["exponent"] == "D"
    cms = {line.split("|")[1].strip(): line.split("|")[2].strip()
           for line in viz.departures_table("condensation-mean-shift").splitlines()[2:]}
    assert cms["bandwidth"] == "diagonal"


def test_departures_table_drops_the_quote_references_of_a_why():
    from trackbook import trackers, viz
    whys = {r["param"]: r["why"] for r in trackers.departures("color-hog-ipca")}
    assert "[quote: lee2012.remove_old]" in whys["forgetting"]      # the source cites ...
    table = viz.departures_table("color-hog-ipca")
    assert "[quote:" not in table                                   # ... the table does not
    assert "the paper removes old features, read as a 40-frame window" in table


def test_cli_marks_readings_in_the_paper_column(capsys):
    from trackbook import cli
    assert cli.main(["trackers", "color-hog-ipca"]) == 0
    lines = {line.split()[0]: line for line in capsys.readouterr().out.splitlines() if line.strip()}
    assert "40 (a reading)" in lines["window"]
    assert "'D'" in lines["exponent"] and "(a reading)" not in lines["exponent"]
    assert "not printed" in lines["forgetting"]


def test_departures_table_keeps_only_the_asked_rows():
    from trackbook import viz
    rows = viz.departures_table("condensation-mean-shift",
                                params={"max_iter", "eps"}).splitlines()[2:]
    cells = {line.split("|")[1].strip(): line.split("|")[2].strip() for line in rows}
    # eq. 12-13's one shift is a reading; epsilon is named without a value
    assert cells == {"max_iter": "1 (a reading)", "eps": "not printed"}
    assert not any("[quote:" in line for line in rows)
