"""throwmap — throw maps, limit sets and design for parts handling by repeated throwing.

Implements the method of Murphey & Lynch, "Parts handling and self-assembly using
stable limit sets" (an unpublished draft, restated in docs/paper-notes.md), corrected where the draft is wrong
(docs/explanation/errata.md).
SI units throughout; see :mod:`throwmap.conventions`.

``import throwmap`` loads neither matplotlib nor mujoco.
"""

from .system.arm import Arm, regime_problems
from .conventions import G, cm
from .errors import (
    ConfigError,
    InvalidArmError,
    InvalidPartError,
    InvalidStateError,
    RegimeWarning,
    ThrowmapError,
    ThrowmapWarning,
)
from .analysis import ConfigSet, FunctionMap, ThrowMap, basins, critical_points, funnels, limit_set, push
from .records.orbit import Orbit
from .throws.orbit import iterate
from .records.outcome import BatchOutcome, Status, ThrowOutcome
from .system.part import Part, Side
from .system.catalogue import rectangle, regular_polygon, triangle_30_60_90
from . import models
from .models import DEFAULT_MODEL, get_model, model_names, register
from .system.fixtures import Cavity, Wall
from .system.system import System
from .throws.throw import MODELS, throw, throw_batch
from .analysis.maps import plot_throw_map

from .version import __version__

__all__ = [
    "Arm", "BatchOutcome", "Cavity", "DEFAULT_MODEL", "System", "Wall", "get_model", "model_names", "models", "register", "ConfigError", "ConfigSet", "FunctionMap", "ThrowMap", "basins", "critical_points",
    "funnels", "limit_set", "push", "G", "InvalidArmError", "InvalidPartError", "InvalidStateError",
    "MODELS", "Orbit", "Part", "RegimeWarning", "Side", "Status", "ThrowOutcome", "ThrowmapError",
    "ThrowmapWarning", "cm", "iterate", "plot_throw_map", "rectangle", "regime_problems", "regular_polygon",
    "throw", "throw_batch", "triangle_30_60_90", "__version__",
]
