"""``throwmap statics …``: the Fig. 13/14 tables on the command line, engine checks included."""

from typer.testing import CliRunner

from throwmap.cli.app import app

runner = CliRunner()


def test_lean_table_closed_form_equals_lp_and_engine_agrees_off_the_cap():
    r = runner.invoke(app, ["statics", "lean", "--n", "12", "--seed", "3"])
    assert r.exit_code == 0, r.output
    assert "closed form (i)-(iii) = LP: 12/12" in r.stdout
    line = next(x for x in r.stdout.splitlines() if "LP = engine without them" in x)
    agree, total = line.rsplit(": ", 1)[1].split("/")
    assert agree == total  # every lean the engine's friction cap can hold is answered as the LP does


def test_partial_table_lp_and_engine_agree_both_ways():
    # at μ = 0.03 some partial assemblies rest and some do not: the engine must see both the same way
    r = runner.invoke(app, ["statics", "partial", "--mu", "0.03"])
    assert r.exit_code == 0, r.output
    rows = [x.split("|")[1:-1] for x in r.stdout.splitlines() if x.startswith("| -")]
    assert len(rows) == 7
    assert {row[2].strip() for row in rows} == {"yes", "no"}
    for row in rows:
        assert row[2].strip() == row[3].strip().split(" ")[0]


def test_bad_figure_path_is_one_line():
    r = runner.invoke(app, ["statics", "partial", "--no-engine", "--plot", "out.xyz"])
    assert r.exit_code == 2 and r.stderr.startswith("error: plot:")


def test_a_huge_lean_table_is_refused_before_work():
    r = runner.invoke(app, ["statics", "lean", "--n", "100000000"])
    assert r.exit_code == 2, r.output
    assert "n: lean table on 100,000,000 leans needs" in r.output and "Traceback" not in r.output
