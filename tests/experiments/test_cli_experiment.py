"""``throwmap experiment``: the shared contract of every experiment command."""

import json

from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.experiments.runner import run_experiment

runner = CliRunner()


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def one_error(result, field):
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}:"), result.stderr
    assert result.stdout == ""
    return lines[0]


def test_json_is_one_object_with_the_contract_keys():
    r = invoke("experiment", "settle", "--n", 6, "--seed", 2, "--workers", 1, "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    for key in ("n", "successes", "success_rate", "ci95", "failures", "seed", "parameters"):
        assert key in doc
    lib = run_experiment("settle", n=6, seed=2, workers=1)
    assert (doc["n"], doc["successes"], doc["failures"], doc["ci95"]) == (6, lib.successes, lib.failures, list(lib.ci95))


def test_table_and_list():
    r = invoke("experiment", "settle", "--n", 4, "--seed", 1, "--workers", 1)
    assert r.exit_code == 0 and "success" in r.stdout and "Wilson 95 %" in r.stdout
    for args in (("experiment", "--list"), ("experiment", "list")):
        r = invoke(*args)
        assert r.exit_code == 0 and any(line.startswith("settle ") for line in r.stdout.splitlines())
    assert "settle" in json.loads(invoke("experiment", "--list", "--json").stdout)


def test_config_file_and_out_dir(tmp_path):
    cfg = tmp_path / "settle.toml"
    cfg.write_text("height = [0.03, 0.05]\n[arm]\nlength = 0.5\n[noise]\nmu_range = [0.5, 1.0]\n")
    out = tmp_path / "run"
    r = invoke("experiment", "settle", cfg, "--n", 5, "--seed", 4, "--workers", 1, "--json", "--out", out)
    doc = json.loads(r.stdout)
    assert doc["parameters"]["length_m"] == 0.5 and doc["parameters"]["height_m"] == [0.03, 0.05]
    assert {"run.json", "trials.jsonl", "result.json", "trials.parquet"} <= {p.name for p in out.iterdir()}
    again = json.loads(invoke("experiment", "settle", cfg, "--n", 5, "--seed", 4, "--workers", 1, "--json",
                              "--out", out).stdout)
    assert again["resumed"] == 5 and again["successes"] == doc["successes"]
    one_error(invoke("experiment", "settle", cfg, "--n", 5, "--seed", 5, "--out", out), "seed")


def test_errors_are_one_line():
    line = one_error(invoke("experiment", "nope"), "experiment")
    assert "settle" in line
    one_error(invoke("experiment"), "name")
    one_error(invoke("experiment", "settle", "--n", 500, "--workers", 1, "--max-time", 0.01), "n")


def test_bad_config_names_the_field(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[arm]\nlenght = 0.5\n")
    assert "did you mean 'length'" in one_error(invoke("experiment", "settle", bad, "--n", 2), "config.arm.lenght")
    flat = tmp_path / "flat.toml"  # an arm key outside the [arm] table: said so
    flat.write_text("length = 0.5\n")
    assert "[arm] table" in one_error(invoke("experiment", "settle", flat, "--n", 2), "config.length")
    worse = tmp_path / "worse.json"
    worse.write_text('{"noise": {"omega_rel": "a lot"}}')
    one_error(invoke("experiment", "settle", worse, "--n", 2), "config.noise.omega_rel")
    one_error(invoke("experiment", "settle", tmp_path / "missing.toml", "--n", 2), "file")


def test_plot(tmp_path):
    fig = tmp_path / "settle.png"
    r = invoke("experiment", "settle", "--n", 4, "--seed", 1, "--workers", 1, "--json", "--plot", fig)
    assert r.exit_code == 0 and fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    json.loads(r.stdout)
    one_error(invoke("experiment", "settle", "--n", 4, "--plot", tmp_path / "f.xyz"), "plot")
