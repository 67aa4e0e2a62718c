"""The second part of the draft's sequential assembly (Sec. V-D, Fig. 10): a four-sided part that fills the
cavity on top of the captured triangle.

The first part is the recoil feeder (:mod:`throwmap.experiments.feed`'s built-in example: the 17 cm
30-60-90 triangle with 80 g of lead, captured on side 0, its hypotenuse, in the 1 cm pocket ending at the end wall,
L = 0.38 m). Captured, it lies with its 60° vertex in the corner of the pocket's floor and the end wall; its exposed
top is two legs meeting at the right angle 6.4 cm above the arm: the short leg (8.5 cm) rising at 60° from the wall
corner, the long leg falling at 30° to the pocket's floor toward the joint.

The wedge between the short leg and the end wall (30° at the corner) is the slot the second part fills: a right
trapezoid whose *tip* (30°) sits in the corner, whose *wall side* is vertical against the end wall, whose *leg side*
lies on the triangle's short leg, with a vertical side above the apex and a flat top ``top`` above it
(:func:`stack_part`). The pair then fills the end of the cavity: the wall from the floor to the top, the triangle's
long leg the only slope left, facing the joint.

Why this slot and not the long leg's side (measured in the engine, recoil arm, 3 % ω jitter): a part
resting on the arm against the long leg (30° slope) is pushed up the slope by every throw (a throw spins it
counter-clockwise, its outer lower vertex drives into the slope) and ends leaning on the triangle 0.5 rad after 3
throws; in the wedge the end wall blocks the same turn (the tip would move into the wall), as it does for the
captured triangle, and the part hops in place. A plain plexiglas wedge (17 g, its CM 6 cm above the floor) is still
thrown out over the apex by the first throw; lead low in the tip keeps it: with 50 g the pair held 30 throws of 30
in two runs, the triangle moving ≤ 5 mm in its pocket and the part tilting ≤ 0.04 rad with it.

What still fails (the experiments, about 100 trials each): a *trap* — the
wedge flat on its leg side on the pocket's floor at the wall with the triangle leaning 30° on it. It forms when the
wedge reaches the wall corner while the triangle is off it (the triangle hops at every throw; in
``assemble-sequential`` the wedge, 2–5× faster outward than the triangle, usually reaches the pocket first) and no
throw rate breaks it (3.5, 4.56, 5.0, 5.5 rad/s: 3 of 3 traps unchanged after 3 throws each). Making the leg side
unstable (the CM beyond the apex end of the leg side: lead in the top corner, top 4–6 cm) removes the trap's
resting state but also the hold: 0 of 10 throws held in 3 of 3 runs (the CM 6–7 cm above the arm is thrown out).
The experiments break it by feedback instead (:class:`throwmap.experiments.sequential.RecoverConfig`: a throw with
the arm tilted 10° once a one-bit sensor sees the pair stuck in the pocket): 187/200 sequential, 96/100 serial.

:func:`design_stack` builds the :class:`StackDesign` (the pocket design, both parts and their assembled poses);
:meth:`StackDesign.assembled` is the predicate with pose tolerances; :meth:`StackDesign.checks` the geometry
(no overlap, the part inside the cavity's end, its CM over its wedge).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown
from ..system.part import Part

__all__ = ["PMMA_AREAL", "StackDesign", "design_stack", "stack_part", "wrap"]

PMMA_AREAL = 1190.0 * 0.00635
"""kg/m²: 6.35 mm plexiglas (1190 kg/m³), the draft's parts (as :mod:`throwmap.design.examples`)."""


def wrap(a: float) -> float:
    """An angle wrapped to (−π, π]."""
    return float((a + math.pi) % (2.0 * math.pi) - math.pi)


def _num(v, name: str, *, lo: float | None = None, positive: bool = False) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or not math.isfinite(v):
        raise InvalidStateError(name, f"must be a finite number, got {shown(v)}")
    if positive and v <= 0:
        raise InvalidStateError(name, f"must be > 0, got {shown(v)}")
    if lo is not None and v < lo:
        raise InvalidStateError(name, f"must be ≥ {lo:g}, got {shown(v)}")
    return float(v)


def stack_part(triangle_vertices, length: float, *, top: float = 0.02, clearance: float = 0.001,
               lead_mass: float = 0.05, lead_at=(-0.005, 0.03), areal: float = PMMA_AREAL):
    """The wedge part for a triangle at rest in the pocket: ``(part, pose)``, the part in its assembled pose.

    ``triangle_vertices``: the captured triangle's world vertices (arm frame, m); ``length``: the end wall's face
    L (m). The part's leg side is the triangle's outer leg (the one ending at the vertex nearest the wall) moved
    ``clearance`` (m) off it, its wall side at L − ``clearance``, its left side through the apex, its top ``top``
    (m) above the apex. ``lead_mass`` (kg, 0: none) at ``lead_at`` (m) from the tip; plate ``areal`` kg/m².
    The part's body frame is the arm frame of the assembled pose, so ``pose`` = (CM x, CM y, 0).
    """
    V = np.asarray(triangle_vertices, dtype=float)
    L = _num(length, "length", positive=True)
    top = _num(top, "top", positive=True)
    c = _num(clearance, "clearance", lo=0.0)
    m = _num(lead_mass, "lead_mass", lo=0.0)
    outer, apex = V[np.argmax(V[:, 0])], V[np.argmax(V[:, 1])]
    u = (apex - outer) / float(np.linalg.norm(apex - outer))
    n = np.array([u[1], -u[0]]) if u[1] > 0 else np.array([-u[1], u[0]])
    if n[0] < 0:
        n = -n
    p0 = outer + c * n

    def at_x(x):
        return p0 + (x - p0[0]) / u[0] * u

    tip, low = at_x(L - c), at_x(apex[0])
    W = np.array([tip, [L - c, apex[1] + top], [apex[0], apex[1] + top], low])
    area = 0.5 * abs(float(np.dot(W[:, 0], np.roll(W[:, 1], -1)) - np.dot(W[:, 1], np.roll(W[:, 0], -1))))
    pms = ()
    if m > 0:
        at = (float(tip[0] + lead_at[0]), float(tip[1] + lead_at[1]))
        pms = ((m, at),)
    part = Part.from_vertices([tuple(map(float, w)) for w in W], areal * area, point_masses=pms,
                              name=f"stack wedge (top {100 * top:.3g} cm, {1000 * m:.3g} g lead)")
    return part, (float(part.com[0]), float(part.com[1]), 0.0)


@dataclass(frozen=True, slots=True, eq=False)
class StackDesign:
    """The sequential-assembly design: ``cavity`` (the pocket's :class:`~throwmap.design.cavity.CavityDesign`,
    its part the triangle), ``triangle``/``triangle_pose`` (at rest at the wall on the target side),
    ``wedge``/``wedge_pose`` (the second part, assembled), ``numbers`` (m, kg, rad)."""

    cavity: object
    triangle: Part
    triangle_pose: tuple
    wedge: Part
    wedge_pose: tuple
    numbers: dict

    arm = property(lambda self: self.cavity.arm)
    fixtures = property(lambda self: self.cavity.fixtures)
    parts = property(lambda self: (self.triangle, self.wedge))
    poses = property(lambda self: (self.triangle_pose, self.wedge_pose))

    def triangle_captured(self, pose) -> bool:
        """The triangle flat on its target side in the pocket (:meth:`CavityDesign.where` == "target")."""
        return self.cavity.where(pose) == "target"

    def wedge_error(self, pose) -> tuple[float, float]:
        """``(position error m, angle error rad)`` of the wedge part at ``pose`` from its assembled pose."""
        e = np.asarray(pose, dtype=float) - np.asarray(self.wedge_pose)
        return float(math.hypot(e[0], e[1])), abs(wrap(float(e[2])))

    def in_cavity(self, part_index: int, pose) -> bool:
        """Whether a part's CM is past the cavity's lip (it is in the cavity's end of the arm)."""
        return float(pose[0]) > self.cavity.lip_x

    def assembled(self, poses, *, pos_tol: float = 0.01, ang_tol: float = 0.1) -> bool:
        """The predicate: the triangle captured on its target side and the wedge part within ``pos_tol`` (m) and
        ``ang_tol`` (rad) of its assembled pose (the pocket's 5 mm play moves the triangle and so the wedge
        resting on it: measured ≤ 5 mm and ≤ 0.04 rad over 30 throws)."""
        p, a = self.wedge_error(poses[1])
        return self.triangle_captured(poses[0]) and p <= pos_tol and a <= ang_tol

    def checks(self) -> dict:
        """Geometry (m): ``overlap_m`` (the parts' overlap depth, < 0: apart), ``wall_gap_m`` (wall face − the
        wedge's outermost x), ``floor_gap_m`` (wedge's lowest y − the pocket floor), ``cm_over_tip_m`` (wedge CM
        x − its left side: > 0 the CM lies over the wedge), ``filled`` (area of the pair / area of the slot
        [apex x, L] × [floor, top] plus the triangle's part left of the apex: 1 − the clearances)."""
        from ..system.geometry import overlap_depth
        from ..system.pose import world_vertices

        T = world_vertices(self.triangle, self.triangle_pose)
        W = world_vertices(self.wedge, self.wedge_pose)
        return {"overlap_m": float(overlap_depth(T, W)), "wall_gap_m": float(self.cavity.length - W[:, 0].max()),
                "floor_gap_m": float(W[:, 1].min() - self.cavity.floor_y),
                "cm_over_tip_m": float(self.wedge.com[0] - W[:, 0].min()),
                "wedge_top_m": float(W[:, 1].max() - self.cavity.arm.h)}

    def to_dict(self) -> dict:
        w = self.wedge
        return {"triangle": {"part": self.triangle.name, "pose": list(self.triangle_pose), "side": self.cavity.side},
                "wedge": {"vertices_m": [list(v) for v in w.vertices], "mass_kg": w.mass, "com_m": list(w.com),
                          "radius_of_gyration_m": w.radius_of_gyration,
                          "point_masses": [[m, list(p)] for m, p in w.point_masses], "pose": list(self.wedge_pose)},
                "cavity": self.cavity.to_dict(), "numbers": dict(self.numbers), "checks": self.checks()}


def design_stack(cavity, *, top: float = 0.02, clearance: float = 0.001, lead_mass: float = 0.05,
                 lead_at=(-0.005, 0.03), areal: float = PMMA_AREAL) -> StackDesign:
    """The :class:`StackDesign` on a pocket design ``cavity`` (:class:`~throwmap.design.cavity.CavityDesign`, its
    part the triangle): the triangle at rest at the end wall on the target side (0.1 mm off it), the wedge part
    of :func:`stack_part` on it."""
    from ..system.pose import pose_at_rest, world_vertices

    tri, k = cavity.part, cavity.side
    tpose = tuple(float(v) for v in pose_at_rest(tri, cavity.floor_y, cavity.length - float(tri.uR[k]) - 1e-4, k))
    V = world_vertices(tri, tpose)
    if float(V[:, 1].max()) <= cavity.arm.h:
        raise InvalidStateError("cavity", "the captured triangle does not rise above the arm: nothing to stack on")
    wedge, wpose = stack_part(V, cavity.length, top=top, clearance=clearance, lead_mass=lead_mass, lead_at=lead_at,
                              areal=areal)
    apex = V[np.argmax(V[:, 1])]
    numbers = {"top_m": top, "clearance_m": clearance, "lead_mass_kg": lead_mass, "lead_at_m": list(map(float, lead_at)),
               "apex_height_m": float(apex[1] - cavity.arm.h), "apex_x_m": float(apex[0]),
               "wedge_mass_kg": wedge.mass, "wedge_width_m": float(cavity.length - clearance - apex[0])}
    return StackDesign(cavity, tri, tpose, wedge, wpose, numbers)
