"""Hardening found by an outside tester: ``experiment --workers``, the feed config's ``settings``
overrides and the keys of a ``--cavity`` file. Each refusal is one ``error: <field>: …`` line on
stderr, exit 2, no traceback, nothing on stdout.

The feed configs use the impulse arm (its cavity design uses the exact model: about a second) and
``--workers 1``: a config error must surface before any trial's physics.
"""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from throwmap.cli.app import app

runner = CliRunner()
PROFILE = "[[0.06, 0.0], [0.06, -0.02], [0.0, -0.02]]"
THROW = ["throw", "--part", "triangle", "--h", "-0.01", "--length", "0.3", "--mu", "1", "--x", "0.15",
         "--side", "0", "--omega", "5", "--model", "engine"]
FEED = 'max_throws = 1\nhold_throws = 0\n[noise]\nomega_rel = 0.03\nmu_rel = 0.1\nrealisation = "impulse"\n'


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def one_error(result, field):
    """Exit 2, exactly one stderr line ``error: <field>: …``, nothing on stdout, no traceback."""
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}: "), result.stderr
    assert result.stdout == "" and "Traceback" not in result.output
    return lines[0]


# ---------------------------------------------------------------- 1. --workers
def test_workers_below_zero_are_refused_and_zero_is_documented_as_all_cores():
    # 0 is the documented default ("all cores", as in run_experiment and the engine options): kept
    line = one_error(invoke("experiment", "feed", "--workers", -1, "--n", 2), "workers")
    assert "got -1" in line and "0: all cores" in line
    one_error(invoke("experiment", "feed", "--workers", "1.5", "--n", 2), "workers")
    assert "0: all cores" in invoke("experiment", "--help").stdout
