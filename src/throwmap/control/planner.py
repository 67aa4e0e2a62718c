"""Open-loop throw plans from any start to (x_f, side_f) (paper Sec. IV: Lemma 4.1, Lemma 4.2, Prop. 4.3).

The draft's constructive proof, made a planner:

* **Reachability (Prop. 4.3).** (x_f, side_f) is reachable with a high rate ω when the limit set
  S(ω) visits side_f with its lower bound l_{side_f} < x_f, and x_f is a rest on the arm (its
  support inside the arm, below the arm's end). :func:`reachability` computes S(ω) for each rate
  offered (:func:`throwmap.limit_set`, on the stated x range) and says, per rate, why not: the
  limit set never visits side_f, every orbit escapes (the canonical triangle at the draft's
  5.6 rad/s: all leave behind the joint), or l_{side_f} ≥ x_f.
* **Go round the limit set (Lemma 4.1).** Throw at the high rate until the part rests on side_f
  short of x_f.
* **Jog (Lemma 4.2).** Throws of computed low rates (:func:`~throwmap.control.inverse.inverse_jog`)
  carry it to x_f, one jog when x_f is within reach, else a jog to 90 % of the way to the end of
  the branch and again. Where jogs make no progress (they vanish near the joint, the erratum of
  Lemma 4.1's δ) or overshoot, the plan goes back to high throws.

A plan is simulated on the model it is made for, so it is exact there; on another model
(or with noise) it is open loop and can fail: that is what the feedback of
:mod:`throwmap.control.controllers` is for. Units: m, rad/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, ThrowmapError, shown
from ..models import DEFAULT_MODEL
from ..models._checks import finite_float
from ..system.arm import regime_warnings_once
from .inverse import ESCAPES, inverse_jog, realisation_factory

__all__ = ["Plan", "PlanStep", "Reachability", "plan_throws", "reachability"]

JOG_SHARE = 0.9
"""A jog that cannot reach x_f in one throw goes this share of the way to the end of its branch."""


@dataclass(frozen=True)
class PlanStep:
    """One throw of a plan: rate ``omega`` (rad/s), from (``x``, ``side``) to (``x_next``, ``side_next``)
    (m); ``phase`` ``"round"`` (a high throw, Lemma 4.1) or ``"jog"`` (Lemma 4.2); ``status`` of the throw."""

    omega: float
    x: float
    side: int
    x_next: float
    side_next: int
    phase: str
    status: str = "ok"


@dataclass(frozen=True)
class Reachability:
    """Prop. 4.3 per rate: ``per_omega`` maps ω (rad/s) → ``(ok, reason, l)`` with ``l`` = l_{side_f} (m,
    nan if side_f is not visited); ``rest_ok``/``rest_reason`` whether x_f is a rest on the arm;
    ``x_max`` the range the limit sets were searched on (m)."""

    x_f: float
    side_f: int
    rest_ok: bool
    rest_reason: str
    per_omega: dict
    x_max: float

    @property
    def reachable(self) -> bool:
        return self.rest_ok and any(v[0] for v in self.per_omega.values())

    @property
    def usable(self) -> tuple:
        """The rates whose limit set reaches side_f short of x_f, in the order given."""
        return tuple(w for w, v in self.per_omega.items() if v[0])

    def explanation(self) -> str:
        if not self.rest_ok:
            return self.rest_reason
        if self.reachable:
            return (f"reachable: S(ω) visits side {self.side_f} below x_f = {self.x_f:.4f} m for ω = "
                    + ", ".join(f"{w:g}" for w in self.usable) + " rad/s")
        return (f"unreachable (x ≤ {self.x_max:.3g} m searched): "
                + "; ".join(f"ω = {w:g} rad/s: {v[1]}" for w, v in self.per_omega.items()))


def _rest_check(part, arm, x_f: float, side_f: int) -> tuple[bool, str]:
    from ..system.starts import start_interval

    lo, hi = start_interval(part, arm, side_f)
    if x_f <= lo:
        return False, (f"x_f = {x_f:.6g} m is not a rest on side {side_f}: its support would start behind the joint "
                       f"(rests need x > {lo:.6g} m)")
    if x_f > hi:
        return False, (f"x_f = {x_f:.6g} m is not a rest on side {side_f}: it would overhang the arm's end at "
                       f"{arm.length:.6g} m (rests need x ≤ {hi:.6g} m)")
    return True, ""


def check_rates(omegas, field: str = "omegas") -> tuple:
    """Release rates (rad/s) as a tuple of floats: one number or a sequence, each finite and > 0 (a throw at
    ω = 0 does not move the part); else :class:`~throwmap.errors.InvalidStateError` on ``field``."""
    if isinstance(omegas, (str, bytes)):
        raise InvalidStateError(field, f"must be numbers (rad/s), not text, got {shown(omegas)}")
    try:
        rates = tuple(float(w) for w in np.atleast_1d(np.asarray(omegas, dtype=float)))
    except (TypeError, ValueError):
        raise InvalidStateError(field, f"must be rates > 0 rad/s, got {shown(omegas)}") from None
    if not rates or not all(math.isfinite(w) and w > 0 for w in rates):
        raise InvalidStateError(field, f"must be rates > 0 rad/s, got {shown(omegas)}")
    return rates


def _x_range(arm, x_max) -> float:
    """The upper end (m) of the starts a limit set is sought over: ``x_max``, else the arm's length, else 0.6 m;
    finite, > 0 and on the arm."""
    if x_max is None:
        return 0.6 if arm.length is None else float(arm.length)
    xm = finite_float(x_max, "x_max")
    if xm <= 0:
        raise InvalidStateError("x_max", f"must be > 0 m (the far end of the starts searched), got {xm}")
    if arm.length is not None and xm > arm.length:
        raise InvalidStateError("x_max", f"{xm} m is beyond the arm's end at {arm.length} m")
    return xm


@regime_warnings_once()
def reachability(part, arm, x_f: float, side_f: int, omegas, model: str = DEFAULT_MODEL, *, x_max=None,
                 n_starts: int = 32, realisation=None, **throw_options) -> Reachability:
    """Prop. 4.3's test for each rate in ``omegas`` (rad/s): does S(ω) visit side ``side_f`` below ``x_f`` (m)?

    Limit sets from :func:`throwmap.limit_set` (``n_starts`` per side, x ≤ ``x_max``: the arm
    length, else 0.6 m); the answer holds for that range only. ``realisation``: as
    :func:`~throwmap.control.inverse.inverse_jog` (``"recoil"``: each rate's limit set on the draft's arm)."""
    from ..analysis.limitset import limit_set

    factory = realisation_factory(realisation)

    side_f = part.check_side(side_f, field="side_f")
    x_f = finite_float(x_f, "x_f")
    omegas = check_rates(omegas)
    xm = _x_range(arm, x_max)
    ok, why = _rest_check(part, arm, x_f, side_f)
    per = {}
    for w in omegas:
        extra = {} if factory is None else {"realisation": factory(w)}
        ls = limit_set(part, arm, w, model, n_starts=n_starts, x_max=xm, **extra, **throw_options)
        lows = [lo for a in ls.attractors for (k, lo, hi) in a.bands if k == side_f]
        if not ls.attractors:
            fates = ", ".join(f"{k} {100 * v:.0f} %" for k, v in ls.escapes.items()) or "none"
            per[w] = (False, f"every orbit escapes ({fates} of the starts)", math.nan)
        elif not lows:
            seen = sorted({k for a in ls.attractors for (k, _, _) in a.bands})
            per[w] = (False, f"the limit set never visits side {side_f} (only sides {seen})", math.nan)
        else:
            low = min(lows)
            per[w] = ((low < x_f), (f"l_{side_f} = {low:.4f} m < x_f" if low < x_f else
                                    f"l_{side_f} = {low:.4f} m is not below x_f = {x_f:.4f} m"), low)
    return Reachability(x_f, side_f, ok, why, per, xm)


@dataclass(frozen=True)
class Plan:
    """An open-loop plan (see the module docstring): ``steps``; ``reachable``; ``explanation`` (why
    not, or how); ``final`` (x, side) after the steps; ``error`` = |x − x_f| (m) when on side_f."""

    x0: float
    side0: int
    x_f: float
    side_f: int
    model: str
    steps: tuple
    reachable: bool
    explanation: str
    tol: float

    @property
    def final(self) -> tuple:
        return (self.steps[-1].x_next, self.steps[-1].side_next) if self.steps else (self.x0, self.side0)

    @property
    def error(self) -> float:
        x, k = self.final
        return abs(x - self.x_f) if k == self.side_f else math.inf

    @property
    def omegas(self) -> tuple:
        return tuple(s.omega for s in self.steps)

    def __repr__(self) -> str:
        """One line: :meth:`summary` (the steps are in :meth:`table`)."""
        return f"Plan<{self.summary()}>"

    def summary(self) -> str:
        n_round = sum(s.phase == "round" for s in self.steps)
        head = (f"plan ({self.model}) from ({self.x0:.4f} m, side {self.side0}) to ({self.x_f:.4f} m, side {self.side_f}): ")
        if not self.reachable:
            return head + "NOT REACHED — " + self.explanation
        n = len(self.steps)
        return head + (f"{n} throw{'s' if n != 1 else ''} ({n_round} round the limit set, {n - n_round} "
                       f"jog{'s' if n - n_round != 1 else ''}), "
                       f"ends {self.error * 1e6:.3g} µm from x_f; {self.explanation}")

    def table(self) -> str:
        rows = ["| # | phase | ω (rad/s) | from (x m, side) | to (x m, side) | status |", "|---|---|---|---|---|---|"]
        for i, s in enumerate(self.steps, 1):
            rows.append(f"| {i} | {s.phase} | {s.omega:.6f} | {s.x:.6f}, {s.side} | {s.x_next:.6f}, {s.side_next} | {s.status} |")
        return "\n".join(rows)


@regime_warnings_once()
def plan_throws(part, arm, x0: float, side0: int, x_f: float, side_f: int, *, omegas=(4.0,),
                model: str = DEFAULT_MODEL, max_throws: int = 500, tol: float = 1e-6, jog_omega_max: float = 10.0,
                check_reachability: bool = True, x_max=None, realisation=None, **throw_options) -> Plan:
    """A throw sequence from (``x0``, ``side0``) to (``x_f``, ``side_f``) (m) on ``model``.

    ``omegas``: the high rates offered for going round the limit set (rad/s, tried in order);
    ``max_throws`` bounds each attempt; ``tol`` (m) the final |x − x_f|; ``jog_omega_max`` the
    jogs' largest rate. With ``check_reachability`` the rates are first screened by
    :func:`reachability` (limit sets on x ≤ ``x_max``) and an unreachable target returns a plan
    with ``reachable=False`` and the reasons, without throwing. ``realisation`` (None/"impulse",
    "recoil" or a callable ω → realisation, for models that take one) applies to every throw.
    """
    side0 = part.check_side(side0, field="side0")
    side_f = part.check_side(side_f, field="side_f")
    for value, name in ((x0, "x0"), (x_f, "x_f"), (tol, "tol"), (jog_omega_max, "jog_omega_max")):
        finite_float(value, name)
    if tol <= 0:
        raise InvalidStateError("tol", f"must be > 0 m (the final |x − x_f|), got {tol}")
    if jog_omega_max <= 0:
        raise InvalidStateError("jog_omega_max", f"must be > 0 rad/s (the jogs' largest rate), got {jog_omega_max}")
    if isinstance(max_throws, bool) or not isinstance(max_throws, int) or max_throws < 1:
        raise InvalidStateError("max_throws", f"must be an integer ≥ 1, got {shown(max_throws)}")
    omegas = check_rates(omegas)
    if check_reachability:
        _x_range(arm, x_max)

    def done(steps, ok, why):
        return Plan(float(x0), side0, float(x_f), side_f, model, tuple(steps), ok, why, tol)

    ok, why = _rest_check(part, arm, float(x_f), side_f)
    if not ok:
        return done([], False, why)
    goal = _Goal(part, arm, float(x_f), side_f, model, max_throws, tol, jog_omega_max, throw_options, realisation)
    if side0 == side_f:  # Prop. 4.3 is sufficient, not necessary: jogs alone may already get there
        steps, why = _attempt(goal, float(x0), side0, None)
        if why is None:
            return done(steps, True, "jogs only (Lemma 4.2): already on side_f, no high throw needed")
    if check_reachability:
        r = reachability(part, arm, x_f, side_f, omegas, model, x_max=x_max, realisation=realisation, **throw_options)
        if not r.reachable:
            return done([], False, r.explanation())
        omegas = r.usable
    reasons = []
    for w_high in omegas:
        steps, why = _attempt(goal, float(x0), side0, w_high)
        if why is None:
            n_round = sum(s.phase == "round" for s in steps)
            how = (f"round the limit set at ω = {w_high:g} rad/s ({n_round} throws, Lemma 4.1), then jogs (Lemma 4.2)"
                   if n_round else "jogs only (Lemma 4.2): already on side_f short of x_f")
            return done(steps, True, how)
        reasons.append(f"ω = {w_high:g} rad/s: {why}")
    return done(steps, False, "; ".join(reasons))


@dataclass(frozen=True)
class _Goal:
    """What every attempt of one plan shares: the part on the arm, the goal ``(x_f, side_f)`` (m), the model and
    its throw options, the caps (``max_throws``, ``tol`` m, ``jog_max`` rad/s) and the arm's ``realisation``."""

    part: object
    arm: object
    x_f: float
    side_f: int
    model: str
    max_throws: int
    tol: float
    jog_max: float
    opts: dict
    realisation: object


def _attempt(g: _Goal, x: float, k: int, w_high):
    """One plan from ``(x, k)`` with high rate ``w_high`` (None: jogs only), its throws on one throwing session
    (:func:`~throwmap.throws.session.open_session`): ``(steps, None)`` or ``(steps, reason)``."""
    from ..throws.session import open_session

    part, arm, x_f, side_f, model, tol, jog_max = g.part, g.arm, g.x_f, g.side_f, g.model, g.tol, g.jog_max
    factory = realisation_factory(g.realisation)
    session = open_session(part, arm, (x, k), model, **g.opts)

    def throw(w):
        return session.throw(w, None if factory is None else factory(w)).outcome

    opts_inv = dict(g.opts, realisation=g.realisation)
    steps = []
    stuck = 0
    while len(steps) < g.max_throws:
        if k == side_f and abs(x - x_f) <= tol:
            return steps, None
        if k == side_f and stuck < 2:
            try:
                inv = inverse_jog(part, arm, x, k, x_f, model, omega_max=jog_max, tol=tol, **opts_inv)
                w = inv.omega
            except InvalidStateError as err:
                if err.field != "x_target":
                    return steps, f"the jog map is discontinuous at x_f ({err.reason})"
                w = _partial_jog(part, arm, x, k, x_f, model, jog_max, tol, opts_inv)
            if w is not None:
                out = throw(w)
                st = str(out.status)
                steps.append(PlanStep(w, x, k, float(out.x), int(out.side), "jog", st))
                if st != "ok":
                    return steps, f"a jog ended {st}"
                moved = abs(out.x - x)
                x, k = float(out.x), int(out.side)
                stuck = stuck + 1 if moved < 1e-7 else 0
                continue
        if w_high is None:  # jogs only: no progress left
            return steps, f"jogs alone stop at x = {x:.4f} m on side {k}"
        out = throw(w_high)
        st = str(out.status)
        steps.append(PlanStep(w_high, x, k, float(out.x), int(out.side), "round", st))
        if st != "ok":
            kind = "escapes" if st in ESCAPES else "is refused"
            return steps, f"the orbit {kind} ({st}) after {len(steps)} throws"
        x, k, stuck = float(out.x), int(out.side), 0
    return steps, (f"not reached within {g.max_throws} throws (last at x = {x:.4f} m on side {k}; jogs make no "
                   f"progress there or the orbit never rests on side {side_f} short of x_f)")


def _partial_jog(part, arm, x, k, x_f, model, jog_max, tol, opts):
    """A rate that jogs a share :data:`JOG_SHARE` of the way to the branch's end when it leads towards
    ``x_f``; None when the branch leads away or nowhere (then a high throw follows)."""
    try:
        probe = inverse_jog(part, arm, x, k, x, model, omega_max=jog_max, tol=max(tol, 1e-9), **opts)
    except ThrowmapError:
        return None
    lo, hi = probe.reach
    end = hi if x_f > x else lo
    if abs(end - x) < 1e-6 or (end - x) * (x_f - x) <= 0:
        return None
    target = x + JOG_SHARE * (end - x)
    try:
        return inverse_jog(part, arm, x, k, target, model, omega_max=jog_max, tol=max(tol, 1e-7), **opts).omega
    except ThrowmapError:
        return None
