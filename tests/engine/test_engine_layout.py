"""The engine package's shape: public names, lazy imports, and the fast Chipmunk calls agreeing with pymunk's API."""

import subprocess
import sys

import numpy as np
import pytest

import throwmap.engine as engine
from throwmap import Arm
from throwmap.engine import FiniteThrow, Friction, ImpulseThrow, Placement, Scene
from throwmap.engine.pymunk.run import _simulate_once
from throwmap.engine.settings import EngineSettings
from throwmap.system.catalogue import rectangle, triangle_30_60_90
from throwmap.system.fixtures import Wall

TRI = triangle_30_60_90()
ARM = Arm(h=-0.01, mu=1.5)
SHORT = Arm(h=-0.01, mu=1.5, length=0.4)
SQ = rectangle(0.06, 0.06)


def test_public_names():
    for name in ("engine_batch", "engine_run", "engine_throw", "engine_trajectory", "EngineRun", "simulate",
                 "FiniteThrow", "ImpulseThrow", "RecoilThrow", "TiltTo", "Placement", "Scene", "EngineSettings",
                 "Friction"):
        assert name in engine.__all__ and hasattr(engine, name)


def test_importing_the_engine_loads_neither_pymunk_nor_mujoco():
    code = ("import sys, throwmap, throwmap.engine, throwmap.engine.mujoco; "
            "from throwmap.engine.mujoco import MujocoSettings, mujoco_model_xml, mujoco_throw, MODEL_NAME; "
            "print(' '.join(m for m in ('pymunk', 'mujoco') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == []


def _key(run):
    return (run.status, run.statuses, run.states, run.poses, run.records.tobytes(), run.t_end, run.n_steps,
            run.n_leaps, run.n_coarse, run.n_checks, run.n_clearance, run.penetration_max, run.alpha)


@pytest.mark.parametrize("scene, real", [
    (Scene(ARM, (Placement(TRI, x=0.3, side=1),)), ImpulseThrow(5.0)),
    (Scene(SHORT, (Placement(TRI, x=0.3, side=0),), fixtures=(Wall(0.05),), alpha=-0.1), ImpulseThrow(6.0)),
    (Scene(ARM, (Placement(TRI, x=0.25, side=1),)), FiniteThrow(5.0, 0.005)),
    (Scene(SHORT, (Placement(SQ, x=0.1, side=0), Placement(SQ, x=0.25, side=0)), friction=Friction(part_part=0.8)),
     ImpulseThrow(4.0)),
])
def test_fast_chipmunk_calls_match_pymunks_api_bit_for_bit(scene, real):
    s = EngineSettings()
    fast = _simulate_once(scene, real, s, True, None, None, raw=True)
    api = _simulate_once(scene, real, s, True, None, None, raw=False)
    assert _key(fast) == _key(api)
    assert np.array_equal(fast.trajectory.poses, api.trajectory.poses)


def test_run_cost_counts_are_consistent():
    run = engine.engine_run(TRI, ARM, 0.3, 1, 5.0)
    assert 0 < run.n_coarse < run.n_steps
    assert run.n_leaps > 0 and run.n_clearance >= run.n_leaps
    assert run.n_checks > 0
    # the steps, coarse steps and leaps cover the simulated time (leaps are at most 50 ms)
    s = EngineSettings()
    stepped = (run.n_steps - run.n_coarse) * s.dt + run.n_coarse * s.coarse_dt
    assert stepped < run.t_end <= stepped + 0.05 * run.n_leaps + 1e-9
