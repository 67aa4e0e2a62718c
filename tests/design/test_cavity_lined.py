"""A lined pocket (:attr:`throwmap.system.fixtures.Cavity.lined`): the recoil feeder's pocket floor faced with the end
wall's low-friction material (μ 0.2), so a part left leaning on the end wall slides flat (issue 11, the feeder on the
exact engine).

With the arm's μ = 1 ± 10 % on the floor a lean of the triangle on the wall (vertex 0 on the wall, vertex 1 on the
floor, side 0 tilted 0.50–0.87 rad as the hold throws left it) rests whenever μ ≥ (x_CM − x_floor vertex)/(wall
contact height) = 0.45–1.11, and the next throw flips it out of the pocket. Lined, the statics (LP) has no rest for
those leans, and the engine lets the part slide down flat.
"""

import math
import warnings

import numpy as np
import pytest

import throwmap as tm
from throwmap.statics.rest import Body, Contact, analyse_rest
from throwmap.system.arm import Arm
from throwmap.system.fixtures import Cavity, Wall, fixture_from_dict, fixture_to_dict
from throwmap.system.part import Part

PART = Part(vertices=((0.14722431864335458, 0.0), (0.0, 0.085), (0.0, 0.0)), mass=0.12728127396271163,
            com=(0.037125249452450236, 0.04010804106650658), radius_of_gyration=0.027617919039357206,
            point_masses=((0.08, (0.030062890815516597, 0.04706708084354437)),), name="recoil feeder")
H, L, DEPTH, WALL_H = -0.02042023480254783, 0.38, 0.01, 0.15376261062739635
PROFILE = ((0.18077350269189627, 0.0), (0.17500000000000002, -0.01), (0.0, -0.01))
FLOOR_Y = H - DEPTH
LEAN = (0.3225128460757078, 0.044320252670049264, 4.1831278400448735)  # feed seed 0 trial 0, throw 12 (tilt 0.518)
BETA0 = float(PART.beta[0])


def test_lined_round_trips_and_unlined_dict_is_unchanged():
    c = Cavity(PROFILE, lined=True)
    assert fixture_from_dict(fixture_to_dict(c)) == c
    assert "lined" not in fixture_to_dict(Cavity(PROFILE))
    assert fixture_from_dict(fixture_to_dict(Cavity(PROFILE))) == Cavity(PROFILE)
    with pytest.raises(tm.errors.InvalidStateError):
        Cavity(PROFILE, lined="yes")


def test_only_the_floor_gets_the_fixture_friction():
    from throwmap.engine.pymunk.world import _static_geometry

    wall = Wall(WALL_H, 0.01, 0.2)
    lined = _static_geometry(H, L, 0.02, (Cavity(PROFILE, lined=True), wall), 0.0)
    plain = _static_geometry(H, L, 0.02, (Cavity(PROFILE), wall), 0.0)
    assert [p for p, _ in lined[0]] == [p for p, _ in plain[0]] and lined[1:] == plain[1:]
    assert [f for _, f in plain[0]] == [False, False, False, True]  # surface, lip ramp, floor; the wall
    assert [f for _, f in lined[0]] == [False, False, True, True]  # the floor now has the wall's μ


def _lean(phi, mu_floor, mu_wall):
    """Vertex 0 on the wall face x = L, vertex 1 on the pocket's floor, the part turned to ``phi``."""
    c, s = math.cos(phi), math.sin(phi)
    V = np.asarray(PART.w) @ np.array([[c, -s], [s, c]]).T
    cm = np.array([L - (V[0][0] - V[1][0]), FLOOR_Y]) - V[1]
    Vw = V + cm
    cons = (Contact(0, None, tuple(Vw[0]), (-1.0, 0.0), mu_wall, "wall"),
            Contact(0, None, tuple(Vw[1]), (0.0, 1.0), mu_floor, "arm"))
    return Body(PART, float(cm[0]), float(cm[1]), phi), cons


def test_the_leans_of_the_feed_runs_cannot_rest_on_the_lined_floor():
    body, cons = _lean(LEAN[2], 1.09, 0.0)
    # the pose the engine held (its contacts a collision slop deep)
    assert body.x == pytest.approx(LEAN[0], abs=1e-4) and body.y == pytest.approx(LEAN[1], abs=1e-4)
    unlined = analyse_rest([body], cons)
    assert unlined.can_rest and unlined.mu_needed == pytest.approx(1.072, abs=0.002)  # feedfix's statics
    for tilt in np.linspace(0.45, 0.95, 11):  # every lean the exact engine held (0.50–0.87 rad), and beyond
        body, cons = _lean(BETA0 + tilt, 0.2, 0.2)
        assert not analyse_rest([body], cons, detail=False).can_rest, tilt
        body, cons = _lean(BETA0 + tilt, 1.3, 0.0)  # unlined, at the arm's μ + 3σ: every one of them rests
        assert analyse_rest([body], cons, detail=False).can_rest, tilt
    # lined, only leans steeper than 1.12 rad (the wall contact 15.3 cm or more above the floor, at the wall's top)
    body, cons = _lean(BETA0 + 1.10, 0.2, 0.2)
    assert not analyse_rest([body], cons, detail=False).can_rest
    body, cons = _lean(BETA0 + 1.15, 0.2, 0.2)
    assert analyse_rest([body], cons, detail=False).can_rest


def test_a_part_released_leaning_slides_flat_on_the_lined_floor():
    """The lean that the exact engine holds at μ = 1.09 on the unlined pocket (tests/engine/test_high_friction.py):
    lined, at arm μ 1.3, it slides down flat against the wall."""
    from throwmap.engine import ImpulseThrow, simulate
    from throwmap.engine.scene import Placement, Scene

    arm = Arm(h=H, length=L, mu=1.3)
    scene = Scene(arm, (Placement(PART, pose=LEAN),), (Cavity(PROFILE, lined=True), Wall(WALL_H, 0.01, 0.2)))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = simulate(scene, ImpulseThrow(0.0), tm.engine.EngineSettings(agreement=0.005, retries=4))
    assert run.statuses[0].name == "OK" and run.states[0][1] == 0 and abs(run.states[0][2]) < 0.01
