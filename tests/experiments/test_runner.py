"""The Monte Carlo runner: seeds, parallel determinism, keeping and resuming trials, the work guard.

Runs the real ``settle`` experiment (a pymunk drop, ≈ 10 ms a trial) on short runs.
"""

import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pyarrow.parquet as pq
import pytest

from throwmap.errors import ConfigError, InvalidStateError
from throwmap.budget import Limits
from throwmap.experiments import Trial, experiment_names, get_experiment, trial_seed
from throwmap.experiments.runner import run_experiment
from throwmap.experiments.stats import wilson_interval

CFG = {"arm": {"length": 0.4}}


@pytest.fixture(scope="module")
def reference():
    """12 settle trials, seed 7, in this process."""
    return run_experiment("settle", CFG, n=12, seed=7, workers=1)


def test_settle_is_registered():
    assert "settle" in experiment_names()
    with pytest.raises(InvalidStateError, match=r"^experiment: unknown experiment 'nope' \(choose from .*settle"):
        get_experiment("nope")


def test_same_seed_same_trials_on_any_number_of_workers(reference):
    two = run_experiment("settle", CFG, n=12, seed=7, workers=2)
    assert two.trials == reference.trials and two.workers == 2
    other = run_experiment("settle", CFG, n=12, seed=8, workers=1)
    assert [t.values["x0"] for t in other.trials] != [t.values["x0"] for t in reference.trials]


def test_trial_seeds_are_spawned(reference):
    kids = np.random.SeedSequence(7).spawn(12)
    assert [t.index for t in reference.trials] == list(range(12))
    assert [t.seed for t in reference.trials] == [int(k.generate_state(1)[0]) for k in kids]
    # a trial's stream does not depend on n: trial 3 of a longer run is the same trial
    longer = run_experiment("settle", CFG, n=1, seed=7, workers=1)
    assert longer.trials[0] == reference.trials[0]


def test_summary_is_consistent(reference):
    r = reference
    assert r.n == 12 and r.complete and r.successes == sum(t.success for t in r.trials)
    assert r.successes + sum(r.failures.values()) == r.n
    assert r.ci95 == wilson_interval(r.successes, r.n)
    assert r.failures == {k: sum(t.failure == k for t in r.trials) for k in r.failures}
    doc = r.to_json()
    for key in ("n", "successes", "success_rate", "ci95", "failures", "seed", "parameters", "experiment", "version"):
        assert key in doc
    json.dumps(doc, allow_nan=False)
    assert doc["parameters"]["length_m"] == 0.4 and doc["seed"] == 7
    assert "Wilson 95 %" in r.table()


def test_out_keeps_every_trial(tmp_path, reference):
    r = run_experiment("settle", CFG, n=12, seed=7, workers=1, out=tmp_path)
    lines = (tmp_path / "trials.jsonl").read_text().splitlines()
    assert len(lines) == 12
    stored = sorted((Trial.from_json(json.loads(s)) for s in lines), key=lambda t: t.index)
    assert tuple(stored) == reference.trials
    assert json.loads((tmp_path / "result.json").read_text()) == json.loads(json.dumps(r.to_json()))
    table = pq.read_table(tmp_path / "trials.parquet")
    assert table.num_rows == 12
    assert {"index", "seed", "success", "failure", "x", "side", "tilt", "x0", "phi0"} <= set(table.column_names)
    assert table.column("success").to_pylist() == [t.success for t in reference.trials]
    meta = json.loads(table.schema.metadata[b"throwmap.result"])
    assert meta["n"] == 12 and meta["ci95"] == list(r.ci95)
    assert not [p for p in os.listdir(tmp_path) if p.endswith(".tmp")]


def test_interrupted_run_resumes_without_redoing(tmp_path, reference):
    first = run_experiment("settle", CFG, n=12, seed=7, workers=1, out=tmp_path, stop_after=5)
    assert first.n == 5 and not first.complete and first.planned == 12
    assert len((tmp_path / "trials.jsonl").read_text().splitlines()) == 5
    done = []
    second = run_experiment("settle", CFG, n=12, seed=7, workers=2, out=tmp_path, progress=lambda d, t: done.append(d))
    assert second.resumed == 5 and done[0] == 5 and done[-1] == 12
    lines = (tmp_path / "trials.jsonl").read_text().splitlines()
    assert len(lines) == 12  # the 5 stored trials were not run again
    assert second.trials == reference.trials and second.to_json()["failures"] == reference.to_json()["failures"]
    # extending the run to more trials reuses all 12
    third = run_experiment("settle", CFG, n=14, seed=7, workers=1, out=tmp_path)
    assert third.resumed == 12 and third.trials[:12] == reference.trials


def test_a_run_read_back_keeps_its_timing_and_a_shorter_look_writes_nothing(tmp_path, reference):
    """Reading a finished run back runs nothing: its ``result.json`` then says so (``resumed``) and keeps the time the
    trials took (the read-back call adds its own, near 0 s); a look at fewer of them (the feeder search reads its
    first trials back 5 at a time) writes nothing over the longer run; a run extended by new trials writes its
    new result."""
    first = run_experiment("settle", CFG, n=12, seed=7, workers=1, out=tmp_path)
    again = run_experiment("settle", CFG, n=12, seed=7, workers=1, out=tmp_path)
    assert again.resumed == 12 and again.trials == reference.trials
    doc = json.loads((tmp_path / "result.json").read_text())
    assert doc["resumed"] == 12 and first.elapsed_s <= doc["elapsed_s"] < first.elapsed_s + 1.0
    before = {p: (tmp_path / p).read_bytes() for p in ("result.json", "trials.parquet")}
    fewer = run_experiment("settle", CFG, n=5, seed=7, workers=1, out=tmp_path)  # a shorter look: its own result
    assert fewer.n == 5 and {p: (tmp_path / p).read_bytes() for p in before} == before
    more = run_experiment("settle", CFG, n=14, seed=7, workers=1, out=tmp_path)
    assert json.loads((tmp_path / "result.json").read_text())["n"] == more.n == 14


@pytest.mark.parametrize("workers", [1, 2])
def test_no_trial_is_started_past_stop_by(tmp_path, reference, workers):
    """A deadline already past starts no trial (the stored ones still count); a deadline in the middle of a run
    stops it early with the trials finished by then, each equal to the uninterrupted run's."""
    first = run_experiment("settle", CFG, n=12, seed=7, workers=1, out=tmp_path, stop_after=3)
    late = run_experiment("settle", CFG, n=12, seed=7, workers=workers, out=tmp_path, stop_by=time.perf_counter() - 1)
    assert first.n == late.n == 3 and not late.complete and late.resumed == 3
    if workers == 1:  # a deadline passed while the run goes on (the 6th trial's progress waits past it)
        stop = time.perf_counter() + 2.0

        def wait(done, total):
            if done == 6:
                time.sleep(max(0.0, stop - time.perf_counter()) + 0.05)

        cut = run_experiment("settle", CFG, n=12, seed=7, workers=1, out=tmp_path / "b", stop_by=stop, progress=wait)
        assert cut.n == 6 and cut.trials == reference.trials[:6]  # 6 settle trials take ≈ 0.1 s of the 2 s
    with pytest.raises(InvalidStateError, match=r"^stop_by: must be a time.perf_counter\(\) instant"):
        run_experiment("settle", CFG, n=2, seed=7, workers=1, stop_by=float("nan"))


def _processes_running(marker: str) -> list[int]:
    """Live processes whose command line contains ``marker`` (Linux /proc; empty elsewhere)."""
    pids = []
    for d in os.listdir("/proc") if os.path.isdir("/proc") else []:
        if d.isdigit():
            try:
                with open(f"/proc/{d}/cmdline", "rb") as fh:
                    cmd = fh.read()
                with open(f"/proc/{d}/stat") as fh:
                    state = fh.read().rsplit(")", 1)[1].split()[0]
            except OSError:
                continue
            if marker.encode() in cmd and state != "Z":
                pids.append(int(d))
    return pids


def test_killed_run_resumes(tmp_path):
    """SIGKILL a run in a subprocess mid-way: the trials it reported survive and are not redone."""
    out = tmp_path / "run"
    code = ("from throwmap.experiments.runner import run_experiment; "
            f"run_experiment('settle', {CFG!r}, n=150, seed=3, workers=2, out={str(out)!r})")
    proc = subprocess.Popen([sys.executable, "-c", code])
    lines = out / "trials.jsonl"
    t0 = time.monotonic()
    while time.monotonic() - t0 < 60:
        if lines.exists() and lines.read_bytes().count(b"\n") >= 5:
            break
        time.sleep(0.005)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    # its workers die with it (no orphan keeps computing or writing)
    t0 = time.monotonic()
    while _processes_running(str(out)) and time.monotonic() - t0 < 10:
        time.sleep(0.05)
    assert not _processes_running(str(out))
    kept = lines.read_bytes().count(b"\n")
    assert 5 <= kept < 150 and not (out / "result.json").exists()
    resumed = run_experiment("settle", CFG, n=150, seed=3, workers=1, out=out)
    assert resumed.resumed == kept and resumed.n == 150
    assert len(lines.read_text().splitlines()) == 150
    fresh = run_experiment("settle", CFG, n=150, seed=3, workers=2)
    assert resumed.trials == fresh.trials and resumed.ci95 == fresh.ci95


def test_torn_last_line_is_cut_and_redone(tmp_path, reference):
    run_experiment("settle", CFG, n=12, seed=7, workers=1, out=tmp_path, stop_after=4)
    with open(tmp_path / "trials.jsonl", "a") as fh:
        fh.write('{"index": 4, "seed": 1')  # the run was killed while writing trial 4
    r = run_experiment("settle", CFG, n=12, seed=7, workers=1, out=tmp_path)
    assert r.resumed == 4 and r.trials == reference.trials
    assert len((tmp_path / "trials.jsonl").read_text().splitlines()) == 12


def test_a_different_run_in_the_same_directory_is_refused(tmp_path):
    run_experiment("settle", CFG, n=3, seed=7, workers=1, out=tmp_path)
    with pytest.raises(InvalidStateError, match=r"^seed: differs from the run stored in .*stored 7, given 8"):
        run_experiment("settle", CFG, n=3, seed=8, workers=1, out=tmp_path)
    with pytest.raises(InvalidStateError, match=r"^config\.arm\.length: differs"):
        run_experiment("settle", {"arm": {"length": 0.5}}, n=3, seed=7, workers=1, out=tmp_path)
    fresh = run_experiment("settle", {"arm": {"length": 0.5}}, n=3, seed=8, workers=1, out=tmp_path, resume=False)
    assert fresh.resumed == 0 and len((tmp_path / "trials.jsonl").read_text().splitlines()) == 3


def test_work_guard_refuses_long_runs_and_keeps_the_trials(tmp_path):
    with pytest.raises(InvalidStateError, match=r"^n: experiment settle on [\d,]+ trials needs ≈ .* ms per trial .*--force.* kept in"):
        run_experiment("settle", CFG, n=500, seed=1, workers=1, out=tmp_path, limits=Limits(max_seconds=0.01))
    kept = len((tmp_path / "trials.jsonl").read_text().splitlines())
    assert kept >= 4  # the trials timed before the refusal are kept for a resume
    with pytest.raises(InvalidStateError, match="memory"):
        run_experiment("settle", CFG, n=10**9, seed=1, workers=1)
    r = run_experiment("settle", CFG, n=6, seed=1, workers=1, limits=Limits(max_seconds=1e-6, force=True))
    assert r.n == 6


def test_bad_inputs_are_one_line_errors():
    with pytest.raises(InvalidStateError, match="^seed:"):
        run_experiment("settle", n=2, seed=-1)
    with pytest.raises(InvalidStateError, match="^n:"):
        run_experiment("settle", n=-2, seed=0)
    with pytest.raises(InvalidStateError, match="^workers:"):
        run_experiment("settle", n=2, seed=0, workers=-1)
    with pytest.raises(ConfigError, match=r"^config\.arm\.lenght: unknown key 'lenght' \(did you mean 'length'"):
        run_experiment("settle", {"arm": {"lenght": 0.4}}, n=2, seed=0)
    with pytest.raises(ConfigError, match=r"^config\.noise\.omega_rel:"):
        run_experiment("settle", {"noise": {"omega_rel": -1}}, n=2, seed=0)


def test_no_trials_is_refused_before_work():
    # an experiment of 0 trials would report an empty table and exit 0: it is a usage error
    with pytest.raises(InvalidStateError, match=r"^n: must be an integer ≥ 1, got 0"):
        run_experiment("settle", n=0, seed=0, workers=1)


def test_trial_values_are_checked():
    with pytest.raises(InvalidStateError, match="^trial.failure:"):
        Trial(0, 1, True, "wrong_side")
    with pytest.raises(InvalidStateError, match="^trial.failure:"):
        Trial(0, 1, False)
    with pytest.raises(InvalidStateError, match=r"^trial.values\['a'\]:"):
        Trial(0, 1, True, None, {"a": [1, 2]})
    t = Trial(2, trial_seed(5, 2), False, "ejected", {"x": np.float64(0.1), "k": np.int64(2), "ok": np.bool_(True)})
    assert Trial.from_json(json.loads(json.dumps(t.to_json()))) == t


def test_plot(reference):
    ax = reference.plot()
    assert ax.get_ylabel() == "fraction of trials"
    assert [tick.get_text() for tick in ax.get_xticklabels()][0] == "success"


def test_parquet_takes_columns_of_mixed_types():
    import pyarrow as pa

    from throwmap.experiments.runner import _arrow_table

    t = _arrow_table(pa, [{"a": 1, "b": True, "c": 1}, {"a": "x", "b": 2, "c": 2.5}, {"a": None}])
    assert t.column("a").to_pylist() == ["1", "x", None]
    assert t.column("b").to_pylist() == [1.0, 2.0, None] and t.column("c").to_pylist() == [1.0, 2.5, None]


def test_an_unregistered_experiment_runs_in_this_process_only():
    from throwmap.experiments.settle import Settle

    mine = Settle()  # same class, not the registered object
    assert run_experiment(mine, CFG, n=2, seed=7, workers=1).trials == run_experiment("settle", CFG, n=2, seed=7,
                                                                                       workers=1).trials
    with pytest.raises(InvalidStateError, match="^experiment: 'settle' is not the registered experiment"):
        run_experiment(mine, CFG, n=2, seed=7, workers=2)


def test_the_result_has_to_dict_like_every_result(tmp_path):
    from throwmap.experiments import run_experiment

    r = run_experiment("settle", {"part": "triangle"}, n=2, seed=1, workers=1, out=tmp_path)
    assert r.to_dict() == r.to_json() and r.to_dict()["n"] == 2


def test_a_shorter_rerun_keeps_exactly_its_first_n_stored_trials(tmp_path, reference):
    run_experiment("settle", CFG, n=12, seed=7, workers=1, out=tmp_path)
    short = run_experiment("settle", CFG, n=5, seed=7, workers=1, out=tmp_path)
    assert short.n == 5 and short.resumed == 5 and [t.index for t in short.trials] == [0, 1, 2, 3, 4]
    assert short.trials == reference.trials[:5]
