"""What one task of a sweep computes: the rows of a chunk of design points, for each kind of target.

:func:`run_chunk` is the function a Dask worker runs. It receives only JSON-ready values (the target, the
points' configs, seeds and indices, ``n``) and returns one dict per point; the client writes them
(:mod:`throwmap.sweeps.store`). Each row's result columns by target:

* ``experiment:NAME`` — ``n``, ``successes``, ``success_rate``, ``ci95_low``, ``ci95_high`` (Wilson 95 %),
  ``failures`` (JSON: count by kind), ``values`` (JSON: the per-trial value summary), via
  :func:`throwmap.experiments.runner.run_experiment` (``workers=1``: the worker is the process);
* ``throw`` — ``landing_x`` (m), ``landing_side``, ``status`` (label), via :func:`throwmap.throw_batch`
  (``on_invalid="status"``: an inadmissible start is a row with status ``invalid_start``); ``landing_x`` and
  ``landing_side`` are null unless the status is ``ok`` (the part came to rest on the arm);
* ``limit_set`` — ``kind``, ``n_attractors``, ``unique``, ``escapes`` (JSON: share by fate),
  ``attractors`` (JSON: :meth:`Attractor.to_dict` each), via :func:`throwmap.limit_set`.

Every row also has ``elapsed_s`` (wall time of the point, s; a throw chunk's time shared equally) and
``version`` (``throwmap.__version__`` in the worker) and ``error`` (None, or ``"field: reason"`` when the library refused the point: the row is kept, so a
restart does not try it again).
"""

from __future__ import annotations

import functools
import json
import math
import time
import warnings
from dataclasses import dataclass

from ..budget import Limits
from ..version import __version__
from ..errors import ThrowmapError

__all__ = ["run_chunk", "run_trials", "summarise_trials", "seconds_per_point", "PointSummary", "RESULT_COLUMNS"]

RESULT_COLUMNS = {
    "experiment": {"n": "int64", "successes": "int64", "success_rate": "float64", "ci95_low": "float64",
                   "ci95_high": "float64", "failures": "string", "values": "string"},
    "throw": {"landing_x": "float64", "landing_side": "int64", "status": "string"},
    "limit_set": {"kind": "string", "n_attractors": "int64", "unique": "bool", "escapes": "string",
                  "attractors": "string"},
}
"""The result columns of each target kind and their Arrow types."""


def _json(obj) -> str:
    return json.dumps(obj, sort_keys=True, allow_nan=False, default=lambda v: None)


def _clean(v):
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, dict):
        return {k: _clean(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_clean(x) for x in v]
    return v


@functools.lru_cache(maxsize=64)
def _part(name: str):
    from ..io.config import resolve_part

    return resolve_part(name).part


def _spec(cfg: dict, kind):
    """A design point's config as its :class:`~throwmap.io.spec.SystemSpec` (validated once per distinct map)."""
    return kind.model_validate(cfg)


def _error_row(err: Exception) -> dict:
    return {"error": str(err) if isinstance(err, ThrowmapError) else f"{type(err).__name__}: {err}"}


def _experiment_point(name: str, cfg: dict, seed: int, n: int) -> dict:
    from ..experiments.runner import run_experiment

    res = run_experiment(name, cfg, n=n, seed=seed, workers=1, limits=Limits(force=True))
    return {"n": res.n, "successes": res.successes,
            "success_rate": None if math.isnan(res.success_rate) else res.success_rate,
            "ci95_low": float(res.ci95[0]), "ci95_high": float(res.ci95[1]),
            "failures": _json(dict(res.failures)), "values": _json(_clean(res.value_summary()))}


def run_trials(name: str, cfg: dict, seed: int, start: int, stop: int) -> tuple:
    """Trials ``start … stop−1`` of experiment ``name`` with ``cfg`` and run seed ``seed`` (each trial's generator
    is ``trial_generator(seed, i)`` (:mod:`throwmap.experiments.base`), as the runner's: a point split into
    several tasks gives the trials one task would). Returns ``(trials as JSON objects, seconds, the worker's
    throwmap.__version__, error)``: ``error`` is None, or ``"field: reason"`` where the library refused."""
    from ..experiments.base import config_of, trial_generator
    from ..experiments.registry import get_experiment

    t0 = time.perf_counter()
    try:
        exp = get_experiment(name)
        config = config_of(exp, cfg)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            trials = [exp.trial(config, i, trial_generator(seed, i)).to_json() for i in range(start, stop)]
    except ThrowmapError as err:
        return [], time.perf_counter() - t0, __version__, str(err)
    return trials, time.perf_counter() - t0, __version__, None


@dataclass(frozen=True, slots=True)
class PointSummary:
    """One design point of an experiment sweep, summarised from its trials (:func:`summarise_trials`): ``n`` trials,
    ``successes``, ``success_rate`` (None when n = 0) with its Wilson 95 % interval ``ci95_low``/``ci95_high``,
    ``failures`` and ``values`` (JSON text: counts by kind, the per-trial value summary), ``error`` (None, or
    ``"field: reason"`` where the library refused the point; then only ``elapsed_s`` and ``version`` are set),
    ``elapsed_s`` (s), ``version`` (the worker's throwmap)."""

    elapsed_s: float
    version: str
    error: str | None = None
    n: int = 0
    successes: int = 0
    success_rate: float | None = None
    ci95_low: float = 0.0
    ci95_high: float = 1.0
    failures: str = "{}"
    values: str = "{}"

    def to_dict(self) -> dict:
        """The point's row of the sweep's table (its result columns, ``error``, ``elapsed_s``, ``version``); a
        refused point's row has ``error``, ``elapsed_s`` and ``version`` only."""
        if self.error is not None:
            return {"error": self.error, "elapsed_s": self.elapsed_s, "version": self.version}
        return {"n": self.n, "successes": self.successes, "success_rate": self.success_rate,
                "ci95_low": self.ci95_low, "ci95_high": self.ci95_high, "failures": self.failures,
                "values": self.values, "error": None, "elapsed_s": self.elapsed_s, "version": self.version}

    def table(self) -> str:
        """One line: successes of n with the Wilson interval, then the failures by kind (or the refusal)."""
        if self.error is not None:
            return f"refused: {self.error}"
        rate = "n/a" if self.success_rate is None else f"{100 * self.success_rate:.1f} %"
        fails = ", ".join(f"{k} {v}" for k, v in json.loads(self.failures).items()) or "none"
        return (f"{self.successes}/{self.n} succeeded = {rate}, Wilson 95 % [{100 * self.ci95_low:.1f}, "
                f"{100 * self.ci95_high:.1f}] %; failures: {fails}")

    def plot(self, ax=None):
        """The outcomes with the success rate's interval (:func:`throwmap.viz.sweep.plot_point_summary`)."""
        from ..viz.sweep import plot_point_summary

        return plot_point_summary(self, ax=ax)


def summarise_trials(name: str, cfg: dict, seed: int, n: int, blocks: list) -> PointSummary:
    """A point's summary (:class:`PointSummary`; its ``to_dict()`` is the point's row) from the ``blocks``
    (:func:`run_trials` results) that together hold its trials 0 … n−1."""
    from ..experiments.base import Trial
    from ..experiments.runner import ExperimentResult

    errors = [b[3] for b in blocks if b[3] is not None]
    if errors:
        return PointSummary(sum(b[1] for b in blocks), blocks[0][2], errors[0])
    trials = [Trial.from_json(t) for b in blocks for t in b[0]]
    if sorted(t.index for t in trials) != list(range(n)):
        raise ValueError(f"the tasks of a point returned trials {sorted(t.index for t in trials)[:5]}…, not 0…{n - 1}")
    res = ExperimentResult.from_trials(name, trials, seed=seed, parameters={}, planned=n,
                                       elapsed_s=sum(b[1] for b in blocks), workers=len(blocks))
    return PointSummary(res.elapsed_s, blocks[0][2], None, res.n, res.successes,
                        None if math.isnan(res.success_rate) else res.success_rate, float(res.ci95[0]),
                        float(res.ci95[1]), _json(dict(res.failures)), _json(_clean(res.value_summary())))


def _limit_set_point(cfg: dict, seed: int) -> dict:
    from ..analysis.limitset import limit_set
    from .schema import LimitSetConfig

    c = _spec(cfg, LimitSetConfig)
    part = _part(c.part) if c.weight_x is None and c.weight_y is None else c.build_part()
    ls = limit_set(part, c.build_arm(), c.omega, c.model, n_starts=c.n_starts, rng=seed, x_max=c.x_max,
                   transient=c.transient, n_record=c.n_record, limits=Limits(force=True),
                   **({"fixtures": c.fixtures()} if c.wall is not None else {}), **({"alpha": c.alpha} if c.alpha else {}))
    return {"kind": ls.kind, "n_attractors": len(ls.attractors), "unique": bool(ls.unique),
            "escapes": _json(dict(ls.escapes)), "attractors": _json(_clean([a.to_dict() for a in ls.attractors]))}


def _throw_rows(configs: list) -> list:
    """Rows of a chunk of throws: one :func:`throw_batch` per distinct map (all but x, side, ω)."""
    import numpy as np

    from ..records.outcome import Status
    from ..throws.throw import throw_batch
    from .schema import ThrowConfig

    rows: list = [None] * len(configs)
    groups: dict = {}
    for i, cfg in enumerate(configs):
        key = json.dumps({k: v for k, v in cfg.items() if k not in ("x", "side", "omega")}, sort_keys=True)
        groups.setdefault(key, []).append(i)
    for key, idx in groups.items():
        t0 = time.perf_counter()
        try:
            c = _spec(configs[idx[0]], ThrowConfig)
            out = throw_batch(_part(c.part), c.build_arm(), np.array([configs[i]["x"] for i in idx], dtype=float),
                              np.array([configs[i]["side"] for i in idx], dtype=np.int64),
                              np.array([configs[i]["omega"] for i in idx], dtype=float), c.model,
                              on_invalid="status", fixtures=c.fixtures(), alpha=c.alpha)
        except ThrowmapError as err:
            dt = (time.perf_counter() - t0) / len(idx)
            for i in idx:
                rows[i] = {**_error_row(err), "elapsed_s": dt}
            continue
        dt = (time.perf_counter() - t0) / len(idx)
        for j, i in enumerate(idx):
            st = int(out.status[j])
            landed = st == Status.OK and math.isfinite(out.x[j])  # else the batch echoes the start: not a landing
            rows[i] = {"landing_x": float(out.x[j]) if landed else None,
                       "landing_side": int(out.side[j]) if landed else None, "status": Status(st).label,
                       "error": None, "elapsed_s": dt}
    return rows


def run_chunk(target: str, configs: list, seeds: list, n: int | None) -> list:
    """The result columns of each point of a chunk (``target``: ``"throw"``, ``"limit_set"`` or
    ``"experiment:NAME"``); a point the library refuses gets its ``error`` instead."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # regime warnings: a worker has no one to tell
        if target == "throw":
            return [{**r, "version": __version__} for r in _throw_rows(configs)]
        rows = []
        for cfg, seed in zip(configs, seeds):
            t0 = time.perf_counter()
            try:
                if target == "limit_set":
                    row = _limit_set_point(cfg, seed)
                else:
                    row = _experiment_point(target.split(":", 1)[1], cfg, seed, n)
                row["error"] = None
            except ThrowmapError as err:
                row = _error_row(err)
            row["elapsed_s"] = time.perf_counter() - t0
            row["version"] = __version__
            rows.append(row)
        return rows


SAMPLE_THROWS = 16
"""Throw points timed by :func:`seconds_per_point` (after one untimed throw that warms the kernels)."""
SAMPLE_TRIALS = 2
"""Trials of an experiment point timed by :func:`seconds_per_point` (after one untimed trial)."""


def seconds_per_point(target: str, configs: list, seeds: list, n: int | None) -> float | None:
    """Seconds one design point of ``target`` takes in this process, measured now on a sample of the first of
    ``configs`` (with their ``seeds``; ``n``: an experiment's trials per point), each sample run once untimed first
    (kernels compiled, caches filled): ``throw`` the first :data:`SAMPLE_THROWS` points; ``limit_set`` the first
    point with one start per side, times its ``n_starts``; an experiment :data:`SAMPLE_TRIALS` of the first point's
    trials, times ``n``. None where the library refuses the sample (that point gets its ``error`` row when it runs)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the run itself reports nothing of a worker's warnings either
        if target == "throw":
            sample = list(configs[:SAMPLE_THROWS])
            run_chunk(target, sample[:1], list(seeds[:1]), None)
            t0 = time.perf_counter()
            rows = run_chunk(target, sample, list(seeds[:len(sample)]), None)
            dt = time.perf_counter() - t0
            return None if all(r.get("error") for r in rows) else dt / len(sample)
        cfg, seed = configs[0], seeds[0]
        if target == "limit_set":
            one = {**cfg, "n_starts": 1}
            try:
                _limit_set_point(one, seed)
                t0 = time.perf_counter()
                _limit_set_point(one, seed)
            except ThrowmapError:
                return None
            return (time.perf_counter() - t0) * int(cfg["n_starts"])
        name = target.split(":", 1)[1]
        k = max(1, min(SAMPLE_TRIALS, int(n)))
        if run_trials(name, cfg, seed, 0, 1)[3] is not None:
            return None
        t0 = time.perf_counter()
        run_trials(name, cfg, seed, 0, k)
        return (time.perf_counter() - t0) / k * int(n)
