"""The validation studies on the experiment runner (throwmap.studies.study): the same seed draws the same cases
(those of the parent commit, pinned here), a study interrupted and resumed gives the result of one uninterrupted
run, and the command line keeps its options, exit codes and one-line errors."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.errors import InvalidStateError
from throwmap.experiments.base import trial_generator
from throwmap.experiments.runner import run_experiment
from throwmap.studies import recoil_validation as rv
from throwmap.studies.study import StudyRun
from throwmap.studies import tilt_wall as tw
from throwmap.studies.validation import (VALIDATE, ValidationConfig, default_parts, make_cases, realisation_cases,
                                        validate)
from throwmap.studies.validation_report import ValidationReport

runner = CliRunner()
PARTS = default_parts()
SMALL = {"triangle": PARTS["triangle"], "square": PARTS["square"]}


# ------------------------------------------------------------------ same seed, same cases
def test_the_cases_of_a_seed_are_those_the_studies_always_drew():
    """Values drawn by the parent commit's code (np.random.default_rng(seed) and SeedSequence(seed).spawn): the
    one seeding path must not move a single case of the recorded validation tables."""
    c = make_cases(PARTS, 10, 0)
    assert (c[0].part_name, float(c[0].x[-1]), int(c[0].side[-1]), float(c[0].omega[-1])) == \
        ("triangle", 0.3854226243900942, 0, 6.651022309110887)
    assert (float(c[1].x[-1]), int(c[1].side[-1]), float(c[1].omega[-1]), float(c[1].h[-1])) == \
        (0.38060841393474376, 1, 3.0109540006805924, -0.005)
    r = rv.recoil_cases(2, 0)[1]
    assert (r["part"], r["side"], r["x"], r["omega"], r["mu"], r["h"], r["zeta"]) == \
        ("pentagon", 3, 0.2865136047055711, 5.917986243935994, math.inf, -0.005, 0.5)
    t = tw.make_cases(PARTS, "wall, μ_w = 0", 2, trial_generator(0, 2))
    assert (t.part[1], float(t.x[1]), int(t.side[1]), float(t.alpha[1]), float(t.mu[1])) == \
        ("rectangle+lead", 0.25711748484354724, 0, -0.08323508322250456, 2.127503043208594)
    x, k, om = realisation_cases(PARTS["triangle"], 3, 0)
    assert (k.tolist(), float(x[2]), float(om[2])) == ([2, 1, 1], 0.37700262584951205, 5.917986243935994)


def test_same_seed_same_cases_another_seed_other_cases():
    for seed in (0, 7):
        a, b = make_cases(SMALL, 12, seed), make_cases(SMALL, 12, seed)
        assert all(np.array_equal(p.x, q.x) and np.array_equal(p.omega, q.omega) for p, q in zip(a, b))
        assert rv.recoil_cases(5, seed) == rv.recoil_cases(5, seed)
    assert not np.array_equal(make_cases(SMALL, 12, 0)[0].x, make_cases(SMALL, 12, 1)[0].x)
    # a generator is accepted as well as its seed (throwmap.rng.as_generator): the same stream
    assert np.array_equal(make_cases(SMALL, 12, np.random.default_rng(3))[1].x, make_cases(SMALL, 12, 3)[1].x)


def test_a_condition_draws_from_its_own_child_of_the_seed():
    cfg = tw.TiltWallConfig(n=3, seed=4, conditions=("wall, μ_w = μ",))
    _, by = tw._tilt_cases(cfg)
    alone = tw.make_cases(PARTS, "wall, μ_w = μ", 3, np.random.default_rng(np.random.SeedSequence(4).spawn(4)[3]))
    assert np.array_equal(by["wall, μ_w = μ"].x, alone.x)


# ------------------------------------------------------------------ configs
def test_study_configs_refuse_unknown_keys_and_spell_infinity():
    with pytest.raises(Exception, match="config.bogus"):
        run_experiment("validate", {"bogus": 1}, n=1, seed=0, workers=1)
    cfg = ValidationConfig(mu_rows=(0.3, math.inf), n=0, grid=False)
    doc = json.loads(cfg.model_dump_json())
    assert doc["mu_rows"] == [0.3, "inf"] and ValidationConfig.model_validate(doc) == cfg
    assert VALIDATE.parameters(cfg)["mu_rows"][-1] == "inf"


# ------------------------------------------------------------------ resume
def _engine_only(**kw):
    return tw.validate_tilt_wall(SMALL, n=2, seed=5, models=("engine",), fixed_point=False, baseline=False,
                                 run=StudyRun(**kw))


@pytest.mark.slow
def test_a_study_interrupted_and_resumed_equals_one_uninterrupted_run(tmp_path):
    whole = _engine_only(workers=1)
    out = tmp_path / "run"
    with pytest.raises(InvalidStateError, match="^out: validate-fixtures: 3 of 8 cases ran"):
        _engine_only(workers=1, out=out, stop_after=3)
    assert len((out / "trials.jsonl").read_text().splitlines()) == 3
    resumed = _engine_only(workers=1, out=out)
    assert json.loads((out / "result.json").read_text())["resumed"] == 3
    assert resumed.table() == whole.table() and resumed.agreement_table() == whole.agreement_table()
    assert resumed.to_dict() == whole.to_dict()
    # a torn last line (killed while writing) is cut off and its case thrown again
    lines = (out / "trials.jsonl").read_bytes().splitlines(keepends=True)
    (out / "trials.jsonl").write_bytes(b"".join(lines[:5]) + lines[5][:20])
    assert _engine_only(workers=1, out=out).to_dict() == whole.to_dict()
    # another seed into the same directory is refused, naming what differs
    with pytest.raises(InvalidStateError, match="^seed: differs from the run stored"):
        tw.validate_tilt_wall(SMALL, n=2, seed=6, models=("engine",), fixed_point=False, baseline=False,
                              run=StudyRun(out=out))


@pytest.mark.slow
def test_two_workers_give_the_cases_one_gives(tmp_path):
    assert _engine_only(workers=2).to_dict() == _engine_only(workers=1).to_dict()


@pytest.mark.slow
def test_validate_resumes_with_its_realisation_cases(tmp_path):
    kw = dict(n=3, grid=False, models=("paper",), mu_rows=(0.6,), n_realisations=1)
    whole = validate({"square": PARTS["square"]}, run=StudyRun(workers=1), **kw)
    out = tmp_path / "v"
    with pytest.raises(InvalidStateError, match="^out: validate: 2 of 4 cases ran"):
        validate({"square": PARTS["square"]}, run=StudyRun(workers=1, out=out, stop_after=2), **kw)
    again = validate({"square": PARTS["square"]}, run=StudyRun(workers=1, out=out), **kw)
    assert again.table() == whole.table() and again.realisation_table() == whole.realisation_table()
    assert again.agreement_table() == whole.agreement_table()
    labels = [r.label for r in again.agreement]
    assert labels[0] == "paper" and "pymunk (self)" in labels and "rigid_body, μ = 0.6" in labels
    assert labels[-3:] == ["finite, Δt = 5 ms vs impulse", "finite, Δt = 20 ms vs impulse",
                           "recoil 3°, PD overshoot vs impulse"]
    assert ValidationReport.from_dict(json.loads(json.dumps(again.to_dict()))).agreement == again.agreement


# ------------------------------------------------------------------ the command line
def _one_line_error(r, field: str):
    assert r.exit_code == 2, r.output
    err = r.stderr.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"error: {field}"), err


@pytest.mark.parametrize("cmd, args, field", [
    ("validate-fixtures", ["--workers", "-1"], "workers"),
    ("validate-fixtures", ["--n", "0"], "n"),
    ("validate-fixtures", ["--seed", "-1"], "seed"),
    ("validate-fixtures", ["--conditions", "nope"], "conditions"),
    ("validate-recoil", ["--workers", "-2"], "workers"),
    ("validate-recoil", ["--n", "0"], "n"),
    ("validate-recoil", ["--impact-law", "hard"], "impact_law"),
    ("validate-recoil", ["--max-time", "0"], "max_time"),
    ("validate", ["--workers", "-1", "--n", "2", "--no-grid", "--realisations", "0"], "workers"),
])
def test_cli_bad_input_is_one_line_exit_2(tmp_path, cmd, args, field):
    _one_line_error(runner.invoke(app, [cmd, "--out", str(tmp_path / "o")] + args), field)


@pytest.mark.parametrize("cmd", ["validate", "validate-fixtures", "validate-recoil"])
def test_cli_help_shows_the_runner_options(cmd):
    r = runner.invoke(app, [cmd, "--help"], env={"COLUMNS": "200"})
    assert r.exit_code == 0
    for opt in ("--workers", "--out", "--resume", "--no-resume", "--json", "--seed", "--n"):
        assert opt in r.stdout, opt


@pytest.mark.slow
def test_cli_validate_writes_the_agreement_and_resumes(tmp_path):
    out = tmp_path / "v"
    args = ["validate", "--part", "square", "--n", "3", "--no-grid", "--models", "paper", "--workers", "1",
            "--realisations", "0", "--out", str(out)]
    first = runner.invoke(app, args)
    assert first.exit_code == 0, first.output
    md = (out / "validation.md").read_text()
    assert "## Agreement" in md and "| agreement with the pymunk engine |" in md
    assert md.index("| model vs pymunk |") < md.index("## Agreement")  # the old table first, unchanged
    doc = json.loads((out / "validation.json").read_text())
    assert [r["label"] for r in doc["agreement"]["rows"]][:1] == ["paper"]
    again = runner.invoke(app, args)
    assert again.exit_code == 0 and (out / "validation.md").read_text() == md
    assert json.loads((out / "result.json").read_text())["resumed"] == 3
    # the same directory with another n: refused on the config's field, nothing overwritten
    _one_line_error(runner.invoke(app, args[:4] + ["4"] + args[5:]), "config.n")
    assert (out / "validation.md").read_text() == md
    fresh = runner.invoke(app, args[:4] + ["4"] + args[5:] + ["--no-resume"])
    assert fresh.exit_code == 0, fresh.output
    assert json.loads((out / "validation.json").read_text())["settings"]["n_throws"] == 4


def test_a_fresh_worker_imports_the_study_it_is_handed():
    """Workers look experiments up by name; a worker that was spawned (not forked) has not imported the study,
    so the runner hands it the registering module too."""
    import subprocess
    import sys

    cfg = rv.RecoilConfig(n=1).model_dump_json()
    code = ("import sys\nfrom throwmap.experiments.runner import _run_chunk\n"
            "assert 'throwmap.studies.recoil_validation' not in sys.modules\n"
            f"rows, secs = _run_chunk('validate-recoil', {cfg!r}, 0, (), 'throwmap.studies.recoil_validation')\n"
            "print(rows, 'throwmap.studies.recoil_validation' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["[]", "True"]
