"""Repeated throws: orbits of the throw map (paper Sec. III-D, Figs. 5, 7, 16)."""

from __future__ import annotations


import numpy as np

import time

from ..budget import Limits, check_count, guard_work
from ..system.arm import Arm
from ..errors import InvalidStateError, shown
from ..records.orbit import Orbit
from ..system.part import Part
from .throw import DEFAULT_MODEL

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

    def __init__(self, what: str, field: str, n_planned: int, bytes_per_throw: float, limits: Limits | None,
                 hint: str):
        self.args = (what, field, n_planned, bytes_per_throw, Limits.of(limits))
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


def iterate(part: Part, arm: Arm, state, omegas, n: int | None = None, model: str = DEFAULT_MODEL, *, progress=None,
            limits: Limits | None = None, **throw_kwargs) -> Orbit:
    """Throw repeatedly from ``state = (x, side)`` (paper Sec. III-D): an orbit of the throw map.

    ``omegas`` is one release rate (then ``n`` throws) or a sequence, one per throw
    (then ``n`` may be omitted, or must equal its length). Stops early, with the
    escape's status, if a throw leaves the arm or does not come to rest.
    ``progress``, if given, is called with the number of throws done after each throw.

    The throws run on one throwing session (:func:`~throwmap.throws.session.open_session`): model,
    system, options and start are validated once. A model that keeps poses (``features.pose``, the
    engine) starts each throw from the pose the previous one left the part in (not from a flat rest at
    the reported ``(x, side)``), so a part held tilted by a fixture stays so, and :attr:`Orbit.poses`
    lists those poses; its ``state`` may also be an engine :class:`~throwmap.engine.Scene` (or a
    :class:`~throwmap.experiments.drop.DropResult`) holding this one part, which brings its fixtures and α.
    A model that follows arm motions (``features.realisation``) may take ``realisation`` as a callable
    ``omega -> realisation`` (one realisation per throw).

    Work guard (:mod:`throwmap.budget`, ``limits``): the orbit's memory (:data:`BYTES_PER_THROW` per
    throw) is checked before any throw, its time from the first throws (:data:`TIMED_THROWS`, timed now);
    above the limits it is refused with one line on ``n``, unless ``limits.force``.
    """
    from .session import open_session

    kw = dict(throw_kwargs)
    real = kw.get("realisation")
    factory = real if callable(real) and not hasattr(real, "angle") else None
    if factory is not None:
        kw["realisation"] = None
    gd = ThrowGuard("iterate", "n", planned_throws(omegas, n), BYTES_PER_THROW, limits, hint="fewer throws (-n)")
    om = throw_rates(omegas, n)
    if not hasattr(getattr(state, "scene", state), "placements"):
        try:
            _, _ = state
        except (TypeError, ValueError):
            raise InvalidStateError("state", f"must be a pair (x, side), got {shown(state)}") from None
    session = open_session(part, arm, state, model, **kw)
    s0 = session.states[0]
    poses = [s0.pose] if session.features.pose else None
    xs, ss = [s0.x], [s0.side]
    outs = []
    for w in om:
        step = session.throw(float(w), factory(float(w)) if factory is not None else None)
        outs.append(step.outcome)
        gd.tick()
        if progress is not None:
            progress(len(outs))
        if not step.ok:
            break
        s = step.states[0]
        xs.append(s.x)
        ss.append(s.side)
        if poses is not None:
            poses.append(s.pose)
    system = session.system
    return Orbit(x=np.array(xs), side=np.array(ss, dtype=int), omegas=om[: len(outs)].copy(), outcomes=tuple(outs),
                 status=session.status, model=session.model.name if hasattr(session.model, "name") else str(model),
                 poses=None if poses is None else tuple(poses), alpha=float(system.alpha),
                 fixtures=tuple(system.fixtures), part=part, arm=system.arm)
