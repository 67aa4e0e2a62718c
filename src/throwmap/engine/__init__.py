"""Full rigid-body physics backends: pymunk (the "engine" model) and an optional MuJoCo cross-check.

``throwmap.engine`` imports pymunk only when a simulation runs and MuJoCo only in
:mod:`throwmap.engine.mujoco_backend`.
"""

from .api import engine_batch, engine_run, engine_throw, engine_trajectory
from .pymunk_backend import EngineRun, simulate
from .realisation import FiniteThrow, ImpulseThrow, RecoilThrow, TiltTo
from .scene import Placement, Scene
from .settings import EngineSettings, Friction

__all__ = [
    "EngineRun", "EngineSettings", "FiniteThrow", "Friction", "ImpulseThrow", "Placement", "RecoilThrow",
    "Scene", "TiltTo", "engine_batch", "engine_run", "engine_throw", "engine_trajectory", "simulate",
]
