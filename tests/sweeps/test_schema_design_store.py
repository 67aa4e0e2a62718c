"""Sweep files, designs and the Parquet store, without a cluster (fast)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from throwmap.errors import ThrowmapError
from throwmap.sweeps import make_design, parse_sweep, read_sweep, spec_hash
from throwmap.sweeps.schema import jsonable
from throwmap.sweeps.design import point_seed
from throwmap.sweeps.run import sweep_status
from throwmap.sweeps.store import column_types, finished_chunks, part_path, prepare_out, read_table, write_chunk

SETTLE = {"kind": "grid", "target": "experiment:settle", "n": 5, "seed": 3,
          "parameters": {"arm.mu": [0.4, 0.8], "arm.h": {"low": -0.02, "high": 0.0, "num": 3}}}


def test_import_throwmap_loads_no_dask():
    code = "import sys, throwmap, throwmap.sweeps, throwmap.cli.sweep; print(sorted(m for m in ('dask', 'distributed', 'pyarrow') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_grid_is_every_combination_last_fastest():
    d = make_design(parse_sweep(SETTLE))
    assert d.n_points == 6 and d.names == ("arm.mu", "arm.h")
    assert d.points[:3] == ((0.4, -0.02), (0.4, -0.01), (0.4, 0.0))
    assert d.configs[4]["arm"]["mu"] == 0.8 and d.configs[4]["arm"]["h"] == -0.01
    assert set(d.seeds) == {3}  # common random numbers by default
    assert d.chunk == 1 and d.n_chunks == 6


def test_random_design_is_seeded_and_within_ranges():
    doc = {"kind": "random", "target": "throw", "samples": 50, "seed": 11,
           "parameters": {"omega": {"low": 2.0, "high": 8.0}, "arm.mu": {"low": 0.1, "high": 10.0, "log": True},
                          "side": [0, 1, 2]}}
    a, b = make_design(parse_sweep(doc)), make_design(parse_sweep(doc))
    assert a.points == b.points and a.n_points == 50
    assert all(2.0 <= p[0] < 8.0 and 0.1 <= p[1] < 10.0 and p[2] in (0, 1, 2) for p in a.points)
    c = make_design(parse_sweep({**doc, "seed": 12}))
    assert c.points != a.points
    assert a.chunk == 256 and a.n_chunks == 1


def test_spawned_point_seeds():
    d = make_design(parse_sweep({**SETTLE, "common_random_numbers": False}))
    assert d.seeds == tuple(point_seed(3, i) for i in range(6)) and len(set(d.seeds)) == 6


def test_plus_key_sets_several_fields():
    doc = {"kind": "grid", "target": "experiment:settle", "n": 2,
           "parameters": {"noise.mu_rel+noise.omega_rel": [0.0, 0.1]}}
    d = make_design(parse_sweep(doc))
    assert [(c["noise"]["mu_rel"], c["noise"]["omega_rel"]) for c in d.configs] == [(0.0, 0.0), (0.1, 0.1)]


@pytest.mark.parametrize("doc, field", [
    ({**SETTLE, "bogus": 1}, "bogus"),
    ({**SETTLE, "kind": "lattice"}, "kind"),
    ({**SETTLE, "target": "experiment:nosuch"}, "target"),
    ({**SETTLE, "target": "throws"}, "target"),
    ({k: v for k, v in SETTLE.items() if k != "n"}, "n"),
    ({**SETTLE, "parameters": {"arm.mu": [0.4, -1.0]}}, "parameters.arm.mu"),
    ({**SETTLE, "parameters": {"muu": [0.4]}}, "parameters.muu"),
    ({**SETTLE, "parameters": {"arm.mu": 3}}, "parameters.arm.mu"),
    ({**SETTLE, "parameters": {"arm.mu": []}}, "parameters"),
    ({**SETTLE, "parameters": {"arm.h": {"low": 0.0, "high": 1.0}}}, "parameters.arm.h.num"),
    ({**SETTLE, "parameters": {"arm.h": {"low": 1.0, "high": 0.0, "num": 2}}}, "parameters.arm.h.high"),
    ({**SETTLE, "parameters": {"arm.h": {"low": 0.0, "high": 1.0, "num": 2, "step": 1}}}, "parameters.arm.h.step"),
    ({**SETTLE, "kind": "random"}, "samples"),
    ({**SETTLE, "config": {"muu": 1}}, "config.muu"),
    ({"kind": "grid", "target": "throw", "n": 3, "parameters": {"x": [0.1]}}, "n"),
    ({"kind": "grid", "target": "throw", "trials_per_task": 3, "parameters": {"x": [0.1]}}, "trials_per_task"),
    ({**SETTLE, "trials_per_task": 0}, "trials_per_task"),
    ({"kind": "grid", "target": "throw", "parameters": {"side": [0.5]}}, "parameters.side"),
    ({"kind": "grid", "target": "throw", "parameters": {"status": ["ok"]}}, "parameters.status"),
    ({"kind": "grid", "target": "throw", "config": {"omega": -1}, "parameters": {"x": [0.1]}}, "config.omega"),
])
def test_errors_are_one_line_naming_the_field(doc, field):
    with pytest.raises(ThrowmapError) as info:
        spec = parse_sweep(doc)
        d = make_design(spec)
        column_types(d.names, d.points, {"status": "string"})
    assert info.value.field == field, str(info.value)
    assert "\n" not in str(info.value)


def test_hash_ignores_layout_and_comments(tmp_path):
    a = tmp_path / "a.toml"
    b = tmp_path / "b.toml"
    a.write_text('kind = "grid"\ntarget = "throw"\n[parameters]\nx = [0.1, 0.2]\nomega = [5.0]\n')
    b.write_text('# a comment\ntarget = "throw"\nkind = "grid"\n\n[parameters]\nx = [0.1, 0.2]  # m\nomega = [5.0]\n')
    assert spec_hash(read_sweep(a)[0]) == spec_hash(read_sweep(b)[0])
    b.write_text(a.read_text().replace('target = "throw"', 'target = "throw"\nretries = 5'))
    assert spec_hash(read_sweep(a)[0]) == spec_hash(read_sweep(b)[0])  # retries do not change the results
    b.write_text('kind = "grid"\ntarget = "throw"\n[parameters]\nx = [0.1, 0.3]\nomega = [5.0]\n')
    assert spec_hash(read_sweep(a)[0]) != spec_hash(read_sweep(b)[0])


def test_inf_in_a_sweep_file(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('kind = "grid"\ntarget = "limit_set"\n[config.arm]\nlength = inf\n[parameters]\n"arm.mu" = [0.5, inf]\n')
    spec, _ = read_sweep(f)
    d = make_design(spec)
    assert d.configs[1]["arm"]["mu"] == "inf" and d.configs[0]["arm"]["length"] is None  # μ = ∞ as JSON writes it; unbounded
    st = sweep_status(spec, tmp_path / "out")
    assert (st.n_points, st.rows, st.missing) == (2, 0, 2) and st.to_dict()["n_points"] == 2
    from throwmap.sweeps.run import _plan

    _plan(spec, tmp_path / "out")  # a run's first step writes the manifest (--status does not)
    assert json.loads((tmp_path / "out" / "_manifest.json").read_text())["spec"]["config"]["arm"]["length"] == "inf"


def test_store_parts_are_atomic_and_a_changed_sweep_is_refused(tmp_path):
    spec = parse_sweep({"kind": "grid", "target": "throw", "chunk": 2, "parameters": {"x": [0.1, 0.2, 0.3]}})
    d = make_design(spec)
    cols = column_types(d.names, d.points, {"status": "string"})
    out = tmp_path / "out"
    prepare_out(out, {"sweep_sha256": spec_hash(spec), "spec": jsonable(spec.model_dump()), "columns": cols})
    write_chunk(out, 0, [{"point": 0, "x": 0.1, "seed": 0, "version": "v", "status": "ok", "elapsed_s": 0.1},
                         {"point": 1, "x": 0.2, "seed": 0, "version": "v", "status": "ok", "elapsed_s": 0.1}], cols)
    (out / ".part-000001.parquet.123.tmp").write_bytes(b"torn")  # a killed run's temporary file
    part_path(out, 5).write_bytes(b"not parquet")  # a chunk the design does not have
    assert finished_chunks(out, 2, lambda c: 2 if c == 0 else 1) == {0}
    assert sorted(p.name for p in out.iterdir()) == ["_manifest.json", "part-000000.parquet"]
    t = read_table(out)
    assert t.num_rows == 2 and t.column("x").to_pylist() == [0.1, 0.2] and t.column("error").to_pylist() == [None, None]
    other = parse_sweep({"kind": "grid", "target": "throw", "chunk": 2, "parameters": {"x": [0.1, 0.2, 0.4]}})
    with pytest.raises(ThrowmapError) as info:
        prepare_out(out, {"sweep_sha256": spec_hash(other), "spec": jsonable(other.model_dump()), "columns": cols})
    assert info.value.field == "out" and "first difference: parameters.x" in str(info.value)


def _cli(*args):
    from typer.testing import CliRunner

    from throwmap.cli.app import app

    return CliRunner().invoke(app, ["sweep", *[str(a) for a in args]])


@pytest.mark.parametrize("text, field", [
    ('kind = "grid"\ntarget = "throw"\n[parameters]\nx = {low = 0.1, high = 0.2}\n', "parameters.x.num"),
    ('kind = "grid"\ntarget = "experiment:settle"\nn = 2\n[parameters]\n"arm.mu" = [0.5, -1.0]\n', "parameters.arm.mu"),
    ('kind = "grid"\ntarget = "throw"\n[parameters\n', "sweep"),
])
def test_cli_errors_are_one_line(tmp_path, text, field):
    f = tmp_path / "s.toml"
    f.write_text(text)
    res = _cli(f, "--status")
    assert res.exit_code == 2 and res.stdout == ""
    assert len(res.stderr.splitlines()) == 1 and res.stderr.startswith(f"error: {field}: "), res.stderr


def test_cli_status_and_a_changed_sweep(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the default output is a run folder in the current one
    f = tmp_path / "s.toml"
    f.write_text('kind = "grid"\ntarget = "throw"\nchunk = 2\n[parameters]\nx = [0.1, 0.2, 0.3]\n')
    res = _cli(f, "--status", "--json")
    assert res.exit_code == 0, res.stderr
    st = json.loads(res.stdout)
    assert (st["n_points"], st["n_chunks"], st["rows"], st["missing"]) == (3, 2, 0, 3)
    assert st["out"] == str(Path("runs") / "s.parquet") and not (tmp_path / "runs").exists()  # --status creates nothing
    from throwmap.sweeps.run import _plan

    (tmp_path / "runs").mkdir()
    _plan(read_sweep(f)[0], tmp_path / "runs" / "s.parquet")  # what a run does first: the manifest
    f.write_text('kind = "grid"\ntarget = "throw"\nchunk = 3\n[parameters]\nx = [0.1, 0.2, 0.3]\n')
    res = _cli(f, "--status")
    assert res.exit_code == 2 and "first difference: chunk" in res.stderr and res.stderr.startswith("error: out: ")
