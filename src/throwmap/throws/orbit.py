"""Repeated throws: orbits of the throw map (paper Sec. III-D, Figs. 5, 7, 16)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..system.arm import Arm
from ..errors import InvalidStateError, shown
from .outcome import Status, ThrowOutcome
from ..system.part import Part
from .throw import DEFAULT_MODEL, throw

__all__ = ["Orbit", "iterate"]


@dataclass(frozen=True, slots=True)
class Orbit:
    """An orbit (T^{ω_k} ∘ … ∘ T^{ω_1})(x_0, i_0).

    ``x`` (m) and ``side`` hold the start and the state after each completed throw
    (length ``n_throws + 1``); ``omegas`` the release rates used (rad/s);
    ``outcomes`` each throw's :class:`ThrowOutcome`. ``status`` is OK if every throw
    was, else the escape that ended the orbit early (its outcome is the last one).
    """

    x: np.ndarray
    side: np.ndarray
    omegas: np.ndarray
    outcomes: tuple
    status: Status
    model: str

    def __repr__(self) -> str:
        om = np.asarray(self.omegas, dtype=float)
        if om.size == 0:
            omega = "no throw"
        elif np.all(om == om[0]):
            omega = f"omega={om[0]:g} rad/s"
        else:
            omega = f"omega∈[{om.min():g}, {om.max():g}] rad/s"
        kinds = self.kinds
        jogs, flips = kinds.count("jog"), kinds.count("flip")
        sides = ", ".join(str(int(s)) for s in np.unique(self.side))
        return (f"Orbit(model={self.model!r}, {omega}, {self.n_throws} throws ({jogs} jogs, {flips} flips), "
                f"{self.status.label}, sides {sides}, x∈[{np.min(self.x):.4g}, {np.max(self.x):.4g}] m, "
                f"final (x={self.x[-1]:.4g} m, side {int(self.side[-1])}))")

    @property
    def n_throws(self) -> int:
        return len(self.outcomes)

    @property
    def escaped(self) -> bool:
        return self.status != Status.OK

    @property
    def kinds(self) -> tuple[str, ...]:
        return tuple(o.kind for o in self.outcomes)

    def to_dict(self) -> dict:
        return {
            "model": self.model,
            "status": self.status.label,
            "x": [float(v) for v in self.x],
            "side": [int(v) for v in self.side],
            "omegas": [float(v) for v in self.omegas],
            "kinds": list(self.kinds),
            "outcomes": [o.to_dict() for o in self.outcomes],
        }

    @classmethod
    def from_dict(cls, d: dict) -> "Orbit":
        """Inverse of :meth:`to_dict`."""
        return cls(x=np.array(d["x"], dtype=float), side=np.array(d["side"], dtype=int),
                   omegas=np.array(d["omegas"], dtype=float),
                   outcomes=tuple(ThrowOutcome.from_dict(o) for o in d["outcomes"]),
                   status=Status.from_label(d["status"]), model=d["model"])

    def table(self) -> str:
        """One line per throw: ω, the start, the kind of throw and where it ended."""
        lines = [f"orbit, model {self.model}: {self.n_throws} throws, {self.status.label}",
                 f"{'#':>5}{'ω rad/s':>10}{'x m':>12}{'side':>6}  {'kind':<14}{'new x m':>12}{'side':>7}"]
        for i, o in enumerate(self.outcomes):
            lines.append(f"{i + 1:>5}{o.omega:>10.4g}{o.x0:>12.6f}{o.side0:>6d}  {o.kind:<14}{o.x:>12.6f}{o.side:>7d}")
        return "\n".join(lines)

    def plot(self, ax=None, **kwargs):
        """x against throw number, side by colour (like paper Figs. 7, 16)."""
        from ..viz.orbit import plot_orbit

        return plot_orbit(self, ax=ax, **kwargs)


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
        if n is None:
            raise InvalidStateError("n", "the number of throws is required with a single omega")
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < min_n:
            kind = "positive" if min_n >= 1 else "non-negative"
            raise InvalidStateError("n", f"must be a {kind} integer, got {shown(n)}")
        om = np.full(int(n), float(om[0]))
    elif n is not None and n != len(om):
        raise InvalidStateError("n", f"got n = {n} but {len(om)} omegas")
    if om.size < min_n:
        raise InvalidStateError("omegas", "at least one throw is needed")
    return om


def iterate(part: Part, arm: Arm, state, omegas, n: int | None = None, model: str = DEFAULT_MODEL, *, progress=None,
            **throw_kwargs) -> Orbit:
    """Throw repeatedly from ``state = (x, side)``.

    ``omegas`` is one release rate (then ``n`` throws) or a sequence, one per throw
    (then ``n`` may be omitted, or must equal its length). Stops early, with the
    escape's status, if a throw leaves the arm or does not come to rest.
    ``progress``, if given, is called with the number of throws done after each throw.
    """
    try:
        x0, s0 = state
    except (TypeError, ValueError):
        raise InvalidStateError("state", f"must be a pair (x, side), got {shown(state)}") from None
    om = throw_rates(omegas, n)
    xs = [float(x0)]
    ss = [part.check_side(s0)]
    outs = []
    status = Status.OK
    for w in om:
        o: ThrowOutcome = throw(part, arm, xs[-1], ss[-1], float(w), model=model, **throw_kwargs)
        outs.append(o)
        if progress is not None:
            progress(len(outs))
        if o.status != Status.OK:
            status = o.status
            break
        xs.append(o.x)
        ss.append(o.side)
    return Orbit(
        x=np.array(xs),
        side=np.array(ss, dtype=int),
        omegas=om[: len(outs)].copy(),
        outcomes=tuple(outs),
        status=status,
        model=model,
    )
