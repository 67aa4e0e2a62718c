"""``throwmap design passage`` / ``feed-search`` / ``cavity --config`` end to end: figures in the
JSON agree with the library, bad input is one line with exit 2."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.design.passage import first_passage, recoil_table
from throwmap.io.config import load_config

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[2]
PART = str(ROOT / "examples" / "recoil_feeder.toml")
QUICK = ["--step", "0.04", "--x-max", "0.44", "--n", "300", "--throws", "20", "--workers", "1"]


@pytest.mark.slow
def test_passage_json_matches_the_library():
    res = runner.invoke(app, ["design", "passage", "--part", PART, "--omega", "4.56", "--side", "0", "--json"] + QUICK)
    assert res.exit_code in (0, 1), res.output
    doc = json.loads(res.stdout)
    cfg = load_config(PART)
    table = recoil_table(cfg.part, cfg.arm, 4.56, step=0.04, x_max=0.44, workers=1)
    p = first_passage(cfg.part, table, 0, n=300, throws=20, seed=0)
    assert [r["good"] for r in doc["rows"]] == pytest.approx(list(p.good))
    assert [r["holds"] for r in doc["rows"]] == [bool(h) for h in p.holds]
    assert (doc["window_m"] is None) == (res.exit_code == 1)
    assert doc["arm"]["h"] == pytest.approx(cfg.arm.h)


@pytest.mark.parametrize("args, field", [
    (["design", "passage", "--part", PART, "--omega", "4.5", "--workers", "-2"], "workers"),
    (["design", "passage", "--part", PART, "--omega", "4.5", "--purity", "2"], "purity"),
    (["design", "passage", "--part", PART, "--omega", "4.5", "--step", "-1"], "step"),
    (["design", "passage", "--part", PART, "--omega", "4.5", "--side", "5"], "side"),
    (["design", "feed-search", "--n", "0"], "n"),
    (["design", "feed-search", "--workers", "-1"], "workers"),
])
def test_bad_input_is_one_line_exit_2(args, field):
    res = runner.invoke(app, args)
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and field in lines[0] and "Traceback" not in res.output


def test_cavity_config_must_be_a_closed_cavity_run(tmp_path):
    cfg = tmp_path / "wall.toml"
    cfg.write_text(f'part = "{PART}"\nside = 0\nomega = 4.56\nh = -0.02\nfixture = "wall"\n')
    res = runner.invoke(app, ["design", "cavity", "--config", str(cfg), "--no-verify"])
    assert res.exit_code == 2 and "config" in res.output


@pytest.mark.parametrize("extra, field", [
    (["--zeta", "1"], "zeta"), (["--zeta", "-1"], "zeta"), (["--zeta", "1.5"], "zeta"),
    (["--seed", "-3"], "seed"), (["--step", "1"], "step"), (["--sigma", "0.4"], "sigma"),
    (["--recoil", "3"], "recoil"), (["--workers", "-1"], "workers"),
])
def test_more_bad_passage_input(extra, field):
    res = runner.invoke(app, ["design", "passage", "--part", PART, "--omega", "4.5"] + extra)
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}"), lines


@pytest.mark.slow
def test_short_table_still_scans_end_stops():
    res = runner.invoke(app, ["design", "passage", "--part", PART, "--omega", "4.5", "--x-max", "0.3", "--step", "0.02",
                              "--n", "50", "--throws", "5", "--workers", "1", "--json"])
    assert res.exit_code in (0, 1), res.output
    doc = json.loads(res.stdout)
    assert doc["rows"] and all(r["X_m"] < 0.3 for r in doc["rows"])


def test_feed_search_negative_seed():
    res = runner.invoke(app, ["design", "feed-search", "--seed", "-1"])
    assert res.exit_code == 2 and "seed" in res.output
