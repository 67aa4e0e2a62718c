"""throwmap.design on the exact map: the contract, bounds at every iterate, failures, the small-angle F."""

from __future__ import annotations

import dataclasses
import math

import pytest

import throwmap as tm
from throwmap.design import (DesignResult, SMALL_ANGLE_F, Separation, Target, design, design_critical_points,
                             energy_critical_points, inset_polygon)
from throwmap.design.api import SolveOptions
from throwmap.design.examples import exact_r, plexiglas_triangle
from throwmap.errors import InvalidStateError

PLATE = plexiglas_triangle()
ARM = tm.Arm(h=-0.01, length=0.6)
TARGET = {0: 0.30, 1: 0.15, 2: 0.15}


@pytest.fixture(scope="module")
def result():
    return design_critical_points(PLATE, ARM, 5.0, weight_mass=0.03, weight_at=(0.03, 0.03), target=TARGET)


def test_contract(result):
    assert isinstance(result, DesignResult)
    assert result.targets_reached, result.message
    # the draft-style targets are hit where every orbit escapes behind the joint: no limit set, no success
    assert not result.success and "feeds nothing" in result.message
    assert "every orbit escapes" in result.limit_set_note
    assert set(result.achieved) == set(TARGET)
    for s, r in TARGET.items():
        assert abs(result.achieved[s] - r) <= 1e-4
    assert result.jacobian_rank == 3 and result.jacobian_rank_start == 3
    assert 1 <= result.condition < 1e3
    assert result.part.point_masses == ((0.03, result.weight_at),)
    assert result.omega == result.history[-1].values["omega"]
    with pytest.raises(dataclasses.FrozenInstanceError):
        result.success = False


def test_achieved_r_are_the_maps_own(result):
    """Independent re-evaluation: critical_points on the designed part at the designed ω."""
    r = exact_r(result.part, ARM, result.omega).r
    for s, v in TARGET.items():
        assert abs(r[s] - v) <= 1e-4


def test_history_starts_at_the_start_and_the_residual_falls(result):
    h = result.history
    assert h[0].values["weight_x"] == 0.03 and h[0].values["omega"] == 5.0
    norms = [st.norm for st in h]
    assert all(b < a for a, b in zip(norms, norms[1:]))
    assert result.table().count("\n") >= len(h)
    d = result.to_dict()
    assert d["jacobian"]["rank"] == 3 and len(d["history"]) == len(h)


def test_weight_stays_inside_the_plate_at_every_iterate():
    """The draft's targets as printed (r_2 largest) push the weight to the plate's edge: every iterate, and
    every point the Jacobian is taken at, stays margin inside."""
    res = design(PLATE, ARM, 5.6, {0: 0.10, 1: 0.10, 2: 0.20}, weight_mass=0.115, weight_at=(0.008, 0.0378),
                 solve=SolveOptions(max_iter=8))
    ins = inset_polygon(PLATE.vertices, res.margin)
    assert not res.success
    assert "bound" in res.message
    for st in res.history:
        assert ins.contains((st.values["weight_x"], st.values["weight_y"]), tol=1e-12)
        assert ARM.length and 1.0 <= st.values["omega"] <= 15.0


def test_too_few_parameters_is_rank_deficient_and_fails():
    res = design(PLATE, ARM, 5.0, TARGET, weight_mass=0.03, weight_at=(0.03, 0.03), vary=("weight_x",), solve=SolveOptions(max_iter=6))
    assert not res.success
    assert res.jacobian_rank == 1
    assert "rank deficient" in res.message


def test_unreachable_target_says_why():
    res = design(PLATE, ARM, 5.0, {1: 0.01}, weight_mass=0.03, weight_at=(0.03, 0.03), solve=SolveOptions(max_iter=10))
    assert not res.success
    assert res.message and not res.message.startswith("reached")


def test_bad_input_is_refused_naming_the_field():
    with pytest.raises(InvalidStateError, match="weight_at"):
        design_critical_points(PLATE, ARM, 5.0, weight_mass=0.03, weight_at=(0.2, 0.2), target=TARGET)
    with pytest.raises(InvalidStateError, match="vary"):
        design_critical_points(PLATE, ARM, 5.0, weight_mass=0.03, weight_at=(0.03, 0.03), target=TARGET,
                               vary=("colour",))
    with pytest.raises(InvalidStateError, match="target"):
        design_critical_points(PLATE, ARM, 5.0, weight_mass=0.03, weight_at=(0.03, 0.03), target={0: math.nan})
    with pytest.raises(InvalidStateError, match="weight_mass"):
        design_critical_points(PLATE, ARM, 5.0, weight_mass=-1.0, weight_at=(0.03, 0.03), target=TARGET)


def test_energy_test_agrees_with_the_small_angle_model():
    """design.small_angle (NumPy) and the small_angle kernel (Numba) implement the same corrected forms: where the
    kernel's r_i is a flip (not an escape or a backward turn), the switches coincide to its xtol."""
    from throwmap.analysis.critical import critical_points

    for om in (5.0, 5.6, 6.5):
        f = energy_critical_points(PLATE, ARM, om).r
        cp = critical_points(PLATE, ARM, om, model="small_angle", xtol=1e-7)
        for s in PLATE.stable_sides:
            if cp.next_kind[s].startswith("flip") and math.isfinite(f[s]):
                assert abs(f[s] - cp.r[s]) < 1e-6, (om, s)


def test_small_angle_design_is_a_fast_first_guess_that_misses_on_the_exact_map():
    res = design(PLATE, ARM, 5.6, {0: 0.20, 1: 0.10, 2: 0.10}, weight_mass=0.115, weight_at=(0.008, 0.0378),
                 model=SMALL_ANGLE_F)
    assert res.targets_reached, res.message
    r = exact_r(res.part, ARM, res.omega).r
    miss = max(abs(r[s] - v) for s, v in {0: 0.20, 1: 0.10, 2: 0.10}.items())
    assert miss > 0.005  # centimetres off on the exact model
    fin = design(PLATE, ARM, res.omega, {0: 0.20, 1: 0.10, 2: 0.10}, weight_mass=0.115, weight_at=res.weight_at)
    assert fin.targets_reached and fin.n_steps <= res.n_steps + 3


def test_separation_target_on_the_limit_set():
    """The separation objective's hinge residuals are zero exactly when it holds."""
    sep = Separation(0, 0.335, 0.035)
    assert sep.holds({0: 0.40, 1: 0.29, 2: 0.26})
    assert not sep.holds({0: 0.36, 1: 0.29, 2: 0.26})
    assert sep.residual({0: 0.36, 1: 0.31, 2: 0.26}) == pytest.approx({"sep_0": 0.01, "sep_1": 0.01, "sep_2": 0.0})
    res = design(PLATE, ARM, 4.9, [Target("r", 0, 0.32), sep], weight_mass=0.05, weight_at=(0.0125, 0.0285),
                 vary=("omega",), solve=SolveOptions(max_iter=5, limit_options={"n_starts": 12}))
    assert res.success, res.message
    assert sep.holds({int(k.split("_")[1]): v for k, v in res.features.items() if k.startswith("top_")})


def test_alpha_is_passed_to_the_model_as_a_throw_option():
    from throwmap.design.space import DesignSpace

    sp = DesignSpace(plate=PLATE, arm=ARM, start={"weight_x": 0.03, "weight_y": 0.03, "weight_mass": 0.03,
                                                   "omega": 5.0, "alpha": 0.05},
                     vary=("alpha", "omega"), bounds={}, margin=0.008, scales={}, steps={})
    st = sp.setup([0.07, 5.0])
    assert st.throw_options == {"alpha": 0.07}
    assert sp.setup([0.0, 5.0]).arm == ARM


def test_wall_window_target_widens_the_end_wall_window():
    """The robust-separation objective: S = [r_0 + u_R(0)](1.06 ω) − max_j [r_j + u_R(j)](0.94 ω) ≥ 6 cm."""
    from throwmap.design import WallWindow
    from throwmap.design.examples import end_wall_window

    res = design(PLATE, ARM, 5.0, [Target("r", 0, 0.32), WallWindow(0, 0.06, 0.06)], weight_mass=0.05)
    assert res.success, res.message
    *_, S = end_wall_window(res.part, ARM, res.omega, 0, 0.06)
    assert S >= 0.06 - 1e-4
    assert res.features["wall_0"] == pytest.approx(S, abs=1e-6)
    assert res.to_dict()["targets"][1] == {"kind": "wall_window", "side": 0, "jitter": 0.06, "width_m": 0.06}


def test_weight_mass_and_omega_vary():
    res = design(PLATE, ARM, 5.0, {0: 0.31, 2: 0.20}, weight_mass=0.02, weight_at=(0.02, 0.02),
                 vary=("weight_mass", "omega"))
    assert res.targets_reached, res.message
    assert res.part.mass == pytest.approx(PLATE.mass + res.weight_mass)
    assert res.weight_mass != 0.02 and res.jacobian_rank == 2


def test_band_top_target():
    """A band top of the limit set (from limit_set) as the target, ω varied: reached, with full rank
    (the default difference steps grow tenfold for limit-set features)."""
    res = design(PLATE, ARM, 4.9, [Target("top", 0, 0.41)], weight_mass=0.05, weight_at=(0.0125, 0.0285),
                 vary=("omega",), solve=SolveOptions(limit_options={"n_starts": 8}, max_iter=6))
    assert res.success, res.message
    assert abs(res.features["top_0"] - 0.41) <= 1e-4
    assert res.jacobian_rank == 1
