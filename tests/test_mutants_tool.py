"""tools/mutants.py on a toy package: a mutant is applied, judged by its tests and always restored."""

import importlib.util
import sys
from pathlib import Path

import pytest

TOOL = Path(__file__).resolve().parent.parent / "tools" / "mutants.py"


@pytest.fixture
def mutants(tmp_path, monkeypatch):
    spec = importlib.util.spec_from_file_location("mutants_tool_under_test", TOOL)
    mod = importlib.util.module_from_spec(spec)
    monkeypatch.setitem(sys.modules, spec.name, mod)
    spec.loader.exec_module(mod)
    src = tmp_path / "src" / "throwmap"
    src.mkdir(parents=True)
    (src / "__init__.py").write_text("")
    (src / "toy.py").write_text("def clip(x):\n    return x if x >= 0 else 0\n")
    tests = tmp_path / "tests"
    tests.mkdir()
    (tests / "test_toy.py").write_text("from throwmap.toy import clip\n\ndef test_clip():\n    assert clip(-2) == 0\n")
    monkeypatch.setattr(mod, "ROOT", tmp_path)
    monkeypatch.setattr(mod, "SRC", src)
    monkeypatch.delenv("PYTHONPATH", raising=False)
    return mod, src / "toy.py"


def test_killed_survived_stale_and_equivalent_are_told_apart_and_the_file_is_restored(mutants):
    mod, toy = mutants
    before = toy.read_text()
    cases = [
        mod.Mutant("T1", "toy.py", "x >= 0 else 0", "x >= 0 else x", "negative passes through"),  # test fails
        mod.Mutant("T2", "toy.py", "x >= 0 else 0", "x > 0 else 0", "zero takes the else branch"),  # equal result
        mod.Mutant("T3", "toy.py", "no such text", "x", "stale snippet"),
        mod.Mutant("T4", "toy.py", "x >= 0", "x > 0", "boundary", equivalent="clip(0) is 0 either way"),
    ]
    rows = mod.run(cases, timeout=120, log=lambda s: None, baseline=True, tests=("tests/test_toy.py",))
    assert [r["result"] for r in rows] == ["killed", "survived", "stale", "equivalent"]
    assert rows[0]["detail"].endswith("test_toy.py::test_clip")
    assert toy.read_text() == before
    caught, decided, share = mod.score(rows)
    assert (caught, decided) == (1, 2) and share == 0.5
    assert "1/2" in mod.markdown(rows)


def test_a_snippet_must_occur_exactly_once(mutants):
    mod, toy = mutants
    toy.write_text("a = 0\nb = 0\n")
    with pytest.raises(ValueError, match="2 times"):
        mod.apply(mod.Mutant("T5", "toy.py", "= 0", "= 1", "ambiguous"))
    assert toy.read_text() == "a = 0\nb = 0\n"


def test_the_catalogue_has_unique_ids_and_reasons_only_where_equivalent(mutants):
    mod, _ = mutants
    ids = [m.id for m in mod.MUTANTS]
    assert len(ids) == len(set(ids))
    assert all(m.old != m.new and m.what for m in mod.MUTANTS)
    repo = TOOL.parent.parent
    for m in mod.MUTANTS:  # every mutant's file exists and has a test subset, every file of which exists
        assert (repo / "src" / "throwmap" / m.path).is_file(), m.id
        assert m.tests and all((repo / t).is_file() for t in m.tests), m.id


def test_specific_prefixes_come_before_the_generic_ones(mutants):
    mod, _ = mutants
    prefixes = [p for p, _ in mod.TESTS]
    for i, p in enumerate(prefixes):  # first match wins: a prefix listed after a shorter one it extends is never used
        assert not any(p.startswith(q) for q in prefixes[:i]), p


def test_the_kill_files_run_last_in_their_subsets(mutants):
    mod, _ = mutants
    for prefix, tests in mod.TESTS:
        kills = [i for i, t in enumerate(tests) if t in mod.ADDED_BY_THE_PASS]
        assert kills == list(range(len(tests) - len(kills), len(tests))), prefix
