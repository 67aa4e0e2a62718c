"""The sweep file: a pydantic schema (``extra="forbid"``) read from TOML, and its content hash.

A sweep file names a target, a design and the parameters it varies::

    kind = "grid"                  # or "random"
    target = "experiment:settle"   # or "throw", "limit_set"
    seed = 0                       # the experiments' seed; the random design's generator
    n = 20                         # trials per design point (experiments only)

    [config]                       # fixed values: the target's config (dotted fields below)
    part = "triangle"

    [parameters]                   # one column each; every combination (grid) or `samples` draws (random)
    mu = [0.4, 0.8]
    h = { low = -0.02, high = 0.0, num = 3 }     # grid: `num` values, ends included
    "noise.omega_rel" = { low = 0.0, high = 0.1 } # random: uniform (log = true: log-uniform)

A parameter is a dotted path into the target's config (``noise.omega_rel``); a key
``"a+b"`` sets several fields to the same value (``"sensor.false_positive+sensor.false_negative"``).
Every design point's config is validated before anything runs (:mod:`throwmap.sweeps.design`),
so a bad value is one line naming the parameter.

The targets ``throw`` and ``limit_set`` take the configs :class:`ThrowConfig` and
:class:`LimitSetConfig` (SI units); an experiment target takes its registered
``config_type``.
"""

from __future__ import annotations

import hashlib
import json
import math
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator

from ..errors import ConfigError, InvalidStateError
from ..io.spec import ArmSpec, Omega, SystemSpec

__all__ = ["Range", "SweepSpec", "ThrowConfig", "LimitSetConfig", "read_sweep", "parse_sweep", "spec_hash",
           "MAX_POINTS", "DEFAULT_CHUNK", "jsonable"]

Finite = Annotated[float, Field(allow_inf_nan=False)]

MAX_POINTS = 1_000_000
"""Most design points a sweep may have."""
DEFAULT_CHUNK = {"throw": 256, "limit_set": 1, "experiment": 1}
"""Design points per task and per Parquet file when ``chunk`` is not given (a throw costs ~0.1 ms, an
experiment point or a limit set seconds)."""


class Range(BaseModel):
    """A numeric range: on a grid ``num`` values from ``low`` to ``high`` (both included; log-spaced with
    ``log = true``); in a random design a uniform draw in [low, high) (log-uniform with ``log``), rounded
    down to an integer with ``integer = true``."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    low: Finite
    high: Finite
    num: int | None = Field(None, ge=1, description="grid: how many values (random: not used)")
    log: bool = False
    integer: bool = False

    @field_validator("high")
    @classmethod
    def _ordered(cls, v, info):
        low = info.data.get("low")
        if low is not None and v < low:
            raise ValueError(f"must be ≥ low ({low:g}), got {v:g}")
        return v


Value = Any
"""A parameter value: a number, a string, a boolean, or a list/table (given as the config field wants it)."""


class SweepSpec(BaseModel):
    """A sweep: ``kind`` (grid or random), ``target``, ``parameters`` (name → a list of values or a
    :class:`Range`), ``samples`` (random: how many points), ``seed`` (≥ 0), ``n`` (experiment: trials per
    point), ``common_random_numbers`` (experiment: every point runs with ``seed`` itself, so that points
    differ only by their parameters; false: point i's seed is spawned from ``seed``), ``chunk`` (points per
    task and per Parquet file), ``trials_per_task`` (experiment: a point's trials split into Dask tasks of this
    many; its row is written when all of them are done), ``retries`` (Dask retries of a task that raised),
    ``config`` (the fixed values of the target's config)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    kind: Literal["grid", "random"]
    target: str
    parameters: dict[str, list[Value] | Range]
    samples: int | None = Field(None, ge=1, le=MAX_POINTS, description="random design: number of points")
    seed: int = Field(0, ge=0)
    n: int | None = Field(None, ge=1, description="experiment targets: trials per design point")
    common_random_numbers: bool = True
    chunk: int | None = Field(None, ge=1, description="design points per task and per Parquet file")
    trials_per_task: int | None = Field(None, ge=1, description="experiment: split a point's n trials into tasks "
                                                                 "of this many (None: one task per chunk)")
    retries: int = Field(2, ge=0, le=100)
    config: dict[str, Any] = Field(default_factory=dict)

    @field_validator("target")
    @classmethod
    def _target(cls, v):
        if v in ("throw", "limit_set"):
            return v
        if v.startswith("experiment:") and v[len("experiment:"):]:
            from ..experiments import experiment_names

            name = v[len("experiment:"):]
            if name not in experiment_names():
                raise ValueError(f"no experiment {name!r} (choose from {', '.join(experiment_names())})")
            return v
        raise ValueError(f"must be 'experiment:NAME', 'throw' or 'limit_set', got {v!r}")

    @field_validator("parameters")
    @classmethod
    def _parameters(cls, v):
        if not v:
            raise ValueError("give at least one parameter")
        for key, values in v.items():
            paths = key.split("+")
            if any(not p or any(not s for s in p.split(".")) for p in paths):
                raise ValueError(f"{key!r}: a parameter is a dotted config field, or fields joined by '+'")
            if isinstance(values, list) and not values:
                raise ValueError(f"{key!r}: give at least one value")
        return v

    @property
    def experiment(self) -> str | None:
        """The experiment's name for an ``experiment:NAME`` target, else None."""
        return self.target.split(":", 1)[1] if self.target.startswith("experiment:") else None

    @property
    def target_kind(self) -> str:
        return "experiment" if self.experiment else self.target

    @property
    def points_per_chunk(self) -> int:
        return self.chunk if self.chunk is not None else DEFAULT_CHUNK[self.target_kind]

    def check(self) -> "SweepSpec":
        """The rules across fields (one :class:`~throwmap.errors.InvalidStateError` naming the field)."""
        if self.kind == "random" and self.samples is None:
            raise InvalidStateError("samples", "a random design needs `samples` (how many points)")
        if self.kind == "grid" and self.samples is not None:
            raise InvalidStateError("samples", "only a random design takes `samples` (a grid is every combination)")
        for key, values in self.parameters.items():
            if isinstance(values, Range):
                if self.kind == "grid" and values.num is None:
                    raise InvalidStateError(f"parameters.{key}.num", "a grid range needs `num` (how many values)")
                if self.kind == "random" and values.num is not None:
                    raise InvalidStateError(f"parameters.{key}.num", "only a grid range takes `num`")
                if values.log and values.low <= 0:
                    raise InvalidStateError(f"parameters.{key}.low", f"a log range needs low > 0, got {values.low:g}")
        if self.experiment:
            if self.n is None:
                raise InvalidStateError("n", "an experiment sweep needs `n` (trials per design point)")
        elif self.n is not None:
            raise InvalidStateError("n", f"only experiment targets take `n` (target is {self.target!r})")
        elif not self.common_random_numbers:
            raise InvalidStateError("common_random_numbers", f"only experiment targets use it (target is {self.target!r})")
        elif self.trials_per_task is not None:
            raise InvalidStateError("trials_per_task", f"only experiment targets have trials (target is {self.target!r})")
        return self


class ThrowConfig(SystemSpec):
    """One throw (target ``throw``): the system (:class:`~throwmap.io.spec.SystemSpec`: ``part``, ``[arm]``
    (``arm.h``, ``arm.length`` — ``inf``: unbounded —, ``arm.mu`` — ``inf``: no slip —, ``arm.g``, ``arm.back``),
    ``alpha`` (rad), ``[wall]`` (``wall.height``, ``wall.mu``)), the rest ``(x, side)`` it starts from, thrown at
    ``omega`` by ``model``."""

    arm: ArmSpec = Field(default_factory=lambda: ArmSpec(h=-0.01, length=0.40, mu=0.8))
    model: str = "rigid_body"
    x: Finite = Field(0.15, description="CM abscissa at rest, m")
    side: int = Field(0, ge=0, description="the side it rests on")
    omega: Omega = Field(5.0, description="release rate, rad/s")


class LimitSetConfig(SystemSpec):
    """One limit set (target ``limit_set``): the map of :class:`ThrowConfig` (without ``x``, ``side``), from
    ``n_starts`` starts per stable side, with the recurrence caps ``transient`` and ``n_record`` and the
    domain's end ``x_max`` (m; None: the arm length, else 0.6 m); ``weight_x``/``weight_y`` (m, the part's frame)
    move the part's first lead weight."""

    arm: ArmSpec = Field(default_factory=lambda: ArmSpec(h=-0.01, length=0.40, mu=0.8))
    model: str = "rigid_body"
    omega: Omega = Field(5.0, description="release rate, rad/s")
    n_starts: int = Field(16, ge=1, description="starts per stable side")
    transient: int = Field(200, ge=0, description="throws discarded")
    n_record: int = Field(400, ge=1, description="throws recorded")
    x_max: Finite | None = Field(None, gt=0, description="domain end, m")
    weight_x: Finite | None = Field(None, description="the part's first lead weight moved to this x, m (part frame)")
    weight_y: Finite | None = Field(None, description="the part's first lead weight moved to this y, m (part frame)")

    def build_part(self):
        """The part, its first lead weight moved to ``weight_x`` / ``weight_y`` where given
        (:func:`throwmap.analysis.continuation.system_at`)."""
        part = super().build_part()
        for name in ("weight_x", "weight_y"):
            value = getattr(self, name)
            if value is not None:
                from ..analysis.continuation import system_at

                part = system_at(part, None, None, name, value, {})[0]
        return part


def parse_sweep(doc: Any, source: str = "sweep") -> SweepSpec:
    """A :class:`SweepSpec` from a parsed document, checked (:meth:`SweepSpec.check`); the first problem is one
    :class:`~throwmap.errors.ConfigError` naming the dotted field."""
    if not isinstance(doc, dict):
        raise ConfigError("sweep", f"{source}: must be a table of keys, got {type(doc).__name__}")
    try:
        spec = SweepSpec.model_validate(doc)
    except ValidationError as err:
        raise _first_error(err, doc) from None
    return spec.check()


def _first_error(err: ValidationError, doc: dict) -> ConfigError:
    errors = sorted(err.errors(include_url=False), key=lambda e: e["type"] != "extra_forbidden")
    e = errors[0]
    if e["loc"][:1] == ("parameters",) and len(e["loc"]) >= 2:
        key = e["loc"][1]
        value = (doc.get("parameters") or {}).get(key)
        mine = [x for x in errors if x["loc"][:2] == ("parameters", key)]
        if isinstance(value, dict):  # it meant a Range: its own error, not the list branch's
            mine = [x for x in mine if len(x["loc"]) > 2 and x["loc"][2] == "Range"] or mine
            mine.sort(key=lambda x: x["type"] != "extra_forbidden")
            e = mine[0]
            rest = [str(x) for x in e["loc"][3:]]
            field = ".".join(["parameters", str(key), *rest])
            if e["type"] == "extra_forbidden":
                return ConfigError(field, f"unknown key (a range has: {', '.join(Range.model_fields)})")
            return ConfigError(field, "required" if e["type"] == "missing" else e["msg"].removeprefix("Value error, "))
        if not isinstance(value, list):
            return ConfigError(f"parameters.{key}", f"must be a list of values or a range table {{low, high, num}}, "
                                                    f"got {type(value).__name__}")
        e = mine[0] if mine else e
    loc = [str(x) for x in e["loc"]]
    field = ".".join(loc) or "sweep"
    if e["type"] == "extra_forbidden":
        return ConfigError(field, f"unknown key (allowed: {', '.join(SweepSpec.model_fields)})")
    if e["type"] == "missing":
        return ConfigError(field, "required")
    return ConfigError(field, e["msg"].removeprefix("Value error, "))


def read_sweep(path) -> tuple[SweepSpec, str]:
    """The sweep in the TOML (or JSON) file ``path`` and the file's text."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise ConfigError("sweep", f"cannot read {str(path)!r}: {err.strerror or err}") from None
    try:
        if path.suffix.lower() == ".json":
            doc = json.loads(text)
        else:
            import tomllib

            doc = tomllib.loads(text)
    except ValueError as err:
        raise ConfigError("sweep", f"{path.name}: not valid {'JSON' if path.suffix.lower() == '.json' else 'TOML'}: "
                                   f"{' '.join(str(err).split())}") from None
    return parse_sweep(doc, path.name), text


def jsonable(obj):
    """``obj`` with non-finite floats as the strings ``"inf"``, ``"-inf"``, ``"nan"`` (TOML has them, strict JSON not)."""
    if isinstance(obj, float) and not math.isfinite(obj):
        return str(obj)
    if isinstance(obj, dict):
        return {k: jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    return obj


def spec_hash(spec: SweepSpec) -> str:
    """SHA-256 of the sweep's canonical content (the validated spec as sorted JSON): comments, key order and
    layout of the file do not change it, nor does ``retries``; any value that changes the results or their
    partitioning does."""
    content = jsonable(spec.model_dump(exclude={"retries"}))
    canon = json.dumps(content, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return hashlib.sha256(canon.encode()).hexdigest()
