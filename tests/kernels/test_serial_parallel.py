"""Serial twins of the batch kernels give the same results as the parallel ones (issue 10, item 2 "Threads").

Small batches run on the calling thread (waking Numba's pool cost 108 ms against
3.7 ms serial under load); the choice must never change an answer.
"""

import numpy as np
import pytest

import throwmap as tm
from throwmap.kernels import codes as C
from throwmap.kernels import paper as P
from throwmap.kernels import rigid_body as RB
from throwmap.kernels import small_angle as S


def _starts(part, n=300, seed=1):
    rng = np.random.default_rng(seed)
    stable = np.flatnonzero(part.stable)
    side = rng.choice(stable, n).astype(np.int64)
    x = -part.uL[side] + rng.uniform(-0.01, 0.5, n)  # some starts invalid (behind the joint)
    om = rng.uniform(0.0, 9.0, n)
    valid = x + part.uL[side] > 0
    return x, side, om, valid


def _out(n):
    return np.empty(n), np.empty(n, np.int64), np.empty(n, np.int64), np.empty((n, C.NREC))


def _same(a, b):
    for u, v in zip(a, b):
        np.testing.assert_array_equal(u, v)  # identical, NaNs included


@pytest.mark.parametrize("mu", [np.inf, 0.5, 0.0])
def test_rigid_body_serial_equals_parallel(triangle, mu):
    arm = tm.Arm(h=-0.01, length=0.6)
    x, side, om, valid = _starts(triangle)
    args = (x, side, om, valid, RB.part_arrays(triangle),
            RB.arm_arrays(arm.h, arm.g, 0.0, arm.length_or_inf, 0.0, mu, RB.LAW_ROUTH), RB.run_limits(1e-14, 100_000, 10_000))
    for par, ser in ((RB.throw_many_rigid_body, RB.throw_many_rigid_body_serial),
                     (RB.throw_many_rigid_body_rk4, RB.throw_many_rigid_body_rk4_serial)):
        a, b = _out(x.size), _out(x.size)
        par(*args, *a)  # no wall, as the model passes it
        ser(*args, *b)
        _same(a, b)
        assert np.all(a[2][~valid] == C.INVALID_START)


def test_paper_serial_equals_parallel(triangle):
    arm = tm.Arm(h=-0.01)
    x, side, om, valid = _starts(triangle, n=700)  # several chunks of CHUNK throws
    args = (x, side, om, valid, arm.h, arm.g, 0.0, arm.length_or_inf, 0.0, triangle.radius_of_gyration**2,
            triangle.w, triangle.beta, triangle.d, triangle.uL, triangle.uR, triangle.ell, triangle.stable, 1e-14, 100_000,
            10_000, 16)
    a, b = _out(x.size), _out(x.size)
    P.throw_many(*args, *a)
    P.throw_many_serial(*args, *b)
    _same(a, b)


@pytest.mark.parametrize("order", [1, 2])
def test_small_angle_serial_equals_parallel(triangle, order):
    arm = tm.Arm(h=-0.01)
    x, side, om, valid = _starts(triangle)
    args = (x, side, om, valid, arm.h, arm.g, arm.length_or_inf, 0.0, triangle.radius_of_gyration**2, triangle.d,
            triangle.uL, triangle.uR, triangle.ell, triangle.length, triangle.stable, order)
    a, b = _out(x.size), _out(x.size)
    S.throw_many_small_angle(*args, *a)
    S.throw_many_small_angle_serial(*args, *b)
    _same(a, b)


def test_batch_size_picks_the_kernel():
    assert RB.pick(RB.PARALLEL_MIN - 1) is RB.throw_many_rigid_body_serial
    assert RB.pick(RB.PARALLEL_MIN) is RB.throw_many_rigid_body
    assert RB.pick(1, rk4=True) is RB.throw_many_rigid_body_rk4_serial
    assert 1 <= RB.PARALLEL_MIN <= P.PARALLEL_MIN <= S.PARALLEL_MIN


@pytest.mark.parametrize("model", ["paper", "small_angle", "rigid_body"])
def test_model_batches_on_both_sides_of_the_threshold_agree(triangle, model, monkeypatch):
    """The same throws through the model layer, once forced serial and once forced parallel."""
    arm = tm.Arm(h=-0.01)
    k = int(np.flatnonzero(triangle.stable)[0])
    x = np.linspace(0.1, 0.5, 50)
    mod = {"paper": "throwmap.models.paper", "small_angle": "throwmap.models.small_angle",
           "rigid_body": "throwmap.kernels.rigid_body.batch"}[model]
    monkeypatch.setattr(mod + ".PARALLEL_MIN", 10**9)
    b1 = tm.throw_batch(triangle, arm, x, k, 6.0, model=model)
    monkeypatch.setattr(mod + ".PARALLEL_MIN", 1)
    b2 = tm.throw_batch(triangle, arm, x, k, 6.0, model=model)
    np.testing.assert_array_equal(b1.x, b2.x)
    np.testing.assert_array_equal(b1.status, b2.status)
    np.testing.assert_array_equal(b1.records, b2.records)
