"""The model interface: what a throw model is, what it supports, and its options.

A model (paper Sec. III-D: a throw map T^ω) turns resting configurations
``(x, side)`` of a part on a :class:`~throwmap.system.system.System` into new
ones. Every model is one module of :mod:`throwmap.models` holding

* a frozen options dataclass (its tolerances, caps, settings) — the keywords
  ``throw(..., **options)`` accepts for that model and no others;
* a :class:`Features` value: which parts of a System and which extras it supports;
* ``throw_one`` / ``throw_batch`` (kernel calls on validated, flat inputs) and,
  where it can, ``trajectory`` (the sampled motion of one throw);
* where its state between throws is more than a rest ``(x, side)`` (the engine keeps every part's
  pose), ``session(parts, system, states, options)``: a :class:`ThrowSession`. The analytic models
  get the dispatcher's session on ``(x, side)`` (:mod:`throwmap.throws.session`).

It registers itself once with :func:`throwmap.models.registry.register`. Callers never branch on a
model's name: they ask its :class:`Features`.
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import numpy as np

from ..errors import InvalidStateError, shown

__all__ = ["Features", "ThrowModel", "ThrowSession", "BatchArrays", "NoOptions", "build_options"]


@dataclass(frozen=True, slots=True)
class Features:
    """What a model supports beyond a part on the paper's plain arm.

    ``fixtures`` (walls, cavities), ``tilt`` (an arm rest angle α ≠ 0),
    ``realisation`` (finite arm motions instead of the impulse: its option ``realisation``),
    ``trajectory`` (sampled motion for animation), ``friction`` (uses ``Arm.mu``),
    ``parallel`` (batches run on all cores). Sessions (:class:`ThrowSession`): ``pose`` (a part keeps
    its whole pose between throws — held tilted by a fixture it stays so; without it a session keeps
    the rest ``(x, side)``), ``parts`` (the most parts one scene may hold; 0: any number), ``moves``
    (the arm may turn to a new rest angle between throws, :class:`~throwmap.system.motion.TiltTo`),
    ``ensemble`` (many independent scenes thrown together in one batch call).
    """

    fixtures: bool = False
    tilt: bool = False
    realisation: bool = False
    trajectory: bool = False
    friction: bool = False
    parallel: bool = True
    pose: bool = False
    parts: int = 1
    moves: bool = False
    ensemble: bool = True

    def supported(self) -> tuple[str, ...]:
        return tuple(f.name for f in dataclasses.fields(self) if getattr(self, f.name))


@dataclass(frozen=True, slots=True)
class BatchArrays:
    """Flat outputs of a model's batch call: new x (m), side, status code and records (n, NREC)."""

    x: np.ndarray
    side: np.ndarray
    status: np.ndarray
    records: np.ndarray


@dataclass(frozen=True, slots=True)
class NoOptions:
    """A model without options."""


@runtime_checkable
class ThrowModel(Protocol):
    """One throw model. Inputs are validated by :mod:`throwmap.throws.throw` before any call.

    ``throw_one(part, system, x, side, omega, options) -> (x', side', status, record)``;
    ``throw_batch(part, system, x, side, omega, valid, options, progress) -> BatchArrays``
    on flat arrays (``valid`` marks admissible starts; the rest get ``INVALID_START``);
    ``trajectory(part, system, x, side, omega, options, dt) -> (ThrowOutcome, Trajectory)``
    where ``features.trajectory``. Optional: ``assumptions(records, mu, status) -> str``, what
    the model assumes and how often that failed over a batch (the validation table's last column).
    """

    name: str
    summary: str
    options_type: type
    features: Features

    def throw_one(self, part, system, x: float, side: int, omega: float, options) -> tuple: ...

    def throw_batch(self, part, system, x, side, omega, valid, options, progress=None) -> BatchArrays: ...

    def trajectory(self, part, system, x: float, side: int, omega: float, options, dt: float) -> Any: ...


@runtime_checkable
class ThrowSession(Protocol):
    """A scene thrown again and again, keeping its state (STYLE §14; like Gymnasium's ``Env.step``).

    Made once by :func:`throwmap.throws.session.open_session`, which validates the model, the
    :class:`~throwmap.system.system.System`, the options and the start; each step then only throws.
    ``parts``, ``system`` (its α follows the arm's moves), ``options`` (the model's, validated),
    ``features`` (the model's :class:`Features`), ``states`` (one
    :class:`~throwmap.records.session.PartState` per part), ``status`` (``ok`` while every part rests
    on the arm; the session has ended otherwise), ``n_throws``.

    ``throw(omega, motion=None, *, options=None, record=False)``: one throw at release rate ``omega``
    (rad/s) — the paper's impulse, or the arm's ``motion`` where the model follows one
    (``features.realisation``); ``options`` replaces the session's options for this throw (a value of
    the model's options type); ``record`` keeps the step's motion where the model can
    (``features.trajectory``): True, or the sample interval in s (the engines sample at their own). ``move(motion)``: the arm turns without a throw (``features.moves``).
    Both return a :class:`~throwmap.records.session.SessionStep`; after a step that did not end at
    rest the session has ended and refuses further steps.
    """

    parts: tuple
    system: Any
    options: Any
    features: Features
    states: tuple
    status: Any
    n_throws: int

    def throw(self, omega: float, motion=None, *, options=None, record: bool = False) -> Any: ...

    def move(self, motion, *, options=None, record: bool = False) -> Any: ...


@functools.lru_cache(maxsize=None)
def _default_options(typ: type):
    """The defaults of an options dataclass, made once (they are frozen)."""
    return typ()


CALL_KEYWORDS = ("n_starts", "starts", "x_max", "rng", "caps", "limits", "progress", "fixtures", "alpha", "options",
                 "horizon", "n_grid", "omega", "model", "seed", "dt", "max_throws")
"""Keywords of the analysis and throw functions that pass the rest to the model: a slip in one of them arrives here
as an unknown model option, and the error suggests the nearest (``n_start`` → ``n_starts``)."""


def _same(a, b) -> bool:
    """Whether an option given twice (in ``options`` and as a keyword) agrees."""
    try:
        return bool(a == b)
    except Exception:  # e.g. arrays: compare by identity
        return a is b


def build_options(model: ThrowModel, options=None, overrides: dict | None = None):
    """The model's options value: ``options`` (an instance of its options type, or None
    for the defaults) with keyword ``overrides`` applied. Unknown keywords are refused
    with the field named and the model's keywords listed; a keyword that contradicts
    the same field of ``options`` is refused (the two would silently disagree)."""
    typ = model.options_type
    if options is None and not overrides:
        return _default_options(typ)
    if options is None:
        opts = typ()
    elif isinstance(options, typ):
        opts = options
    else:
        raise InvalidStateError("options", f"model {model.name!r} takes {typ.__name__}, got {type(options).__name__}")
    if overrides:
        names = {f.name for f in dataclasses.fields(typ)}
        for key in overrides:
            if key not in names:
                known = ", ".join(sorted(names)) or "none"
                near = difflib.get_close_matches(key, sorted(names) + list(CALL_KEYWORDS), n=1)
                hint = f"; did you mean {near[0]!r}?" if near else ""
                raise InvalidStateError(key, f"unknown keyword for model {model.name!r} (its options: {known}){hint}")
        if options is not None:
            for key, val in overrides.items():
                given = getattr(options, key)
                if not _same(given, val):
                    raise InvalidStateError(key, f"given twice with different values: options={typ.__name__}(…, {key}={shown(given)}) "
                                                 f"and the keyword {key}={shown(val)}; give it once")
        opts = dataclasses.replace(opts, **overrides)
    return opts
