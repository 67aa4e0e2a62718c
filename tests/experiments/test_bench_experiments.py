"""The experiments benchmark runs end to end at tiny sizes (no timing assertions)."""

import importlib.util
import json
import math
from pathlib import Path

BENCH = Path(__file__).resolve().parents[2] / "benchmarks" / "experiments.py"


def test_bench_experiments_runs_small(tmp_path, capsys):
    spec = importlib.util.spec_from_file_location("experiments_bench", BENCH)
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    out = tmp_path / "b.json"
    data = bench.main(["--quick", "--experiments", "settle", "--workers", "1,2", "--json", str(out)])
    text = capsys.readouterr().out
    assert "reference: one engine throw" in text and "settle" in text and "1,000 trials" in text
    assert json.loads(out.read_text()) == json.loads(json.dumps(data))
    runs = data["experiments"][0]["runs"]
    assert [r["workers"] for r in runs] == [1, 2]
    for r in runs:
        assert math.isfinite(r["projected_1000_s"]) and r["projected_1000_s"] == 1000 / r["trials_per_s"]


def _bench():
    spec = importlib.util.spec_from_file_location("experiments_bench", BENCH)
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    return bench


def test_bench_config_needs_one_experiment():
    import pytest

    with pytest.raises(SystemExit):
        _bench().main(["--quick", "--config", str(BENCH.parents[1] / "examples" / "feed_recoil.toml")])


def test_bench_runs_a_config_file(tmp_path, capsys):
    import pytest

    cfg = tmp_path / "feed.toml"
    src = (BENCH.parents[1] / "examples" / "feed_recoil.toml").read_text()
    cfg.write_text(src.replace('part = "recoil_feeder.toml"', f'part = "{BENCH.parents[1] / "examples" / "recoil_feeder.toml"}"')
                   .replace("max_throws = 100", "max_throws = 3\nhold_throws = 1"))
    data = _bench().main(["--quick", "--experiments", "feed", "--workers", "1", "--config", str(cfg)])
    assert data["experiments"][0]["config"] == str(cfg)
    assert data["experiments"][0]["runs"][0]["workers"] == 1
    assert "feed" in capsys.readouterr().out
