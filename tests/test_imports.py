"""The shape of the package: import graph, module sizes and what ``import throwmap`` loads.

The graph is read from the source with :mod:`ast` (nothing is imported): every
``import``/``from … import`` inside ``src/throwmap``, function-local ones included
(only ``if TYPE_CHECKING:`` blocks are skipped), resolved to the modules it executes:
the named module or submodule, and the packages on the way to it (bar the importer's
own enclosing packages, which are already being imported).

Allow-lists record exceptions; all are empty and may only stay so:

- :data:`KNOWN_CYCLES`: import cycles (none; :data:`ENFORCED` is the whole package).
- :data:`KNOWN_LONG`: modules over :data:`MAX_LINES` lines (none).
- :data:`KNOWN_HEAVY`: optional heavy packages that ``import throwmap`` loads (none).
"""

from __future__ import annotations

import ast
import subprocess
import sys
import warnings
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = "throwmap"
MAX_LINES = 700
"""Past this many lines a module is doing two jobs (modules are split by concept, never by a line count)."""

ENFORCED: tuple[str, ...] = (PACKAGE,)
"""Packages in which an import cycle fails the tests: the whole package."""

KNOWN_CYCLES: tuple[frozenset[str], ...] = ()
"""Import cycles tolerated for now: none."""

KNOWN_LONG: frozenset[str] = frozenset()
"""Modules (paths under ``src``) allowed over :data:`MAX_LINES` lines: none."""

HEAVY = ("matplotlib", "mujoco", "pymunk")
"""Optional or slow packages that ``import throwmap`` must not load."""
KNOWN_HEAVY: frozenset[str] = frozenset()
"""Those of :data:`HEAVY` that ``import throwmap`` still loads (none today)."""


# ---------------------------------------------------------------- the graph
def module_files(src: Path = SRC, package: str = PACKAGE) -> dict[str, Path]:
    """Dotted module name → file, for every module of the package (``__init__`` as the package)."""
    out = {}
    for path in sorted((src / package).rglob("*.py")):
        parts = list(path.relative_to(src).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def _is_package(name: str, modules: dict[str, Path]) -> bool:
    return modules[name].name == "__init__.py"


def _type_checking_nodes(tree: ast.AST) -> set[int]:
    """ids of the statements inside ``if TYPE_CHECKING:`` blocks (not imported at run time)."""
    skip = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If):
            test = node.test
            name = test.id if isinstance(test, ast.Name) else test.attr if isinstance(test, ast.Attribute) else None
            if name == "TYPE_CHECKING":
                for stmt in node.body:
                    skip.update(id(n) for n in ast.walk(stmt))
    return skip


def _executed(target: str, importer: str, modules: dict[str, Path]) -> set[str]:
    """The package modules that importing ``target`` runs: it and its packages, bar the importer's own."""
    parts = target.split(".")
    own = {".".join(importer.split(".")[:i]) for i in range(1, importer.count(".") + 1)}
    if _is_package(importer, modules):
        own.add(importer)
    done = set()
    for i in range(1, len(parts) + 1):
        name = ".".join(parts[:i])
        if name in modules and (name == target or name not in own):
            done.add(name)
    return done


def imports_of(name: str, modules: dict[str, Path]) -> set[str]:
    """The package modules that module ``name`` imports anywhere in its body (function-local included)."""
    with warnings.catch_warnings():  # a module's own bad escapes are Python's to report, not this test's
        warnings.simplefilter("ignore", (SyntaxWarning, DeprecationWarning))
        tree = ast.parse(modules[name].read_text(encoding="utf-8"), filename=str(modules[name]))
    skip = _type_checking_nodes(tree)
    package = name if _is_package(name, modules) else name.rpartition(".")[0]
    out: set[str] = set()
    for node in ast.walk(tree):
        if id(node) in skip:
            continue
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name == PACKAGE or alias.name.startswith(PACKAGE + "."):
                    out |= _executed(alias.name, name, modules)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base_parts = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                base = ".".join(base_parts + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            if not (base == PACKAGE or base.startswith(PACKAGE + ".")):
                continue
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                if sub in modules:  # a submodule
                    out |= _executed(sub, name, modules)
                else:  # a name defined by ``base`` (its __init__ when a package): it must have run
                    out |= _executed(base, name, modules) | ({base} if base in modules else set())
    out.discard(name)
    return out


def import_graph(modules: dict[str, Path] | None = None) -> dict[str, set[str]]:
    """module → the package modules it imports."""
    modules = module_files() if modules is None else modules
    return {name: imports_of(name, modules) for name in modules}


def cycles(graph: dict[str, set[str]]) -> list[frozenset[str]]:
    """The strongly connected components with more than one module (Tarjan, iterative), sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            v, children = work[-1]
            for w in children:
                if w not in graph:
                    continue
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    comp = set()
                    while True:
                        w = stack.pop()
                        on_stack.discard(w)
                        comp.add(w)
                        if w == v:
                            break
                    if len(comp) > 1:
                        out.append(frozenset(comp))
    return sorted(out, key=lambda c: sorted(c))


def _in(package: str, module: str) -> bool:
    return module == package or module.startswith(package + ".")


# ---------------------------------------------------------------- the checker checks
def _graph(edges: dict[str, set[str]]) -> dict[str, set[str]]:
    return {k: set(v) for k, v in edges.items()}


def test_cycle_finder_finds_cycles_and_only_cycles():
    g = _graph({"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": {"e"}, "e": set(), "f": {"f", "e"}})
    assert cycles(g) == [frozenset("abc")]
    assert cycles(_graph({"a": {"b"}, "b": {"c"}, "c": set()})) == []
    assert cycles(_graph({"a": {"b"}, "b": {"a"}, "c": {"d"}, "d": {"c"}})) == [frozenset("ab"), frozenset("cd")]


def test_import_resolution(tmp_path):
    """Relative, absolute, function-local and TYPE_CHECKING imports on a small package."""
    root = tmp_path / PACKAGE
    files = {
        "__init__.py": "from .a import f\n__version__ = '0'\n",
        "a.py": "def f():\n    from .sub import g\n    return g\n",
        "b.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .a import f\nimport throwmap.sub.c\n",
        "sub/__init__.py": "from .c import g\n",
        "sub/c.py": "from .. import __version__\nfrom . import d\ng = 1\n",
        "sub/d.py": "from ..a import f\n",
    }
    for rel, text in files.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text)
    modules = module_files(tmp_path, PACKAGE)
    g = import_graph(modules)
    assert g["throwmap"] == {"throwmap.a"}
    assert g["throwmap.a"] == {"throwmap.sub"}  # runs the package, then reads g from it
    assert g["throwmap.b"] == {"throwmap.sub", "throwmap.sub.c"}  # the TYPE_CHECKING import is not run
    assert g["throwmap.sub"] == {"throwmap.sub.c"}
    assert g["throwmap.sub.c"] == {"throwmap", "throwmap.sub.d"}  # its own package is already being imported
    assert g["throwmap.sub.d"] == {"throwmap.a"}
    assert cycles(g) == [frozenset({"throwmap", "throwmap.a", "throwmap.sub", "throwmap.sub.c", "throwmap.sub.d"})]


# ---------------------------------------------------------------- the package
def test_no_import_cycles():
    """No cycle through :data:`ENFORCED` packages; others are recorded (:data:`KNOWN_CYCLES`) or warned of."""
    found = cycles(import_graph())
    for comp in found:
        print("import cycle:", " ".join(sorted(comp)))
    assert not any(_in(p, m) for c in KNOWN_CYCLES for m in c for p in ENFORCED), "enforced cycles are never allowed"
    enforced = [sorted(c) for c in found if any(_in(p, m) for m in c for p in ENFORCED)]
    assert not enforced, f"import cycles through {', '.join(ENFORCED)}: {enforced}"
    new = [sorted(c) for c in found if not any(c & known for known in KNOWN_CYCLES)]
    if new:
        warnings.warn(f"new import cycles (not in KNOWN_CYCLES): {new}", stacklevel=1)


def test_only_the_cli_imports_the_cli():
    """The library never imports the command line (``python -m throwmap`` is its entry point)."""
    graph = import_graph()
    cli = f"{PACKAGE}.cli"
    offenders = {m: sorted(t for t in targets if _in(cli, t)) for m, targets in graph.items()
                 if not _in(cli, m) and m != f"{PACKAGE}.__main__"}
    assert not {m: t for m, t in offenders.items() if t}


def test_no_module_over_max_lines():
    long = {}
    for path in module_files().values():
        rel = path.relative_to(SRC).as_posix()
        n = len(path.read_text(encoding="utf-8").splitlines())
        if n > MAX_LINES:
            long[rel] = n
    print("modules over", MAX_LINES, "lines:", long)
    assert not {rel: n for rel, n in long.items() if rel not in KNOWN_LONG}
    assert not any(rel.startswith(f"{PACKAGE}/cli/") for rel in KNOWN_LONG)


def test_import_throwmap_loads_no_heavy_package():
    code = f"import sys, {PACKAGE}; print(' '.join(m for m in {HEAVY!r} if m in sys.modules))"
    loaded = set(subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
                 .stdout.split())
    assert loaded <= KNOWN_HEAVY, f"import throwmap loads {sorted(loaded - KNOWN_HEAVY)}"
