"""``throwmap design`` end to end (typer's CliRunner): points, example, one-line errors with exit 2."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from throwmap.cli import design as cli_design
from throwmap.cli.app import app
from throwmap.design.examples import feeder_design

runner = CliRunner()
PNG = b"\x89PNG\r\n\x1a\n"
POINTS = ["design", "points", "--part", "triangle", "--h", "-0.01", "--length", "0.6", "--omega", "4",
          "--weight-mass", "0.03", "--weight-at", "0.03,0.03", "--target", "0=0.40", "--target", "1=0.25",
          "--target", "2=0.25", "--escape-margin", "0"]


def test_points_json_and_plot(tmp_path):
    out = tmp_path / "design.png"
    res = runner.invoke(app, POINTS + ["--json", "--plot", str(out)])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["success"] is True
    assert doc["jacobian"]["rank"] == 3
    for s, v in {"0": 0.40, "1": 0.25, "2": 0.25}.items():
        assert abs(doc["achieved_r_m"][s] - v) <= 1e-4
    assert out.read_bytes().startswith(PNG)


def test_points_table():
    res = runner.invoke(app, POINTS)
    assert res.exit_code == 0, res.output
    assert "success: reached" in res.stdout and "rank 3 → 3 of 3" in res.stdout


def test_points_that_feed_nothing_exit_1():
    # the critical points are hit, but at that ω every orbit escapes: not a design
    escaping = POINTS[:8] + ["--omega", "5", "--weight-mass", "0.03", "--weight-at", "0.03,0.03",
                             "--target", "0=0.30", "--target", "1=0.15", "--target", "2=0.15"]
    res = runner.invoke(app, escaping + ["--json"])
    assert res.exit_code == 1, res.output
    doc = json.loads(res.stdout)
    assert doc["success"] is False and doc["targets_reached"] is True and "every orbit escapes" in doc["limit_set"]


def test_a_design_within_its_escape_margin_is_refused(monkeypatch):
    """The margins (a continuation along ω and the weight's place) are reported; within --escape-margin × ω of
    escape the design is refused (a stated margin stands in for the continuation here)."""
    import throwmap.analysis.margins as margins
    from throwmap.analysis.continuation import Event

    calls = []

    def near(part, arm, param, value, *, span, omega=None, model="rigid_body", **kw):
        calls.append((param, span))
        e = Event("escape_onset", value * 1.03, 1e-3)
        return margins.Margin(param, "", value, (value - span, value + span), e, value * 0.03, e, value * 0.03, None)

    monkeypatch.setattr(margins, "margin", near)
    args = POINTS[:-2]
    res = runner.invoke(app, args + ["--json"])
    assert res.exit_code == 1, res.output
    doc = json.loads(res.stdout)
    assert doc["success"] is False and "within 5 % of ω of escape" in doc["message"]
    assert [m["param"] for m in doc["margins"]] == ["omega", "weight_x", "weight_y"] and calls[1:] == [
        ("weight_x", 0.01), ("weight_y", 0.01)]
    res = runner.invoke(app, args + ["--escape-margin", "0.02", "--json"])  # 3 % away: outside a 2 % margin
    assert res.exit_code == 0 and json.loads(res.stdout)["margins"][0]["escape_distance"] > 0


def test_points_not_reached_exits_1():
    res = runner.invoke(app, POINTS[:-6] + ["--target", "1=0.01", "--vary", "weight_x"])
    assert res.exit_code == 1, res.output
    assert "FAILED" in res.stdout


@pytest.mark.parametrize("bad, field", [
    (["--target", "0:0.3"], "target"),
    (["--target", "0=abc"], "target"),
    (["--weight-at", "0.3"], "weight_at"),
    (["--weight-at", "0.5,0.5"], "weight_at"),
    (["--vary", "colour"], "vary"),
])
def test_bad_input_one_line_exit_2(bad, field):
    args = [a for a in POINTS]
    if bad[0] == "--target":
        args = args[:-6]
    elif bad[0] == "--weight-at":
        i = args.index("--weight-at")
        del args[i:i + 2]
    res = runner.invoke(app, args + bad)
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}:"), res.stderr


def test_example_feeder(tmp_path):
    out = tmp_path / "feeder.png"
    data = tmp_path / "feeder.toml"
    res = runner.invoke(app, ["design", "example", "feeder", "--no-engine", "--plot", str(out), "--write-data",
                              str(data), "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["separation"]["holds"] is True
    assert doc["end_wall"]["S_m"] > 0.02
    assert out.read_bytes().startswith(PNG)
    assert "[end_wall]" in data.read_text()
    fd = feeder_design()
    assert abs(doc["design"]["omega_rad_s"] - fd.omega) < 1e-4


def test_example_unknown_name():
    res = runner.invoke(app, ["design", "example", "nonsense", "--plot", "none"])
    assert res.exit_code == 2
    assert res.stderr.strip().startswith("error: name:")


def test_cavity_subcommand_registers_only_when_present(monkeypatch):
    calls = []

    class Fake:
        @staticmethod
        def register(group):
            calls.append(group)

    imported = []
    monkeypatch.setattr(cli_design.importlib.util, "find_spec", lambda name: object())
    monkeypatch.setattr(cli_design.importlib, "import_module", lambda name: imported.append(name) or Fake)
    cli_design._register_cavity("group")
    assert calls == ["group", "group"]  # design cavity and design passage/feed-search
    assert [n.rsplit(".", 1)[-1] for n in imported] == ["cavity", "passage"]
    monkeypatch.setattr(cli_design.importlib.util, "find_spec", lambda name: None)
    cli_design._register_cavity("other")
    assert calls == ["group", "group"]


def test_benchmark_script_runs_small(tmp_path, capsys):
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "benchmarks" / "design.py"
    spec = importlib.util.spec_from_file_location("bench_design", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    res = mod.main(["--repeat", "1", "--json", str(tmp_path / "b.json")])
    assert "ratio design / critical_points" in capsys.readouterr().out
    assert res["design_success"] and res["critical_points_ms"] > 0 and res["design_ms"] > 0
    assert json.loads((tmp_path / "b.json").read_text())["design_evaluations"] == res["design_evaluations"]
