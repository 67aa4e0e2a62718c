"""The half-step check calls two runs different when the side differs, or when x differs by more than the
agreement — either alone is enough (a rest on the wrong side at the same x is a different answer)."""

from types import SimpleNamespace

import throwmap as tm
from throwmap.engine.pymunk.verify import disagreement
from throwmap.records.outcome import Status

SETTINGS = SimpleNamespace(penetration_tol=5e-4, agreement=5e-4)
SCENE = SimpleNamespace(arm=tm.Arm(h=-0.01))


def _run(x, side, status=Status.OK, dt=1e-3):
    return SimpleNamespace(scene=SCENE, energy_gain=0.0, statuses=(status,), states=((x, side, None),), dt=dt)


def test_same_x_other_side_disagrees():
    why = disagreement(_run(0.2, 0), _run(0.2, 1, dt=5e-4), SETTINGS)
    assert "side 0" in why and "side 1" in why


def test_same_side_x_beyond_the_agreement_disagrees():
    assert disagreement(_run(0.2, 0), _run(0.2 + 2e-3, 0, dt=5e-4), SETTINGS)


def test_same_side_x_within_the_agreement_agrees():
    assert disagreement(_run(0.2, 0), _run(0.2 + 1e-4, 0, dt=5e-4), SETTINGS) == ""


def test_other_status_disagrees():
    assert "off_end" in disagreement(_run(0.2, 0), _run(0.3, 0, Status.OFF_END, dt=5e-4), SETTINGS)
