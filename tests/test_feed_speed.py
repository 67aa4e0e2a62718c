"""The feed experiment's speedups change no result: the fast paths equal the plain ones bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from throwmap.engine.realisation import FiniteThrow, ImpulseThrow, RecoilThrow, TiltTo, angle_function


@pytest.mark.parametrize("omega", [2.0, 4.559824565181344, 7.3])
@pytest.mark.parametrize("zeta", [0.2, 0.5, 0.9])
def test_recoil_angle_function_is_bit_identical(omega, zeta):
    r = RecoilThrow.for_release_rate(omega, zeta=zeta)
    f = angle_function(r)
    ts = list(np.linspace(-1e-3, r.duration + 0.01, 4001))
    ts += [0.0, r.t_recoil, r.t_peak, r.t_peak + r.hold, r.duration]
    t = 0.0
    while t < r.duration + 1e-3:  # the run loop's own times: t += dt
        ts.append(t)
        t += 1.25e-4
    for t in ts:
        assert f(float(t)) == r.angle(float(t)), t


@pytest.mark.parametrize("r", [ImpulseThrow(3.0), FiniteThrow(4.0, 0.01), TiltTo(-0.1, 0.5)])
def test_other_realisations_keep_their_angle(r):
    f = angle_function(r)
    for t in np.linspace(-0.01, 0.5, 101):
        assert f(float(t)) == r.angle(float(t))
    assert math.isfinite(f(0.0))
