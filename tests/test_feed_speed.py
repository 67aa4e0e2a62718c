"""The feed experiment's speedups change no result: the fast paths equal the plain ones bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from throwmap.system.motion import FiniteThrow, ImpulseThrow, RecoilThrow, TiltTo, angle_function


@pytest.mark.parametrize("omega", [2.0, 4.559824565181344, 7.3])
@pytest.mark.parametrize("zeta", [0.2, 0.5, 0.9])
def test_recoil_angle_function_is_bit_identical(omega, zeta):
    r = RecoilThrow.for_release_rate(omega, zeta=zeta)
    f = angle_function(r)
    ts = list(np.linspace(-1e-3, r.duration + 0.01, 4001))
    ts += [0.0, r.t_recoil, r.t_peak, r.t_peak + r.hold, r.duration]
    t = 0.0
    while t < r.duration + 1e-3:  # the run loop's own times: t += dt
        ts.append(t)
        t += 1.25e-4
    for t in ts:
        assert f(float(t)) == r.angle(float(t)), t


@pytest.mark.parametrize("r", [ImpulseThrow(3.0), FiniteThrow(4.0, 0.01), TiltTo(-0.1, 0.5)])
def test_other_realisations_keep_their_angle(r):
    f = angle_function(r)
    for t in np.linspace(-0.01, 0.5, 101):
        assert f(float(t)) == r.angle(float(t))
    assert math.isfinite(f(0.0))


def _cavity_world(x=0.3, side=0):
    import throwmap as tm
    from throwmap.engine import EngineSettings, ImpulseThrow
    from throwmap.engine.pymunk.world import build_world
    from throwmap.engine.scene import Placement, Scene
    from throwmap.system.fixtures import Cavity

    part = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=-0.02, mu=1.0, length=0.38)
    fixtures = (Cavity(profile=((0.18, 0.0), (0.175, -0.01), (0.0, -0.01))), tm.Wall(0.15, mu=0.0))
    scene = Scene(arm, (Placement(part, x=x, side=side),), fixtures)
    return build_world(scene, ImpulseThrow(0.0), EngineSettings(), length=0.38)


def _poses(w, n, seed=0):
    """Random poses and velocities of part 0 near the arm's end (in, on, beside and above the cavity)."""
    rng = np.random.default_rng(seed)
    b = w.bodies[0]
    for _ in range(n):
        b.position = (float(rng.uniform(0.0, 0.45)), float(rng.uniform(-0.06, 0.2)))
        b.angle = float(rng.uniform(0.0, 2.0 * math.pi))
        b.velocity = (float(rng.normal(0, 1.0)), float(rng.normal(0, 1.0)))
        b.angular_velocity = float(rng.normal(0, 5.0))
        w.arm.angle = float(rng.uniform(-0.1, 0.1))
        w.space.reindex_shapes_for_body(w.arm)
        w.space.reindex_shapes_for_body(b)
        yield


def test_inspect_box_skips_change_nothing():
    from throwmap.engine.pymunk.checks import inspect

    w = _cavity_world()
    full = [None] * len(w.boxes[0])
    for _ in _poses(w, 3000):
        aa = w.arm.angle
        args = (w, 0, aa, math.cos(aa), math.sin(aa))
        for horizon in (0.0, 4e-3):
            fast = inspect(*args, horizon)
            boxes, w.boxes[0] = w.boxes[0], full
            slow = inspect(*args, horizon)
            w.boxes[0] = boxes
            assert fast == slow


def test_clearance_with_enough_decides_as_the_full_search():
    from throwmap.engine.pymunk.checks import clearance

    w = _cavity_world()
    margin = w.margin
    for _ in _poses(w, 3000, seed=1):
        exact = clearance(w, 0)  # also leaves the hint
        w.space.reindex_shapes_for_body(w.bodies[0])
        quick = clearance(w, 0, margin)
        assert (quick > margin) == (exact > margin)
        assert quick >= exact
        if exact > margin:
            assert quick == exact


@pytest.mark.slow
def test_fixture_hook_fast_path_is_bit_identical(monkeypatch):
    import throwmap as tm
    from throwmap.engine import RecoilThrow, simulate
    from throwmap.engine.pymunk import friction as F
    from throwmap.engine.scene import Placement, Scene

    part = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=-0.01, mu=1.5, length=0.3)
    runs = {}
    calls = {"slow": 0}
    slow = F._SinglePartFixtureCap._slow

    def counted(self, *a):
        calls["slow"] += 1
        return slow(self, *a)

    monkeypatch.setattr(F._SinglePartFixtureCap, "_slow", counted)
    monkeypatch.setenv("THROWMAP_NATIVE", "0")  # the Python hooks (the C one: tests/engine/test_native.py)
    for fast in (True, False):
        if not fast:
            init = F._SinglePartFixtureCap.__init__

            def no_fast(self, *a, **kw):
                init(self, *a, **kw)
                self.by_u, self.raw = None, self._slow

            monkeypatch.setattr(F._SinglePartFixtureCap, "__init__", no_fast)
        out = []
        for x, k, omega in ((0.2, 0, 4.0), (0.19, 1, 5.0), (0.18, 2, 4.5)):
            scene = Scene(arm, (Placement(part, x=x, side=k),), (tm.Wall(0.08, mu=0.0),))
            r = simulate(scene, RecoilThrow.for_release_rate(omega, zeta=0.3))
            out.append((r.statuses, r.poses, r.t_end, r.n_steps, r.n_capped, r.records.tobytes()))
        runs[fast] = out
    assert runs[True] == runs[False]
    assert any(o[4] > 0 for o in runs[True])  # the cap was needed
    assert calls["slow"] > 0
