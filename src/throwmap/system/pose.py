"""Poses of a part on the arm and the resting configurations they are nearest to.

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

import numpy as np

from .part import Part

__all__ = ["pose_at_rest", "pose_against_wall", "state_from_pose", "to_arm_frame", "world_vertices"]


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


def pose_against_wall(part: Part, h: float, wall_x: float, side: int) -> tuple[float, float, float]:
    """World pose ``(x, y, φ)`` of ``part`` resting flat on ``side`` (arm surface at ``h``, m) pushed outward until
    its outermost point touches a vertical wall at ``wall_x`` (m): the side's own end where its neighbour leans back,
    the neighbour's far vertex where it overhangs the side."""
    pose = pose_at_rest(part, h, 0.0, side)
    reach = float(np.max(world_vertices(part, pose)[:, 0]))
    return pose_at_rest(part, h, float(wall_x) - reach, side)


def world_vertices(part: Part, pose) -> np.ndarray:
    """World coordinates (n, 2) of the part's clockwise vertices ``w`` at ``pose``."""
    x, y, phi = pose
    c, s = math.cos(phi), math.sin(phi)
    w = part.w
    return np.column_stack((x + c * w[:, 0] - s * w[:, 1], y + s * w[:, 0] + c * w[:, 1]))
