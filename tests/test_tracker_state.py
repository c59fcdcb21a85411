"""``Tracker.state()``: the one interface drawings read (figures, playground, video).

Each registered tracker's state after a few frames must carry what its kind of tracker has,
checked against the tracker's documented model rather than against ``state()`` itself: a
particle filter's estimate is the weighted mean of its particles, a mean-shift box is the box
the ellipse is inscribed in, a covariance search looks at target-sized windows inside its
search window.
"""

import numpy as np
import pytest

from .conftest import moving_square_frames
from trackbook import trackers
from trackbook.trackers import TrackerState
from trackbook.trackers.particle_filter import ParticleFilterTracker

BOX0 = (30.0, 40.0, 30.0, 30.0)
FIELDS = ("particles", "weights", "search_window", "ellipse", "candidates", "rays", "response",
          "response_box")

#: what each tracker's kind has (the rest must be None)
KIND = {
    "color-pf": {"particles", "weights"},
    "color-hog-pf": {"particles", "weights"},
    "color-hog-ipca": {"particles", "weights"},
    "hsi-color-pf": {"particles", "weights"},
    "hog-pf": {"particles", "weights"},
    "edge-ray-pf": {"particles", "weights", "rays"},
    "covariance": {"search_window", "candidates"},
    "kalman-covariance": {"search_window", "candidates", "ellipse"},
    "condensation": {"particles", "weights", "ellipse"},
    "condensation-mean-shift": {"particles", "weights", "ellipse"},
    "mean-shift": {"particles", "weights", "ellipse"},
    "mosse": {"search_window", "response", "response_box"},
    "kcf": {"search_window", "response", "response_box"},
    "staple": {"search_window", "response", "response_box"},
    "dsst": {"search_window", "response", "response_box"},
    "bacf": {"search_window", "response", "response_box"},
    "camshift": {"search_window", "ellipse"},
    "median-flow": set(),
    "kalman-covariance-manoeuvre": {"search_window", "candidates", "ellipse"},
}
# a re-detecting variant draws what its algorithm draws
KIND.update({f"{n}-redetect": v for n, v in list(KIND.items())})


def _frames(n=5):
    """A red, blue-striped 30 x 30 square moving 4 px a frame over grey noise."""
    return moving_square_frames(n, size=(160, 120), side=30, grey=(60, 140), top=40, left=30,
                                step=4, colour=(20, 30, 220), stripes=(220, 60, 20))[0]


@pytest.fixture(scope="module")
def runs():
    """name -> (tracker after 4 updates, its last returned (ok, box), box before the last)."""
    frames = _frames()
    out = {}
    for name in trackers.available(reference=False):
        t = trackers.create(name, seed=0)
        t.init(frames[0], BOX0)
        prev = BOX0
        for f in frames[1:-1]:
            prev = t.update(f)[1]
        last = t.update(frames[-1])
        out[name] = (t, last, prev)
    return out


def _library_trackers():
    """The trackers trackbook registers (other tests may have loaded users' trackers)."""
    return {n for n in trackers.available(reference=False) if trackers.get(n).__module__.startswith("trackbook.")}


def test_every_registered_tracker_is_described_here():
    assert set(KIND) == _library_trackers()


def test_state_before_init_has_nothing_to_draw():
    for name in sorted(KIND):
        st = trackers.create(name).state()
        assert isinstance(st, TrackerState)
        assert st.box is None and st.ok is False
        assert all(getattr(st, f) is None for f in FIELDS)


@pytest.mark.parametrize("name", sorted(KIND))
def test_state_has_the_fields_of_its_kind(runs, name):
    t, (ok, box), _ = runs[name]
    st = t.state()
    assert isinstance(st, TrackerState)
    assert st.ok == ok and np.allclose(st.box, box)
    for f in FIELDS:
        assert (getattr(st, f) is not None) == (f in KIND[name]), f
    for f in ("particles", "weights", "candidates", "rays", "response"):
        a = getattr(st, f)
        if a is not None:
            assert not a.flags.writeable, f"{f} must be read-only"


@pytest.mark.parametrize("name", [n for n in sorted(KIND) if "particles" in KIND[n]])
def test_particle_states_weights_and_weighted_mean(runs, name):
    """Weights are a distribution over the particles; on a tracked frame the box centre is the
    weighted mean of the particles' centres (columns 0-1), computed here with a plain loop."""
    t, (ok, box), _ = runs[name]
    st = t.state()
    p, w = np.asarray(st.particles), np.asarray(st.weights)
    n = t.params.n_particles if isinstance(t, ParticleFilterTracker) else 1
    assert p.ndim == 2 and p.shape[0] == n and p.shape[1] >= 2 and w.shape == (n,)
    assert np.all(w >= 0) and abs(sum(float(v) for v in w) - 1.0) < 1e-9
    assert ok, "the moving square is easy: every tracker keeps it"
    cx = sum(float(w[i]) * float(p[i, 0]) for i in range(n))
    cy = sum(float(w[i]) * float(p[i, 1]) for i in range(n))
    assert np.allclose([cx, cy], [box[0] + box[2] / 2, box[1] + box[3] / 2], atol=1e-6)


@pytest.mark.parametrize("name", ["condensation", "condensation-mean-shift", "mean-shift"])
def test_mean_shift_family_box_is_the_ellipse_box(runs, name):
    """Cho & Kang 2005's trackers: the box is the one the ellipse (cx, cy, Hx, Hy) is
    inscribed in."""
    t, (ok, box), _ = runs[name]
    cx, cy, hx, hy = t.state().ellipse
    assert hx > 0 and hy > 0
    assert np.allclose(box, (cx - hx, cy - hy, 2 * hx, 2 * hy), atol=1e-6)


def test_mean_shift_single_candidate_has_all_the_weight(runs):
    t, _, _ = runs["mean-shift"]
    st = t.state()
    assert st.particles.shape == (1, 7) and list(st.weights) == [1.0]


@pytest.mark.parametrize("name", ["covariance", "kalman-covariance"])
def test_covariance_candidates_lie_in_the_search_window(runs, name):
    """Lee 2015: candidates are target-sized windows (30 x 30 here) inside the search window."""
    t, _, _ = runs[name]
    st = t.state()
    x, y, w, h = st.search_window
    c = np.asarray(st.candidates)
    assert c.ndim == 2 and c.shape[1] == 4 and len(c) > 0
    assert np.all(c[:, 2] == BOX0[2]) and np.all(c[:, 3] == BOX0[3])
    assert np.all(c[:, 0] >= x - 1) and np.all(c[:, 1] >= y - 1)
    assert np.all(c[:, 0] + c[:, 2] <= x + w + 1) and np.all(c[:, 1] + c[:, 3] <= y + h + 1)


def test_kalman_gate_ellipse(runs):
    cx, cy, hx, hy, angle = runs["kalman-covariance"][0].state().ellipse
    assert hx > 0 and hy > 0 and -180 <= angle <= 180


def test_edge_ray_rays_belong_to_particles(runs):
    t, _, _ = runs["edge-ray-pf"]
    st = t.state()
    r = np.asarray(st.rays)
    assert r.shape == (len(st.particles), 8)
    assert t.params.max_ray == 0                    # no cap: a ray ends at an edge or the border
    assert np.all(r >= 0) and np.all(r <= np.hypot(160, 120))


def test_state_is_a_copy_that_outlives_the_next_frame():
    frames = _frames()
    t = trackers.create("color-pf", seed=0, n_particles=30)
    t.init(frames[0], BOX0)
    t.update(frames[1])
    st = t.state()
    before = np.array(st.particles)
    t.update(frames[2])
    np.testing.assert_array_equal(st.particles, before)
    with pytest.raises(ValueError):
        st.particles[0, 0] = 1.0


def test_playground_and_figures_draw_from_state(runs):
    """The viewer's snapshot and the matplotlib drawing read only the state."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from trackbook.playground.data import snapshot
    from trackbook.viz import draw_state_cv, draw_tracker_state

    snap = snapshot(runs["kalman-covariance"][0].state())
    assert {"search_window", "ellipse", "candidates"} <= set(snap)
    snap = snapshot(runs["edge-ray-pf"][0].state())
    assert len(snap["rays"]) == 2 + 8 and len(snap["particles"]) <= 40
    fake = TrackerState(box=(1, 2, 3, 4), ok=True, particles=[[10.0, 20.0]], weights=[1.0],
                        ellipse=(50, 50, 10, 5))
    fig, ax = plt.subplots()
    draw_tracker_state(ax, fake)
    assert len(ax.patches) == 1 and len(ax.collections) == 1       # the ellipse, the dots
    plt.close(fig)
    img = np.zeros((100, 100, 3), np.uint8)
    draw_state_cv(img, fake)
    assert img[20, 10].any() and img[50, 60].any()      # a particle dot, the ellipse's edge


# MOSSE, whose window is the box itself, loses this square (its last frame is judged lost and
# keeps the previous box: nothing to compare the peak with)
@pytest.mark.parametrize("name", [n for n in sorted(KIND)
                                  if "response" in KIND[n] and not n.startswith("mosse")])
def test_the_responses_brightest_cell_is_where_the_box_went(runs, name):
    """A correlation filter's drawn response is laid out over ``response_box``: the centre of
    its brightest cell is the centre of the box the last ``update`` returned, up to the
    parabola that refines the peak (half a cell each way)."""
    t, (ok, box), _ = runs[name]
    st = t.state()
    r = np.asarray(st.response)
    R, C = r.shape
    x, y, w, h = st.response_box
    i, j = np.unravel_index(int(np.argmax(r)), r.shape)
    assert ok, "the moving square is easy: every tracker keeps it"
    peak = (x + (j + 0.5) * w / C, y + (i + 0.5) * h / R)
    centre = (box[0] + box[2] / 2, box[1] + box[3] / 2)
    assert abs(peak[0] - centre[0]) <= 0.5 * w / C + 1e-6
    assert abs(peak[1] - centre[1]) <= 0.5 * h / R + 1e-6
