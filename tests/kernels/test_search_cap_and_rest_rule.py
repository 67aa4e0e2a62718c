"""A search cap is a refusal (UNRESOLVED + cap_hit), never NO_CONTACT; tol is bounded;
the kernels' rests obey the start rule (both support vertices on the arm)."""

import json
import subprocess
import sys

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.kernels import codes as C
from throwmap.records.outcome import Status, ThrowOutcome
from throwmap.system.starts import start_interval

PART = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01)


@pytest.mark.parametrize("model, max_iter", [("paper", 1), ("paper", 3), ("rigid_body", 1), ("rigid_body", 2),
                                             ("rigid_body", 5)])
def test_search_cap_is_unresolved_not_no_contact(model, max_iter):
    o = tm.throw(PART, ARM, 0.2, 0, 4.0, model=model, max_iter=max_iter)
    assert o.status == Status.UNRESOLVED and o.cap_hit
    back = ThrowOutcome.from_dict(o.to_dict())
    assert back.cap_hit and back.status == Status.UNRESOLVED
    assert "max_iter" in o.message and f"reason: {o.message}" in o.table() and "none resolved" in o.table()


def test_unresolved_says_why_and_other_statuses_say_nothing():
    o = tm.throw(PART, ARM, 2e8, 0, 1e6, model="rigid_body")
    assert o.status == Status.UNRESOLVED and not o.cap_hit and "spin angle" in o.message
    o = tm.throw(PART, ARM, 0.2, 0, 4.0)
    assert o.ok and o.message == "" and "reason" not in o.table()
    d = o.to_dict()
    del d["message"], d["cap_hit"]  # JSON written before these fields existed
    old = ThrowOutcome.from_dict(d)
    assert old.message == "" and not old.cap_hit and old.x == o.x


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
def test_search_cap_batch_matches_single_and_flags_cap(model):
    x = np.linspace(0.1, 5, 40)
    om = np.linspace(1, 50, 40)
    b = tm.throw_batch(PART, ARM, x, 0, om, model=model, max_iter=3)
    assert not np.any(b.status == Status.NO_CONTACT)
    assert np.all(b.status == Status.UNRESOLVED) and np.all(b.record("CAP_HIT") == 1.0)
    for i in (0, 17, 39):
        o = tm.throw(PART, ARM, x[i], 0, om[i], model=model, max_iter=3)
        assert o.status == b.status[i] and o.cap_hit


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
def test_default_cap_not_hit(model):
    o = tm.throw(PART, ARM, 0.2, 0, 4.0, model=model)
    assert o.ok and not o.cap_hit
    b = tm.throw_batch(PART, ARM, np.linspace(0.1, 1.0, 20), 0, 4.0, model=model)
    assert np.all(b.record("CAP_HIT") == 0.0)


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
@pytest.mark.parametrize("tol", [1e300, 1.0, 1e-3, 0.0, -1e-14])
def test_tol_bounded(model, tol):
    with pytest.raises(InvalidStateError, match="tol"):
        tm.throw(PART, ARM, 0.2, 0, 4.0, model=model, tol=tol)


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
def test_tol_at_bound_accepted(model):
    assert tm.throw(PART, ARM, 0.2, 0, 4.0, model=model, tol=1e-6).ok


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "throwmap", *args], capture_output=True, text=True, timeout=300)


def test_cli_max_iter_and_tol():
    base = ["throw", "--part", "triangle", "--h", "-0.01", "--x", "0.2", "--side", "0", "--omega", "4",
            "--model", "paper"]
    r = _cli(*base, "-O", "max_iter=1", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["status"] == "unresolved" and d["cap_hit"] is True and "max_iter" in d["message"]
    r = _cli(*base, "-O", "tol=1e300")
    assert r.returncode == 2 and "tol" in r.stderr and "Traceback" not in r.stderr


@pytest.mark.parametrize("model", ["paper", "rigid_body", "small_angle"])
def test_ok_rests_have_both_support_vertices_on_the_arm(model):
    """Throws that rest ok on an unbounded arm, rethrown on an arm ending between the CM and the right
    support vertex of that rest: the rest overhangs the end, so it must not be ok (engine.rest rule)."""
    rng = np.random.default_rng(20261123)
    n_checked = 0
    for _ in range(60):
        k = int(rng.choice(PART.stable_sides))
        lo, _ = start_interval(PART, ARM, k)
        x0 = lo + rng.uniform(0.01, 0.5)
        om = rng.uniform(2.0, 8.0)
        o = tm.throw(PART, ARM, x0, k, om, model=model)
        if not o.ok or o.x + float(PART.uR[o.side]) <= x0 + float(PART.uR[k]):
            continue  # need a rest whose right vertex is beyond the start's (so the start stays admissible)
        L = o.x + 0.5 * float(PART.uR[o.side]) if PART.uR[o.side] > 0 else o.x
        L = max(L, x0 + float(PART.uR[k]))
        arm = tm.Arm(h=-0.01, length=L)
        if not o.x + float(PART.uR[o.side]) > L:
            continue
        p = tm.throw(PART, arm, x0, k, om, model=model)
        n_checked += 1
        assert p.status != Status.OK, (x0, k, om, p)
    assert n_checked >= 5


@pytest.mark.parametrize("model, mu", [("paper", None), ("rigid_body", None), ("rigid_body", 0.3),
                                       ("rigid_body", 0.1), ("small_angle", None)])
def test_batch_ok_rests_inside_start_interval(model, mu):
    """Every ok rest on a bounded arm lies in start_interval (rigid_body at μ < ∞: after flat slides too)."""
    arm = tm.Arm(h=-0.01, length=0.45) if mu is None else tm.Arm(h=-0.01, length=0.45, mu=mu)
    rng = np.random.default_rng(7)
    x = rng.uniform(0.06, 0.40, 400)
    om = rng.uniform(1.0, 8.0, 400)
    b = tm.throw_batch(PART, arm, x, 1, om, model=model, on_invalid="status")
    for xi, ki in zip(b.x[b.ok], b.side[b.ok]):
        lo, hi = start_interval(PART, arm, int(ki))
        assert lo < xi <= hi
    assert C.CAP_HIT < C.NREC and C.NREC == C.WHY + 1  # the last column: the reason of a refusal
