"""Part files round-trip every field of a part and an arm, in TOML and in JSON.

The fields come from the dataclasses themselves: a field added to :class:`throwmap.Part`
or :class:`throwmap.Arm` fails these tests until the file format reads and writes it.
"""

from __future__ import annotations

import dataclasses
import json
import math
import tomllib

import pytest

import throwmap as tm
from throwmap.errors import ConfigError
from throwmap.io.config import load_config, part_to_toml, save_part, save_part_toml

VERTICES = [[0.0, 0.0], [0.11, 0.0], [0.13, 0.035], [0.02, 0.05]]

PART_VALUES = {
    "vertices": VERTICES,
    "mass": 0.07,  # kg, the plate (the part's mass is plate + point masses)
    "com": (0.061, 0.024),  # m, given, not the computed one
    "radius_of_gyration": 0.0375,  # m, given
    "point_masses": [(0.012, (0.09, 0.01)), (0.004, (0.03, 0.04))],
    "name": 'odd "name" — ünï\\code\t',
}
"""A non-default value for every :class:`Part` field (keyword of :meth:`Part.from_vertices`)."""

ARM_VALUES = {"h": -0.013, "g": 9.7, "length": 0.45, "mu": 0.35, "back": 0.015}
"""A non-default value for every :class:`Arm` field."""


def _init_fields(cls) -> set[str]:
    return {f.name for f in dataclasses.fields(cls) if f.init}


def full_part() -> tm.Part:
    return tm.Part.from_vertices(**PART_VALUES)


def full_arm() -> tm.Arm:
    return tm.Arm(**ARM_VALUES)


def test_every_field_has_a_non_default_value():
    """The values above cover every field and differ from its default (else a dropped field goes unseen)."""
    assert _init_fields(tm.Part) == set(PART_VALUES), "a Part field without a value here: give it one, and I/O"
    assert _init_fields(tm.Arm) == set(ARM_VALUES), "an Arm field without a value here: give it one, and I/O"
    plain = tm.Part.from_vertices(VERTICES, mass=PART_VALUES["mass"])  # every optional field at its default
    part = full_part()
    for name in _init_fields(tm.Part) - {"vertices"}:  # the one field without a default
        assert getattr(part, name) != getattr(plain, name), name
    arm = full_arm()
    for f in dataclasses.fields(tm.Arm):
        assert getattr(arm, f.name) != f.default, f.name


@pytest.mark.parametrize("suffix", [".toml", ".json"])
def test_part_and_arm_round_trip_every_field(tmp_path, suffix):
    part, arm = full_part(), full_arm()
    loaded = load_config(save_part(part, arm, tmp_path / f"full{suffix}"))
    for name in _init_fields(tm.Part):
        assert getattr(loaded.part, name) == getattr(part, name), f"part.{name}"
    for name in _init_fields(tm.Arm):
        assert getattr(loaded.arm, name) == getattr(arm, name), f"arm.{name}"
    assert loaded.part == part and loaded.arm == arm


@pytest.mark.parametrize("suffix", [".toml", ".json"])
def test_default_arm_round_trips(tmp_path, suffix):
    """μ = ∞ (no slip) and an unbounded arm are left out of the file and come back as such."""
    arm = tm.Arm(h=-0.01)
    loaded = load_config(save_part(full_part(), arm, tmp_path / f"plain{suffix}"))
    assert loaded.arm == arm and math.isinf(loaded.arm.mu) and loaded.arm.length is None


def test_toml_writer_is_the_save_part_toml_text(tmp_path):
    part, arm = full_part(), full_arm()
    path = save_part_toml(part, arm, tmp_path / "p.toml")
    assert path.read_text(encoding="utf-8") == part_to_toml(part, arm)
    doc = tomllib.loads(path.read_text(encoding="utf-8"))
    assert doc["arm"] == ARM_VALUES


def test_json_file_is_strict_json(tmp_path):
    path = save_part(full_part(), full_arm(), tmp_path / "p.json")

    def refuse(token):
        raise ValueError(token)

    doc = json.loads(path.read_text(encoding="utf-8"), parse_constant=refuse)
    assert doc["arm"] == ARM_VALUES


def test_save_part_refuses_other_extensions(tmp_path):
    with pytest.raises(ConfigError) as err:
        save_part(full_part(), None, tmp_path / "p.yaml")
    assert err.value.field == "file" and ".yaml" in err.value.reason


@pytest.mark.parametrize("suffix, text, field, meant", [
    (".toml", "[part]\nvertices = [[0,0],[0.05,0],[0,0.05]]\nmas = 0.05\n", "part.mas", "mass"),
    (".toml", "[part]\nvertices = [[0,0],[0.05,0],[0,0.05]]\nmass = 0.05\n[arm]\nh = -0.01\nmu0 = 1\n", "arm.mu0",
     "mu"),
    (".toml", "[part]\nvertice = [[0,0],[0.05,0],[0,0.05]]\nmass = 0.05\n", "part.vertice", "vertices"),
    (".json", '{"part": {"vertices": [[0,0],[0.05,0],[0,0.05]], "mass": 0.05}, "amr": {"h": -0.01}}', "amr", "arm"),
])
def test_typo_names_the_unknown_key(tmp_path, suffix, text, field, meant):
    """A misspelt key is named (not the key it meant, reported missing), with the nearest allowed key."""
    path = tmp_path / f"typo{suffix}"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ConfigError) as err:
        load_config(path)
    assert err.value.field == field
    assert "unknown key" in err.value.reason and f"did you mean {meant!r}" in err.value.reason
    assert "\n" not in str(err.value)


def test_mu_inf_may_be_written(tmp_path):
    path = tmp_path / "inf.toml"
    path.write_text("[part]\nvertices = [[0,0],[0.05,0],[0,0.05]]\nmass = 0.05\n[arm]\nh = -0.01\nmu = inf\n")
    assert math.isinf(load_config(path).arm.mu)
