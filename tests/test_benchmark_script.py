"""The benchmark script runs end to end at tiny sizes (no timing assertions)."""

from __future__ import annotations

import importlib.util
import sys
import json
import math
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "benchmarks" / "bench_throw.py"


def _load():
    spec = importlib.util.spec_from_file_location("bench_throw", BENCH)
    mod = importlib.util.module_from_spec(spec)
    # registered before it runs: Numba's on-disk cache of the script's kernels then names an importable module
    # (a module missing from sys.modules is cached as '<dynamic>', which a later run cannot load)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


def test_bench_script_runs_small(tmp_path, capsys):
    bench = _load()
    out = tmp_path / "bench.json"
    res = bench.main(["--n", "2000", "--n-reference", "5", "--n-single", "50", "--repeat", "1", "--json", str(out)])
    text = capsys.readouterr().out
    for label in ("reference", "throw_batch, model paper", "small_angle", "throw() single", "cores"):
        assert label in text
    data = json.loads(out.read_text())
    assert data["n_batch"] == 2000 and data["n_reference"] == 5 and data["n_single"] == 50
    for key in ("reference_throws_per_s", "batch_paper_throws_per_s", "batch_small_angle_throws_per_s",
                "single_throw_us", "ratio_batch_paper_over_reference"):
        assert math.isfinite(data[key]) and data[key] > 0
        assert data[key] == pytest.approx(res[key])
    assert data["machine"]["cpu_count"] >= 1
    assert data["reference_agreement"]["compared"] <= 5


def test_bench_script_rejects_bad_sizes():
    bench = _load()
    with pytest.raises(SystemExit):
        bench.main(["--n", "0"])


def _load_named(name):
    path = BENCH.parent / name
    spec = importlib.util.spec_from_file_location(name.removesuffix(".py"), path)
    mod = importlib.util.module_from_spec(spec)
    # registered before it runs: Numba's on-disk cache of the script's kernels then names an importable module
    # (a module missing from sys.modules is cached as '<dynamic>', which a later run cannot load)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


def test_engine_bench_runs_small(tmp_path, capsys):
    res = _load_named("bench_engine.py").main(["--n", "3", "--json", str(tmp_path / "e.json")])
    text = capsys.readouterr().out
    assert "one core" in text and "all cores" in text
    assert res["n"] == 3 and res["throws_per_s_one_core"] > 0
    assert json.loads((tmp_path / "e.json").read_text())["steps_per_throw"] > 0


def test_rigid_body_bench_runs_small(capsys):
    res = _load_named("bench_rigid_body.py").main(["--n", "500", "--repeat", "1", "--mu", "1.5"])
    text = capsys.readouterr().out
    assert "1.5" in text
    assert res is not None


def test_analysis_bench_runs_quick(tmp_path, capsys):
    out = tmp_path / "a.json"
    res = _load_named("bench_analysis.py").main(["--quick", "--models", "paper", "--json", str(out)])
    text = capsys.readouterr().out
    for label in ("critical_points", "limit_set", "basins", "cores", "paper"):
        assert label in text
    data = json.loads(out.read_text())
    assert data["machine"]["cpu_count"] >= 1 and data["models"] == ["paper"]
    cp, ls, b = data["critical_points"]["paper"], data["limit_set"]["paper"], data["basins"]["paper"]
    assert math.isfinite(cp["median_ms"]) and cp["median_ms"] > 0 and cp["map_evaluations"] > 0
    assert ls["throws"] > 0 and ls["throws_per_s"] > 0
    assert b["n_configs"] == 3 * b["grid_per_side"] and b["throws"] > 0
    assert 0.0 <= b["check_agreement"] <= 1.0 and b["check_n"] <= 50
    assert b["throws_per_s"] == pytest.approx(res["basins"]["paper"]["throws_per_s"])


def test_analysis_bench_rejects_bad_sizes():
    with pytest.raises(SystemExit):
        _load_named("bench_analysis.py").main(["--grid", "1"])
