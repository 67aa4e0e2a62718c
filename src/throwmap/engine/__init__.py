"""Full rigid-body physics backends: pymunk (the "engine" model) and an optional MuJoCo cross-check.

Shared by both: :mod:`.scene` (what is simulated), :mod:`.settings`,
:mod:`.realisation` (how the arm throws) and :mod:`.api` (the engine as a throw
map). :mod:`throwmap.engine.pymunk` is the reference engine; pymunk is imported
only when a simulation runs. :mod:`throwmap.engine.mujoco` (not imported here)
is the MuJoCo cross-check; the ``mujoco`` package is imported only when it runs.
"""

from .api import engine_batch, engine_run, engine_throw, engine_trajectory
from .pymunk import EngineRun, simulate
from ..system.motion import FiniteThrow, ImpulseThrow, RecoilThrow, TiltTo
from .scene import Placement, Scene
from .settings import EngineSettings, Friction

__all__ = [
    "EngineRun", "EngineSettings", "FiniteThrow", "Friction", "ImpulseThrow", "Placement", "RecoilThrow",
    "Scene", "TiltTo", "engine_batch", "engine_run", "engine_throw", "engine_trajectory", "simulate",
]
