"""Sampled motion of parts on the arm: the :class:`Trajectory` type and pose ↔ state helpers.

A pose is ``(x, y, φ)``: the world position of the part's CM (m) and the body
rotation φ (rad, CCW +) that maps the part's internal clockwise, CM-centred
vertices ``part.w`` to the world: ``vertex_j = (x, y) + R(φ) w_j``. Resting flat on
side k of a horizontal arm, φ = ``part.beta[k]`` and y = h + d_k.

The arm turns about the joint (the origin) by ``arm_angle`` (rad, CCW +); its
surface is the line through R(angle)·(0, h) along R(angle)·(1, 0). The *arm
frame* is the world frame turned back by the arm angle; resting configurations
``(x, side)`` are always read in the arm frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown
from ..system.part import Part

__all__ = ["Trajectory", "pose_at_rest", "state_from_pose", "to_arm_frame", "world_vertices"]


def _wrap(a):
    return (np.asarray(a) + math.pi) % (2.0 * math.pi) - math.pi


def pose_at_rest(part: Part, h: float, x: float, side: int, arm_angle: float = 0.0) -> tuple[float, float, float]:
    """World pose ``(x, y, φ)`` of ``part`` resting flat on ``side`` at CM abscissa ``x`` (arm frame, m)."""
    k = part.check_side(side)
    xa, ya = float(x), float(h + part.d[k])
    c, s = math.cos(arm_angle), math.sin(arm_angle)
    return c * xa - s * ya, s * xa + c * ya, float(part.beta[k]) + arm_angle


def to_arm_frame(pose, arm_angle: float) -> tuple[float, float, float]:
    """A world pose expressed in the arm frame (the world turned back by ``arm_angle``)."""
    x, y, phi = pose
    c, s = math.cos(arm_angle), math.sin(arm_angle)
    return c * x + s * y, -s * x + c * y, phi - arm_angle


def state_from_pose(part: Part, pose, arm_angle: float = 0.0) -> tuple[float, int, float]:
    """The resting configuration nearest to a pose: ``(x, side, tilt)``.

    ``x`` is the CM abscissa in the arm frame (m), ``side`` the side whose resting
    orientation ``beta[side]`` is nearest to the pose's orientation relative to the
    arm, and ``tilt`` the remaining angle (rad; 0 when flat on that side).
    """
    xa, _, phi = to_arm_frame(pose, arm_angle)
    diff = _wrap(phi - part.beta)
    k = int(np.argmin(np.abs(diff)))
    return float(xa), k, float(diff[k])


def world_vertices(part: Part, pose) -> np.ndarray:
    """World coordinates (n, 2) of the part's clockwise vertices ``w`` at ``pose``."""
    x, y, phi = pose
    c, s = math.cos(phi), math.sin(phi)
    w = part.w
    return np.column_stack((x + c * w[:, 0] - s * w[:, 1], y + s * w[:, 0] + c * w[:, 1]))


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
