"""The draft's example and the feeder design (throwmap.design.examples): re-run and checked against the data."""

from __future__ import annotations

import math

import numpy as np
import pytest

from throwmap.design.examples import (DRAFT_TARGETS, FEEDER, draft_example, end_wall_window, engine_r, exact_r,
                                      feeder_design, run_feeder_design)
from throwmap.design.targets import Separation


@pytest.fixture(scope="module")
def rerun():
    return run_feeder_design(engine=False, limit_starts=24)


def test_stored_feeder_design_still_meets_its_targets_on_the_exact_model(rerun):
    fd = feeder_design()
    # the stored part at the stored ω: exact r_i within 1 mm of the targets (re-evaluated, not read back), and
    # within 0.1 mm of the stored r_i (else the data file is stale: regenerate it)
    r = exact_r(fd.part, fd.arm, fd.omega).r
    for s, v in fd.targets.items():
        assert abs(r[s] - v) <= 1e-3
        assert abs(r[s] - fd.r[s]) <= 1e-4
    # and the design re-run from scratch lands on the stored numbers
    res, new = rerun
    assert res.success, res.message
    assert np.allclose(new.weight_at, fd.weight_at, atol=1e-4)
    assert new.omega == pytest.approx(fd.omega, abs=1e-3)
    for s in fd.targets:
        assert abs(new.r[s] - fd.targets[s]) <= 1e-4


def test_feeder_separation_holds(rerun):
    fd = feeder_design()
    sep = Separation(fd.target_side, fd.separation_x, fd.separation_margin)
    assert sep.holds(fd.tops)
    _, new = rerun
    assert sep.holds(new.tops)
    assert all(math.isfinite(new.bottoms[s]) for s in new.bottoms)  # every side visited: one band over all sides
    lo, hi, S = end_wall_window(fd.part, fd.arm, fd.omega, fd.target_side, fd.jitter)
    assert S > 0.02
    assert (lo, hi) == pytest.approx(fd.wall_window, abs=1e-4)


def test_feeder_part_is_plate_plus_weight_inside_the_margin():
    fd = feeder_design()
    assert fd.part.mass == pytest.approx(fd.plate.mass + FEEDER["weight_mass"])
    from throwmap.design.plate import inset_polygon

    assert inset_polygon(fd.plate.vertices, 0.008).contains(fd.weight_at)


@pytest.mark.slow
def test_feeder_engine_r_within_a_millimetre_of_the_exact():
    fd = feeder_design()
    er = engine_r(fd.part, fd.arm, fd.omega).r
    for s in fd.r:
        assert abs(er[s] - fd.r[s]) <= 1e-3
        # 0.1 mm: the engine's exact-model oracle reruns a disagreeing throw at a finer step (55 µm seen)
        assert abs(er[s] - fd.engine_r[s]) <= 1e-4


def test_draft_example():
    ex = draft_example(engine=False)
    # the exact design meets the draft's goal within 0.1 mm (the corrected small-angle one misses on the exact map),
    # but at that ω every orbit escapes: the draft's targets place critical points that feed nothing
    assert ex.exact.targets_reached and not ex.exact.success
    assert "every orbit escapes" in ex.exact.limit_set_note
    for s, v in DRAFT_TARGETS.items():
        assert abs(ex.rows[3].exact_r[s] - v) <= 1e-3
    assert ex.small_angle.targets_reached
    miss = max(abs(ex.rows[2].exact_r[s] - v) for s, v in DRAFT_TARGETS.items())
    assert 0.005 < miss < 0.05
    # the draft's design point does not give its claimed {14, 14, 20} cm on the exact map
    assert max(abs(ex.rows[1].exact_r[s] - v) for s, v in ex.rows[1].draft_r.items()) > 0.02
    assert not ex.as_printed.success
    assert "OUTSIDE" in ex.table()
