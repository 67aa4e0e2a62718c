"""The one agreement statistic of the validation studies (throwmap.studies.agreement): hand-counted cases,
refusals out of the denominators, Wilson bounds against the closed form, the empty and all-refused edges."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from throwmap.errors import InvalidStateError
from throwmap.kernels import codes as C
from throwmap.studies.agreement import REFUSED, Agreement, AgreementTable, agreement

Z = 1.959963984540054
TOL = 2.0 ** -11  # ≈ 0.49 mm, exact in binary: the boundary case is exact


def wilson_closed_form(k: int, n: int) -> tuple[float, float]:
    """Wilson's score interval written out (Brown, Cai & DasGupta 2001, Eq. 4), independently of the library."""
    p = k / n
    centre = (k + Z * Z / 2) / (n + Z * Z)
    half = Z * math.sqrt(n) / (n + Z * Z) * math.sqrt(p * (1 - p) + Z * Z / (4 * n))
    return centre - half, centre + half


def answers(status, side, x):
    return {"status": np.array(status), "side": np.array(side), "x": np.array(x, dtype=float)}


def test_hand_counted_throws_with_refusals_on_either_side():
    model = answers([C.OK, C.OK, C.OK, C.OK, C.OFF_END, C.OFF_END, C.UNRESOLVED, C.OK, C.TIMEOUT],
                    [0, 1, 0, 2, -1, -1, -1, 0, -1],
                    [0.1000, 0.2, 0.3, 0.5, math.nan, math.nan, math.nan, 0.5, math.nan])
    ref = answers([C.OK, C.OK, C.OK, C.OK, C.OFF_END, C.BEHIND_JOINT, C.OK, C.UNCONVERGED, C.UNCONVERGED],
                  [0, 1, 1, 2, -1, -1, 0, -1, -1],
                  [0.1004, 0.2006, 0.3, 0.5 + TOL, math.nan, math.nan, 0.6, math.nan, math.nan])
    a = agreement(model, ref, label="m vs r", tol=TOL)
    # throws 6 (model refused), 7 (reference refused) and 8 (both) are not compared
    assert (a.n, a.refused_model, a.refused_reference, a.refused_both) == (9, 2, 2, 1)
    assert a.compared == 6  # 9 − 2 − 2 + 1
    # compared: 0 same side, 1 same side, 2 another side, 3 same side, 4 same escape, 5 another escape
    assert a.same == 4 and a.rests == 3
    # rests: 0 off by 0.4 mm, 1 off by 0.6 mm, 3 off by exactly the tolerance (counts as within)
    assert a.within == 2
    assert a.same_rate == pytest.approx(4 / 6) and a.within_rate == pytest.approx(2 / 3)
    assert a.same_ci95 == pytest.approx(wilson_closed_form(4, 6), abs=1e-12)
    assert a.within_ci95 == pytest.approx(wilson_closed_form(2, 3), abs=1e-12)


@pytest.mark.parametrize("k, n", [(0, 1), (1, 1), (3, 7), (99, 100), (0, 500), (500, 500), (250, 500)])
def test_wilson_bounds_equal_the_closed_form(k, n):
    model = answers([C.OK] * n, [0] * n, [0.0] * k + [1.0] * (n - k))
    ref = answers([C.OK] * n, [0] * n, [0.0] * n)
    a = agreement(model, ref)
    assert a.rests == n and a.within == k
    lo, hi = wilson_closed_form(k, n)
    assert a.within_ci95[0] == pytest.approx(max(lo, 0.0), abs=1e-12)
    assert a.within_ci95[1] == pytest.approx(min(hi, 1.0), abs=1e-12)
    assert a.same_ci95 == pytest.approx(wilson_closed_form(n, n)[:1] + (1.0,), abs=1e-12)


def test_no_throws_at_all():
    a = agreement(answers([], [], []), answers([], [], []), label="empty")
    assert (a.n, a.compared, a.same, a.rests, a.within) == (0, 0, 0, 0, 0)
    assert math.isnan(a.same_rate) and math.isnan(a.within_rate)
    assert a.same_ci95 == (0.0, 1.0) and a.within_ci95 == (0.0, 1.0)
    assert "| empty | 0 | 0 / 0 | 0 | — | 0 | — |" in a.table()
    d = a.to_dict()
    assert d["same_rate"] is None and d["within_rate"] is None
    json.dumps(d, allow_nan=False)


def test_every_throw_refused_compares_nothing():
    n = len(REFUSED)
    model = answers(list(REFUSED), [-1] * n, [math.nan] * n)
    ref = answers([C.OK] * n, [0] * n, [0.1] * n)
    a = agreement(model, ref)
    assert (a.refused_model, a.refused_reference, a.compared) == (n, 0, 0)
    assert math.isnan(a.same_rate) and a.same_ci95 == (0.0, 1.0)
    both = agreement(model, model)
    assert (both.refused_model, both.refused_reference, both.refused_both, both.compared) == (n, n, n, 0)


def test_nothing_at_rest_alike_leaves_the_position_share_undefined():
    a = agreement(answers([C.OFF_END, C.OK], [-1, 0], [math.nan, 0.1]),
                  answers([C.OFF_END, C.OK], [-1, 1], [math.nan, 0.1]))
    assert a.compared == 2 and a.same == 1 and a.rests == 0
    assert a.same_rate == 0.5 and math.isnan(a.within_rate) and a.within_ci95 == (0.0, 1.0)


def test_round_trip_table_and_figure():
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    rows = (agreement(answers([0, 0, 1], [0, 0, -1], [0.1, 0.2, 0.0]), answers([0, 0, 1], [0, 0, -1], [0.1, 0.3, 0.0]),
                      label="a"),
            agreement(answers([9, 0], [0, 0], [0.1, 0.2]), answers([0, 0], [0, 0], [0.1, 0.2]), label="b", tol=1e-3))
    t = AgreementTable(rows, "engine")
    back = AgreementTable.from_dict(json.loads(json.dumps(t.to_dict(), allow_nan=False)))
    assert back == t and back.table() == t.table()
    assert t.to_dict()["definition"].startswith("refused throws")
    assert "| a | 3 | 0 / 0 | 3 | 100.0 [43.9, 100.0] | 2 | 50.0 [9.5, 90.5] |" in t.table()
    assert "0.5/1 mm" in t.table()  # two tolerances in one table
    assert t.row("b").refused_model == 1
    with pytest.raises(InvalidStateError, match="^label: no row 'c'"):
        t.row("c")
    assert isinstance(t.plot(), Figure) and isinstance(rows[0].plot(), Figure)
    assert isinstance(AgreementTable((), "engine").plot(), Figure)


def test_bad_input_names_the_field():
    with pytest.raises(InvalidStateError, match="^reference"):
        agreement(answers([0, 0], [0, 0], [0, 0]), answers([0], [0], [0]))
    with pytest.raises(InvalidStateError, match="^tol"):
        agreement(answers([0], [0], [0]), answers([0], [0], [0]), tol=-1.0)
    with pytest.raises(InvalidStateError, match="^agreement.compared"):
        Agreement("x", 3, 1, 1, 0, 3, 0, 0, 0)
    with pytest.raises(InvalidStateError, match="^agreement.within"):
        Agreement("x", 3, 0, 0, 0, 3, 1, 2, 0)
    with pytest.raises(InvalidStateError, match="^rows"):
        AgreementTable(({"label": "x"},))


statuses = st.sampled_from([C.OK, C.OK, C.OK, C.OFF_END, C.BEHIND_JOINT, *REFUSED])


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(statuses, statuses, st.integers(0, 2), st.integers(0, 2),
                          st.floats(0, 1e-3), st.floats(0, 1e-3)), max_size=40))
def test_counts_are_consistent_and_symmetric(rows):
    model = answers([r[0] for r in rows], [r[2] for r in rows], [r[4] for r in rows])
    ref = answers([r[1] for r in rows], [r[3] for r in rows], [r[5] for r in rows])
    a, b = agreement(model, ref), agreement(ref, model)
    refused = np.isin(model["status"], REFUSED) | np.isin(ref["status"], REFUSED)
    assert a.compared == int((~refused).sum())
    assert 0 <= a.within <= a.rests <= a.same <= a.compared <= a.n == len(rows)
    # swapping model and reference swaps the refusal columns and changes no share
    assert (a.same, a.rests, a.within) == (b.same, b.rests, b.within)
    assert (a.refused_model, a.refused_reference) == (b.refused_reference, b.refused_model)


def test_goals_read_the_one_statistic_and_are_never_met_on_nothing():
    """Escapes that end far apart agree on the outcome but say nothing of the position; with no same-outcome
    rest there is no position goal, and with nothing compared no goal is met."""
    from throwmap.studies.agreement import goals

    esc = agreement(answers([C.OFF_END], [-1], [0.44]), answers([C.OFF_END], [-1], [0.39]))
    g = goals(esc, "wall")
    assert list(g) == ["wall: same outcome"] and g["wall: same outcome"]["met"] and g["wall: same outcome"]["n"] == 1
    none = agreement(answers([C.UNRESOLVED], [-1], [math.nan]), answers([C.OK], [0], [0.3]))
    g = goals(none, "x")
    assert not g["x: same outcome"]["met"] and g["x: same outcome"]["n"] == 0
    rest = agreement(answers([C.OK, C.OK], [0, 0], [0.3, 0.3]), answers([C.OK, C.OK], [0, 0], [0.3, 0.302]))
    g = goals(rest, "r")
    pos = g["r: |Δx| ≤ 0.5 mm (same-outcome rests)"]
    assert pos["value"] == 50.0 and not pos["met"] and pos["n"] == 2
    assert pos["ci95"] == pytest.approx([100 * v for v in wilson_closed_form(1, 2)])
