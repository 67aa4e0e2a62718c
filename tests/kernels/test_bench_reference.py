"""The rigid_body benchmark measures its reference rate in the same run (issue 10, item 2 "Threads").

It used to divide by a hard-coded 421 throws/s, a figure from another run.
"""

import importlib.util
import sys
import math
from pathlib import Path

BENCH = Path(__file__).resolve().parents[2] / "benchmarks"


def _load(name):
    spec = importlib.util.spec_from_file_location(name.removesuffix(".py"), BENCH / name)
    mod = importlib.util.module_from_spec(spec)
    # registered before it runs: Numba's on-disk cache of the script's kernels then names an importable module
    # (a module missing from sys.modules is cached as '<dynamic>', which a later run cannot load)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


def test_rigid_body_bench_measures_its_reference(capsys):
    bench = _load("bench_rigid_body.py")
    assert not hasattr(bench, "REFERENCE_RATE")
    res = bench.main(["--n", "40", "--mu", "inf", "0", "--repeat", "1", "--repeat-critical", "0", "--n-reference", "3"])
    text = capsys.readouterr().out
    assert res["n_reference"] == 3
    assert math.isfinite(res["reference_rate"]) and res["reference_rate"] > 0
    for row in res["rows"]:
        assert row["ratio"] == row["throws_per_s"] / res["reference_rate"]
    assert "measured in this run" in text


def test_no_benchmark_divides_by_a_typed_in_rate():
    """No benchmark keeps a reference rate constant (every ratio's denominator is timed in the same run)."""
    for path in BENCH.glob("bench_*.py"):
        src = path.read_text()
        assert "REFERENCE_RATE" not in src and "421" not in src, path.name
