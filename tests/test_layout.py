"""The layout section of the development page (docs/reference/development.md) matches the tree: every package and
every public module is named there, and nothing named there as a package is missing from the tree."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "throwmap"


def layout_block() -> str:
    text = (ROOT / "docs" / "reference" / "development.md").read_text(encoding="utf-8")
    start = text.index("```\nsrc/throwmap/")
    return text[start:text.index("```", start + 4)]


def public_modules() -> list[Path]:
    return sorted(p for p in SRC.rglob("*.py") if not p.name.startswith("_") and "__pycache__" not in p.parts)


def test_every_public_module_is_named_in_the_layout():
    block = layout_block()
    missing = [str(p.relative_to(SRC)) for p in public_modules()
               if not re.search(rf"(?<![\w.]){re.escape(p.stem)}\b", block)]
    assert not missing, f"modules the layout (docs/reference/development.md) does not name: {missing}"


def test_every_package_of_the_layout_exists():
    block = layout_block()
    named = set(re.findall(r"^\s{2}(\w+)/", block, flags=re.M))
    packages = {p.parent.name for p in SRC.glob("*/__init__.py")}
    assert named == packages, (sorted(named - packages), sorted(packages - named))
