"""Orbits on a limit set, for drawing (throwmap.analysis.orbits; paper Fig. 5)."""

from __future__ import annotations

import numpy as np

import throwmap as tm
from throwmap.analysis import limit_set
from throwmap.analysis.orbits import ORBIT_THROWS, orbit_on_attractor


def test_orbit_on_attractor_lies_on_the_limit_set():
    part, arm = tm.triangle_30_60_90(0.17), tm.Arm(-0.01)
    limit = limit_set(part, arm, 4.0, "paper", n_starts=8, n_record=64, transient=50)
    orbit = orbit_on_attractor(part, arm, 4.0, "paper", limit)
    assert orbit.n_throws == ORBIT_THROWS and not orbit.escaped
    (a,) = limit.attractors
    assert np.all(a.contains(orbit.x, orbit.side, tol=5e-3))
