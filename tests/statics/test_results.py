"""The statics' results are objects: ``table()``, ``to_dict()`` (strict JSON) and ``.plot()`` (a figure) for the
rest analysis, the Fig. 13/14 data, the partial-assembly region, the lean and γ tables and the engine's rest check."""

from __future__ import annotations

import json
import math

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

import throwmap as tm  # noqa: E402
from throwmap.statics import analyse_rest, find_contacts, leaning_bodies  # noqa: E402
from throwmap.statics.assembly import PartialRegion, partial_region  # noqa: E402
from throwmap.statics.engine_check import EngineRest  # noqa: E402
from throwmap.statics.figures import LeanData, PartialData, lean_data, partial_data  # noqa: E402
from throwmap.statics.tables import LeanTable, PartialTable, lean_table, partial_table  # noqa: E402

TRI = tm.triangle_30_60_90()


def _strict(d: dict) -> dict:
    return json.loads(json.dumps(d, allow_nan=False))


def test_rest_analysis_to_dict_and_plot():
    bodies, cs = leaning_bodies(TRI, 0.5, length=0.3, h=-0.01, mu_arm=2.0)
    a = analyse_rest(bodies, cs, alpha=math.radians(-10))
    d = _strict(a.to_dict())
    assert d["can_rest"] == a.can_rest and len(d["contacts"]) == len(a.contacts)
    if a.can_rest:
        assert d["contacts"][0]["force_n"] == pytest.approx(list(a.forces[0]))
    assert isinstance(a.plot(), Figure)
    none = analyse_rest(bodies, (), alpha=0.0)  # no contact: falls; μ needed ∞ written as null
    assert _strict(none.to_dict())["mu_needed"] is None and isinstance(none.plot(), Figure)
    with pytest.raises(Exception):
        a.can_rest = False  # frozen


def test_lean_and_partial_data_are_results():
    ld = lean_data(TRI, alpha=math.radians(-10), beta_show=0.5, mu_show=2.0, n_beta=12, n_mu=8)
    assert isinstance(ld, LeanData) and ld.possible.shape == (8, 12)
    d = _strict(ld.to_dict())
    assert d["part_name"] == TRI.name and len(d["betas"]) == 12 and d["analysis"]["can_rest"] == ld.analysis.can_rest
    assert "leaning at β = 0.5 rad" in ld.table()
    assert isinstance(ld.plot(), Figure)
    pd = partial_data(TRI, alpha=math.radians(-10), gamma_show=math.radians(-15), gammas_deg=[-25, -5], mus=[0.0, 1.0])
    assert isinstance(pd, PartialData) and pd.rests.shape == (2, 2)
    assert _strict(pd.to_dict())["gammas_deg"] == [-25.0, -5.0] and "| -25 |" in pd.table()
    assert isinstance(pd.plot(), Figure)


def test_partial_region_is_a_result():
    reg = partial_region(TRI, np.radians([-25, -5]), [0.0, 1.0], alpha=math.radians(-10))
    assert isinstance(reg, PartialRegion) and reg.rests.shape == (2, 2)
    d = _strict(reg.to_dict())
    assert set(d) >= {"gamma", "mu", "rests", "mu_needed"} and d["rests"] == reg.rests.tolist()
    assert reg.table().splitlines()[0] == "| γ (deg) | arm μ needed (LP) | rests at μ of the grid |"
    assert isinstance(reg.plot(), Figure)


def test_lean_and_partial_tables_without_the_engine():
    t = lean_table(TRI, n=6, seed=1, engine=False)
    assert isinstance(t, LeanTable) and t.table() == "\n".join(t.lines())
    d = _strict(t.to_dict())
    assert d["n"] == 6 and len(d["rows"]) == 6 and d["rows"][0]["engine_status"] == "skipped"
    assert isinstance(t.plot(), Figure)
    p = partial_table(TRI, (-25, -5), engine=False)
    assert isinstance(p, PartialTable) and [r[0] for r in p.rows] == [-25, -5]
    assert p.table().splitlines()[2].startswith("| -25 | ") and "| — |" in p.table()
    assert _strict(p.to_dict())["rows"][1]["gamma_deg"] == -5
    assert isinstance(p.plot(), Figure)


def test_engine_rest_is_a_result():
    r = EngineRest((2e-4, 3e-3), (1e-3, 0.2), "ok", 1.0)
    assert not r.stayed and "| 1 | 3 | 0.2 |" in r.table() and r.table().endswith("moved (thresholds 1 mm, 0.01 rad)")
    assert _strict(r.to_dict()) == {"moved_m": [2e-4, 3e-3], "turned_rad": [1e-3, 0.2], "status": "ok",
                                    "run_for_s": 1.0, "stayed": False}
    assert isinstance(r.plot(), Figure)


def test_contacts_of_a_placement_still_feed_the_lp():
    bodies, _ = leaning_bodies(TRI, 0.5, length=0.3, h=0.0, mu_arm=1.0)
    cs = find_contacts(bodies, h=0.0, mu_arm=1.0, length=0.3, wall=tm.Wall(0.2, mu=0.0), mu_wall=0.0)
    assert analyse_rest(bodies, cs, alpha=0.0).to_dict()["contacts"]
