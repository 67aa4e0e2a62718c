"""The tilt/wall validation study (throwmap.studies.tilt_wall): its draws, its comparison
arithmetic, its report, and a small run of the engine against itself (which must agree on every throw)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from throwmap import Arm, Wall, triangle_30_60_90
from throwmap.errors import InvalidStateError
from throwmap.kernels import codes as C
from throwmap.studies import tilt_wall as tw
from throwmap.studies.validation import default_parts
from throwmap.system.starts import start_interval, tilted_rest_reason, wall_reach, wall_start_reason

PARTS = default_parts()


@pytest.mark.parametrize("condition", list(tw.CONDITIONS))
def test_draws_stay_in_their_ranges(condition):
    cases = tw.make_cases(PARTS, condition, 60, np.random.default_rng(7))
    spec = tw.CONDITIONS[condition]
    assert cases.n == 60
    for i in range(cases.n):
        part = PARTS[cases.part[i]]
        lo, hi = start_interval(part, Arm(h=cases.h[i], length=cases.length[i]), int(cases.side[i]))
        assert lo < cases.x[i] <= hi  # a start throw() accepts
        arm = Arm(h=cases.h[i], mu=cases.mu[i], length=cases.length[i])
        assert tilted_rest_reason(part, arm, int(cases.side[i]), float(cases.alpha[i])) == ""  # at rest at α
        if spec["wall"] is not None:  # the outer quarter of the starts clear of the wall, where jogs reach it
            hi = min(hi, cases.length[i] - wall_reach(part, int(cases.side[i]), tw.WALL_HEIGHT))
            assert cases.x[i] <= hi + 1e-12
            assert cases.x[i] >= hi - tw.WALL_X_SHARE * (hi - lo) - 1e-12
            fx = (Wall(tw.WALL_HEIGHT),)
            assert wall_start_reason(part, arm, int(cases.side[i]), float(cases.x[i]), fx) == ""
    assert np.all(np.abs(cases.alpha) <= math.radians(15) + 1e-12)
    assert np.all((cases.mu >= 0.3) | np.isinf(cases.mu)) and np.all(cases.mu[np.isfinite(cases.mu)] <= 3.0)
    assert np.all((cases.omega >= 3.0) & (cases.omega <= 7.0))
    assert set(np.unique(cases.h)) <= set(tw.H_VALUES)
    if spec["mu"] == "inf":
        assert np.all(np.isinf(cases.mu))
    if spec["wall"] is None:
        assert np.all(np.isnan(cases.wall_mu))
    elif spec["wall"] == "zero":
        assert np.all(cases.wall_mu == 0.0)
    else:
        assert np.array_equal(cases.wall_mu, cases.mu)


def test_same_seed_same_draws():
    a = tw.make_cases(PARTS, "tilt", 20, np.random.default_rng(3))
    b = tw.make_cases(PARTS, "tilt", 20, np.random.default_rng(3))
    c = tw.make_cases(PARTS, "tilt", 20, np.random.default_rng(3), alpha_range=(0.0, 0.0))
    for f in ("x", "side", "omega", "alpha", "mu", "h", "length"):
        assert np.array_equal(getattr(a, f), getattr(b, f))
    assert np.all(c.alpha == 0.0) and np.all(a.alpha != 0.0)


def _res(x, side, status):
    return {"x": np.array(x, dtype=float), "side": np.array(side), "status": np.array(status), "message": None}


def test_compare_rows_counts_by_hand():
    cases = tw.make_cases(PARTS, "tilt", 5, np.random.default_rng(0))
    ref = _res([0.1, 0.2, 0.3, 0.4, 0.5], [0, 0, 1, 0, 0], [0, 0, 0, C.BEHIND_JOINT, 0])
    # throw 0 within 0.4 mm; 1 off by 2 mm; 2 on another side; 3 the same escape; 4 refused by the model
    res = _res([0.1004, 0.202, 0.3, 0.0, 0.5], [0, 0, 0, 0, 0], [0, 0, 0, C.BEHIND_JOINT, C.UNRESOLVED])
    r = tw.compare_rows("row", cases, PARTS, res, ref)
    assert r.n == 5 and r.n_compared == 4
    assert r.same_pct == pytest.approx(75.0)  # 0, 1, 3
    assert r.within_pct == pytest.approx(50.0)  # 0, 3
    assert r.dx_median_mm == pytest.approx(1.2)  # median of 0.4 and 2.0 mm
    assert r.model_refused == {"unresolved": 1} and r.engine_refused == {}
    lo, hi = r.within_ci95
    assert lo < 50.0 < hi
    # the one agreement statistic: the refusal is left out; of 4 compared, 3 alike; of the 2 alike rests, 1 within
    a = r.agreement
    assert (a.n, a.refused_model, a.refused_reference, a.compared, a.same, a.rests, a.within) == (5, 1, 0, 4, 3, 2, 1)
    assert tw.TiltWallRow.from_dict(r.to_dict()).to_dict() == r.to_dict()
    worst = r.worst
    assert worst[0]["dx_mm"] is None and worst[0]["model"]["side"] == 0 and worst[0]["engine"]["side"] == 1
    assert worst[1]["dx_mm"] == pytest.approx(2.0)  # the side miss first, then the largest |Δx|
    for key in ("part", "x_m", "side", "omega_rad_s", "alpha_rad", "mu", "h_m", "length_m", "wall"):
        assert key in worst[0]  # a reproducer carries every parameter


def test_a_model_that_refuses_the_keyword_gives_a_row_that_says_so():
    cases = tw.make_cases(PARTS, "tilt", 3, np.random.default_rng(0))
    out = tw._throw_all(cases, PARTS, "small_angle", {}, None)
    assert "alpha" in out["message"] and "small_angle" in out["message"]
    r = tw.compare_rows("row", cases, PARTS, out, out)
    assert r.available is False and r.n_compared == 0 and set(r.to_dict()) == {"row", "n", "n_compared", "available",
                                                                               "message"}


def test_bad_arguments_are_refused_naming_the_field():
    with pytest.raises(InvalidStateError, match="conditions"):
        tw.validate_tilt_wall(n=1, conditions=("nope",))
    with pytest.raises(InvalidStateError, match="alpha_range"):
        tw.validate_tilt_wall(n=1, alpha_range=(0.1, -0.1))
    with pytest.raises(InvalidStateError, match="^n"):
        tw.validate_tilt_wall(n=0)


@pytest.mark.slow
def test_engine_against_itself_agrees_on_every_throw_and_the_report_round_trips():
    """The comparison is exact where both sides are the same deterministic engine (a failing row means
    the bookkeeping, not the physics, is wrong); the report's JSON is strict and reads back."""
    rep = tw.validate_tilt_wall({"triangle": PARTS["triangle"], "square": PARTS["square"]}, n=6, seed=1,
                                models=("engine",), fixed_point=False, baseline=False)
    assert len(rep.rows) == len(tw.CONDITIONS)
    for r in rep.rows:
        assert r.available and r.n_compared + sum(r.engine_refused.values()) == 6
        assert r.n_compared >= 1
        assert r.same_pct == 100.0 and r.within_pct == 100.0
        assert r.dx_max_mm == 0.0 or math.isnan(r.dx_max_mm)  # nan: no throw came to rest
        assert r.agreement.same == r.agreement.compared == r.n_compared
    walled = [r for r in rep.rows if r.row.startswith("wall")]
    assert all(r.wall_changed_pct is not None for r in walled)
    doc = json.loads(json.dumps(rep.to_dict(), allow_nan=False))
    back = tw.TiltWallReport.from_dict(doc)
    assert back.table() == rep.table() and back.goals == rep.goals
    assert back.agreement_table() == rep.agreement_table() != ""
    assert doc["settings"]["seed"] == 1 and doc["settings"]["alpha_range_deg"] == [-15.0, 15.0]
    for line in rep.goal_lines():  # a verdict on a handful of throws shows how little it says
        assert "by the estimate; 95 % interval [" in line and "throws" in line
        lo = float(line.split("interval [")[1].split(",")[0])
        assert lo < 95.0  # ≤ 6 throws all agreeing: the Wilson lower bound is far below the goal


def test_wall_fixed_point_reports_a_refusal_as_not_found():
    fp = tw.wall_fixed_point(triangle_30_60_90(), Arm(h=-0.01, mu=1.0, length=0.3), 5.0, 0, model="small_angle")
    assert fp.found is False and "fixtures" in fp.message
    assert tw.WallFixedPoint.from_dict(fp.to_dict()) == fp and "NOT found" in fp.table()


@pytest.mark.slow
def test_a_small_real_run_has_every_row_with_its_baseline_and_by_mu_bands():
    rep = tw.validate_tilt_wall({"square": PARTS["square"]}, n=4, seed=2, conditions=("tilt, μ = ∞", "tilt"),
                                fixed_point=False)
    names = [r.row for r in rep.rows]
    assert names[:3] == ["tilt, μ = ∞: paper vs engine", "tilt, μ = ∞: rigid_body vs engine",
                         "tilt, μ = ∞: paper vs rigid_body"] and names[-1] == "tilt: rigid_body vs engine"
    for r in rep.rows:
        assert r.available, r.message
        assert sum(v["n"] for v in r.by_mu.values()) == r.n_compared <= r.n
        if "no lift-off" not in r.row:
            assert r.baseline is not None and 0 <= r.baseline["within_pct"] <= 100
    assert all(set(r.by_mu) == {"∞"} for r in rep.rows if r.row.startswith("tilt, μ = ∞"))
    assert set(rep.results["tilt"]) == {"engine", "rigid_body", "engine, α = 0", "rigid_body, α = 0"}
