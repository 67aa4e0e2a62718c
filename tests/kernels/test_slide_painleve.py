"""A sliding pivot that meets D = 0 exactly (the Painlevé boundary of ``slide_rhs``) is a refused
throw (``inconsistent``), never a ZeroDivisionError out of the compiled kernel.

Found by a random design search (issue 11): a 30-60-90 plexiglas triangle with 30 g of lead,
thrown from 3.5 m on side 1 at ω = 6.24 rad/s, h = −4.19 cm.
"""

import math
import warnings

import numpy as np

from throwmap import Part, throw, throw_batch
from throwmap.kernels.rigid_body.slide import slide_rhs
from throwmap.system.arm import Arm
from throwmap.records.outcome import Status

PART = Part.from_vertices(((0.14722431864335458, 0.0), (0.0, 0.085), (0.0, 0.0)), mass=0.04728127396271163,
                          point_masses=((0.03, (0.08687472106326836, 0.011300485154194025)),))
ARM = Arm(h=-0.04188266582814847, mu=1.0)
X, SIDE, OMEGA = 3.506321439199996, 1, 6.241562609189007


def test_slide_rhs_at_d_zero_returns_nan_and_zero_d():
    # θ with c·(c + μσ s) = −ρ²/ℓ²: pick ℓ = ρ = 1, μσ = 0 → c² = −1 impossible; use μσ so that D = 0 at θ = 3π/4
    th = 3 * math.pi / 4
    c, s = math.cos(th), math.sin(th)
    musig = (-1.0 / c - c) / s  # 1 + c (c + μσ s) = 0 with ℓ = ρ = 1
    thdd, xdd, n, d = slide_rhs(th, 1.0, 1.0, 1.0, 9.81, musig, 0.0)
    assert abs(1.0 + c * (c + musig * s)) < 1e-12
    if d == 0.0:
        assert math.isnan(thdd) and math.isnan(xdd) and math.isnan(n)
    else:  # rounding left D a hair off zero: a finite (huge) force, still no exception
        assert abs(d) < 1e-12


def test_throw_at_painleve_boundary_is_refused_not_raised():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out = throw(PART, ARM, X, SIDE, OMEGA, "rigid_body")
        batch = throw_batch(PART, ARM, np.array([X, 0.2]), SIDE, OMEGA, "rigid_body", on_invalid="status")
    assert out.status != Status.OK
    assert int(batch.status[0]) == int(out.status)
    assert int(batch.status[1]) == int(Status.OK)  # the rest of the batch is still thrown
