"""Funnel mouths stop at the searched range, and an edge counts only the spout inside the mouth (issue 10).

On the canonical triangle (x ≤ 1.0 m), ω=3 #2 → ω=4 #1 was reported 100 % although that
spout (1.05–1.29 m) lies beyond the mouth, which ends at 1.00 m, and mouths ran past
x_max (to 1.0011 m, half a grid cell). Synthetic maps reproduce both in closed form.
"""

from __future__ import annotations

import numpy as np
import pytest

from throwmap.analysis import FunctionMap, basins, funnels
from throwmap.analysis.funnels import mouth_of


def _ok(x):
    return np.zeros(x.size, dtype=np.int64)


def to(a, name, k=0.5):
    """Contracts every x (searched on (0, 1]) to a: its basin holds every start, even beyond the range."""
    return FunctionMap(lambda x, s: (a + k * (x - a), s, _ok(x)), {0: (0.0, 1.0)}, name=name)


def two_cycle_across_the_end(c0=0.8, c1=1.2, name="straddle"):
    """Every x goes to the 2-cycle c0 ↔ c1 on side 0; c1 lies beyond the searched range (0, 1]."""
    def f(x, s):
        near0 = np.abs(x - c0) <= np.abs(x - c1)
        return np.where(near0, c1 + 0.5 * (x - c0), c0 + 0.5 * (x - c1)), s, _ok(x)
    return FunctionMap(f, {0: (0.0, 1.0)}, name=name)


def test_a_mouth_never_extends_past_the_searched_range():
    b = basins(to(0.5, "B"), grid=50, n_seeds=4)
    mouth = mouth_of(b, 1)
    assert mouth.intervals[0][2] == pytest.approx(1.0, abs=1e-15)  # not 1.0 + half a cell
    assert mouth.intervals[0][1] >= 0.0
    assert not mouth.contains(1.005, 0)


def test_a_spout_beyond_the_range_is_in_no_mouth():
    """A's fixed point 1.2 lies beyond B's searched range; B's map would take it home, but B's mouth ends at 1.0."""
    fg = funnels(None, maps=[to(1.2, "A"), to(0.5, "B")], grid=100, containment=0.01)
    names = [f.name for f in fg.funnels]
    ia, ib = names.index("A #1"), names.index("B #1")
    assert fg.funnels[ia].spout.intervals[0][1] == pytest.approx(1.2)
    assert all(e[:2] != (ia, ib) for e in fg.edges), fg.table()
    assert any(e[:2] == (ib, ia) and e[2] == 1.0 for e in fg.edges)  # 0.5 is in A's mouth (all of (0, 1])


def test_an_edge_counts_only_the_part_of_the_spout_inside_the_mouth():
    """The 2-cycle {0.8, 1.2}: half of its points lie in B's mouth (0, 1], so the share is one half."""
    fg = funnels(None, maps=[two_cycle_across_the_end(), to(0.5, "B")], grid=100, containment=0.4)
    ia = next(i for i, f in enumerate(fg.funnels) if f.name.startswith("straddle"))
    ib = next(i for i, f in enumerate(fg.funnels) if f.name == "B #1")
    (share,) = [e[2] for e in fg.edges if e[:2] == (ia, ib)]
    assert share == pytest.approx(0.5)
    strict = funnels(None, maps=[two_cycle_across_the_end(), to(0.5, "B")], grid=100)  # containment 1
    assert all(e[:2] != (ia, ib) for e in strict.edges)
