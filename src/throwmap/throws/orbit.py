"""Repeated throws: orbits of the throw map (paper Sec. III-D, Figs. 5, 7, 16)."""

from __future__ import annotations

import dataclasses

import numpy as np

import time

from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, check_count, check_limits, guard_work
from ..system.arm import Arm
from ..errors import InvalidStateError, shown
from ..records.outcome import Status, ThrowOutcome
from ..records.orbit import Orbit
from ..system.part import Part
from .throw import DEFAULT_MODEL, _invalid_outcome, throw

__all__ = ["Orbit", "iterate", "BYTES_PER_THROW", "TIMED_THROWS", "ThrowGuard", "planned_throws", "throw_rates"]

BYTES_PER_THROW = 1200
"""Memory an orbit holds per throw, bytes: its :class:`ThrowOutcome` (≈ 1 kB measured) and the x, side, ω entries."""
TIMED_THROWS = 8
"""Throws of an orbit timed (after :data:`WARM_THROWS` that warm the kernels) to estimate the whole orbit's time."""
WARM_THROWS = 2
"""Throws at the start of a run not counted in its time estimate (first calls compile or warm caches)."""


def throw_rates(omegas, n=None, *, min_n: int = 0) -> np.ndarray:
    """The release rate of each throw: ``omegas`` as given, or one ω repeated ``n`` times.

    Raises :class:`InvalidStateError` (fields ``omegas``/``n``) for a non-1-D
    sequence, a missing or bad ``n`` with a single ω, an ``n`` that contradicts the
    sequence, or fewer than ``min_n`` throws.
    """
    om = np.atleast_1d(np.asarray(omegas, dtype=float))
    if om.ndim != 1:
        raise InvalidStateError("omegas", "must be a number or a 1-D sequence")
    if np.ndim(omegas) == 0:
        om = np.full(planned_throws(omegas, n, min_n=min_n), float(om[0]))
    elif n is not None and n != len(om):
        raise InvalidStateError("n", f"got n = {n} but {len(om)} omegas")
    if om.size < min_n:
        raise InvalidStateError("omegas", "at least one throw is needed")
    return om


def planned_throws(omegas, n, *, min_n: int = 0) -> int:
    """How many throws ``(omegas, n)`` ask for, without building the rates.

    With a single ω, ``n`` must be an integer from ``min_n`` to 2^63 − 1 (else
    :class:`InvalidStateError` on ``n``); with a sequence, its length.
    """
    if np.ndim(omegas) != 0:
        return int(np.size(omegas))
    if n is None:
        raise InvalidStateError("n", "the number of throws is required with a single omega")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < min_n:
        kind = "positive" if min_n >= 1 else "non-negative"
        raise InvalidStateError("n", f"must be a {kind} integer, got {shown(n)}")
    return check_count("n", n, minimum=min_n)


class ThrowGuard:
    """The work guard of a run of ``n_planned`` throws (:mod:`throwmap.budget`), field ``field``.

    Construction checks the memory (``bytes_per_throw`` each) at once; call
    :meth:`tick` after each throw: after :data:`TIMED_THROWS` timed throws (the first
    :data:`WARM_THROWS`, which warm the kernels, are not counted) it checks the time of the whole run.
    """

    def __init__(self, what: str, field: str, n_planned: int, bytes_per_throw: float, max_memory, max_seconds,
                 force, hint: str):
        self.args = (what, field, n_planned, bytes_per_throw, *check_limits(max_memory, max_seconds, force))
        self.hint = hint
        self.done = 0
        self.t0 = None
        guard_work(*self.args, hint=hint, unit="throws")

    def tick(self) -> None:
        self.done += 1
        if self.done == WARM_THROWS:
            self.t0 = time.perf_counter()
        elif self.done == WARM_THROWS + TIMED_THROWS and self.args[2] > self.done:
            per = (time.perf_counter() - self.t0) / TIMED_THROWS
            guard_work(*self.args, throws_per_config=1.0, timer=lambda: per, hint=self.hint, unit="throws")


def _restart_reason(part: Part, arm: Arm, x: float, side: int, omega: float) -> str:
    """Why the rest ``(x, side)`` of the last throw is not a start of the next one (``""`` if it is): a part at
    rest leaning on a wall reports its CM's x and the nearest side, which may lie past the last flat start."""
    from ..system.starts import check_start

    try:
        check_start(part, arm, x, side, omega)
    except InvalidStateError as err:
        return f"the last throw's rest is not a start of the map ({err.reason}): the part leans, e.g. on a wall"
    return ""


def iterate(part: Part, arm: Arm, state, omegas, n: int | None = None, model: str = DEFAULT_MODEL, *, progress=None,
            max_memory: float = DEFAULT_MAX_MEMORY, max_seconds: float = DEFAULT_MAX_SECONDS, force: bool = False,
            **throw_kwargs) -> Orbit:
    """Throw repeatedly from ``state = (x, side)``.

    ``omegas`` is one release rate (then ``n`` throws) or a sequence, one per throw
    (then ``n`` may be omitted, or must equal its length). Stops early, with the
    escape's status, if a throw leaves the arm or does not come to rest.
    ``progress``, if given, is called with the number of throws done after each throw.

    Work guard (:mod:`throwmap.budget`): the orbit's memory (:data:`BYTES_PER_THROW`
    per throw) is checked before any throw, its time from the first throws
    (:data:`TIMED_THROWS`, timed now); above ``max_memory`` (bytes) or ``max_seconds``
    (s) it is refused with one line on ``n``, unless ``force``.

    Model ``"engine"``: ``state`` may also be an engine :class:`~throwmap.engine.Scene` (or a
    :class:`~throwmap.experiments.drop.DropResult`, whose ``scene`` is used) holding this one part, e.g.
    a part dropped onto the arm: the first throw starts from its pose, with its fixtures and α.
    Each throw starts from the pose the previous one left the part in
    (not from a flat rest at the reported ``(x, side)``), so a part held tilted by a
    fixture stays so; :attr:`Orbit.poses` lists those poses. Its ``realisation`` keyword
    may also be a callable ``omega -> realisation`` (one realisation per throw).
    """
    scene = getattr(state, "scene", state)  # a DropResult carries its engine scene
    if hasattr(scene, "placements"):  # an engine Scene: the part already at rest in the engine
        if not _is_engine(model):
            raise InvalidStateError("state", f"an engine Scene is a start for model 'engine' only (model is {model!r})")
        x0 = s0 = None
    else:
        scene = None
        try:
            x0, s0 = state
        except (TypeError, ValueError):
            raise InvalidStateError("state", f"must be a pair (x, side), got {shown(state)}") from None
    gd = ThrowGuard("iterate", "n", planned_throws(omegas, n), BYTES_PER_THROW, max_memory, max_seconds, force,
                      hint="fewer throws (-n)")
    om = throw_rates(omegas, n)
    if _is_engine(model):
        return _iterate_engine(part, arm, x0, s0, om, model, gd, progress, throw_kwargs, scene)
    xs = [float(x0)]
    ss = [part.check_side(s0)]
    outs = []
    status = Status.OK
    for i, w in enumerate(om):
        if i > 0:  # a rest the next throw cannot start from (leaning on a wall past the last start): the orbit ends
            reason = _restart_reason(part, arm, xs[-1], ss[-1], float(w))
            if reason:
                outs.append(_invalid_outcome(part, xs[-1], ss[-1], float(w), model, reason))
                status = Status.INVALID_START
                break
        o: ThrowOutcome = throw(part, arm, xs[-1], ss[-1], float(w), model=model, **throw_kwargs)
        outs.append(o)
        gd.tick()
        if progress is not None:
            progress(len(outs))
        if o.status != Status.OK:
            status = o.status
            break
        xs.append(o.x)
        ss.append(o.side)
    first = outs[0] if outs else None
    return Orbit(
        x=np.array(xs),
        side=np.array(ss, dtype=int),
        omegas=om[: len(outs)].copy(),
        outcomes=tuple(outs),
        status=status,
        model=model,
        alpha=first.alpha if first is not None else float(throw_kwargs.get("alpha", 0.0) or 0.0),
        fixtures=first.fixtures if first is not None else tuple(throw_kwargs.get("fixtures", ()) or ()),
    )


def _is_engine(model) -> bool:
    """Whether ``model`` is the pymunk engine (the model whose runs hand their end scene to the next throw)."""
    from ..models import get_model

    return getattr(get_model(model), "name", None) == "engine"


def _iterate_engine(part, arm, x0, s0, om, model, gd, progress, throw_kwargs, start_scene=None) -> Orbit:
    """:func:`iterate` for model ``"engine"``: a chain of engine runs, each starting from the scene the
    previous one ended in (:meth:`throwmap.engine.EngineRun.next_scene`), so a part keeps its settled
    pose — tilted against a wall or in a cavity — from throw to throw. Only the first start is the
    flat rest at ``(x0, s0)``. ``realisation`` may be a realisation (every throw), None (the impulse at
    each throw's ω) or a callable ``omega -> realisation`` (e.g. :meth:`throwmap.experiments.noise.Noise.realisation_for`).
    """
    from ..engine import Friction, ImpulseThrow, Placement, Scene, simulate
    from ..system.arm import warn_if_outside_regime
    from ..system.starts import check_start
    from .throw import prepare

    kw = dict(throw_kwargs)
    fixtures, alpha, options = kw.pop("fixtures", ()), kw.pop("alpha", 0.0), kw.pop("options", None)
    real = kw.get("realisation")
    factory = real if callable(real) and not hasattr(real, "angle") else None
    if factory is not None:
        kw["realisation"] = None
    if start_scene is not None:
        from ..system.pose import state_from_pose

        if len(start_scene.placements) != 1 or start_scene.placements[0].part != part or start_scene.arm != arm:
            raise InvalidStateError("state", "the engine Scene must hold this one part on this arm")
        if fixtures not in ((), None) or alpha != 0.0:
            raise InvalidStateError("fixtures", "a start Scene brings its own fixtures and alpha: do not pass them")
        fixtures, alpha = start_scene.fixtures, start_scene.alpha
        if kw.get("friction") is None:
            kw["friction"] = start_scene.friction
    _, system, opts = prepare(model, arm, fixtures, alpha, options, kw)
    warn_if_outside_regime(part, arm)
    if start_scene is None:
        x, k, _ = check_start(part, arm, x0, s0, float(om[0]) if om.size else 0.0)
        friction = Friction() if opts.friction is None else opts.friction
        scene = Scene(arm, (Placement(part, x=x, side=k),), system.fixtures, system.alpha, friction)
    else:
        scene = start_scene
        x, k, _ = state_from_pose(part, scene.placements[0].arm_pose(arm.h))
    xs, ss = [float(x)], [int(k)]
    poses = [tuple(float(c) for c in scene.placements[0].arm_pose(arm.h))]
    outs = []
    status = Status.OK
    for w in om:
        w = float(w)
        if w < 0 or not np.isfinite(w):
            raise InvalidStateError("omegas", f"must be finite and ≥ 0, got {shown(w)}")
        realisation = factory(w) if factory is not None else (ImpulseThrow(w) if opts.realisation is None
                                                               else opts.realisation)
        run = simulate(scene, realisation, opts.settings)
        o = run.outcome(0, x0=xs[-1], side0=ss[-1], omega=w)
        if system.alpha != 0.0 or system.fixtures:
            o = dataclasses.replace(o, alpha=float(system.alpha), fixtures=tuple(system.fixtures))
        outs.append(o)
        gd.tick()
        if progress is not None:
            progress(len(outs))
        if o.status != Status.OK:
            status = o.status
            break
        xs.append(o.x)
        ss.append(o.side)
        poses.append(tuple(float(c) for c in run.poses[0]))
        scene = run.next_scene()
    return Orbit(x=np.array(xs), side=np.array(ss, dtype=int), omegas=om[: len(outs)].copy(), outcomes=tuple(outs),
                 status=status, model="engine", poses=tuple(poses), alpha=float(system.alpha),
                 fixtures=tuple(system.fixtures))
