"""Sensitivity of an experiment's success rate to one parameter (e.g. success against tilt rate, μ, ω noise
and sensor error).

:func:`sensitivity` runs a registered experiment once per value of a config field (or of several fields set to
the same value, e.g. both sensor error rates), every run with the same seed and trial count, and returns one
:class:`SensitivityRow` per value: successes, the Wilson 95 % interval, failures by kind and the run's seed, so
that a curve's points differ only by the parameter (common random numbers: trial *i* of every run draws from the
same stream). Fields are dotted paths into the experiment's pydantic config (``tilt_rate``, ``noise.omega_rel``,
``sensor.false_positive``); each value is validated by the config type, so a bad value is a one-line error naming
the field. With ``out`` every run keeps its trials in ``out/<field>=<value>/`` and a rerun resumes them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import InvalidStateError, shown
from ..io.files import make_directory
from .base import config_of
from .registry import get_experiment

__all__ = ["SensitivityRow", "Sensitivity", "sensitivity", "set_fields"]


@dataclass(frozen=True, slots=True)
class SensitivityRow:
    """One value's run: ``value`` (the fields' SI value), ``n``, ``successes``, ``success_rate``, ``ci95`` (Wilson
    95 %), ``failures`` (counts by kind), ``elapsed_s`` (wall time, s), ``values`` (the run's per-trial value
    summary: median/p90 of throws…)."""

    value: float
    n: int
    successes: int
    success_rate: float
    ci95: tuple
    failures: dict
    elapsed_s: float
    values: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        return {"value": self.value, "n": self.n, "successes": self.successes,
                "success_rate": None if math.isnan(self.success_rate) else self.success_rate,
                "ci95": list(self.ci95), "failures": dict(self.failures), "elapsed_s": self.elapsed_s,
                "values": self.values}


@dataclass(frozen=True, slots=True)
class Sensitivity:
    """Success against one parameter: ``experiment``, ``fields`` (the dotted config paths set to each value),
    ``rows`` (one :class:`SensitivityRow` per value, in the order given), ``seed``, ``parameters`` (the base
    run's full parameter table, SI)."""

    experiment: str
    fields: tuple
    rows: tuple
    seed: int
    parameters: dict

    @property
    def label(self) -> str:
        return " = ".join(self.fields)

    def to_dict(self) -> dict:
        return {"experiment": self.experiment, "fields": list(self.fields), "seed": self.seed,
                "rows": [r.to_dict() for r in self.rows], "parameters": self.parameters}

    def table(self) -> str:
        lines = [f"experiment {self.experiment}, seed {self.seed}: success against {self.label}",
                 f"{'value':>12} {'success':>12} {'Wilson 95 %':>18}  failures"]
        for r in self.rows:
            lo, hi = r.ci95
            fails = ", ".join(f"{k} {c}" for k, c in sorted(r.failures.items(), key=lambda kv: -kv[1]))
            lines.append(f"{r.value:>12.6g} {r.successes:>5}/{r.n:<6} [{100 * lo:5.1f}, {100 * hi:5.1f}] %  {fails}")
        return "\n".join(lines)

    def plot(self, ax=None, *, goal: float | None = None):
        """Success rate against the parameter with the Wilson intervals (:func:`throwmap.viz.sensitivity.plot_sensitivity`)."""
        from ..viz.sensitivity import plot_sensitivity

        return plot_sensitivity(self, ax=ax, goal=goal)


def set_fields(data: dict, paths, value) -> dict:
    """A copy of the nested dict ``data`` with each dotted path in ``paths`` set to ``value``; a path that names
    no field of ``data`` is an :class:`InvalidStateError` naming it."""
    out = _copy(data)
    for path in paths:
        keys = str(path).split(".")
        node = out
        for i, key in enumerate(keys):
            if not isinstance(node, dict) or key not in node:
                known = ", ".join(sorted(node)) if isinstance(node, dict) else "none (not a table)"
                where = ".".join(keys[:i]) or "the config"
                raise InvalidStateError("param", f"{path!r}: {where} has no field {key!r} (fields: {known})")
            if i == len(keys) - 1:
                node[key] = value
            else:
                node = node[key]
    return out


def _copy(d):
    return {k: _copy(v) for k, v in d.items()} if isinstance(d, dict) else d


def sensitivity(experiment, config=None, *, fields, values, n: int, seed: int, workers: int = 0, out=None,
                progress=None, limits=None) -> Sensitivity:
    """Run ``experiment`` (a registered name or object) with each of ``values`` set into every dotted config path
    of ``fields`` (a string or a sequence; e.g. ``("sensor.false_positive", "sensor.false_negative")``), ``n``
    trials each with seed ``seed``; ``progress(done, total)`` is called after every trial of every run (totals
    over all runs). ``out``: a directory; run *k* keeps its trials in ``out/<first field>=<value>``. ``limits``
    (a :class:`~throwmap.budget.Limits`) go to :func:`~throwmap.experiments.runner.run_experiment` and guard each run."""
    from .runner import run_experiment

    exp = get_experiment(experiment)
    base = config_of(exp, config)
    paths = (fields,) if isinstance(fields, str) else tuple(fields)
    if not paths or any(not isinstance(p, str) or not p for p in paths):
        raise InvalidStateError("param", f"give at least one dotted config field, got {shown(fields)}")
    vals = [float(v) for v in values]
    if not vals:
        raise InvalidStateError("values", "give at least one value")
    if any(not math.isfinite(v) for v in vals):
        raise InvalidStateError("values", f"must be finite, got {shown(values)}")
    data = base.model_dump(mode="json")
    configs = []
    for v in vals:
        try:
            configs.append(exp.config_type.model_validate(set_fields(data, paths, v)))
        except InvalidStateError:
            raise
        except ValueError as err:  # pydantic.ValidationError is a ValueError
            first = err.errors()[0] if hasattr(err, "errors") else {"msg": str(err), "loc": ()}
            loc = ".".join(str(x) for x in first.get("loc", ())) or paths[0]
            raise InvalidStateError(loc, f"value {v:g}: {first['msg']}") from None
    total = n * len(vals)
    rows, done0 = [], 0
    if out is not None:
        make_directory(out, "out")  # only it (a missing folder above it is refused); each run makes its own in it
    for v, cfg in zip(vals, configs):
        sub = None if out is None else Path(out) / f"{paths[0]}={v:g}"

        def update(done, _total, _base=done0):
            if progress is not None:
                progress(_base + done, total)

        res = run_experiment(exp, cfg, n=n, seed=seed, workers=workers, out=sub, progress=update, limits=limits)
        done0 += n
        rows.append(SensitivityRow(v, res.n, res.successes, res.success_rate, tuple(res.ci95), dict(res.failures),
                                   res.elapsed_s, res.value_summary()))
    return Sensitivity(exp.name, paths, tuple(rows), int(seed), exp.parameters(base))
