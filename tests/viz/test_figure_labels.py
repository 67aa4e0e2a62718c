"""What every figure tells its reader: the setting in the title, a colour key that shows the drawn
colours, axes from the joint, labels that never break inside an interval, and animations with a
length scale, phase names and the frame count of the file (issue 10, "Figures").

The objects are inspected, not the pixels of a saved image.
"""

import math
import re
import types

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_rgba  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

import throwmap as tm  # noqa: E402
from throwmap.analysis import limit_set  # noqa: E402
from throwmap.analysis.attractors import Attractor  # noqa: E402
from throwmap.analysis.basins import Basins  # noqa: E402
from throwmap.analysis.maps import ThrowMap  # noqa: E402
from throwmap.analysis.sets import ConfigSet  # noqa: E402
from throwmap.studies.compare import ModelComparison  # noqa: E402
from throwmap.throws.orbit_trajectory import paper_trajectory  # noqa: E402
from throwmap.throws.samples import throw_map_samples  # noqa: E402
from throwmap.viz.animation import animate, frame_label, frame_times, scale_bar_length, still  # noqa: E402
from throwmap.viz.basins import plot_basins, shade  # noqa: E402
from throwmap.viz.funnels import plot_funnel_graph, wrap_intervals  # noqa: E402
from throwmap.viz.limit_set import plot_limit_set  # noqa: E402

PImage = pytest.importorskip("PIL.Image")

PART = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01)
SETTING = (PART.name, "h = -0.01 m", "'paper'")
"""What every title must name: the part, h, ω (:data:`OMEGA`) and the model."""
OMEGA = re.compile(r"ω = ([0-9.]+, )*4( rad/s|, )")


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _titles(fig) -> str:
    parts = [fig._suptitle.get_text()] if fig._suptitle is not None else []
    parts += [ax.get_title() for ax in fig.axes]
    return "\n".join(parts)


def _map_info(omega=4.0, part=PART):
    info = ThrowMap(part, ARM, omega, "paper", 0.6).describe()
    info["label"] = "old label without h"
    return info


def _fake_basins(labels_cycle=(1, 2, -1), n=300):
    """Two sides, labels 1, 2 and −1 in stripes, throws 0 … 40: a basin map with a known colouring."""
    x = np.tile(np.linspace(0.05, 0.6, n), 2)
    side = np.repeat(np.array([0, 1], dtype=np.int64), n)
    labels = np.array(labels_cycle, dtype=np.int64)[(np.arange(2 * n) // 40) % len(labels_cycle)]
    throws = (np.arange(2 * n) % 41).astype(np.int64)
    atts = tuple(Attractor(id=i, kind="band", period=0, points=(), bands=((0, 0.1 * i, 0.1 * i + 0.05),),
                           multiplier=float("nan"), lyapunov=0.2, fraction=0.3, side_visits=((0, 1.0),))
                 for i in (1, 2))
    cert = types.SimpleNamespace(statement="not unique: 2 attractors")
    return Basins(x=x, side=side, labels=labels, fates=(labels == -1).astype(np.int64), throws=throws,
                  attractors=atts, certificate=cert, method="cells", check={}, caps={}, map_info=_map_info())


# ------------------------------------------------------------------ titles
def _throw_map():
    return throw_map_samples(PART, ARM, 4.0, model="paper", n=30).plot()


def _throw_map_compact():
    return throw_map_samples(PART, ARM, 4.0, model="paper", n=30).plot(compact=True)


def _orbit():
    return tm.iterate(PART, ARM, (0.12, 0), 4.0, n=10, model="paper").plot(part=PART, arm=ARM)


def _limit_set():
    return plot_limit_set(limit_set(PART, ARM, 4.0, model="paper", n_starts=4, n_record=64, transient=50))


def _basins():
    return plot_basins(_fake_basins())


def _funnels():
    graph = types.SimpleNamespace(funnels=(), edges=(), goal=ConfigSet.parse("0:0.5-0.9"), rank={},
                                  map_info={"maps": [_map_info(3.0), _map_info(4.0)]})
    return plot_funnel_graph(graph)


def _comparison():
    row = {"model": "small_angle", "omega": 4.0, "jog_rel_err_median": 0.1}
    comp = ModelComparison(PART.name, ARM.h, "paper", ("small_angle",), (row, dict(row, omega=2.0)))
    return comp.plot()


def _animation_still():
    return still(paper_trajectory(PART, ARM, 0.34, 1, 4.0), 0.1)


FIGURES = {"throw map": _throw_map, "throw map (Fig. 2 look)": _throw_map_compact, "orbit": _orbit,
           "limit set": _limit_set, "basins": _basins, "funnels": _funnels, "comparison": _comparison,
           "animation": _animation_still}


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_every_title_names_part_h_omega_and_model(name):
    text = _titles(FIGURES[name]())
    missing = [v for v in SETTING if v not in text] + ([] if OMEGA.search(text) else ["ω = 4"])
    assert not missing, f"{name}: title {text!r} lacks {missing}"


def test_orbit_title_says_what_it_was_not_told():
    """An orbit remembers its part and arm; one that was not told them (built by hand) says so in its title
    rather than leaving them out."""
    import dataclasses

    orbit = tm.iterate(PART, ARM, (0.12, 0), 4.0, n=3, model="paper")
    assert "h = -0.01 m" in _titles(orbit.plot())
    bare = dataclasses.replace(orbit, part=None, arm=None)
    assert "h = ?" in _titles(bare.plot(part=PART))
    assert "part ?" in _titles(bare.plot())


def test_weighted_and_plain_parts_get_different_titles():
    heavy = tm.triangle_30_60_90(0.17, point_masses=[(0.03, (0.10, 0.01))])
    a = _titles(throw_map_samples(PART, ARM, 4.0, model="paper", n=5).plot())
    b = _titles(throw_map_samples(heavy, ARM, 4.0, model="paper", n=5).plot())
    assert a != b and "lead" in b and "lead" not in a


def test_analysis_titles_state_the_range():
    assert "x ≤ 60 cm" in _titles(_basins()) and "x ≤ 60 cm" in _titles(_limit_set())


# ------------------------------------------------------------------ basin map
def test_basin_key_shows_the_colours_drawn():
    """Each key column is one drawn label, starting at that label's legend colour and fading as the lanes do."""
    fig = plot_basins(_fake_basins())
    ax, cax = fig.axes
    key = np.asarray(cax.images[0].get_array(), dtype=float)  # (rows, labels, 4)
    names = [t.get_text() for t in cax.get_xticklabels()]
    assert names == ["−1", "#1", "#2"]
    legend = {h.get_label().split()[0]: np.array(to_rgba(h.get_facecolor())) for h in ax.get_legend().legend_handles
              if isinstance(h, Patch)}
    assert set(legend) == {"#1", "#2", "−1:"}
    for j, nm in enumerate(names):
        np.testing.assert_allclose(key[0, j], legend[nm if nm != "−1" else "−1:"], atol=1e-12)
    # the ticks are throw counts, at the height where the key has that count's shade
    t_norm = math.log1p(40)
    lo, hi = cax.get_ylim()
    assert (lo, hi) == pytest.approx((0.0, t_norm))
    for pos, lab in zip(cax.get_yticks(), [t.get_text() for t in cax.get_yticklabels()]):
        v = int(lab)
        assert pos == pytest.approx(math.log1p(v))
        row = min(key.shape[0] - 1, int(round(pos / t_norm * (key.shape[0] - 1))))
        for j, nm in enumerate(names):
            want = shade(legend[nm if nm != "−1" else "−1:"], [v], t_norm)[0]
            np.testing.assert_allclose(key[row, j, :3], want[:3], atol=0.01)
    # every lane column's colour is in the key column of its label
    for im in ax.images:
        lane = np.asarray(im.get_array(), dtype=float)[0]
        for c in lane[lane[:, 3] > 0]:
            d = np.min(np.abs(key[:, :, :3] - c[None, None, :3]).max(axis=2))
            assert d < 0.01, f"lane colour {c} is not in the key"


def test_basin_axis_starts_at_the_joint():
    fig = plot_basins(_fake_basins())
    ax = fig.axes[0]
    assert ax.get_xlim()[0] == 0.0
    assert "joint" in ax.get_xlabel()


# ------------------------------------------------------------------ funnel labels
def test_funnel_labels_never_break_inside_an_interval():
    goal = ConfigSet.parse("0:0.5-0.9,1:0.5-0.9,2:0.5-0.9,3:0.123-0.4567")
    graph = types.SimpleNamespace(funnels=(), edges=(), goal=goal, rank={}, map_info={"maps": [_map_info()]})
    fig = plot_funnel_graph(graph)
    texts = [t.get_text() for t in fig.axes[0].texts] + [fig.axes[0].get_title()]
    goal_text = next(t for t in texts if t.startswith("goal"))
    assert goal_text.count("side") == 4
    for text in texts:
        for line in text.split("\n"):
            assert line.count("[") == line.count("]"), f"line {line!r} breaks an interval"
            assert not re.match(r"^\s*(cm|m)\b", line), f"line {line!r} starts with a unit"
            assert not line.rstrip().endswith(("=", "ω = 3")), f"line {line!r} breaks a setting"


def test_wrap_intervals_breaks_only_between_items():
    text = " ∪ ".join(f"side {k}: [{10 * k}, {10 * k + 5}] cm" for k in range(6))
    lines = wrap_intervals(text, 30)
    assert " ∪ ".join(lines) == text
    assert all(line.count("[") == line.count("]") == line.count("side") for line in lines)
    assert wrap_intervals("x" * 50, 10) == ["x" * 50]


# ------------------------------------------------------------------ animations
@pytest.fixture(scope="module")
def traj():
    return paper_trajectory(PART, ARM, 0.34, 1, 4.0)


@pytest.mark.parametrize("hold", [0.0, 0.5])
def test_reported_frame_count_is_the_frames_in_the_file(traj, tmp_path, hold):
    res = animate(traj, tmp_path / "a.gif", fps=10, speed=0.5, dpi=25, hold=hold)
    with PImage.open(res.path) as im:
        assert res.n_frames == im.n_frames
    assert res.frames_drawn == len(frame_times(traj, 10, 0.5, hold))
    assert res.n_frames <= res.frames_drawn
    assert res.fps == 10 and res.duration_s == pytest.approx(res.frames_drawn / 10)


def test_every_frame_has_a_scale_bar_of_the_length_it_says(traj):
    fig = still(traj, 0.1)
    ax = fig.axes[0]
    bars = [ln for ln in ax.lines if ln.get_gid() == "scale-bar"]
    labels = [t.get_text() for t in ax.texts if t.get_gid() == "scale-bar-label"]
    assert len(bars) == 1 and len(labels) == 1
    value, unit = labels[0].split()
    metres = float(value) * {"mm": 1e-3, "cm": 1e-2, "m": 1.0}[unit]
    assert np.ptp(bars[0].get_xdata()) == pytest.approx(metres)
    assert np.ptp(bars[0].get_ydata()) == 0.0
    width = np.diff(ax.get_xlim())[0]
    assert width / 10 < metres <= width / 5  # readable: a fifth of the view at most


@pytest.mark.parametrize("width, bar", [(0.5, 0.1), (0.26, 0.05), (0.099, 0.01), (3.0, 0.5), (12.0, 2.0)])
def test_scale_bar_length_is_a_round_fifth(width, bar):
    assert scale_bar_length(width) == pytest.approx(bar)


def test_mid_flight_is_labelled_flight_not_release(traj):
    t_impact = next(t for t, lab in traj.events if lab.startswith("impact"))
    phase = {t: next(x.get_text() for x in still(traj, t).axes[0].texts if x.get_gid() == "phase")
             for t in (0.0, 0.5 * t_impact)}
    assert "release" in phase[0.0]
    assert "flight" in phase[0.5 * t_impact] and "release" not in phase[0.5 * t_impact]
    # every frame of an animation between the release frame and the impact says flight
    step = 0.5 / 10
    for t in frame_times(traj, 10, 0.5):
        label = frame_label(list(traj.events), float(t), step)
        if step <= t < t_impact:
            assert label == "flight", (t, label)
        if t_impact + step <= t < traj.t[-1]:
            assert "release" not in label and "impact" in label and "contact" in label, (t, label)
