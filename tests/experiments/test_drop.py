"""Random initial conditions by dropping the part onto the arm in the pymunk engine."""

import math

import numpy as np
import pytest

from throwmap import Arm, Status
from throwmap.engine import ImpulseThrow, simulate
from throwmap.errors import InvalidStateError
from throwmap.experiments.drop import drop_part
from throwmap.system.fixtures import Cavity, Wall
from throwmap.system.pose import world_vertices

ARM = Arm(h=-0.01, length=0.4, mu=0.8)


def test_a_drop_rests_flat_on_the_arm_and_is_the_next_start(triangle):
    d = drop_part(triangle, ARM, 11)
    assert d.ok and d.kind is None and abs(d.tilt) < 0.02
    assert sum(d.rejected.values()) == d.redraws
    V = world_vertices(triangle, d.pose)
    assert V[:, 1].min() == pytest.approx(ARM.h, abs=5e-4)  # resting on the surface y = h
    assert -ARM.back <= d.x <= ARM.length
    assert d.scene.placements[0].pose == pytest.approx(d.pose)
    # the drop's start was in the stated ranges
    x0, y0, phi0 = d.start
    assert 0.0 <= phi0 < 2 * math.pi and 0.0 <= x0 <= 0.4 and 0.02 <= d.height <= 0.10
    assert world_vertices(triangle, d.start)[:, 1].min() - ARM.h == pytest.approx(d.height)
    # a part at rest stays at rest: dropping again with no throw does not move it
    still = simulate(d.scene, ImpulseThrow(0.0))
    assert still.states[0][1] == d.side and still.states[0][0] == pytest.approx(d.x, abs=1e-4)


def test_same_seed_same_drop(triangle):
    a, b = drop_part(triangle, ARM, 4), drop_part(triangle, ARM, np.random.default_rng(4))
    assert (a.x, a.side, a.pose, a.start, a.redraws) == (b.x, b.side, b.pose, b.start, b.redraws)


def test_redraws_or_report(triangle):
    """On a short arm many drops fall off: with max_redraws=0 they are reported, else re-drawn and counted."""
    short = Arm(h=-0.01, length=0.2, mu=0.8)
    raw = [drop_part(triangle, short, s, max_redraws=0) for s in range(12)]
    kinds = {d.kind for d in raw}
    assert None in kinds and kinds & {"off_end", "behind_joint"}
    for d in raw:
        assert d.redraws == 0 and (d.kind is None) == d.ok
    first_fail = next(s for s, d in enumerate(raw) if not d.ok)
    kept = drop_part(triangle, short, first_fail, max_redraws=50)
    assert kept.ok and kept.redraws >= 1 and sum(kept.rejected.values()) == kept.redraws


def test_drop_into_a_cavity_may_rest_tilted(triangle):
    fixtures = (Cavity(((0.12, 0.0), (0.12, -0.015), (0.0, -0.015))), Wall(height=0.04))
    tilts = []
    for s in range(6):
        d = drop_part(triangle, ARM, s, fixtures=fixtures, x_range=(0.30, 0.36), max_redraws=0)
        assert d.status in (Status.OK, Status.OFF_END, Status.BEHIND_JOINT, Status.UNCONVERGED, Status.TIMEOUT)
        # nothing starts inside the wall: the start pose is above its top where it overlaps it
        V = world_vertices(triangle, d.start)
        over = V[:, 0] >= ARM.length
        assert not over.any() or V[:, 1].min() >= ARM.h + 0.04 + 0.02 - 1e-12
        if d.ok:
            tilts.append(abs(d.tilt))
    assert tilts and max(tilts) > 0.02  # held tilted by the pocket, which only a fixture can do


def test_bad_drops_are_refused(triangle):
    with pytest.raises(InvalidStateError, match="^x_range:"):
        drop_part(triangle, Arm(h=-0.01), 0)
    with pytest.raises(InvalidStateError, match="^height:"):
        drop_part(triangle, ARM, 0, height=(-0.01, 0.02))
    with pytest.raises(InvalidStateError, match="^max_redraws:"):
        drop_part(triangle, ARM, 0, max_redraws=-1)
    with pytest.raises(InvalidStateError, match="^rng:"):
        drop_part(triangle, ARM, "seed")
