"""An UNRESOLVED throw says why: rigid_body's wall refusals carry their reason code (codes.WHY), not the
flight's spin-angle text."""

import numpy as np
import pytest

import throwmap as tm
from throwmap.kernels import codes as C
from throwmap.kernels.rigid_body.modes import WHY_MESSAGES
from throwmap.studies.validation import default_parts
from throwmap.system.starts import start_interval


def test_a_walled_refusal_names_its_wall_reason():
    rng = np.random.default_rng(0)
    parts = list(default_parts().values())
    wall = (tm.Wall(0.05, mu=0.0),)
    found = []
    for _ in range(300):
        part = parts[rng.integers(len(parts))]
        k = part.stable_sides[rng.integers(len(part.stable_sides))]
        L = rng.uniform(0.25, 0.4)
        arm = tm.Arm(h=-0.01, mu=1.0, length=L)
        lo, hi = start_interval(part, arm, k)
        x = rng.uniform(L - 0.1, L - 0.03)
        if not lo < x <= hi:
            continue
        o = tm.throw(part, arm, x, k, rng.uniform(3, 6), fixtures=wall)
        if o.status == tm.Status.UNRESOLVED:
            found.append(o)
            if len(found) == 3:
                break
    assert found, "no refused walled throw in 300 draws"
    for o in found:
        assert o.message in WHY_MESSAGES.values()
        assert "spin angle" not in o.message


def test_the_why_column_is_empty_for_resolved_throws():
    part, arm = tm.triangle_30_60_90(), tm.Arm(h=-0.01, length=0.5)
    o = tm.throw(part, arm, 0.2, 0, 4.0)
    assert o.ok and o.message == ""
    rec = tm.throw_batch(part, arm, [0.2, 0.25], [0, 0], 4.0).records
    assert rec.shape[1] == C.NREC and not np.any(rec[:, C.WHY] > 0)


def test_a_trajectory_refuses_a_start_that_is_not_at_rest_on_the_tilted_arm():
    import math

    import pytest

    from throwmap.errors import InvalidStateError
    from throwmap.throws.orbit_trajectory import throw_trajectory

    part, arm = tm.triangle_30_60_90(), tm.Arm(h=-0.01, mu=0.1, length=0.5)
    alpha = math.radians(-12)  # |tan α| = 0.21 > μ: the part slides
    assert tm.throw(part, arm, 0.2, 0, 4.0, alpha=alpha).status == tm.Status.INVALID_START
    with pytest.raises(InvalidStateError, match="^side: not at rest on the tilted arm: slides"):
        throw_trajectory(part, arm, 0.2, 0, 4.0, alpha=alpha)


def test_the_cli_refuses_a_tilted_start_that_slides_with_one_line():
    from typer.testing import CliRunner

    from throwmap.cli.app import app

    res = CliRunner().invoke(app, ["throw", "--part", "triangle", "--h", "-0.01", "--length", "0.3", "--mu", "0.05",
                                   "--x", "0.2", "--side", "0", "--omega", "5", "--alpha", "5deg"])
    assert res.exit_code == 2
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: side: not at rest on the tilted arm: slides")


def test_two_walls_are_refused_naming_fixtures():
    import pytest

    from throwmap.errors import InvalidStateError

    arm = tm.Arm(h=-0.01, length=0.3)
    with pytest.raises(InvalidStateError, match="^fixtures: at most one Wall"):
        tm.throw(tm.triangle_30_60_90(), arm, 0.2, 0, 4.0, fixtures=[tm.Wall(0.05), tm.Wall(0.03)])


@pytest.mark.filterwarnings("ignore::throwmap.errors.RegimeWarning")  # h below −min d, as the user's scene had
def test_inconsistent_says_why():
    """A walled throw rigid_body finds inconsistent (Painlevé) carries that reason; its message was empty."""
    import throwmap as tm

    o = tm.throw(tm.triangle_30_60_90(), tm.Arm(h=-0.028540605254305105, mu=1.0, length=0.3574225161685043),
                 0.2604150972921227, 2, 7.938424011861821, "rigid_body",
                 fixtures=(tm.Wall(height=0.07964949487141797, mu=0.0),), alpha=-0.14229352001542472,
                 impact_law="velocity")
    assert o.status == tm.Status.INCONSISTENT
    assert "Painlevé" in o.message and o.to_dict()["message"] == o.message
