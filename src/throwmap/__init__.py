"""throwmap — throw maps, limit sets and design for parts handling by repeated throwing.

Implements the method of Murphey & Lynch, "Parts handling and self-assembly using
stable limit sets" (draft in ``shared/paper``), corrected where the draft is wrong.
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
from .throws.orbit import Orbit, iterate
from .throws.outcome import BatchOutcome, Status, ThrowOutcome
from .system.part import Part, Side
from .system.catalogue import rectangle, regular_polygon, triangle_30_60_90
from .throws.throw import MODELS, throw, throw_batch

__version__ = "0.1.0"

__all__ = [
    "Arm", "BatchOutcome", "ConfigError", "ConfigSet", "FunctionMap", "ThrowMap", "basins", "critical_points",
    "funnels", "limit_set", "push", "G", "InvalidArmError", "InvalidPartError", "InvalidStateError",
    "MODELS", "Orbit", "Part", "RegimeWarning", "Side", "Status", "ThrowOutcome", "ThrowmapError",
    "ThrowmapWarning", "cm", "iterate", "plot_throw_map", "rectangle", "regime_problems", "regular_polygon",
    "throw", "throw_batch", "triangle_30_60_90", "__version__",
]


def plot_throw_map(*args, **kwargs):
    """T(x) against x per side (paper Fig. 2); see :func:`throwmap.viz.plotting.plot_throw_map`."""
    from .viz.plotting import plot_throw_map as _plot

    return _plot(*args, **kwargs)
