"""Sampled motion of parts on the arm: the :class:`Trajectory` record and helpers for models' trajectories.

Poses ``(x, y, φ)`` and the arm frame are as :mod:`throwmap.system.pose` states them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown
from ..system.pose import world_vertices

__all__ = ["Trajectory", "DEFAULT_DT", "NO_CONTACT", "contact_points", "check_dt", "drawn_length"]


@dataclass(frozen=True, slots=True)
class Trajectory:
    """Sampled motion of one or more parts on the arm (for animation and inspection).

    Attributes
    ----------
    t : (T,) array, s
        Sample times from the start of the run.
    arm_angle : (T,) array, rad
        Arm rotation about the joint (CCW +; 0 is horizontal).
    poses : (T, P, 3) array
        Pose ``(x, y, φ)`` of each of the P parts (see the module docstring).
    parts : tuple of Part
        The parts, in the order of ``poses``' second axis.
    h : float
        Arm surface height at rest (m) in the arm frame.
    length : float
        Arm length (m) drawn.
    fixtures : tuple
        Fixture objects drawn with the arm (see :mod:`throwmap.system.fixtures`).
    contacts : tuple of (K, 2) arrays, m
        World contact points at each sample (K may be 0).
    events : tuple of (t, label)
        Named events (``"impact"``, ``"lift-off"``, ``"flip 0→1"``, ``"rest"`` …).
    source : str
        What produced it (``"engine:pymunk"``, ``"rigid_body"``, ``"paper"`` …).
    """

    t: np.ndarray
    arm_angle: np.ndarray
    poses: np.ndarray
    parts: tuple
    h: float
    length: float
    fixtures: tuple = ()
    contacts: tuple = ()
    events: tuple = ()
    source: str = ""
    meta: dict = field(default_factory=dict)

    def __post_init__(self):
        t = np.asarray(self.t, dtype=float)
        a = np.asarray(self.arm_angle, dtype=float)
        p = np.asarray(self.poses, dtype=float)
        if p.ndim != 3 or p.shape[2] != 3 or p.shape[0] != t.shape[0] or a.shape != t.shape:
            raise ValueError(f"poses: expected shape (T, P, 3) with T = {t.shape[0]}, got {p.shape}")
        if p.shape[1] != len(self.parts):
            raise ValueError(f"parts: {len(self.parts)} parts for {p.shape[1]} pose columns")
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "arm_angle", a)
        object.__setattr__(self, "poses", p)

    def __repr__(self) -> str:
        span = f"t∈[{self.t[0]:.4g}, {self.t[-1]:.4g}] s" if self.n_samples else "no samples"
        names = ", ".join(dict.fromkeys(p.name or "part" for p in self.parts))
        if len(names) > 40:
            names = names[:39] + "…"
        return (f"Trajectory(source={self.source!r}, {len(self.parts)} part{'s' if len(self.parts) != 1 else ''} "
                f"({names}), {self.n_samples} samples, {span}, {len(self.events)} events, h={self.h:g} m)")

    @property
    def n_samples(self) -> int:
        return int(self.t.shape[0])

    def vertices(self, i: int, p: int = 0) -> np.ndarray:
        """World vertices of part ``p`` at sample ``i``."""
        return world_vertices(self.parts[p], self.poses[i, p])

    def concat(self, other: "Trajectory") -> "Trajectory":
        """This trajectory followed by ``other`` (times shifted to continue)."""
        t0 = self.t[-1] if self.n_samples else 0.0
        shift = t0 - (other.t[0] if other.n_samples else 0.0)
        return Trajectory(
            np.concatenate((self.t, other.t + shift)),
            np.concatenate((self.arm_angle, other.arm_angle)),
            np.concatenate((self.poses, other.poses)),
            self.parts, self.h, self.length, self.fixtures,
            tuple(self.contacts) + tuple(other.contacts),
            tuple(self.events) + tuple((te + shift, lab) for te, lab in other.events),
            self.source, dict(self.meta),
        )


# ------------------------------------------------------------------ helpers for models' trajectories
DEFAULT_DT = 1.0 / 240.0
"""Default sample interval of recorded trajectories, s."""
NO_CONTACT = np.zeros((0, 2))
NO_CONTACT.setflags(write=False)


def contact_points(*points) -> np.ndarray:
    """Read-only (n, 2) array of contact points (m)."""
    a = np.array(points, dtype=float).reshape(-1, 2)
    a.setflags(write=False)
    return a


def check_dt(dt) -> float:
    """A positive finite sample interval (s), or :class:`InvalidStateError` naming ``dt``."""
    if isinstance(dt, bool):
        raise InvalidStateError("dt", f"must be a number, got {shown(dt)}")
    try:
        v = float(dt)
    except (TypeError, ValueError):
        raise InvalidStateError("dt", f"must be a number, got {shown(dt)}") from None
    if not (math.isfinite(v) and v > 0):
        raise InvalidStateError("dt", f"must be a positive finite time step (s), got {shown(dt)}")
    return v


def drawn_length(arm, poses: np.ndarray, parts) -> float:
    """The arm's length (m), or for an unbounded arm one reaching a little past every vertex."""
    if arm.length is not None:
        return float(arm.length)
    reach = 0.0
    for p, part in enumerate(parts):
        r = float(np.max(part.ell))
        reach = max(reach, float(np.max(poses[:, p, 0])) + r)
    return max(1.15 * reach, reach + 0.03)
