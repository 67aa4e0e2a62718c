"""fixtures= and alpha= through every entry point (issue 11, item 2): handed to the model, recorded in the
results, refused by models without the feature; and the fixed point a wall makes, found by limit_set.

A synthetic registered model (``walled_jog``) makes the plumbing checkable without any physics: it
jogs every part outward by a fixed step that the rest angle shortens, stops it against a wall at
x* = length − u_R (the last start throw() accepts), and records the System each call received.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.analysis import ThrowMap
from throwmap.errors import InvalidStateError
from throwmap.kernels import codes as C
from throwmap.models import get_model, model_names
from throwmap.models.base import BatchArrays, Features, NoOptions
from throwmap.models.registry import register, unregister
from throwmap.records.outcome import ThrowOutcome
from throwmap.system.starts import start_interval

STEP = 0.02
"""The synthetic jog at ω = 1 rad/s and α = 0, m."""


class WalledJog:
    """T(x, k) = (min(x + STEP·ω·(1 − α), x*_k), k) with a wall, else off_end past x*_k."""

    name = "walled_jog"
    summary = "test model: a jog that stops at the wall"
    options_type = NoOptions
    features = Features(fixtures=True, tilt=True, parallel=False)

    def __init__(self):
        self.seen = []

    def throw_batch(self, part, system, x, side, omega, valid, options, progress=None):
        self.seen.append((system.fixtures, system.alpha))
        hi = np.array([start_interval(part, system.arm, int(k))[1] for k in side])
        xn = x + STEP * omega * (1.0 - system.alpha)
        wall = any(isinstance(f, tm.Wall) for f in system.fixtures)
        status = np.zeros(x.size, dtype=np.int64)
        if wall:
            xn = np.minimum(xn, hi)
        else:
            status[xn > hi] = C.OFF_END
        status[~valid] = C.INVALID_START
        return BatchArrays(np.where(valid, xn, x), side.copy(), status, np.full((x.size, C.NREC), np.nan))

    def throw_one(self, part, system, x, side, omega, options):
        b = self.throw_batch(part, system, np.array([x]), np.array([side]), np.array([omega]), np.array([True]),
                             options)
        return float(b.x[0]), int(b.side[0]), int(b.status[0]), b.records[0]

    def trajectory(self, part, system, x, side, omega, options, dt):  # features.trajectory is False
        raise NotImplementedError


@pytest.fixture
def model():
    m = WalledJog()
    register(m, replace=True)
    yield m
    unregister(m.name)


PART = tm.triangle_30_60_90()
ARM = tm.Arm(h=-0.01, mu=1.0, length=0.30)
WALL = tm.Wall(0.05, mu=0.0)
ALPHA = math.radians(5.0)
KW = {"fixtures": (WALL,), "alpha": ALPHA}
SMALL = {"transient": 20, "n_record": 10, "max_period": 2, "n_fill": 20, "fill_rounds": 1}


def test_wall_and_cavity_are_importable_from_throwmap():
    assert tm.Wall is not None and tm.Cavity is not None
    assert "Wall" in tm.__all__ and "Cavity" in tm.__all__


def _calls():
    """Every entry point, each called with the walled, tilted system (model given by keyword)."""
    return {
        "throw": lambda m: tm.throw(PART, ARM, 0.15, 0, 1.0, m, **KW),
        "throw_batch": lambda m: tm.throw_batch(PART, ARM, [0.15, 0.2], 0, 1.0, m, **KW),
        "iterate": lambda m: tm.iterate(PART, ARM, (0.15, 0), 1.0, 3, m, **KW),
        "ThrowMap": lambda m: ThrowMap(PART, ARM, 1.0, m, None, dict(KW))(np.array([0.15]), np.array([0])),
        "critical_points": lambda m: tm.critical_points(PART, ARM, 1.0, m, n_grid=8, **KW),
        "limit_set": lambda m: tm.limit_set(PART, ARM, 1.0, m, n_starts=3, **SMALL, **KW),
        "basins": lambda m: tm.basins(PART, ARM, 1.0, m, grid=20, n_seeds=3, max_throws=50, n_check=0, **SMALL, **KW),
        "funnels": lambda m: tm.funnels(PART, ARM, [1.0, 2.0], m, grid=10, n_seeds=2, max_throws=50, **SMALL, **KW),
        "push": lambda m: tm.push(PART, ARM, [1.0, 1.0], "0:0.12-0.15", m, n=4, **KW),
    }


@pytest.mark.parametrize("entry", list(_calls()))
def test_every_entry_point_hands_fixtures_and_alpha_to_the_model(model, entry):
    _calls()[entry](model.name)
    assert model.seen, "the model was never called"
    assert all(fx == (WALL,) and a == ALPHA for fx, a in model.seen)


@pytest.mark.parametrize("entry", list(_calls()))
@pytest.mark.parametrize("key", ["alpha", "fixtures"])
def test_models_without_the_feature_refuse_it_from_every_entry_point(entry, key):
    feature = {"alpha": "tilt", "fixtures": "fixtures"}[key]
    lacking = [n for n in model_names() if not getattr(get_model(n).features, feature)]
    able = [n for n in model_names() if getattr(get_model(n).features, feature)]
    assert lacking and able
    for name in lacking:
        kw = {key: KW[key]}
        with pytest.raises(InvalidStateError) as err:
            if entry == "throw":
                tm.throw(PART, ARM, 0.15, 0, 1.0, name, **kw)
            elif entry == "ThrowMap":
                ThrowMap(PART, ARM, 1.0, name, None, kw)
            else:
                _refused(entry, name, kw)
        msg = str(err.value)
        assert err.value.field == key and "\n" not in msg
        assert f"(model is {name!r})" in msg and all(repr(a) in msg for a in able)


def _refused(entry, name, kw):
    calls = {
        "throw_batch": lambda: tm.throw_batch(PART, ARM, [0.15], 0, 1.0, name, **kw),
        "iterate": lambda: tm.iterate(PART, ARM, (0.15, 0), 1.0, 3, name, **kw),
        "critical_points": lambda: tm.critical_points(PART, ARM, 1.0, name, **kw),
        "limit_set": lambda: tm.limit_set(PART, ARM, 1.0, name, **kw),
        "basins": lambda: tm.basins(PART, ARM, 1.0, name, **kw),
        "funnels": lambda: tm.funnels(PART, ARM, [1.0], name, **kw),
        "push": lambda: tm.push(PART, ARM, [1.0], "0:0.12-0.15", name, **kw),
    }
    calls[entry]()


def test_results_record_alpha_and_fixtures(model):
    ls = tm.limit_set(PART, ARM, 1.0, model.name, n_starts=3, **SMALL, **KW)
    b = tm.basins(PART, ARM, 1.0, model.name, grid=20, n_seeds=3, max_throws=50, n_check=0, **SMALL, **KW)
    cp = tm.critical_points(PART, ARM, 1.0, model.name, n_grid=8, **KW)
    fg = tm.funnels(PART, ARM, [1.0], model.name, grid=10, n_seeds=2, max_throws=50, **SMALL, **KW)
    for info in (ls.map_info, b.map_info, cp.map_info, fg.map_info["maps"][0]):
        assert info["alpha_rad"] == ALPHA
        assert info["fixtures"] == [{"kind": "wall", "height_m": 0.05, "thickness_m": 0.01, "mu": 0.0}]
    for text in (repr(ls), repr(b), repr(cp), repr(fg)):
        assert "alpha=5°" in text and "wall 5 cm (μ 0)" in text, text
    assert "α = 5°, wall 5 cm (μ 0)" in ls.summary()
    back = tm.analysis.LimitSet.from_dict(ls.to_dict())
    assert back.map_info["fixtures"] == ls.map_info["fixtures"] and back.wall_points == ls.wall_points
    tm_map = ThrowMap(PART, ARM, 1.0, model.name, None, {"fixtures": tm.Wall(0.05), "alpha": 0})
    assert tm_map.describe()["fixtures"][0]["mu"] == "arm" and "wall 5 cm (arm μ)" in repr(tm_map)


def test_the_domain_ends_at_the_wall(model):
    """x_max defaults to the arm length; the last start on side k is length − u_R, where the part touches the wall."""
    cmap = ThrowMap(PART, ARM, 1.0, model.name, None, dict(KW))
    assert cmap.x_max == ARM.length
    for k in cmap.sides:
        assert cmap.x_hi[k] == start_interval(PART, ARM, k)[1]
        assert cmap.x_hi[k] + PART.uR[k] <= ARM.length < math.nextafter(cmap.x_hi[k], 1) + PART.uR[k]


def test_limit_set_finds_the_superstable_fixed_point_at_the_wall(model):
    ls = tm.limit_set(PART, ARM, 1.0, model.name, n_starts=8, **KW)
    assert [a.kind for a in ls.attractors] == ["fixed_point"] * len(PART.stable_sides)
    assert not ls.escapes
    walls = ls.wall_points
    assert sorted(s for s, _ in walls.values()) == sorted(PART.stable_sides)
    for a in ls.attractors:
        (side, x), = a.points
        assert x == start_interval(PART, ARM, side)[1]  # exactly x* = length − u_R
        assert a.multiplier == 0.0 and a.residual == 0.0 and a.stable
        assert walls[a.id] == (side, x)
    assert "against the wall" in ls.summary() and "left derivative" in ls.summary()
    assert [d["id"] for d in ls.to_dict()["at_wall"]] == [a.id for a in ls.attractors]


def test_without_the_wall_the_same_jogs_leave_the_arm(model):
    ls = tm.limit_set(PART, ARM, 1.0, model.name, n_starts=4, alpha=ALPHA)
    assert not ls.attractors and set(ls.escapes) == {"off_end"} and ls.wall_points == {}


def test_a_fixed_point_at_x_max_below_the_wall_is_not_called_a_wall_point(model):
    """With x_max short of the wall the domain ends at x_max, and no attractor there touches the wall."""
    ls = tm.limit_set(PART, ARM, 1.0, model.name, n_starts=4, x_max=0.2, **KW)
    assert ls.wall_points == {}


def test_tilt_changes_the_map_the_model_sees(model):
    level = tm.throw(PART, ARM, 0.15, 0, 1.0, model.name)
    tilted = tm.throw(PART, ARM, 0.15, 0, 1.0, model.name, alpha=ALPHA)
    assert level.x - 0.15 == pytest.approx(STEP) and tilted.x - 0.15 == pytest.approx(STEP * (1 - ALPHA))
    assert model.seen[-2] == ((), 0.0) and model.seen[-1] == ((), ALPHA)


def test_orbit_records_do_not_lose_the_system(model):
    o = tm.iterate(PART, ARM, (0.15, 0), 1.0, 20, model.name, **KW)
    assert o.x[-1] == start_interval(PART, ARM, 0)[1]  # stopped by the wall, not escaped
    assert o.status == tm.Status.OK
    out: ThrowOutcome = o.outcomes[-1]
    assert dataclasses.is_dataclass(out)


def test_the_throw_map_figure_is_sampled_up_to_the_wall_and_draws_it(model):
    pytest.importorskip("matplotlib")
    fig = tm.plot_throw_map(PART, ARM, 1.0, model=model.name, n=40, **KW)
    title = fig._suptitle.get_text()
    assert "α = 5°, wall 5 cm (μ 0)" in title.replace("\n", " ")
    walls = [a for ax in fig.axes for a in ax.get_lines() if a.get_gid() == "wall"]
    assert len(walls) == len(PART.stable_sides)  # one stop per panel, at T = length − u_R
    for ax, k in zip(fig.axes, PART.stable_sides):
        xs = np.concatenate([c.get_offsets()[:, 0] for c in ax.collections if c.get_gid() == "branch-" + str(k)])
        assert xs.max() == pytest.approx(100 * start_interval(PART, ARM, k)[1])  # the last start: at the wall
        assert not [c for c in ax.collections if c.get_gid() == "escapes"]  # no start past the wall
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_an_animation_draws_the_tilted_arm_and_the_wall_and_names_them():
    pytest.importorskip("pymunk")
    pytest.importorskip("matplotlib")
    from throwmap.throws.orbit_trajectory import throw_trajectory
    from throwmap.viz.frames import _default_title

    _, traj = throw_trajectory(PART, ARM, 0.2, 0, 5.0, "engine", fixtures=(WALL,), alpha=math.radians(8))
    assert np.allclose(traj.arm_angle, math.radians(8)) and traj.fixtures == (WALL,)
    title = _default_title(traj)
    assert "α = 8°" in title and "wall 5 cm (μ 0)" in title


def test_wall_fixed_point_checks_the_multiplier_by_left_differences(model):
    from throwmap.analysis.wall import wall_fixed_point
    from throwmap.studies.tilt_wall import TiltWallReport

    fp = wall_fixed_point(PART, ARM, 1.0, 0, wall=WALL, model=model.name, n_starts=4, reference=model.name)
    x_star = start_interval(PART, ARM, 0)[1]
    assert fp.found and fp.x_star_m == x_star == fp.x_wall_m
    assert fp.multiplier == 0.0 and list(fp.fd_left) == [0.0] * 4 and fp.n_at_wall == 3
    assert math.isnan(fp.free_slope)  # without the wall x* jogs off the end: no slope there
    assert [g["dx_from_x_wall_m"] for g in fp.reference["images"]] == [0.0, 0.0, 0.0] and fp.gap_m == 0.0
    lines = TiltWallReport((), {}, fp, {}).fixed_point_lines()
    assert "multiplier +0" in lines[0] and "h = 1e-06 m: +0" in lines[1] and "T(x_w -5 mm) − x_w = +0 µm" in lines[2]
    assert fp.to_dict()["found"] is True and fp.to_dict()["fd_left"] == [0.0] * 4
    missing = wall_fixed_point(PART, ARM, 1.0, 0, wall=WALL, model="small_angle")
    assert not missing.found and "fixtures" in missing.message
    assert "NOT found" in TiltWallReport((), {}, missing, {}).fixed_point_lines()[0]
