"""`throwmap validate` and :mod:`throwmap.studies.validation` at small sizes (the full table is in docs/explanation/validation.md)."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.studies.validation import default_parts, make_cases, validate
from throwmap.studies.study import StudyRun
from throwmap.studies.validation_report import compare_row

runner = CliRunner()


def test_cases_cover_every_stable_side_and_are_admissible():
    parts = default_parts()
    cases = make_cases(parts, 50, seed=1)
    for c in cases:
        part = parts[c.part_name]
        assert set(np.unique(c.side)) == set(np.flatnonzero(part.stable))
        assert np.all(c.x + part.uL[c.side] > 0)
        assert np.all((c.omega >= 3.0) & (c.omega <= 7.0))
    again = make_cases(parts, 50, seed=1)
    assert all(np.array_equal(a.x, b.x) for a, b in zip(cases, again))


@pytest.mark.parametrize("n", [0, 3, 7, 12, 400])
def test_n_random_cases_are_exactly_n(n):
    cases = make_cases(default_parts(), n, seed=2, grid=False)
    assert sum(len(c.x) for c in cases) == n
    assert all(np.all(c.kind == "random") for c in cases)


def test_compare_counts_matching_escapes_as_agreement():
    ref = {"x": np.array([0.1, 0.2, 0.3]), "side": np.array([0, 1, 0]), "status": np.array([0, 0, 1])}
    res = {"x": np.array([0.1002, 0.2, 0.5]), "side": np.array([0, 2, 0]), "status": np.array([0, 0, 1])}
    row = compare_row("m", ref, res, "")
    assert row.same_status_pct == 100.0
    assert row.same_side_pct == pytest.approx(200 / 3)
    assert row.within_0p5mm_pct == pytest.approx(200 / 3)
    assert row.dx_max_mm == pytest.approx(0.2)
    assert type(row).from_dict(json.loads(json.dumps(row.to_dict()))) == row
    assert row.table().splitlines()[-1] == row.line() and row.line().startswith("| m | 3 | 100.0 | 66.7 |")


@pytest.mark.slow
def test_validate_small_run_paper_exact_where_assumptions_hold():
    rep = validate({"triangle": default_parts()["triangle"]}, n=40, grid=False, models=("paper",),
                   run=StudyRun(workers=1))
    rows = {r.model: r for r in rep.rows}
    assert rows["pymunk (self)"].same_side_pct == 100.0
    held = rows.get("paper, assumptions hold")
    assert held is not None and held.within_0p5mm_pct >= 90.0
    assert "lift-off" in rows["paper"].assumptions
    doc = rep.to_dict()
    assert json.loads(json.dumps(doc))["reference"] == "pymunk"
    back = type(rep).from_dict(json.loads(json.dumps(doc)))
    assert back.table() == rep.table() and back.goals == json.loads(json.dumps(rep.goals))


def test_validate_cli_writes_table_and_json(tmp_path):
    r = runner.invoke(app, ["validate", "--part", "square", "--n", "6", "--no-grid", "--models", "paper",
                            "--workers", "1", "--realisations", "2", "--out", str(tmp_path)])
    assert r.exit_code == 0, r.output
    assert "| paper |" in r.stdout
    assert "recoil 3°" in r.stdout
    doc = json.loads((tmp_path / "validation.json").read_text())
    assert doc["settings"]["n_throws"] == 6
    assert (tmp_path / "validation.md").read_text().startswith("# throwmap validation")


@pytest.mark.parametrize("args, field", [
    (["--engines", "bullet"], "engines"),
    (["--models", "engine"], "models"),
    (["--models", "nope"], "model"),
    (["--n", "-1"], "n"),
    (["--n", "0", "--no-grid"], "n"),
    (["--mu", "-1"], "mu"),
    (["--realisations", "-1"], "realisations"),
])
def test_validate_cli_bad_input(tmp_path, args, field):
    r = runner.invoke(app, ["validate", "--out", str(tmp_path), "--realisations", "0"] + args)
    assert r.exit_code == 2
    err = r.stderr.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"error: {field}")


def test_validate_adds_mu_rows_and_keeps_the_old_ones():
    """One extra row per μ (rigid_body vs pymunk at that μ); the rows at the set's own μ are unchanged,
    and the μ row at that same μ reproduces the rigid_body row (the same throws, thrown again)."""
    parts = {"square": default_parts()["square"]}
    kw = dict(n=8, grid=False, models=("rigid_body",), run=StudyRun(workers=1))
    plain = validate(parts, mu_rows=(), **kw)
    rep = validate(parts, mu_rows=(0.3, 1.5, float("inf")), **kw)
    names = [r.model for r in rep.rows]
    assert names[:len(plain.rows)] == [r.model for r in plain.rows]
    assert rep.rows[:len(plain.rows)] == plain.rows
    assert names[len(plain.rows):] == ["rigid_body, μ = 0.3", "rigid_body, μ = 1.5", "rigid_body, μ = ∞"]
    same = {k: v for k, v in next(r for r in rep.rows if r.model == "rigid_body").to_dict().items()
            if k not in ("model", "assumptions")}
    again = {k: v for k, v in rep.rows[names.index("rigid_body, μ = 1.5")].to_dict().items()
             if k not in ("model", "assumptions")}
    assert again == same
    assert "| rigid_body, μ = ∞ |" in rep.table() and rep.settings["mu_rows"] == [0.3, 1.5, float("inf")]
    assert all(r.n == 8 for r in rep.rows)
    # the agreement statistic of the same comparisons: one row each, none refused by the engine here
    assert [a.label for a in rep.agreement] == names
