"""The MJCF model of a part on the arm (see :mod:`throwmap.engine.mujoco`, "Model"); needs no MuJoCo installed."""

from __future__ import annotations

import math

from ...errors import InvalidStateError
from ...system.arm import Arm
from ...system.part import Part
from ...system.pose import pose_at_rest
from .settings import ARM_DEPTH, NO_SLIP_MU, UNBOUNDED_EXTRA, MujocoSettings, finite

__all__ = ["mujoco_model_xml", "arm_length"]


def _f(v: float) -> str:
    return repr(float(v))


def arm_length(arm: Arm, x: float | None) -> float:
    """Simulated arm length, m: ``arm.length``, or ``x`` + :data:`UNBOUNDED_EXTRA` for an unbounded arm."""
    if arm.length is not None:
        return arm.length
    return max(0.0 if x is None else float(x), 0.0) + UNBOUNDED_EXTRA


def mujoco_model_xml(part: Part, arm: Arm, settings: MujocoSettings = MujocoSettings(), x: float | None = None,
                     side: int | None = None, length: float | None = None) -> str:
    """MJCF text of the part on the arm (see the module docstring).

    ``length`` (m) is the simulated length of an unbounded arm (None: ``x + 2 m``,
    :func:`arm_length`; :func:`throwmap.engine.mujoco.mujoco_throw` sizes it for the
    throw); with ``x`` and ``side`` the model also has a keyframe ``"rest"``: the
    part at rest on ``side`` with its CM at ``x``. Needs no MuJoCo installed.
    """
    if not isinstance(part, Part):
        raise InvalidStateError("part", f"must be a Part, got {type(part).__name__}")
    if not isinstance(arm, Arm):
        raise InvalidStateError("arm", f"must be an Arm, got {type(arm).__name__}")
    if not isinstance(settings, MujocoSettings):
        raise InvalidStateError("settings", f"must be MujocoSettings, got {type(settings).__name__}")
    if x is not None:
        x = finite(x, "x")
    s = settings
    L = arm_length(arm, x) if length is None or arm.length is not None else finite(length, "length")
    t2 = 0.5 * s.thickness
    verts = " ".join(f"{_f(wx)} {_f(sy)} {_f(wy)}" for wx, wy in part.w for sy in (-t2, t2))
    inertia = part.moment_of_inertia
    mu = NO_SLIP_MU if math.isinf(arm.mu) else arm.mu
    condim = 1 if mu == 0.0 else 3
    friction = f'friction="{_f(max(mu, 1e-5))} 0 0"'
    if s.defaults:
        option_extra, flags = "", ""
        arm_contact = f'{friction} condim="{condim}"'
        part_contact = f'condim="{condim}"'
    else:
        ref, imp = s.contact_solref, s.solimp
        sol = f'solref="{" ".join(map(_f, ref))}" solimp="{" ".join(map(_f, imp))}"'
        flags = f'\n    <flag multiccd="{"enable" if s.multiccd else "disable"}"/>'
        option_extra = f' cone="{s.cone}"'
        arm_contact = f'{friction} condim="{condim}" {sol}'
        part_contact = f'condim="{condim}" {sol}'
        if s.contact_priority:
            arm_contact += ' priority="1"'
    key = ""
    if x is not None and side is not None:
        px, py, phi = pose_at_rest(part, arm.h, x, side)
        key = f'\n  <keyframe>\n    <key name="rest" qpos="{_f(px)} {_f(py)} {_f(phi)}"/>\n  </keyframe>'
    back = arm.back  # the surface spans -back <= x <= L (Arm.back)
    box = f'size="{_f(0.5 * (L + back))} {_f(s.thickness)} {_f(0.5 * ARM_DEPTH)}"'
    box += f' pos="{_f(0.5 * (L - back))} 0 {_f(arm.h - 0.5 * ARM_DEPTH)}"'
    name = part.name.replace('"', "'").replace("&", "and").replace("<", "(").replace(">", ")")
    return f"""<mujoco model="throwmap {name}">
  <compiler angle="radian"/>
  <option timestep="{_f(s.timestep)}" gravity="0 0 {_f(-arm.g)}"{option_extra}>{flags}
  </option>
  <asset>
    <mesh name="part" vertex="{verts}"/>
  </asset>
  <worldbody>
    <geom name="arm" type="box" {box} {arm_contact}/>
    <body name="part">
      <joint name="x" type="slide" axis="1 0 0"/>
      <joint name="y" type="slide" axis="0 0 1"/>
      <joint name="phi" type="hinge" axis="0 -1 0"/>
      <inertial pos="0 0 0" mass="{_f(part.mass)}" diaginertia="{_f(inertia)} {_f(inertia)} {_f(inertia)}"/>
      <geom name="part" type="mesh" mesh="part" {part_contact}/>
    </body>
  </worldbody>{key}
</mujoco>
"""
