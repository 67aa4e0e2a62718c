"""The studies' results are objects: ``table()``, ``to_dict()`` (the old dict, read back) and ``.plot()`` (a figure).

Built from hand-made trials and values, so that no throw runs: the reports' arithmetic, their JSON and their
figures are checked here; the physics of the studies in their own tests."""

from __future__ import annotations

import json
import math

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

from throwmap.analysis.wall import WallFixedPoint  # noqa: E402
from throwmap.experiments.base import Trial, trial_seed  # noqa: E402
from throwmap.kernels import codes as C  # noqa: E402
from throwmap.studies import recoil_validation as rv  # noqa: E402
from throwmap.studies.demo import DemoResult  # noqa: E402
from throwmap.studies.study import answer_values, answers, stored  # noqa: E402
from throwmap.studies.validation_report import ValidationReport, compare_row  # noqa: E402


def _trial(i, values, seed=0):
    t = Trial(i, trial_seed(seed, i), True, None, values)
    return Trial.from_json(json.loads(json.dumps(t.to_json())))  # as the runner stores and reads it back


def test_answers_survive_the_runners_json_lines_with_infinities():
    rec = np.array([1.0, math.inf, -math.inf, math.nan])
    t = _trial(0, answer_values("m", math.inf, 2, C.OK, rec, message="why"))
    a = answers([t], "m", record=4)
    assert a["x"][0] == math.inf and a["side"][0] == 2 and a["status"][0] == C.OK
    assert a["recs"][0, 0] == 1.0 and a["recs"][0, 1] == math.inf and a["recs"][0, 2] == -math.inf
    assert math.isnan(a["recs"][0, 3]) and t.values["m.message"] == "why"
    assert stored(0.25) == 0.25 and stored(-math.inf) == "-inf"


def _recoil_trials(cfg, statuses):
    out = []
    for i, st in enumerate(statuses):
        v = {}
        for key in rv.KEYS:
            x = 0.2 + 1e-4 * i + (3e-4 if key == "rb" else 0.0)
            s = st if key == "engine" else C.OK
            v.update({f"{key}.x": stored(x if s == C.OK else math.nan), f"{key}.side": 0 if s == C.OK else -1,
                      f"{key}.status": int(s), f"{key}.message": "" if s == C.OK else "refused here",
                      f"{key}.seconds": 0.01})
        out.append(_trial(i, v))
    return out


def test_recoil_report_from_trials_round_trips_and_draws():
    cfg = rv.RecoilConfig(n=4, seed=0)
    rep = rv.recoil_report(cfg, _recoil_trials(cfg, [C.OK, C.OK, C.UNCONVERGED, C.OFF_END]))
    s = rep.summary["rb vs engine/16 (recoil)"]
    assert (s["n"], s["n_compared"]) == (4, 3) and s["refused_second"] == {"unconverged": 1}
    a = rep.agreement.row("rb vs engine/16 (recoil)")
    assert (a.n, a.refused_reference, a.compared, a.same, a.rests, a.within) == (4, 1, 3, 2, 2, 2)
    assert rep.table() == rv.recoil_table(rep.to_dict()) and "| rb vs engine/16 (recoil) | 3/4 |" in rep.table()
    doc = json.loads(json.dumps(rep.to_dict(), default=str))
    assert set(doc) == {"cases", "results", "seconds", "impact_law", "engine_refine", "cap_bound", "summary",
                        "agreement"}
    back = rv.RecoilValidation.from_dict(doc)
    assert back.agreement == rep.agreement and back.table() == rep.table()
    assert isinstance(rep.plot(), Figure)
    with pytest.raises(Exception, match="^trials"):
        rv.recoil_report(cfg, _recoil_trials(cfg, [C.OK]))


def test_validation_report_round_trips_with_its_agreement():
    from throwmap.studies.agreement import AgreementTable, agreement

    ref = {"x": np.array([0.1, 0.2, math.nan]), "side": np.array([0, 1, -1]), "status": np.array([0, 0, C.TIMEOUT])}
    res = {"x": np.array([0.1003, 0.2, 0.3]), "side": np.array([0, 2, 0]), "status": np.array([0, 0, 0])}
    row = compare_row("m", ref, res, "—")
    rep = ValidationReport("pymunk", {}, {}, (row,), {}, {"n_throws": 3}, (),
                           AgreementTable((agreement(res, ref, label="m"),), "pymunk engine"))
    back = ValidationReport.from_dict(json.loads(json.dumps(rep.to_dict(), allow_nan=False)))
    assert back.table() == rep.table() and back.agreement_table() == rep.agreement_table()
    assert "| m | 3 | 0 / 1 | 2 | 50.0 [9.5, 90.5] | 1 | 100.0 [20.7, 100.0] |" in rep.agreement_table()
    assert row.same_status_pct == pytest.approx(200 / 3)  # the old table counts the refusal as a miss
    assert isinstance(rep.plot(), Figure)


def _fixed_point(found=True) -> WallFixedPoint:
    base = dict(model="rigid_body", part="square", side=0, omega_rad_s=3.0, length_m=0.3, h_m=-0.01, mu=1.0,
                alpha_deg=0.0, wall_mu=0.0, x_wall_m=0.27, fd_steps_m=(1e-3, 1e-4))
    if not found:
        return WallFixedPoint(**base, found=False, message="limit_set found none", range="all starts")
    return WallFixedPoint(**base, found=True, x_star_m=0.269998, gap_m=2e-6, multiplier=-0.0026, residual_m=5e-17,
                          fraction=0.25, n_starts=64, range="starts", fd_left=(-0.002, math.nan), free_slope=math.nan,
                          n_at_wall=4, reference={"model": "engine", "images": [
                              {"start_offset_m": 0.0, "dx_from_x_wall_m": 0.0, "side": 0, "status": 0}]},
                          limit_set={"kind": "fixed_point"})


@pytest.mark.parametrize("found", [True, False])
def test_wall_fixed_point_round_trips_and_draws(found):
    fp = _fixed_point(found)
    d = json.loads(json.dumps(__import__("throwmap.serial", fromlist=["json_ready"]).json_ready(fp.to_dict())))
    back = WallFixedPoint.from_dict(d)
    assert back.lines() == fp.lines() and back.table() == fp.table()
    assert ("range" in d) and d["found"] is found
    if found:
        assert "multiplier -0.0026" in fp.table() and "T(x_w +0 mm) − x_w = +0 µm (side 0, ok)" in fp.table()
    assert isinstance(fp.plot(), Figure)


def test_demo_result_is_its_summary():
    summary = {"example": {"h": -0.01, "omega": 4.0, "n_throws": 300, "model": "paper"},
               "part": {"name": "triangle"}, "orbit": {"status": "ok"},
               "analysis": {"parameters": {"model": "rigid_body"}, "limit_set": {"kind": "cycle"}},
               "files": ["out/a.png"], "x": math.nan}
    r = DemoResult("out", ("out/a.png",), summary)
    assert r.to_dict()["x"] is None and r.to_dict()["files"] == ["out/a.png"]
    assert r.table().splitlines()[-1] == "wrote out/a.png" and "limit set (rigid_body): cycle" in r.table()
