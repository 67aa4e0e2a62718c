"""The engine's exact-flight leaps see the wall's top corner coming at a part.

While every part is clear, the engine moves parts along their exact parabolas in leaps bounded by the
clearance, which measures the arm's and the fixtures' corners against each part's shape. Chipmunk caches a
shape's world vertices at each step: a single part's shape was left stale through a run of leaps, so the
corner was measured against where the part had been, and on a tilted arm with a wall the top corner passed
10.7 mm into a triangle flying over it; the throw came back ``ok`` 11.5 mm from its converged rest. The
rest is checked against "rigid_body" (an exact model that follows the edge along the corner) and against the
engine with exact flight off, and the corner's depth inside the part over the recorded run is bounded.
"""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.engine.settings import EngineSettings
from throwmap.system.fixtures import Wall
from throwmap.throws.orbit_trajectory import throw_trajectory

ARM = tm.Arm(h=-0.01, mu=0.4134738387683247, length=0.30238323553756874)
WALL = Wall(height=0.05117009284152568)
ALPHA = -0.24123656446928166  # rad
START = (0.2578857007646339, 2, 4.5077042072520594)  # x (m), side, ω (rad/s)


def corner_depth(traj, corner) -> float:
    """Deepest the point ``corner`` (arm frame, m) lies inside the part over the recorded samples (m; < 0: outside)."""
    worst = -math.inf
    for i in range(traj.n_samples):
        a = float(traj.arm_angle[i])
        c, s = math.cos(a), math.sin(a)
        V = traj.vertices(i)
        P = np.c_[c * V[:, 0] + s * V[:, 1], -s * V[:, 0] + c * V[:, 1]]
        n = len(P)
        area = 0.5 * sum(P[j, 0] * P[(j + 1) % n, 1] - P[(j + 1) % n, 0] * P[j, 1] for j in range(n))
        inside = math.inf
        for j in range(n):
            e = P[(j + 1) % n] - P[j]
            normal = np.array([-e[1], e[0]]) / math.hypot(*e) * (1.0 if area > 0 else -1.0)
            inside = min(inside, float(normal @ (corner - P[j])))
        worst = max(worst, inside)
    return worst


@pytest.mark.slow
def test_a_wall_corner_does_not_pass_into_a_part_in_exact_flight():
    part = tm.triangle_30_60_90(0.17)
    corner = np.array([ARM.length, ARM.h + WALL.height])
    out, traj = throw_trajectory(part, ARM, *START, "engine", fixtures=(WALL,), alpha=ALPHA)
    assert corner_depth(traj, corner) <= 1e-4  # was 10.7 mm
    stepped = tm.throw(part, ARM, *START, "engine", fixtures=(WALL,), alpha=ALPHA,
                       settings=EngineSettings(exact_flight=False, dt=1.25e-4 / 4))
    exact = tm.throw(part, ARM, *START, "rigid_body", fixtures=(WALL,), alpha=ALPHA)
    assert out.status == stepped.status == exact.status == tm.Status.OK
    assert out.side == stepped.side == exact.side == 0
    assert abs(out.x - stepped.x) < 5e-4 and abs(out.x - exact.x) < 5e-4  # was 11.5 mm off
