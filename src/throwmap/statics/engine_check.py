"""Rest states checked in the engine: place the bodies, let pymunk run, see whether they stay (Sec. VI).

The independent check of :func:`~throwmap.statics.rest.analyse_rest`: the placement is simulated for
``run_for`` seconds with the arm still (no throw) and each part's displacement is measured. A placement
the LP says can rest should stay put (up to the engine's contact slop and creep); one it says cannot
should move by millimetres at least (it slides, falls back or topples). Units: m, rad, s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["EngineRest", "engine_rest"]

STAYED = 1e-3
"""A part "stayed" when its CM moved less than this (m) and it turned less than :data:`STAYED_TURN`."""
STAYED_TURN = 0.01
"""rad."""
REFUSED = ("penetration", "unconverged", "timeout", "unresolved")
"""Engine statuses whose run is refused."""


@dataclass(frozen=True, slots=True)
class EngineRest:
    """``moved`` (m) and ``turned`` (rad) per part after ``run_for`` s; ``stayed`` all within the thresholds;
    ``status`` the engine run's: a refused run (:data:`REFUSED`) is never read as resting; the others
    (``ok``, ``off_end``…) only classify the final pose as a throw's rest would, so they do not decide."""

    moved: tuple
    turned: tuple
    status: str
    run_for: float

    @property
    def stayed(self) -> bool:
        return self.status not in REFUSED and all(m < STAYED for m in self.moved) and all(t < STAYED_TURN for t in self.turned)

    def table(self) -> str:
        """Per part: moved (mm) and turned (rad) after ``run_for`` s, then the verdict."""
        lines = ["| part | moved (mm) | turned (rad) |", "|---|---|---|"]
        lines += [f"| {i} | {1e3 * m:.4g} | {t:.4g} |" for i, (m, t) in enumerate(zip(self.moved, self.turned))]
        verdict = "stayed" if self.stayed else ("refused" if self.status in REFUSED else "moved")
        return "\n".join(lines + [f"engine run of {self.run_for:g} s: {self.status}; {verdict} (thresholds "
                                   f"{1e3 * STAYED:g} mm, {STAYED_TURN:g} rad)"])

    def to_dict(self) -> dict:
        """``moved_m``, ``turned_rad`` (per part), ``status``, ``run_for_s``, ``stayed``."""
        return {"moved_m": list(self.moved), "turned_rad": list(self.turned), "status": self.status,
                "run_for_s": self.run_for, "stayed": self.stayed}

    def plot(self, ax=None):
        """How far each part moved against the threshold of "stayed" (:func:`throwmap.viz.statics.plot_engine_rest`)."""
        from ..viz.statics import plot_engine_rest

        return plot_engine_rest(self, ax=ax, threshold=STAYED)


def engine_rest(bodies, *, h: float, mu_arm: float, length: float, wall=None, mu_parts: float = 0.0,
                alpha: float = 0.0, run_for: float = 1.0, settings=None) -> EngineRest:
    """Simulate the placement ``bodies`` (arm frame, surface y = ``h``) for ``run_for`` s on an arm at rest
    angle ``alpha`` with an optional end ``wall``; see :class:`EngineRest`."""
    from ..engine import Friction, Placement, Scene, simulate
    from ..system.arm import Arm

    arm = Arm(h=h, mu=mu_arm, length=length)
    pls = tuple(Placement(b.part, pose=(b.x, b.y, b.phi)) for b in bodies)
    scene = Scene(arm, pls, fixtures=() if wall is None else (wall,), alpha=alpha,
                  friction=Friction(part_part=mu_parts))
    run = simulate(scene, None, settings, run_for=run_for)
    moved, turned = [], []
    for b, pose in zip(bodies, run.poses):
        moved.append(float(math.hypot(pose[0] - b.x, pose[1] - b.y)))
        turned.append(float(abs((pose[2] - b.phi + math.pi) % (2 * math.pi) - math.pi)))
    return EngineRest(tuple(moved), tuple(turned), str(run.status), float(run_for))
