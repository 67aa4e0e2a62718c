"""Feedback controllers for throwing a part to a chosen rest ``(x_f, side_f)`` (paper Sec. IV-A).

A controller is an immutable value; what changes during an episode lives in a
:class:`ControlState` that the loop (:func:`throwmap.control.loop.closed_loop`) passes back in.
Before every throw the loop reads the controller's :meth:`sensors` at the part's true rest and
calls ``decide(state, readings) -> Decision``: throw at ``omega`` (nominal, rad/s), ``stop``, or
``look`` (read the sensors again without throwing: a confirmation). What each one observes:

* :class:`PaperController` — the draft's strategy, **one-bit sensors only**: ``side`` (on side_f),
  ``goal`` (within ε of x_f), ``beyond`` (beyond x_f + ε: an overshoot) and optional ``approach<i>``
  (beyond x_i). High ω until the side sensor fires, then low ω until the goal sensor fires (stop);
  back to high after an overshoot or when the side is lost. Optional approach rungs
  ``((x_1, ω_1), …)`` jog faster while the part is short of x_i (an extra one-bit sensor per rung);
  optional kick rungs ``((x_1, ω_1), …)`` replace the high ω off the goal side while the part is short
  of x_i (``kick<i>`` sensors): near the joint the recoil arm's high throws creep a part inward.
* :class:`InverseJogController` — model-based: reads a **position estimate** (x + σ N(0, 1), side)
  from a :class:`~throwmap.control.sensors.PositionSensor`; on side_f short of the goal it throws
  the inverse jog ``jog_rate(part, arm, x̂, side_f, x̂ + gain (x_f − x̂), model)`` (the rate whose
  modelled jog ends there) clipped to ``[omega_min, omega_max]``; ``omega_max`` when no jog of the
  model reaches; high ω off side_f or past the goal; stop within ``eps`` of x_f.
* :class:`FunnelController` — a funnel policy (:meth:`throwmap.analysis.funnels.FunnelGraph.policy`):
  reads a position estimate, throws the (possibly composed) ω of the highest-priority funnel whose
  mouth holds it, ``omega_fallback`` outside every mouth, stops when the estimate is in the goal.

Every mode change other than the first to ``high`` must be seen on ``confirm`` consecutive
observations, and once one is suggested the controller keeps looking (``look`` decisions, no
throw) until ``confirm`` readings in a row ask for the change or for staying: a single false
reading neither switches the mode nor makes a throw; ``confirm = 1`` is the draft's controller.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import InvalidStateError, shown
from .sensors import BeyondSensor, PositionSensor, SideSensor, WithinSensor

__all__ = ["Goal", "ControlState", "Decision", "PaperController", "InverseJogController", "FunnelController",
           "CONTROLLER_KINDS"]

CONTROLLER_KINDS = ("paper", "inverse", "funnel")


def _omega(value, field: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value) or value <= 0:
        raise InvalidStateError(field, f"must be a finite release rate > 0 (rad/s), got {shown(value)}")
    return float(value)


def _confirm(value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 1 <= value <= 100:
        raise InvalidStateError("controller.confirm", f"must be an integer in [1, 100], got {shown(value)}")
    return int(value)


@dataclass(frozen=True, slots=True)
class Goal:
    """The target rest: CM abscissa ``x`` (m) on side ``side``, within ``eps`` (m)."""

    x: float
    side: int
    eps: float

    def __post_init__(self):
        if isinstance(self.x, bool) or not isinstance(self.x, (int, float, np.integer, np.floating)) \
                or not math.isfinite(self.x):
            raise InvalidStateError("goal.x", f"must be a finite abscissa (m), got {shown(self.x)}")
        if isinstance(self.side, bool) or not isinstance(self.side, (int, np.integer)) or self.side < 0:
            raise InvalidStateError("goal.side", f"must be a side index (integer ≥ 0), got {shown(self.side)}")
        if isinstance(self.eps, bool) or not isinstance(self.eps, (int, float, np.integer, np.floating)) \
                or not math.isfinite(self.eps) or self.eps <= 0:
            raise InvalidStateError("goal.eps", f"must be a finite length > 0 (m), got {shown(self.eps)}")
        object.__setattr__(self, "x", float(self.x))
        object.__setattr__(self, "side", int(self.side))
        object.__setattr__(self, "eps", float(self.eps))

    def reached(self, x: float, side: int) -> bool:
        return int(side) == self.side and abs(float(x) - self.x) <= self.eps

    def to_dict(self) -> dict:
        return {"x_m": self.x, "side": self.side, "eps_m": self.eps}


@dataclass(frozen=True, slots=True)
class ControlState:
    """A controller's state between decisions: ``mode`` (``"start"`` before the first), the mode
    awaiting confirmation (``pending``, asked for ``seen`` times in a row; ``stay``: readings in a row
    that asked to stay in ``mode`` since) and the throws left of a composed funnel sequence (``queue``, rad/s)."""

    mode: str = "start"
    pending: str | None = None
    seen: int = 0
    queue: tuple = ()
    stay: int = 0


@dataclass(frozen=True, slots=True)
class Decision:
    """What to do next: ``action`` ``"throw"`` (at nominal ``omega``, rad/s), ``"stop"`` or ``"look"``
    (read again, no throw); the next ``state``; ``mode`` the controller is in after it; ``switched``
    whether the mode changed; ``reason`` in words."""

    action: str
    omega: float
    state: ControlState
    mode: str
    switched: bool = False
    reason: str = ""


def _transition(state: ControlState, want: str, confirm: int) -> tuple[bool, ControlState]:
    """``(accepted, next state)`` for a wish to be in mode ``want``. With ``confirm`` = 1 every wish is
    accepted (the draft's controller), and so is the first mode ``high``. Otherwise a wish to change mode
    opens a sequential test, decided by looks: the change is accepted after ``confirm`` wishes for it in a
    row, and dropped (the mode kept) after ``confirm`` wishes in a row to stay; a single contrary reading
    neither switches nor ends the test."""
    if confirm <= 1 or (state.mode == "start" and want == "high"):
        return True, ControlState(want, None, 0, state.queue if want == state.mode else ())
    if want == state.mode:
        if state.pending is None:
            return True, ControlState(want, None, 0, state.queue)
        stay = state.stay + 1
        if stay >= confirm:
            return True, ControlState(want, None, 0, state.queue)
        return False, ControlState(state.mode, state.pending, 0, state.queue, stay)
    seen = state.seen + 1 if state.pending == want else 1
    if seen >= confirm:
        return True, ControlState(want, None, 0, ())
    return False, ControlState(state.mode, want, seen, state.queue, 0)


def _decide(state: ControlState, want: str, omega: float, confirm: int, reason: str, queue: tuple = ()) -> Decision:
    ok, nxt = _transition(state, want, confirm)
    if not ok:
        what = f"confirming {want} ({nxt.seen}/{confirm})" if nxt.seen else \
            f"confirming {nxt.pending} against staying in {state.mode} ({nxt.stay}/{confirm})"
        return Decision("look", math.nan, nxt, state.mode, False, what)
    if queue:
        nxt = replace(nxt, queue=tuple(queue))
    switched = want != state.mode
    if want == "stop":
        return Decision("stop", math.nan, nxt, "stop", switched, reason)
    return Decision("throw", float(omega), nxt, want, switched, reason)


@dataclass(frozen=True, slots=True)
class PaperController:
    """The draft's two-sensor controller (see the module docstring); all sensors share the error rates
    ``false_positive``/``false_negative``, and the position ones ``hysteresis`` and ``sigma`` (m).
    ``overshoot=False`` drops the ``beyond`` sensor (the draft's two sensors only)."""

    goal: Goal
    omega_high: float
    omega_low: float
    approach: tuple = ()
    false_positive: float = 0.0
    false_negative: float = 0.0
    hysteresis: float = 0.0
    sigma: float = 0.0
    confirm: int = 1
    overshoot: bool = True
    kick: tuple = ()

    kind = "paper"
    rest_policy = True
    """Its decisions depend on the sensors' readings at the rest alone (with ``confirm = 1`` and no hysteresis)."""

    def __post_init__(self):
        if not isinstance(self.goal, Goal):
            raise InvalidStateError("controller.goal", f"must be a Goal, got {type(self.goal).__name__}")
        object.__setattr__(self, "omega_high", _omega(self.omega_high, "controller.omega_high"))
        object.__setattr__(self, "omega_low", _omega(self.omega_low, "controller.omega_low"))
        object.__setattr__(self, "approach", _rungs(self.approach, "controller.approach"))
        object.__setattr__(self, "kick", _rungs(self.kick, "controller.kick"))
        object.__setattr__(self, "confirm", _confirm(self.confirm))
        self.sensors()  # validates the rates, hysteresis and sigma (errors name sensor.<field>)

    def sensors(self) -> dict:
        g, e = self.goal, dict(false_positive=self.false_positive, false_negative=self.false_negative)
        p = dict(e, hysteresis=self.hysteresis, sigma=self.sigma)
        out = {"side": SideSensor(g.side, **e), "goal": WithinSensor(g.x, g.eps, **p)}
        if self.overshoot:
            out["beyond"] = BeyondSensor(g.x + g.eps, **p)
        for i, (x, _) in enumerate(self.approach):
            out[f"approach{i}"] = BeyondSensor(x, **p)
        for i, (x, _) in enumerate(self.kick):
            out[f"kick{i}"] = BeyondSensor(x, **p)
        return out

    def initial(self) -> ControlState:
        return ControlState()

    def want(self, obs: dict) -> tuple[str, float, str]:
        """``(mode, ω, reason)`` the readings ask for, whatever the current mode (the strategy is memoryless)."""
        if not obs["side"]:
            for i, (x, w) in enumerate(self.kick):
                if not obs[f"kick{i}"]:
                    return f"kick{i}", w, f"side sensor off, short of {100 * x:.4g} cm"
            return "high", self.omega_high, "side sensor off"
        if obs.get("beyond", False):
            return "high", self.omega_high, "overshoot (beyond x_f + ε)"
        if obs["goal"]:
            return "stop", math.nan, "goal sensor on"
        for i, (x, w) in enumerate(self.approach):
            if not obs[f"approach{i}"]:
                return f"approach{i}", w, f"short of {100 * x:.4g} cm"
        return "low", self.omega_low, "on side, short of goal"

    def decide(self, state: ControlState, obs: dict) -> Decision:
        mode, w, why = self.want(obs)
        return _decide(state, mode, w, self.confirm, why)

    def to_dict(self) -> dict:
        return {"kind": self.kind, "goal": self.goal.to_dict(), "omega_high": self.omega_high,
                "omega_low": self.omega_low, "approach": [list(r) for r in self.approach],
                "false_positive": self.false_positive, "false_negative": self.false_negative,
                "hysteresis_m": self.hysteresis, "sigma_m": self.sigma, "confirm": self.confirm,
                "overshoot": self.overshoot, "kick": [list(r) for r in self.kick]}


def _rungs(value, field: str) -> tuple:
    """Rungs ``((x m, ω rad/s), …)`` validated, in increasing x."""
    rungs = []
    for i, rung in enumerate(value):
        try:
            x, w = rung
        except (TypeError, ValueError):
            raise InvalidStateError(f"{field}[{i}]", f"must be a pair (x m, ω rad/s), got {shown(rung)}") from None
        if isinstance(x, bool) or not isinstance(x, (int, float, np.integer, np.floating)) or not math.isfinite(x):
            raise InvalidStateError(f"{field}[{i}]", f"x must be finite (m), got {shown(x)}")
        rungs.append((float(x), _omega(w, f"{field}[{i}]")))
    if any(b[0] <= a[0] for a, b in zip(rungs, rungs[1:])):
        raise InvalidStateError(field, "rungs must be in increasing x")
    return tuple(rungs)


def _jog_rate(*args, **kw):
    """:func:`throwmap.control.inverse.jog_rate` (imported when first used; tests may replace this)."""
    from .inverse import jog_rate

    return jog_rate(*args, **kw)


@dataclass(frozen=True, slots=True)
class InverseJogController:
    """Model-based jogs (see the module docstring). ``part``/``arm`` are the model's (the controller's
    belief, which may differ from the plant's arm μ); ``throw_options`` are passed to ``jog_rate``
    as keywords (a tuple of (name, value) pairs, kept hashable); it stops when the estimate is within
    ``eps − margin`` of x_f (m; a margin of about 2σ of the estimate keeps a blurred stop inside ε);
    ``kick`` rungs as :class:`PaperController`'s, on the estimate."""

    goal: Goal
    part: object
    arm: object
    omega_high: float
    omega_min: float
    omega_max: float
    sensor: PositionSensor = field(default_factory=PositionSensor)
    gain: float = 1.0
    model: str = "rigid_body"
    confirm: int = 1
    throw_options: tuple = ()
    margin: float = 0.0
    kick: tuple = ()

    kind = "inverse"
    rest_policy = True
    """Its decisions depend on the sensors' readings at the rest alone (with ``confirm = 1`` and no hysteresis)."""

    def __post_init__(self):
        if not isinstance(self.goal, Goal):
            raise InvalidStateError("controller.goal", f"must be a Goal, got {type(self.goal).__name__}")
        for name in ("omega_high", "omega_min", "omega_max"):
            object.__setattr__(self, name, _omega(getattr(self, name), f"controller.{name}"))
        if self.omega_min > self.omega_max:
            raise InvalidStateError("controller.omega_min", f"must be ≤ omega_max = {self.omega_max:g} rad/s, "
                                                            f"got {self.omega_min:g}")
        if not isinstance(self.sensor, PositionSensor):
            raise InvalidStateError("controller.sensor", f"must be a PositionSensor, got {type(self.sensor).__name__}")
        g = self.gain
        if isinstance(g, bool) or not isinstance(g, (int, float)) or not math.isfinite(g) or not 0 < g <= 2:
            raise InvalidStateError("controller.gain", f"must be in (0, 2], got {shown(g)}")
        object.__setattr__(self, "gain", float(g))
        object.__setattr__(self, "confirm", _confirm(self.confirm))
        object.__setattr__(self, "throw_options", tuple(self.throw_options))
        mg = self.margin
        if isinstance(mg, bool) or not isinstance(mg, (int, float)) or not math.isfinite(mg) or not 0 <= mg < self.goal.eps:
            raise InvalidStateError("controller.margin", f"must be in [0, eps = {self.goal.eps:g}) m, got {shown(mg)}")
        object.__setattr__(self, "margin", float(mg))
        object.__setattr__(self, "kick", _rungs(self.kick, "controller.kick"))

    def sensors(self) -> dict:
        return {"position": self.sensor}

    def initial(self) -> ControlState:
        return ControlState()

    def rate(self, x_est: float) -> tuple[float, str]:
        """The clipped inverse jog from ``x_est`` and the mode it means (``jog``, ``jog_min``, ``jog_max``): the
        rate is searched on (0, ``omega_max``]; ``omega_max`` where no jog of the model reaches the aim."""
        target = x_est + self.gain * (self.goal.x - x_est)
        try:
            w = float(_jog_rate(self.part, self.arm, x_est, self.goal.side, target, model=self.model,
                                omega_max=self.omega_max, **dict(self.throw_options)))
        except InvalidStateError:
            return self.omega_max, "jog_max"
        if not math.isfinite(w) or w >= self.omega_max:
            return self.omega_max, "jog_max"
        if w <= self.omega_min:
            return self.omega_min, "jog_min"
        return w, "jog"

    def decide(self, state: ControlState, obs: dict) -> Decision:
        x_est, side_est = obs["position"]
        g = self.goal
        if side_est != g.side:
            for i, (x, w) in enumerate(self.kick):
                if x_est <= x:
                    return _decide(state, f"kick{i}", w, self.confirm, f"estimate on side {side_est}, short of "
                                                                        f"{100 * x:.4g} cm")
            return _decide(state, "high", self.omega_high, self.confirm, f"estimate on side {side_est}")
        if x_est > g.x + g.eps - self.margin:  # jogs cannot come back: past the stop band is an overshoot
            return _decide(state, "high", self.omega_high, self.confirm, "overshoot (estimate beyond x_f + ε − margin)")
        if abs(x_est - g.x) <= g.eps - self.margin:
            return _decide(state, "stop", math.nan, self.confirm, "estimate within ε − margin")
        w, mode = self.rate(x_est)
        # the jog modes are one mode for confirmation: the rate changes from throw to throw
        d = _decide(replace(state, mode="jog") if state.mode.startswith("jog") else state, "jog", w, self.confirm,
                    f"inverse jog from {100 * x_est:.4g} cm ({mode})")
        return replace(d, mode=mode if d.action == "throw" else d.mode, switched=d.switched)

    def to_dict(self) -> dict:
        return {"kind": self.kind, "goal": self.goal.to_dict(), "omega_high": self.omega_high,
                "omega_min": self.omega_min, "omega_max": self.omega_max, "sigma_m": self.sensor.sigma,
                "side_error": self.sensor.side_error, "gain": self.gain, "model": self.model, "confirm": self.confirm,
                "margin_m": self.margin, "kick": [list(r) for r in self.kick]}


@dataclass(frozen=True, slots=True)
class FunnelController:
    """A funnel policy (see the module docstring). ``graph`` is a
    :class:`~throwmap.analysis.funnels.FunnelGraph` (its priority order picks the funnel)."""

    goal: Goal
    graph: object
    omega_fallback: float
    sensor: PositionSensor = field(default_factory=PositionSensor)
    confirm: int = 1

    kind = "funnel"

    def __post_init__(self):
        if not isinstance(self.goal, Goal):
            raise InvalidStateError("controller.goal", f"must be a Goal, got {type(self.goal).__name__}")
        if not hasattr(self.graph, "order") or not hasattr(self.graph, "funnels"):
            raise InvalidStateError("controller.graph", f"must be a FunnelGraph, got {type(self.graph).__name__}")
        object.__setattr__(self, "omega_fallback", _omega(self.omega_fallback, "controller.omega_fallback"))
        if not isinstance(self.sensor, PositionSensor):
            raise InvalidStateError("controller.sensor", f"must be a PositionSensor, got {type(self.sensor).__name__}")
        object.__setattr__(self, "confirm", _confirm(self.confirm))

    def sensors(self) -> dict:
        return {"position": self.sensor}

    def initial(self) -> ControlState:
        return ControlState()

    def funnel_at(self, x: float, side: int):
        """``(index, funnel)`` of the highest-priority funnel whose mouth holds ``(x, side)``, else ``(None, None)``."""
        for i in self.graph.order:
            f = self.graph.funnels[i]
            if bool(f.mouth.contains(x, side)):
                return i, f
        return None, None

    def decide(self, state: ControlState, obs: dict) -> Decision:
        x_est, side_est = obs["position"]
        if self.goal.reached(x_est, side_est):
            return _decide(state, "stop", math.nan, self.confirm, "estimate in the goal")
        if state.queue and state.mode.startswith("funnel"):  # the rest of a composed throw sequence
            return Decision("throw", float(state.queue[0]), replace(state, queue=state.queue[1:]), state.mode, False,
                            "composed sequence")
        i, f = self.funnel_at(x_est, side_est)
        if f is None or not f.omegas:
            return _decide(state, "fallback", self.omega_fallback, self.confirm, "outside every mouth")
        oms = tuple(float(w) for w in f.omegas)
        return _decide(state, f"funnel{i}", oms[0], self.confirm, f"mouth of {f.name}", queue=oms[1:])

    def to_dict(self) -> dict:
        return {"kind": self.kind, "goal": self.goal.to_dict(), "omega_fallback": self.omega_fallback,
                "funnels": [self.graph.funnels[i].name for i in self.graph.order], "sigma_m": self.sensor.sigma,
                "confirm": self.confirm}
