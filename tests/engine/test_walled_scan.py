"""Random throws on tilted arms with an end wall: "rigid_body" against the engine, throw by throw.

Random convex parts (3–7 vertices, some with a lead weight) and the canonical triangle, arm length 0.25–0.45 m,
h −3…0 cm, α −0.35…−0.03 rad, μ ∈ {0.2, 0.4, 0.6, 1, 2}, walls 2–8 cm high with μ_w = μ or drawn from
{0, 0.3, 1}, starts at rest anywhere on the arm, ω 2.5–7 rad/s. rigid_body runs with the engines' impact law
(``impact_law="velocity"``; the default Routh law differs from it by millimetres at μ ≤ 0.6, a law choice). A
throw either side refuses is left out; every other throw must end the same way, and rests on the same side
within 2 mm — except rests leaning on the wall's top corner (an edge on the corner, a vertex on the arm), where
the two disagree in 4 of 59 such rests of a 1,000-throw scan (seed 12): that gap is known and stated in docs/explanation/validation.md.
"""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap import Part
from throwmap.studies.agreement import REFUSED
from throwmap.system.fixtures import Wall
from throwmap.system.starts import tilted_rest_reason, wall_start_reason
from throwmap.throws.orbit_trajectory import throw_trajectory


def random_part(rng) -> Part:
    while True:
        n = int(rng.integers(3, 8))
        ang = np.sort(rng.uniform(0, 2 * np.pi, n))
        rad = rng.uniform(0.03, 0.09, n)
        pts = np.c_[rad * np.cos(ang), rad * np.sin(ang)]
        try:
            pm = [(0.03, tuple(0.5 * pts[int(rng.integers(n))]))] if rng.random() < 0.4 else []
            return Part.from_vertices(pts.tolist(), mass=0.05, point_masses=pm)
        except tm.ThrowmapError:
            continue


def scenes(seed: int, n: int):
    rng = np.random.default_rng(seed)
    while n:
        part = tm.triangle_30_60_90(0.17) if rng.random() < 0.4 else random_part(rng)
        L = float(rng.uniform(0.25, 0.45))
        mu = float(rng.choice([0.2, 0.4, 0.6, 1.0, 2.0]))
        alpha = float(rng.uniform(-0.35, -0.03))
        H = float(rng.uniform(0.02, 0.08))
        wall = Wall(height=H) if rng.random() < 0.5 else Wall(height=H, mu=float(rng.choice([0.0, 0.3, 1.0])))
        arm = tm.Arm(h=float(rng.uniform(-0.03, 0.0)), mu=mu, length=L)
        x = float(rng.uniform(0.1, L - 0.03))
        om = float(rng.uniform(2.5, 7.0))
        sides = [k for k in part.stable_sides
                 if not tilted_rest_reason(part, arm, k, alpha, True) and not wall_start_reason(part, arm, k, x, (wall,))]
        if sides:
            n -= 1
            yield part, arm, wall, alpha, x, int(rng.choice(sides)), om


def leans_on_the_top_corner(part, arm, wall, alpha, x, k, om) -> bool:
    """Whether rigid_body's rest has an edge within 0.1 mm of the wall's top corner."""
    _, traj = throw_trajectory(part, arm, x, k, om, "rigid_body", fixtures=(wall,), alpha=alpha, impact_law="velocity")
    i = traj.n_samples - 1
    c, s = math.cos(float(traj.arm_angle[i])), math.sin(float(traj.arm_angle[i]))
    V = traj.vertices(i)
    P = np.c_[c * V[:, 0] + s * V[:, 1], -s * V[:, 0] + c * V[:, 1]]
    Q = np.array([arm.length, arm.h + wall.height])
    best = math.inf
    for j in range(len(P)):
        a, e = P[j], P[(j + 1) % len(P)] - P[j]
        u = min(max(float((Q - a) @ e / (e @ e)), 0.0), 1.0)
        best = min(best, float(np.linalg.norm(Q - a - u * e)))
    return best < 1e-4


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore::throwmap.errors.RegimeWarning")  # random h below −min d: flips may move outward
def test_rigid_body_and_the_engine_agree_on_random_walled_throws():
    compared = agree = corner = 0
    for scene in scenes(seed=7, n=150):
        part, arm, wall, alpha, x, k, om = scene
        rb = tm.throw(part, arm, x, k, om, "rigid_body", fixtures=(wall,), alpha=alpha, impact_law="velocity")
        en = tm.throw(part, arm, x, k, om, "engine", fixtures=(wall,), alpha=alpha)
        if int(rb.status) in REFUSED or int(en.status) in REFUSED:
            continue
        compared += 1
        same = rb.status == en.status and (rb.status != tm.Status.OK or (rb.side == en.side and abs(rb.x - en.x) <= 2e-3))
        if same:
            agree += 1
            continue
        assert rb.status == tm.Status.OK and leans_on_the_top_corner(*scene), (scene, rb, en)
        corner += 1
    print(f"compared {compared}, agree {agree}, corner leans apart {corner}")
    assert compared >= 100  # the scan compares most throws (refusals are a minority)
    assert corner <= 2, f"{corner} rests leaning on the wall's top corner disagree"
