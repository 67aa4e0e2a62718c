"""The raw-call friction cap for one part with fixtures gives the general hook's results (to rounding) and
picks the wall's μ for wall contacts."""

import math
import warnings

import pytest

import throwmap as tm
from throwmap.engine.pymunk import friction as F
from throwmap.engine.pymunk import native

PART = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01, mu=1.5, length=0.3)
CASES = ((0.2, 0, 4.0), (0.19, 1, 5.0), (0.18, 2, 4.5))


@pytest.fixture(autouse=True)
def _python_hooks():
    """These tests compare the engine's Python hooks with each other (its C hook: tests/engine/test_native.py)."""
    with native.disabled():
        yield


def _throw(x, k, w, mu_w, fast: bool, monkeypatch):
    if not fast:
        monkeypatch.setattr(F, "_single_part_fixture_hook", lambda *a, **kw: None)
    else:
        monkeypatch.undo()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return tm.throw(PART, ARM, x, k, w, "engine", fixtures=(tm.Wall(0.08, mu=mu_w),))


@pytest.mark.slow
@pytest.mark.parametrize("mu_w", [0.0, 1.0, math.inf])
def test_fast_hook_matches_the_general_one(mu_w, monkeypatch):
    for x, k, w in CASES:
        general = _throw(x, k, w, mu_w, False, monkeypatch)
        fast = _throw(x, k, w, mu_w, True, monkeypatch)
        assert (fast.status, fast.side) == (general.status, general.side)
        assert fast.x == pytest.approx(general.x, abs=1e-9)


def test_fast_hook_is_installed_for_one_part_with_a_wall():
    from throwmap.engine import EngineSettings, ImpulseThrow
    from throwmap.engine.pymunk.world import build_world
    from throwmap.engine.scene import Placement, Scene

    scene = Scene(ARM, (Placement(PART, x=0.2, side=0),), (tm.Wall(0.08, mu=0.0),))
    world = build_world(scene, ImpulseThrow(4.0), EngineSettings(), length=0.3)
    hook = F.install_friction_cap(world)
    assert isinstance(hook, F._SinglePartFixtureCap)  # μ = 1.5 exceeds what this part meets uncapped
