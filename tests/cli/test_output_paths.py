"""Every command that writes files checks its output paths before any computation.

A path that cannot be written (its folder is a file, the target is a folder, the folder
is not writable) is refused with one line ``error: <field>: …`` and exit 2, and the
computation is never started (the library call is replaced by one that fails the test).
"""

from __future__ import annotations

import os
import tempfile

import pytest
from typer.testing import CliRunner

from throwmap.cli import analysis as cli_analysis
from throwmap.cli import animate as cli_animate
from throwmap.cli import options as cli_options
from throwmap.cli import throws as cli_throws
from throwmap.cli.app import app

runner = CliRunner()

ARM = ["--part", "triangle", "--h", "-0.01"]
START = ["--x", "0.2", "--side", "0", "--omega", "4"]


def _never(*args, **kwargs):
    raise AssertionError("the computation started although the output path cannot be written")


@pytest.fixture
def no_work(monkeypatch):
    """Replace every long library call the commands make by :func:`_never`."""
    import throwmap.studies.compare as compare
    import throwmap.studies.demo as demo
    import throwmap.studies.validation as validation

    monkeypatch.setattr(demo, "run_demo", _never)
    monkeypatch.setattr(validation, "validate", _never)
    monkeypatch.setattr(compare, "compare_models", _never)
    monkeypatch.setattr(cli_throws, "iterate", _never)
    monkeypatch.setattr(cli_throws, "_iterate_with_progress", _never)
    monkeypatch.setattr(cli_animate, "_trajectory", _never)
    for name in ("limit_set", "critical_points", "basins", "funnels"):
        monkeypatch.setattr(cli_analysis, name, _never)


FILE_COMMANDS = [
    (["iterate", *ARM, *START, "-n", "2", "--plot"], "orbit.png", "plot"),
    (["compare", *ARM, "--out"], "cmp.json", "out"),
    (["animate", *ARM, *START, "--out"], "throw.gif", "out"),
    (["limitset", *ARM, "--omega", "4", "--plot"], "ls.png", "plot"),
    (["funnels", *ARM, "--omega", "4", "--plot"], "f.png", "plot"),
]
"""Commands writing one file: (command line without the path, file name, field)."""

DIR_COMMANDS = [
    (["demo", "--out"], "out"),
    (["validate", "--n", "5", "--out"], "out"),
    (["limitset", *ARM, "--omega", "4", "--out"], "out"),
    (["basins", *ARM, "--omega", "4", "--out"], "out"),
]
"""Commands writing into an ``--out`` directory: (command line without the path, field)."""


def commands(target_file, target_dir):
    """(command line, field) for each command that writes: a file target or a directory target."""
    return ([([*args, target_file(name)], field) for args, name, field in FILE_COMMANDS]
            + [([*args, target_dir()], field) for args, field in DIR_COMMANDS])


def assert_refused(result, field, *words):
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}: "), result.stderr
    for w in words:
        assert w in lines[0], (w, lines[0])
    assert "Traceback" not in result.output


def _cases(tmp_path, kind):
    blocker = tmp_path / "a_file"
    blocker.write_text("not a directory")
    if kind == "folder is a file":
        return commands(lambda name: blocker / name, lambda: blocker / "sub"), "not a directory"
    if kind == "target is a folder":
        folder = tmp_path / "a_folder"
        folder.mkdir()
        (folder / "x.gif").mkdir()
        for name in ("orbit.png", "cmp.json", "throw.gif", "ls.png", "f.png"):
            (folder / name).mkdir(exist_ok=True)
        return commands(lambda name: folder / name, lambda: blocker), "directory"
    raise AssertionError(kind)


@pytest.mark.parametrize("kind", ["folder is a file", "target is a folder"])
def test_unwritable_outputs_refused_before_work(tmp_path, no_work, kind):
    cases, words = _cases(tmp_path, kind)
    for args, field in cases:
        result = runner.invoke(app, [str(a) for a in args])
        assert_refused(result, field, words)


def test_folder_that_is_not_writable_refused_before_work(tmp_path, no_work, monkeypatch):
    """A folder where no file can be created (simulated: root may write anywhere)."""
    locked = tmp_path / "locked"
    locked.mkdir()
    real = tempfile.mkstemp

    def refuse_in_locked(*args, dir=None, **kwargs):
        if dir is not None and os.path.samefile(dir, locked):
            raise PermissionError(13, "Permission denied")
        return real(*args, dir=dir, **kwargs)

    monkeypatch.setattr(cli_options.tempfile, "mkstemp", refuse_in_locked)
    for args, field in commands(lambda name: locked / name, lambda: locked / "new" / "deeper"):
        result = runner.invoke(app, [str(a) for a in args])
        assert_refused(result, field, "not writable", "Permission denied")


def test_missing_folder_of_a_file_is_created(tmp_path, monkeypatch):
    """One rule for every output: a missing folder (however deep) of a figure, result file or
    animation is made, as ``--out`` directories are; the check itself creates nothing."""
    for args, name, field in FILE_COMMANDS:
        cli_options.check_output(tmp_path / "new" / "deep" / name, field)
    assert list(tmp_path.iterdir()) == []
    for args, name in ((["iterate", *ARM, *START, "-n", "5", "--plot"], "x.png"),
                       (["limitset", *ARM, "--omega", "4", "--starts", "4", "--plot"], "ls.png"),
                       (["basins", *ARM, "--omega", "4", "--grid", "40", "--plot"], "b.png"),
                       (["compare", *ARM, "--omegas", "4", "--n-x", "5", "--out"], "cmp.json")):
        target = tmp_path / args[0] / "new" / "deep" / name
        result = runner.invoke(app, [str(a) for a in [*args, target]])
        assert result.exit_code == 0, (args[0], result.output)
        assert target.is_file() and target.stat().st_size > 0, args[0]
        assert sorted(p.name for p in target.parent.iterdir()) == [name]  # no probe file left behind


def test_missing_folders_are_created(tmp_path):
    out = tmp_path / "new" / "deeper" / "throw.gif"
    result = runner.invoke(app, ["animate", *ARM, *START, "--model", "paper", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    assert sorted(p.name for p in out.parent.iterdir()) == ["throw.gif"]  # no probe file left behind


def test_check_leaves_nothing_behind(tmp_path):
    cli_options.check_output(tmp_path / "sub" / "x.json", "out", create=True)
    cli_options.check_output(tmp_path / "x.json", "out")
    cli_options.check_out_dir(tmp_path / "d")
    assert list(tmp_path.iterdir()) == []  # nothing created by a check
