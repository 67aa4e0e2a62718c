"""``throwmap map``: the throw map per side as runs of one outcome, its JSON, its figure, its errors."""

from __future__ import annotations

import json

import numpy as np
from typer.testing import CliRunner

import throwmap as tm
from throwmap.cli.app import app

runner = CliRunner()
BASE = ["map", "--part", "triangle", "--h", "-0.01", "--omega", "4", "--model", "paper", "--n", "60"]


def test_the_runs_cover_every_sample_and_agree_with_single_throws(tmp_path):
    fig = tmp_path / "map.png"
    r = runner.invoke(app, BASE + ["--json", "--plot", str(fig)])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    smp = doc["samples"]
    assert len(smp["x_m"]) == 60 * len(doc["sides"]) and fig.read_bytes().startswith(b"\x89PNG")
    covered = sum(sum(1 for x, s in zip(smp["x_m"], smp["side"]) if s == run["side"]
                      and run["x_from_m"] <= x <= run["x_to_m"]) for run in doc["runs"])
    assert covered == len(smp["x_m"])  # runs partition the samples
    tri, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01)
    for i in np.random.default_rng(3).choice(len(smp["x_m"]), 8, replace=False):
        out = tm.throw(tri, arm, smp["x_m"][i], smp["side"][i], 4.0, model="paper")
        assert out.status.label == smp["status"][i]
        if out.ok:
            assert out.side == smp["side_next"][i] and abs(out.x - smp["x_next_m"][i]) < 1e-12
    kinds = {run["outcome"] for run in doc["runs"]}
    assert "jog" in kinds and any(k.startswith("flip to side") for k in kinds)


def test_the_table_names_each_run_and_bad_input_is_one_line():
    r = runner.invoke(app, BASE)
    assert r.exit_code == 0 and "flip to side 1" in r.stdout and "jog:" in r.stdout
    r = runner.invoke(app, BASE[:-2] + ["--n", "1"])
    assert r.exit_code == 2 and r.stderr.strip() == "error: n: must be ≥ 2, got 1"


def test_an_x_max_below_a_sides_first_start_is_refused():
    for bad in ("-1", "0.02"):
        res = runner.invoke(app, ["map", "--part", "triangle", "--h", "-0.01", "--omega", "4", "--x-max", bad])
        assert res.exit_code == 2 and res.stdout == "", res.output
        assert res.stderr.startswith("error: x_max: must exceed the first valid x on every side"), res.stderr
