"""Contact with the arm and with the end wall holds through every phase on a tilted arm at low μ.

Two throws an audit found: on the triangle (hypotenuse 17 cm), h = −1 cm, arm 0.35 m long, μ = 0.3, a 5 cm
end wall with μ 0.5, "rigid_body" let a vertex sink 0.58 mm and 6.3 mm into the arm (a free-flight exclusion
window kept after the wall's impulse; a corner guard with its rate's sign flipped) and reported ``off_end`` past
a wall the part cannot cross. The engine at its converged step rests both on side 0 near 0.279 m. Checked here:
the rest agrees with the engine, and no recorded vertex is deeper than 0.1 mm inside the arm or the wall.
"""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.kernels.rigid_body.foot import foot_holds, foot_impact
from throwmap.system.fixtures import Wall
from throwmap.throws.orbit_trajectory import throw_trajectory

CASES = [
    (math.radians(-15.562638283870395), 0.2590497482283082, 2, 5.0808360238956025),
    (-0.27876147344524876, 0.24107875587934002, 2, 5.53980366191929),
]


def depth(traj, length, h, wall):
    """Deepest recorded vertex inside the arm (over 0 ≤ x ≤ length) or inside the wall (m)."""
    worst = 0.0
    for i in range(traj.n_samples):
        a = float(traj.arm_angle[i])
        c, s = math.cos(a), math.sin(a)
        V = traj.vertices(i)
        xa, ya = c * V[:, 0] + s * V[:, 1], -s * V[:, 0] + c * V[:, 1]
        on = (xa >= 0.0) & (xa <= length)
        worst = max(worst, float(np.max(np.where(on, h - ya, 0.0))))
        inw = (xa > length) & (xa < length + wall.thickness) & (ya < h + wall.height) & (ya > h - 0.05)
        d = np.minimum(np.minimum(xa - length, h + wall.height - ya), length + wall.thickness - xa)
        worst = max(worst, float(np.max(np.where(inw, d, 0.0))))
    return worst


@pytest.fixture(scope="module")
def scene():
    return tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01, mu=0.3, length=0.35), Wall(height=0.05, mu=0.5)


@pytest.mark.slow
@pytest.mark.parametrize("case", CASES, ids=["corner-impulse", "wall-slide"])
def test_the_rest_agrees_with_the_engine_and_no_vertex_sinks(scene, case):
    part, arm, wall = scene
    alpha, x, k, om = case
    out, traj = throw_trajectory(part, arm, x, k, om, "rigid_body", fixtures=(wall,), alpha=alpha)
    eng = tm.throw(part, arm, x, k, om, "engine", fixtures=(wall,), alpha=alpha)
    assert eng.status == tm.Status.OK and eng.side == 0
    assert out.status == tm.Status.OK, out.message
    assert out.side == eng.side and abs(out.x - eng.x) < 2e-3
    assert out.x < arm.length  # never past the wall
    assert depth(traj, arm.length, arm.h, wall) <= 1e-4


def test_the_foot_impact_keeps_angular_momentum_about_the_foot():
    """Reset at the wall's foot: the vertex stops, angular momentum about it is kept, energy is lost, the arm pushes."""
    rng = np.random.default_rng(3)
    for _ in range(200):
        theta = rng.uniform(0.2, math.pi - 0.2)
        thdot, va = rng.uniform(-3, 3), rng.uniform(0.0, 1.0)
        lj, rho2 = rng.uniform(0.01, 0.1), rng.uniform(1e-4, 3e-3)
        ok, th1, pt, pn, k0, k1 = foot_impact(theta, thdot, va, lj, rho2)
        # angular momentum about the foot (unit mass): ρ² θ̇ + r × v_cm with r = ℓ(cos θ, sin θ)
        vx, vy = va - thdot * lj * math.sin(theta), thdot * lj * math.cos(theta)
        before = rho2 * thdot + lj * (math.cos(theta) * vy - math.sin(theta) * vx)
        after = (rho2 + lj * lj) * th1
        assert after == pytest.approx(before, rel=1e-12, abs=1e-15)
        assert k1 <= k0 * (1 + 1e-12)
        # the normal impulse is the change of the CM's vertical velocity
        assert pn == pytest.approx(max(lj * math.cos(theta) * (th1 - thdot), 0.0), abs=1e-15)
        assert ok == (lj * math.cos(theta) * (th1 - thdot) >= -1e-12 * (abs(va) + abs(thdot) * lj))


def test_the_foot_holds_only_at_the_wall_at_rest_inside_the_cone():
    # a pivot short of the wall, a moving pivot or no wall: not the foot
    args = dict(theta=1.0, thdot=0.0, lj=0.05, I=0.004, g=9.81, mu=0.5, alpha=0.0)
    assert not foot_holds(False, 0.35, 0.35, 0.0, *args.values())
    assert not foot_holds(True, 0.34, 0.35, 0.0, *args.values())
    assert not foot_holds(True, 0.35, 0.35, 0.1, *args.values())
    assert foot_holds(True, 0.35, 0.35, 0.0, *args.values())
    # an arm too slippery to hold the pull away from the wall: the pivot slips back
    slippery = dict(args, mu=0.0, theta=0.6)
    assert not foot_holds(True, 0.35, 0.35, 0.0, *slippery.values())
    assert foot_holds(True, 0.35, 0.35, 0.0, *dict(slippery, mu=5.0).values())


@pytest.mark.slow
def test_a_throw_that_chatters_to_the_event_cap_is_refused_with_its_reason():
    """An edge rocking on the wall's top corner while a vertex slides on the arm: rigid_body's mode changes run
    into ``max_impacts`` at t ≈ 0.447 s without rest (the engine rests it leaning at x ≈ 0.3546 m). Refused,
    status ``unresolved`` with a reason naming the cap — it was ``no_rest`` with no message."""
    part = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=-0.01, mu=0.6567309517173876, length=0.38382780871429306)
    wall = Wall(height=0.05801286385064064)
    out = tm.throw(part, arm, 0.2530936301966614, 0, 5.728010779044818, "rigid_body", fixtures=(wall,),
                   alpha=-0.17920436981011884)
    assert out.status == tm.Status.UNRESOLVED
    assert "max_impacts" in out.message and "chatter" in out.message


def test_a_part_slid_into_the_wall_rests_on_the_arm_to_the_last_ulp():
    """A lead-weighted pentagon slides into the wall's foot on a tilted arm: the kernel's x + u_R landed 1 ulp
    past L and the throw was ``off_end`` at a wall nothing passes. It rests at the last start throw() accepts,
    in the single throw and in a batch."""
    from throwmap.system.starts import start_interval

    pm = ((0.036600159664174646, (0.054296599342909806, 0.02461689254532025)),)
    part = tm.Part.from_vertices([(0.04261978409677654, 0.11387127090709849), (0.0, 0.06643355330464477),
                                  (0.022682049898273837, 0.02197556534737153), (0.04040465381580416, 0.0),
                                  (0.08937004082538766, 0.0452424529556376)],
                                 mass=0.05907393514331355 - pm[0][0], point_masses=pm)
    arm = tm.Arm(h=-0.01771060281702496, mu=0.4, length=0.20944278900367255)
    kw = dict(fixtures=(tm.Wall(height=0.03789182472984673),), alpha=-0.33586349969540374, impact_law="velocity")
    one = tm.throw(part, arm, 0.12152043288847172, 1, 3.0839452176473636, "rigid_body", **kw)
    batch = tm.throw_batch(part, arm, np.array([0.12152043288847172]), 1, 3.0839452176473636, "rigid_body", **kw)
    hi = start_interval(part, arm, 1)[1]
    assert one.status == tm.Status.OK and one.side == 1 and one.x == hi
    assert int(batch.status[0]) == int(tm.Status.OK) and batch.x[0] == hi
    tm.throw(part, arm, one.x, 1, 0.5, "rigid_body", **kw)  # a start throw() accepts (it refused 1 ulp past)
