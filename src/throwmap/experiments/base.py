"""The experiment contract (STYLE §13, "experiments are declared, then run").

An experiment is a named, registered object with a pydantic config type (SI units,
``extra="forbid"``; ``config_type()`` is the built-in example) and one method,
:meth:`Experiment.trial`, that runs trial ``index`` with its own
:class:`numpy.random.Generator` and returns a :class:`Trial`. The runner
(:func:`throwmap.experiments.run_experiment`) spawns the seeds, runs the trials on all
cores, keeps them on disk, resumes an interrupted run and summarises them with Wilson
95 % intervals.

Seeds: trial ``i`` of a run with seed ``S`` uses
``np.random.default_rng(np.random.SeedSequence(S).spawn(n)[i])``. Its
:attr:`Trial.seed` is the integer ``SeedSequence(S).spawn(n)[i].generate_state(1)[0]``
(uint32): a label that identifies the trial's stream; :func:`trial_generator`
re-creates the generator itself from ``(S, i)`` (``spawn`` of the i-th child is
independent of ``n``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np

from ..errors import InvalidStateError, shown

__all__ = ["Trial", "Experiment", "FAILURE_KINDS", "trial_seed_sequence", "trial_generator", "trial_seed", "seed_of", "config_of", "read_config"]

FAILURE_KINDS = ("wrong_side", "ejected", "not_captured", "off_end", "tilted",
                 "refused:unconverged", "refused:timeout", "refused:drop")
"""Failure kinds used by the built-in experiments (an experiment may use others: any
non-empty string). ``refused:…`` kinds mark trials whose simulation did not give an
answer (the engine did not settle, a drop could not be placed…): they count as failures
in the success rate, never silently dropped."""

_SCALARS = (bool, int, float, str, np.bool_, np.integer, np.floating, np.str_)


@dataclass(frozen=True, slots=True)
class Trial:
    """One trial's result.

    Attributes
    ----------
    index : int
        0…n−1, the trial's place in the run.
    seed : int
        The trial's stream label, ``SeedSequence(run seed).spawn(n)[index].generate_state(1)[0]``
        (see the module docstring; :func:`trial_generator` re-creates the generator).
    success : bool
        Whether the trial met the experiment's goal.
    failure : str or None
        The failure kind when not ``success`` (``"wrong_side"``, ``"refused:timeout"``…);
        None when ``success``.
    values : dict
        Extra per-trial scalars (float/int/str/bool; SI units, named with the unit where it
        is not obvious) that become columns of the trials table.
    """

    index: int
    seed: int
    success: bool
    failure: str | None = None
    values: dict = field(default_factory=dict)

    def __post_init__(self):
        if isinstance(self.index, bool) or not isinstance(self.index, (int, np.integer)) or self.index < 0:
            raise InvalidStateError("trial.index", f"must be a non-negative integer, got {shown(self.index)}")
        object.__setattr__(self, "index", int(self.index))
        object.__setattr__(self, "seed", int(self.seed))
        object.__setattr__(self, "success", bool(self.success))
        if self.success and self.failure is not None:
            raise InvalidStateError("trial.failure", f"must be None for a successful trial, got {shown(self.failure)}")
        if not self.success and not (isinstance(self.failure, str) and self.failure):
            raise InvalidStateError("trial.failure", f"a failed trial needs a failure kind (non-empty string), got {shown(self.failure)}")
        clean = {}
        for key, value in dict(self.values).items():
            if not isinstance(key, str) or not key or key in _RESERVED:
                raise InvalidStateError("trial.values", f"keys must be non-empty strings other than {', '.join(_RESERVED)}, got {shown(key)}")
            if value is not None and not isinstance(value, _SCALARS):
                raise InvalidStateError(f"trial.values[{key!r}]", f"must be a float, int, str, bool or None, got {shown(value)}")
            clean[key] = value.item() if isinstance(value, np.generic) else value
        object.__setattr__(self, "values", clean)

    def to_json(self) -> dict:
        """The trial as one JSON object (NaN/inf floats written as null)."""
        return {"index": self.index, "seed": self.seed, "success": self.success, "failure": self.failure,
                "values": {k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                           for k, v in self.values.items()}}

    @classmethod
    def from_json(cls, data: dict) -> "Trial":
        """The inverse of :meth:`to_json` (null values come back as NaN)."""
        values = {k: (math.nan if v is None else v) for k, v in data.get("values", {}).items()}
        return cls(int(data["index"]), int(data["seed"]), bool(data["success"]), data.get("failure"), values)


_RESERVED = ("index", "seed", "success", "failure")


@runtime_checkable
class Experiment(Protocol):
    """What the runner needs from an experiment.

    ``trial`` must be a pure function of ``(config, index, rng)``: no global state, no
    wall-clock dependence, so that the same seed gives the same trials on any number of
    workers. ``parameters(config)`` returns every parameter (SI) for the result header,
    JSON-serialisable.
    """

    name: str
    summary: str
    config_type: type

    def trial(self, config, index: int, rng: np.random.Generator) -> Trial: ...

    def parameters(self, config) -> dict: ...


def trial_seed_sequence(seed: int, index: int) -> np.random.SeedSequence:
    """The :class:`~numpy.random.SeedSequence` of trial ``index`` of a run seeded ``seed``.

    Equal to ``SeedSequence(seed).spawn(n)[index]`` for every ``n > index``.
    """
    return np.random.SeedSequence(int(seed), spawn_key=(int(index),))


def trial_generator(seed: int, index: int) -> np.random.Generator:
    """The generator trial ``index`` of a run seeded ``seed`` receives."""
    return np.random.default_rng(trial_seed_sequence(seed, index))


def trial_seed(seed: int, index: int) -> int:
    """The integer stored in :attr:`Trial.seed` for trial ``index`` of a run seeded ``seed``."""
    return int(trial_seed_sequence(seed, index).generate_state(1)[0])


def seed_of(rng: np.random.Generator) -> int:
    """The :attr:`Trial.seed` for the trial whose generator is ``rng`` (as the runner passes it):
    ``rng``'s SeedSequence's ``generate_state(1)[0]``. Experiments write ``Trial(index, seed_of(rng), …)``."""
    ss = getattr(rng.bit_generator, "seed_seq", None) or rng.bit_generator._seed_seq
    return int(ss.generate_state(1)[0])


def config_of(experiment: Any, config=None, source=None):
    """``config`` validated as ``experiment.config_type`` (None → the built-in example: the
    experiment's ``example()`` where it has one, else the config type's defaults; a dict is
    validated, its first problem raised as one :class:`~throwmap.errors.ConfigError` naming the
    dotted field, ``config.<key>…``, as part files are (:mod:`throwmap.io.config`))."""
    from pydantic import BaseModel, ValidationError

    ctype = experiment.config_type
    if config is None:
        example = getattr(experiment, "example", None)
        return example() if example is not None else ctype()
    if isinstance(config, ctype):
        return config
    if not isinstance(config, dict):
        raise InvalidStateError("config", f"must be a {ctype.__name__} or a dict, got {type(config).__name__}")
    from ..io.schema import refuse_coerced_numbers

    refuse_coerced_numbers(ctype, config)
    try:
        return ctype.model_validate(config)
    except ValidationError as err:
        from ..errors import ConfigError
        from ..io.config import _config_error

        e = _config_error(err, "config", source)
        first = sorted(err.errors(include_url=False), key=lambda x: x["type"] != "extra_forbidden")[0]
        if first["type"] == "extra_forbidden":  # name the allowed keys of the table the typo is in
            model = ctype
            for item in first["loc"][:-1]:
                sub = model.model_fields.get(item) if isinstance(item, str) else None
                inner = _model_in(getattr(sub, "annotation", None), BaseModel)
                if inner is not None:
                    model = inner
            import difflib

            key = str(first["loc"][-1])
            close = difflib.get_close_matches(key, list(model.model_fields), n=1)
            hint = f"did you mean {close[0]!r}? " if close else ""
            e = ConfigError(e.field, f"unknown key {key!r} ({table_hint(key, model) or hint}allowed: "
                                     f"{', '.join(model.model_fields)})")
        raise e from None


def _model_in(annotation, base):
    """The pydantic model class an annotation holds: itself, or the one inside ``X | None``, ``Optional[X]``,
    ``Annotated[X, …]``; None when there is none."""
    import typing

    if isinstance(annotation, type) and issubclass(annotation, base):
        return annotation
    for arg in typing.get_args(annotation):
        found = _model_in(arg, base)
        if found is not None:
            return found
    return None


def table_hint(key: str, model) -> str:
    """``"an arm key goes in the [arm] table (arm.length); "`` where ``key`` belongs to a table ``model`` has
    (an arm, a wall), else ``""``."""
    from ..io.spec import ArmSpec, WallSpec

    fields = getattr(model, "model_fields", {})
    for table, spec in (("arm", ArmSpec), ("wall", WallSpec)):
        if table in fields and key in spec.model_fields:
            return f"{'an' if table == 'arm' else 'a'} {table} key goes in the [{table}] table ({table}.{key}); "
        if table in fields and key.startswith(table + "_") and key[len(table) + 1:] in spec.model_fields:
            return f"the {table}'s keys go in the [{table}] table ({table}.{key[len(table) + 1:]}); "
    return ""


def read_config(experiment: Any, path):
    """An experiment's config from a ``.toml`` or ``.json`` file (the document is the config's table
    of keys), validated by its ``config_type``; errors as :func:`config_of` (``field="file"`` when the
    file cannot be read or parsed). A ``part`` that names a ``.toml``/``.json`` file not found from the
    working directory is looked for next to the config file."""
    from pathlib import Path

    from ..io.config import _read_document

    path = Path(path)
    doc = _read_document(path)
    part = doc.get("part") if isinstance(doc, dict) else None
    if isinstance(part, str) and part.lower().endswith((".toml", ".json")):
        p = Path(part)
        if not p.is_absolute() and not p.exists() and (path.parent / p).exists():
            doc = dict(doc, part=str(path.parent / p))  # a part file named relative to the config file
    return config_of(experiment, doc, source=path)
