"""r_i of a design point as a result (throwmap.design.radii.SideRadii): the energy test's, with ``table()``,
``to_dict()`` (the old ``{side: r}``) and ``.plot()``."""

from __future__ import annotations

import json
import math

import matplotlib

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

import throwmap as tm  # noqa: E402
from throwmap.design import energy_critical_points  # noqa: E402
from throwmap.design.examples import plexiglas_triangle  # noqa: E402
from throwmap.design.radii import SideRadii  # noqa: E402


def test_energy_test_radii_are_a_result():
    plate = plexiglas_triangle()
    r = energy_critical_points(plate, tm.Arm(h=-0.01, length=0.6), 3.0)
    assert isinstance(r, SideRadii) and r.method == "energy test" and r.omega == 3.0
    assert set(r.r) == set(plate.stable_sides) and r.to_dict() == r.r
    assert json.loads(json.dumps({str(k): v for k, v in r.to_dict().items()}))
    lines = r.table().splitlines()
    assert lines[1] == "| side | r_i (m) | r_i (cm) |" and len(lines) == 3 + len(r.r)
    assert isinstance(r.plot(), Figure)


def test_a_side_without_a_flip_is_shown_as_a_dash():
    r = SideRadii({0: 0.2, 1: math.nan}, "rigid_body", "plate", 4.0)
    assert "| 1 | — | — |" in r.table() and "| 0 | 0.200000 | 20.00 |" in r.table()
    assert isinstance(r.plot(), Figure)
