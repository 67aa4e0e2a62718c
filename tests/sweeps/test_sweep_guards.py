"""Sweeps refuse and stop cleanly: a huge grid range, a bad throw config, non-landing throw rows, ``--status`` without
creating ``--out`` and a malformed ``--scheduler`` (Ctrl-C on a running sweep: tests/cli/test_ctrl_c.py)."""

from __future__ import annotations

import math
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from throwmap.errors import ThrowmapError
from throwmap.sweeps import make_design, parse_sweep
from throwmap.sweeps.targets import run_chunk

BIN = Path(sys.executable).parent


def _cli(*args):
    from throwmap.cli import app

    return CliRunner().invoke(app, ["sweep", *[str(a) for a in args]])


def _one_line(res, field):
    assert res.exit_code == 2 and res.stdout == "", (res.exit_code, res.stdout)
    assert len(res.stderr.splitlines()) == 1 and res.stderr.startswith(f"error: {field}: "), res.stderr


def test_a_huge_range_is_refused_before_it_is_built(tmp_path):
    t0 = time.perf_counter()
    with pytest.raises(ThrowmapError) as err:
        make_design(parse_sweep({"kind": "grid", "target": "throw",
                                 "parameters": {"arm.mu": {"low": 0.1, "high": 0.5, "num": 100_000_000_000}}}))
    assert err.value.field == "parameters.arm.mu.num" and time.perf_counter() - t0 < 5
    with pytest.raises(ThrowmapError) as err:  # each axis fine, the product not
        make_design(parse_sweep({"kind": "grid", "target": "throw",
                                 "parameters": {"arm.mu": {"low": 0.1, "high": 0.5, "num": 2000},
                                                "omega": {"low": 1.0, "high": 5.0, "num": 2000}}}))
    assert err.value.field == "parameters"
    f = tmp_path / "s.toml"
    f.write_text('kind = "grid"\ntarget = "throw"\n[parameters]\n"arm.mu" = { low = 0.1, high = 0.5, num = 100000000000 }\n')
    _one_line(_cli(f, "--status"), "parameters.arm.mu.num")


@pytest.mark.parametrize("text, field", [
    ('kind = "grid"\ntarget = "throw"\n[config]\nmodel = "nosuch"\n[parameters]\nomega = [4.0, 5.0]\n', "config.model"),
    ('kind = "grid"\ntarget = "limit_set"\n[config]\npart = "nopart"\n[parameters]\nomega = [4.0]\n', "config.part"),
    ('kind = "grid"\ntarget = "throw"\n[parameters]\nmodel = ["paper", "nosuch"]\n', "parameters.model"),
])
def test_a_bad_target_config_is_refused_before_running(tmp_path, text, field):
    f = tmp_path / "s.toml"
    f.write_text(text)
    _one_line(_cli(f, "--out", tmp_path / "o"), field)
    assert not (tmp_path / "o").exists()


def test_throws_that_did_not_land_store_no_landing():
    d = make_design(parse_sweep({"kind": "grid", "target": "throw", "parameters": {"x": [0.15, 0.001], "side": [0, 7]}}))
    rows = run_chunk("throw", list(d.configs), list(d.seeds), None)
    by = {(c["x"], c["side"]): r for c, r in zip(d.configs, rows)}
    ok = by[(0.15, 0)]
    assert ok["status"] == "ok" and math.isfinite(ok["landing_x"]) and ok["landing_side"] >= 0
    for key in [(0.15, 7), (0.001, 0), (0.001, 7)]:
        r = by[key]
        assert r["status"] != "ok" and r["landing_x"] is None and r["landing_side"] is None, (key, r)


def test_status_creates_nothing(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('kind = "grid"\ntarget = "throw"\n[parameters]\nx = [0.1, 0.2]\n')
    res = _cli(f, "--status", "--out", tmp_path / "o")
    assert res.exit_code == 0, res.stderr
    assert "rows stored 0, missing 2" in res.stdout and not (tmp_path / "o").exists()


SETTLE = 'kind = "grid"\ntarget = "experiment:settle"\nseed = 1\nn = 4\n[parameters]\n"arm.mu" = [0.3, 0.9]\n'


def test_a_sweep_over_max_time_is_refused_before_any_work_and_runs_with_force(tmp_path, monkeypatch):
    """``--max-time`` / ``--force`` as in the other long commands: the missing points' time, from a sample timed
    in this process, over the limit is one line on ``sweep``, exit 2, before ``--out`` is made or a cluster
    started; ``--force`` runs the same sweep."""
    import throwmap.sweeps.run as run_mod

    def no_cluster(*args, **kwargs):
        raise AssertionError("a cluster was started for a refused sweep")

    f = tmp_path / "s.toml"
    f.write_text(SETTLE)
    out = tmp_path / "o"
    monkeypatch.setattr(run_mod, "_client", no_cluster)
    res = _cli(f, "--out", out, "--workers", "1", "--max-time", "1e-6")
    _one_line(res, "sweep")
    assert "experiment:settle sweep on 2 points needs ≈" in res.stderr and "over the limit of 1e-06 s" in res.stderr
    assert "--force" in res.stderr and not out.exists()
    monkeypatch.undo()
    proc = subprocess.run([sys.executable, "-m", "throwmap", "sweep", str(f), "--out", str(out), "--workers", "1",
                           "--max-time", "1e-6", "--force"], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert "rows after 2" in proc.stdout and "complete" in proc.stdout


def test_a_malformed_scheduler_is_one_line(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('kind = "grid"\ntarget = "throw"\n[parameters]\nx = [0.1, 0.2]\n')
    res = subprocess.run([str(BIN / "throwmap"), "sweep", str(f), "--out", str(tmp_path / "o"), "--scheduler",
                          "nonsense"], capture_output=True, text=True, timeout=60)
    assert res.returncode == 2 and res.stderr.startswith("error: scheduler: cannot connect to 'nonsense'")
    assert len(res.stderr.strip().splitlines()) == 1, res.stderr
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("address", ["tcp://127.0.0.1:9", "tcp://127.0.0.1:99999"])
def test_an_unreachable_scheduler_fails_before_the_out_folder_is_written(tmp_path, address):
    f = tmp_path / "s.toml"
    f.write_text('kind = "grid"\ntarget = "throw"\n[parameters]\nx = [0.1, 0.2]\n')
    res = subprocess.run([str(BIN / "throwmap"), "sweep", str(f), "--out", str(tmp_path / "o"), "--scheduler",
                          address, "--connect-timeout", "2"], capture_output=True, text=True, timeout=120)
    assert res.returncode == 2, res.stderr
    assert res.stderr.startswith("error: scheduler: cannot connect to"), res.stderr
    assert len(res.stderr.strip().splitlines()) == 1, res.stderr
    assert not (tmp_path / "o").exists()
