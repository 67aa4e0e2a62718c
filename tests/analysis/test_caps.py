"""The recurrence caps as one value (:class:`RecurrenceCaps`), and the old keywords that still set them.

Synthetic maps keep these fast; the caps reach the recurrence test either way
(``caps=RecurrenceCaps(...)`` or ``transient=...``) and must give the same result.
"""

from __future__ import annotations

import ast
import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from throwmap.analysis import FunctionMap, RecurrenceCaps, basins, limit_set
from throwmap.analysis.caps import DEFAULT_CAPS, check_caps
from throwmap.analysis.recurrence import Recurrence, find_attractors, start_grid
from throwmap.errors import InvalidStateError

ANALYSIS = Path(__file__).resolve().parents[2] / "src" / "throwmap" / "analysis"


def _ok(x):
    return np.zeros(x.size, dtype=np.int64)


def contraction(a=0.4, k=0.5):
    return FunctionMap(lambda x, s: (a + k * (x - a), s, _ok(x)), {0: (0.0, 1.0)}, name="contraction")


def tent(slope=1.9):
    return FunctionMap(lambda x, s: (slope * np.minimum(x, 1.0 - x), s, _ok(x)), {0: (0.0, 1.0)}, name="tent")


def test_defaults_are_the_documented_ones():
    c = RecurrenceCaps()
    assert (c.transient, c.max_transient, c.n_record, c.tol, c.max_period) == (200, 5000, 400, 1e-8, 32)
    assert (c.cell, c.band_gap, c.fd_step, c.n_fill, c.fill_rounds) == (1e-3, 2e-3, 1e-6, 2000, 2)
    assert c.to_dict() == DEFAULT_CAPS == check_caps()
    assert list(DEFAULT_CAPS) == [f.name for f in dataclasses.fields(RecurrenceCaps)]


def test_caps_are_frozen_and_round_trip_through_json():
    c = RecurrenceCaps(transient=np.int64(50), n_record=80, tol=1, cell=2e-3)
    assert type(c.transient) is int and type(c.tol) is float  # coerced once, JSON-ready
    with pytest.raises(dataclasses.FrozenInstanceError):
        c.transient = 3
    d = json.loads(json.dumps(c.to_dict()))
    assert RecurrenceCaps.from_dict(d) == c
    assert RecurrenceCaps.from_dict({**d, "transient_used": 1234}) == c  # a result's record reads back


@pytest.mark.parametrize("caps, field", [
    ({"transient": -1}, "transient"), ({"transient": 1.5}, "transient"),
    ({"n_record": 10, "max_period": 8}, "n_record"), ({"max_period": 0}, "max_period"),
    ({"tol": 0.0}, "tol"), ({"tol": math.nan}, "tol"), ({"cell": math.inf}, "cell"),
    ({"band_gap": "2e-3"}, "band_gap"), ({"fd_step": True}, "fd_step"),
    ({"max_transient": 10, "transient": 20}, "max_transient"), ({"n_fill": -1}, "n_fill"),
    ({"fill_rounds": None}, "fill_rounds"),
])
def test_the_dataclass_refuses_what_check_caps_refuses_with_the_same_line(caps, field):
    with pytest.raises(InvalidStateError) as built:
        RecurrenceCaps(**caps)
    assert built.value.field == field and "\n" not in str(built.value)
    if None not in caps.values():  # as a keyword, None means "the default"
        with pytest.raises(InvalidStateError) as checked:
            check_caps(**caps)
        assert str(checked.value) == str(built.value)


def test_replace_keeps_none_and_refuses_unknown_names():
    c = RecurrenceCaps(transient=50)
    assert c.replace(transient=None, n_record=None) is c
    assert c.replace(n_record=80) == RecurrenceCaps(transient=50, n_record=80)
    with pytest.raises(InvalidStateError) as err:
        c.replace(max_throw=3)
    assert err.value.field == "max_throw" and "transient" in str(err.value) and "\n" not in str(err.value)


def test_caps_value_and_keywords_give_the_same_limit_set():
    by_value = limit_set(tent(), caps=RecurrenceCaps(transient=50, n_record=80, n_fill=300))
    by_keyword = limit_set(tent(), transient=50, n_record=80, n_fill=300)
    mixed = limit_set(tent(), caps=RecurrenceCaps(transient=50), n_record=80, n_fill=300)
    as_mapping = limit_set(tent(), caps={"transient": 50, "n_record": 80, "n_fill": 300})
    assert by_value.to_dict() == by_keyword.to_dict() == mixed.to_dict() == as_mapping.to_dict()
    default = limit_set(tent())
    assert default.recurrence_caps == RecurrenceCaps()
    assert by_value.to_dict() != default.to_dict()  # the caps did reach the test
    assert by_value.recurrence_caps == RecurrenceCaps(transient=50, n_record=80, n_fill=300)
    assert by_value.transient_used == by_value.caps["transient_used"] >= 50


def test_keyword_override_wins_over_the_caps_value():
    ls = limit_set(contraction(), caps=RecurrenceCaps(transient=50), transient=70)
    assert ls.caps["transient"] == 70


def test_unknown_keywords_are_refused_naming_them(triangle, arm):
    with pytest.raises(InvalidStateError) as err:
        limit_set(contraction(), max_throw=3)  # a map given as the part takes no throw options
    assert err.value.field == "max_throw" and "\n" not in str(err.value)
    with pytest.raises(InvalidStateError) as err:
        basins(contraction(), grid=20, n_recrod=80)
    assert err.value.field == "n_recrod"
    with pytest.raises(InvalidStateError) as err:  # with a part, the throw refuses what it does not know
        limit_set(triangle, arm, 4.0, "paper", n_starts=1, transient=2, n_record=64, max_throw=3)
    assert err.value.field == "max_throw"
    with pytest.raises(InvalidStateError) as err:
        limit_set(contraction(), caps=5)
    assert err.value.field == "caps"


def test_basins_take_the_caps_value_like_the_keywords():
    a = basins(tent(), grid=60, method="orbits", caps=RecurrenceCaps(transient=50, n_record=80))
    b = basins(tent(), grid=60, method="orbits", transient=50, n_record=80)
    assert a.to_dict() == b.to_dict()
    assert a.caps["transient"] == 50 and a.caps["n_record"] == 80


def test_find_attractors_knows_nothing_of_limit_sets():
    x0, s0 = start_grid(contraction(), 10, 0)
    rec = find_attractors(contraction(), x0, s0, RecurrenceCaps(transient=30, n_record=64))
    assert isinstance(rec, Recurrence)
    (fp,) = rec.attractors
    assert fp.kind == "fixed_point" and fp.points[0][1] == pytest.approx(0.4, abs=1e-8)
    assert np.all(rec.labels == 1) and np.all(rec.fates == 0)
    assert rec.x_tail.shape == (10, 64) and rec.transient_used >= 30
    # the module imports none of the results built on it
    tree = ast.parse((ANALYSIS / "recurrence.py").read_text(encoding="utf-8"))
    imported = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.module}
    assert imported and not imported & {"limitset", "basins", "funnels", "critical", "cellmap", "sets"}


def test_every_analysis_module_is_at_most_500_lines():
    sizes = {p.name: len(p.read_text(encoding="utf-8").splitlines()) for p in ANALYSIS.glob("*.py")}
    assert "recurrence.py" in sizes and "limitset.py" in sizes and "cellmap.py" in sizes
    assert {k: n for k, n in sizes.items() if n > 500} == {}
