"""Settings and constants of the MuJoCo cross-check (see :mod:`throwmap.engine.mujoco`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from ...errors import InvalidStateError, shown

__all__ = ["MujocoSettings", "MODEL_NAME", "NO_SLIP_MU", "UNBOUNDED_EXTRA", "ARM_DEPTH", "POST_SPEED_FRACTION",
           "POST_WINDOW", "TOUCH_HYSTERESIS", "finite"]

MODEL_NAME = "engine:mujoco"
NO_SLIP_MU = 10.0
"""Friction coefficient given to MuJoCo for μ = ∞ (MuJoCo needs a finite number)."""
UNBOUNDED_EXTRA = 2.0
"""Arm length simulated beyond the bound on the flight when ``Arm.length`` is None, m (× 4 per rerun,
:mod:`throwmap.engine.reach`)."""
ARM_DEPTH = 0.05
"""Depth of the arm box below its top face, m."""
POST_SPEED_FRACTION = 0.05
"""The impact has settled into pivoting when the contact vertex is slower than this fraction of its pre-impact speed."""
POST_WINDOW = 0.01
"""Longest wait after the first contact for the post-impact state, s."""
TOUCH_HYSTERESIS = 1e-4
"""A vertex counts as having left the arm once its gap exceeds this, m (impact counting)."""


def finite(value, key: str) -> float:
    """``value`` as a finite float, or a :class:`~throwmap.errors.InvalidStateError` naming ``key``."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise InvalidStateError(key, f"must be a number, got {shown(value)}")
    v = float(value)
    if not math.isfinite(v):
        raise InvalidStateError(key, f"must be finite, got {shown(value)}")
    return v


@dataclass(frozen=True, slots=True)
class MujocoSettings:
    """Numerical settings of :func:`mujoco_throw` (SI units).

    timestep : MuJoCo's fixed step, s (> 0, ≤ 2 ms).
    solref : contact ``(timeconst s, dampratio)``; ``None``: ``(2·timestep, 10)``,
        a stiff over-damped contact (plastic impact, no rebound). MuJoCo's direct
        form ``(−stiffness, −damping)`` (both < 0) is accepted too.
    solimp : contact impedance ``(dmin, dmax, width m[, midpoint, power])``.
    multiccd : multi-point convex collision (a side rests on two contacts).
    cone : MuJoCo's friction cone, ``"elliptic"`` or ``"pyramidal"``.
    contact_priority : the arm geom has priority, so exactly ``arm.mu`` is used
        (otherwise MuJoCo takes the larger of the arm's and the part's μ, the part
        geom keeping MuJoCo's default 1).
    defaults : write none of solref/solimp/multiccd/cone/priority: MuJoCo's own
        defaults, kept to show how wrong they are for plastic impacts (``timestep``
        is still used).
    settle_speed, settle_spin, settle_hold : settled when the CM is slower than
        ``settle_speed`` (m/s) and the spin below ``settle_spin`` (rad/s) for
        ``settle_hold`` (s).
    t_max : give up after this much simulated time (status ``timeout``), s.
    penetration_tol : a vertex deeper than this in the arm (m) means MuJoCo lost
        the contact: status ``penetration``, result refused.
    thickness : depth of the prism along the out-of-plane axis, m.
    """

    timestep: float = 5e-4
    solref: tuple | None = None
    solimp: tuple = (0.99, 0.999, 1e-4, 0.5, 2)
    multiccd: bool = True
    contact_priority: bool = True
    cone: str = "elliptic"
    defaults: bool = False
    settle_speed: float = 1e-3
    settle_spin: float = 1e-2
    settle_hold: float = 0.05
    t_max: float = 5.0
    penetration_tol: float = 1e-3
    thickness: float = 0.02

    def __post_init__(self):
        for f in fields(self):
            key = f"mujoco.{f.name}"
            v = getattr(self, f.name)
            if f.name in ("multiccd", "contact_priority", "defaults"):
                if not isinstance(v, (bool, np.bool_)):
                    raise InvalidStateError(key, f"must be true or false, got {shown(v)}")
                object.__setattr__(self, f.name, bool(v))
            elif f.name == "cone":
                if v not in ("elliptic", "pyramidal"):
                    raise InvalidStateError(key, f"must be 'elliptic' or 'pyramidal', got {shown(v)}")
            elif f.name == "solref":
                if v is None:
                    continue
                vals = self._tuple(v, key, (2,))
                if not ((vals[0] > 0 and vals[1] > 0) or (vals[0] < 0 and vals[1] <= 0)):
                    raise InvalidStateError(
                        key, f"must be (timeconst > 0, dampratio > 0) or (-stiffness < 0, -damping ≤ 0), got {shown(v)}"
                    )
                object.__setattr__(self, f.name, vals)
            elif f.name == "solimp":
                vals = self._tuple(v, key, (3, 5))
                dmin, dmax, width = vals[:3]
                if not (0 < dmin < 1 and 0 < dmax < 1):
                    raise InvalidStateError(key, f"dmin and dmax must lie in (0, 1), got {shown(v)}")
                if width <= 0:
                    raise InvalidStateError(key, f"width must be > 0 m, got {shown(v)}")
                if len(vals) == 5 and not (0 < vals[3] < 1 and vals[4] >= 1):
                    raise InvalidStateError(key, f"midpoint must lie in (0, 1) and power be ≥ 1, got {shown(v)}")
                object.__setattr__(self, f.name, vals)
            else:
                x = finite(v, key)
                if x <= 0:
                    raise InvalidStateError(key, f"must be > 0, got {shown(v)}")
                object.__setattr__(self, f.name, x)
        if self.timestep > 2e-3:
            raise InvalidStateError("mujoco.timestep", f"must be ≤ 2e-3 s to resolve impacts, got {shown(self.timestep)}")
        if self.settle_hold < 4 * self.timestep:
            raise InvalidStateError(
                "mujoco.settle_hold", f"must cover at least 4 steps ({4 * self.timestep:g} s), got {shown(self.settle_hold)}"
            )
        if self.t_max < self.settle_hold:
            raise InvalidStateError("mujoco.t_max", f"must be ≥ settle_hold ({self.settle_hold:g} s), got {shown(self.t_max)}")

    @staticmethod
    def _tuple(v, key, lengths) -> tuple:
        counts = " or ".join(map(str, lengths))
        try:
            vals = tuple(v)
        except TypeError:
            raise InvalidStateError(key, f"must be a sequence of {counts} numbers, got {shown(v)}") from None
        if len(vals) not in lengths:
            raise InvalidStateError(key, f"must have {counts} numbers, got {shown(v)}")
        return tuple(finite(c, key) for c in vals)

    @property
    def contact_solref(self) -> tuple:
        """The solref written to the model: ``solref`` or ``(2·timestep, 10)``."""
        return self.solref if self.solref is not None else (2.0 * self.timestep, 10.0)
