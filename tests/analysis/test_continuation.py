"""Continuation of limit sets: matching, events located against closed forms and dense scans, fractions against
a brute-force count, the physical parameters, and the command line."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

import throwmap as tm
from throwmap.analysis.attractors import Attractor
from throwmap.analysis.continuation import Resolution, continuation, system_at
from throwmap.analysis.maps import FunctionMap, ThrowMap
from throwmap.analysis.matching import match, set_distance
from throwmap.cli.app import app
from throwmap.errors import InvalidStateError
from throwmap.records.outcome import Status


def logistic(r):
    """x → r x (1 − x) on (0, 0.999]; an image outside (0, 1] leaves the arm. Fixed point 1 − 1/r with
    multiplier 2 − r: it doubles at r = 3; for r > 4 the orbits escape."""
    def f(x, side):
        y = r * x * (1 - x)
        ok = (y > 0) & (y <= 1)
        return np.where(ok, y, x), side, np.where(ok, 0, int(Status.OFF_END))

    return FunctionMap(f, {0: (0.0, 0.999)}, name=f"logistic r = {r:g}", deterministic=True)


def _att(ident, bands, kind="band", points=(), multiplier=math.nan):
    return Attractor(ident, kind, len(points) if kind != "band" else 0, tuple(points), tuple(bands), multiplier,
                     math.nan, 0.5, ())


def test_set_distance_and_the_changes_a_matching_names():
    a = _att(1, [(0, 0.10, 0.20), (1, 0.30, 0.40)])
    b = _att(2, [(0, 0.11, 0.22)])
    assert set_distance(a, b) == pytest.approx(0.02) and set_distance(a, _att(3, [(2, 0.1, 0.2)])) == math.inf
    far = _att(4, [(0, 0.50, 0.55)])
    to_before, changes = match([a, far], [b], 0.03)
    assert to_before == {0: 0} and [c.kind for c in changes] == ["vanish"]
    to_before, changes = match([a], [b, _att(5, [(0, 0.12, 0.21)])], 0.03)  # two near one: a split
    assert to_before == {0: 0} and [(c.kind, c.before, c.after) for c in changes] == [("split", (0,), (0, 1))]
    to_before, changes = match([a, _att(6, [(0, 0.12, 0.21)])], [b], 0.03)
    assert to_before == {0: 1} and [(c.kind, c.before, c.after) for c in changes] == [("merge", (0, 1), (0,))]
    to_before, changes = match([far], [b], 0.03, forced=[(0, 0)])  # a doubling pairs whatever the distance
    assert to_before == {0: 0} and changes == []
    # a band that takes in two far apart (a crisis): the larger continues (a jump), the other merged into it
    big = _att(7, [(0, 0.10, 0.55)])
    small = _att(8, [(0, 0.48, 0.54)]).with_fraction(0.1)
    a0 = _att(9, [(0, 0.10, 0.20)])
    to_before, changes = match([a0, small], [big], 0.03)
    assert to_before == {0: 0} and sorted((c.kind, c.before) for c in changes) == [("jump", (0,)), ("merge", (1, 0))]
    to_before, changes = match([big], [a0, small], 0.03)  # and back: a jump and a split
    assert to_before == {0: 0} and sorted((c.kind, c.after) for c in changes) == [("jump", (0,)), ("split", (0, 1))]


def test_the_logistic_family_doubles_at_three_and_escapes_past_four():
    """Closed forms: the fixed point 1 − 1/r doubles where its multiplier 2 − r is −1 (r = 3); past r = 4 the map
    leaves (0, 1]. Both located to the tolerance; no other event."""
    res = Resolution(starts=100, tol=1e-3)
    c = continuation(logistic, None, "r", np.linspace(2.8, 3.2, 9), resolution=res)
    assert [e.kind for e in c.events] == ["period_doubling"]
    e = c.events[0]
    assert e.tol <= 1e-3 and abs(e.value - 3.0) <= e.tol + 1e-9
    for p in c.at_grid():
        (a,) = p.attractors
        if p.value < 2.99:
            assert a.kind == "fixed_point" and a.points[0][1] == pytest.approx(1 - 1 / p.value, abs=1e-6)
        elif p.value > 3.01:
            assert a.kind == "cycle" and a.period == 2 and a.id == 1
    c = continuation(logistic, None, "r", np.linspace(3.9, 4.1, 5), resolution=res)
    onset = [e for e in c.events if e.kind == "escape_onset"]
    assert len(onset) == 1 and 4.0 - 1e-9 <= onset[0].value + onset[0].tol and onset[0].value - onset[0].tol <= 4.0 + 2e-3
    assert c.at_grid()[-1].escape_fraction == 1.0


@pytest.fixture(scope="module")
def tri_paper():
    tri = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=-0.01)
    c = continuation(tri, arm, "omega", np.linspace(4.36, 4.44, 3), model="paper",
                     resolution=Resolution(starts=60, horizon=300))
    return tri, arm, c


def _brute_escape(tri, arm, omega, starts, horizon):
    """The share of the grid's starts that leave the arm within ``horizon`` throws, by iterating the map."""
    cmap = ThrowMap(tri, arm, omega, "paper")
    xs, ss = [], []
    for s in cmap.sides:
        lo, hi = cmap.domain()[s]
        x = np.linspace(lo, hi, starts + 1)[1:]
        xs.append(x)
        ss.append(np.full(x.size, s))
    x, s = np.concatenate(xs), np.concatenate(ss)
    alive = np.ones(x.size, dtype=bool)
    for _ in range(horizon):
        i = np.flatnonzero(alive)
        if i.size == 0:
            break
        xn, sn, st = cmap(x[i], s[i])
        ok = st == 0
        alive[i[~ok]] = False
        x[i[ok]], s[i[ok]] = xn[ok], sn[ok]
    return 1.0 - alive.mean()


def test_escape_shares_equal_a_brute_force_count_and_the_onset_a_dense_scan(tri_paper):
    tri, arm, c = tri_paper
    res = c.resolution
    for p in c.at_grid():
        assert p.escape_fraction == pytest.approx(_brute_escape(tri, arm, p.value, res.starts, res.horizon), abs=1e-12)
        assert sum(a.fraction for a in p.attractors) + p.escape_fraction + p.unresolved_fraction == pytest.approx(1.0)
    (onset,) = [e for e in c.events if e.kind == "escape_onset"]
    assert onset.tol <= res.tol
    below, above = onset.value - onset.tol, onset.value + onset.tol
    assert _brute_escape(tri, arm, below, res.starts, res.horizon) == 0
    assert _brute_escape(tri, arm, above, res.starts, res.horizon) > 0
    # a dense scan at the tolerance's step finds no escape before the located onset
    for w in np.arange(4.36, below, 0.005):
        assert _brute_escape(tri, arm, float(w), res.starts, res.horizon) == 0


def test_the_json_has_the_documented_keys(tri_paper):
    doc = json.loads(json.dumps(tri_paper[2].to_dict(), allow_nan=False))
    assert {"param", "points", "events", "range"} <= set(doc) and doc["param"] == "omega"
    for p in doc["points"]:
        assert {"value", "escape_fraction", "attractors"} <= set(p)
        for a in p["attractors"]:
            assert {"id", "kind", "sides", "x", "fraction"} <= set(a) and a["x"][0] <= a["x"][1]
    for e in doc["events"]:
        assert set(e) >= {"kind", "value", "tol"}


def test_the_weight_moves_and_bad_parameters_are_refused():
    tri = tm.triangle_30_60_90(0.17)
    part = tm.Part.from_vertices(tri.vertices, 0.05, point_masses=((0.03, (0.03, 0.02)),))
    moved = system_at(part, tm.Arm(h=-0.01), 4.0, "weight_x", 0.05, {})[0]
    assert moved.point_masses[0][1] == (0.05, 0.02) and moved.mass == pytest.approx(part.mass)
    assert moved.com[0] > part.com[0]
    with pytest.raises(InvalidStateError, match=r"^weight_x: .*puts the lead weight"):
        system_at(part, tm.Arm(h=-0.01), 4.0, "weight_x", 0.5, {})
    with pytest.raises(InvalidStateError, match=r"^weight_y: .*no lead weight"):
        continuation(tri, tm.Arm(h=-0.01), "weight_y", [0.01, 0.02], omega=4.0, model="paper")
    with pytest.raises(InvalidStateError, match=r"^param: must be one of omega, h"):
        continuation(tri, tm.Arm(h=-0.01), "speed", [1, 2], omega=4.0)
    with pytest.raises(InvalidStateError, match=r"^values: must be ≥ 2 finite values in ascending order"):
        continuation(tri, tm.Arm(h=-0.01), "omega", [4.0, 3.0])
    with pytest.raises(InvalidStateError, match=r"^omega: a release rate"):
        continuation(tri, tm.Arm(h=-0.01), "h", [-0.02, -0.01])
    with pytest.raises(InvalidStateError, match=r"^tol: must be a number > 0"):
        Resolution(tol=0)
    with pytest.raises(InvalidStateError, match=r"^param: mu: model 'paper' does not use the arm's friction"):
        continuation(tri, tm.Arm(h=-0.01), "mu", [0.3, 1.0], omega=4.0, model="paper")
    bad = FunctionMap(lambda x, s: (x, s, np.array(["ok"] * x.size)), {0: (0.0, 1.0)})
    with pytest.raises(InvalidStateError, match=r"^status: f must return integer status codes"):
        continuation(lambda r: bad, None, "r", [1.0, 2.0])


def test_the_command_line_prints_json_and_draws(tmp_path):
    runner = CliRunner()
    fig = tmp_path / "c.png"
    r = runner.invoke(app, ["continuation", "--part", "triangle", "--h", "-0.01", "--model", "paper", "--param", "h",
                            "--from", "-0.012", "--to", "-0.008", "--n", "3", "--omega", "4.0", "--starts", "20",
                            "--json", "--plot", str(fig)])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["param"] == "h" and len([p for p in doc["points"] if not p["refined"]]) == 3
    assert fig.stat().st_size > 10_000
    r = runner.invoke(app, ["continuation", "--part", "triangle", "--h", "-0.01", "--param", "speed", "--from", "1",
                            "--to", "2"])
    assert r.exit_code == 2 and "error: param: must be one of" in r.output
    r = runner.invoke(app, ["continuation", "--part", "triangle", "--h", "-0.01", "--param", "omega", "--from", "nan",
                            "--to", "5"])
    assert r.exit_code == 2 and r.stderr.strip() == "error: from: must be a finite number, got nan"


def test_the_margin_to_escape_is_the_distance_to_the_located_onset(tri_paper):
    """At ω = 4.36 the onset (≈ 4.42 rad/s on this grid of starts) is within ± 0.1: the margin is the distance to
    it; at ω = 4.0 it is beyond ± 0.1: no number, the span is stated instead."""
    from throwmap.analysis.continuation import Resolution as R
    from throwmap.analysis.margins import margin

    tri, arm, c = tri_paper
    res = R(starts=60, horizon=300)
    m = margin(tri, arm, "omega", 4.36, span=0.1, model="paper", n=5, resolution=res)
    e = m.escape
    assert e is not None and e.kind == "escape_onset" and m.escape_distance == pytest.approx(e.value - 4.36)
    # a true edge of escape (the chaotic band lets single starts escape in windows: the edge found is the first
    # one that the grid of values brackets)
    assert _brute_escape(tri, arm, e.value - e.tol, res.starts, res.horizon) == 0
    assert _brute_escape(tri, arm, e.value + e.tol, res.starts, res.horizon) > 0
    far = margin(tri, arm, "omega", 4.0, span=0.1, model="paper", n=3, resolution=res)
    assert far.escape is None and math.isinf(far.escape_distance) and "none within [3.9, 4.1]" in far.text()
