"""Controllers' switching logic on scripted readings (no physics)."""

import math
from types import SimpleNamespace

import pytest

import throwmap.control.controllers as C
from throwmap.control import ControlState, FunnelController, Goal, InverseJogController, PaperController
from throwmap.errors import InvalidStateError

GOAL = Goal(0.45, 1, 0.01)


def obs(side, goal=False, beyond=False, **approach):
    return {"side": side, "goal": goal, "beyond": beyond, **approach}


def run(ctl, readings):
    """Feed a script of readings; the decisions' (action, mode, ω)."""
    state, out = ctl.initial(), []
    for r in readings:
        d = ctl.decide(state, r)
        state = d.state
        out.append((d.action, d.mode, None if math.isnan(d.omega) else d.omega))
    return out


def test_paper_controller_high_until_side_then_low_until_goal():
    c = PaperController(GOAL, 4.0, 1.8)
    got = run(c, [obs(False), obs(False), obs(True), obs(True), obs(True, goal=True)])
    assert got == [("throw", "high", 4.0), ("throw", "high", 4.0), ("throw", "low", 1.8), ("throw", "low", 1.8),
                   ("stop", "stop", None)]


def test_paper_controller_back_to_high_after_overshoot_or_lost_side():
    c = PaperController(GOAL, 4.0, 1.8)
    got = run(c, [obs(True), obs(True, beyond=True), obs(True), obs(False), obs(True)])
    assert [g[1] for g in got] == ["low", "high", "low", "high", "low"]
    s = c.initial()
    d1 = c.decide(s, obs(True))
    d2 = c.decide(d1.state, obs(True, beyond=True))
    assert d1.switched and d2.switched and "overshoot" in d2.reason


def test_paper_controller_without_overshoot_sensor_keeps_jogging():
    c = PaperController(GOAL, 4.0, 1.8, overshoot=False)
    assert "beyond" not in c.sensors()
    assert run(c, [{"side": True, "goal": False}])[0][1] == "low"


def test_approach_rungs_in_order():
    c = PaperController(GOAL, 5.0, 1.8, approach=((0.2, 4.5), (0.43, 3.0)))
    assert set(c.sensors()) == {"side", "goal", "beyond", "approach0", "approach1"}
    got = run(c, [obs(True, approach0=False, approach1=False), obs(True, approach0=True, approach1=False),
                  obs(True, approach0=True, approach1=True)])
    assert got == [("throw", "approach0", 4.5), ("throw", "approach1", 3.0), ("throw", "low", 1.8)]
    assert c.sensors()["approach1"].x == 0.43


def test_confirm_asks_for_looks_before_a_switch():
    c = PaperController(GOAL, 4.0, 1.8, confirm=3)
    # the first high needs no confirmation; the switch to low needs 3 readings in a row; a reading to stay
    # in the middle of a test does not throw (the test goes on), 3 in a row end it
    got = run(c, [obs(False), obs(True), obs(True), obs(True), obs(True, goal=True), obs(True), obs(True, goal=True),
                  obs(True, goal=True), obs(True, goal=True)])
    assert [g[0] for g in got] == ["throw", "look", "look", "throw", "look", "look", "look", "look", "stop"]
    assert got[3][1] == "low"
    got = run(c, [obs(True)] * 3 + [obs(True, goal=True)] + [obs(True)] * 3)
    assert [g[0] for g in got] == ["look", "look", "throw", "look", "look", "look", "throw"] and got[-1][1] == "low"


def test_a_single_false_reading_does_not_switch_with_confirm():
    c = PaperController(GOAL, 4.0, 1.8, confirm=2)
    got = run(c, [obs(False), obs(True), obs(False), obs(False)])  # side flickers on once
    assert [g[0] for g in got] == ["throw", "look", "look", "throw"] and got[3][1] == "high"


@pytest.mark.parametrize("kw, field", [
    (dict(omega_high=0.0), "controller.omega_high"),
    (dict(omega_low=math.nan), "controller.omega_low"),
    (dict(approach=((0.3, 2.0), (0.2, 2.0))), "controller.approach"),
    (dict(approach=((0.3,),)), "controller.approach[0]"),
    (dict(confirm=0), "controller.confirm"),
    (dict(false_positive=2.0), "sensor.false_positive"),
    (dict(hysteresis=-1.0), "sensor.hysteresis"),
])
def test_paper_controller_validation(kw, field):
    args = dict(goal=GOAL, omega_high=4.0, omega_low=1.8) | kw
    with pytest.raises(InvalidStateError) as err:
        PaperController(**args)
    assert err.value.field == field


@pytest.mark.parametrize("kw, field", [(dict(x=math.inf), "goal.x"), (dict(side=-1), "goal.side"),
                                       (dict(eps=0.0), "goal.eps")])
def test_goal_validation(kw, field):
    with pytest.raises(InvalidStateError) as err:
        Goal(**(dict(x=0.4, side=0, eps=0.01) | kw))
    assert err.value.field == field


def _inverse(monkeypatch, rate):
    calls = []

    def fake(part, arm, x0, side, target, model="rigid_body", **kw):
        calls.append((x0, side, target, model, kw.get("omega_max")))
        if rate is None:
            raise InvalidStateError("x_target", "no jog reaches it")
        return rate

    monkeypatch.setattr(C, "_jog_rate", fake)
    return InverseJogController(GOAL, object(), object(), 5.0, 0.5, 3.0, gain=0.5), calls


def test_inverse_controller_jogs_towards_the_goal(monkeypatch):
    c, calls = _inverse(monkeypatch, 2.0)
    d = c.decide(ControlState(), {"position": (0.35, 1)})
    assert (d.action, d.mode, d.omega) == ("throw", "jog", 2.0)
    assert calls == [(0.35, 1, pytest.approx(0.40), "rigid_body", 3.0)]  # aims half-way (gain 0.5)


@pytest.mark.parametrize("rate, mode, omega", [(9.0, "jog_max", 3.0), (0.1, "jog_min", 0.5), (None, "jog_max", 3.0)])
def test_inverse_controller_clips(monkeypatch, rate, mode, omega):
    c, _ = _inverse(monkeypatch, rate)
    d = c.decide(ControlState(), {"position": (0.35, 1)})
    assert (d.mode, d.omega) == (mode, omega)


def test_inverse_controller_high_off_side_or_past_goal_and_stops_in_goal(monkeypatch):
    c, calls = _inverse(monkeypatch, 2.0)
    assert c.decide(ControlState(), {"position": (0.30, 0)}).mode == "high"
    assert c.decide(ControlState(), {"position": (0.47, 1)}).mode == "high"
    assert c.decide(ControlState(), {"position": (0.455, 1)}).action == "stop"
    assert calls == []
    # jog, jog_max … are one mode: changing the rate is not a switch
    s = c.decide(ControlState(), {"position": (0.35, 1)}).state
    assert not c.decide(s, {"position": (0.36, 1)}).switched


def test_inverse_controller_validation():
    with pytest.raises(InvalidStateError) as err:
        InverseJogController(GOAL, None, None, 5.0, 3.5, 3.0)
    assert err.value.field == "controller.omega_min"
    with pytest.raises(InvalidStateError) as err:
        InverseJogController(GOAL, None, None, 5.0, 0.5, 3.0, gain=0.0)
    assert err.value.field == "controller.gain"


class _Mouth:
    def __init__(self, lo, hi, side):
        self.lo, self.hi, self.side = lo, hi, side

    def contains(self, x, side):
        return side == self.side and self.lo <= x <= self.hi


def _graph():
    f0 = SimpleNamespace(name="slow", omegas=(1.5,), mouth=_Mouth(0.3, 0.44, 1))
    f1 = SimpleNamespace(name="pair", omegas=(4.0, 2.0), mouth=_Mouth(0.0, 1.0, 0))
    return SimpleNamespace(order=(0, 1), funnels=(f0, f1))


def test_funnel_controller_follows_the_graph_and_composed_sequences():
    c = FunnelController(GOAL, _graph(), 5.0)
    s = c.initial()
    d = c.decide(s, {"position": (0.35, 1)})
    assert (d.action, d.mode, d.omega) == ("throw", "funnel0", 1.5)
    d = c.decide(d.state, {"position": (0.2, 0)})
    assert (d.mode, d.omega, d.state.queue) == ("funnel1", 4.0, (2.0,))
    d = c.decide(d.state, {"position": (0.25, 0)})  # the rest of the composed throw
    assert (d.mode, d.omega, d.state.queue) == ("funnel1", 2.0, ())
    assert c.decide(d.state, {"position": (0.2, 2)}).mode == "fallback"
    assert c.decide(d.state, {"position": (0.452, 1)}).action == "stop"


def test_funnel_controller_needs_a_graph():
    with pytest.raises(InvalidStateError) as err:
        FunnelController(GOAL, object(), 5.0)
    assert err.value.field == "controller.graph"


def test_kick_rungs_replace_high_off_the_goal_side():
    c = PaperController(GOAL, 5.0, 1.8, kick=((0.13, 6.0),))
    assert c.sensors()["kick0"].x == 0.13
    got = run(c, [obs(False, kick0=False), obs(False, kick0=True), obs(True, kick0=False)])
    assert got == [("throw", "kick0", 6.0), ("throw", "high", 5.0), ("throw", "low", 1.8)]
    with pytest.raises(InvalidStateError) as err:
        PaperController(GOAL, 5.0, 1.8, kick=((0.13, -1.0),))
    assert err.value.field == "controller.kick[0]"


def test_inverse_controller_stops_inside_a_margin(monkeypatch):
    monkeypatch.setattr(C, "_jog_rate", lambda *a, **k: 1.0)
    c = InverseJogController(GOAL, None, None, 5.0, 0.5, 3.0, margin=0.004)
    assert c.decide(ControlState(), {"position": (0.457, 1)}).mode == "high"  # past the stop band: an overshoot
    assert c.decide(ControlState(), {"position": (0.443, 1)}).mode == "jog"
    assert c.decide(ControlState(), {"position": (0.455, 1)}).action == "stop"
    with pytest.raises(InvalidStateError) as err:
        InverseJogController(GOAL, None, None, 5.0, 0.5, 3.0, margin=0.01)
    assert err.value.field == "controller.margin"


def test_inverse_controller_kicks_near_the_joint(monkeypatch):
    monkeypatch.setattr(C, "_jog_rate", lambda *a, **k: 1.0)
    c = InverseJogController(GOAL, None, None, 5.0, 0.5, 3.0, kick=((0.13, 6.0),))
    assert (c.decide(ControlState(), {"position": (0.12, 0)}).mode, c.decide(ControlState(), {"position": (0.12, 0)}).omega) == ("kick0", 6.0)
    assert c.decide(ControlState(), {"position": (0.14, 0)}).mode == "high"
    assert c.decide(ControlState(), {"position": (0.12, 1)}).mode == "jog"
