"""Model "rigid_body" on a moving arm (issue 12 item 2): independent checks of the moving-arm phase.

* the arm's θ̈ in closed form against differences of θ̇;
* the handover: the static automaton started from the release state is today's throw bit for bit,
  and ``realisation=ImpulseThrow(ω)`` is today's throw;
* the sticking ride: contact forces from the glued part's world-frame kinematics (no fictitious
  forces, no constrained solve) against :func:`~throwmap.kernels.rigid_body.moving.dynamics.solve`,
  the first lift-off time, and the work done by the arm against the part's energy;
* the pivot after the first lift-off against a scipy ``solve_ivp`` integration in the world frame
  about the moving vertex (separation time and velocity);
* the impulse limit (FiniteThrow, Δt → 0), a SampledThrow of a RecoilThrow, and (slow) the engine.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

import throwmap
from throwmap.system.motion import FiniteThrow, ImpulseThrow, RecoilThrow, SampledThrow, TiltTo
from throwmap.errors import InvalidStateError
from throwmap.kernels import codes as C
from throwmap.kernels.flight import release_state
from throwmap.kernels.rigid_body.automaton import throw_from_state, throw_one_rigid_body
from throwmap.kernels.rigid_body.inputs import arm_arrays, part_arrays, run_limits
from throwmap.kernels.rigid_body.moving import arm_motion, throw_moving
from throwmap.kernels.rigid_body.moving.dynamics import Body, applied, offsets, solve
from throwmap.kernels.rigid_body.moving.handover import start_pose
from throwmap.kernels.rigid_body.moving.phase import Phase, run_phase
from throwmap.system.arm import Arm
from throwmap.system.catalogue import triangle_30_60_90
from throwmap.system.fixtures import Wall

PART = triangle_30_60_90()
SIDE = int(np.flatnonzero(PART.stable)[0])
SLOW = dict(t_recoil=0.15)  # a slow recoil (θ̈ ≈ 11 rad/s²): the part rides it flat


def test_recoil_second_derivative_closed_form():
    for zeta in (0.2, 0.5):
        r = RecoilThrow.for_release_rate(5.0, zeta=zeta)
        m = arm_motion(r)
        for t in np.linspace(0.001, r.duration - 0.001, 157):
            if min(abs(t - b) for b in m.breaks) < 1e-4:
                continue
            th, thd, thdd = m.state(t)
            assert th == pytest.approx(r.angle(t), abs=1e-15)
            assert thd == pytest.approx(r.rate(t), abs=1e-12)
            h = 1e-6
            fd = (r.rate(t + h) - r.rate(t - h)) / (2 * h)
            assert thdd == pytest.approx(fd, rel=1e-6, abs=1e-6)


def test_handover_from_release_is_todays_throw_bit_for_bit():
    rng = np.random.default_rng(3)
    for mu in (0.3, 1.5, math.inf):
        arm = Arm(h=-0.01, mu=mu)
        for _ in range(25):
            k = int(rng.choice(np.flatnonzero(PART.stable)))
            x = rng.uniform(-PART.uL[k] + 1e-4, 0.4)
            om = rng.uniform(3, 7)
            args = (part_arrays(PART), arm_arrays(arm.h, arm.g, 0.0, math.inf, arm.back, arm.mu, 0),
                    run_limits(1e-14, 100000, 10000))
            r1, r2 = np.empty(C.NREC), np.empty(C.NREC)
            a = throw_one_rigid_body(x, k, om, *args, r1, np.empty((0, 4)), 0.0)
            vx, vy, w = release_state(x, PART.d[k], arm.h, om)
            st = np.array([0.0, 0.0, x, arm.h + PART.d[k], vx, vy, w, PART.beta[k], k, 0, 0, 0, 0, 1.0])
            b = throw_from_state(st, *args, r2, np.empty((0, 4)), 0.0)
            assert a == b
            keep = np.arange(C.NREC) != C.E_RELEASE
            np.testing.assert_array_equal(r1[keep], r2[keep])


def test_impulse_realisation_is_todays_throw():
    arm = Arm(h=-0.01, mu=1.5)
    xs = np.linspace(0.11, 0.4, 7)
    for om in (3.0, 6.5):
        a = throwmap.throw_batch(PART, arm, xs, SIDE, om, model="rigid_body")
        b = throwmap.throw_batch(PART, arm, xs, SIDE, om, model="rigid_body", realisation=ImpulseThrow(om))
        np.testing.assert_array_equal(a.x, b.x)
        np.testing.assert_array_equal(a.side, b.side)


def _glued_forces(part, side, x0, h, g, alpha, r, t):
    """(N_A, N_B, F_t) per unit mass holding the part glued flat to the arm: world-frame kinematics only."""
    th, thd, thdd = arm_motion(r).state(t)
    psi = alpha + th
    y0 = h + part.d[side]
    rx, _ry = offsets(Body(part.w, part.radius_of_gyration ** 2, part.d, part.beta), part.beta[side])
    a_, b_ = side, (side + 1) % part.w.shape[0]
    fn = -thd * thd * y0 + thdd * x0 + g * math.cos(psi)
    ft = -thd * thd * x0 - thdd * y0 + g * math.sin(psi)
    # ρ² θ̈ = rA N_A + rB N_B − (h − y0) F_t,  N_A + N_B = F_n
    rA, rB = rx[a_], rx[b_]
    rhs = part.radius_of_gyration ** 2 * thdd + (h - y0) * ft
    nb = (rhs - rA * fn) / (rB - rA)
    return fn - nb, nb, ft


def test_sticking_ride_forces_and_lift_off_time():
    arm = Arm(h=-0.01, mu=math.inf)
    r = RecoilThrow.for_release_rate(5.0, **SLOW)
    x0 = 0.2
    body = Body(PART.w, PART.radius_of_gyration ** 2, PART.d, PART.beta)
    s = start_pose(PART, arm.h, x0, SIDE)
    m = arm_motion(r)
    act = (SIDE, (SIDE + 1) % 3)
    for t in np.linspace(0.0, 0.16, 33):
        th, thd, thdd = m.state(t)
        _a, N, T, ok = solve(body, s, applied(s, arm.g, th, thd, thdd), act, 0, arm.mu)
        na, nb, ft = _glued_forces(PART, SIDE, x0, arm.h, arm.g, 0.0, r, t)
        assert ok
        assert N[0] == pytest.approx(na, rel=1e-10, abs=1e-10)
        assert N[1] == pytest.approx(nb, rel=1e-10, abs=1e-10)
        assert T == pytest.approx(ft, rel=1e-10, abs=1e-10)
    # the first lift-off: the first root of min(N_A, N_B), found independently
    p = Phase(0.0, s, SIDE)
    run_phase(p, body, m, arm.g, 0.0, arm.h, arm.mu, 0, math.inf, 0.0)
    t1 = p.log[1][0]
    assert p.log[0][1] == act and len(p.log[1][1]) == 1
    grid = np.linspace(0.0, t1 + 0.01, 4001)
    nmin = [min(_glued_forces(PART, SIDE, x0, arm.h, arm.g, 0.0, r, t)[:2]) for t in grid]
    i = int(np.argmax(np.array(nmin) < 0))
    t_ind = brentq(lambda t: min(_glued_forces(PART, SIDE, x0, arm.h, arm.g, 0.0, r, t)[:2]), grid[i - 1], grid[i],
                   xtol=1e-15)
    assert t1 == pytest.approx(t_ind, abs=1e-11)


def test_work_done_by_the_arm_is_the_parts_energy_gain():
    arm = Arm(h=-0.01, mu=math.inf)
    r = RecoilThrow.for_release_rate(4.0, **SLOW)
    x0 = 0.15
    body = Body(PART.w, PART.radius_of_gyration ** 2, PART.d, PART.beta)
    s = start_pose(PART, arm.h, x0, SIDE)
    m = arm_motion(r)
    act = (SIDE, (SIDE + 1) % 3)
    rx, _ry = offsets(body, s[2])
    y0 = s[1]

    def power(t):  # Σ F_j · v_j of the contact forces on the part; the arm's points move at θ̇ ẑ × (x_j, h)
        th, thd, thdd = m.state(t)
        _a, N, T, _ok = solve(body, s, applied(s, arm.g, th, thd, thdd), act, 0, arm.mu)
        return thd * (-arm.h * T + sum(N[i] * (x0 + rx[j]) for i, j in enumerate(act)))

    def energy(t):  # per unit mass: ½ θ̇² (x² + y² + ρ²) + g Y
        th, thd, _ = m.state(t)
        return 0.5 * thd * thd * (x0 * x0 + y0 * y0 + body.rho2) + arm.g * (math.sin(th) * x0 + math.cos(th) * y0)

    t_rec = r.t_recoil  # θ̈ jumps there: integrate each piece on its own
    for t1 in (0.1, t_rec, 0.16):
        w = quad(power, 0.0, min(t1, t_rec), limit=200, epsabs=1e-13)[0]
        if t1 > t_rec:
            w += quad(power, t_rec, t1, limit=200, epsabs=1e-13)[0]
        assert w == pytest.approx(energy(t1) - energy(0.0), rel=1e-8, abs=1e-11)


def test_pivot_after_lift_off_matches_world_frame_ode():
    """After the first vertex lifts, the part turns about the other (sticking, μ = ∞) until it leaves: the
    world-frame equation about the accelerating vertex, I_P Φ̈ = r_PC × (g − a_P), by solve_ivp."""
    arm = Arm(h=-0.01, mu=math.inf)
    r = RecoilThrow.for_release_rate(5.0, **SLOW)
    x0 = 0.2
    body = Body(PART.w, PART.radius_of_gyration ** 2, PART.d, PART.beta)
    m = arm_motion(r)
    p = Phase(0.0, start_pose(PART, arm.h, x0, SIDE), SIDE)
    run_phase(p, body, m, arm.g, 0.0, arm.h, arm.mu, 0, math.inf, 0.0)
    t1, act1, tm1, s1 = p.log[1]
    t2, act2, _tm2, s2 = p.log[2]
    assert len(act1) == 1 and tm1 == 0 and act2 == ()
    j = act1[0]
    rx, ry = offsets(body, s1[2])
    px = s1[0] + rx[j]
    wj = PART.w[j]
    ip = body.rho2 + wj @ wj
    g = arm.g

    def kin(t, y):
        th, thd, thdd = m.state(t)
        c, s_ = math.cos(th), math.sin(th)
        aP = np.array([c * (-thd * thd * px - thdd * arm.h) - s_ * (-thd * thd * arm.h + thdd * px),
                       s_ * (-thd * thd * px - thdd * arm.h) + c * (-thd * thd * arm.h + thdd * px)])
        cp, sp = math.cos(y[0]), math.sin(y[0])
        rpc = -np.array([cp * wj[0] - sp * wj[1], sp * wj[0] + cp * wj[1]])
        f = np.array([0.0, -g]) - aP
        phidd = (rpc[0] * f[1] - rpc[1] * f[0]) / ip
        aC = aP + phidd * np.array([-rpc[1], rpc[0]]) - y[1] ** 2 * rpc
        F = aC - np.array([0.0, -g])
        return phidd, F @ np.array([-s_, c]), th, thd, rpc, c, s_

    def rhs(t, y):
        return [y[1], kin(t, y)[0]]

    def normal(t, y):
        return kin(t, y)[1]

    normal.terminal = True
    normal.direction = -1
    th1, thd1, _ = m.state(t1)
    sol = solve_ivp(rhs, (t1, t1 + 0.2), [s1[2] + th1, s1[5] + thd1], method="DOP853", rtol=1e-12, atol=1e-14,
                    events=normal)
    t_ind = sol.t_events[0][0]
    assert t2 == pytest.approx(t_ind, abs=1e-9)
    # the CM's world velocity at separation
    yv = sol.y_events[0][0]
    _pdd, _n, th, thd, rpc, c, s_ = kin(t_ind, yv)
    vP = thd * np.array([-(s_ * px + c * arm.h), c * px - s_ * arm.h])
    v_ind = vP + yv[1] * np.array([-rpc[1], rpc[0]])
    th2, thd2, _ = m.state(t2)
    cm = np.array([s2[0], s2[1]])
    v_arm = np.array([s2[3], s2[4]]) + thd2 * np.array([-cm[1], cm[0]])
    v_world = np.array([math.cos(th2) * v_arm[0] - math.sin(th2) * v_arm[1],
                        math.sin(th2) * v_arm[0] + math.cos(th2) * v_arm[1]])
    np.testing.assert_allclose(v_world, v_ind, rtol=0, atol=1e-8)
    assert s2[5] + thd2 == pytest.approx(yv[1], abs=1e-7)


def test_finite_throw_converges_to_the_impulse():
    arm = Arm(h=-0.01, mu=1.5)
    for x, om in ((0.15, 4.0), (0.3, 6.0)):
        imp = throwmap.throw(PART, arm, x, SIDE, om, model="rigid_body")
        errs = []
        for dt in (1e-3, 1e-4, 1e-5):
            o = throwmap.throw(PART, arm, x, SIDE, om, model="rigid_body", realisation=FiniteThrow(om, dt))
            assert o.side == imp.side and o.status == imp.status
            errs.append(abs(o.x - imp.x))
        assert errs[-1] < 1e-5 and errs[-1] <= errs[0]


def test_sampled_throw_of_a_recoil_gives_the_recoils_answer():
    arm = Arm(h=-0.01, mu=1.5)
    for x, om in ((0.15, 5.0), (0.3, 3.0)):
        r = RecoilThrow.for_release_rate(om)
        a = throwmap.throw(PART, arm, x, SIDE, om, model="rigid_body", realisation=r)
        b = throwmap.throw(PART, arm, x, SIDE, om, model="rigid_body", realisation=SampledThrow.of(r, 3000))
        assert a.side == b.side and a.status == b.status
        assert abs(a.x - b.x) < 5e-6


def test_options_and_batch():
    arm = Arm(h=-0.01, mu=1.5)
    with pytest.raises(InvalidStateError, match="realisation"):
        throwmap.throw(PART, arm, 0.2, SIDE, 4.0, model="rigid_body", realisation=TiltTo(0.1))
    with pytest.raises(InvalidStateError, match="realisation"):
        throwmap.throw(PART, Arm(h=-0.01, mu=1.5, length=0.5), 0.2, SIDE, 4.0, model="rigid_body",
                       fixtures=(Wall(),), realisation=RecoilThrow.for_release_rate(4.0))
    xs = np.array([0.15, 0.3])
    b = throwmap.throw_batch(PART, arm, xs, SIDE, 4.0, model="rigid_body", realisation=RecoilThrow.for_release_rate)
    for i, x in enumerate(xs):
        o = throwmap.throw(PART, arm, x, SIDE, 4.0, model="rigid_body", realisation=RecoilThrow.for_release_rate(4.0))
        assert (o.x, o.side) == (b.x[i], b.side[i])
    from throwmap.models import get_model

    assert get_model("rigid_body").features.realisation


def test_throw_moving_direct_call():
    x, k, st, rec = throw_moving(PART, Arm(h=-0.01, mu=1.5), 0.2, SIDE, RecoilThrow.for_release_rate(5.0))
    assert st == C.OK and k in np.flatnonzero(PART.stable)
    assert rec[C.N_IMPACTS] >= 1


@pytest.mark.slow
def test_rigid_body_against_the_engine_on_recoil_throws():
    """The engine with its steps / 16 (at its default step it is not converged on impacts against the moving
    arm: studies/recoil_validation.py); rigid_body with the engine's velocity-level impact law."""
    from throwmap.engine.settings import EngineSettings

    base = EngineSettings()
    fine = EngineSettings(dt=base.dt / 16, coarse_dt=base.coarse_dt / 16)
    arm = Arm(h=-0.01, mu=1.5)
    for x in (0.11, 0.15, 0.3):
        for om in (3.0, 5.0, 7.0):
            r = RecoilThrow.for_release_rate(om, zeta=0.2 if om == 5.0 else 0.5)
            a = throwmap.throw(PART, arm, x, SIDE, om, model="rigid_body", realisation=r, impact_law="velocity")
            e = throwmap.throw(PART, arm, x, SIDE, om, model="engine", realisation=r, settings=fine)
            assert a.side == e.side and a.status == e.status
            assert abs(a.x - e.x) <= 0.5e-3


# a side that lands flat out of a lift-off (B touches while A, just lifted, is still on the line): the
# land_side law, not an endless alternation of single-vertex impacts at one instant (was UNRESOLVED)
FLAT_LANDING = (0, 0.44347, 6.768)


def test_side_landing_right_after_a_lift_off_is_resolved():
    side, x, om = FLAT_LANDING
    o = throwmap.throw(PART, Arm(h=-0.01, mu=1.5), x, side, om, model="rigid_body",
                       realisation=RecoilThrow.for_release_rate(om), impact_law="velocity")
    assert o.status == C.OK


@pytest.mark.slow
def test_side_landing_right_after_a_lift_off_against_the_engine():
    from throwmap.engine.settings import EngineSettings

    base = EngineSettings()
    fine = EngineSettings(dt=base.dt / 16, coarse_dt=base.coarse_dt / 16)
    side, x, om = FLAT_LANDING
    arm = Arm(h=-0.01, mu=1.5)
    r = RecoilThrow.for_release_rate(om)
    a = throwmap.throw(PART, arm, x, side, om, model="rigid_body", realisation=r, impact_law="velocity")
    e = throwmap.throw(PART, arm, x, side, om, model="engine", realisation=r, settings=fine)
    assert a.side == e.side and abs(a.x - e.x) <= 0.5e-3


def test_iterate_takes_a_realisation_factory():
    arm = Arm(h=-0.01, mu=1.5)
    o = throwmap.iterate(PART, arm, (0.15, SIDE), [5.0, 4.0], model="rigid_body",
                         realisation=RecoilThrow.for_release_rate)
    a = throwmap.throw(PART, arm, 0.15, SIDE, 5.0, model="rigid_body", realisation=RecoilThrow.for_release_rate(5.0))
    assert o.outcomes[0].x == a.x and o.outcomes[0].side == a.side


def test_frictionless_flat_slide_after_the_arm_stops_is_the_static_slide():
    """μ = 0: a part still sliding flat when the arm stops never stops (NO_REST on an unbounded arm, the edge on
    a bounded one), as the static automaton's slide_away — not an integration to the step cap."""
    from throwmap.studies.validation import default_parts

    pent = default_parts()["pentagon"]
    r = RecoilThrow.for_release_rate(4.35)
    o = throwmap.throw(pent, Arm(h=-0.01, mu=0.0), 0.0517, 1, 4.35, model="rigid_body", realisation=r)
    assert o.status == C.NO_REST
    o = throwmap.throw(pent, Arm(h=-0.01, mu=0.0, length=0.3), 0.0517, 1, 4.35, model="rigid_body", realisation=r)
    assert o.status in (C.OFF_END, C.BEHIND_JOINT)
