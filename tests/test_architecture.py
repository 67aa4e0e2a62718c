"""The package's layers hold (``tools/architecture.py`` measures them; these are its limits).

* imports up the layers: only the result records' ``.plot()`` delegating to :mod:`throwmap.viz` (at most 4);
* nothing in ``models/``, ``engine/`` or ``kernels/`` imports the dispatcher (``throws/``);
* kernels import only kernels, conventions and errors;
* no branch on a built-in model's name outside ``models/`` and ``cli/`` (callers ask ``features``);
* at most 10 functions outside ``kernels/`` and ``cli/`` take 12 or more parameters.
"""

from __future__ import annotations

import functools
import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _tool():
    spec = importlib.util.spec_from_file_location("architecture", ROOT / "tools" / "architecture.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


ARCH = _tool()
pytestmark = pytest.mark.xdist_group("architecture")  # one worker scans the tree, once


@functools.cache
def _report() -> dict:
    """The scan of ``src/`` (seconds: made when a test first asks, not while the tests are collected)."""
    return ARCH.report(ROOT / "src")


def test_every_top_level_module_has_a_layer():
    for name in ARCH.module_files(ROOT / "src"):
        ARCH._layer_of(ARCH._top(name))


def test_imports_up_the_layers_are_only_plot_delegations():
    up = _report()["imports_up"]
    assert len(up) <= 4, up
    assert all(target.split(" -> ")[1].startswith("throwmap.viz.") for target in up), up


def test_nothing_below_the_dispatcher_imports_it():
    assert _report()["imports_into_dispatcher"] == []
    assert _report()["kernel_imports_outside"] == []


def test_no_branch_on_a_model_name():
    assert _report()["model_name_comparisons"] == []


def test_few_wide_functions():
    assert len(_report()["wide_functions"]) <= 10, _report()["wide_functions"]


def test_the_checker_sees_what_it_counts(tmp_path):
    """The scanner finds a model-name branch, an import up and a wide function in a planted package."""
    pkg = tmp_path / "throwmap"
    (pkg / "kernels").mkdir(parents=True)
    (pkg / "analysis").mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "kernels" / "__init__.py").write_text("")
    (pkg / "analysis" / "__init__.py").write_text("")
    (pkg / "kernels" / "k.py").write_text("from ..analysis import a\n")
    (pkg / "analysis" / "a.py").write_text(
        "def f(model):\n    return model == 'engine'\n\n"
        "def g(a, b, c, d, e, f, g, h, i, j, k, l):\n    return 0\n")
    r = ARCH.report(tmp_path)
    assert r["imports_up"] == ["throwmap/kernels/k.py:1 -> throwmap.analysis.a"]
    assert r["kernel_imports_outside"] == ["throwmap/kernels/k.py:1 -> throwmap.analysis.a"]
    assert r["model_name_comparisons"] == ["throwmap/analysis/a.py:2"]
    assert [w.split()[-1] for w in r["wide_functions"]] == ["g"]
