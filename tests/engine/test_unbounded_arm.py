"""Engines on an unbounded arm (Arm.length None): the simulated arm is long enough for the throw, and
a part that reaches its end is refused as ``unresolved`` — never ``off_end``, which means leaving a
real arm's end (outsider defect 4, round 2)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.engine import EngineSettings, ImpulseThrow, Placement, Scene, engine_run
from throwmap.engine.reach import GROWTH, flight_reach, lengths
from throwmap.system.catalogue import builtin_part
from throwmap.records.outcome import Status

TRI = builtin_part("triangle")

SLIDE = dict(x=0.3, side=0, omega=5.0)
"""On a frictionless level arm the CM's horizontal velocity, −ω(h + d), never changes; with
h = −0.05 m below −d the triangle slides outward for ever (rigid_body: no_rest)."""
SLIDE_ARM = dict(h=-0.05, mu=0.0)
TINY = 1e-3
"""m: a margin beyond the flight bound so small that the sliding part reaches every simulated end."""


def test_outsider_throw_on_unbounded_arm_is_not_off_end():
    """The outsider's throw: it lands at x ≈ 6 m after a 6.2 s flight and tumbles on past the old
    simulated end (start + 2 m = 7.97 m); the engine said off_end at 8.698 m."""
    arm = tm.Arm(h=-0.01, mu=1.0)
    out = tm.throw(TRI, arm, 5.973, 2, 5.080001, model="engine")
    assert out.status != Status.OFF_END
    assert out.status in (Status.OK, Status.UNCONVERGED, Status.UNRESOLVED, Status.PENETRATION, Status.TIMEOUT)
    if out.ok:  # it went past where the old simulated arm ended: the arm was sized for the throw
        assert out.x > 5.973 + 2.0


def _slide_lengths(margin):
    scene = Scene(tm.Arm(**SLIDE_ARM), (Placement(TRI, x=SLIDE["x"], side=SLIDE["side"]),))
    return lengths(scene, ImpulseThrow(SLIDE["omega"]), margin, 10.0)


def test_part_at_the_simulated_end_is_unresolved_with_reason():
    """pymunk: the sliding part reaches the end of every simulated arm: unresolved, the message says
    the arm is unbounded and which lengths were tried; on a real arm that long it is off_end."""
    tried = _slide_lengths(TINY)
    assert len(tried) >= 2 and all(b > a for a, b in zip(tried, tried[1:]))  # reruns on longer arms
    run = engine_run(TRI, tm.Arm(**SLIDE_ARM), **SLIDE, settings=EngineSettings(default_length=TINY))
    assert run.status == Status.UNRESOLVED and run.statuses == (Status.UNRESOLVED,)
    assert "unbounded" in run.message and f"{tried[-1]:.4g}" in run.message
    out = run.outcome(0, x0=SLIDE["x"], side0=SLIDE["side"], omega=SLIDE["omega"])
    assert out.status == Status.UNRESOLVED
    assert "unbounded" in out.message
    # the same throw on a real arm of the longest length: it leaves that arm's end
    real = engine_run(TRI, tm.Arm(**SLIDE_ARM, length=tried[-1]), **SLIDE)
    assert real.status == Status.OFF_END


FAST = dict(x=0.3, side=0, omega=20.0)
"""The same slide at 0.5 m/s: it passes start + 2 m (the old simulated end) within t_max."""


def test_default_margin_lets_the_slide_run_out_of_time_not_off_the_arm():
    """With the default margin the arm is extended past where the never-ending slide gets in t_max:
    timeout (refused), not off_end (before: off_end at 2.307 m)."""
    run = engine_run(TRI, tm.Arm(**SLIDE_ARM), **FAST)
    assert run.status not in (Status.OFF_END, Status.OK)
    assert run.states[0][0] > FAST["x"] + 2.0  # it did get past the old end


def test_mujoco_unbounded_arm(monkeypatch):
    """MuJoCo: the same rules (its margin is engine.mujoco.settings.UNBOUNDED_EXTRA)."""
    pytest.importorskip("mujoco")
    import throwmap.engine.mujoco.throw as MT
    from throwmap.engine.mujoco import mujoco_throw

    monkeypatch.setattr(MT, "UNBOUNDED_EXTRA", TINY)
    out = mujoco_throw(TRI, tm.Arm(**SLIDE_ARM), **SLIDE)
    assert out.status == Status.UNRESOLVED
    assert "unbounded" in out.message
    real = mujoco_throw(TRI, tm.Arm(**SLIDE_ARM, length=_slide_lengths(TINY)[-1]), **SLIDE)
    assert real.status == Status.OFF_END
    monkeypatch.undo()
    fast = mujoco_throw(TRI, tm.Arm(**SLIDE_ARM), **FAST)  # before: off_end at 2.307 m
    assert fast.status not in (Status.OFF_END, Status.OK) and fast.x > FAST["x"] + 2.0


def test_flight_bound_holds_for_free_flights():
    """Independent check of the bound: fly the part on its exact parabola, spinning at ω, until a
    vertex reaches the surface line; its CM never gets past flight_reach's x."""
    rng = np.random.default_rng(20261123)
    h, g = -0.01, 9.81
    for _ in range(200):
        side = int(rng.choice(np.flatnonzero(TRI.stable)))
        x = float(rng.uniform(0.05, 3.0))
        om = float(rng.uniform(0.5, 12.0))
        alpha = float(rng.uniform(-0.3, 0.3))
        px, py, phi = tm.system.pose.pose_at_rest(TRI, h, x, side)
        vx, vy = -om * py, om * px  # ω × r in the arm frame (Sec. III-B)
        R = float(np.max(np.hypot(TRI.w[:, 0], TRI.w[:, 1])))
        far, vmax = flight_reach(px, py, vx, vy, g, h, R, alpha)
        ax, ay = -g * math.sin(alpha), -g * math.cos(alpha)
        t = np.linspace(1e-4, 2.0 * (abs(vy) + 1.0) / abs(ay) + 1.0, 20000)
        cx, cy, a = px + vx * t + 0.5 * ax * t * t, py + vy * t + 0.5 * ay * t * t, phi + om * t
        c, s = np.cos(a)[:, None], np.sin(a)[:, None]
        vy_all = cy[:, None] + s * TRI.w[:, 0] + c * TRI.w[:, 1]
        hit = np.flatnonzero((vy_all < h).any(axis=1))
        end = hit[0] if hit.size else t.size
        assert cx[:end].max(initial=px) <= far + 1e-9
        speed = np.hypot(vx + ax * t[:end], vy + ay * t[:end])
        assert speed.max(initial=0.0) <= vmax + 1e-9
        # knowing only the launch speed (a moving arm): a weaker bound, still a bound
        far_s, vmax_s = flight_reach(px, py, 0.0, 0.0, g, h, R, alpha, speed=math.hypot(vx, vy))
        assert cx[:end].max(initial=px) <= far_s + 1e-9 and speed.max(initial=0.0) <= vmax_s + 1e-9


def test_lengths_grow_and_bounded_arm_is_kept():
    assert _slide_lengths(2.0)[0] > SLIDE["x"] + 2.0 - 1e-12
    tried = _slide_lengths(0.5)
    assert all(math.isclose(b - a, 0.5 * (GROWTH**(k + 1) - GROWTH**k)) or b == tried[-1]
               for k, (a, b) in enumerate(zip(tried, tried[1:])))
    scene = Scene(tm.Arm(h=-0.01, length=0.4), (Placement(TRI, x=0.2, side=0),))
    assert lengths(scene, ImpulseThrow(4.0), 2.0, 10.0) == [0.4]


def test_cli_engine_throw_on_unbounded_arm():
    from typer.testing import CliRunner

    from throwmap.cli.app import app

    res = CliRunner().invoke(app, ["throw", "--part", "triangle", "--h", "-0.01", "--mu", "1", "--omega", "5.080001",
                                   "--x", "5.973", "--side", "2", "--model", "engine"])
    assert res.exit_code == 0, res.output
    assert "off_end" not in res.output


def test_flight_longer_than_t_max_times_out_and_says_so():
    """A flight longer than t_max (x = 20 m, ω = 5 rad/s: about 20 s up and down) is a timeout whose
    message says the part never landed, not an escape (the arm reaches past the whole flight)."""
    run = engine_run(TRI, tm.Arm(h=-0.01, mu=1.0), 20.0, 0, 5.0)
    assert run.status == Status.TIMEOUT
    assert "first flight" in run.message and "t_max" in run.message


def test_batch_failures_count_unresolved():
    from throwmap.models.engine import engine_failures

    assert "unresolved" not in engine_failures(np.array([int(Status.OK), int(Status.TIMEOUT)]))
    assert "unresolved refused 1/2" in engine_failures(np.array([int(Status.OK), int(Status.UNRESOLVED)]))


def test_refusal_reason_reaches_throw_and_json():
    """The reason of a refused engine throw is on the ThrowOutcome from tm.throw and in its JSON."""
    with pytest.warns(tm.RegimeWarning):  # h = -0.05 m is below -min d: outside the paper's regime
        out = tm.throw(TRI, tm.Arm(**SLIDE_ARM), SLIDE["x"], SLIDE["side"], SLIDE["omega"], model="engine",
                       settings=EngineSettings(default_length=TINY))
    assert out.status == Status.UNRESOLVED
    assert "unbounded" in out.message and "unbounded" in out.to_dict()["message"]
    assert "reason: " in out.table()
    late = tm.throw(TRI, tm.Arm(h=-0.01, mu=1.0), 20.0, 0, 5.0, model="engine")
    assert late.status == Status.TIMEOUT and "first flight" in late.message
