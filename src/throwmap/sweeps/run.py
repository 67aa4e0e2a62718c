"""Run a sweep on Dask: a local cluster by default, or an existing one; resume what a killed run left.

:func:`run_sweep` builds the design (:mod:`throwmap.sweeps.design`), creates or checks ``out``
(:mod:`throwmap.sweeps.store`), lists the chunks already stored, and submits only the missing ones, one
Dask task per chunk (:func:`throwmap.sweeps.targets.run_chunk`; with ``trials_per_task`` one task per block
of a point's trials, :func:`~throwmap.sweeps.targets.run_trials`; ``retries`` from the sweep). The client writes each chunk's Parquet file as its task finishes (workers need no access to
``out``), so a run killed at any moment keeps every chunk it reported, and a worker killed mid-task only
delays its chunk: the scheduler runs it again on another worker (``distributed.scheduler.allowed-failures``,
default 3, bounds how many worker deaths one task survives). A chunk is written once, under its own name,
so no point is ever duplicated.

Without ``scheduler`` or ``client`` a :class:`distributed.LocalCluster` is started for the call (worker
processes, one thread each; ``workers=0``: all cores) and closed at the end. ``import throwmap`` does not
import dask: it is imported here, inside the functions.

Work guard (:mod:`throwmap.budget`, ``limits``): before ``out`` is written or a cluster started, the points still
to compute are estimated, their memory in this process (:data:`BYTES_PER_POINT` and each one's config) and their
time (a sample of the first of them timed now, :func:`~throwmap.sweeps.targets.seconds_per_point`, shared by the
workers); above the limits the sweep is refused with one line on ``sweep``, unless ``limits.force``.
"""

from __future__ import annotations

import os
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from ..budget import Limits, guard_work, human_seconds
from ..errors import InvalidStateError, shown
from .design import make_design
from .schema import SweepSpec, jsonable, spec_hash
from .store import MANIFEST, column_types, count_rows, finished_chunks, part_path, prepare_out, write_chunk
from .targets import RESULT_COLUMNS

__all__ = ["SweepRun", "SweepStatus", "run_sweep", "sweep_status", "BYTES_PER_POINT"]

BYTES_PER_POINT = 1024
"""Memory this process holds per design point still to compute, bytes, besides twice its config's JSON (the
design's copy and its Dask task's): its future, its row before it is written (an estimate)."""


@dataclass(frozen=True, slots=True)
class SweepRun:
    """What a call did: ``out`` (the directory), ``sweep_sha256``, ``n_points``/``n_chunks`` of the design,
    ``rows_before`` (rows stored when it began), ``computed`` (points computed by this call) in
    ``chunks_computed`` chunks, ``rows_after`` (rows stored at the end), ``complete`` (every point stored),
    ``elapsed_s`` (s), ``workers`` (Dask workers seen; 0 when nothing was computed), ``scheduler`` (its
    address, or ``"local"``)."""

    out: str
    sweep_sha256: str
    target: str
    n_points: int
    n_chunks: int
    rows_before: int
    computed: int
    chunks_computed: int
    rows_after: int
    complete: bool
    elapsed_s: float
    workers: int
    scheduler: str

    def to_dict(self) -> dict:
        return {k: getattr(self, k) for k in self.__slots__}

    def summary(self) -> str:
        state = "complete" if self.complete else f"incomplete ({self.n_points - self.rows_after} points missing)"
        return (f"sweep {self.sweep_sha256[:12]} ({self.target}): {self.n_points} points in {self.n_chunks} parts; "
                f"rows before {self.rows_before}, computed now {self.computed}, rows after {self.rows_after} — "
                f"{state}; {self.elapsed_s:.3g} s on {self.workers} worker(s) ({self.scheduler}) → {self.out}")


@dataclass(frozen=True, slots=True)
class SweepStatus:
    """What ``out`` holds of a sweep, computed without running anything (:func:`sweep_status`): ``out``,
    ``sweep_sha256``, ``n_points`` and ``n_chunks`` of the design, ``rows`` stored, ``missing`` points,
    ``chunks_missing`` parts."""

    out: str
    sweep_sha256: str
    n_points: int
    n_chunks: int
    rows: int
    missing: int
    chunks_missing: int

    def to_dict(self) -> dict:
        return {k: getattr(self, k) for k in self.__slots__}

    def table(self) -> str:
        """One line: points and parts, rows stored and missing."""
        return (f"sweep {self.sweep_sha256[:12]} in {self.out}: {self.n_points} points in {self.n_chunks} parts; "
                f"rows stored {self.rows}, missing {self.missing} ({self.chunks_missing} parts)")

    def plot(self, ax=None):
        """Parts stored and missing as one bar (:func:`throwmap.viz.sweep.plot_sweep_status`)."""
        from ..viz.sweep import plot_sweep_status

        return plot_sweep_status(self, ax=ax)


def _manifest(spec: SweepSpec, design, columns: dict) -> dict:
    return {"sweep_sha256": spec_hash(spec), "target": spec.target, "kind": spec.kind, "n_points": design.n_points,
            "n_chunks": design.n_chunks, "chunk": design.chunk, "parameters": list(design.names),
            "columns": columns, "spec": jsonable(spec.model_dump())}


def _plan(spec: SweepSpec, out, create: bool = True, design=None):
    """``(design, columns, chunks done)``; ``create=False`` (``--status``): ``out`` is checked if it holds a
    manifest, never created. ``design``: :func:`make_design` of ``spec`` if already made."""
    design = make_design(spec) if design is None else design
    columns = column_types(design.names, design.points, RESULT_COLUMNS[spec.target_kind])
    if create or (Path(out) / MANIFEST).exists() or (Path(out).exists() and not Path(out).is_dir()):
        columns = prepare_out(out, _manifest(spec, design, columns))["columns"]
    done = finished_chunks(out, design.n_chunks, lambda c: len(design.chunk_points(c)))
    return design, columns, done


def _tasks(spec: SweepSpec, design, todo, digest: str) -> dict:
    """``{key: (function, args, (chunk, point, block))}``: one :func:`run_chunk` per chunk, or with
    ``trials_per_task`` one :func:`run_trials` per block of trials of each point (point, block = −1 otherwise)."""
    from .targets import run_chunk, run_trials

    tasks = {}
    for c in todo:
        pts = design.chunk_points(c)
        if spec.trials_per_task is None:
            args = (spec.target, [design.configs[i] for i in pts], [design.seeds[i] for i in pts], spec.n)
            tasks[f"throwmap-sweep-{digest[:16]}-{c}"] = (run_chunk, args, (c, -1, -1))
            continue
        for i in pts:
            for j, start in enumerate(range(0, spec.n, spec.trials_per_task)):
                stop = min(start + spec.trials_per_task, spec.n)
                args = (spec.experiment, design.configs[i], design.seeds[i], start, stop)
                tasks[f"throwmap-sweep-{digest[:16]}-{c}-{i}-{j}"] = (run_trials, args, (c, i, j))
    return tasks


def _results(spec: SweepSpec, design, c: int, got: dict) -> list:
    """The result columns of chunk ``c``'s points from its finished tasks ``{(point, block): result}``."""
    if spec.trials_per_task is None:
        return got[(-1, -1)]
    from .targets import summarise_trials

    out = []
    for i in design.chunk_points(c):
        blocks = [got[k] for k in sorted(k for k in got if k[0] == i)]
        out.append(summarise_trials(spec.experiment, design.configs[i], design.seeds[i], spec.n, blocks).to_dict())
    return out


def _missing_points(out: Path, design) -> list:
    """The design points whose chunk ``out`` does not seem to hold yet (no Parquet file of it there; nothing read,
    nothing deleted): the guard's count, before ``out`` is checked."""
    names = {p.name for p in out.iterdir()} if out.is_dir() else set()
    return [i for c in range(design.n_chunks) if part_path(out, c).name not in names for i in design.chunk_points(c)]


def _guard(spec: SweepSpec, design, out: Path, limits: Limits, n_workers: int) -> None:
    """Refuse, with one line on ``sweep``, a sweep whose points still missing from ``out`` would hold more memory
    than ``limits.max_memory`` or take longer than ``limits.max_seconds`` on ``n_workers`` workers (module
    docstring); nothing is refused under ``limits.force``, nor timed."""
    import json

    if limits.force:
        return
    todo = _missing_points(out, design)
    if not todo:
        return
    config_bytes = len(json.dumps(design.configs[todo[0]], default=str))
    per_point = BYTES_PER_POINT + 2 * config_bytes
    if spec.trials_per_task is not None:  # a point's trials wait in this process until its last task is done
        from ..experiments.runner import BYTES_PER_TRIAL

        per_point += spec.n * BYTES_PER_TRIAL
    hint = "a smaller design (fewer values or samples)"
    guard_work(f"{spec.target} sweep", "sweep", len(todo), per_point, limits, hint=hint, unit="points")
    from .targets import seconds_per_point

    first = todo[:16]
    try:
        each = seconds_per_point(spec.target, [design.configs[i] for i in first], [design.seeds[i] for i in first],
                                 spec.n)
    except Exception:  # noqa: BLE001 - a sample the run's own tasks would fail on: no estimate, the run says why
        each = None
    if each is None:
        return
    secs = each * len(todo) / max(1, n_workers)
    if secs > limits.max_seconds:
        raise InvalidStateError(
            "sweep", f"{spec.target} sweep on {len(todo):,} points needs ≈ {human_seconds(secs)} "
                     f"({human_seconds(each)} per point measured now, on {n_workers} worker(s)), over the limit of "
                     f"{human_seconds(limits.max_seconds)}: raise the limits, limits=Limits(max_seconds=…) (CLI "
                     f"--max-time s), pass limits=Limits(force=True) (--force), or use {hint}")


def _workers_of(client, workers: int) -> int:
    """The workers that will share the points: ``client``'s (at least 1), else the local cluster's."""
    if client is not None:
        try:
            return max(1, len(client.scheduler_info().get("workers", {})))
        except Exception:  # noqa: BLE001 - a client that cannot say: one worker (the longest estimate)
            return 1
    return (os.cpu_count() or 1) if workers == 0 else workers


def sweep_status(spec: SweepSpec, out) -> SweepStatus:
    """What is stored in ``out`` for ``spec`` without computing anything (a :class:`SweepStatus`: ``n_points``,
    ``n_chunks``, ``rows`` stored, ``missing`` points, ``chunks_missing``)."""
    design, _, done = _plan(spec, out, create=False)
    rows = count_rows(out)
    return SweepStatus(str(out), spec_hash(spec), design.n_points, design.n_chunks, rows, design.n_points - rows,
                       design.n_chunks - len(done))


def _check_address(scheduler: str) -> None:
    """A malformed scheduler address (no port, unknown scheme, unknown host): one line on ``scheduler``."""
    from distributed.comm import resolve_address

    try:
        resolve_address(scheduler)
    except (OSError, ValueError) as err:
        raise InvalidStateError("scheduler", f"cannot connect to {shown(scheduler)}: {' '.join(str(err).split())}") from None


def _client(scheduler, workers: int, timeout: float):
    """``(client, cluster or None)``: connect to ``scheduler``, or start a local cluster of worker processes."""
    import logging

    from distributed import Client, LocalCluster

    if scheduler is not None:
        _check_address(scheduler)  # a malformed address fails here, before a half-built Client to clean up
        try:
            return Client(scheduler, timeout=f"{timeout}s", set_as_default=False), None
        except (OSError, TimeoutError, ValueError) as err:
            raise InvalidStateError("scheduler", f"cannot connect to {shown(scheduler)}: {' '.join(str(err).split())}") from None
    n = (os.cpu_count() or 1) if workers == 0 else workers
    cluster = None
    try:
        with _sigint_ignored() as interrupted:
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0",
                                   silence_logs=logging.CRITICAL)
        if interrupted():
            raise KeyboardInterrupt
        return Client(cluster, set_as_default=False), cluster
    except BaseException:
        if cluster is not None:
            cluster.close()
        raise


@contextmanager
def _sigint_ignored():
    """Run the block with SIGINT ignored, so that the worker processes it starts inherit that: a Ctrl-C then
    reaches only this process, which closes the cluster, instead of killing every worker mid-task with a
    traceback each. Yields ``interrupted()``: whether a Ctrl-C came meanwhile — a terminal signals the whole
    process group, so a sentinel child keeping SIGINT's default action dies of it; ignored here, it would be
    lost and the run would go on to the end. Outside the main thread SIGINT is left as it is."""
    import signal
    import subprocess
    import sys
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield lambda: False
        return
    sentinel = None
    if signal.getsignal(signal.SIGINT) is not signal.SIG_IGN:  # already ignored (a background run): no Ctrl-C
        sentinel = subprocess.Popen([sys.executable, "-c", "import sys; sys.stdin.read()"], stdin=subprocess.PIPE,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield lambda: sentinel is not None and sentinel.poll() == -signal.SIGINT
    finally:
        if sentinel is not None:
            sentinel.stdin.close()  # ends it, unless a Ctrl-C did
            try:
                sentinel.wait(timeout=10)
            except subprocess.TimeoutExpired:  # pragma: no cover - a stuck interpreter
                sentinel.kill()
                sentinel.wait()
        signal.signal(signal.SIGINT, old)


def _quiet_close(client, cluster, own: bool) -> None:
    """On an interruption: cancel what runs and close the client (and cluster) with Dask's loggers silenced, so
    that the shutdown prints no worker tracebacks (the parts already written stay)."""
    import logging

    for name in ("distributed", "tornado", "asyncio"):
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)
    for step in ((lambda: client.cancel(list(client.futures.values()), force=True)),
                 (lambda: client.close(timeout=10) if own else None),
                 (lambda: cluster.close(timeout=10) if cluster is not None else None)):
        try:
            step()
        except BaseException:  # noqa: BLE001 - a second Ctrl-C or a dying cluster: still exit quietly
            pass


def run_sweep(spec: SweepSpec, out, *, scheduler: str | None = None, client=None, workers: int = 0,
              progress=None, stop_after: int | None = None, connect_timeout: float = 20.0,
              limits: Limits | None = None) -> SweepRun:
    """Compute every design point of ``spec`` missing from ``out`` on Dask and store it (module docstring).

    ``scheduler``: the address of a running Dask scheduler (``tcp://host:8786``); ``client``: a
    :class:`distributed.Client` to use as it is; neither: a local cluster of ``workers`` processes (0: all
    cores). ``progress(done, total)`` counts points (stored ones count as done at the start). ``stop_after``:
    write at most this many chunks, then cancel the rest and return (an interruption on purpose).
    ``connect_timeout``: seconds to wait for ``scheduler`` before giving up (one line on ``scheduler``).
    ``limits`` (a :class:`~throwmap.budget.Limits`; None: 2 GB, 30 min) bound the estimated work of the points
    still missing (module docstring); ``limits.force`` runs anyway.

    Raises :class:`~throwmap.errors.InvalidStateError` on a bad sweep (before anything runs), a sweep over the
    limits (before ``out`` is written or a cluster started), a changed sweep in ``out``, an unreachable
    scheduler, or a task that failed after its retries (chunks already written are kept).
    """
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 0:
        raise InvalidStateError("workers", f"must be an integer ≥ 0 (0: all cores), got {shown(workers)}")
    if stop_after is not None and (isinstance(stop_after, bool) or not isinstance(stop_after, int) or stop_after < 1):
        raise InvalidStateError("stop_after", f"must be an integer ≥ 1, got {shown(stop_after)}")
    if isinstance(connect_timeout, bool) or not isinstance(connect_timeout, (int, float)) or not connect_timeout > 0:
        raise InvalidStateError("connect_timeout", f"must be a number of seconds > 0, got {shown(connect_timeout)}")
    limits = Limits.of(limits)
    early = None
    if scheduler is not None and client is None:
        _check_address(scheduler)  # before ``out`` is created
        early = _client(scheduler, workers, connect_timeout)  # an unreachable scheduler fails before out is written
    t0 = time.perf_counter()
    out = Path(out)
    try:
        design = make_design(spec)
        _guard(spec, design, out, limits, _workers_of(early[0] if early is not None else client, workers))
        design, columns, done = _plan(spec, out, design=design)
    except BaseException:
        if early is not None:
            early[0].close()
        raise
    rows_before = count_rows(out)
    todo = [c for c in range(design.n_chunks) if c not in done]
    digest = spec_hash(spec)
    n_done = rows_before
    if progress is not None:
        progress(n_done, design.n_points)
    computed = chunks = n_workers = 0
    where = "local" if scheduler is None and client is None else (scheduler or "client")
    if not todo and early is not None:
        early[0].close()
    if todo:
        from distributed import as_completed

        own = client is None
        cluster = None
        if own:
            client, cluster = early if early is not None else _client(scheduler, workers, connect_timeout)
        try:
            if client.scheduler is not None and where == "client":
                where = client.scheduler.address
            n_workers = len(client.scheduler_info().get("workers", {}))
            tasks = _tasks(spec, design, todo, digest)
            futures = []
            for fn in {v[0] for v in tasks.values()}:  # one client.map per function: the graph goes in one message
                keys = [k for k, v in tasks.items() if v[0] is fn]
                futures += client.map(fn, *zip(*(tasks[k][1] for k in keys)), key=keys, retries=spec.retries,
                                      pure=False)
            need = {c: 0 for c in todo}
            for _, _, (c, _, _) in tasks.values():
                need[c] += 1
            got: dict = {c: {} for c in todo}
            for fut in as_completed(futures, loop=client.loop):
                c, i, j = tasks[fut.key][2]
                try:
                    got[c][(i, j)] = fut.result()
                except Exception as err:  # a task that failed after its retries, or killed too many workers
                    client.cancel(futures)
                    pts = design.chunk_points(c)
                    raise InvalidStateError("sweep", f"part {c} (points {pts.start}–{pts.stop - 1}) failed: "
                                                     f"{type(err).__name__}: {' '.join(str(err).split())[:300]}; the "
                                                     f"{chunks} parts finished are kept in {str(out)!r}") from None
                if len(got[c]) < need[c]:
                    continue
                rows = []
                for i, res in zip(design.chunk_points(c), _results(spec, design, c, got.pop(c))):
                    rows.append({"point": i, **dict(zip(design.names, design.points[i])), "seed": design.seeds[i],
                                 **res})
                write_chunk(out, c, rows, columns)
                computed += len(rows)
                chunks += 1
                n_done += len(rows)
                if progress is not None:
                    progress(n_done, design.n_points)
                if stop_after is not None and chunks >= stop_after:
                    client.cancel(futures)
                    break
            n_workers = max(n_workers, len(client.scheduler_info().get("workers", {})))
        except KeyboardInterrupt:
            _quiet_close(client, cluster if own else None, own)
            raise
        finally:
            if own:
                client.close()
                if cluster is not None:
                    cluster.close()
    rows_after = count_rows(out)
    return SweepRun(str(out), digest, spec.target, design.n_points, design.n_chunks, rows_before, computed, chunks,
                    rows_after, rows_after == design.n_points, time.perf_counter() - t0, n_workers, where)

