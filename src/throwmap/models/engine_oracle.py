"""The exact model as the engine's oracle: a throw the engine and "rigid_body" see differently is rerun finer.

Why
---
pymunk's result can depend on its step where nothing marks the run as hard (no deep vertex, no repeated
flips, no energy gain: :mod:`throwmap.engine.pymunk.verify`), so no half-step rerun happens and a wrong
``ok`` is reported. Measured on random convex parts with lead weights, μ ∈ {0.6, 1, 2, ∞}: see the
``engine oracle`` paragraph of docs/explanation/models.md. One part thrown from rest on a bare or tilted arm, with at most an end
wall and the friction of the arm and wall, is a throw the exact model "rigid_body" takes too, at a small
fraction of the engine's cost.

What
----
After the engine's run, the same throw by "rigid_body" with the engines' velocity-level impact law
(``impact_law="velocity"``; its default Routh law differs by 1–30 mm at μ ≤ 0.6, a law choice). Where both
ended (ok, off_end or behind_joint) and they disagree — another status, another side, or rests more than
:data:`ORACLE_TOL` apart — the engine reruns at a half and a quarter of its step (and an eighth where those two
disagree). Where the first run, the half and the quarter step agree (``EngineSettings.agreement``), the first run
stands: the step has converged and the difference is between the models. Otherwise the coarsest rerun that the
next finer one confirms is returned (its message says so), else the throw is refused as ``unconverged``. (A
half step alone is not enough: on random parts a throw whose default and half step agree 3 mm from the quarter
step was seen.) ``EngineSettings.verify = False``
turns the oracle off with the half-step check.
"""

from __future__ import annotations

from dataclasses import replace

from ..errors import InvalidStateError
from ..kernels import codes as C
from ..records.outcome import Status

__all__ = ["ORACLE_TOL", "oracle_options", "disagrees", "settle_disagreement"]

ORACLE_TOL = 2e-3
"""m. Rests of the engine and of "rigid_body" (velocity law) further apart than this call for a finer rerun."""

ENDED = (C.OK, C.OFF_END, C.BEHIND_JOINT)
"""Statuses both models can give for the same throw; any other (a refusal, a timeout) is not compared."""


def oracle_options(system, o):
    """The "rigid_body" options that throw what the engine options ``o`` throw on ``system``, or None where the
    oracle does not apply: verify off, the pair friction set by hand, a Cavity, a wall on an unbounded arm, a
    realisation the exact model does not take (a tilt, a moving arm with fixtures), or a moving arm at all: rigid_body
    integrates the arm's motion phase in Python (about 0.65 s a throw, 40 times the engine's run), no cheap check."""
    from .registry import get_model

    settings = o.settings
    if settings is not None and not settings.verify:
        return None
    if o.realisation is not None and not getattr(o.realisation, "impulsive", True):
        return None
    if o.friction is not None and (o.friction.arm_part is not None or o.friction.wall_part is not None):
        return None
    rb = get_model("rigid_body")
    try:
        rb.check_system(system)
        opts = rb.options_type(impact_law="velocity", realisation=o.realisation)
        from .rigid_body import realisation_for

        realisation_for(opts, 1.0, system)
    except InvalidStateError:
        return None
    return rb, opts


def disagrees(a, b, tol: float) -> bool:
    """Whether two results ``(x, side, status)`` differ: status, or side and x (beyond ``tol``, m) of rests."""
    (xa, ka, sa), (xb, kb, sb) = a, b
    if int(sa) != int(sb):
        return True
    return int(sa) == C.OK and (int(ka) != int(kb) or not abs(float(xa) - float(xb)) <= tol)


def settle_disagreement(first, rerun, settings):
    """The engine's answer after the oracle disagreed with ``first`` = ``(x, side, status, run)``.

    ``rerun(dt, coarse_dt)`` runs the same throw at another step and returns ``(x, side, status, run)`` (``run``:
    whatever the caller keeps of it). The throw is rerun at 1/2 and 1/4 of the step, and at 1/8 where those two
    disagree; the answer is the coarsest run that a finer one confirms (two successive steps agree within
    ``EngineSettings.agreement``). Returns ``(x, side, status, run, message)``: the first result and ``""`` (it,
    the half and the quarter step agree: the step has converged and the difference is between the models), the
    half- or quarter-step result with a message naming the runs, or the first with status UNCONVERGED (no two
    successive steps agree)."""
    from ..engine.settings import EngineSettings

    s = EngineSettings() if settings is None else settings
    tol = s.agreement
    runs = [(s.dt, first)]
    for f in (2, 4):
        runs.append((s.dt / f, rerun(s.dt / f, max(s.coarse_dt / f, s.dt / f))))
    if not disagrees(runs[1][1][:3], runs[2][1][:3], tol) and not disagrees(first[:3], runs[1][1][:3], tol):
        return (*first, "")
    if disagrees(runs[1][1][:3], runs[2][1][:3], tol):
        runs.append((s.dt / 8, rerun(s.dt / 8, max(s.coarse_dt / 8, s.dt / 8))))

    def show(r, dt):
        return f"{Status(int(r[2])).label} side {int(r[1])} x = {float(r[0]):.5f} m at dt = {dt:g} s"

    seen = ", ".join(show(r, dt) for dt, r in runs)
    for (dt, a), (_, b) in zip(runs[1:], runs[2:]):
        if not disagrees(a[:3], b[:3], tol):
            return (*a, f"the exact model disagreed with the engine at dt = {s.dt:g} s; rerun: {seen}; "
                        f"the dt = {dt:g} s result stands")
    return (first[0], first[1], C.UNCONVERGED, first[3],
            f"the exact model disagreed and finer steps do not converge: {seen}; result refused")


def engine_settings_at(settings, dt: float, coarse_dt: float):
    """``settings`` (None: the defaults) at step ``dt`` and ``coarse_dt`` (s), the half-step check off (the
    oracle compares the reruns itself)."""
    from ..engine.settings import EngineSettings

    s = EngineSettings() if settings is None else settings
    return replace(s, dt=dt, coarse_dt=coarse_dt, verify=False)
