"""The command line's modules import one way: ``app`` → command modules (and ``usage``) → ``options``.

Read from the source with :mod:`ast` (function-local imports included), and checked
by importing each module first in a fresh interpreter.
"""

from __future__ import annotations

import ast
import json
import subprocess
import sys
from pathlib import Path

import pytest

import throwmap.cli

CLI_DIR = Path(throwmap.cli.__file__).parent
MODULES = sorted(p.stem for p in CLI_DIR.glob("*.py"))
COMMAND_MODULES = ("analysis", "animate", "assemble", "chain", "continuation", "control", "design", "experiment", "feeder", "plan", "reproduce", "statics", "studies", "sweep", "throws", "view")
SUPPORT_MODULES = ("usage",)  # the app's command group (usage errors as one line); imports options only
SUBCOMMAND_MODULES = {"cavity": "design", "passage": "design"}  # module → the command group that registers it (by name, at run time)
GROUP_MODULES = ("assemble", "chain", "control", "design", "feeder", "plan", "statics")  # commands that are groups of subcommands (they use usage's ThrowmapGroup)


def cli_imports(stem: str) -> set[str]:
    """The ``throwmap.cli`` modules (by stem) that ``cli/<stem>.py`` imports anywhere in its body."""
    tree = ast.parse((CLI_DIR / f"{stem}.py").read_text(encoding="utf-8"))
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level == 1:  # from . import x / from .x import y
                out |= {a.name for a in node.names} if node.module is None else {node.module.split(".")[0]}
            elif node.level == 0 and (node.module or "").startswith("throwmap.cli"):
                rest = node.module.split(".")[2:]
                out |= {rest[0]} if rest else {a.name for a in node.names}
            elif node.level == 2 and (node.module or "").startswith("cli"):  # from ..cli(.x) import
                rest = node.module.split(".")[1:]
                out |= {rest[0]} if rest else {a.name for a in node.names}
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("throwmap.cli."):
                    out.add(a.name.split(".")[2])
    return {m for m in out if m in MODULES} - {stem}


GRAPH = {stem: cli_imports(stem) for stem in MODULES}


def test_the_modules_are_there():
    subs = {m for m in SUBCOMMAND_MODULES if m in MODULES}
    assert set(MODULES) == {"__init__", "app", "options", *COMMAND_MODULES, *SUPPORT_MODULES, *subs}


def test_options_imports_no_cli_module():
    assert GRAPH["options"] == set()


@pytest.mark.parametrize("stem", COMMAND_MODULES + SUPPORT_MODULES + tuple(m for m in SUBCOMMAND_MODULES if m in MODULES))
def test_command_modules_import_only_options(stem):
    allowed = {"options"} | ({"usage"} if stem in GROUP_MODULES else set())
    assert GRAPH[stem] <= allowed


def test_app_registers_every_command_module():
    assert GRAPH["app"] == set(COMMAND_MODULES) | set(SUPPORT_MODULES)


def test_only_the_package_imports_app():
    assert {stem for stem, targets in GRAPH.items() if "app" in targets} == {"__init__"}


def test_no_cycle():
    """Depth-first search for a back edge in the module graph."""
    state: dict[str, int] = {}  # 1: on the path, 2: done

    def visit(stem, path):
        state[stem] = 1
        for t in sorted(GRAPH[stem]):
            assert state.get(t) != 1, f"import cycle: {' → '.join(path + [stem, t])}"
            if t not in state:
                visit(t, path + [stem])
        state[stem] = 2

    for stem in MODULES:
        if stem not in state:
            visit(stem, [])


_FIRST_IMPORTS = """
import importlib, json, sys, traceback
stems = sys.argv[1:]
for stem in stems:
    for name in [k for k in sys.modules if k == "throwmap.cli" or k.startswith("throwmap.cli.")]:
        del sys.modules[name]  # the command line's modules afresh; the library below them stays imported
    try:
        importlib.import_module("throwmap.cli." + stem)
        for m in reversed(stems):
            if m != stem:
                importlib.import_module("throwmap.cli." + m)
        from throwmap.cli import app
        import typer.main
        print(json.dumps([stem, sorted(typer.main.get_command(app).commands)]))
    except Exception:
        print(json.dumps([stem, traceback.format_exc()]))
"""


def test_each_module_imports_first_in_a_fresh_interpreter():
    """Importing any module of the command line first (then the rest, in reverse order) works, and builds the whole
    app. One interpreter: before each module the command line's modules are dropped from ``sys.modules`` (nothing
    outside the command line imports it: ``test_only_the_cli_imports_the_cli``)."""
    stems = [m for m in MODULES if m != "__init__"]
    done = subprocess.run([sys.executable, "-c", _FIRST_IMPORTS, *stems], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    seen = dict(json.loads(line) for line in done.stdout.splitlines())
    assert sorted(seen) == sorted(stems)
    want = sorted(["throw", "iterate", "demo", "compile", "compare", "validate", "validate-fixtures", "validate-recoil",
                   "animate", "limitset", "basins", "funnels", "design", "experiment", "feeder", "control", "plan", "statics",
                   "assemble", "sensitivity", "reproduce", "view", "sweep", "chain", "continuation", "map"])
    for stem, got in seen.items():
        assert got == want, f"throwmap.cli.{stem} imported first: {got}"
