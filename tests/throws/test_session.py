"""Throwing sessions: a scene thrown again and again keeps its state, validated once, the same for every model."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.models import Features, get_model, model_names
from throwmap.records.outcome import Status
from throwmap.system.motion import RecoilThrow, TiltTo
from throwmap.throws.session import MapEnsemble, MapSession, open_ensemble, open_session

PART = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01, mu=1.5)


def same(a, b) -> bool:
    """Two outcomes equal field by field (nan equal to nan: their JSON forms)."""
    return a.to_dict() == b.to_dict()


@pytest.mark.parametrize("model", ["paper", "rigid_body", "small_angle"])
def test_a_session_throws_what_throw_throws(model):
    """Each step equals throw() from the rest the last step left (the session only keeps the state)."""
    s = open_session(PART, ARM, (0.15, 0), model)
    x, k = 0.15, 0
    for w in (3.0, 4.5, 2.0, 5.0):
        step = s.throw(w)
        ref = tm.throw(PART, ARM, x, k, w, model=model)
        assert same(step.outcome, ref) and step.status == ref.status
        if not step.ok:
            assert s.status == ref.status and s.n_throws >= 1
            with pytest.raises(InvalidStateError, match="session"):
                s.throw(w)
            break
        x, k = ref.x, ref.side
        assert s.states[0].x == x and s.states[0].side == k and s.states[0].pose is None


def test_iterate_is_a_session():
    orbit = tm.iterate(PART, ARM, (0.2, 1), [4.0, 4.0, 3.0], model="rigid_body")
    s = open_session(PART, ARM, (0.2, 1), "rigid_body")
    assert all(same(s.throw(w).outcome, o) for w, o in zip((4.0, 4.0, 3.0), orbit.outcomes))


def test_a_start_is_validated_once_when_opened():
    with pytest.raises(InvalidStateError) as err:
        open_session(PART, ARM, (-0.5, 0), "paper")
    assert err.value.field == "x"
    with pytest.raises(InvalidStateError, match="state"):
        open_session(PART, ARM, 0.2, "paper")
    with pytest.raises(InvalidStateError, match="tol"):
        open_session(PART, ARM, (0.2, 0), "paper", tol=-1.0)
    s = open_session(PART, ARM, (0.2, 0), "paper")
    with pytest.raises(InvalidStateError, match="omega"):
        s.throw(-1.0)
    assert s.n_throws == 0  # a refused ω is no throw


def test_a_model_that_follows_no_arm_motion_refuses_one():
    s = open_session(PART, ARM, (0.2, 0), "paper")
    assert not s.features.realisation
    with pytest.raises(InvalidStateError, match="motion"):
        s.throw(4.0, RecoilThrow.for_release_rate(4.0))
    with pytest.raises(InvalidStateError, match="motion"):
        s.move(TiltTo(0.1))


def test_rigid_body_rides_the_motion_it_is_given():
    s = open_session(PART, ARM, (0.2, 0), "rigid_body")
    real = RecoilThrow.for_release_rate(4.0)
    step = s.throw(4.0, real)
    ref = tm.throw(PART, ARM, 0.2, 0, 4.0, model="rigid_body", realisation=real)
    assert same(step.outcome, ref) and step.motion is real


def test_a_rest_that_is_no_start_ends_the_session_as_invalid():
    """A rest leaning on a wall past the last flat start: the next throw is INVALID_START (not an exception)."""
    s = open_session(PART, ARM, (0.2, 0), "paper")
    s._x = -0.05  # as a throw that left the part leaning could
    s.n_throws = 1
    step = s.throw(3.0)
    assert step.status == Status.INVALID_START and "not a start" in step.message and s.ended


def test_an_ensemble_is_independent_sessions_in_one_batch():
    x = np.array([0.12, 0.18, 0.25, 0.3])
    k = np.array([0, 1, 2, 0])
    ens = open_ensemble(PART, ARM, x, k, "rigid_body")
    assert isinstance(ens, MapEnsemble)
    sessions = [open_session(PART, ARM, (xi, ki), "rigid_body") for xi, ki in zip(x, k)]
    for w in (4.0, 5.5, 3.0):
        b = ens.throw(w)
        for i, s in enumerate(sessions):
            if s.ended:
                assert b.status[i] == int(s.status)  # an ended scene keeps its last status
                continue
            o = s.throw(w).outcome
            assert (b.x[i], b.side[i], b.status[i]) == (o.x, o.side, int(o.status))


def test_the_engine_keeps_poses_and_several_parts():
    eng = get_model("engine")
    assert eng.features.pose and eng.features.parts == 0 and eng.features.moves and not eng.features.ensemble
    arm = tm.Arm(h=-0.01, length=0.5, mu=1.0)
    s = open_session((PART, PART), arm, [(0.12, 0), (0.32, 1)], "engine")
    assert len(s.states) == 2 and all(st.pose is not None for st in s.states)
    step = s.throw(0.0)  # settle: the rests stay
    assert step.ok and [o.status for o in step.outcomes] == [Status.OK, Status.OK]
    moved = s.move(TiltTo(0.05, 0.5))
    assert moved.kind == "move" and s.system.alpha == pytest.approx(0.05)
    with pytest.raises(InvalidStateError, match="TiltTo"):
        s.throw(1.0, TiltTo(0.1))
    with pytest.raises(InvalidStateError, match="one part at a time"):
        open_session((PART, PART), arm, [(0.12, 0), (0.32, 1)], "rigid_body")
    with pytest.raises(InvalidStateError, match="ensembles"):
        open_ensemble(PART, arm, [0.2], [0], "engine")


def test_a_pose_start_is_only_for_models_that_keep_poses():
    from throwmap.engine import Placement, Scene

    arm = tm.Arm(h=-0.01, length=0.5)
    scene = Scene(arm, (Placement(PART, x=0.2, side=0),))
    s = open_session(PART, arm, scene, "engine")
    assert s.states[0].x == 0.2 and s.states[0].side == 0
    with pytest.raises(InvalidStateError, match="keep poses"):
        open_session(PART, arm, scene, "rigid_body")
    with pytest.raises(InvalidStateError, match="this one part"):
        open_session(tm.regular_polygon(5, 0.05), arm, scene, "engine")


def test_every_registered_model_gives_a_session():
    """Each model provides a session: its own (``model.session``) or the dispatcher's on rests."""
    for name in model_names():
        m = get_model(name)
        if name == "mujoco":
            pytest.importorskip("mujoco")
        if m.features.pose:
            continue  # the engine's: tested above (a run costs more)
        s = open_session(PART, ARM, (0.2, 0), name)
        assert isinstance(s, MapSession) and s.features == m.features
        assert isinstance(s.throw(3.0).outcome, tm.ThrowOutcome)


def test_features_default_to_a_model_of_rests():
    f = Features()
    assert (f.pose, f.parts, f.moves, f.ensemble) == (False, 1, False, True)
    assert dataclasses.replace(f, pose=True).pose
