"""Two-part runs: rest by confinement (a solver limit cycle is not a timeout) and a blow-up refused."""

import math

import pytest

from throwmap import Arm
from throwmap.engine import EngineSettings, Friction, ImpulseThrow, Placement, RecoilThrow, Scene, simulate
from throwmap.engine.pymunk import run as R
from throwmap.system.catalogue import triangle_30_60_90
from throwmap.system.fixtures import Wall

TRI = triangle_30_60_90(0.17)


def test_moved_window():
    ref = [(0.1, 0.02, 1.0), None]
    assert not R._moved(ref, [(0.1 + 0.0004, 0.02, 1.0 + 0.004), None])
    assert R._moved(ref, [(0.1 + 0.0006, 0.02, 1.0), None])
    assert R._moved(ref, [(0.1, 0.02, 1.0 + 0.006), None])
    assert R._moved(ref, [(0.1, 0.02, 1.0), (0.2, 0.0, 0.0)])  # a part came back: not the same window


@pytest.mark.slow
def test_rocking_pair_rests_by_confinement():
    """Two triangles against a frictionless wall (self-assembly, low phase) that Chipmunk keeps rocking by ±1 mrad
    for the whole 10 s limit: at rest once every part stayed within 0.5 mm and 5 mrad for 1 s."""
    arm = Arm(h=-0.01, length=0.5, mu=0.9369932075421221)
    scene = Scene(arm, (Placement(TRI, pose=(0.4386355346525391, 0.08951287085299166, 5.220315128913962)),
                        Placement(TRI, pose=(0.36168955158443394, 0.03907167040626191, 7.854089942860744))),
                  (Wall(0.8, mu=0.0),), friction=Friction(part_part=0.5))
    settings = EngineSettings(exact_flight=False, penetration_tol=0.002, retries=2, verify=False)
    run = simulate(scene, RecoilThrow(omega_n=144.2202304137244, recoil=0.05235987755982989, zeta=0.5), settings)
    assert int(run.status) == 0 and "confinement" in run.message
    assert run.t_end < 3.0
    # where it rests: the first part leaning on the wall, the second standing (as at the 10 s limit before)
    assert run.poses[0][0] == pytest.approx(0.4754, abs=1e-3) and run.poses[1][0] == pytest.approx(0.3824, abs=1e-3)


def test_one_part_never_rests_by_confinement():
    """One part settles by the speeds only (its runs are unchanged): a long slide is not cut short."""
    arm = Arm(h=-0.01, length=1.0, mu=0.3)
    run = simulate(Scene(arm, (Placement(TRI, x=0.3, side=0),)), ImpulseThrow(4.0))
    assert int(run.status) == 0 and "confinement" not in run.message


def test_blow_up_refused_when_the_rerun_blows_up_too(monkeypatch):
    monkeypatch.setattr(R, "BLOWUP_RISE", -1.0)  # every run "blows up"
    arm = Arm(h=-0.01, length=1.0, mu=0.8)
    run = simulate(Scene(arm, (Placement(TRI, x=0.3, side=0),)), ImpulseThrow(4.0), EngineSettings(verify=False))
    assert run.status.label == "unconverged" and "a blow-up" in run.message and "result refused" in run.message
    run = simulate(Scene(arm, (Placement(TRI, x=0.3, side=0),)), ImpulseThrow(4.0), EngineSettings(verify=True))
    assert int(run.status) == 0  # with the half-step rerun on, its own energy check applies instead
    assert math.isfinite(run.energy_gain)
