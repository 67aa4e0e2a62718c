"""The closed loop: a controller throwing a part on any throw model (paper Sec. IV-A).

:func:`closed_loop` reads the controller's sensors at the part's true rest, asks it for a decision
(:class:`~throwmap.control.controllers.Decision`: throw at ω, look again, or stop) and throws, on one
throwing session of the chosen model (:func:`~throwmap.throws.session.open_session`): a model of rests
starts each throw flat at the reported ``(x, side)``; a model that keeps poses (the engine) starts each
run from the pose the previous one ended in, as :func:`throwmap.iterate` does, so a start may also be a
dropped part (:class:`~throwmap.experiments.drop.DropResult`). Noise
(:class:`~throwmap.system.noise.Noise`): each throw's ω is jittered, and where the model follows arm
motions (``features.realisation``) the arm moves by the noise's realisation (``recoil``: the Flatland arm)
built for that ω; the others throw the paper's impulse. The arm's μ is the caller's (draw a trial's μ with
``noise.arm(arm, rng)`` first; a dropped start carries its own).

The result is an :class:`Episode` (frozen): every decision with the readings it was made on,
the rests after every throw, and how it ended. ``success`` needs the controller to have stopped
with the part at rest within the goal; a refused throw ends the episode as ``refused:<status>``,
never as a success.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown
from ..rng import as_generator
from ..records.outcome import Status
from ..system.arm import regime_warnings_once

__all__ = ["Step", "Episode", "closed_loop", "MAX_LOOKS_PER_THROW"]

MAX_LOOKS_PER_THROW = 10
"""An episode may take at most this many looks (reads without a throw) per allowed throw."""


@dataclass(frozen=True, slots=True)
class Step:
    """One decision: the rest it was made at (``x`` m, ``side``, ``tilt`` rad) after ``n_thrown`` throws,
    the ``readings`` ((name, value) pairs: a bool, or ``(x̂, side)`` of a position sensor), the
    ``action`` with its nominal and actual ω (rad/s; nan unless a throw), the controller's ``mode``
    after it, whether it ``switched`` and why (``reason``)."""

    n_thrown: int
    x: float
    side: int
    tilt: float
    readings: tuple
    action: str
    omega_nominal: float
    omega: float
    mode: str
    switched: bool
    reason: str


@dataclass(frozen=True, slots=True)
class Episode:
    """One closed-loop run (SI units).

    ``x``/``side``: the rest at the start and after every throw; ``steps``: every decision;
    ``status``: the last throw's status label (``ok`` when every throw ended at rest);
    ``stopped``: the controller stopped; ``success``: stopped at rest within the goal;
    ``failure``: None on success, else ``not_stopped`` (``max_throws`` used, or the looks' cap),
    ``stopped_off_goal`` / ``stopped_wrong_side``, ``off_end`` / ``behind_joint`` (left the arm),
    ``refused:<status>`` (a throw the model or engine refused: never a success).
    """

    part: str
    model: str
    goal: object
    controller: dict
    x: tuple
    side: tuple
    steps: tuple
    status: str
    stopped: bool
    success: bool
    failure: str | None
    throws: int
    looks: int
    switches: int
    first_on_side: int | None

    @property
    def ok(self) -> bool:
        return self.success

    @property
    def refused(self) -> bool:
        return bool(self.failure and self.failure.startswith("refused:"))

    @property
    def error(self) -> float:
        """Final |x − x_f| (m), nan when not on the goal's side."""
        return abs(self.x[-1] - self.goal.x) if self.side[-1] == self.goal.side else math.nan

    def throw_steps(self) -> tuple:
        return tuple(s for s in self.steps if s.action == "throw")

    def summary(self) -> dict:
        return {"success": self.success, "failure": self.failure, "throws": self.throws, "looks": self.looks,
                "switches": self.switches, "x": self.x[-1], "side": self.side[-1], "status": self.status,
                "first_on_side": self.first_on_side}

    def __repr__(self) -> str:
        end = "success" if self.success else self.failure
        return (f"Episode({self.part}, {self.model}, goal ({100 * self.goal.x:.4g} cm, side {self.goal.side}, "
                f"±{1000 * self.goal.eps:.3g} mm): {end} after {self.throws} throws, {self.switches} switches, "
                f"final ({100 * self.x[-1]:.4g} cm, side {self.side[-1]}))")

    def plot(self, ax=None, **kwargs):
        """x against throw number, coloured by side, the switches marked (:func:`throwmap.viz.control.plot_episode`)."""
        from ..viz.control import plot_episode

        return plot_episode(self, ax=ax, **kwargs)


def _read(sensors: dict, x: float, side: int, rng, last: dict) -> dict:
    out = {}
    for name in sorted(sensors):
        out[name] = sensors[name].read(x, side, rng, last.get(name))
    return out


@regime_warnings_once()
def closed_loop(part, arm, controller, x0, side0=None, *, model: str = "rigid_body", noise=None,
                max_throws: int = 200, rng=None, **throw_options) -> Episode:
    """Run ``controller`` on ``part`` resting at ``(x0, side0)`` on ``arm`` until it stops or ``max_throws``.

    ``x0`` may instead be an engine :class:`~throwmap.engine.Scene` or a
    :class:`~throwmap.experiments.drop.DropResult`: a model that keeps poses (``features.pose``, the engine)
    starts from it; the others start flat at the drop's nearest rest (``side0`` then unused).
    ``model``: any registered throw model; the throws run on one throwing session
    (:func:`~throwmap.throws.session.open_session`). ``noise``: a
    :class:`~throwmap.system.noise.Noise` (ω jitter per throw, and the arm's realisation for every model
    that follows one, ``features.realisation``: the engine, and rigid_body, which rides the recoil arm exactly)
    or None (exact ω; the impulse). ``rng``: generator or seed, used for the sensors and the jitter.
    ``throw_options``: keywords of the throw (``fixtures``, ``alpha``, ``settings``, ``friction``, model
    options). See the module docstring for what the result says.
    """
    from ..models import get_model
    from ..throws.session import open_session

    if isinstance(max_throws, bool) or not isinstance(max_throws, (int, np.integer)) or max_throws < 0:
        raise InvalidStateError("max_throws", f"must be an integer ≥ 0, got {shown(max_throws)}")
    for name in ("sensors", "decide", "initial", "goal"):
        if not hasattr(controller, name):
            raise InvalidStateError("controller", f"must be a controller (with .{name}), got {type(controller).__name__}")
    rng = as_generator(rng)
    start = getattr(x0, "scene", x0)
    if hasattr(start, "placements"):
        if get_model(model).features.pose:
            if len(start.placements) != 1 or start.placements[0].part != part:
                raise InvalidStateError("x0", "the engine Scene must hold this one part")
            arm = start.arm
            state = x0
        else:  # a dropped part: a model of rests starts flat at its nearest rest
            state = (float(getattr(x0, "x")), int(getattr(x0, "side")))
    else:
        state = (x0, side0)
    session = open_session(part, arm, state, model, **throw_options)
    moving = session.features.realisation and noise is not None and "realisation" not in throw_options
    goal = controller.goal
    s0 = session.states[0]
    x, k, tilt = s0.x, s0.side, s0.tilt
    sensors = controller.sensors()
    state = controller.initial()
    xs, ss, steps = [x], [k], []
    last: dict = {}
    throws = looks = switches = 0
    status, failure, stopped = "ok", None, False
    first_on_side = 0 if k == goal.side else None
    max_looks = MAX_LOOKS_PER_THROW * max(1, int(max_throws))
    while True:
        obs = _read(sensors, x, k, rng, last)
        last = obs
        d = controller.decide(state, obs)
        state = d.state
        switches += int(d.switched)
        readings = tuple((n, v) for n, v in obs.items())
        if d.action == "stop":
            steps.append(Step(throws, x, k, tilt, readings, "stop", math.nan, math.nan, d.mode, d.switched, d.reason))
            stopped = True
            break
        if d.action == "look":
            steps.append(Step(throws, x, k, tilt, readings, "look", math.nan, math.nan, d.mode, d.switched, d.reason))
            looks += 1
            if looks > max_looks:
                failure = "not_stopped"
                break
            continue
        if throws >= max_throws:
            steps.append(Step(throws, x, k, tilt, readings, "cap", d.omega, math.nan, d.mode, d.switched,
                              "max_throws reached"))
            failure = "not_stopped"
            break
        w_nom = float(d.omega)
        w = noise.omega(w_nom, rng) if noise is not None else w_nom
        steps.append(Step(throws, x, k, tilt, readings, "throw", w_nom, w, d.mode, d.switched, d.reason))
        throws += 1
        step = session.throw(w, noise.realisation_for(w) if moving else None)
        st = step.status
        status = st.label
        if st == Status.INVALID_START:  # the rest the last throw left is not a start of the map
            failure = f"refused:{st.label}"
            break
        after = step.states[0]
        x, k, tilt = after.x, after.side, after.tilt
        xs.append(x)
        ss.append(k)
        if st != Status.OK:
            failure = st.label if st in (Status.OFF_END, Status.BEHIND_JOINT) else f"refused:{st.label}"
            break
        if first_on_side is None and k == goal.side:
            first_on_side = throws
    success = False
    if stopped:
        if k != goal.side:
            failure = "stopped_wrong_side"
        elif abs(x - goal.x) > goal.eps:
            failure = "stopped_off_goal"
        else:
            success = True
    ctl = controller.to_dict() if hasattr(controller, "to_dict") else {"kind": type(controller).__name__}
    return Episode(getattr(part, "name", str(part)), str(model), goal, ctl, tuple(xs), tuple(ss), tuple(steps),
                   status, stopped, success, None if success else failure, throws, looks, switches, first_on_side)
