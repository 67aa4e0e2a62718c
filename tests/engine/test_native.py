"""The engine's C helper (:mod:`throwmap.engine.pymunk.native`) gives the runs of the engine's Python code bit for
bit: the friction hook (one part, fixtures, several parts), the exact contact solve (with its mode enumeration),
the step loop, the checks, exact flight and trajectories; and its Python arithmetic (``math.hypot``, float ``%``)
is CPython's."""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.engine import (
    FiniteThrow,
    Friction,
    ImpulseThrow,
    Placement,
    RecoilThrow,
    Scene,
    TiltTo,
    simulate,
)
from throwmap.engine.pymunk import exact, native
from throwmap.system.fixtures import Cavity, Wall

TRI = tm.triangle_30_60_90(0.17)
LEAD = tm.triangle_30_60_90(0.17, point_masses=[(0.03, (0.1, 0.01))])
PENTAGON = tm.regular_polygon(5, 0.05)
SQUARE = tm.rectangle(0.06, 0.06)


def test_the_helper_is_built_and_used():
    assert native.available(), native.reason()
    with native.disabled():
        assert not native.available()
    assert native.available()


def _key(run):
    traj = run.trajectory
    return (run.status, run.statuses, run.states, run.poses, run.records.tobytes(), run.t_end, run.n_steps,
            run.n_leaps, run.n_coarse, run.n_checks, run.n_clearance, run.n_capped, run.penetration_max,
            run.energy_gain, run.alpha, run.message, run.retries, run.verified,
            None if traj is None else (traj.t.tobytes(), traj.poses.tobytes(), traj.arm_angle.tobytes(),
                                       tuple(c.tobytes() for c in traj.contacts), traj.events))


def _both(scene, real, record=False):
    fast = simulate(scene, real, record=record)
    with native.disabled():
        slow = simulate(scene, real, record=record)
    return fast, slow


CASES = {
    "bare arm": (Scene(tm.Arm(h=-0.01, mu=1.5), (Placement(TRI, x=0.3, side=1),)), ImpulseThrow(5.0)),
    "no slip": (Scene(tm.Arm(h=-0.01, mu=math.inf), (Placement(TRI, x=0.2, side=0),)), ImpulseThrow(5.0)),
    "pentagon": (Scene(tm.Arm(h=-0.005, mu=0.6), (Placement(PENTAGON, x=0.1, side=2),)), ImpulseThrow(6.5)),
    "wall, tilted": (Scene(tm.Arm(h=-0.01, mu=math.inf, length=0.35), (Placement(LEAD, x=0.2, side=0),),
                           (Wall(0.05, mu=0.5),), 0.1), ImpulseThrow(4.5)),
    "cavity, lined": (Scene(tm.Arm(h=-0.01, mu=1.5, length=0.45), (Placement(TRI, x=0.12, side=1),),
                            (Cavity(((0.08, 0.0), (0.07, -0.01), (0.0, -0.01)), lined=True), Wall(0.05, mu=0.2))),
                      ImpulseThrow(4.0)),
    "recoil": (Scene(tm.Arm(h=-0.01, mu=1.5), (Placement(TRI, x=0.25, side=1),)),
               RecoilThrow.for_release_rate(5.0)),
    "finite throw": (Scene(tm.Arm(h=-0.01, mu=math.inf), (Placement(LEAD, x=0.2, side=1),)), FiniteThrow(5.0, 0.02)),
    "tilt to a wall": (Scene(tm.Arm(h=-0.01, mu=0.8, length=0.35), (Placement(PENTAGON, x=0.15, side=0),),
                             (Wall(0.05, mu=0.0),)), TiltTo(-0.15, 0.4)),
    "two parts": (Scene(tm.Arm(h=-0.01, mu=1.2, length=0.4),
                        (Placement(TRI, x=0.28, side=0), Placement(TRI, pose=(0.14, 0.07, 1.1))),
                        (Wall(0.05, mu=0.0),), friction=Friction(part_part=0.5)), ImpulseThrow(4.5)),
    "two parts, no slip": (Scene(tm.Arm(h=-0.01, mu=math.inf, length=0.4),
                                 (Placement(TRI, x=0.28, side=0), Placement(TRI, pose=(0.14, 0.07, 1.1))),
                                 friction=Friction(part_part=2.0)), ImpulseThrow(3.5)),
    # a square dropped onto another at μ_pp = 50: the part–part contact's own cap binds (both bodies' terms of K)
    "two parts stacked, sticky": (Scene(tm.Arm(h=-0.01, mu=1.5, length=0.5),
                                        (Placement(SQUARE, x=0.25, side=0), Placement(SQUARE, pose=(0.26, 0.09, 0.3))),
                                        friction=Friction(part_part=50.0)), ImpulseThrow(3.0)),
}


@pytest.mark.parametrize("name", list(CASES))
def test_runs_are_the_python_runs_bit_for_bit(name):
    scene, real = CASES[name]
    fast, slow = _both(scene, real, record=name in ("bare arm", "two parts", "tilt to a wall"))
    assert _key(fast) == _key(slow)


def test_capped_steps_and_their_mode_enumeration_are_the_python_ones(monkeypatch):
    """A μ = ∞ throw whose exact solve cycles in a few steps: those are solved by the same Python enumeration."""
    calls = []
    enumerate_modes = exact.enumerate_modes

    def spy(*args, **kw):
        calls.append(args[0])
        return enumerate_modes(*args, **kw)

    monkeypatch.setattr(exact, "enumerate_modes", spy)
    scene = Scene(tm.Arm(h=-0.01, mu=math.inf), (Placement(LEAD, x=0.356, side=1),))
    fast, slow = _both(scene, ImpulseThrow(5.444))
    assert _key(fast) == _key(slow)
    assert fast.n_capped > 1000 and len(calls) >= 2 and len(calls) % 2 == 0  # the same number in both runs


def test_pythons_hypot_and_remainder_are_reproduced():
    lib = native.load().lib
    rng = np.random.default_rng(0)
    x = rng.standard_normal(50_000) * 10.0 ** rng.uniform(-12, 6, 50_000)
    y = rng.standard_normal(50_000) * 10.0 ** rng.uniform(-12, 6, 50_000)
    x[:4], y[:4] = (0.0, 0.0, 5e-324, 1e300), (0.0, -9.81, 5e-324, 1e300)
    for a, b in zip(x.tolist(), y.tolist()):
        assert lib.tm_py_hypot(a, b) == math.hypot(a, b)
        assert lib.tm_py_mod(a, 2.0 * math.pi) == a % (2.0 * math.pi)
    assert math.isnan(lib.tm_py_hypot(math.nan, 1.0)) and lib.tm_py_hypot(math.inf, math.nan) == math.inf


@pytest.mark.slow
def test_the_helper_builds_from_its_sources(tmp_path):
    from throwmap.engine.pymunk.native import build

    target = tmp_path / ("_throwmap_engine_fresh" + ".so")
    build._compile("_throwmap_engine_fresh", str(target))
    module = build._load("_throwmap_engine_fresh", str(target))
    assert module.lib.tm_py_hypot(3.0, 4.0) == 5.0
