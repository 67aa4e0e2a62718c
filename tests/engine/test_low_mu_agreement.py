"""Model "rigid_body" against the pymunk engine at low friction (μ = 0.3, 0.6) and at μ = 1.

At μ ≤ 0.6 many impacts stop their slip and cannot keep it stopped; there the
impact law decides (docstring of :mod:`throwmap.kernels.rigid_body.impact`):
rigid_body follows Routh's impulse-space process, pymunk a one-step velocity-level
impulse. Swapping only that reset for the velocity-level law brings the two within
0.45 mm on this grid (measured; the issue's evidence file), so the tolerance here is
the law gap, not a numerical one: same status and side everywhere, |Δx| ≤ 10 mm on
every throw and ≤ 0.5 mm on most; at μ = 1, where the laws coincide on this grid,
≤ 0.5 mm on every throw.
"""

import numpy as np
import pytest

from throwmap import Arm, throw_batch
from throwmap.system.catalogue import triangle_30_60_90
from throwmap.testing.grids import side_grid
from throwmap.records.outcome import Status

TRI = triangle_30_60_90()


def _grid():
    """The triangle's 3 sides × 5 x × ω ∈ {3, 5, 7} rad/s (:func:`throwmap.testing.grids.side_grid`)."""
    return side_grid(TRI)


@pytest.mark.parametrize("mu, dx_all, share_close", [(0.3, 10e-3, 0.5), (0.6, 10e-3, 0.9), (1.0, 0.5e-3, 1.0)])
def test_rigid_body_and_engine_agree_at_low_friction_within_the_impact_law_gap(mu, dx_all, share_close):
    xs, ks, oms = _grid()
    arm = Arm(h=-0.01, mu=mu)
    rb = throw_batch(TRI, arm, xs, ks, oms, model="rigid_body")
    en = throw_batch(TRI, arm, xs, ks, oms, model="engine", workers=1)
    assert np.array_equal(rb.status, en.status)
    both = rb.status == Status.OK
    assert both.sum() >= 35  # the comparison is made on throws that land, not on escapes
    assert np.array_equal(rb.side[both], en.side[both])
    dx = np.abs(rb.x - en.x)[both]
    assert dx.max() <= dx_all, dx.max()
    assert np.mean(dx <= 0.5e-3) >= share_close
    # the grid exercises slip: throws that slide (impacts or contact phases outside the cone)
    assert np.mean(rb.record("N_SLIPS")[both] > 0) >= 0.5
