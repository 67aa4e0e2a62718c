"""Part/arm files (throwmap.io.config) and atomic writes (throwmap.io.files)."""

from __future__ import annotations

import json
import os

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import throwmap as tm
from throwmap.io.config import (
    LoadedConfig,
    arm_from_spec,
    load_config,
    part_from_spec,
    part_to_toml,
    resolve_part,
    save_part_toml,
)
from throwmap.errors import ConfigError, InvalidArmError, InvalidPartError
from throwmap.io.files import atomic_write_bytes, atomic_write_text
from throwmap.system.catalogue import BUILTIN_PARTS, builtin_part

QUAD = "[[0.0, 0.0], [0.1, 0.0], [0.13, 0.02], [0.03, 0.02]]"


def write(tmp_path, text, name="part.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def part_toml(vertices=QUAD, mass="0.05", extra="", arm=None):
    text = f"[part]\nvertices = {vertices}\nmass = {mass}\n{extra}"
    if arm is not None:
        text += f"\n[arm]\n{arm}\n"
    return text


# ---------------------------------------------------------------- happy paths
def test_load_minimal_toml_defaults(tmp_path):
    cfg = load_config(write(tmp_path, part_toml(), name="slab.toml"))
    assert isinstance(cfg, LoadedConfig)
    assert cfg.arm is None
    assert cfg.part.name == "slab"  # default name: the file's stem
    assert cfg.part.mass == pytest.approx(0.05)
    assert cfg.part.stable_sides == (0, 2)


def test_load_full_toml_with_arm_and_point_masses(tmp_path):
    text = part_toml(
        extra='name = "weighted"\n[[part.point_masses]]\nmass = 0.01\nat = [0.05, 0.01]\n',
        arm="h = -0.01\ng = 9.8\nlength = 0.5",
    )
    cfg = load_config(write(tmp_path, text))
    assert cfg.part.name == "weighted"
    assert cfg.part.mass == pytest.approx(0.06)
    assert cfg.part.point_masses == ((0.01, (0.05, 0.01)),)
    assert cfg.arm == tm.Arm(h=-0.01, g=9.8, length=0.5)


def test_json_equals_toml(tmp_path):
    toml_cfg = load_config(write(tmp_path, part_toml(arm="h = -0.02"), name="p.toml"))
    doc = {"part": {"vertices": json.loads(QUAD), "mass": 0.05}, "arm": {"h": -0.02}}
    json_cfg = load_config(write(tmp_path, json.dumps(doc), name="p.json"))
    assert json_cfg.part == toml_cfg.part
    assert json_cfg.arm == toml_cfg.arm


def test_integers_are_numbers(tmp_path):
    cfg = load_config(write(tmp_path, part_toml(vertices="[[0, 0], [1, 0], [0, 1]]", mass="2")))
    assert cfg.part.mass == 2.0


@pytest.mark.parametrize("name", sorted(BUILTIN_PARTS))
def test_round_trip_builtin_parts(tmp_path, name):
    part = builtin_part(name)
    path = save_part_toml(part, None, tmp_path / "p.toml")
    back = load_config(path)
    assert back.part == part
    assert back.arm is None


def test_round_trip_with_point_masses_arm_and_odd_name(tmp_path):
    part = tm.triangle_30_60_90(0.17, point_masses=[(0.03, (0.10, 0.01)), (0.0123, (0.01, 0.02))])
    part = __import__("dataclasses").replace(part, name='lead "A"\\\t\x7f ünï 😀')
    arm = tm.Arm(h=-0.01, g=9.81, length=0.6)
    back = load_config(save_part_toml(part, arm, tmp_path / "w.toml"))
    assert back.part == part
    assert back.arm == arm


@settings(max_examples=60, deadline=None)
@given(
    plate=st.floats(1e-4, 10.0),
    weights=st.lists(st.tuples(st.floats(1e-5, 5.0), st.floats(0.001, 0.099), st.floats(0.001, 0.099)), max_size=4),
)
def test_round_trip_exact_total_mass(plate, weights):
    """The file holds the plate mass; reading it back must give the total mass bit for bit."""
    part = tm.Part.from_vertices([(0, 0), (0.1, 0), (0.1, 0.1), (0, 0.1)], plate,
                                 point_masses=[(m, (x, y)) for m, x, y in weights])
    import tomllib

    spec = tomllib.loads(part_to_toml(part))["part"]
    assert part_from_spec(spec) == part


def test_part_and_arm_from_spec():
    part = part_from_spec({"vertices": [[0, 0], [1, 0], [0, 1]], "mass": 1.0, "name": "t"})
    assert part.name == "t" and part.n_sides == 3
    assert arm_from_spec({"h": -0.01}) == tm.Arm(h=-0.01)
    with pytest.raises(ConfigError) as err:
        part_from_spec({"vertices": [[0, 0], [1, 0], [0, 1]], "mass": "1"})
    assert err.value.field == "part.mass"
    with pytest.raises(ConfigError) as err:
        arm_from_spec({"h": -0.01, "height": 2})
    assert err.value.field == "arm.height"
    assert "allowed: h, g, length" in err.value.reason


def test_resolve_part_builtin_and_file(tmp_path):
    assert resolve_part("square").part == builtin_part("square")
    path = write(tmp_path, part_toml())
    assert resolve_part(str(path)).part == load_config(path).part
    with pytest.raises(InvalidPartError) as err:
        resolve_part("dodecahedron")
    assert err.value.field == "part"
    with pytest.raises(ConfigError) as err:
        resolve_part(str(tmp_path / "nope.toml"))
    assert err.value.field == "file"


# ---------------------------------------------------------------- refusals
@pytest.mark.parametrize(
    "text, field, words",
    [
        pytest.param(part_toml(mass="nan"), "part.mass", "finite", id="nan-mass"),
        pytest.param(part_toml(vertices="[[0, 0], [inf, 0], [0, 1]]"), "part.vertices[1][0]", "finite", id="inf-vertex"),
        pytest.param(part_toml(extra="com = [0.05, -inf]\n"), "part.com[1]", "finite", id="inf-com"),
        pytest.param(part_toml(arm="h = nan"), "arm.h", "finite", id="nan-h"),
        pytest.param(part_toml(extra="colour = 'red'\n"), "part.colour", "unknown key", id="unknown-key"),
        pytest.param(part_toml() + "\n[table]\nh = 1\n", "table", "unknown key", id="unknown-table"),
        pytest.param(part_toml(extra="[[part.point_masses]]\nmass = 0.01\nat = [0.05, 0.01]\nsize = 1\n"),
                     "part.point_masses[0].size", "unknown key", id="unknown-key-point-mass"),
        pytest.param("[part]\nmass = 0.05\n", "part.vertices", "missing", id="missing-vertices"),
        pytest.param("[arm]\nh = -0.01\n", "part", "missing", id="missing-part"),
        pytest.param(part_toml(mass="true"), "part.mass", "number", id="bool-mass"),
        pytest.param(part_toml(mass="'0.05'"), "part.mass", "number", id="string-mass"),
        pytest.param(part_toml(vertices="[[0, 0, 0], [1, 0], [0, 1]]"), "part.vertices[0]", "at most 2", id="3d-vertex"),
        pytest.param(part_toml(extra="[[part.point_masses]]\nmass = inf\nat = [0.05, 0.01]\n"),
                     "part.point_masses[0].mass", "finite", id="inf-point-mass"),
    ],
)
def test_schema_errors_name_the_field(tmp_path, text, field, words):
    with pytest.raises(ConfigError) as err:
        load_config(write(tmp_path, text))
    assert err.value.field == field
    assert words in err.value.reason
    assert "\n" not in str(err.value)


@pytest.mark.parametrize(
    "text, field, words",
    [
        pytest.param(part_toml(vertices="[[0, 0], [0.1, 0], [0.02, 0.02], [0, 0.1]]"), "part.vertices", "not convex",
                     id="non-convex"),
        pytest.param(part_toml(vertices="[[0, 1], [0.588, -0.809], [-0.951, 0.309], [0.951, 0.309], [-0.588, -0.809]]"),
                     "part.vertices", "self-intersecting", id="pentagram"),
        pytest.param(part_toml(vertices="[[0, 0], [0.05, 0], [0.1, 0]]"), "part.vertices", "collinear", id="collinear"),
        pytest.param(part_toml(vertices="[[0, 0], [0.1, 0], [0.1, 0], [0, 0.1]]"), "part.vertices", "coincide",
                     id="repeated"),
        pytest.param(part_toml(vertices="[[0, 0], [0.1, 0]]"), "part.vertices", "at least 3", id="two-vertices"),
        pytest.param(part_toml(extra="com = [0.5, 0.5]\n"), "part.com", "inside", id="com-outside"),
        pytest.param(part_toml(extra="[[part.point_masses]]\nmass = 0.01\nat = [0.5, 0.01]\n"),
                     "part.point_masses[0].at", "outside", id="point-mass-outside"),
        pytest.param(part_toml(mass="0"), "part.mass", "positive", id="zero-mass"),
        pytest.param(part_toml(mass="-0.05"), "part.mass", "positive", id="negative-mass"),
        pytest.param(part_toml(extra="[[part.point_masses]]\nmass = -0.01\nat = [0.05, 0.01]\n"),
                     "part.point_masses[0].mass", "positive", id="negative-point-mass"),
        pytest.param(part_toml(extra="radius_of_gyration = 0\n"), "part.radius_of_gyration", "positive", id="zero-rho"),
    ],
)
def test_invalid_parts_keep_their_field(tmp_path, text, field, words):
    with pytest.raises(InvalidPartError) as err:
        load_config(write(tmp_path, text))
    assert err.value.field == field
    assert words in err.value.reason


@pytest.mark.parametrize(
    "arm, field",
    [("h = -0.01\ng = 0", "arm.g"), ("h = -0.01\nlength = -1", "arm.length")],
    ids=["zero-g", "negative-length"],
)
def test_invalid_arms_keep_their_field(tmp_path, arm, field):
    with pytest.raises((ConfigError, InvalidArmError)) as err:  # the Arm's own rule, applied as the file is read
        load_config(write(tmp_path, part_toml(arm=arm)))
    assert err.value.field == field


def test_malformed_toml_names_path_and_line(tmp_path):
    path = write(tmp_path, "[part]\nvertices = [[0, 0],\nmass = = 1\n")
    with pytest.raises(ConfigError) as err:
        load_config(path)
    assert err.value.field == "file"
    assert str(path) in err.value.reason
    assert "line" in err.value.reason


def test_malformed_json_names_path_and_line(tmp_path):
    path = write(tmp_path, '{"part": {"mass": 1,}}', name="p.json")
    with pytest.raises(ConfigError) as err:
        load_config(path)
    assert err.value.field == "file" and "line 1" in err.value.reason


def test_json_duplicate_key_refused(tmp_path):
    path = write(tmp_path, '{"part": {"vertices": [[0,0],[1,0],[0,1]], "mass": 1, "mass": 2}}', name="p.json")
    with pytest.raises(ConfigError, match="duplicate key 'mass'"):
        load_config(path)


def test_json_top_level_must_be_an_object(tmp_path):
    with pytest.raises(ConfigError) as err:
        load_config(write(tmp_path, "[1, 2]", name="p.json"))
    assert err.value.field == "file"


@pytest.mark.parametrize("name, words", [("missing.toml", "no such file"), ("part.yaml", "unsupported")])
def test_unreadable_files(tmp_path, name, words):
    if name.endswith(".yaml"):
        write(tmp_path, "part: {}", name=name)
    with pytest.raises(ConfigError) as err:
        load_config(tmp_path / name)
    assert err.value.field == "file" and words in err.value.reason


def test_directory_is_not_a_file(tmp_path):
    (tmp_path / "d.toml").mkdir()
    with pytest.raises(ConfigError, match="directory"):
        load_config(tmp_path / "d.toml")


def test_save_refuses_other_extensions(tmp_path):
    with pytest.raises(ConfigError):
        save_part_toml(builtin_part("square"), None, tmp_path / "p.json")


# ---------------------------------------------------------------- atomic writes
def test_atomic_write_text_and_bytes(tmp_path):
    p = atomic_write_text(tmp_path / "a.txt", "héllo\n")
    assert p.read_text(encoding="utf-8") == "héllo\n"
    atomic_write_bytes(p, b"\x00\x01")
    assert p.read_bytes() == b"\x00\x01"
    assert sorted(os.listdir(tmp_path)) == ["a.txt"]  # no temporary file left behind


def test_atomic_write_failure_keeps_old_file(tmp_path, monkeypatch):
    p = atomic_write_text(tmp_path / "a.txt", "old")

    def boom(src, dst):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", boom)
    with pytest.raises(OSError):
        atomic_write_text(p, "new")
    assert p.read_text() == "old"
    assert sorted(os.listdir(tmp_path)) == ["a.txt"]


def test_atomic_write_missing_directory(tmp_path):
    with pytest.raises(FileNotFoundError):
        atomic_write_text(tmp_path / "nope" / "a.txt", "x")
