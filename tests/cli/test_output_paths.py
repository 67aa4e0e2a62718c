"""Every command that writes files checks its output paths before any computation.

A path that cannot be written (its folder is missing or is a file, the target is a folder,
the folder is not writable) is refused with one line ``error: <field>: …`` and exit 2, and
the computation is never started (the library call is replaced by one that fails the test).
No output creates a missing folder: an ``--out`` directory is made itself, never a folder
above it.
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
from throwmap.errors import ConfigError

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
    import throwmap.design as design
    import throwmap.design.cavity as cavity
    import throwmap.design.examples as examples
    import throwmap.experiments.runner as runner_mod
    import throwmap.experiments.sensitivity as sensitivity
    import throwmap.reproduce as reproduce
    import throwmap.statics.tables as statics_tables
    import throwmap.stochastic as stochastic
    import throwmap.stochastic.assembly as assembly
    import throwmap.studies.recoil_validation as recoil
    import throwmap.studies.tilt_wall as tilt_wall
    import throwmap.sweeps as sweeps
    from throwmap.cli import assemble as cli_assemble
    from throwmap.cli import control as cli_control
    from throwmap.cli import view as cli_view

    for module, name in ((runner_mod, "run_experiment"), (sweeps, "run_sweep"), (reproduce, "reproduce"),
                         (sensitivity, "sensitivity"), (statics_tables, "lean_table"),
                         (statics_tables, "partial_table"), (tilt_wall, "validate_tilt_wall"),
                         (recoil, "validate_recoil"), (design, "design"), (examples, "draft_example"),
                         (examples, "run_feeder_design"), (cavity, "evaluate_cavity"),
                         (stochastic, "build_mixture"), (assembly, "record_episodes"), (cli_assemble, "_episode"),
                         (cli_control, "_config"), (cli_view, "_orbit_source")):
        monkeypatch.setattr(module, name, _never)


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
    for args, field in commands(lambda name: locked / name, lambda: locked / "new"):
        result = runner.invoke(app, [str(a) for a in args])
        assert_refused(result, field, "not writable", "Permission denied")


SWEEP = 'kind = "grid"\ntarget = "throw"\n[parameters]\nx = [0.1, 0.2]\n'


def missing_folder_cases(tmp_path):
    """(command line, field, kind) for every output option of every command, the path given by ``target(kind)``:
    ``"file"`` a file, ``"dir"`` an ``--out`` directory (each in a missing folder)."""
    sweep = tmp_path / "s.toml"
    sweep.write_text(SWEEP)
    run = tmp_path / "run"  # an experiment's --out folder (read by `chain position`)
    run.mkdir()
    sens = ["sensitivity", "settle", "--param", "alpha", "--values", "0,0.05"]
    return [
        (lambda t: ["iterate", *ARM, *START, "-n", "2", "--plot", t("orbit.png")], "plot"),
        (lambda t: ["limitset", *ARM, "--omega", "4", "--plot", t("ls.png")], "plot"),
        (lambda t: ["limitset", *ARM, "--omega", "4", "--plot-map", t("map.png")], "plot_map"),
        (lambda t: ["limitset", *ARM, "--omega", "4", "--out", t()], "out"),
        (lambda t: ["basins", *ARM, "--omega", "4", "--plot", t("b.png")], "plot"),
        (lambda t: ["basins", *ARM, "--omega", "4", "--out", t()], "out"),
        (lambda t: ["funnels", *ARM, "--omega", "4", "--plot", t("f.png")], "plot"),
        (lambda t: ["funnels", *ARM, "--omega", "4", "--out", t()], "out"),
        (lambda t: ["compare", *ARM, "--out", t("cmp.json")], "out"),
        (lambda t: ["animate", *ARM, *START, "--out", t("throw.gif")], "out"),
        (lambda t: ["demo", "--out", t()], "out"),
        (lambda t: ["validate", "--n", "5", "--out", t()], "out"),
        (lambda t: ["validate-fixtures", "--out", t()], "out"),
        (lambda t: ["validate-recoil", "--out", t()], "out"),
        (lambda t: ["experiment", "settle", "--n", "3", "--out", t()], "out"),
        (lambda t: ["experiment", "settle", "--n", "3", "--plot", t("settle.png")], "plot"),
        (lambda t: [*sens, "--out", t()], "out"),
        (lambda t: [*sens, "--plot", t("sens.png")], "plot"),
        (lambda t: ["reproduce", "--quick", "--out", t()], "out"),
        (lambda t: ["sweep", sweep, "--out", t()], "out"),
        (lambda t: ["statics", "lean", "--plot", t("lean.png")], "plot"),
        (lambda t: ["statics", "partial", "--plot", t("partial.png")], "plot"),
        (lambda t: ["design", "points", "--h", "-0.01", "--target", "0=0.3", "--plot", t("design.png")], "plot"),
        (lambda t: ["design", "example", "draft", "--plot", t("design.png")], "plot"),
        (lambda t: ["design", "example", "feeder", "--plot", "none", "--write-data", t("feeder.toml")], "write_data"),
        (lambda t: ["design", "cavity", "--plot", t("capture.png")], "plot"),
        (lambda t: ["control", "episode", "--plot", t("episode.png")], "plot"),
        (lambda t: ["control", "fan", "--plot", t("fan.png")], "plot"),
        (lambda t: ["control", "tradeoff", "--plot", t("tradeoff.png")], "plot"),
        (lambda t: ["assemble", "episode", "--plot", t("fig16.png")], "plot"),
        (lambda t: ["assemble", "episode", "--snapshots", t("fig15.png")], "snapshots"),
        (lambda t: ["assemble", "animate", "--out", t("a.gif")], "out"),
        (lambda t: ["view", *ARM, *START, "--out", t("view.html")], "out"),
        (lambda t: ["view", *ARM, *START, "--save-trajectory", t("t.npz")], "save_trajectory"),
        (lambda t: ["chain", "throw", "--out", t("chain.json")], "out"),
        (lambda t: ["chain", "throw", "--plot", t("chain.png")], "plot"),
        (lambda t: ["chain", "throw", "--plot-stationary", t("st.png")], "plot_stationary"),
        (lambda t: ["chain", "throw", "--plot-quasi", t("q.png")], "plot_quasi"),
        (lambda t: ["chain", "position", run, "--out", t("chain.json")], "out"),
        (lambda t: ["chain", "position", run, "--plot", t("chain.png")], "plot"),
        (lambda t: ["chain", "position", run, "--plot-stationary", t("st.png")], "plot_stationary"),
        (lambda t: ["chain", "assemble", t("episodes.jsonl"), "--record", "2"], "episodes"),
        (lambda t: ["chain", "assemble", t("episodes.jsonl"), "--out", t("chain.json")], "out"),
        (lambda t: ["chain", "assemble", t("episodes.jsonl"), "--plot", t("chain.png")], "plot"),
    ]


def test_missing_folder_refused_before_work(tmp_path, no_work):
    """No output creates a missing folder: a file in one, or an ``--out`` directory in one, is refused
    before any work with one line naming the option and the folder, exit 2, and nothing is created."""
    missing = tmp_path / "missing" / "deeper"
    target = lambda name="dir": missing / name  # noqa: E731 - the cases take it as a function
    failures = []
    for make, field in missing_folder_cases(tmp_path):
        args = [str(a) for a in make(target)]
        if args[:2] == ["chain", "assemble"] and "--record" not in args:  # its episodes file: one that is there
            args[2] = str(tmp_path / "episodes.jsonl")
        result = runner.invoke(app, args)
        want = f"error: {field}: folder {str(missing)!r} does not exist"
        lines = result.stderr.splitlines()
        if result.exit_code != 2 or lines != [want] or "Traceback" in result.output:
            failures.append((" ".join(args[:3]), field, result.exit_code, result.output[-300:]))
        assert not (tmp_path / "missing").exists(), args
    assert not failures, "\n".join(map(repr, failures))


def test_missing_folder_message(tmp_path, monkeypatch):
    """The message names the option (as the library spells its fields) and the missing folder the output goes in."""
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["iterate", *ARM, *START, "-n", "2", "--plot", "a/b/orbit.png"])
    assert (result.exit_code, result.stderr) == (2, "error: plot: folder 'a/b' does not exist\n")
    result = runner.invoke(app, ["limitset", *ARM, "--omega", "4", "--out", "a/b/c"])
    assert (result.exit_code, result.stderr) == (2, "error: out: folder 'a/b' does not exist\n")
    assert list(tmp_path.iterdir()) == []


def test_out_directory_itself_is_made(tmp_path):
    """An ``--out`` directory in a folder that is there is made (and only it)."""
    out = tmp_path / "new"
    result = runner.invoke(app, ["limitset", *ARM, "--omega", "4", "--starts", "4", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in out.iterdir()) == ["limit_set.json"]  # no probe file left behind


def test_file_in_a_folder_that_is_there_is_written(tmp_path):
    out = tmp_path / "throw.gif"
    result = runner.invoke(app, ["animate", *ARM, *START, "--model", "paper", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["throw.gif"]  # no probe file left behind


def test_check_leaves_nothing_behind(tmp_path):
    with pytest.raises(ConfigError, match="folder .* does not exist"):
        cli_options.check_output(tmp_path / "sub" / "x.json", "out", create=True)
    with pytest.raises(ConfigError, match="folder .* does not exist"):
        cli_options.check_out_dir(tmp_path / "sub" / "d")
    cli_options.check_output(tmp_path / "x.json", "out")
    cli_options.check_out_dir(tmp_path / "d")
    assert list(tmp_path.iterdir()) == []  # nothing created by a check


def test_library_outputs_make_no_missing_folder(tmp_path):
    """What the commands call keeps the rule too: an output directory is made alone, never a folder above it."""
    from throwmap.errors import ThrowmapError
    from throwmap.experiments.runner import run_experiment
    from throwmap.io.files import make_directory
    from throwmap.sweeps.store import prepare_out

    missing = tmp_path / "missing"
    for call in (lambda: run_experiment("settle", n=1, seed=0, workers=1, out=missing / "run"),
                 lambda: prepare_out(missing / "sweep", {"sweep_sha256": "0" * 64}),
                 lambda: make_directory(missing / "d")):
        with pytest.raises(ThrowmapError, match=f"folder {str(missing)!r} does not exist") as err:
            call()
        assert err.value.field == "out"
    assert list(tmp_path.iterdir()) == []
    assert make_directory(tmp_path / "d").is_dir() and make_directory(tmp_path / "d") == tmp_path / "d"
    (tmp_path / "f").write_text("a file")
    with pytest.raises(ThrowmapError, match="not a directory"):
        make_directory(tmp_path / "f")


STUDY_COMMANDS = {
    "validate-fixtures": ["validate-fixtures", "--n", "1", "--conditions", "wall-0", "--no-fixed-point", "--part",
                          "square", "--workers", "1"],
    "validate": ["validate", "--part", "square", "--n", "1", "--no-grid", "--models", "paper", "--workers", "1",
                 "--realisations", "0"],
    "validate-recoil": ["validate-recoil", "--n", "1", "--engine-refine", "1", "--workers", "1"],
}
"""The validation commands at their smallest sizes."""


@pytest.mark.parametrize("cmd", sorted(STUDY_COMMANDS))
def test_validation_commands_write_nothing_without_out(tmp_path, monkeypatch, cmd):
    """Without ``--out DIR`` the validation commands print their tables and leave the current directory as it was
    (no ``./out`` made unasked); with it they write there (the commands' own tests)."""
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, STUDY_COMMANDS[cmd])
    assert result.exit_code == 0, result.output
    assert "| " in result.stdout and "wrote" not in result.stdout
    assert list(tmp_path.iterdir()) == []


def test_an_interrupt_before_any_trial_says_nothing_was_stored(tmp_path):
    """Ctrl-C before the first trial ended said "0 trial(s) stored …; the same command resumes from them"."""
    from throwmap.cli.options import interrupted_line

    assert interrupted_line(tmp_path) == f"interrupted: no trial was finished, nothing stored in {str(tmp_path)!r}"
    (tmp_path / "trials.jsonl").write_text('{"i": 0}\n')
    assert interrupted_line(tmp_path).startswith("interrupted: 1 trial(s) stored in")
