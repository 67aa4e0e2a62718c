"""Design points of a sweep: a grid (every combination) or a seeded random design, each point validated.

Grid: the parameters in file order, the last varying fastest (``itertools.product``); a range gives
``num`` values from ``low`` to ``high`` (``numpy.linspace``, or ``geomspace`` with ``log``).

Random: ``samples`` points drawn from ``numpy.random.default_rng(SeedSequence(seed, spawn_key=(2**32 − 1,)))``
(a stream apart from the experiments' trial streams), parameter by parameter in file order: a list is a
uniform choice of one of its values, a range a uniform (log-uniform with ``log``) draw, floored with
``integer``. The same file gives the same points.

Seeds: with ``common_random_numbers`` (default) every experiment point runs with the sweep's ``seed``
(points then differ only by their parameters, as in :mod:`throwmap.experiments.sensitivity`); else point
``i`` runs with ``SeedSequence(seed, spawn_key=(i,)).generate_state(1)[0]``. A ``throw`` point has no
randomness; a ``limit_set`` point draws its starts with the sweep's seed.
"""

from __future__ import annotations

import itertools
import json
import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown
from .schema import MAX_POINTS, LimitSetConfig, Range, SweepSpec, ThrowConfig

__all__ = ["Design", "make_design", "point_seed", "axis_values", "DESIGN_STREAM"]

DESIGN_STREAM = 2**32 - 1
"""The spawn key of the random design's generator (trial streams use 0, 1, …)."""


@dataclass(frozen=True, slots=True)
class Design:
    """The design of a sweep: ``names`` (the parameter keys, in file order), ``points`` (one tuple of values per
    point, in ``names`` order), ``configs`` (each point's full target config as a JSON-ready dict), ``seeds``
    (each point's seed), ``chunk`` (points per task / Parquet file)."""

    names: tuple
    points: tuple
    configs: tuple
    seeds: tuple
    chunk: int

    @property
    def n_points(self) -> int:
        return len(self.points)

    @property
    def n_chunks(self) -> int:
        return -(-len(self.points) // self.chunk)

    def chunk_points(self, c: int) -> range:
        """The point indices of chunk ``c``."""
        return range(c * self.chunk, min((c + 1) * self.chunk, len(self.points)))


def point_seed(seed: int, index: int) -> int:
    """The seed of design point ``index`` when points do not share the sweep's seed."""
    return int(np.random.SeedSequence(int(seed), spawn_key=(int(index),)).generate_state(1)[0])


def axis_values(key: str, values, kind: str) -> list:
    """A grid axis: a list as given, a :class:`Range` as ``num`` values (ends included)."""
    if not isinstance(values, Range):
        return list(values)
    fn = np.geomspace if values.log else np.linspace
    out = fn(values.low, values.high, values.num)
    if values.integer:
        return sorted({int(math.floor(v)) for v in out})
    return [float(v) for v in out]


def _draw(key: str, values, rng, k: int) -> list:
    if not isinstance(values, Range):
        idx = rng.integers(0, len(values), size=k)
        return [values[i] for i in idx]
    if values.log:
        out = np.exp(rng.uniform(math.log(values.low), math.log(values.high), size=k))
    else:
        out = rng.uniform(values.low, values.high, size=k)
    return [int(math.floor(v)) for v in out] if values.integer else [float(v) for v in out]


def _base_config(spec: SweepSpec):
    """``(config type, base dict)`` of the target: ``spec.config`` validated (errors name ``config.<field>``)."""
    if spec.experiment:
        from ..experiments import get_experiment
        from ..experiments.base import config_of

        exp = get_experiment(spec.experiment)
        base = config_of(exp, dict(spec.config) if spec.config else None)  # errors name "config.<field>"
        return exp.config_type, base.model_dump(mode="json")
    ctype = ThrowConfig if spec.target == "throw" else LimitSetConfig
    try:
        return ctype, ctype.model_validate(spec.config).model_dump(mode="json")
    except ValueError as err:
        first = err.errors(include_url=False)[0]
        loc = ".".join(str(x) for x in first["loc"])
        msg = first["msg"].removeprefix("Value error, ")
        if first["type"] == "extra_forbidden":
            msg = f"unknown field (fields: {', '.join(ctype.model_fields)})"
        raise InvalidStateError(f"config.{loc}" if loc else "config", msg) from None


def _check_refs(cfg: dict, names: tuple, values: tuple, seen: dict) -> None:
    """A ``throw``/``limit_set`` point's ``model`` and ``part`` must exist (as an experiment's config is checked):
    else one line naming the parameter that set it (``parameters.<key>``) or ``config.<field>``."""
    from ..errors import ThrowmapError
    from ..io.config import resolve_part
    from ..models.registry import check_model

    for field, check in (("model", check_model), ("part", resolve_part)):
        value = cfg[field]
        if (field, value) not in seen:
            try:
                check(value)
                seen[(field, value)] = None
            except ThrowmapError as err:
                seen[(field, value)] = getattr(err, "reason", None) or str(err)
        reason = seen[(field, value)]
        if reason is not None:
            key = next((k for k in names if field in k.split("+")), None)
            if key is None:
                raise InvalidStateError(f"config.{field}", reason)
            raise InvalidStateError(f"parameters.{key}", f"value {shown(values[names.index(key)])}: {reason}")


def make_design(spec: SweepSpec) -> Design:
    """Every design point of ``spec``, each one's full config validated by the target's config type (the first
    bad point is one :class:`~throwmap.errors.InvalidStateError` naming ``parameters.<key>`` and the value)."""
    from ..experiments.sensitivity import set_fields

    ctype, base = _base_config(spec)
    names = tuple(spec.parameters)
    if spec.kind == "grid":
        sizes = []  # checked before any axis is built: a huge `num` must not allocate
        for k in names:
            v = spec.parameters[k]
            size = v.num if isinstance(v, Range) else len(v)
            if size > MAX_POINTS:
                raise InvalidStateError(f"parameters.{k}.num" if isinstance(v, Range) else f"parameters.{k}",
                                        f"{size} values (> {MAX_POINTS} grid points): fewer values")
            sizes.append(size)
        if math.prod(sizes) > MAX_POINTS:
            raise InvalidStateError("parameters", f"the grid has {math.prod(sizes)} points (> {MAX_POINTS}): "
                                                  f"fewer values")
        axes = [axis_values(k, spec.parameters[k], "grid") for k in names]
        total = math.prod(len(a) for a in axes)
        if total > MAX_POINTS:
            raise InvalidStateError("parameters", f"the grid has {total} points (> {MAX_POINTS}): fewer values")
        points = list(itertools.product(*axes))
    else:
        rng = np.random.default_rng(np.random.SeedSequence(spec.seed, spawn_key=(DESIGN_STREAM,)))
        cols = [_draw(k, spec.parameters[k], rng, spec.samples) for k in names]
        points = list(zip(*cols))
    configs = []
    cache: dict = {}
    refs: dict = {}
    for values in points:
        data = base
        for key, value in zip(names, values):
            try:
                data = set_fields(data, key.split("+"), value)
            except InvalidStateError as err:
                raise InvalidStateError(f"parameters.{key}", err.reason) from None
        memo = json.dumps(data, sort_keys=True, default=str)
        if memo not in cache:
            try:
                cache[memo] = ctype.model_validate(data).model_dump(mode="json")
            except ValueError as err:
                first = err.errors(include_url=False)[0] if hasattr(err, "errors") else {"msg": str(err), "loc": ()}
                loc = ".".join(str(x) for x in first.get("loc", ()))
                key = next((k for k in names if loc in k.split("+")), None) or next(
                    (k for k in names if any(loc.startswith(p) or p.startswith(loc) for p in k.split("+"))), names[0])
                value = values[names.index(key)]
                raise InvalidStateError(f"parameters.{key}", f"value {shown(value)}: "
                                                             f"{first['msg'].removeprefix('Value error, ')}"
                                                             + (f" ({loc})" if loc and loc != key else "")) from None
            if not spec.experiment:
                _check_refs(cache[memo], names, values, refs)
        configs.append(cache[memo])
    if spec.experiment and not spec.common_random_numbers:
        seeds = tuple(point_seed(spec.seed, i) for i in range(len(points)))
    else:
        seeds = (int(spec.seed),) * len(points)
    return Design(names, tuple(tuple(p) for p in points), tuple(configs), seeds, spec.points_per_chunk)
