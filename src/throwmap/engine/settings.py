"""Settings of the pymunk engine backend: time step, solver, settling and safety checks."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from ..errors import InvalidStateError, shown

__all__ = ["EngineSettings", "Friction", "NO_SLIP_MU"]

NO_SLIP_MU = 1.0e4
"""Shape friction given to pymunk for μ = ∞ (pymunk needs a finite number); each contact's friction
is then set per solve by :mod:`throwmap.engine.pymunk.friction` (capped where Chipmunk's solver needs it)."""


@dataclass(frozen=True, slots=True)
class EngineSettings:
    """Numerical settings of :func:`throwmap.engine.simulate` (SI units).

    dt : fixed step while any body is in or near contact, s. The default 0.125 ms
        is the converged value of ``tests/test_engine.py::test_step_convergence``
        (0.5 ms lands hard throws up to 0.5 mm too far out).
    exact_flight : advance bodies that are clear of everything by the exact
        ballistic solution instead of stepping (pymunk's symplectic Euler drifts
        by g·t·dt/2 in free flight); switched to stepping within ``flight_margin``
        (m) of any contact.
    coarse_dt, impact_window : while every part is in contact, the arm is still and
        no contact has begun for ``impact_window`` (s), smooth pivoting, rocking
        and resting advance by ``coarse_dt`` (s); impacts and their aftermath use ``dt``.
    iterations : pymunk solver iterations per step.
    collision_slop : allowed overlap, m (pymunk's default 0.1 is for pixels).
    settle_speed, settle_spin, settle_hold : settled when every part moves slower
        than ``settle_speed`` (m/s) and spins slower than ``settle_spin`` (rad/s)
        for ``settle_hold`` (s), after the arm has stopped.
    t_max : give up after this much simulated time (status ``timeout``), s.
    penetration_tol : a vertex deeper than this inside the arm or a fixture (m)
        means pymunk lost the contact: status ``penetration``, result refused.
    retries : a run that lost a contact is repeated this many times, each with
        half the previous step (0: report the failure at once).
    arm_thickness : thickness of the arm's solid below its surface, m.
    default_length : when ``Arm.length`` is None, the simulated arm reaches this
        far (m) beyond the bound on the parts' flight; a part that reaches its end
        reruns with 4×, 16×, 64× this margin, and beyond that is refused as
        ``unresolved`` (:mod:`throwmap.engine.reach`).
    record_dt : sampling interval of recorded trajectories, s.
    verify, agreement : rerun hard runs (deep penetration, repeated side changes,
        energy gain, timeout) at half the step and refuse them (status
        ``unconverged``) unless both agree: same status, side and x within
        ``agreement`` (m); see :mod:`throwmap.engine.pymunk.verify`.
    refine : where the half-step rerun disagrees, halve the step again up to this many times: the run whose result
        the next halving confirms (the same agreement) stands, verified at that step; none confirmed is refused as
        before (0: refuse at the first disagreement).
    """

    dt: float = 1.25e-4
    exact_flight: bool = True
    flight_margin: float = 0.004
    coarse_dt: float = 5e-4
    impact_window: float = 5e-3
    iterations: int = 30
    collision_slop: float = 1e-5
    settle_speed: float = 1e-3
    settle_spin: float = 1e-2
    settle_hold: float = 0.05
    t_max: float = 10.0
    penetration_tol: float = 1e-3
    retries: int = 2
    arm_thickness: float = 0.02
    default_length: float = 2.0
    record_dt: float = 1.0 / 240.0
    verify: bool = True
    agreement: float = 5e-4
    refine: int = 0

    def __post_init__(self):
        for f in fields(self):
            v = getattr(self, f.name)
            key = f"settings.{f.name}"
            if f.name in ("exact_flight", "verify"):
                if not isinstance(v, bool):
                    raise InvalidStateError(key, f"must be true or false, got {shown(v)}")
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InvalidStateError(key, f"must be a finite number, got {shown(v)}")
            if f.name in ("retries", "refine"):
                if int(v) != v or v < 0:
                    raise InvalidStateError(key, f"must be an integer ≥ 0, got {shown(v)}")
                continue
            if f.name == "iterations":
                if int(v) != v or v < 1:
                    raise InvalidStateError(key, f"must be a positive integer, got {shown(v)}")
                continue
            if v <= 0:
                raise InvalidStateError(key, f"must be > 0, got {shown(v)}")
        if self.dt > 2e-3:
            raise InvalidStateError("settings.dt", f"{self.dt:g} s is too coarse for impacts (≤ 2 ms; 0.125 ms converged)")
        if self.coarse_dt < self.dt:
            raise InvalidStateError("settings.coarse_dt", f"must be ≥ dt ({self.dt:g} s), got {self.coarse_dt:g}")
        if self.settle_hold < 4 * self.dt:
            raise InvalidStateError("settings.settle_hold", f"must cover at least 4 steps ({4 * self.dt:g} s), got {self.settle_hold:g}")
        if self.t_max < self.settle_hold:
            raise InvalidStateError("settings.t_max", f"must exceed settle_hold ({self.settle_hold:g} s), got {self.t_max:g}")


@dataclass(frozen=True, slots=True)
class Friction:
    """Coulomb friction per pair of bodies (pymunk multiplies shape values, so each pair is set here).

    ``arm_part`` ``None`` takes the arm's μ (:attr:`throwmap.Arm.mu`);
    ``wall_part`` ``None`` takes the wall's own μ or else the arm's;
    ``part_part`` between parts. ``inf`` means no slip.
    """

    arm_part: float | None = None
    wall_part: float | None = None
    part_part: float = 0.5

    def __post_init__(self):
        for name in ("arm_part", "wall_part", "part_part"):
            v = getattr(self, name)
            if v is None and name != "part_part":
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float)) or math.isnan(v) or v < 0:
                raise InvalidStateError(f"friction.{name}", f"must be a number ≥ 0 (inf: no slip), got {shown(v)}")
            object.__setattr__(self, name, float(v))


def engine_mu(mu: float) -> float:
    """μ as pymunk can take it."""
    return NO_SLIP_MU if math.isinf(mu) else mu
