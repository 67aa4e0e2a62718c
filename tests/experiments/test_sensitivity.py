"""``throwmap.experiments.sensitivity`` and ``throwmap sensitivity``: one run per value, common random numbers, the
same seed and n, errors naming the field."""

import json

import numpy as np
import pytest
from pydantic import BaseModel, ConfigDict, Field
from typer.testing import CliRunner

from throwmap.cli import app
from throwmap.errors import InvalidStateError
from throwmap.experiments import Trial, register_experiment, unregister_experiment
from throwmap.experiments.base import seed_of
from throwmap.experiments.runner import run_experiment
from throwmap.experiments.sensitivity import sensitivity, set_fields


class CoinConfig(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    p: float = Field(0.5, ge=0, le=1)
    inner: dict = Field(default_factory=lambda: {"q": 0.0})


class Coin:
    """Success when the trial's first uniform is below p: with common random numbers, every trial that succeeds at
    p also succeeds at any p' > p."""

    name = "coin-sensitivity-test"
    summary = "a biased coin"
    config_type = CoinConfig

    def trial(self, cfg, index, rng):
        u = float(rng.random())
        ok = u < cfg.p
        return Trial(index, seed_of(rng), ok, None if ok else "tails", {"u": u})

    def parameters(self, cfg):
        return {"p": cfg.p}


@pytest.fixture(scope="module")
def coin():
    exp = register_experiment(Coin(), replace=True)
    yield exp
    unregister_experiment(exp.name)


def test_one_row_per_value_and_common_random_numbers(coin):
    ps = [0.1, 0.3, 0.5, 0.9]
    res = sensitivity(coin, None, fields="p", values=ps, n=60, seed=4, workers=1)
    assert [r.value for r in res.rows] == ps and all(r.n == 60 for r in res.rows)
    succ = [r.successes for r in res.rows]
    assert succ == sorted(succ)  # the same uniforms at every p: successes nested
    # each row is exactly the run the runner makes for that value
    for p, r in zip(ps, res.rows):
        direct = run_experiment(coin, {"p": p}, n=60, seed=4, workers=1)
        assert direct.successes == r.successes and direct.ci95 == r.ci95
        assert r.failures == ({"tails": 60 - r.successes} if r.successes < 60 else {})
    assert res.rows[-1].ci95[0] <= res.rows[-1].success_rate <= res.rows[-1].ci95[1]
    d = res.to_dict()
    assert d["fields"] == ["p"] and d["seed"] == 4 and d["parameters"] == {"p": 0.5}
    json.dumps(d)


def test_several_fields_take_the_same_value(coin):
    data = {"p": 0.5, "inner": {"q": 0.0}}
    out = set_fields(data, ("p", "inner.q"), 0.25)
    assert out == {"p": 0.25, "inner": {"q": 0.25}} and data == {"p": 0.5, "inner": {"q": 0.0}}


def test_bad_field_and_bad_value_name_the_field(coin):
    with pytest.raises(InvalidStateError, match=r"^param: 'inner\.r': inner has no field 'r' \(fields: q\)"):
        sensitivity(coin, None, fields="inner.r", values=[1], n=1, seed=0, workers=1)
    with pytest.raises(InvalidStateError, match=r"^p: value 2: Input should be less than or equal to 1"):
        sensitivity(coin, None, fields="p", values=[0.5, 2], n=1, seed=0, workers=1)
    with pytest.raises(InvalidStateError, match=r"^values: must be finite"):
        sensitivity(coin, None, fields="p", values=[float("nan")], n=1, seed=0, workers=1)


def test_kept_runs_resume(coin, tmp_path):
    a = sensitivity(coin, None, fields="p", values=[0.2, 0.7], n=10, seed=1, workers=1, out=tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p=0.2", "p=0.7"]
    b = sensitivity(coin, None, fields="p", values=[0.2, 0.7], n=10, seed=1, workers=1, out=tmp_path)
    assert [r.successes for r in a.rows] == [r.successes for r in b.rows]


def test_cli_table_json_plot_and_errors(coin, tmp_path):
    runner = CliRunner()
    png = tmp_path / "s.png"
    r = runner.invoke(app, ["sensitivity", coin.name, "--param", "p", "--values", "0.2,0.8", "--n", "20",
                            "--workers", "1", "--json", "--plot", str(png), "--goal", "0.9"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert [row["value"] for row in d["rows"]] == [0.2, 0.8] and png.stat().st_size > 1000
    rates = np.array([row["success_rate"] for row in d["rows"]])
    assert rates[0] <= rates[1]
    r = runner.invoke(app, ["sensitivity", coin.name, "--values", "0.2", "--n", "2"])
    assert r.exit_code == 2 and "error: param: give at least one --param" in r.output
    r = runner.invoke(app, ["sensitivity", coin.name, "--param", "p", "--values", "0.2", "--goal", "3"])
    assert r.exit_code == 2 and "error: goal: must be a rate in [0, 1]" in r.output
