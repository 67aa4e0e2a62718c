"""Validation studies as experiments: declared as a config, run case by case on the experiment runner (STYLE §13).

A study (``validate``, ``validate-fixtures``, ``validate-recoil``) is an :class:`~throwmap.experiments.Experiment`
whose trial ``i`` throws case ``i`` of the study through every model it compares and stores each answer (x, side,
status and, where the study needs them, the model's record and message) as the trial's values. The cases are drawn
once per config from the config's ``seed`` through :func:`throwmap.rng.as_generator` (or its children,
:func:`throwmap.experiments.base.trial_generator`), so that the same seed gives the same cases whatever the number of
workers, and a run interrupted and resumed from its ``out`` directory gives the result of one uninterrupted run.

:func:`run_study` hands the study to :func:`throwmap.experiments.run_experiment` (parallel, resumable, atomic result
files) with the run's seed = the config's; the study then builds its report from the trials. A trial succeeds when
no throw of its case was refused (failure ``refused:<who>``, see :data:`~throwmap.studies.agreement.REFUSED`): the
runner's success rate is the share of cases every model answered; the study's own figures are agreements
(:mod:`throwmap.studies.agreement`).
"""

from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np
from pydantic import BaseModel, ConfigDict

from ..budget import Limits
from ..errors import InvalidStateError
from ..io.schema import Friction
from ..experiments.base import Trial, seed_of
from .agreement import REFUSED

__all__ = ["StudyConfig", "StudyRun", "Mu", "stored", "answer_values", "answers", "case_trial", "cached_cases", "run_study"]


Mu = Friction
"""An arm friction in a study config: the one μ of every config (:data:`throwmap.io.schema.Friction`)."""


class StudyConfig(BaseModel):
    """What every study config shares: unknown keys refused, frozen, ``seed`` of the cases (int ≥ 0)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    seed: int = 0


def stored(v) -> float | str:
    """A float as a trial value that survives the runner's JSON lines exactly: ±inf as the text ``"inf"`` /
    ``"-inf"`` (the runner writes non-finite numbers as null, read back as nan; a record field such as the
    friction an impact needs may be infinite); finite numbers and nan as they are. :func:`float` reads it back."""
    v = float(v)
    return ("inf" if v > 0 else "-inf") if math.isinf(v) else v


def answer_values(key: str, x, side, status, record=None, message: str | None = None) -> dict:
    """One model's answer to one throw as trial values: ``key.x`` (m), ``key.side``, ``key.status`` (code), and
    optionally ``key.r0`` … (the record's fields, :mod:`throwmap.kernels.codes`) and ``key.message``; floats
    through :func:`stored` (±inf kept)."""
    out = {f"{key}.x": stored(x), f"{key}.side": int(side), f"{key}.status": int(status)}
    if record is not None:
        out.update({f"{key}.r{j}": stored(v) for j, v in enumerate(np.asarray(record, dtype=float))})
    if message is not None:
        out[f"{key}.message"] = str(message)
    return out


def answers(trials, key: str, *, record: int = 0) -> dict:
    """The answers stored under ``key`` over ``trials`` (in their order) as arrays ``x``, ``side``, ``status`` and,
    with ``record`` = the record's length, ``recs`` (rows × ``record``)."""
    vals = [t.values for t in trials]
    out = {"x": np.array([float(v[f"{key}.x"]) for v in vals], dtype=float),
           "side": np.array([v[f"{key}.side"] for v in vals], dtype=np.int64),
           "status": np.array([v[f"{key}.status"] for v in vals], dtype=np.int64)}
    if record:
        out["recs"] = np.array([[float(v[f"{key}.r{j}"]) for j in range(record)] for v in vals], dtype=float).reshape(
            len(vals), record)
    return out


def case_trial(index: int, rng, values: dict, statuses) -> Trial:
    """The trial of one case: ``values`` as its values; failed (``refused:<who>``) when one of ``statuses``
    (``(who, status code)`` pairs, in order) is a refusal, else a success."""
    for who, st in statuses:
        if int(st) in REFUSED:
            return Trial(index, seed_of(rng), False, f"refused:{who}", values)
    return Trial(index, seed_of(rng), True, None, values)


_CACHE: OrderedDict = OrderedDict()
_CACHE_SIZE = 4


def cached_cases(config: BaseModel, make):
    """``make(config)`` (a study's cases), computed once per config (by its JSON) in this process."""
    key = (type(config).__qualname__, config.model_dump_json())
    if key not in _CACHE:
        _CACHE[key] = make(config)
        while len(_CACHE) > _CACHE_SIZE:
            _CACHE.popitem(last=False)
    return _CACHE[key]


@dataclass(frozen=True)
class StudyRun:
    """How a study runs on the experiment runner: ``workers`` processes (0: one per core), ``out`` (a directory
    keeping the cases' trials; None: memory only), ``resume`` (reuse the trials stored in ``out``), ``stop_after``
    (run at most this many new cases, then stop: an interruption on purpose), ``progress(done, total)`` (cases),
    ``limits`` (the work guard, :class:`~throwmap.budget.Limits`)."""

    workers: int = 1
    out: object = None
    resume: bool = True
    stop_after: int | None = None
    progress: object = None
    limits: Limits | None = None


def run_study(experiment, config, n: int, run: StudyRun = StudyRun()):
    """Trials ``0 … n−1`` of the study ``experiment`` on :func:`throwmap.experiments.run_experiment`, seeded with
    ``config.seed``, run as ``run`` says. Returns the runner's :class:`~throwmap.experiments.ExperimentResult` (its
    ``trials`` sorted by index). An incomplete run (``stop_after``, or an interruption) raises
    :class:`~throwmap.errors.InvalidStateError` on ``out`` after keeping its trials."""
    from ..experiments.runner import run_experiment

    res = run_experiment(experiment, config, n=n, seed=config.seed, workers=run.workers, out=run.out,
                         resume=run.resume, progress=run.progress, limits=run.limits, stop_after=run.stop_after)
    if not res.complete:
        where = f" in {str(run.out)!r}: the same call resumes from them" if run.out is not None else ""
        raise InvalidStateError("out", f"{experiment.name}: {res.n} of {res.planned} cases ran{where}")
    return res
