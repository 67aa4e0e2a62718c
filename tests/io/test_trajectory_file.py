"""Trajectory files (throwmap.io.trajectory_file): a Trajectory comes back equal, objects in meta by name,
anything else refused, and a file that is not one says so."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from throwmap.errors import RegimeWarning

from throwmap.errors import InvalidStateError
from throwmap.io.trajectory_file import (load_trajectory, save_trajectory, trajectory_from_arrays,
                                         trajectory_to_arrays)
from throwmap.system.arm import Arm
from throwmap.system.catalogue import triangle_30_60_90
from throwmap.system.fixtures import Cavity, Wall
from throwmap.records.trajectory import Trajectory


def _traj(**meta) -> Trajectory:
    part = triangle_30_60_90(point_masses=((0.01, (0.02, 0.01)),))
    t = np.linspace(0.0, 0.5, 31)
    poses = np.stack([np.column_stack((0.1 + 0.1 * t, 0.02 + 0.01 * t, 0.3 * t)),
                      np.column_stack((0.3 + 0 * t, 0.02 + 0 * t, 0 * t))], axis=1)
    contacts = tuple(np.zeros((0, 2)) if i % 3 else np.array([[0.1, 0.0], [0.3, 0.0]]) for i in range(t.size))
    return Trajectory(t, 0.2 * np.sin(t), poses, (part, triangle_30_60_90()), 0.02, 0.5,
                      (Wall(0.05, 0.01, mu=0.3), Cavity(((0.06, 0.0), (0.04, -0.01), (0.0, -0.01)))), contacts,
                      ((0.1, "release"), (0.4, "impact v1")), "made-up", meta)


def test_a_trajectory_comes_back_equal(tmp_path):
    tr = _traj(view=(0.0, 0.5, -0.1, 0.2), orbit={"throw": [0, 1], "x": [[0.1, 0.3], [0.15, 0.3]], "t": [None, 0.0]})
    back = load_trajectory(save_trajectory(tr, tmp_path / "a.npz"))
    for name in ("t", "arm_angle", "poses"):
        np.testing.assert_array_equal(getattr(back, name), getattr(tr, name))
    assert back.parts == tr.parts and back.parts[0].point_masses == tr.parts[0].point_masses
    assert back.fixtures == tr.fixtures
    assert len(back.contacts) == tr.n_samples
    assert all(np.array_equal(a, b) for a, b in zip(back.contacts, tr.contacts))
    assert back.events == tr.events and back.source == "made-up" and (back.h, back.length) == (0.02, 0.5)
    assert back.meta == {"view": [0.0, 0.5, -0.1, 0.2], "orbit": tr.meta["orbit"]}  # tuples come back as lists


def test_outcomes_and_the_arm_come_back_as_objects(tmp_path):
    from throwmap.throws.orbit_trajectory import orbit_trajectory

    arm = Arm(0.02)
    with pytest.warns(RegimeWarning, match="jogs are no longer guaranteed"):  # h ≥ 0: as every throw warns
        tr = orbit_trajectory(triangle_30_60_90(), arm, 0.1, 0, 3.0, 2, model="paper")
    back = load_trajectory(save_trajectory(tr, tmp_path / "orbit.npz"))
    assert back.meta["arm"] == arm and math.isinf(back.meta["arm"].mu)
    assert [o.x for o in back.meta["outcomes"]] == [o.x for o in tr.meta["outcomes"]]
    assert [o.status for o in back.meta["outcomes"]] == [o.status for o in tr.meta["outcomes"]]
    assert back.meta["throw_starts"] == list(tr.meta["throw_starts"])


def test_other_objects_in_meta_are_refused_by_name(tmp_path):
    with pytest.raises(InvalidStateError, match=r"meta\['thing'\]"):
        save_trajectory(_traj(thing=object()), tmp_path / "a.npz")
    assert not (tmp_path / "a.npz").exists()


def test_the_file_name_and_the_file_are_checked(tmp_path):
    with pytest.raises(InvalidStateError, match="path: .*ends in .npz"):
        save_trajectory(_traj(), tmp_path / "a.json")
    with pytest.raises(InvalidStateError, match="no such file"):
        load_trajectory(tmp_path / "missing.npz")
    (tmp_path / "junk.npz").write_bytes(b"not a zip")
    with pytest.raises(InvalidStateError, match="not a trajectory file"):
        load_trajectory(tmp_path / "junk.npz")
    arrays = trajectory_to_arrays(_traj())
    head = json.loads(str(arrays["header"][()]))
    arrays["header"] = np.array(json.dumps(dict(head, version=99)))
    with pytest.raises(InvalidStateError, match="header.version"):
        trajectory_from_arrays(arrays)
    arrays["header"] = np.array(json.dumps(dict(head, format="other")))
    with pytest.raises(InvalidStateError, match="header.format"):
        trajectory_from_arrays(arrays)
    arrays = trajectory_to_arrays(_traj())
    arrays["contact_counts"] = arrays["contact_counts"] + 1
    with pytest.raises(InvalidStateError, match="contact_counts"):
        trajectory_from_arrays(arrays)


def test_a_file_is_read_without_pickle(tmp_path):
    path = save_trajectory(_traj(), tmp_path / "a.npz")
    with np.load(path, allow_pickle=False) as data:
        assert set(data.files) == {"t", "arm_angle", "poses", "contact_counts", "contacts", "event_t", "header"}
        assert all(data[k].dtype != object for k in data.files)
