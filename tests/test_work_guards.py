"""Work guards on the user-given sizes outside the analyses: ``iterate -n``, ``animate -n``,
``compare --n-x``, ``validate --n`` (:mod:`throwmap.budget`).

Each oversized case is refused before any big allocation, with one line naming the field
(``n``, ``n_x``) and saying how to go bigger; counts past 2^63 − 1 are refused whatever the
limits; ``force`` (``--force``) or raised limits let a moderate case run. No wall-clock
asserts: "fast" is what a refusal before allocation means (a 2^31-throw orbit would
otherwise hold terabytes).
"""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

import throwmap as tm
from throwmap.budget import Limits
from throwmap.studies.study import StudyRun
from throwmap.budget import MAX_COUNT, check_count, guard_work
from throwmap.cli.app import app
from throwmap.errors import InvalidStateError
from throwmap.studies.compare import compare_models
from throwmap.studies.validation import validate
from throwmap.throws.orbit_trajectory import orbit_trajectory

PART = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01)
HUGE = [2**31, 10**11, 10**12]
TOO_BIG = [MAX_COUNT + 1, 10**30]


def _one_line(err: InvalidStateError, field: str) -> str:
    text = str(err)
    assert err.field == field
    assert "\n" not in text
    return text


# ------------------------------------------------------------------ library
@pytest.mark.parametrize("n", HUGE)
def test_iterate_refuses_huge_n_on_memory(n):
    with pytest.raises(InvalidStateError) as info:
        tm.iterate(PART, ARM, (0.12, 0), 4.0, n=n)
    text = _one_line(info.value, "n")
    assert "memory" in text and "force" in text and "max_memory" in text


@pytest.mark.parametrize("n", TOO_BIG)
def test_iterate_refuses_counts_past_int64_even_forced(n):
    with pytest.raises(InvalidStateError) as info:
        tm.iterate(PART, ARM, (0.12, 0), 4.0, n=n, limits=Limits(force=True))
    assert "2^63" in _one_line(info.value, "n")


def test_iterate_time_guard_measures_throws():
    # a tiny time limit: refused after the few timed throws, on n, naming the time
    with pytest.raises(InvalidStateError) as info:
        tm.iterate(PART, ARM, (0.12, 0), 4.0, n=10**6, limits=Limits(max_seconds=1e-6))
    text = _one_line(info.value, "n")
    assert "measured now" in text and "max_seconds" in text


def test_iterate_force_and_raised_limits_run():
    o = tm.iterate(PART, ARM, (0.12, 0), 4.0, n=50, limits=Limits(max_memory=1.0, max_seconds=1e-9, force=True))
    assert o.n_throws == 50
    o = tm.iterate(PART, ARM, (0.12, 0), 4.0, n=50, limits=Limits(max_memory=1e6))  # 50 × 1.2 kB fits in 1 MB
    assert o.n_throws == 50
    with pytest.raises(InvalidStateError) as info:  # … and 1000 throws do not
        tm.iterate(PART, ARM, (0.12, 0), 4.0, n=1000, limits=Limits(max_memory=1e6))
    _one_line(info.value, "n")


@pytest.mark.parametrize("bad", [0, -1.0, float("inf"), True, "1"])
def test_iterate_bad_limits_named(bad):
    with pytest.raises(InvalidStateError) as info:
        tm.iterate(PART, ARM, (0.12, 0), 4.0, n=2, limits=Limits(max_memory=bad))
    assert info.value.field == "max_memory"


def test_orbit_trajectory_guarded():
    with pytest.raises(InvalidStateError) as info:
        orbit_trajectory(PART, ARM, 0.12, 0, 4.0, 2**31)
    assert "memory" in _one_line(info.value, "n")
    with pytest.raises(InvalidStateError):
        orbit_trajectory(PART, ARM, 0.12, 0, 4.0, MAX_COUNT + 1, limits=Limits(force=True))
    traj = orbit_trajectory(PART, ARM, 0.12, 0, 4.0, 2, model="paper", limits=Limits(max_memory=1.0, force=True))
    assert len(traj.meta["outcomes"]) == 2


@pytest.mark.parametrize("n_x", [10**9, 10**12])
def test_compare_refuses_huge_n_x(n_x):
    with pytest.raises(InvalidStateError) as info:
        compare_models(PART, ARM, omegas=(1.0, 2.0), n_x=n_x)
    assert "memory" in _one_line(info.value, "n_x")


def test_compare_past_int64_and_time_and_force():
    with pytest.raises(InvalidStateError) as info:
        compare_models(PART, ARM, n_x=MAX_COUNT + 1, limits=Limits(force=True))
    assert "2^63" in _one_line(info.value, "n_x")
    with pytest.raises(InvalidStateError) as info:
        compare_models(PART, ARM, omegas=(1.0,), n_x=10**5, limits=Limits(max_seconds=1e-6))
    assert "measured now" in _one_line(info.value, "n_x")
    r = compare_models(PART, ARM, omegas=(1.0,), n_x=20, limits=Limits(max_memory=1.0, max_seconds=1e-9, force=True))
    assert r.settings["n_x"] == 20


@pytest.mark.parametrize("n", [10**9, 10**12])
def test_validate_refuses_huge_n(n):
    with pytest.raises(InvalidStateError) as info:
        validate(n=n)
    assert "memory" in _one_line(info.value, "n")


def test_validate_past_int64():
    with pytest.raises(InvalidStateError) as info:
        validate(n=MAX_COUNT + 1, run=StudyRun(limits=Limits(force=True)))
    assert "2^63" in _one_line(info.value, "n")


def test_check_count_and_generic_guard():
    assert check_count("n", 5) == 5
    assert check_count("n", MAX_COUNT) == MAX_COUNT
    for bad in (-1, 1.5, True, MAX_COUNT + 1):
        with pytest.raises(InvalidStateError):
            check_count("n", bad)
    est = guard_work("w", "n", 10, 8, Limits(1e3, 1e3, False), throws_per_config=1.0, timer=lambda: 1e-3, unit="throws")
    assert est["memory_bytes"] == 80 and est["seconds"] == pytest.approx(1e-2)
    with pytest.raises(InvalidStateError):
        guard_work("w", "n", 10, 8, Limits(1e3, 1e-3, False), throws_per_config=1.0, timer=lambda: 1e-3)
    # the analysis module re-exports the same guard (one guard, not two)
    from throwmap.analysis import budget as ab
    import throwmap.budget as gb

    assert ab.Limits is gb.Limits and ab.DEFAULT_LIMITS is gb.DEFAULT_LIMITS


# ------------------------------------------------------------------ command line
RUNNER = CliRunner()
BASE_ITERATE = ["iterate", "--part", "triangle", "--h", "-0.01", "--omega", "4", "--x", "0.12", "--side", "0"]
BASE_ANIMATE = ["animate", "--part", "triangle", "--h", "-0.01", "--omega", "4", "--x", "0.12", "--side", "0"]
BASE_COMPARE = ["compare", "--part", "triangle", "--h", "-0.01", "--omegas", "1,2"]


def _refused(args, field):
    res = RUNNER.invoke(app, args)
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1, res.output
    assert lines[0].startswith(f"error: {field}: "), lines[0]
    assert "Traceback" not in res.output
    return lines[0]


@pytest.mark.parametrize("n", ["2147483648", "100000000000", "9223372036854775808", "1" + "0" * 30])
def test_cli_iterate_refused(n):
    line = _refused(BASE_ITERATE + ["-n", n], "n")
    assert "--force" in line or "2^63" in line


def test_cli_iterate_limits_and_force(tmp_path):
    line = _refused(BASE_ITERATE + ["-n", "100000", "--max-memory", "0.001"], "n")
    assert "--max-memory" in line
    _refused(BASE_ITERATE + ["-n", "1000000", "--max-time", "0.000001"], "n")
    res = RUNNER.invoke(app, BASE_ITERATE + ["-n", "30", "--max-memory", "0.000001", "--force", "--json"])
    assert res.exit_code == 0, res.output
    _refused(BASE_ITERATE + ["-n", "3", "--max-memory", "0"], "max_memory")
    _refused(BASE_ITERATE + ["-n", "3", "--max-time", "-1"], "max_time")


@pytest.mark.parametrize("n", ["2147483648", "9223372036854775808"])
def test_cli_animate_refused(n, tmp_path):
    _refused(BASE_ANIMATE + ["-n", n, "--out", str(tmp_path / "a.gif")], "n")
    assert not (tmp_path / "a.gif").exists()


@pytest.mark.parametrize("n_x", ["1000000000", "9223372036854775808"])
def test_cli_compare_refused(n_x):
    _refused(BASE_COMPARE + ["--n-x", n_x], "n_x")


def test_cli_compare_force_runs():
    _refused(BASE_COMPARE + ["--n-x", "100000", "--max-time", "0.000001"], "n_x")
    res = RUNNER.invoke(app, BASE_COMPARE + ["--n-x", "10", "--max-time", "0.000001", "--force", "--json"])
    assert res.exit_code == 0, res.output


@pytest.mark.parametrize("n", ["1000000000", "9223372036854775808", "1e9"])
def test_cli_validate_refused(n, tmp_path):
    _refused(["validate", "--n", n, "--out", str(tmp_path / "v")], "n")
    assert not (tmp_path / "v").exists()


def test_the_suite_has_a_per_test_timeout(request):
    """A hang (an uncapped search) fails its test instead of stalling CI: pytest-timeout with a stated limit."""
    assert request.config.pluginmanager.hasplugin("timeout")
    assert float(request.config.getini("timeout")) == 900.0


def test_a_time_limit_set_by_hand_is_checked_on_small_work_too():
    """A few hundred throws are not timed under the default limits; a --max-time below the default is always
    checked (it was ignored below a million throws)."""
    import throwmap as tm
    from throwmap.budget import Limits
    from throwmap.errors import InvalidStateError

    part, arm = tm.triangle_30_60_90(), tm.Arm(h=-0.01)
    tight = Limits(max_seconds=1e-7)
    with pytest.raises(InvalidStateError, match="over the limit of"):
        tm.limit_set(part, arm, 4.5, "paper", n_starts=16, limits=tight)
    with pytest.raises(InvalidStateError, match="over the limit of"):
        tm.critical_points(part, arm, 4.5, "paper", limits=tight)
    assert tm.limit_set(part, arm, 4.5, "paper", n_starts=16, limits=Limits(max_seconds=600)).attractors is not None
