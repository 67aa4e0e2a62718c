"""Imports point inward: no figure module computes physics (checked on the source with :mod:`ast`).

Every module of ``throwmap.viz`` may import only the plotting layer itself, errors,
conventions, I/O and the plain result/geometry types it draws — never a throw, an
orbit iteration, a kernel, an engine, an analysis or a study. Function-local imports
count too, and so does naming a physics entry point at all.
"""

import ast
from pathlib import Path

import pytest

VIZ = Path(__file__).resolve().parents[2] / "src" / "throwmap" / "viz"

ALLOWED = ("throwmap.viz", "throwmap.errors", "throwmap.conventions", "throwmap.io", "throwmap.serial",
           "throwmap.records", "throwmap.system.part", "throwmap.system.pose", "throwmap.system.fixtures")
"""Package modules a figure module may import (each with its submodules); ``records``: the results it draws;
``system.part``: the part's type and its descriptive name for titles (:func:`throwmap.system.part.default_name`),
no throws; ``system.pose``: where a part's vertices are at a pose; ``system.fixtures``: the outline of a wall or
cavity to draw (:func:`~throwmap.system.fixtures.surface_profile`); ``serial``: plain JSON values."""

PHYSICS_NAMES = {"throw", "throw_batch", "iterate", "engine_batch", "as_map", "sample_map", "throw_map_samples",
                 "limit_set", "critical_points", "basins", "funnels", "push", "compare_models", "kernels"}
"""Entry points that compute throws or maps: a figure module neither imports nor names them."""


def _inside(name: str, prefixes) -> bool:
    return any(name == p or name.startswith(p + ".") for p in prefixes)


def problems(source: str, module: str) -> list[str]:
    """What in ``source`` (module ``module``, e.g. ``throwmap.viz.basins``) breaks the rule."""
    tree = ast.parse(source)
    package = module.rpartition(".")[0]
    out = []
    for node in ast.walk(tree):
        targets = []
        if isinstance(node, ast.Import):
            targets = [(a.name, None) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = ".".join(package.split(".")[: len(package.split(".")) - node.level + 1])
                base = ".".join(p for p in (base, node.module) if p)
            else:
                base = node.module or ""
            targets = [(base, a.name) for a in node.names]
        for base, name in targets:
            if name in PHYSICS_NAMES:
                out.append(f"imports {name} from {base}")
            if base == "throwmap" or base.startswith("throwmap."):
                full = f"{base}.{name}" if name and base == "throwmap" else base
                if not _inside(full, ALLOWED):
                    out.append(f"imports {full}")
        if isinstance(node, ast.Name) and node.id in PHYSICS_NAMES - {"basins", "funnels", "push"}:
            out.append(f"names {node.id}")
        if isinstance(node, ast.Attribute) and node.attr in PHYSICS_NAMES - {"basins", "funnels", "push"}:
            out.append(f"names .{node.attr}")
    return out


MODULES = sorted(VIZ.glob("*.py"))


def test_the_viz_package_is_split_by_job():
    names = {p.stem for p in MODULES}
    assert {"style", "throw_map", "orbit", "limit_set", "basins", "funnels", "comparison", "animation"} <= names
    assert not names & {"plotting", "analysis"}  # the old catch-all modules are gone
    for p in MODULES:
        assert len(p.read_text(encoding="utf-8").splitlines()) <= 500, p.name


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.stem)
def test_figure_modules_compute_no_physics(path):
    assert problems(path.read_text(encoding="utf-8"), f"throwmap.viz.{path.stem}") == []


@pytest.mark.parametrize("source, culprit", [
    ("from ..throws.throw import throw_batch\n", "throw_batch"),
    ("def f():\n    from ..throws.orbit import iterate\n", "iterate"),
    ("import throwmap.kernels.paper\n", "throwmap.kernels.paper"),
    ("from .. import analysis\n", "throwmap.analysis"),
    ("from ..analysis.maps import ThrowMap\n", "throwmap.analysis.maps"),
    ("from throwmap import throw\n", "throw"),
    ("def f(cmap):\n    return cmap.sample_map(3)\n", ".sample_map"),
])
def test_the_checker_catches_physics(source, culprit):
    found = problems(source, "throwmap.viz.example")
    assert found and any(culprit in p for p in found), found


def test_the_checker_passes_plain_figures():
    src = ("from __future__ import annotations\nimport numpy as np\nfrom ..errors import InvalidStateError\n"
           "from .style import _plt\nfrom ..records.outcome import Status\n"
           "def f(basins):\n    from matplotlib.patches import Patch\n    return basins.x\n")
    assert problems(src, "throwmap.viz.example") == []
