"""Every claim says the range it covers, and every result has a short summary repr (issue 10, items 1–2).

On an unbounded arm the analysis searches x ≤ 0.6 m by default; beyond it the canonical
triangle has other attractors (a fixed point near 1.17 m at ω = 5.6 rad/s, μ = 1,
rigid_body, although every orbit from x ≤ 0.6 m leaves behind the joint). So the
certificate, the summaries and the tables name their range, and searching further
finds that attractor. Reprs summarise (kind, range, ω, counts) instead of dumping arrays.
"""

from __future__ import annotations

import numpy as np
import pytest

import throwmap as tm
from throwmap.analysis import (
    ConfigSet,
    FunctionMap,
    ThrowMap,
    basins,
    critical_points,
    funnels,
    limit_set,
    push,
)
from throwmap.analysis.caps import DEFAULT_CAPS
from throwmap.analysis.recurrence import find_attractors, start_grid

REPR_MAX = 200


def _ok(x):
    return np.zeros(x.size, dtype=np.int64)


def contraction(a=0.4, k=0.5, name="contraction"):
    return FunctionMap(lambda x, s: (a + k * (x - a), s, _ok(x)), {0: (0.0, 1.0)}, name=name)


def bistable():
    return FunctionMap(lambda x, s: (np.where(x < 0.37, 0.2 + 0.5 * (x - 0.2), 0.7 + 0.5 * (x - 0.7)), s, _ok(x)),
                       {0: (0.0, 1.0)}, name="bistable")


@pytest.fixture(scope="module")
def far():
    """The triangle at ω = 5.6 rad/s on a μ = 1 arm (rigid_body): searched to 0.6 m (default) and to 1.5 m."""
    part, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01, mu=1.0)
    caps = dict(transient=50, n_record=64, max_transient=600)
    near = limit_set(part, arm, 5.6, "rigid_body", n_starts=4, **caps)
    wide = limit_set(part, arm, 5.6, "rigid_body", n_starts=8, x_max=1.5, **caps)
    return near, wide


def test_the_default_search_says_it_stops_at_0_6_m(far):
    near, _ = far
    assert near.attractors == () and set(near.escapes) <= {"behind_joint", "unresolved"}
    assert near.range_text == "valid starts with x ≤ 0.600 m"
    text = near.summary()
    assert "valid starts with x ≤ 0.600 m" in text and "beyond this range are not ruled out" in text
    assert near.to_dict()["range"] == near.range_text
    assert "x∈(" in repr(near) and "0.6] m" in repr(near)


def test_searching_further_finds_the_fixed_point_near_1_17_m(far):
    _, wide = far
    fps = [a for a in wide.attractors if a.kind == "fixed_point"]
    assert fps, wide.summary()
    (side, x), = fps[0].points
    assert x == pytest.approx(1.17, abs=0.01) and x > 0.6
    assert fps[0].residual <= DEFAULT_CAPS["tol"] and fps[0].stable
    assert "x ≤ 1.500 m" in wide.summary()
    # the orbit from that point stays there: one throw of the independent batch API
    out = tm.throw_batch(tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01, mu=1.0), np.array([x]), np.array([side]), 5.6,
                         model="rigid_body")
    assert int(out.status[0]) == 0 and out.side[0] == side and abs(out.x[0] - x) <= DEFAULT_CAPS["tol"]


def test_the_certificate_states_its_range():
    b = basins(contraction(), grid=50, n_seeds=4)
    c = b.certificate
    assert c.unique and c.statement.startswith("unique and globally attractive for the starts with 0 < x ≤ 1 m")
    assert c.range_text == "starts with 0 < x ≤ 1 m" and "starts with 0 < x ≤ 1 m" in c.table()
    assert c.to_dict()["range"] == c.range_text
    b2 = basins(bistable(), grid=50, n_seeds=8)
    assert b2.certificate.statement.startswith("not unique for the starts with 0 < x ≤ 1 m")
    b3 = basins(contraction(), grid={0: np.linspace(0.2, 0.5, 20)}, n_seeds=4)
    assert "given grid (side 0: 0.2–0.5 m)" in b3.certificate.statement


def test_a_throw_map_certificate_and_tables_name_the_range():
    part, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01)
    b = basins(part, arm, 5.6, "paper", grid=20, n_seeds=4, transient=50, n_record=64)
    assert "valid starts with x ≤ 0.600 m" in b.certificate.statement
    cp = critical_points(part, arm, 4.0, "paper", n_grid=32, hull_samples=16)
    assert "x ≤ 60.0 cm" in cp.table().splitlines()[0]
    fg = funnels(part, arm, [4.0], "paper", grid=20, x_max=0.5, n_seeds=4, transient=50, n_record=64)
    assert "valid starts with x ≤ 0.500 m" in fg.table()


def _short(r: str):
    assert len(r) <= REPR_MAX, r
    assert "array(" not in r and "\n" not in r, r
    return r


def test_every_result_has_a_short_summary_repr():
    m = bistable()
    ls = limit_set(m, n_starts=300)
    r = _short(repr(ls))
    assert r.startswith("LimitSet(map='bistable', x∈(0, 1] m, 300 starts: 2 fixed points")
    b = basins(m, grid=5000, n_seeds=8)
    r = _short(repr(b))
    assert r.startswith("Basins(map='bistable', x∈(0, 1] m, 5000 configs") and "unique=False" in r
    _short(repr(b.certificate))
    assert "attractor -" in repr(b.certificate)
    a = _short(repr(ls.attractors[0]))
    assert a.startswith("Attractor(#1 fixed point (0.2 m, side 0)")
    fg = funnels(None, maps=[m, contraction(0.5, name="to")], grid=50, goal="0:0.45-0.55")
    assert _short(repr(fg)).startswith("FunnelGraph(2 maps, 3 funnels")
    assert _short(repr(fg.funnels[0])).startswith("Funnel('bistable #1'")
    cs = ConfigSet(tuple((0, 0.01 * i, 0.01 * i + 0.005) for i in range(50)))
    assert "… 50 intervals" in _short(repr(cs))
    cp = critical_points(m)
    assert _short(repr(cp)).startswith("CriticalPoints(map='bistable', x ≤ 1 m")
    x0, s0 = start_grid(m, 200, 0)
    assert _short(repr(find_attractors(m, x0, s0))).startswith("Recurrence(200 starts")
    assert _short(repr(m)) == "FunctionMap('bistable', side 0: (0, 1] m)"


def test_throw_map_results_name_model_omega_and_range():
    part, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01)
    cmap = ThrowMap(part, arm, 4.0, "paper")
    assert _short(repr(cmap)).startswith("ThrowMap(part='triangle_30_60_90(hypotenuse=0.17)', h=-0.01 m, "
                                         "model='paper', omega=4 rad/s")
    ls = limit_set(cmap, n_starts=4, transient=50, n_record=64)
    assert _short(repr(ls)).startswith("LimitSet(model='paper', omega=4 rad/s, x∈(")
    img = push(part, arm, [4, 4], "0:0.20-0.30", model="paper", n=500)
    assert _short(repr(img)).startswith("SetImage(omegas=[4, 4] rad/s, 500 configs")
