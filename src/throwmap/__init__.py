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

from .version import __version__

__all__ = [
    "Arm", "BatchOutcome", "Cavity", "DEFAULT_MODEL", "System", "Wall", "get_model", "model_names", "models", "register", "ConfigError", "ConfigSet", "FunctionMap", "ThrowMap", "basins", "critical_points",
    "funnels", "limit_set", "push", "G", "InvalidArmError", "InvalidPartError", "InvalidStateError",
    "MODELS", "Orbit", "Part", "RegimeWarning", "Side", "Status", "ThrowOutcome", "ThrowmapError",
    "ThrowmapWarning", "cm", "iterate", "plot_throw_map", "rectangle", "regime_problems", "regular_polygon",
    "throw", "throw_batch", "triangle_30_60_90", "__version__",
]


def plot_throw_map(part, arm, omega, *, model: str = DEFAULT_MODEL, sides=None, x_max=None, n: int = 1500, axes=None,
                   unit: str = "cm", **throw_options):
    """T(x) against x, one panel per starting side, with the diagonal (paper Fig. 2); returns the Figure.

    Samples the throw map at ``n`` x per side over ``(x_min(side), x_max]`` (m;
    ``x_max`` defaults to the arm length, or 0.5 m for an unbounded arm) with
    :func:`throwmap.throws.samples.throw_map_samples` (with ``fixtures`` and every side: over each
    side's starts up to the wall, x + u_R ≤ length, by :func:`~throwmap.throws.samples.sample_map`
    of a :class:`~throwmap.analysis.ThrowMap`) and draws it with
    :func:`throwmap.viz.throw_map.plot_map` (``compact`` look): points coloured
    by the side the part lands on, escapes marked ``x`` on the axis. ``omega`` in
    rad/s; ``unit`` ``"cm"`` or ``"m"``; ``throw_options`` go to :func:`throw_batch`.
    """
    from .throws.samples import sample_map, throw_map_samples
    from .viz.throw_map import plot_map

    if throw_options.get("fixtures") and sides is None:  # sampled up to the wall: x + u_R ≤ length per side
        from .analysis.maps import ThrowMap

        samples = sample_map(ThrowMap(part, arm, omega, model, x_max, dict(throw_options)), n)
    else:
        samples = throw_map_samples(part, arm, omega, model=model, sides=sides, x_max=x_max, n=n, **throw_options)
    return plot_map(samples, axes=axes, unit=unit, compact=True)
