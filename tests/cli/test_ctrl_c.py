"""Ctrl-C stops a command with one line ``interrupted: …`` (what it kept, how to resume) and exit status 130, never
a traceback.

The long commands run on a pseudo-terminal, their controlling terminal as in a shell, and Ctrl-C is typed on it
once they have stored some work: the terminal then signals the whole foreground process group, the command and its
worker processes alike, as a user's Ctrl-C does. The group-level rule (a command that keeps nothing as it goes) is
checked in process, with the library call replaced by one that raises :class:`KeyboardInterrupt`.
"""

from __future__ import annotations

import os
import re
import select
import signal
import subprocess
import sys
import time

import pytest
from typer.testing import CliRunner

from throwmap.cli.app import app

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminals are POSIX")

ANSI = re.compile(r"\x1b\[[0-9;?]*[A-Za-z]")


def stored(path) -> int:
    """Non-empty lines of ``path`` (0 while it is missing)."""
    try:
        with open(path, encoding="utf-8") as f:
            return sum(1 for line in f if line.strip())
    except OSError:
        return 0


# The child: a new session (``start_new_session``) whose controlling terminal becomes the pseudo-terminal on its
# standard input (TIOCSCTTY), then the command. Started by subprocess, which forks in C: a fork by Python in this
# (threaded) test process could hang the child before its exec.
_CHILD = ("import fcntl, os, sys, termios; fcntl.ioctl(0, termios.TIOCSCTTY, 0); "
          "os.execv(sys.executable, [sys.executable, '-m', 'throwmap', *sys.argv[1:]])")


def run_in_terminal(args, ready, cwd, limit: float = 600.0) -> tuple[int, str]:
    """Run ``python -m throwmap ARGS`` in ``cwd`` on a pseudo-terminal and type Ctrl-C on it once ``ready()``.

    Returns the exit status and what the terminal showed, without colours (the progress bars' redraws are lines
    of their own). Fails when the command ends before it could be interrupted, or runs past ``limit`` s."""
    import pty

    master, slave = pty.openpty()
    try:
        proc = subprocess.Popen([sys.executable, "-c", _CHILD, *map(str, args)], cwd=cwd, stdin=slave, stdout=slave,
                                stderr=slave, start_new_session=True)
    finally:
        os.close(slave)
    chunks, typed, t0 = [], False, time.monotonic()
    try:
        while time.monotonic() - t0 <= limit:
            readable, _, _ = select.select([master], [], [], 0.05)
            if readable:
                try:
                    data = os.read(master, 65536)
                except OSError:  # EIO: every process holding the terminal has closed it (Linux)
                    data = b""
                if not data:
                    break
                chunks.append(data)
            elif proc.poll() is not None:  # the command has ended and nothing more is coming
                break
            if not typed and proc.poll() is None and ready():
                os.write(master, b"\x03")  # Ctrl-C: the terminal sends SIGINT to its foreground process group
                typed = True
    finally:
        try:
            code = proc.wait(timeout=max(0.0, limit - (time.monotonic() - t0)) + 1.0)
            late = False
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            code, late = proc.wait(), True
        os.close(master)
    text = ANSI.sub("", b"".join(chunks).decode("utf-8", "replace"))
    assert not late, f"still running after {limit} s:\n{text[-3000:]}"
    assert typed, f"the command ended before it could be interrupted:\n{text[-3000:]}"
    return code, text


def interrupted(code: int, text: str) -> str:
    """The one ``interrupted:`` line of an exit-130 run that printed no traceback."""
    lines = [line.strip() for line in re.split(r"[\r\n]+", text)]
    found = [line for line in lines if line.startswith("interrupted: ")]
    assert code == 130 and len(found) == 1 and "Traceback" not in text, (code, text[-3000:])
    return found[0]


def test_experiment_ctrl_c_keeps_the_trials_and_exits_130(tmp_path):
    out = tmp_path / "run"
    trials = out / "trials.jsonl"
    code, text = run_in_terminal(["experiment", "settle", "--n", "2000", "--seed", "1", "--out", out],
                                 lambda: stored(trials) >= 1, tmp_path)
    line = interrupted(code, text)
    k = stored(trials)
    assert k >= 1 and line == f"interrupted: {k} trial(s) stored in {str(out)!r}; the same command resumes from them"


@pytest.mark.slow
def test_sweep_ctrl_c_keeps_the_parts_and_exits_130(tmp_path):
    sweep = tmp_path / "s.toml"
    sweep.write_text('kind = "grid"\ntarget = "experiment:settle"\nseed = 1\nn = 200\n[parameters]\n'
                     '"arm.mu" = { low = 0.3, high = 0.9, num = 40 }\n')  # the first part after ≈ 1/5 of the sweep
    out = tmp_path / "s.parquet"
    code, text = run_in_terminal(["sweep", sweep, "--workers", "2", "--out", out],
                                 lambda: any(out.glob("part-*.parquet")), tmp_path)
    line = interrupted(code, text)
    assert re.fullmatch(rf"interrupted: [1-9]\d* rows stored in {re.escape(repr(str(out)))}, rerun to resume", line), line
    assert (out / "_manifest.json").is_file()


@pytest.mark.slow
def test_reproduce_ctrl_c_keeps_the_trials_and_exits_130(tmp_path):
    out = tmp_path / "rep"
    trials = out / "experiments" / "feeding" / "trials.jsonl"
    code, text = run_in_terminal(["reproduce", "--quick", "--only", "feeding", "--workers", "1", "--out", out],
                                 lambda: stored(trials) >= 1, tmp_path)
    line = interrupted(code, text)
    k = stored(trials)
    assert k >= 1 and line == (f"interrupted: 0 figure(s) and {k} trial(s) stored in {str(out)!r}; the same command "
                               f"resumes the trials")


def _interrupt(*args, **kwargs):
    raise KeyboardInterrupt


def test_ctrl_c_in_a_command_without_its_own_line(monkeypatch):
    """A command that keeps nothing as it goes: the app's group prints the line and exits 130."""
    from throwmap.cli import analysis as cli_analysis

    monkeypatch.setattr(cli_analysis, "basins", _interrupt)
    result = CliRunner().invoke(app, ["basins", "--part", "triangle", "--h", "-0.01", "--omega", "4"])
    assert (result.exit_code, result.stderr, result.stdout) == (130, "interrupted: nothing was written\n", "")


def test_ctrl_c_in_an_experiment_without_out(monkeypatch):
    import throwmap.experiments.runner as runner_mod

    monkeypatch.setattr(runner_mod, "run_experiment", _interrupt)
    result = CliRunner().invoke(app, ["experiment", "settle", "--n", "5"])
    assert (result.exit_code, result.stderr) == (130, "interrupted: no --out DIR, so no trial was kept\n")


# ------------------------------------------------------------------ Ctrl-C while the command line is being imported
def _console_script() -> tuple[str, str]:
    """``(module, function)`` of the ``throwmap`` console script, as pyproject.toml declares it."""
    import tomllib
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    target = tomllib.loads((root / "pyproject.toml").read_text(encoding="utf-8"))["project"]["scripts"]["throwmap"]
    module, _, func = target.partition(":")
    return module, func


# The child: the console script's own entry point, with one import (``SLOW``) held up until the test sends SIGINT:
# it prints "importing" and sleeps, so the signal lands while the command line's modules are still being imported.
_IMPORTING = ("import builtins, sys, time\n"
              "module, func, slow = sys.argv[1:4]\n"
              "sys.argv[1:] = sys.argv[4:]\n"
              "real = builtins.__import__\n"
              "def held(name, *args, **kwargs):\n"
              "    if name == slow and not getattr(held, 'done', False):\n"
              "        held.done = True\n"
              "        sys.stdout.write('importing\\n'); sys.stdout.flush()\n"
              "        time.sleep(120)\n"
              "    return real(name, *args, **kwargs)\n"
              "builtins.__import__ = held\n"
              "getattr(__import__(module, fromlist=[func]), func)()\n")


@pytest.mark.parametrize("slow", ["numpy", "typer"])
def test_ctrl_c_while_the_console_script_imports_exits_130_without_a_traceback(slow):
    """A real SIGINT while ``import throwmap`` (numpy) or ``throwmap.cli`` (typer) is under way: one line, exit
    130. ``numpy`` is imported by the package's ``__init__``, before any of the command line's own code runs."""
    module, func = _console_script()
    proc = subprocess.Popen([sys.executable, "-c", _IMPORTING, module, func, slow, "--version"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline() == "importing\n"
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert (proc.returncode, err, out) == (130, "interrupted: nothing was written\n", ""), (proc.returncode, err)


def test_ctrl_c_in_the_entry_point_after_the_imports(monkeypatch, capsys):
    """An interruption that no command handles (here: as the app starts) still leaves one line and exit 130."""
    import importlib

    cli_app = importlib.import_module("throwmap.cli.app")  # the module (``throwmap.cli.app`` is also the Typer app)
    module, func = _console_script()
    entry = getattr(importlib.import_module(module), func)

    def interrupted_app(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli_app, "main", interrupted_app)
    handler = signal.getsignal(signal.SIGINT)  # the entry point ignores a second Ctrl-C as it exits: restored here,
    try:  # or the worker's later tests that send themselves SIGINT would see it ignored
        with pytest.raises(SystemExit) as exc:
            entry(["--version"])
    finally:
        signal.signal(signal.SIGINT, handler)
    assert exc.value.code == 130 and capsys.readouterr().err.startswith("interrupted: ")
