"""Usage errors of the option parser get the CLI's one line ``error: <field>: <reason>``, exit 2.

Also: ``--side`` follows the library's one rule (:meth:`throwmap.Part.check_side`), so the
command line accepts exactly the sides :func:`throwmap.throw` accepts.
"""

from __future__ import annotations

import subprocess
import sys

import pytest
from typer.testing import CliRunner

import throwmap as tm
from throwmap.cli.app import app
from throwmap.errors import InvalidStateError
from throwmap.io.config import resolve_part

runner = CliRunner()

THROW = ["throw", "--part", "triangle", "--h", "-0.01", "--x", "0.2", "--model", "paper"]


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def assert_one_error(result, field, *words):
    """Exit 2, one stderr line ``error: <field>: …`` naming ``words``, nothing on stdout, no traceback."""
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {field}: "), lines[0]
    for w in words:
        assert w in lines[0], (w, lines[0])
    assert result.stdout == ""
    assert "Traceback" not in result.output and "Usage:" not in result.output and "╭" not in result.output


CASES = {
    "h is not a number": (["throw", "--part", "triangle", "--h", "abc", "--x", "0.2", "--side", "0", "--omega", "4"],
                          "h", ["number", "'abc'"]),
    "h=abc spelling": (["throw", "--part", "triangle", "--h=abc", "--x", "0.2", "--side", "0", "--omega", "4"],
                       "h", ["number", "'abc'"]),
    "omega is not a number": ([*THROW, "--side", "0", "--omega", "abc"], "omega", ["number", "'abc'"]),
    "omega without a value": ([*THROW, "--side", "0", "--omega"], "omega", ["--omega", "value"]),
    "side 0.5": ([*THROW, "--side", "0.5", "--omega", "4"], "side", ["integer", "0.5"]),
    "unknown option": ([*THROW, "--side", "0", "--omega", "4", "--bogus", "1"], "option", ["'--bogus'", "throw"]),
    "misspelt option": ([*THROW, "--side", "0", "--omega", "4", "--jsn"], "option", ["'--jsn'", "--json"]),
    "unknown root option": (["--bogus"], "option", ["'--bogus'"]),
    "missing option": ([*THROW, "--omega", "4"], "side", ["--side", "missing"]),
    "unknown command": (["thrw", "--part", "triangle"], "command", ["'thrw'", "'throw'"]),
    "extra argument": ([*THROW, "--side", "0", "--omega", "4", "surplus"], "arguments", ["surplus"]),
    "n is not an integer": (["iterate", "--part", "triangle", "--h", "-0.01", "--x", "0.2", "--side", "0",
                             "--omega", "4", "-n", "x"], "n", ["integer", "'x'"]),
    "analysis command, grid not an integer": (["basins", "--part", "triangle", "--h", "-0.01", "--omega", "4",
                                               "--grid", "abc"], "grid", ["integer", "'abc'"]),
    "n is a float literal": (["iterate", "--part", "triangle", "--h", "-0.01", "--x", "0.2", "--side", "0",
                              "--omega", "4", "-n", "3.0"], "n", ["integer", "'3.0'"]),
    "fps is a float literal": (["animate", "--part", "triangle", "--h", "-0.01", "--x", "0.2", "--side", "0",
                                "--omega", "4", "--fps", "2.0"], "fps", ["integer", "'2.0'"]),
    "dashed option names the field": (["compare", "--part", "triangle", "--h", "-0.01", "--n-x", "1.0"], "n_x",
                                      ["integer"]),
    "animate, speed not a number": (["animate", "--part", "triangle", "--h", "-0.01", "--x", "0.2", "--side", "0",
                                     "--omega", "4", "--speed", "fast"], "speed", ["number", "'fast'"]),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_usage_error_is_one_line(case):
    args, field, words = CASES[case]
    assert_one_error(invoke(*args), field, *words)


@pytest.mark.parametrize("args, field", [
    (["throw", "--part", "triangle", "--h", "abc", "--x", "0.2", "--side", "0", "--omega", "4"], "h"),
    (["thrw"], "command"),
])
def test_usage_error_through_the_console_entry_point(args, field):
    """``python -m throwmap`` (the real entry point, no test runner in between)."""
    proc = subprocess.run([sys.executable, "-m", "throwmap", *args], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2, proc.stderr
    assert proc.stdout == ""
    lines = proc.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}: "), proc.stderr


def test_help_and_version_still_work():
    assert invoke("--version").exit_code == 0
    result = invoke("throw", "--help")
    assert result.exit_code == 0 and "--side" in result.stdout
    bare = invoke()  # no arguments: the help, as before
    assert "Usage" in bare.output and "throw" in bare.output


# ---------------------------------------------------------------- one rule for --side
SIDES = {"0": 0, "1": 1, "2": 2, "+1": 1, "01": 1, "1.0": 1.0, "0.5": 0.5, "1e0": 1.0, "-1": -1, "3": 3, "7": 7,
         "abc": "abc"}
"""What the user types → the Python value the same user would pass to ``throw()``."""


def _api_refuses_side(value) -> bool:
    part = resolve_part("triangle").part
    try:
        tm.throw(part, tm.Arm(h=-0.01), 0.2, value, 4.0, model="paper")
    except InvalidStateError as err:
        return err.field == "side"
    return False


@pytest.mark.parametrize("text", sorted(SIDES))
def test_side_follows_the_library_rule(text):
    refused_by_api = _api_refuses_side(SIDES[text])
    result = invoke(*THROW, "--side", text, "--omega", "4", "--json")
    if refused_by_api:
        assert_one_error(result, "side")
    else:
        assert result.exit_code == 0, result.output


def test_side_rule_refuses_and_accepts_both_kinds():
    """The table above exercises both outcomes (a rule compared only where it cannot differ proves nothing)."""
    verdicts = {text: _api_refuses_side(v) for text, v in SIDES.items()}
    assert verdicts["1.0"] and verdicts["0.5"] and verdicts["abc"] and verdicts["-1"]
    assert not verdicts["0"] and not verdicts["1"] and not verdicts["+1"]


def test_integer_options_follow_the_library_rule():
    """``iterate(n=3.0)`` is refused by the library, so ``-n 3.0`` is refused too; ``-n 3`` works in both."""
    part, arm = resolve_part("triangle").part, tm.Arm(h=-0.01)
    with pytest.raises(InvalidStateError) as err:
        tm.iterate(part, arm, (0.2, 0), 4.0, n=3.0, model="paper")
    assert err.value.field == "n"
    base = ["iterate", "--part", "triangle", "--h", "-0.01", "--x", "0.2", "--side", "0", "--omega", "4",
            "--model", "paper", "--json"]
    assert_one_error(invoke(*base, "-n", "3.0"), "n", "integer")
    assert tm.iterate(part, arm, (0.2, 0), 4.0, n=3, model="paper").n_throws == 3
    assert invoke(*base, "-n", "3").exit_code == 0
