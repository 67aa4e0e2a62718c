"""What an engine simulates: parts placed on an arm with fixtures at a rest angle."""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field

from ..errors import InvalidStateError, shown
from ..system.arm import Arm
from ..system.fixtures import Cavity, Wall
from ..system.part import Part
from ..system.pose import pose_at_rest
from ..system.system import check_alpha
from .settings import Friction

__all__ = ["Placement", "Scene", "OVERLAP_TOL"]

OVERLAP_TOL = 1e-3
"""m: two placed parts may overlap by at most this much (resting contacts sit a collision slop, ~10 µm,
inside each other, and a chained run starts where the last one ended); deeper is refused,
as the engine refuses a run in which a vertex sinks deeper than its default ``penetration_tol`` (1 mm)."""


def _check_overlap(placements, h: float) -> None:
    """Raise :class:`InvalidStateError` ``placements`` naming the first two placements that overlap by more
    than :data:`OVERLAP_TOL` (separating axes, :func:`throwmap.system.geometry.overlap_depth`)."""
    from ..system.geometry import overlap_depth
    from ..system.pose import world_vertices

    verts = [world_vertices(p.part, p.arm_pose(h)) for p in placements]
    for i in range(len(verts)):
        for j in range(i + 1, len(verts)):
            depth = overlap_depth(verts[i], verts[j])
            if depth > OVERLAP_TOL:
                raise InvalidStateError("placements", f"placements {i} and {j} overlap by {depth * 1e3:.3g} mm "
                                                      f"(> {OVERLAP_TOL * 1e3:g} mm): parts cannot start inside each other")


@dataclass(frozen=True, slots=True)
class Placement:
    """A part on the arm: at rest on ``side`` with CM abscissa ``x`` (m, arm frame),
    or at an explicit arm-frame ``pose`` ``(x, y, φ)`` (see :mod:`throwmap.records.trajectory`)
    with arm-frame ``velocity`` ``(ẋ, ẏ, φ̇)`` (m/s, m/s, rad/s).
    """

    part: Part
    x: float | None = None
    side: int | None = None
    pose: tuple | None = None
    velocity: tuple = (0.0, 0.0, 0.0)

    def __post_init__(self):
        if not isinstance(self.part, Part):
            raise InvalidStateError("placement.part", f"must be a Part, got {type(self.part).__name__}")
        if self.pose is None:
            if self.x is None or self.side is None:
                raise InvalidStateError("placement", "give either (x, side) or pose")
            self.part.check_side(self.side)
            x = self.x
            if isinstance(x, bool) or not isinstance(x, numbers.Real) or not math.isfinite(x):
                raise InvalidStateError("placement.x", f"must be a finite number, got {shown(x)}")
        else:
            p = tuple(float(v) for v in self.pose)
            if len(p) != 3 or not all(math.isfinite(v) for v in p):
                raise InvalidStateError("placement.pose", f"must be 3 finite numbers (x, y, φ), got {shown(self.pose)}")
            object.__setattr__(self, "pose", p)
        v = tuple(float(c) for c in self.velocity)
        if len(v) != 3 or not all(math.isfinite(c) for c in v):
            raise InvalidStateError("placement.velocity", f"must be 3 finite numbers, got {shown(self.velocity)}")
        object.__setattr__(self, "velocity", v)

    def arm_pose(self, h: float) -> tuple[float, float, float]:
        """Arm-frame pose ``(x, y, φ)``."""
        if self.pose is not None:
            return self.pose
        return pose_at_rest(self.part, h, float(self.x), int(self.side))


@dataclass(frozen=True, slots=True)
class Scene:
    """Parts on an arm with fixtures; ``alpha`` is the arm's rest angle (rad, CCW +; Sec. VI).

    ``length`` of the simulated arm is ``arm.length`` or, when that is None, long
    enough for the throw: the bound on the parts' flight plus
    :attr:`EngineSettings.default_length`, longer on reruns (:mod:`throwmap.engine.reach`).
    """

    arm: Arm
    placements: tuple
    fixtures: tuple = ()
    alpha: float = 0.0
    friction: Friction = field(default_factory=Friction)

    def __post_init__(self):
        if not isinstance(self.arm, Arm):
            raise InvalidStateError("arm", f"must be an Arm, got {type(self.arm).__name__}")
        pl = tuple(self.placements)
        if not pl:
            raise InvalidStateError("placements", "needs at least one part")
        object.__setattr__(self, "placements", pl)
        if len(pl) > 1:
            _check_overlap(pl, self.arm.h)
        fx = tuple(self.fixtures)
        for f in fx:
            if not isinstance(f, (Wall, Cavity)):
                raise InvalidStateError("fixtures", f"unknown fixture {shown(f)} (use Wall or Cavity)")
        if fx and self.arm.length is None:
            raise InvalidStateError("arm.length", "fixtures sit at the arm's end: give the arm a length")
        object.__setattr__(self, "fixtures", fx)
        object.__setattr__(self, "alpha", check_alpha(self.alpha))
        if not isinstance(self.friction, Friction):
            raise InvalidStateError(
                "friction", f"must be a throwmap.engine.Friction, got {type(self.friction).__name__}")

    @property
    def parts(self) -> tuple:
        return tuple(p.part for p in self.placements)

    def length(self, default_length: float, realisation=None, t_max: float = 10.0) -> float:
        """Length of the simulated arm (m): ``arm.length``, or for an unbounded arm the first length
        :func:`throwmap.engine.reach.lengths` tries for ``realisation`` (None: the parts just settle)."""
        from .reach import lengths

        return lengths(self, realisation, default_length, t_max)[0]

    def mu(self, which: str) -> float:
        """The pair friction μ for ``"arm"``, ``"wall"`` or ``"part"`` contacts."""
        f = self.friction
        if which == "arm":
            return self.arm.mu if f.arm_part is None else f.arm_part
        if which == "wall":
            if f.wall_part is not None:
                return f.wall_part
            walls = [w for w in self.fixtures if isinstance(w, Wall) and w.mu is not None]
            return walls[0].mu if walls else self.mu("arm")
        return f.part_part
