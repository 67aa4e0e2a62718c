"""``throwmap chain``: bad input and oversized work refused with one line (outside tester's report)."""

import json

import pytest

from throwmap.budget import Limits
from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.errors import InvalidStateError
from throwmap.stochastic.assembly import read_episodes, record_episodes
from throwmap.stochastic.budget import guard_chain

runner = CliRunner()
ROW = {"phases": [], "poses": [], "statuses": []}


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def one_error(result, field, *words):
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {field}: "), lines[0]
    assert "Traceback" not in result.output
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


@pytest.mark.parametrize("args, field, words", [
    (["--cell", "1e-9", "--samples", "20", "--trials", "0", "--k-max", "10"], "cell", ["memory", "--cell"]),
    (["--samples", "1000000000"], "samples", ["memory", "1,000,000,000 throws"]),
    (["--k-max", "1000000000"], "k_max", ["memory"]),
    (["--trials", "100000000"], "trials", ["memory"]),
    (["--mu-nodes", "100000000"], "mu_nodes", ["memory"]),
    (["--max-time", "1e-6"], "", ["over the limit of"]),
    (["--goal", "0:0.5:0.3"], "goal", ["LO < HI"]),
    (["--goal", "5:0.1:0.2"], "goal", ["side 5"]),
    (["--goal", "0:a:b"], "goal", []),
    (["--omega", "-3"], "omega", ["> 0"]),
    (["--omega", "nan"], "omega", []),
    (["--trials", "-1"], "trials", ["≥ 0"]),
    (["--samples", "0"], "samples", ["≥ 2"]),
    (["--samples", "1"], "samples", ["≥ 2"]),
    (["--mu-nodes", "0"], "mu_nodes", ["≥ 1"]),
    (["--max-memory", "0"], "max_memory", []),
])
def test_chain_throw_refuses(args, field, words):
    r = invoke("chain", "throw", *args)
    if field:
        one_error(r, field, *words)
    else:
        assert r.exit_code == 2 and len(r.stderr.splitlines()) == 1 and r.stderr.startswith("error: ")
        for w in words:
            assert w in r.stderr


def test_samples_message_is_one_rule():
    a = one_error(invoke("chain", "throw", "--samples", "0"), "samples")
    b = one_error(invoke("chain", "throw", "--samples", "1"), "samples")
    assert a.rsplit("got", 1)[0] == b.rsplit("got", 1)[0]


def test_guard_chain_estimates_and_force():
    est = guard_chain(n_cells=100, n_labels=4, samples=32, n_mu=5, k_max=60, trials=400, limits=Limits(2e9, 1800),
                      timer=lambda: 1e-5)
    assert 0 < est["memory_bytes"] < 2e9 and 0 < est["seconds"] < 1800
    big = dict(n_cells=10**9, n_labels=4, samples=32, n_mu=5, k_max=60, trials=400, limits=Limits(2e9, 1800))
    with pytest.raises(InvalidStateError, match="^cell: "):
        guard_chain(**big)
    assert guard_chain(**dict(big, limits=Limits(2e9, 1800, True)))["memory_bytes"] > 2e9
    with pytest.raises(InvalidStateError, match="^trials: .*over the limit of 30 min"):
        guard_chain(n_cells=10, n_labels=4, samples=4, n_mu=1, k_max=1000, trials=10**6, limits=Limits(1e12, 1800),
                    timer=lambda: 1e-3)


def test_small_throw_prints_no_dangling_comma():
    r = invoke("chain", "throw", "--samples", "2", "--mu-nodes", "1", "--trials", "0", "--k-max", "3",
               "--cell", "0.05")
    assert r.exit_code == 0, r.output
    line = r.stdout.splitlines()[0]
    assert "long run:" in line and not line.rstrip().endswith(",")


def _lines(path, rows, tail=""):
    path.write_text("".join(json.dumps(r) + "\n" for r in rows) + tail, encoding="utf-8")
    return path


def test_assemble_refuses_non_json_file(tmp_path):
    p = tmp_path / "bad.txt"
    p.write_text("hello\nworld\n", encoding="utf-8")
    one_error(invoke("chain", "assemble", p), "episodes", "not an episode row")
    q = tmp_path / "bin.dat"
    q.write_bytes(b"\x00\xff\x01")
    one_error(invoke("chain", "assemble", q), "episodes")


def test_torn_last_line_is_skipped_with_a_warning(tmp_path):
    rows = [dict(ROW, index=0, seed=0), dict(ROW, index=1, seed=0)]
    p = _lines(tmp_path / "ep.jsonl", rows, tail='{"index": 2, "se')
    with pytest.warns(UserWarning, match="torn last line 3"):
        assert read_episodes(p) == rows
    assert p.read_text(encoding="utf-8").endswith('"se')  # reading leaves the file alone
    with pytest.warns(UserWarning, match="cut off"):
        assert read_episodes(p, cut=True) == rows
    assert p.read_text(encoding="utf-8").endswith("}\n")  # appending will start on a fresh line
    # the command reads it: no traceback, one error line (these rows have no low phase)
    one_error(invoke("chain", "assemble", _lines(tmp_path / "t2.jsonl", rows, tail="{")), "episodes")


def test_bad_line_in_the_middle_is_refused(tmp_path):
    p = _lines(tmp_path / "ep.jsonl", [dict(ROW, index=0, seed=0)], tail='{"index": 1\n' + json.dumps(
        dict(ROW, index=2, seed=0)) + "\n")
    with pytest.raises(InvalidStateError, match="line 2"):
        read_episodes(p)


def test_record_refuses_another_seed(tmp_path):
    p = _lines(tmp_path / "ep.jsonl", [dict(ROW, index=0, seed=3), dict(ROW, index=1, seed=3)])
    with pytest.raises(InvalidStateError, match="^seed: differs from the episodes stored"):
        record_episodes(p, 0, 2)
    one_error(invoke("chain", "assemble", p, "--record", "2", "--seed", "0"), "seed", "stored 3, given 0")
    assert len(read_episodes(p)) == 2  # nothing appended


def test_assemble_refuses_a_file_of_several_seeds(tmp_path):
    p = _lines(tmp_path / "ep.jsonl", [dict(ROW, index=0, seed=0), dict(ROW, index=1, seed=3)])
    one_error(invoke("chain", "assemble", p), "episodes", "several seeds")
