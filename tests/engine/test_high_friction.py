"""The engine's exact contact solve at high friction (:mod:`throwmap.engine.pymunk.exact`, issue 11 item 2).

Where Chipmunk's solver would need the friction cap (μ |K_nt| > 0.7 K_nn at a contact), one part's step is solved
exactly with the pair's true μ instead: a pivot at μ = 2 slips when and as fast as Coulomb says, and a μ = ∞ pivot
sticks. Runs where the cap never binds, and runs of several parts, are unchanged bit for bit.
"""

from __future__ import annotations

import importlib.util
import math
import warnings
from pathlib import Path

import pytest

import throwmap as tm
from throwmap.engine import ImpulseThrow, simulate
from throwmap.engine.pymunk import exact as X
from throwmap.engine.pymunk import friction as F
from throwmap.engine.scene import Placement, Scene
from throwmap.studies.tilt_wall import default_parts
from throwmap.system.pose import world_vertices

PARTS = default_parts()


def _quiet(fn, *a, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fn(*a, **kw)


# ----------------------------------------------------------------------------------------------- one contact
def test_one_contact_stick_slide_separate_and_skid():
    ann, ant, att = 3.0, -1.5, 2.0  # a vertex whose normal and tangential rows are coupled (|K_nt|/K_nn = 0.5)
    jn, jt, mode = X.solve_contact(-1.0, 0.2, ann, ant, att, 1.0)  # sticks: both velocities stopped, inside the cone
    assert mode == 1 and jn > 0 and abs(jt) <= jn
    assert ann * jn + ant * jt - 1.0 == pytest.approx(0.0, abs=1e-12)
    assert ant * jn + att * jt + 0.2 == pytest.approx(0.0, abs=1e-12)
    assert X.solve_contact(0.3, 5.0, ann, ant, att, 1.0)[2] == 0  # moving away: no impulse
    for mu in (0.3, 2.5):  # slides: v_n = 0, |j_t| = μ j_n, friction against the slip (μ |K_nt| / K_nn > 1 too)
        jn, jt, mode = X.solve_contact(-0.1, 4.0, ann, ant, att, mu)
        vt = 4.0 + ant * jn + att * jt
        assert mode == 2 and jn > 0 and jt == pytest.approx(-mu * jn) and vt > 0
        assert -0.1 + ann * jn + ant * jt == pytest.approx(0.0, abs=1e-12)
    jn, jt, mode = X.solve_contact(-1.0, 10.0, ann, ant, att, math.inf)  # μ = ∞ that cannot stick pushing: skids
    assert mode == 2 and 0 < jn < 1e-5 and abs(jt) == pytest.approx(X.MU_SKID * jn)


# ----------------------------------------------------------------------------------------------- unchanged runs
def _run(scene, omega, exact, monkeypatch):
    monkeypatch.setattr(F, "EXACT", exact)
    return _quiet(simulate, scene, ImpulseThrow(omega))


@pytest.mark.parametrize("name, mu, alpha_deg, wall, k, x, omega", [
    ("triangle+lead", 0.71, 9.83, True, 0, 0.15, 4.5),  # (the hook is installed in each: μ above the part's bound)
    ("triangle", 0.75, 0.33, False, 2, 0.18, 5.0),
    ("rectangle+lead", 0.9, -5.0, True, 0, 0.15, 4.0),
    ("triangle", 1.0, -8.0, True, 1, 0.16, 4.0),
])
def test_runs_where_the_cap_never_binds_are_unchanged(name, mu, alpha_deg, wall, k, x, omega, monkeypatch):
    from throwmap.engine import EngineSettings
    from throwmap.engine.pymunk.world import build_world

    part = PARTS[name]
    fx = (tm.Wall(0.27, mu=0.0),) if wall else ()
    scene = Scene(tm.Arm(h=-0.01, mu=mu, length=0.3), (Placement(part, x=x, side=k),), fx, math.radians(alpha_deg))
    hook = F.install_friction_cap(build_world(scene, ImpulseThrow(omega), EngineSettings(), length=0.3))
    assert hook is not None and hook.exact is not None
    on, off = _run(scene, omega, True, monkeypatch), _run(scene, omega, False, monkeypatch)
    assert off.n_capped == 0
    assert (on.poses, on.states, on.status, on.n_steps, on.t_end) == (off.poses, off.states, off.status, off.n_steps,
                                                                       off.t_end)


@pytest.mark.parametrize("mu", [1.0, 2.0, math.inf])
def test_several_parts_keep_the_cap(mu, monkeypatch):
    arm = tm.Arm(h=-0.01, mu=mu, length=0.35)
    scene = Scene(arm, (Placement(PARTS["triangle"], x=0.1, side=0), Placement(PARTS["square"], x=0.2, side=0)), (),
                  0.1)
    on, off = _run(scene, 4.0, True, monkeypatch), _run(scene, 4.0, False, monkeypatch)
    assert (on.poses, on.states, on.n_capped) == (off.poses, off.states, off.n_capped)


# ----------------------------------------------------------------------------------------------- μ = ∞ sticks
def _pivot_range(exact: bool, monkeypatch) -> float:
    """A rectangle+lead released at rest on vertex 0 (CM 0.05 rad past it) on an arm tilted by +10°, μ = ∞: it
    falls over pivoting on that vertex; the vertex's arm-frame x range (m) until another vertex comes within 1 mm."""
    monkeypatch.setattr(F, "EXACT", exact)
    part, j, h, alpha = PARTS["rectangle+lead"], 0, -0.01, math.radians(10.0)
    w = part.w
    phi = -math.pi / 2 - math.atan2(w[j, 1], w[j, 0]) + 0.05
    v = world_vertices(part, (0.0, 0.0, phi))
    scene = Scene(tm.Arm(h=h, mu=math.inf, length=0.4), (Placement(part, pose=(0.2 - v[j, 0], h - v[j, 1], phi)),),
                  alpha=alpha)
    run = _quiet(simulate, scene, settings=tm.engine.EngineSettings(record_dt=1e-3), record=True, run_for=0.4)
    c, s = math.cos(alpha), math.sin(alpha)
    xs = []
    for pose in run.trajectory.poses[:, 0]:
        V = world_vertices(part, pose)
        X_, Y = c * V[:, 0] + s * V[:, 1], -s * V[:, 0] + c * V[:, 1] - h
        if min(y for i, y in enumerate(Y) if i != j) < 1e-3 or Y[j] > 2e-5:
            break
        xs.append(X_[j])
    assert len(xs) > 150  # it pivots for ≈ 0.18 s
    return max(xs) - min(xs)


@pytest.mark.slow
def test_a_sticking_pivot_at_infinite_mu_holds(monkeypatch):
    """Exact: the vertex moves 28 µm (16 µm at dt/2, 11 µm at dt/4: the step's first-order position drift);
    with the cap it slipped 283 µm (256, 234 µm at dt/2, dt/4: a model change, not a discretisation error)."""
    assert _pivot_range(True, monkeypatch) < 50e-6
    assert _pivot_range(False, monkeypatch) > 200e-6


# ----------------------------------------------------------------------------------------------- the reproducer
def _tilt_landing():
    path = Path(__file__).resolve().parents[1] / "kernels" / "test_tilt_landing.py"
    spec = importlib.util.spec_from_file_location("_tilt_landing_reference", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.slow
def test_reproducer_lands_on_the_uncapped_reference(monkeypatch):
    """Case 83 of validate-fixtures (tests/kernels/test_tilt_landing.py): a triangle pivots at μ = 2.02 on an arm
    tilted by 11.5°, slips for the last ≈ 55 ms and lands flat. With the cap the engine landed 0.86 mm down-slope of
    the independent (uncapped) reference; solved exactly it lands within 0.15 mm of it (0.126 mm: its impact offset
    and step drift)."""
    pytest.importorskip("scipy.integrate")
    T = _tilt_landing()
    case = T.CASE83
    part, arm, out, t0, y0 = T._rb_sticking_state(case)
    ref = T.Reference(part, arm, case["alpha"], 0)
    ref.j = min(range(len(ref.W)), key=lambda k: y0[1] + ref.r(y0[2], k)[1])
    _t, y_land, _ts = ref.run(t0, y0)
    args = T._setup(case)[2]
    monkeypatch.setattr(F, "EXACT", True)
    e = _quiet(T.throw_trajectory, *args, "engine", alpha=case["alpha"])[0]
    assert e.status.name == "OK" and e.side == out.side
    assert abs(e.x - y_land[0]) < 0.15e-3, (e.x, y_land[0])
    monkeypatch.setattr(F, "EXACT", False)
    capped = _quiet(T.throw_trajectory, *args, "engine", alpha=case["alpha"])[0]
    assert abs(capped.x - y_land[0]) > 0.5e-3  # the miss this fixes


# ----------------------------------------------------------------------------------------------- a vertex in a corner
def _feeder_scene(mu, pose):
    """The recoil feeder of ``throwmap experiment feed`` (its part, arm, 1 cm pocket and frictionless end wall at
    L = 0.38 m, as the packaged design builds them) with arm μ ``mu`` and the part at arm-frame ``pose``."""
    from throwmap.system.arm import Arm
    from throwmap.system.fixtures import Cavity, Wall
    from throwmap.system.part import Part

    part = Part(vertices=((0.14722431864335458, 0.0), (0.0, 0.085), (0.0, 0.0)), mass=0.12728127396271163,
                com=(0.037125249452450236, 0.04010804106650658), radius_of_gyration=0.027617919039357206,
                point_masses=((0.08, (0.030062890815516597, 0.04706708084354437)),), name="recoil feeder")
    arm = Arm(h=-0.02042023480254783, length=0.38, mu=mu)
    fixtures = (Cavity(profile=((0.18077350269189627, 0.0), (0.17500000000000002, -0.01), (0.0, -0.01))),
                Wall(height=0.15376261062739635, thickness=0.01, mu=0.0))
    return Scene(arm, (Placement(part, pose=pose),), fixtures)


def test_contacts_at_one_point_of_the_part_share_it():
    """Two contacts of one vertex with two shapes (a corner), 10 µm apart and with normals 98° apart: merged, both
    act at their mean point, so a squeeze between them (opposite impulses, inside both μ = 1.14 cones) has no
    couple."""
    m_inv, i_inv = 1.0 / 0.127, 1.0 / (0.127 * 0.0276**2)

    def con(nx, ny, rx, ry, s):
        nx, ny = nx / math.hypot(nx, ny), ny / math.hypot(nx, ny)
        tx, ty = -ny, nx
        gn = (s * nx, s * ny, s * (rx * ny - ry * nx))
        gt = (s * tx, s * ty, s * (rx * ty - ry * tx))
        return [None, gn, gt, 0.0, 0.0, 0.0, 1.14, 0.0, 0.0, 0.0, 0.0, None, rx, ry]

    r1, r2 = (-0.1113565, -0.0364718), (-0.1113468, -0.0364704)
    cons = [con(-1.0, 0.0, *r1, -1.0), con(-0.1418, 0.9899, *r2, 1.0), con(0.0, 1.0, 0.05, -0.03, 1.0)]
    far = list(cons[2])
    X._merge_points(cons, m_inv, i_inv)
    assert cons[2][1] == far[1] and cons[2][2] == far[2]  # a contact elsewhere keeps its point
    mx, my = (r1[0] + r2[0]) / 2, (r1[1] + r2[1]) / 2
    for k in cons[:2]:
        for g in (k[1], k[2]):
            assert g[2] == pytest.approx(mx * g[1] - my * g[0], abs=1e-15)  # the torque row about the mean point
        assert k[3] == pytest.approx(m_inv * (k[1][0] ** 2 + k[1][1] ** 2) + i_inv * k[1][2] ** 2)
    # the squeeze the unmerged contacts could hold: impulse (j_n, j_t) on each with equal and opposite forces
    f = (0.766, -0.643)  # −40°: inside contact 0's cone (about +x) and opposite to one inside contact 1's
    torque = 0.0
    for k, sign in zip(cons[:2], (1.0, -1.0)):
        gn, gt = k[1], k[2]
        jn = sign * (f[0] * gn[0] + f[1] * gn[1])
        jt = sign * (f[0] * gt[0] + f[1] * gt[1])
        assert jn > 0 and abs(jt) <= 1.14 * jn  # friction-consistent on both
        torque += gn[2] * jn + gt[2] * jt
    assert abs(torque) < 1e-12


def test_a_part_landing_in_the_cavity_corner_lies_flat(monkeypatch):
    """Feed trial 0 (seed 0), throw 6: the recoil feeder's triangle lands with a vertex in the corner of the pocket's
    floor and lip ramp (μ = 1.14). Solved with two contacts 10 µm apart it stayed at rest on that one vertex, tilted
    0.142 rad with its CM 11 cm beyond it, held by a 9 N·s squeeze per 0.5 ms step (10⁴ × its weight's impulse);
    at one point it falls flat against the end wall as the capped engine has it (within 2 µm)."""
    from throwmap.engine import RecoilThrow

    scene = _feeder_scene(1.1443690954698125, (0.32435089071059525, -0.010231668381324152, 3.665443924923759))
    throw = RecoilThrow(omega_n=180.94221640791883, recoil=0.05235987755982989, zeta=0.2, t_recoil=0.05, hold=0.03,
                        t_return=0.05)
    settings = tm.engine.EngineSettings(agreement=0.005, retries=4)
    runs = {}
    for exact in (True, False):
        monkeypatch.setattr(F, "EXACT", exact)
        runs[exact] = _quiet(simulate, scene, throw, settings)
    for run in runs.values():
        assert run.statuses[0].name == "OK" and run.states[0][1] == 0 and abs(run.states[0][2]) < 0.05
    assert abs(runs[True].states[0][0] - runs[False].states[0][0]) < 20e-6


def test_a_lean_on_the_frictionless_end_wall_holds_where_coulomb_says(monkeypatch):
    """The recoil feeder's triangle released at rest leaning on the pocket's frictionless end wall (a vertex on the
    wall 84 mm above the floor, one on the floor, its CM 90 mm beyond that vertex: statics need floor friction
    0.0902/0.0842 = 1.072 × the weight). Exact: it stays at μ = 1.09 and slides down flat at μ = 1.06. Capped, the
    floor contact's cap (0.92 there) is below that need, so it slid down at every μ (feed trials at μ ≳ 1.05 were
    held at the end wall by this)."""
    pose = (0.3225128460757078, 0.044320252670049264, 4.1831278400448735)
    settings = tm.engine.EngineSettings(agreement=0.005, retries=4)

    def tilt(mu, exact):
        monkeypatch.setattr(F, "EXACT", exact)
        run = _quiet(simulate, _feeder_scene(mu, pose), ImpulseThrow(0.0), settings)
        assert run.statuses[0].name == "OK" and run.states[0][1] == 0
        return run.states[0][2]

    assert tilt(1.09, True) == pytest.approx(0.518, abs=0.005)  # held: the lean of the feed run
    assert abs(tilt(1.06, True)) < 0.01  # slid down flat
    assert abs(tilt(1.09, False)) < 0.01  # the cap let it slide
