"""One result vocabulary: every analysis result round-trips through JSON and reads as a table.

``CriticalPoints``, ``LimitSet``, ``Basins`` and ``FunnelGraph`` round trips are also
checked beside their computations; here the others (``Attractor``, ``Certificate``,
``SetImage``, ``ConfigSet``) and the text tables of all of them.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from throwmap.analysis import (
    Attractor,
    Basins,
    Certificate,
    ConfigSet,
    FunctionMap,
    LimitSet,
    SetImage,
    basins,
    critical_points,
    limit_set,
    push,
)
from throwmap.errors import InvalidStateError
from throwmap.records.outcome import Status

OK, BEHIND, OFF_END = int(Status.OK), int(Status.BEHIND_JOINT), int(Status.OFF_END)


def _ok(x):
    return np.zeros(x.size, dtype=np.int64)


def bistable(p=0.2, q=0.7, m=0.37, k=0.5):
    return FunctionMap(lambda x, s: (np.where(x < m, p + k * (x - p), q + k * (x - q)), s, _ok(x)),
                       {0: (0.0, 1.0)}, name="bistable")


def period_two():
    def f(x, s):
        return np.where(s == 0, 0.6 + 0.5 * (x - 0.3), 0.3 - 0.4 * (x - 0.6)), 1 - s, _ok(x)
    return FunctionMap(f, {0: (0.0, 1.0), 1: (0.0, 1.0)}, name="period two")


def repeller(a=0.5):
    def f(x, s):
        xn = a + 2.0 * (x - a)
        return xn, s, np.where(xn > 1.0, OFF_END, np.where(xn <= 0.0, BEHIND, OK))
    return FunctionMap(f, {0: (0.0, 1.0)}, name="repeller")


def tent(slope=1.9):
    return FunctionMap(lambda x, s: (slope * np.minimum(x, 1.0 - x), s, _ok(x)), {0: (0.0, 1.0)}, name="tent")


def _json(d):
    return json.loads(json.dumps(d))


def test_attractors_of_every_kind_round_trip():
    found = [a for m in (bistable(), period_two(), tent(), repeller()) for a in limit_set(m, n_starts=8).attractors]
    kinds = {a.kind for a in found}
    assert kinds == {"fixed_point", "cycle", "band"}
    for a in found:
        d = _json(a.to_dict())
        back = Attractor.from_dict(d)
        assert back.to_dict() == d
        if math.isfinite(a.multiplier) and math.isfinite(a.lyapunov):
            assert back == a
        else:  # nan ≠ nan: compare what is comparable
            assert (back.kind, back.points, back.bands, back.side_visits) == (a.kind, a.points, a.bands, a.side_visits)


@pytest.mark.parametrize("cmap", [bistable(), repeller(), tent()], ids=["two", "escapes", "band"])
def test_certificate_round_trips(cmap):
    cert = basins(cmap, grid=40, method="orbits").certificate
    d = _json(cert.to_dict())
    back = Certificate.from_dict(d)
    assert back.to_dict() == d
    assert back.statement == cert.statement and back.unique == cert.unique
    assert (back == cert) or math.isnan(cert.trap_excursion)


def test_set_image_round_trips_and_needs_its_arrays(triangle, arm):
    im = push(triangle, arm, [4.0, 5.6, 5.6, 3.5, 5.6], "0:0.12-0.5, 1:0.06-0.4, 2:0.3-0.35", "paper", n=30)
    assert 0 < im.escaped < 1  # both kinds of configuration are in the record
    d = _json(im.to_dict())
    back = SetImage.from_dict(d)
    assert back.to_dict() == d
    for field in ("x", "side", "status"):
        np.testing.assert_array_equal(getattr(back, field), getattr(im, field))
    assert back.hulls == im.hulls and back.omegas == im.omegas and back.escapes() == im.escapes()
    with pytest.raises(InvalidStateError) as err:
        SetImage.from_dict(_json(im.to_dict(arrays=False)))
    assert err.value.field == "configs"


def test_limit_set_table_has_a_row_per_attractor_and_escape():
    ls = limit_set(repeller(), starts=([0.5, 0.2, 0.7], [0, 0, 0]))
    head, *rows = ls.table().splitlines()
    assert head == f"searched: {ls.range_text} (not beyond)"
    assert len(rows) == 1 + len(ls.attractors) + len(ls.escapes) == 4
    assert rows[1].split()[:2] == ["1", "fixed_point"]
    assert {r.split()[1] for r in rows[2:]} == {"behind_joint", "off_end"}
    assert all(r.split()[0] == "-1" for r in rows[2:])
    assert "50.0000" in rows[1]  # the fixed point at 0.5 m, in cm


def test_basins_table_lists_basin_shares_and_the_certificate():
    b = basins(bistable(), grid=100, method="orbits")
    head, *rows = b.table().splitlines()
    assert head == f"grid over the {b.range_text} (not beyond)" and "x ≤" in head
    assert len(rows) == 1 + 2 + 1 and rows[-1] == b.certificate.statement
    shares = [float(r.split()[5]) for r in rows[1:3]]
    assert sum(shares) == pytest.approx(100.0) and shares[0] == pytest.approx(37.0, abs=1.0)
    cert = b.certificate.table()
    assert cert.splitlines()[0].endswith("no") and cert.endswith(b.certificate.statement)


def test_config_set_and_set_image_tables(triangle, arm):
    cs = ConfigSet.parse("1:0.10-0.15, 0:0.20-0.30")
    rows = cs.table().splitlines()
    assert len(rows) == 1 + 2 + 1
    assert rows[1].split() == ["0", "20.0000", "30.0000", "10.0000"]
    assert rows[-1] == "total length 15.0000 cm"
    im = push(triangle, arm, [4.0, 4.0], cs, "paper", n=10)
    rows = im.table().splitlines()
    assert len(rows) == 1 + 3 and rows[1].split()[:3] == ["0", "-", "100.0"]


def test_every_result_can_be_drawn_or_tabled(triangle, arm):
    """The shared vocabulary: ``to_dict``/``from_dict`` everywhere, ``table`` where text reads well."""
    cp = critical_points(triangle, arm, 4.0, "paper", n_grid=32)
    ls = limit_set(bistable(), n_starts=8)
    b = basins(bistable(), grid=30)
    for obj in (cp, ls, b, b.certificate, ConfigSet.parse("0:0.2-0.3")):
        assert isinstance(obj.table(), str) and obj.table()
        assert type(obj).from_dict(_json(obj.to_dict())).to_dict() == _json(obj.to_dict())
    for cls in (LimitSet, Basins):
        assert callable(getattr(cls, "plot"))
