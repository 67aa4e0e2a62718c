"""The package's shape in figures: layers, imports up them, model-name branches, wide functions.

Reads ``src/throwmap`` as text (:mod:`ast`; nothing is imported) and prints

* **imports up the layers**: each import statement (function-local ones included, ``if TYPE_CHECKING:``
  skipped) whose target module sits in a higher layer of :data:`LAYERS` than the importer;
* **imports into the dispatcher**: statements in ``models/``, ``engine/`` or ``kernels/`` that import
  ``throws/`` (the package of ``throw``, ``throw_batch`` and ``iterate``);
* **kernel imports**: statements in ``kernels/`` importing anything but kernels, conventions and errors;
* **model-name comparisons** outside ``models/`` and ``cli/``: a comparison (``==``, ``!=``, ``in``,
  ``not in``, ``str.startswith``/``endswith``) with the name of a built-in model as a string literal
  (whatever the other side: a branch on a name is a branch on a model, also where the name is a
  controller's kind or a key of a results table);
* **wide functions**: functions outside ``kernels/`` and ``cli/`` with 12 or more parameters;
* the longest modules and functions.

Usage::

    python tools/architecture.py                 # this checkout
    python tools/architecture.py --src OTHER/src # another tree (e.g. a worktree of an older commit)
    python tools/architecture.py --json          # the figures as one JSON object

The layers, low to high (a module may import its own layer and those below):
"""

from __future__ import annotations

import argparse
import ast
import json
import sys
import warnings
from pathlib import Path

PACKAGE = "throwmap"

LAYERS: tuple[tuple[str, ...], ...] = (
    ("conventions", "errors", "version"),
    ("rng", "limits", "budget", "discovery", "serial"),
    ("kernels",),
    ("system",),
    ("records",),
    ("io",),
    ("engine",),
    ("models",),
    ("session", "throws", "warmup"),
    ("viz",),
    ("analysis",),
    ("statics",),
    ("control",),
    ("design",),
    ("experiments",),
    ("feeder",),
    ("stochastic",),
    ("studies",),
    ("sweeps",),
    ("reproduce", "testing"),
    ("", "cli", "__main__"),
)
"""Top-level packages and modules of ``throwmap`` by layer, lowest first (``""`` is ``throwmap`` itself)."""

MODEL_NAMES = ("paper", "small_angle", "small_angle2", "rigid_body", "engine", "mujoco")
"""The built-in models' names, whose comparisons outside ``models/`` and ``cli/`` are branches on a model."""

WIDE = 12
"""A function with this many parameters or more is wide."""

KERNEL_MAY_IMPORT = ("kernels", "conventions", "errors")


def _layer_of(top: str) -> int:
    for i, names in enumerate(LAYERS):
        if top in names:
            return i
    raise KeyError(f"{top!r} is in no layer: add it to LAYERS")


def _top(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def module_files(src: Path) -> dict[str, Path]:
    out = {}
    for path in sorted((src / PACKAGE).rglob("*.py")):
        parts = list(path.relative_to(src).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def _parse(path: Path) -> ast.AST:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", (SyntaxWarning, DeprecationWarning))
        return ast.parse(path.read_text(encoding="utf-8"), filename=str(path))


def _type_checking(tree: ast.AST) -> set[int]:
    skip = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If):
            t = node.test
            name = t.id if isinstance(t, ast.Name) else t.attr if isinstance(t, ast.Attribute) else None
            if name == "TYPE_CHECKING":
                for stmt in node.body:
                    skip.update(id(n) for n in ast.walk(stmt))
    return skip


def import_statements(name: str, path: Path, modules: dict[str, Path]) -> list[tuple[int, str]]:
    """``(line, target)`` per imported name of the package: the deepest module the statement names."""
    tree = _parse(path)
    skip = _type_checking(tree)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out = []
    for node in ast.walk(tree):
        if id(node) in skip:
            continue
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name == PACKAGE or alias.name.startswith(PACKAGE + "."):
                    out.append((node.lineno, alias.name))
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base_parts = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                base = ".".join(base_parts + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            if not (base == PACKAGE or base.startswith(PACKAGE + ".")):
                continue
            targets = {f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base for a in node.names}
            out.extend((node.lineno, t) for t in sorted(targets))
    return out


def _names_in(node: ast.AST) -> set[str]:
    out = set()
    for n in ast.walk(node):
        if isinstance(n, ast.Constant) and isinstance(n.value, str) and n.value in MODEL_NAMES:
            out.add(n.value)
    return out


def model_comparisons(path: Path) -> list[int]:
    """Lines comparing something with a built-in model's name (a string literal)."""
    tree = _parse(path)
    lines = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Compare):
            sides = [node.left, *node.comparators]
            if any(_names_in(s) for s in sides) and not all(_names_in(s) for s in sides):
                lines.append(node.lineno)
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr in ("startswith", "endswith") and any(_names_in(a) for a in node.args)):
            lines.append(node.lineno)
    return sorted(set(lines))


def functions(path: Path):
    """``(qualified name, line, parameters, lines)`` of every function and method."""
    tree = _parse(path)
    out = []

    def visit(node, prefix):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                a = child.args
                params = [p.arg for p in (*a.posonlyargs, *a.args, *a.kwonlyargs)]
                params += [p.arg for p in (a.vararg, a.kwarg) if p is not None]
                params = [p for p in params if p not in ("self", "cls")]
                n_lines = (child.end_lineno or child.lineno) - child.lineno + 1
                out.append((prefix + child.name, child.lineno, len(params), n_lines))
                visit(child, prefix + child.name + ".")
            elif isinstance(child, ast.ClassDef):
                visit(child, prefix + child.name + ".")

    visit(tree, "")
    return out


def report(src: Path) -> dict:
    modules = module_files(src)
    rel = {m: p.relative_to(src).as_posix() for m, p in modules.items()}
    up, dispatcher, kernel_bad, comparisons, wide, long_modules, long_functions = [], [], [], [], [], [], []
    for name, path in modules.items():
        top = _top(name)
        mine = _layer_of(top)
        for line, target in import_statements(name, path, modules):
            ttop = _top(target)
            if ttop == top:
                continue
            where = f"{rel[name]}:{line} -> {target}"
            if _layer_of(ttop) > mine:
                up.append(where)
            if top in ("models", "engine", "kernels") and ttop == "throws":
                dispatcher.append(where)
            if top == "kernels" and ttop not in KERNEL_MAY_IMPORT:
                kernel_bad.append(where)
        if top not in ("models", "cli"):
            comparisons.extend(f"{rel[name]}:{line}" for line in model_comparisons(path))
        n = len(path.read_text(encoding="utf-8").splitlines())
        long_modules.append((n, rel[name]))
        for fn, line, n_params, n_lines in functions(path):
            if n_params >= WIDE and top not in ("kernels", "cli"):
                wide.append((n_params, f"{rel[name]}:{line} {fn}"))
            long_functions.append((n_lines, f"{rel[name]}:{line} {fn}"))
    return {
        "modules": len(modules),
        "lines": sum(n for n, _ in long_modules),
        "imports_up": sorted(set(up)),
        "imports_into_dispatcher": sorted(set(dispatcher)),
        "kernel_imports_outside": sorted(set(kernel_bad)),
        "model_name_comparisons": comparisons,
        "wide_functions": [f"{n:3d} {w}" for n, w in sorted(wide, reverse=True)],
        "longest_modules": [f"{n:5d} {m}" for n, m in sorted(long_modules, reverse=True)[:10]],
        "longest_functions": [f"{n:5d} {f}" for n, f in sorted(long_functions, reverse=True)[:10]],
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--src", type=Path, default=Path(__file__).resolve().parents[1] / "src")
    ap.add_argument("--json", action="store_true", help="print the report as JSON")
    args = ap.parse_args(argv)
    r = report(args.src)
    if args.json:
        print(json.dumps(r, indent=1, ensure_ascii=False))
        return 0
    print(f"{r['modules']} modules, {r['lines']} lines under {args.src}")
    for key in ("imports_up", "imports_into_dispatcher", "kernel_imports_outside", "model_name_comparisons",
                "wide_functions", "longest_modules", "longest_functions"):
        items = r[key]
        label = key.replace("_", " ")
        print(f"\n{label}: {len(items)}" + ("" if key.startswith("longest") else ""))
        for item in items:
            print("  " + item)
    return 0


if __name__ == "__main__":
    sys.exit(main())
