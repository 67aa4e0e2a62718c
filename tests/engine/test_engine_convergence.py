"""The engine refuses results that change at half the step (issue 10, item 1: wrong but ok).

Hard runs (deep penetration, repeated side changes, an energy gain, a timeout)
are rerun at half the step; disagreement is status ``unconverged``, never ok.
"""

import math
import warnings

import pytest

from throwmap import Arm
from throwmap.errors import InvalidStateError
from throwmap.engine import EngineSettings, engine_run
from throwmap.engine.pymunk.verify import flags
from throwmap.system.catalogue import triangle_30_60_90
from throwmap.system.part import Part
from throwmap.records.outcome import Status

TRI = triangle_30_60_90()
# a random pentagon from the hardening scan: at dt it lands on side 4 at x = 0.409 m, at dt/2 on side 2 at 0.200 m
PENTAGON = Part.from_vertices(
    [[0.0557816533320038, 0.05863777315793444], [0.013498808473898494, 0.0848575383186746],
     [-0.05377264934738383, 0.031106810375842123], [-0.07046402107313159, -0.03239532968598235],
     [0.036419334849918245, -0.011701312312762599]], mass=0.05)
HARD = (Arm(h=-0.022415830239647192, mu=1.0), 0.41945388688674945, 2, 6.622077224502996)


def _run(part, arm, x, side, omega, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return engine_run(part, arm, x, side, omega, **kw)


def test_a_step_dependent_landing_is_refused_as_unconverged():
    arm, x, side, omega = HARD
    run = _run(PENTAGON, arm, x, side, omega)
    assert run.status == Status.UNCONVERGED
    assert "half-step rerun" in run.message and "side" in run.message
    unchecked = _run(PENTAGON, arm, x, side, omega, settings=EngineSettings(verify=False))
    assert unchecked.status == Status.OK  # what the engine used to report


def test_the_two_steps_really_disagree():
    """Independent of the flagging: the run at dt and at dt/2 land on different sides."""
    arm, x, side, omega = HARD
    a = _run(PENTAGON, arm, x, side, omega, settings=EngineSettings(verify=False))
    b = _run(PENTAGON, arm, x, side, omega, settings=EngineSettings(verify=False, dt=6.25e-5))
    assert a.states[0][1] != b.states[0][1]


def test_an_easy_throw_is_not_rerun():
    """Only flagged runs pay for a rerun: a soft landing has no flags and is returned as it is."""
    run = _run(TRI, Arm(h=-0.01, mu=1.5), 0.3, 0, 4.0)
    assert run.status == Status.OK and not run.verified and flags(run, EngineSettings()) == []


@pytest.mark.parametrize("mu", [1.5, math.inf])
def test_a_flagged_throw_that_holds_is_ok_and_verified(mu):
    settings = EngineSettings(penetration_tol=1e-4)  # every landing is then "deep": flagged
    run = _run(TRI, Arm(h=-0.01, mu=mu), 0.45, 2, 6.0, settings=settings)
    assert run.status == Status.OK and run.verified


def test_refine_halves_on_until_two_steps_agree_or_refuses():
    """With ``refine`` the step is halved on after the disagreement: the result stands only where two successive
    steps agree (and is marked verified, the step named in its message), and equals a run made at that step."""
    from dataclasses import replace

    arm, x, side, omega = HARD
    run = _run(PENTAGON, arm, x, side, omega, settings=EngineSettings(refine=3))
    if run.status == Status.UNCONVERGED:
        assert "half-step rerun" in run.message
        return
    assert run.verified and "converged at dt = " in run.message
    dt = float(run.message.split("converged at dt = ")[1].split(" s")[0])
    assert dt < EngineSettings().dt / 2
    s = EngineSettings()
    direct = _run(PENTAGON, arm, x, side, omega,
                  settings=replace(s, dt=dt, coarse_dt=max(s.coarse_dt * dt / s.dt, dt), verify=False))
    assert (direct.status, direct.states[0][1]) == (run.status, run.states[0][1])
    assert abs(direct.states[0][0] - run.states[0][0]) <= s.agreement


def test_refine_is_a_count():
    with pytest.raises(InvalidStateError, match=r"^settings.refine: must be an integer ≥ 0"):
        EngineSettings(refine=-1)
