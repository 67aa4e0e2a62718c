"""The raw-call friction hook of several parts (``friction._MultiPartCap``) gives the same runs, bit for bit, as the
hook on pymunk's API (:class:`~throwmap.engine.pymunk.friction.FrictionCap`) — on a bare arm, with a frictionless
wall, with a rough wall whose μ equals the arm's (the arbiter's friction cannot name the pair), and at μ = ∞."""

import math

import numpy as np
import pytest

from throwmap import Arm
from throwmap.engine import Friction, ImpulseThrow, Placement, Scene, simulate
from throwmap.engine.pymunk import friction as F
from throwmap.engine.pymunk import native
from throwmap.system.catalogue import triangle_30_60_90
from throwmap.system.fixtures import Wall

TRI = triangle_30_60_90()


@pytest.fixture(autouse=True)
def _python_hooks():
    """These tests compare the engine's Python hooks with each other (its C hook: tests/engine/test_native.py)."""
    with native.disabled():
        yield


def _scene(mu_arm, wall_mu, mu_pp):
    arm = Arm(h=-0.01, mu=mu_arm, length=0.4)
    fixtures = () if wall_mu is None else (Wall(0.05, mu=wall_mu),)
    pl = (Placement(TRI, x=0.28, side=0), Placement(TRI, pose=(0.14, arm.h + 0.08, 1.1)))
    return Scene(arm, pl, fixtures, friction=Friction(part_part=mu_pp))


def _run(scene, omega, monkeypatch, api: bool):
    with monkeypatch.context() as m:
        if api:
            m.setattr(F, "_multi_part_hook", lambda *a, **k: None)
        run = simulate(scene, ImpulseThrow(omega))
    return run


@pytest.mark.parametrize("mu_arm, wall_mu, mu_pp, omega", [
    (1.0, None, 0.5, 4.0),       # bare arm, arm μ = the part–part pair's product 1.0
    (1.2, 0.0, 0.5, 4.5),        # frictionless wall (the hook leaves μ = 0 pairs alone)
    (0.9, 0.9, 0.8, 4.0),        # wall μ = arm μ: the shapes name the pair
    (math.inf, 0.0, 2.0, 3.5),   # no slip on the arm
])
def test_raw_hook_matches_api_hook(mu_arm, wall_mu, mu_pp, omega, monkeypatch):
    scene = _scene(mu_arm, wall_mu, mu_pp)
    fast, slow = _run(scene, omega, monkeypatch, api=False), _run(scene, omega, monkeypatch, api=True)
    assert fast.status == slow.status
    assert np.array_equal(np.asarray(fast.poses), np.asarray(slow.poses))
    assert fast.n_capped == slow.n_capped > 0  # the cap was exercised, and counted alike
    assert fast.n_steps == slow.n_steps


def test_raw_hook_is_used_for_two_parts():
    calls = []
    orig = F._multi_part_hook

    def spy(*a, **k):
        h = orig(*a, **k)
        calls.append(h)
        return h

    F._multi_part_hook = spy
    try:
        simulate(_scene(1.0, None, 0.5), ImpulseThrow(3.0))
    finally:
        F._multi_part_hook = orig
    assert calls and all(isinstance(h, F._MultiPartCap) for h in calls)
