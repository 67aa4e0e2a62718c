"""The closed loop on the analytic models: the draft's controller reaches a chosen rest; the episode
says how it ended (refusals are refusals, never successes); engine episodes keep the part's pose."""

import dataclasses

import numpy as np
import pytest

import throwmap as tm
from throwmap.control import Episode, Goal, PaperController, closed_loop
from throwmap.errors import InvalidStateError
from throwmap.system.noise import Noise
from throwmap.records.outcome import Status

PART = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01, length=0.6, mu=1.0)
GOAL = Goal(0.45, 1, 0.01)
CTL = PaperController(GOAL, 4.0, 1.8, approach=((0.28, 4.0),))


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
@pytest.mark.parametrize("start", [(0.15, 0), (0.20, 1), (0.15, 2)])
def test_paper_controller_reaches_the_goal(model, start):
    ep = closed_loop(PART, ARM, CTL, *start, model=model, noise=Noise(omega_rel=0.03), rng=4, max_throws=200)
    assert ep.success and ep.failure is None and ep.stopped and ep.ok and not ep.refused
    assert GOAL.reached(ep.x[-1], ep.side[-1]) and ep.error <= GOAL.eps
    assert len(ep.x) == len(ep.side) == ep.throws + 1 == len(ep.throw_steps()) + 1
    assert ep.steps[-1].action == "stop" and dict(ep.steps[-1].readings)["goal"] is True
    # every throw after the part first rested on the goal side below the goal was a jog: x never fell back
    k = ep.first_on_side
    xs = np.array(ep.x[k:])
    assert ep.side[k] == 1 and np.all(np.diff(xs) > -1e-3)
    # the jog phase ends with low throws, and it switched at least into low and stop
    modes = [s.mode for s in ep.steps if s.switched]
    assert modes[-2:] == ["low", "stop"]


def test_seeded_episodes_repeat_and_jitter_the_rates():
    a = closed_loop(PART, ARM, CTL, 0.15, 0, model="rigid_body", noise=Noise(omega_rel=0.03), rng=7)
    b = closed_loop(PART, ARM, CTL, 0.15, 0, model="rigid_body", noise=Noise(omega_rel=0.03), rng=7)
    assert a.x == b.x and a.steps == b.steps
    th = a.throw_steps()
    assert all(s.omega != s.omega_nominal for s in th) and all(abs(s.omega / s.omega_nominal - 1) < 0.2 for s in th)
    c = closed_loop(PART, ARM, CTL, 0.15, 0, model="rigid_body", rng=7)
    assert all(s.omega == s.omega_nominal for s in c.throw_steps())


def test_max_throws_ends_not_stopped():
    ep = closed_loop(PART, ARM, CTL, 0.15, 0, model="paper", max_throws=3)
    assert (ep.success, ep.failure, ep.throws, ep.stopped) == (False, "not_stopped", 3, False)
    assert ep.steps[-1].action == "cap"


def test_a_refused_throw_is_a_refusal(monkeypatch):
    from throwmap.throws import session as S

    real = S.MapSession.throw

    def refusing(self, *args, **kw):  # the model refuses the throw it made
        step = real(self, *args, **kw)
        self.status = Status.UNRESOLVED
        return dataclasses.replace(step, status=Status.UNRESOLVED,
                                   outcomes=(step.outcome.replace(status=Status.UNRESOLVED),))

    monkeypatch.setattr(S.MapSession, "throw", refusing)
    ep = closed_loop(PART, ARM, CTL, 0.15, 0, model="paper")
    assert (ep.success, ep.failure, ep.refused, ep.status, ep.throws) == (False, "refused:unresolved", True,
                                                                         "unresolved", 1)


def test_leaving_the_arm_is_its_own_failure():
    short = tm.Arm(h=-0.01, length=0.36, mu=1.0)  # side 0 jogs past the end before it flips
    ctl = PaperController(Goal(0.2, 2, 0.005), 4.0, 1.8)
    ep = closed_loop(PART, short, ctl, 0.2, 0, model="paper")
    assert ep.failure == "off_end" and not ep.success


def test_a_stop_outside_the_goal_fails():
    # a goal sensor that almost always reads 1 stops the loop where the part lies
    ctl = PaperController(GOAL, 4.0, 1.8, false_positive=0.999999, overshoot=False)
    ep = closed_loop(PART, ARM, ctl, 0.2, 1, model="paper", rng=1)
    assert ep.stopped and not ep.success and ep.failure in ("stopped_off_goal", "stopped_wrong_side")
    ep = closed_loop(PART, ARM, ctl, 0.2, 0, model="paper", rng=1)
    assert ep.failure == "stopped_wrong_side"


def test_confirmation_costs_looks_not_throws():
    ctl = dataclasses.replace(CTL, confirm=2)
    ep = closed_loop(PART, ARM, ctl, 0.20, 1, model="paper", rng=2)
    plain = closed_loop(PART, ARM, CTL, 0.20, 1, model="paper", rng=2)
    assert ep.success and ep.looks >= ep.switches - 1 >= 1 and ep.throws == plain.throws


def test_episode_is_frozen_and_bad_inputs_are_named():
    ep = closed_loop(PART, ARM, CTL, 0.3, 1, model="paper", max_throws=2)
    assert isinstance(ep, Episode)
    with pytest.raises(dataclasses.FrozenInstanceError):
        ep.success = True
    with pytest.raises(InvalidStateError) as err:
        closed_loop(PART, ARM, CTL, 0.3, 1, model="paper", max_throws=-1)
    assert err.value.field == "max_throws"
    with pytest.raises(InvalidStateError) as err:
        closed_loop(PART, ARM, object(), 0.3, 1, model="paper")
    assert err.value.field == "controller"
    with pytest.raises(InvalidStateError):
        closed_loop(PART, ARM, CTL, -0.3, 1, model="paper")


def test_inverse_controller_in_the_loop():
    pytest.importorskip("throwmap.control.inverse")
    from throwmap.control import InverseJogController, PositionSensor

    ctl = InverseJogController(GOAL, PART, ARM, 4.0, 0.5, 3.0, PositionSensor(0.0005), gain=1.0)
    ep = closed_loop(PART, ARM, ctl, 0.435, 1, model="rigid_body", rng=3)
    assert ep.success and ep.throws <= 2  # the model is the plant: one jog, maybe a correction
    assert ep.throw_steps()[0].mode == "jog" and abs(ep.x[1] - GOAL.x) < 2e-3
    far = closed_loop(PART, ARM, ctl, 0.30, 1, model="rigid_body", rng=3)  # beyond one jog's reach at ω ≤ 3
    assert far.success and far.throw_steps()[0].mode == "jog_max"


@pytest.mark.slow
def test_engine_episode_from_a_dropped_part_keeps_its_pose():
    from throwmap.experiments.drop import drop_part

    noise = Noise(omega_rel=0.03, realisation="recoil")
    ctl = PaperController(Goal(0.48, 1, 0.01), 5.0, 1.8, approach=((0.20, 4.5), (0.43, 3.0)))
    drop = drop_part(PART, ARM, np.random.default_rng(3), x_range=(0.18, 0.30))
    ep = closed_loop(PART, ARM, ctl, drop, model="engine", noise=noise, rng=3)
    assert ep.success or ep.failure.startswith("refused:")
    assert ep.x[0] == pytest.approx(drop.x) and ep.side[0] == drop.side
    # analytic models start a dropped part flat at its nearest rest
    ep2 = closed_loop(PART, ARM, CTL, drop, model="paper", rng=3)
    assert ep2.x[0] == pytest.approx(drop.x)
