"""Sweeps on a real local ``distributed`` cluster: scheduler and workers as processes on this machine.

The session's ``LocalCluster`` (2 worker processes, 1 thread each; ``tests/sweeps/conftest.py``) serves the target tests; the
worker-kill test, the ``--scheduler ADDRESS`` test (``dask scheduler`` / ``dask worker`` subprocesses)
and the killed-and-restarted ``throwmap sweep`` test start their own processes.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import throwmap as tm
from throwmap.experiments.runner import run_experiment
from throwmap.sweeps import make_design, parse_sweep, read_table, run_sweep

pytestmark = [pytest.mark.slow, pytest.mark.xdist_group("dask")]
distributed = pytest.importorskip("distributed")
BIN = Path(sys.executable).parent

SETTLE = {"kind": "grid", "target": "experiment:settle", "n": 4, "seed": 5,
          "parameters": {"arm.mu": [0.3, 0.8], "noise.mu_rel": [0.0, 0.2]}}


@pytest.fixture
def client(dask_client):
    """The session's cluster (tests/sweeps/conftest.py)."""
    return dask_client


def test_experiment_sweep_rows_are_the_runner_s(client, tmp_path):
    spec = parse_sweep(SETTLE)
    run = run_sweep(spec, tmp_path / "s", client=client)
    assert (run.n_points, run.rows_before, run.computed, run.rows_after, run.complete) == (4, 0, 4, 4, True)
    assert run.workers == 2
    t = read_table(tmp_path / "s").to_pylist()
    assert [r["point"] for r in t] == [0, 1, 2, 3]
    assert {r["version"] for r in t} == {tm.__version__} and {r["seed"] for r in t} == {5}
    for r, cfg in zip(t, make_design(spec).configs):
        ref = run_experiment("settle", cfg, n=4, seed=5, workers=1)
        assert (r["arm.mu"], r["noise.mu_rel"]) == (cfg["arm"]["mu"], cfg["noise"]["mu_rel"])
        assert (r["n"], r["successes"], r["ci95_low"], r["ci95_high"]) == (4, ref.successes, *ref.ci95)
        assert json.loads(r["failures"]) == ref.failures and r["error"] is None and r["elapsed_s"] > 0
    again = run_sweep(spec, tmp_path / "s", client=client)  # nothing missing: nothing computed
    assert (again.rows_before, again.computed, again.rows_after) == (4, 0, 4)


def test_throw_sweep_matches_throw_batch(client, tmp_path):
    doc = {"kind": "grid", "target": "throw", "chunk": 7,
           "parameters": {"x": {"low": 0.05, "high": 0.3, "num": 6}, "side": [0, 2], "omega": [4.0, 6.0]}}
    run = run_sweep(parse_sweep(doc), tmp_path / "t", client=client)
    assert (run.n_points, run.n_chunks, run.rows_after) == (24, 4, 24)
    t = read_table(tmp_path / "t").to_pydict()
    ref = tm.throw_batch(tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01, length=0.4, mu=0.8), np.array(t["x"]),
                         np.array(t["side"]), np.array(t["omega"]), on_invalid="status")
    assert t["status"] == [str(tm.Status(s)) for s in ref.status]
    landed = ref.status == int(tm.Status.OK)  # other statuses store no landing (null), not the echoed start
    np.testing.assert_array_equal(np.array(t["landing_x"], dtype=float), np.where(landed, ref.x, np.nan))
    assert t["landing_side"] == [int(s) if ok else None for s, ok in zip(ref.side, landed)]
    assert "invalid_start" in t["status"] and "ok" in t["status"] or "behind_joint" in t["status"]


def test_limit_set_sweep(client, tmp_path):
    doc = {"kind": "random", "target": "limit_set", "samples": 3, "seed": 2,
           "config": {"arm": {"length": float("inf")}, "n_starts": 4, "transient": 50, "n_record": 100},
           "parameters": {"omega": {"low": 2.0, "high": 4.0}}}
    spec = parse_sweep(doc)
    run_sweep(spec, tmp_path / "l", client=client)
    t = read_table(tmp_path / "l").to_pylist()
    assert len(t) == 3
    for r in t:
        ls = tm.limit_set(tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01, mu=0.8), r["omega"], n_starts=4, rng=2,
                          transient=50, n_record=100)
        assert (r["kind"], r["n_attractors"], json.loads(r["escapes"])) == (ls.kind, len(ls.attractors), ls.escapes)
        assert len(json.loads(r["attractors"])) == r["n_attractors"]


def test_stopped_sweep_resumes_only_the_missing_points(client, tmp_path):
    spec = parse_sweep({**SETTLE, "parameters": {"arm.mu": [0.2, 0.4, 0.6, 0.8, 1.0, 1.2]}})
    first = run_sweep(spec, tmp_path / "r", client=client, stop_after=2)
    assert (first.rows_before, first.computed, first.rows_after, first.complete) == (0, 2, 2, False)
    stored = {p.name: p.stat().st_mtime_ns for p in (tmp_path / "r").glob("part-*.parquet")}
    second = run_sweep(spec, tmp_path / "r", client=client)
    assert (second.rows_before, second.computed, second.rows_after, second.complete) == (2, 4, 6, True)
    assert all((tmp_path / "r" / k).stat().st_mtime_ns == v for k, v in stored.items())  # not rewritten
    assert read_table(tmp_path / "r").column("point").to_pylist() == list(range(6))


def test_a_worker_killed_mid_sweep(tmp_path):
    """SIGKILL a worker process while its tasks run: every point is stored once, with the values a clean run gives."""
    import logging

    spec = parse_sweep({**SETTLE, "n": 15, "parameters": {"arm.mu": [0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6]}})
    killed = []
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                                  silence_logs=logging.CRITICAL) as cluster, distributed.Client(cluster) as c:
        pids = c.run(os.getpid)

        def progress(done, total):
            if done >= 1 and not killed:  # the first part is stored: the other tasks are running
                victim = sorted(pids.values())[0]
                os.kill(victim, signal.SIGKILL)
                killed.append(victim)

        run = run_sweep(spec, tmp_path / "k", client=c, progress=progress)
        after = set(c.run(os.getpid).values())
        moved = c.run_on_scheduler(lambda dask_scheduler: [
            e[0] for e in dask_scheduler.transition_log if "sweep" in str(e[0]) and e[1] == "processing"
            and e[2] == "released" and str(e[4]).startswith("handle-worker-cleanup")])
    assert killed and killed[0] not in after  # the nanny started a new worker process
    assert moved, "no task was running on the killed worker"  # its tasks were released and run again elsewhere
    assert (run.rows_after, run.computed, run.complete) == (8, 8, True)
    t = read_table(tmp_path / "k").to_pylist()
    assert [r["point"] for r in t] == list(range(8))  # each point once
    for r, cfg in zip(t, make_design(spec).configs):
        assert r["successes"] == run_experiment("settle", cfg, n=15, seed=5, workers=1).successes


def _wait(pred, timeout=60.0, what="condition"):
    t0 = time.monotonic()
    while not pred():
        if time.monotonic() - t0 > timeout:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.1)


def test_cli_on_an_existing_scheduler(tmp_path):
    """``dask scheduler`` and ``dask worker`` as processes; ``throwmap sweep --scheduler ADDRESS`` (an unreachable
    address: ``test_sweep_guards.py``)."""
    sf = tmp_path / "scheduler.json"
    procs = [subprocess.Popen([str(BIN / "dask"), "scheduler", "--host", "127.0.0.1", "--port", "0",
                               "--no-dashboard", "--scheduler-file", str(sf)], stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)]
    try:
        _wait(sf.exists, what="the scheduler file")
        _wait(lambda: "address" in (sf.read_text() or "{}"), what="the scheduler address")
        address = json.loads(sf.read_text())["address"]
        procs.append(subprocess.Popen([str(BIN / "dask"), "worker", address, "--nworkers", "1", "--nthreads", "1",
                                       "--no-dashboard"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        sweep = tmp_path / "s.toml"
        sweep.write_text('kind = "grid"\ntarget = "experiment:settle"\nn = 2\nchunk = 4\n[parameters]\n'
                         '"arm.mu" = [0.3, 0.5, 0.7, 0.9, 1.1, 1.3]\n')
        done = subprocess.run([str(BIN / "throwmap"), "sweep", str(sweep), "--scheduler", address, "--json"],
                              capture_output=True, text=True, timeout=120, cwd=tmp_path)
        assert done.returncode == 0, done.stderr
        res = json.loads(done.stdout)
        assert (res["n_points"], res["computed"], res["rows_after"], res["scheduler"]) == (6, 6, 6, address)
        assert read_table(tmp_path / "runs" / "s.parquet").num_rows == 6  # the default: a run folder
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            p.wait(timeout=30)


def test_cli_sweep_killed_and_restarted(tmp_path):
    """SIGKILL ``throwmap sweep`` mid-run: its worker processes go with it, the parts written stay, and the restart
    computes exactly the missing points."""
    import psutil

    sweep = tmp_path / "s.toml"
    sweep.write_text('kind = "grid"\ntarget = "experiment:settle"\nseed = 1\nn = 15\n[parameters]\n'
                     '"arm.mu" = [0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3]\n')
    out = tmp_path / "runs" / "s.parquet"  # the default: a run folder in the current one
    proc = subprocess.Popen([str(BIN / "throwmap"), "sweep", str(sweep), "--workers", "1"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=tmp_path)
    _wait(lambda: len(list(out.glob("part-*.parquet"))) >= 2 or proc.poll() is not None, timeout=120,
          what="two parts")
    children = psutil.Process(proc.pid).children(recursive=True) if proc.poll() is None else []
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    before = len(list(out.glob("part-*.parquet")))
    assert 2 <= before < 12, "the sweep finished before it could be killed"
    gone, alive = psutil.wait_procs(children, timeout=30)
    assert not alive, f"orphaned worker processes: {[p.pid for p in alive]}"
    status = subprocess.run([str(BIN / "throwmap"), "sweep", str(sweep), "--status", "--json"], capture_output=True,
                            text=True, timeout=60, cwd=tmp_path)
    st = json.loads(status.stdout)
    assert (st["rows"], st["missing"]) == (before, 12 - before)
    done = subprocess.run([str(BIN / "throwmap"), "sweep", str(sweep), "--workers", "1", "--json"],
                          capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    res = json.loads(done.stdout)
    assert (res["rows_before"], res["computed"], res["rows_after"], res["complete"]) == (before, 12 - before, 12, True)
    assert read_table(out).column("point").to_pylist() == list(range(12))


def test_trials_split_across_tasks_give_the_same_rows(client, tmp_path):
    """``trials_per_task``: a point's trials run in several tasks; its row equals the one-task row."""
    whole = run_sweep(parse_sweep({**SETTLE, "n": 7}), tmp_path / "a", client=client)
    split = run_sweep(parse_sweep({**SETTLE, "n": 7, "trials_per_task": 3}), tmp_path / "b", client=client)
    assert (whole.rows_after, split.rows_after) == (4, 4)
    a, b = read_table(tmp_path / "a").drop(["elapsed_s"]), read_table(tmp_path / "b").drop(["elapsed_s"])
    assert a.equals(b)
    bad = run_sweep(parse_sweep({**SETTLE, "n": 2, "trials_per_task": 1, "parameters": {"part": ["triangle", "nosuch"]}}),
                    tmp_path / "c", client=client)
    rows = read_table(tmp_path / "c").to_pylist()
    assert rows[0]["error"] is None and rows[1]["error"].startswith("config.part") and rows[1]["n"] is None
