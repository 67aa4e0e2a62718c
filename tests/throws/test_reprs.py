"""Result objects print as one short summary (a notebook cell is not flooded); statuses print their label."""

from __future__ import annotations

import numpy as np
import pytest

import throwmap as tm
from throwmap.io.config import resolve_part
from throwmap.kernels import codes as C
from throwmap.throws.orbit_trajectory import throw_trajectory
from throwmap.records.outcome import Status
from throwmap.throws.samples import throw_map_samples

SHORT = 200
"""Characters a summary repr may take."""


@pytest.fixture(scope="module")
def part():
    return resolve_part("triangle").part


@pytest.fixture(scope="module")
def arm():
    return tm.Arm(h=-0.01)


def assert_short(obj, *words):
    text = repr(obj)
    assert len(text) <= SHORT and "\n" not in text, (len(text), text[:300])
    for w in words:
        assert w in text, (w, text)
    assert "np." not in text and "array(" not in text, text


def test_orbit_of_300_throws(part, arm):
    orbit = tm.iterate(part, arm, (0.2, 0), 4.0, n=300, model="paper")
    assert orbit.n_throws == 300  # the premise: a long orbit
    sides = ", ".join(str(s) for s in np.unique(orbit.side))
    assert_short(orbit, "Orbit(", "model='paper'", "omega=4 rad/s", "300 throws", f"sides {sides}", "x∈[", " m",
                 orbit.status.label)


def test_orbit_with_varying_omegas_and_escape(part, arm):
    orbit = tm.iterate(part, arm, (0.12, 0), [3.0, 5.0, 4.0], model="paper")
    assert orbit.n_throws == 3  # the premise: every rate used
    assert_short(orbit, "omega∈[3, 5] rad/s", "3 throws")
    escape = tm.iterate(part, tm.Arm(h=-0.01, length=0.3), (0.2, 0), [3.0, 20.0, 4.0], model="paper")
    assert escape.escaped  # the premise
    assert_short(escape, escape.status.label, f"{escape.n_throws} throws")


def test_throw_outcome(part, arm):
    out = tm.throw(part, arm, 0.2, 0, 4.0, model="paper")
    assert_short(out, "ThrowOutcome(", "model='paper'", "omega=4 rad/s", "x=0.2 m", out.kind)


def test_batch_outcome(part, arm):
    res = tm.throw_batch(part, arm, np.linspace(0.0, 0.6, 20_000).reshape(100, 200), 0, 4.0, model="paper",
                         on_invalid="status")
    counts = res.counts()
    assert len(counts) > 1  # the premise: several statuses to list
    assert_short(res, "BatchOutcome(", "20000 throws", "(100, 200)", *(f"{k} {v}" for k, v in counts.items()))


def test_map_samples(part, arm):
    m = throw_map_samples(part, arm, 4.0, model="paper", n=500)
    assert_short(m, "MapSamples(", "model='paper'", "omega=4 rad/s", "500 per side", "x∈(")


def test_trajectory(part, arm):
    _, traj = throw_trajectory(part, arm, 0.2, 0, 4.0, model="paper")
    long_name = tm.Part.from_vertices(part.vertices, part.mass, name="x" * 500)
    assert_short(traj, "Trajectory(", "source='paper'", f"{traj.n_samples} samples", "t∈[")
    assert_short(tm.records.trajectory.Trajectory(traj.t, traj.arm_angle, traj.poses, (long_name,), traj.h,
                                                 traj.length), "1 part")


def test_status_prints_its_label(capsys):
    print(Status.OK)
    assert capsys.readouterr().out == "ok\n"
    assert str(Status.OK) == "ok"
    assert f"{Status.BEHIND_JOINT}" == "behind_joint"
    assert f"{Status.OFF_END:>9}" == "  off_end"
    assert f"{Status.OFF_END:d}" == str(C.OFF_END) and int(Status.OFF_END) == C.OFF_END
    assert Status.OK == 0  # still the kernels' integer code


def test_every_kernel_code_has_a_status():
    assert Status(C.UNRESOLVED).label == "unresolved"
    assert Status(C.UNCONVERGED).label == "unconverged"
    for st in Status:
        assert Status.from_label(str(st)) is st
