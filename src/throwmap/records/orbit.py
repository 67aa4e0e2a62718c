"""The orbit record: repeated throws of one part (paper Sec. III-D, Figs. 5, 7, 16)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .outcome import Status, ThrowOutcome, _system_text

__all__ = ["Orbit"]


@dataclass(frozen=True, slots=True)
class Orbit:
    """An orbit (T^{ω_k} ∘ … ∘ T^{ω_1})(x_0, i_0).

    ``x`` (m) and ``side`` hold the start and the state after each completed throw
    (length ``n_throws + 1``); ``omegas`` the release rates used (rad/s);
    ``outcomes`` each throw's :class:`ThrowOutcome`. ``status`` is OK if every throw
    was, else the escape that ended the orbit early (its outcome is the last one).
    ``poses`` (model ``"engine"`` only, else None): the part's arm-frame pose
    ``(x, y, φ)`` (m, m, rad) at the start and after each completed throw — the pose
    the next throw starts from, tilted where a fixture holds the part so. ``alpha`` (rad) and
    ``fixtures`` are the system the orbit was thrown in, ``part`` and ``arm`` its part and arm (None when
    not known; not compared: two orbits are equal by their states and outcomes).
    """

    x: np.ndarray
    side: np.ndarray
    omegas: np.ndarray
    outcomes: tuple
    status: Status
    model: str
    poses: tuple | None = None
    alpha: float = 0.0
    fixtures: tuple = ()
    part: object = field(default=None, compare=False, repr=False)
    arm: object = field(default=None, compare=False, repr=False)

    def __repr__(self) -> str:
        om = np.asarray(self.omegas, dtype=float)
        if om.size == 0:
            omega = "no throw"
        elif np.all(om == om[0]):
            omega = f"omega={om[0]:g} rad/s"
        else:
            omega = f"omega∈[{om.min():g}, {om.max():g}] rad/s"
        kinds = self.kinds
        jogs, flips, tumbles = kinds.count("jog"), kinds.count("flip"), kinds.count("tumble")
        sides = ", ".join(str(int(s)) for s in np.unique(self.side))
        what = f"{jogs} jogs, {flips} flips" + (f", {tumbles} tumbles over and back" if tumbles else "")
        return (f"Orbit(model={self.model!r}{_system_text(self)}, {omega}, {self.n_throws} throws ({what}), "
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
        from ..system.fixtures import fixture_to_dict

        return {
            "model": self.model,
            "status": self.status.label,
            "x": [float(v) for v in self.x],
            "side": [int(v) for v in self.side],
            "omegas": [float(v) for v in self.omegas],
            "kinds": list(self.kinds),
            "outcomes": [o.to_dict() for o in self.outcomes],
            "alpha": float(self.alpha),
            "fixtures": [fixture_to_dict(f) for f in self.fixtures],
            **({} if self.poses is None else {"poses": [[float(c) for c in p] for p in self.poses]}),
        }

    @classmethod
    def from_dict(cls, d: dict) -> "Orbit":
        """Inverse of :meth:`to_dict`."""
        from ..system.fixtures import fixture_from_dict

        return cls(x=np.array(d["x"], dtype=float), side=np.array(d["side"], dtype=int),
                   omegas=np.array(d["omegas"], dtype=float),
                   outcomes=tuple(ThrowOutcome.from_dict(o) for o in d["outcomes"]),
                   status=Status.from_label(d["status"]), model=d["model"],
                   poses=None if d.get("poses") is None else tuple(tuple(float(c) for c in p) for p in d["poses"]),
                   alpha=float(d.get("alpha", 0.0)), fixtures=tuple(fixture_from_dict(f) for f in d.get("fixtures", ())))

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

        kwargs.setdefault("part", self.part)
        kwargs.setdefault("arm", self.arm)
        return plot_orbit(self, ax=ax, **kwargs)
