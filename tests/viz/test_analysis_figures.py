"""Figures of the analysis objects (paper Figs. 2 and 5 analogues, basin maps, funnel graphs).

Small real runs of the paper's triangle (model "paper", ω = 4 rad/s) and synthetic
function maps with known attractors; every figure is also written to a PNG.
"""

import subprocess
import sys
import types

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch  # noqa: E402

from throwmap import Arm, Status, iterate, triangle_30_60_90  # noqa: E402
from throwmap.analysis import FunctionMap, limit_set  # noqa: E402
from throwmap.throws.samples import sample_map  # noqa: E402
from throwmap.viz.basins import plot_basins  # noqa: E402
from throwmap.viz.funnels import plot_funnel_graph  # noqa: E402
from throwmap.viz.limit_set import plot_limit_set  # noqa: E402
from throwmap.viz.throw_map import plot_map  # noqa: E402
from throwmap.analysis.attractors import Attractor  # noqa: E402
from throwmap.analysis.basins import Basins, basins  # noqa: E402
from throwmap.analysis.critical import critical_points  # noqa: E402
from throwmap.errors import InvalidStateError  # noqa: E402

OMEGA = 4.0


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def part():
    return triangle_30_60_90(0.17)


@pytest.fixture(scope="module")
def arm():
    return Arm(h=-0.01)


@pytest.fixture(scope="module")
def limit(part, arm):
    return limit_set(part, arm, OMEGA, model="paper", n_starts=8, n_record=64, transient=50)


@pytest.fixture(scope="module")
def critical(part, arm):
    return critical_points(part, arm, OMEGA, model="paper")


@pytest.fixture(scope="module")
def basin_map(part, arm):
    return basins(part, arm, OMEGA, model="paper", grid=150)


@pytest.fixture(scope="module")
def orbit(part, arm):
    return iterate(part, arm, (0.2, 0), OMEGA, 60, model="paper")


@pytest.fixture(scope="module")
def contraction():
    """x ↦ 0.2 + (x − 0.2)/2 on one side: a fixed point at 0.2 m with multiplier 0.5."""
    return FunctionMap(lambda x, s: (0.2 + 0.5 * (x - 0.2), s, 0 * s), {0: (0.0, 0.5)}, name="contraction")


@pytest.fixture(scope="module")
def two_cycle():
    """Flips between two sides onto the period-2 cycle (0.2 m, 0) ↔ (0.3 m, 1)."""
    def f(x, s):
        return np.where(s == 0, 0.3 + 0.5 * (x - 0.2), 0.2 + 0.3 * (x - 0.3)), 1 - s, 0 * s

    return FunctionMap(f, {0: (0.0, 0.5), 1: (0.0, 0.5)}, name="two-cycle")


@pytest.fixture(scope="module")
def bistable():
    """Two fixed points (0.1 m and 0.4 m, side 0); x above 0.45 m leaves the arm (off_end)."""
    def f(x, s):
        xn = np.where(x < 0.25, 0.1 + 0.5 * (x - 0.1), 0.4 + 0.5 * (x - 0.4))
        return xn, s, np.where(x > 0.45, 2, 0)

    return FunctionMap(f, {0: (0.0, 0.5)}, name="bistable")


def _texts(ax):
    return [t.get_text() for t in ax.texts]


def _gids(ax, kind):
    return [a for a in getattr(ax, kind) if a.get_gid()]


# --- import ---------------------------------------------------------------------------------


def test_import_does_not_load_matplotlib():
    code = ("import sys, throwmap.viz.style, throwmap.viz.throw_map, throwmap.viz.orbit, throwmap.viz.limit_set, "
            "throwmap.viz.basins, throwmap.viz.funnels, throwmap.viz.comparison, throwmap.throws.samples; "
            "print('matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_bad_unit_is_refused(limit):
    with pytest.raises(InvalidStateError, match="unit"):
        plot_limit_set(limit, unit="inch")


# --- Fig. 5 analogue ------------------------------------------------------------------------


def test_limit_set_triangle_with_critical_and_orbit(limit, critical, orbit, tmp_path):
    fig = plot_limit_set(limit, critical=critical, orbit=orbit, n_arrows=20)
    assert isinstance(fig, Figure)
    ax = fig.axes[0]
    # one lane per stable side, labelled
    assert [t.get_text() for t in ax.get_yticklabels()] == ["side 0", "side 1", "side 2"]
    # r_i and l_i on every lane
    texts = _texts(ax)
    for s in critical.sides:
        assert f"$r_{{{s}}}$" in texts and f"$l_{{{s}}}$" in texts
    assert {c.get_gid() for c in ax.collections} >= {"critical-r", "critical-l", "attractor-1"}
    # the last 20 throws as arrows, jogs arcing along a lane and flips crossing lanes
    arrows = [p for p in ax.patches if isinstance(p, FancyArrowPatch) and p.get_gid() == "orbit"]
    assert len(arrows) == 20
    title = ax.get_title()
    assert "band" in title and all(v in title for v in (limit.map_info["part"], "h = -0.01 m", "ω = 4", "'paper'"))
    # x axis in cm: the band reaches past 40 cm on side 0
    assert ax.get_xlim()[1] > 40
    fig.savefig(tmp_path / "limit_set.png")
    assert (tmp_path / "limit_set.png").stat().st_size > 0


def test_limit_set_in_given_axes_and_metres(limit):
    fig, (a0, a1) = plt.subplots(1, 2)
    out = plot_limit_set(limit, ax=a1, unit="m")
    assert out is fig
    assert not a0.has_data() and a1.has_data()
    assert a1.get_xlim()[1] < 1.0  # metres
    assert "(m;" in a1.get_xlabel()


def test_limit_set_cycle_draws_dots_and_its_throws(two_cycle, tmp_path):
    lim = limit_set(two_cycle, n_starts=6, transient=30, n_record=64)
    assert lim.kind == "cycle"
    crit = critical_points(two_cycle)
    fig = plot_limit_set(lim, critical=crit)
    ax = fig.axes[0]
    dots = [c for c in ax.collections if c.get_gid() == "attractor-1"]
    assert len(dots) == 1 and len(dots[0].get_offsets()) == 2
    # the cycle's two throws are flips between the two lanes
    cyc = [p for p in ax.patches if isinstance(p, FancyArrowPatch) and p.get_gid() == "cycle"]
    assert len(cyc) == 2
    assert "period-2 cycle" in " ".join(t.get_text() for t in ax.get_legend().get_texts())
    fig.savefig(tmp_path / "cycle.png")


def test_limit_set_several_attractors_and_escapes(bistable):
    lim = limit_set(bistable, n_starts=16, transient=30, n_record=64)
    assert len(lim.attractors) == 2 and "off_end" in lim.escapes
    fig = plot_limit_set(lim)
    ax = fig.axes[0]
    assert {"#1", "#2"} <= set(_texts(ax))
    legend = " ".join(t.get_text() for t in ax.get_legend().get_texts())
    assert "off_end" in legend


def test_limit_set_all_escape_still_draws(tmp_path):
    away = FunctionMap(lambda x, s: (x + 0.1, s, np.where(x > 0.3, 2, 0)), {0: (0.0, 0.5)}, name="walks off")
    lim = limit_set(away, n_starts=8, transient=10, n_record=64)
    assert lim.kind == "escape"
    fig = plot_limit_set(lim)
    ax = fig.axes[0]
    assert any("every orbit escapes" in t for t in _texts(ax))
    assert [t.get_text() for t in ax.get_yticklabels()] == ["side 0"]
    fig.savefig(tmp_path / "escape.png")


def test_limit_set_escaping_orbit_is_marked(limit):
    out = [types.SimpleNamespace(kind="jog", status=Status.OK, x=0.25),
           types.SimpleNamespace(kind="flip", status=Status.OK, x=0.3),
           types.SimpleNamespace(kind="off_end", status=Status.OFF_END, x=0.7)]
    orb = types.SimpleNamespace(x=np.array([0.2, 0.25, 0.3]), side=np.array([0, 0, 1]), outcomes=tuple(out),
                                status=Status.OFF_END, escaped=True)
    fig = plot_limit_set(limit, orbit=orb)
    ax = fig.axes[0]
    assert any(c.get_gid() == "escape" for c in ax.collections)
    assert len([p for p in ax.patches if isinstance(p, FancyArrowPatch) and p.get_gid() == "orbit"]) == 2


def test_limit_set_rejects_bad_n_arrows(limit):
    with pytest.raises(InvalidStateError, match="n_arrows"):
        plot_limit_set(limit, n_arrows=-1)


def test_limit_set_plot_method(limit):
    assert isinstance(limit.plot(), Figure)


# --- Fig. 2 analogue ------------------------------------------------------------------------


def test_map_of_throw_map_with_critical_and_limit(part, arm, critical, limit, tmp_path):
    from throwmap.analysis import as_map

    cmap = as_map(part, arm, OMEGA, "paper")
    fig = plot_map(sample_map(cmap, 400), critical=critical, limit=limit)
    assert len(fig.axes) == len(cmap.sides) == 3
    for ax, s in zip(fig.axes, cmap.sides):
        gids = {l.get_gid() for l in ax.lines}
        assert {"critical-r", "critical-l"} <= gids
        assert f"$r_{{{s}}}$" in _texts(ax)
        # the limit set shaded on this side
        assert any(type(p).__name__ == "Rectangle" and p.get_alpha() == pytest.approx(0.12) for p in ax.patches)
        assert ax.get_title() == f"side {s}"
    fig.savefig(tmp_path / "map.png")


def test_map_of_function_map_marks_the_fixed_point(contraction, tmp_path):
    lim = limit_set(contraction, n_starts=4, transient=30, n_record=64)
    assert lim.kind == "fixed_point"
    fig, ax = plt.subplots()
    out = plot_map(sample_map(contraction, 50), axes=ax, limit=lim)
    assert out is fig
    fp = [c for c in ax.collections if c.get_gid() == "attractor-1"]
    assert len(fp) == 1
    np.testing.assert_allclose(fp[0].get_offsets()[0], [20.0, 20.0], atol=1e-6)  # (x, T(x)) in cm
    assert ax.get_legend() is not None
    fig.savefig(tmp_path / "contraction.png")


def test_map_escapes_drawn_on_the_axis(bistable):
    fig = plot_map(sample_map(bistable, 100))
    esc = [c for c in fig.axes[0].collections if c.get_gid() == "escapes"]
    assert len(esc) == 1 and len(esc[0].get_offsets()) == 10  # x in (0.45, 0.5]


def test_map_needs_one_axes_per_side(two_cycle):
    fig, ax = plt.subplots()
    with pytest.raises(InvalidStateError, match="axes"):
        plot_map(sample_map(two_cycle), axes=[ax])


# --- basins ---------------------------------------------------------------------------------


def test_basins_triangle(basin_map, tmp_path):
    fig = plot_basins(basin_map)
    ax = fig.axes[0]
    assert len(ax.images) == 3  # one lane per side
    for im in ax.images:
        assert im.get_array().shape[:2][0] == 1 and im.get_array().shape[1] <= 2000
    assert len(fig.axes) == 2  # and the colour bar of the shade
    assert basin_map.certificate.statement[:30] in ax.get_title()
    fig.savefig(tmp_path / "basins.png")


def _fake_basins(n_per_side=500_000):
    x = np.concatenate([np.linspace(0.05, 0.6, n_per_side), np.linspace(0.1, 0.6, n_per_side)])
    side = np.repeat(np.array([0, 1], dtype=np.int64), n_per_side)
    labels = np.where(x < 0.2, -1, np.where(x < 0.4, 1, 2)).astype(np.int64)
    throws = (np.abs(np.sin(40 * x)) * 50).astype(np.int64)
    fates = np.where(labels == -1, 1, 0).astype(np.int64)
    atts = tuple(Attractor(id=i, kind="band", period=0, points=(), bands=((0, 0.1 * i, 0.1 * i + 0.05),),
                           multiplier=float("nan"), lyapunov=0.2, fraction=0.4, side_visits=((0, 1.0),))
                 for i in (1, 2))
    cert = types.SimpleNamespace(statement="not unique: 2 attractor(s) and escapes share the grid " * 3)
    return Basins(x=x, side=side, labels=labels, fates=fates, throws=throws, attractors=atts, certificate=cert,
                  method="cells", check={}, caps={}, map_info={"label": "fake"})


def test_basins_million_points_binned(tmp_path):
    b = _fake_basins()
    assert b.n_configs == 10**6
    fig, ax = plt.subplots()
    out = plot_basins(b, ax=ax, max_columns=800)
    assert out is fig
    assert len(ax.images) == 2
    assert all(im.get_array().shape[1] <= 800 for im in ax.images)
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(t.startswith("−1: escapes") and "behind_joint" in t for t in legend)
    assert len(ax.get_title()) < 200  # the statement is shortened
    # label −1 is near-black where the escapes are, on side 0 below 0.2 m, fully saturated where throws = 0
    img = ax.images[0].get_array()
    first = img[0, 0]
    assert np.all(np.asarray(first[:3]) < 0.9) and first[3] == 1.0
    fig.savefig(tmp_path / "basins_big.png")


def test_basins_mode_label_per_column():
    from throwmap.viz.basins import _bin_lane

    x = np.array([0.0, 0.1, 0.2, 0.3, 0.9, 1.0])
    labels = np.array([1, 1, 2, -1, 2, 2])
    throws = np.array([0, 2, 4, 6, 1, 3])
    edges = np.array([0.0, 0.5, 1.0 + 1e-12])
    mode, mean_t, total = _bin_lane(x, labels, throws, edges, np.array([-1, 1, 2]))
    assert total.tolist() == [4, 2]
    assert mode.tolist() == [1, 2]  # indices into [-1, 1, 2]: label 1, then label 2
    np.testing.assert_allclose(mean_t, [3.0, 2.0])


def test_basins_plot_method(basin_map):
    assert isinstance(basin_map.plot(max_columns=50), Figure)
    with pytest.raises(InvalidStateError, match="max_columns"):
        plot_basins(basin_map, max_columns=0)


# --- funnel graph ---------------------------------------------------------------------------


def _att(i, kind):
    return Attractor(id=i, kind=kind, period=1 if kind == "fixed_point" else 0,
                     points=((0, 0.1 * i),) if kind == "fixed_point" else (),
                     bands=((0, 0.1 * i, 0.1 * i + (0.0 if kind == "fixed_point" else 0.02)),),
                     multiplier=0.5, lyapunov=-0.7, fraction=0.3, side_visits=((0, 1.0),))


def _stand_in_graph():
    fun = tuple(types.SimpleNamespace(name=f"ω={w:g} #{j}", omegas=(float(w),),
                                      attractor=_att(j, "band" if j % 2 else "fixed_point"),
                                      mouth_fraction=0.1 * j)
                for j, w in enumerate([4, 5, 6, 4.5, 7], start=1))
    goal = types.SimpleNamespace(intervals=((0, 0.2, 0.3),), describe=lambda: "side 0: [0.2, 0.3] m")
    return types.SimpleNamespace(funnels=fun, edges=((1, 0, 1.0), (2, 0, 0.97), (3, 1, 1.0), (4, 3, 1.0)),
                                 goal=goal, rank={0: 0, 1: 1, 2: 1, 3: 2, 4: None})


def test_funnel_graph_layers_by_rank(tmp_path):
    g = _stand_in_graph()
    fig = plot_funnel_graph(g)
    ax = fig.axes[0]
    boxes = {p.get_gid(): p for p in ax.patches if isinstance(p, FancyBboxPatch)}
    assert set(boxes) == {"goal", "funnel-0", "funnel-1", "funnel-2", "funnel-3", "funnel-4"}
    y = {k: b.get_y() for k, b in boxes.items()}
    assert y["goal"] > y["funnel-0"] > y["funnel-1"] == y["funnel-2"] > y["funnel-3"] > y["funnel-4"]
    arrows = [p for p in ax.patches if isinstance(p, FancyArrowPatch)]
    assert len(arrows) == len(g.edges) + 1  # and rank 0 → goal
    texts = _texts(ax)
    assert "97 %" in texts and "in goal" in texts
    assert any("ω = 4.5 rad/s" in t and "mouth 40.0 %" in t for t in texts)
    assert "priority: ω=4 #1" in ax.get_title()
    fig.savefig(tmp_path / "funnels.png")


def test_funnel_graph_real_object_in_given_axes(tmp_path):
    from throwmap.analysis.funnels import ConfigSet, funnels

    to10 = FunctionMap(lambda x, s: (0.1 + 0.5 * (x - 0.1), s, 0 * s), {0: (0.0, 0.5)}, name="to 10 cm")
    to30 = FunctionMap(lambda x, s: (0.3 + 0.5 * (x - 0.3), s, 0 * s), {0: (0.0, 0.5)}, name="to 30 cm")
    g = funnels(None, maps=[to10, to30], goal=ConfigSet(((0, 0.29, 0.31),)), grid=60)
    fig, ax = plt.subplots()
    assert plot_funnel_graph(g, ax=ax) is fig
    assert len([p for p in ax.patches if isinstance(p, FancyBboxPatch)]) == 3
    assert any(t.startswith("goal\nside 0: [29, 31] cm") for t in _texts(ax))
    assert isinstance(g.plot(), Figure)
    fig.savefig(tmp_path / "funnels_real.png")


def test_funnel_graph_without_goal_or_funnels():
    g = _stand_in_graph()
    g.goal = None
    g.rank = {i: None for i in range(len(g.funnels))}
    ax = plot_funnel_graph(g).axes[0]
    assert "goal" not in {p.get_gid() for p in ax.patches}
    empty = types.SimpleNamespace(funnels=(), edges=(), goal=None, rank={})
    assert "no funnels" in _texts(plot_funnel_graph(empty).axes[0])


def test_critical_points_plot_marks_r_and_l_per_side(triangle, arm):
    """CriticalPoints.plot: one row per stable side, r_i drawn where the object says, in the axis unit."""
    from throwmap import critical_points

    cp = critical_points(triangle, arm, 4.0, "paper")
    fig = cp.plot(unit="cm")
    ax = fig.axes[0]
    assert [t.get_text() for t in ax.get_yticklabels()] == [f"side {s}" for s in cp.sides]
    r_marks = sorted(float(line.get_xdata()[0]) for line in ax.lines if line.get_marker() == "|")
    assert r_marks == pytest.approx(sorted(100 * cp.r[s] for s in cp.sides))
    plt.close(fig)


def test_funnel_graph_has_a_key_of_mouth_spout_and_priority(tmp_path):
    ax = plot_funnel_graph(_stand_in_graph()).axes[0]
    key = next(t for t in ax.texts if t.get_gid() == "key").get_text().replace("\n", " ")
    assert all(w in key for w in ("mouth:", "spout:", "priority k:", "dashed: spout inside the goal"))
    ax.figure.savefig(tmp_path / "funnels_key.png")
