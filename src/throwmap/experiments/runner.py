"""The Monte Carlo runner every experiment shares (STYLE §13).

:func:`run_experiment` runs trials ``0 … n−1`` of a registered experiment, each with its
own generator spawned from the run's seed (:func:`throwmap.experiments.base.trial_generator`),
in parallel processes (``workers=0``: all cores). A worker looks the experiment up by
name, so nothing but the name, the config as JSON and two integers crosses the process
boundary; each trial depends only on ``(config, seed, index)``, so the same seed gives
the same trials whatever the number of workers.

Keeping and resuming (``out=DIR``):

* ``DIR/run.json`` — the run's header (experiment, version, config, seed), written first;
* ``DIR/trials.jsonl`` — one JSON line per finished trial, appended as it finishes
  (flushed and fsync'ed line by line: an interrupted run loses no trial it reported);
* ``DIR/result.json`` and ``DIR/trials.parquet`` — written at the end, atomically
  (a temporary file, then :func:`os.replace`).

Running again into the same ``DIR`` (``resume=True``) reuses every stored trial with
index < n and runs only the missing ones; a different experiment, config or seed is
refused with one line naming the field (``resume=False`` discards the stored trials).
Because a trial's generator does not depend on ``n``, a finished run may be extended to a
larger ``n`` into the same directory.

Work guard (:mod:`throwmap.budget`): the trials' memory is checked up front; the time
is estimated from the first trials of this run (their wall time × the trials left ÷
the workers) and above ``max_seconds`` the run stops with one line on ``n`` — unless
``force`` — keeping the trials it finished.
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
from collections import Counter
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from ..version import __version__
from ..budget import Limits, check_count, guard_work, human_seconds
from ..errors import InvalidStateError, shown
from ..io.files import make_directory
from ..system.arm import regime_warnings_once
from .base import Trial, config_of, trial_generator, trial_seed
from .registry import get_experiment
from .stats import wilson_interval

__all__ = ["ExperimentResult", "run_experiment", "load_result", "BYTES_PER_TRIAL", "TIMED_TRIALS"]

BYTES_PER_TRIAL = 4000
"""Memory the runner holds per trial, bytes (its :class:`Trial`, a few values, its JSON line)."""
TIMED_TRIALS = 4
"""Trials (per worker) finished before the run's total time is estimated and guarded."""
CHUNK_SECONDS = 0.2
"""s of work a worker is handed at a time once trials have been timed (at least one trial): cheap trials go
in chunks so that inter-process traffic does not dominate; an interrupted run loses at most the chunks in flight."""
MAX_CHUNK = 64
"""Most trials handed to a worker at a time."""


@dataclass(frozen=True, slots=True)
class ExperimentResult:
    """The summary of a run of an experiment.

    ``n`` trials summarised (``planned`` were asked for; ``complete`` when all ran),
    ``successes``, ``success_rate`` = successes / n (nan when n = 0), ``ci95`` its Wilson
    95 % interval (:func:`~throwmap.experiments.stats.wilson_interval`), ``failures``
    the count of each failure kind, ``seed`` the run's seed, ``parameters`` every
    parameter of the experiment (SI), ``config`` the validated config as JSON,
    ``trials`` sorted by index, ``elapsed_s`` the wall time spent running them (s: this call's, plus that
    of the stored run it read back), ``workers`` the processes used, ``resumed`` how many trials were
    read back from ``out`` instead of run.
    """

    name: str
    n: int
    successes: int
    success_rate: float
    ci95: tuple
    failures: dict
    seed: int
    parameters: dict
    trials: tuple
    elapsed_s: float
    workers: int
    planned: int = 0
    complete: bool = True
    config: dict | None = None
    resumed: int = 0
    version: str = __version__

    @classmethod
    def from_trials(cls, name: str, trials, *, seed: int, parameters: dict, planned: int, elapsed_s: float,
                    workers: int, config: dict | None = None, resumed: int = 0) -> "ExperimentResult":
        trials = tuple(sorted(trials, key=lambda t: t.index))
        n = len(trials)
        k = sum(t.success for t in trials)
        fails = Counter(t.failure for t in trials if not t.success)
        return cls(name, n, k, (k / n if n else math.nan), wilson_interval(k, n), dict(sorted(fails.items())),
                   int(seed), parameters, trials, float(elapsed_s), int(workers), int(planned), n == planned,
                   config, int(resumed))

    def to_json(self) -> dict:
        """The summary as one JSON object (no trials; they are in ``trials.jsonl``/``trials.parquet``)."""
        return {"experiment": self.name, "version": self.version, "n": self.n, "successes": self.successes,
                "success_rate": None if math.isnan(self.success_rate) else self.success_rate,
                "ci95": [self.ci95[0], self.ci95[1]], "failures": dict(self.failures), "seed": self.seed,
                "planned": self.planned, "complete": self.complete, "parameters": self.parameters,
                "config": self.config, "values": self.value_summary(), "elapsed_s": self.elapsed_s,
                "workers": self.workers, "resumed": self.resumed}

    def to_dict(self) -> dict:
        """The summary as a JSON-ready dict, as every result object gives it (the same as :meth:`to_json`)."""
        return self.to_json()

    def value_summary(self) -> dict:
        """For each numeric per-trial value: ``{"mean", "median", "p90", "min", "max", "count", "missing"}`` over
        the trials where it is finite (``missing``: trials where it is nan, e.g. throws to success of a failed
        trial); ``p90`` the 90th percentile (linear interpolation)."""
        import numpy as np

        out = {}
        keys = []
        for t in self.trials:
            keys.extend(k for k in t.values if k not in keys)
        for key in keys:
            vals = [t.values[key] for t in self.trials if key in t.values]
            if not vals or any(isinstance(v, (str, bool)) or not isinstance(v, (int, float)) for v in vals):
                continue
            nums = np.array([float(v) for v in vals if math.isfinite(float(v))])
            if nums.size:
                out[key] = {"mean": float(nums.mean()), "median": float(np.median(nums)),
                            "p90": float(np.percentile(nums, 90)), "min": float(nums.min()), "max": float(nums.max()),
                            "count": int(nums.size), "missing": len(vals) - int(nums.size)}
        return out

    def rows(self) -> list[dict]:
        """One flat dict per trial: index, seed, success, failure, then the values."""
        return [{"index": t.index, "seed": t.seed, "success": t.success, "failure": t.failure, **t.values}
                for t in self.trials]

    def table(self) -> str:
        """The summary as plain text: rate with interval, then the failures by kind."""
        lo, hi = self.ci95
        rate = "n/a" if math.isnan(self.success_rate) else f"{100 * self.success_rate:.1f} %"
        lines = [f"experiment {self.name} (throwmap {self.version}), seed {self.seed}: "
                 f"{self.successes}/{self.n} succeeded = {rate}, Wilson 95 % [{100 * lo:.1f}, {100 * hi:.1f}] %"
                 + ("" if self.complete else f" (incomplete: {self.n} of {self.planned} trials)")]
        for kind, c in self.failures.items():
            lines.append(f"  {kind:<24}{c:>7}  ({100 * c / self.n:.1f} %)")
        return "\n".join(lines)

    def plot(self, ax=None):
        """Bar chart of the outcomes (success and each failure kind) with the success rate's interval."""
        from .plot import plot_result

        return plot_result(self, ax=ax)


# ------------------------------------------------------------------- workers
_CONFIGS: dict = {}


def _worker_init() -> None:
    """In each worker: ignore SIGINT, and die with the parent (Linux ``PR_SET_PDEATHSIG``), so that a run
    killed with SIGKILL leaves no orphaned workers behind.

    A terminal's Ctrl-C signals the whole process group: a worker interrupted inside the pool's queues can
    leave their lock taken and hang the run. Only the parent acts on it (:func:`_stop_workers`); the
    workers start with SIGINT blocked (:func:`_sigint_blocked`), so none is lost or acted on before this."""
    import signal

    if hasattr(signal, "pthread_sigmask"):
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a Ctrl-C pending from the start is dropped
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            ctypes.CDLL(None, use_errno=True).prctl(1, int(signal.SIGTERM), 0, 0, 0)  # PR_SET_PDEATHSIG = 1
        except (OSError, AttributeError):  # pragma: no cover - exotic libc
            pass


@contextmanager
def _sigint_blocked():
    """Block SIGINT in this thread for the block (POSIX), so that a worker process started in it inherits it
    blocked until :func:`_worker_init`; a Ctrl-C meanwhile reaches this process when the block ends."""
    import signal

    if not hasattr(signal, "pthread_sigmask"):  # pragma: no cover - Windows: no process groups to signal
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def _stop_workers(pool) -> None:
    """After a Ctrl-C: end the pool's workers now, instead of waiting for their running trials (those are not
    stored, and a resume runs them); the pool then shuts down at once, as after a worker's crash."""
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        try:
            proc.terminate()
        except (OSError, ValueError, AttributeError):  # already gone or closed
            pass


def _run_chunk(name: str, config_json: str, seed: int, indices: tuple, module: str | None = None) -> tuple[list, float]:
    """Run trials ``indices`` in a worker: look the experiment up by name, rebuild the config from JSON.
    ``module``: the module that registers the experiment, imported first where the worker does not know the
    name yet (an experiment registered outside this package, e.g. a study, in a worker that was spawned rather
    than forked). Returns the trials as JSON objects and the seconds they took."""
    t0 = time.perf_counter()
    if module is not None:
        from .registry import _REGISTRY

        if name not in _REGISTRY:
            import importlib

            importlib.import_module(module)
    exp = get_experiment(name)
    key = (name, config_json)
    cfg = _CONFIGS.get(key)
    if cfg is None:
        cfg = _CONFIGS[key] = exp.config_type.model_validate_json(config_json)
    return [_checked(exp, cfg, seed, i).to_json() for i in indices], time.perf_counter() - t0


def _checked(exp, cfg, seed: int, index: int) -> Trial:
    t = exp.trial(cfg, index, trial_generator(seed, index))
    if not isinstance(t, Trial):
        raise InvalidStateError("experiment.trial", f"{exp.name}: must return a Trial, got {type(t).__name__}")
    want = trial_seed(seed, index)
    if t.index != index or t.seed != want:
        raise InvalidStateError("experiment.trial", f"{exp.name}: trial {index} returned index {t.index}, seed {t.seed} "
                                                    f"(expected index {index}, seed {want} = trial_seed(seed, index))")
    return t


# ------------------------------------------------------------------- storage
def _fsync_line(fh, obj: dict) -> None:
    fh.write(json.dumps(obj, allow_nan=False) + "\n")
    fh.flush()
    os.fsync(fh.fileno())


def _atomic_bytes(path: Path, write) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        write(tmp)
        with open(tmp, "rb") as fh:
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def _read_trials(path: Path) -> dict[int, Trial]:
    """Stored trials by index; a torn last line (the run was killed while writing it) is cut off."""
    out: dict[int, Trial] = {}
    if not path.exists():
        return out
    raw = path.read_bytes()
    good = 0
    for line in raw.splitlines(keepends=True):
        if not line.endswith(b"\n"):
            break
        try:
            t = Trial.from_json(json.loads(line))
        except (ValueError, KeyError, TypeError):
            break
        out.setdefault(t.index, t)
        good += len(line)
    if good < len(raw):
        with open(path, "r+b") as fh:
            fh.truncate(good)
    return out


def _header(name: str, config_json: str, seed: int) -> dict:
    return {"experiment": name, "version": __version__, "config": json.loads(config_json), "seed": int(seed)}


def _first_difference(a, b, path: tuple = ()) -> tuple:
    """``(dotted path, a's value, b's value)`` of the first place two configs differ (nested tables followed)."""
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if a.get(k) != b.get(k):
                return _first_difference(a.get(k), b.get(k), path + (str(k),))
    return path, a, b


def _check_header(stored: dict, want: dict, directory: Path) -> None:
    for key in ("experiment", "seed", "config"):
        if stored.get(key) != want[key]:
            field = "config" if key == "config" else key
            if key == "config":
                path, a, b = _first_difference(stored.get("config") or {}, want["config"])
                field = ".".join(("config",) + path)
                detail = f"stored {shown(a, 60)}, given {shown(b, 60)}"
            else:
                detail = f"stored {shown(stored.get(key))}, given {shown(want[key])}"
            raise InvalidStateError(field, f"differs from the run stored in {str(directory)!r} ({detail}): "
                                           f"use another --out directory, or resume=False (--no-resume) to discard it")


def load_result(directory) -> dict:
    """The ``result.json`` of a finished run stored in ``directory``."""
    return json.loads((Path(directory) / "result.json").read_text())


# ------------------------------------------------------------------- runner
@regime_warnings_once()
def run_experiment(experiment, config=None, *, n: int, seed: int, workers: int = 0, out=None, resume: bool = True,
                   progress=None, limits: Limits | None = None, stop_after: int | None = None,
                   stop_by: float | None = None) -> ExperimentResult:
    """Run trials ``0 … n−1`` of ``experiment`` (a registered name or object) and summarise them.

    ``config``: an instance of the experiment's ``config_type``, a dict validated by it,
    or None (the built-in example). ``seed`` (int ≥ 0): trial i's generator is
    ``default_rng(SeedSequence(seed).spawn(n)[i])``. ``workers``: processes (0: all
    cores, 1: this process). ``out``: a directory keeping the trials (module docstring);
    ``resume``: reuse the trials stored there. ``progress(done, total)`` is called after
    each trial (stored trials count as done at the start). ``limits`` (a :class:`~throwmap.budget.Limits`;
    None: 2 GB, 30 min) bound the estimated work; ``limits.force`` runs anyway. ``stop_after``: run at most this
    many new trials, then return the (incomplete) result — an interruption on purpose. ``stop_by``: a
    ``time.perf_counter()`` instant after which no trial is started (those under way finish; at most one chunk of
    ≈ 0.2 s of work per process); the result is then incomplete, as with ``stop_after``.

    Raises :class:`~throwmap.errors.InvalidStateError` on bad input, on a stored run that
    does not match, and when the work guard refuses (trials already finished are kept in ``out``).
    """
    exp = get_experiment(experiment)
    cfg = config_of(exp, config)
    n = check_count("n", n, minimum=1)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise InvalidStateError("seed", f"must be a non-negative integer, got {shown(seed)}")
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 0:
        raise InvalidStateError("workers", f"must be an integer ≥ 0 (0: all cores), got {shown(workers)}")
    if stop_after is not None:
        stop_after = check_count("stop_after", stop_after)
    if stop_by is not None and not (isinstance(stop_by, (int, float)) and not isinstance(stop_by, bool)
                                    and math.isfinite(stop_by)):
        raise InvalidStateError("stop_by", f"must be a time.perf_counter() instant, s, got {shown(stop_by)}")
    limits = Limits.of(limits)
    max_seconds, force = limits.max_seconds, limits.force
    guard_work(f"experiment {exp.name}", "n", n, BYTES_PER_TRIAL, limits,
               hint="fewer trials (--n)", unit="trials")
    n_workers = (os.cpu_count() or 1) if workers == 0 else workers
    if n_workers > 1:
        from .registry import _REGISTRY

        if _REGISTRY.registered(exp.name) is not exp:
            raise InvalidStateError("experiment", f"{exp.name!r} is not the registered experiment of that name: workers "
                                                  f"look experiments up by name, so register it "
                                                  f"(register_experiment) or run it with workers=1")
    config_json = cfg.model_dump_json()
    parameters = exp.parameters(cfg)
    header = _header(exp.name, config_json, seed)

    stored: dict[int, Trial] = {}
    fh = None
    directory = None
    if out is not None:
        directory = make_directory(out, "out")  # only it: a missing folder above it is refused
        head_path, lines_path = directory / "run.json", directory / "trials.jsonl"
        if resume and head_path.exists():
            _check_header(json.loads(head_path.read_text()), header, directory)
            stored = {i: t for i, t in _read_trials(lines_path).items() if i < n}
            for i, t in stored.items():
                if t.seed != trial_seed(seed, i):
                    raise InvalidStateError("out", f"trial {i} stored in {str(lines_path)!r} has seed {t.seed}, "
                                                   f"not {trial_seed(seed, i)}: the file was not written by this run")
        else:
            _atomic_bytes(head_path, lambda p: p.write_text(json.dumps(header, indent=2) + "\n"))
            lines_path.write_bytes(b"")
        fh = open(lines_path, "a", encoding="utf-8")

    todo = [i for i in range(n) if i not in stored]
    if stop_after is not None:
        todo = todo[:stop_after]
    done: dict[int, Trial] = dict(stored)
    t0 = time.perf_counter()
    if progress is not None:
        progress(len(done), n)
    timed = TIMED_TRIALS * n_workers
    left_total = len([i for i in range(n) if i not in stored])

    def finish(t: Trial, k: int) -> None:
        t = Trial.from_json(t.to_json())  # as stored and read back: a resumed run gives the identical result
        done[t.index] = t
        if fh is not None:
            _fsync_line(fh, t.to_json())
        if progress is not None:
            progress(len(done), n)
        if k == timed and left_total > timed and not force:
            per = (time.perf_counter() - t0) / k  # wall time per trial on n_workers processes
            secs = per * left_total
            if secs > max_seconds:
                raise InvalidStateError(
                    "n", f"experiment {exp.name} on {left_total:,} trials needs ≈ {human_seconds(secs)} "
                         f"({1e3 * per * n_workers:.3g} ms per trial on each of {n_workers} worker(s), measured on the "
                         f"first {k}), over the limit of {human_seconds(max_seconds)}: raise the limits, "
                         f"limits=Limits(max_seconds=…) (CLI --max-time s), pass limits=Limits(force=True) (--force), "
                         f"or use fewer trials (--n); the {len(done)} finished trials are kept"
                         + (f" in {str(directory)!r} for a resume" if directory is not None else ""))

    try:
        if n_workers == 1 or len(todo) <= 1:
            for k, i in enumerate(todo, 1):
                if stop_by is not None and time.perf_counter() > stop_by:
                    break
                finish(_checked(exp, cfg, seed, i), k)
        else:
            with ProcessPoolExecutor(max_workers=n_workers, initializer=_worker_init) as pool:
                queue = list(todo)
                pending = set()
                k = 0
                spent, counted = 0.0, 0

                def more() -> bool:
                    return bool(queue) and len(pending) < 2 * n_workers and (stop_by is None
                                                                             or time.perf_counter() <= stop_by)

                def submit():
                    # one trial per task at first; then chunks of ≈ CHUNK_SECONDS of work (cheap trials
                    # would otherwise spend most of their time in inter-process traffic)
                    size = 1 if counted == 0 else max(1, min(MAX_CHUNK, int(CHUNK_SECONDS * counted / max(spent, 1e-9))))
                    chunk, queue[:] = tuple(queue[:size]), queue[size:]
                    with _sigint_blocked():  # a worker it starts inherits SIGINT blocked (_worker_init)
                        pending.add(pool.submit(_run_chunk, exp.name, config_json, seed, chunk, type(exp).__module__))

                try:
                    while more():
                        submit()
                    while pending:
                        finished, pending = wait(pending, return_when=FIRST_COMPLETED)
                        for f in finished:
                            rows, secs = f.result()
                            spent, counted = spent + secs, counted + len(rows)
                            for row in rows:
                                k += 1
                                finish(Trial.from_json(row), k)
                        while more():
                            submit()
                except BaseException as err:
                    for f in pending:
                        f.cancel()
                    if isinstance(err, KeyboardInterrupt):
                        _stop_workers(pool)
                    raise
    finally:
        if fh is not None:
            fh.close()
    elapsed = time.perf_counter() - t0 + (_prior_elapsed(directory, len(stored)) if directory is not None else 0.0)
    result = ExperimentResult.from_trials(exp.name, done.values(), seed=seed, parameters=parameters, planned=n,
                                          elapsed_s=elapsed, workers=n_workers, config=json.loads(config_json),
                                          resumed=len(stored))
    if directory is not None and not _unchanged(directory, result, len(stored)):
        _write_outputs(directory, result)
    return result


def _stored_result(directory: Path) -> dict | None:
    try:
        return json.loads((directory / "result.json").read_text())
    except (OSError, ValueError):
        return None


def _prior_elapsed(directory: Path, stored: int) -> float:
    """The wall time (s) the stored run in ``directory`` spent on trials this call read back (its ``result.json``'s
    ``elapsed_s`` when it covers no more than them; 0 otherwise)."""
    doc = _stored_result(directory) if stored else None
    try:
        return float(doc["elapsed_s"]) if doc and 0 < int(doc["n"]) <= stored else 0.0
    except (KeyError, TypeError, ValueError):
        return 0.0


def _unchanged(directory: Path, result: ExperimentResult, stored: int) -> bool:
    """Whether this call leaves the run stored in ``directory`` as it is: a look at fewer trials than its
    ``result.json`` covers, all read back (the feeder search reads a verification's first trials back 5 at a time),
    returns its own result without writing it over the longer run's."""
    doc = _stored_result(directory) if stored >= result.n else None
    try:
        return doc is not None and int(doc["n"]) > result.n and (directory / "trials.parquet").exists()
    except (KeyError, TypeError, ValueError):
        return False


def _write_outputs(directory: Path, result: ExperimentResult) -> None:
    """``result.json`` and ``trials.parquet``, each written atomically."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    doc = result.to_json()
    text = json.dumps(doc, indent=2, allow_nan=False) + "\n"
    _atomic_bytes(directory / "result.json", lambda p: p.write_text(text))
    rows = result.rows()
    table = _arrow_table(pa, rows) if rows else pa.table({"index": pa.array([], pa.int64())})
    table = table.replace_schema_metadata({b"throwmap.result": json.dumps(doc, allow_nan=False).encode()})
    _atomic_bytes(directory / "trials.parquet", lambda p: pq.write_table(table, p))



def _arrow_table(pa, rows: list[dict]):
    """The trials as an Arrow table; a value column whose trials disagree on the type (an experiment
    that stores 1 and 2.5, or a number and a text) is written as float, or as text when any entry is text."""
    try:
        return pa.Table.from_pylist(rows)
    except (pa.ArrowInvalid, pa.ArrowTypeError):
        keys = list(dict.fromkeys(k for r in rows for k in r))
        cols = {}
        for k in keys:
            vals = [r.get(k) for r in rows]
            try:
                cols[k] = pa.array(vals)
            except (pa.ArrowInvalid, pa.ArrowTypeError):
                texty = any(isinstance(v, str) for v in vals)
                cols[k] = pa.array([None if v is None else (str(v) if texty else float(v)) for v in vals])
        return pa.table(cols)
