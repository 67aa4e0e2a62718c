"""The cavity design (paper Sec. V-C): its checks pass for the feeder design and fail, by name, for a
cavity that is too shallow (the part is thrown out) or too narrow (the part cannot enter); the
energy bound on the wall holds in the engine.

The designs use the impulse arm (the window from the exact model, about a second); the engine
checks throw the part a few times each.
"""

import dataclasses
import math

import numpy as np
import pytest

from throwmap import Arm
from throwmap.design.cavity import Pocket, design_cavity, evaluate_cavity, jog_map, outward_sweep
from throwmap.design.examples import feeder_design
from throwmap.errors import InvalidStateError
from throwmap.system.noise import Noise
from throwmap.system.fixtures import Cavity, Wall

ANALYTIC = ("window", "hold", "release_1", "release_2", "fits", "wall_energy")


@pytest.fixture(scope="module")
def feeder():
    fd = feeder_design()
    return fd, design_cavity(fd.part, Arm(h=fd.arm.h, mu=1.0), fd.omega, fd.target_side, verify=True)


@pytest.mark.slow
def test_feeder_cavity_checks_pass(feeder):
    fd, d = feeder
    for name in ANALYTIC + ("engine_capture",):
        assert d.check(name).passed, str(d.check(name))
    # the hold at ω_hi: on the exact engine (true μ) the unlined pocket's hold throw leaves side 0 leaning on the end
    # wall after 1 of 3 throws (a lean rests at μ ≥ 0.45); with the floor and wall lined (μ 0.2,
    # tests/design/test_cavity_lined.py) it is held through all 3
    lined = design_cavity(fd.part, Arm(h=fd.arm.h, mu=1.0), fd.omega, fd.target_side,
                          pocket=Pocket(wall_mu=0.2, lined=True))
    assert lined.cavity.lined and lined.check("engine_hold").passed, str(lined.check("engine_hold"))
    for key in ("L_lo_m", "L_hi_m"):  # the window from the jog map on the lined floor (μ 0.2) is the same
        assert lined.numbers[key] == d.numbers[key]
    n = d.numbers
    assert n["L_lo_m"] < d.length < n["L_hi_m"]
    assert d.lip_x == pytest.approx(d.length - d.cavity.span)
    assert n["floor_m"] >= fd.part.length[0]
    # the captured pose from the engine is flat on side 0 inside the cavity, near the end wall
    assert d.captured_pose is not None and d.where(d.captured_pose) == "target"
    assert d.length - 0.01 < d.captured_pose[0] + fd.part.uR[0] <= d.length + 1e-4
    doc = d.to_dict()
    assert {c["name"] for c in doc["checks"]} >= set(ANALYTIC) and doc["cavity_profile_m"][-1][0] == 0.0


@pytest.mark.slow
def test_window_agrees_with_the_jog_map(feeder):
    # independent: the throw at ω_hi from side 0 against the wall is a jog, side 1's and 2's are flips
    fd, d = feeder
    jm = jog_map(fd.part, Arm(h=d.floor_y, mu=1.0), (d.numbers["omega_hi"],), step=0.0025,
                 x_lo=0.15, x_hi=0.35)
    for side, want in ((0, True), (1, False), (2, False)):
        x = d.length - fd.part.uR[side]
        i = int(np.argmin(np.abs(jm.x - x)))
        assert bool(jm.jog[0, jm.sides.index(side), i]) is want


@pytest.mark.slow
def test_too_shallow_is_ejected(feeder):
    _, d = feeder
    shallow = dataclasses.replace(d, cavity=Cavity(((0.19, 0.0), (0.185, -0.004), (0.0, -0.004))),
                                  wall=Wall(height=0.015, mu=0.0))
    e = evaluate_cavity(shallow, verify=True)
    assert not e.success
    assert not e.check("wall_energy").passed
    assert not e.check("engine_hold").passed  # thrown over the low wall
    assert "wall_energy" in e.message and "engine_hold" in e.message


@pytest.mark.slow
def test_too_narrow_cannot_enter(feeder):
    fd, d = feeder
    narrow = dataclasses.replace(d, cavity=Cavity(((0.10, 0.0), (0.09, -0.02), (0.0, -0.02))))
    e = evaluate_cavity(narrow, verify=True)
    assert not e.check("fits").passed and e.check("fits").value < 0
    assert not e.check("engine_capture").passed
    assert not e.check("engine_hold").passed  # side 0 cannot lie on a floor shorter than itself


@pytest.mark.slow
def test_energy_bound_holds_in_the_engine(feeder):
    # the CM of a part thrown from rest on the floor never rises more than ω²(x² + y²)/2g
    from throwmap.engine import ImpulseThrow, Placement, Scene, simulate
    from throwmap.system.pose import pose_at_rest

    fd, d = feeder
    part, w = fd.part, d.numbers["omega_hi"]
    x = d.length - part.uR[0]
    pose = pose_at_rest(part, d.floor_y, x, 0)
    tall = Wall(height=0.5, mu=0.0)
    run = simulate(Scene(d.arm, (Placement(part, pose=pose),), (d.cavity, tall)), ImpulseThrow(w), record=True)
    rise = run.trajectory.poses[:, 0, 1].max() - pose[1]
    bound = w**2 * (x**2 + pose[1] ** 2) / (2 * d.arm.g)
    assert 0 < rise <= bound + 1e-4


def test_outward_sweep_is_zero_without_turning_and_grows_with_omega():
    part = feeder_design().part
    assert outward_sweep(part, 0, 0.25, 0.004, 0.0, 9.81) == 0.0
    s = [outward_sweep(part, 0, 0.25, 0.004, w, 9.81) for w in (1.0, 3.0, 5.0)]
    assert s[0] <= s[1] <= s[2] and s[2] < math.hypot(part.uR[0], part.d[0]) - part.uR[0] + 1e-9


def test_bad_inputs_name_the_field():
    fd = feeder_design()
    arm = Arm(h=fd.arm.h)
    with pytest.raises(InvalidStateError, match="depth"):
        design_cavity(fd.part, arm, fd.omega, 0, pocket=Pocket(depth=-0.01))
    with pytest.raises(InvalidStateError, match="realisation"):
        design_cavity(fd.part, arm, fd.omega, 0, noise=Noise(realisation="catapult"))
    with pytest.raises(InvalidStateError, match="end_gap"):
        design_cavity(fd.part, arm, fd.omega, 0, pocket=Pocket(end_gap=0.5))
    with pytest.raises(InvalidStateError, match="pocket"):
        design_cavity(fd.part, arm, fd.omega, 0, pocket={"depth": 0.01})


def test_check_text_says_one_throw_and_given_length():
    from throwmap.design.cavity import Check

    assert "1 throw (" in str(Check("engine_capture", True, 1.0, "x", unit="throws"))
    assert "2 throws (" in str(Check("engine_capture", True, 2.0, "x", unit="throws"))
    assert "0 throws (" in str(Check("engine_capture", True, 0.0, "x", unit="throws"))
