"""The closed loop: a controller throwing a part on any throw model (paper Sec. IV-A).

:func:`closed_loop` reads the controller's sensors at the part's true rest, asks it for a decision
(:class:`~throwmap.control.controllers.Decision`: throw at ω, look again, or stop) and throws —
through :func:`throwmap.throw` for the analytic models (the next throw starts flat at the reported
``(x, side)``) or through the pymunk engine for ``model="engine"``, where every run starts from the
pose the previous run ended in (:meth:`throwmap.engine.EngineRun.next_scene`, as
:func:`throwmap.iterate` does), so a start may also be a dropped part
(:class:`~throwmap.experiments.drop.DropResult`). Noise (:class:`~throwmap.experiments.noise.Noise`):
each throw's ω is jittered, and in the engine the arm moves by the noise's realisation (``recoil``:
the Flatland arm) built for that ω; the analytic models always throw the paper's impulse. The arm's
μ is the caller's (draw a trial's μ with ``noise.arm(arm, rng)`` first; a dropped start carries its own).

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


def _start_engine(part, arm, x0, side0, opts):
    from ..engine import Friction, Placement, Scene
    from ..system.pose import state_from_pose

    scene = getattr(x0, "scene", x0)
    if hasattr(scene, "placements"):
        if len(scene.placements) != 1 or scene.placements[0].part != part:
            raise InvalidStateError("x0", "the engine Scene must hold this one part")
        x, k, tilt = state_from_pose(part, scene.placements[0].arm_pose(scene.arm.h))
        return scene, float(x), int(k), float(tilt)
    from ..system.starts import check_start

    x, k, _ = check_start(part, arm, x0, side0, 0.0)
    fr = opts.get("friction") or Friction()
    scene = Scene(arm, (Placement(part, x=x, side=k),), tuple(opts.get("fixtures", ()) or ()),
                  float(opts.get("alpha", 0.0) or 0.0), fr)
    return scene, float(x), int(k), 0.0


def _read(sensors: dict, x: float, side: int, rng, last: dict) -> dict:
    out = {}
    for name in sorted(sensors):
        out[name] = sensors[name].read(x, side, rng, last.get(name))
    return out


def closed_loop(part, arm, controller, x0, side0=None, *, model: str = "rigid_body", noise=None,
                max_throws: int = 200, rng=None, **throw_options) -> Episode:
    """Run ``controller`` on ``part`` resting at ``(x0, side0)`` on ``arm`` until it stops or ``max_throws``.

    ``x0`` may instead be an engine :class:`~throwmap.engine.Scene` or a
    :class:`~throwmap.experiments.drop.DropResult` (model ``"engine"`` only; ``side0`` then unused).
    ``model``: any registered throw model (``"engine"``: chained engine runs). ``noise``: a
    :class:`~throwmap.experiments.noise.Noise` (ω jitter per throw, and the arm's realisation for every model
    that takes one: the engine, and rigid_body, which rides the recoil arm exactly) or None (exact ω; the
    impulse). ``rng``: generator or seed, used for the sensors and the jitter.
    ``throw_options``: keywords of the throw (``fixtures``, ``alpha``, ``settings``, ``friction``, model
    options). See the module docstring for what the result says.
    """
    from ..models import get_model

    if isinstance(max_throws, bool) or not isinstance(max_throws, (int, np.integer)) or max_throws < 0:
        raise InvalidStateError("max_throws", f"must be an integer ≥ 0, got {shown(max_throws)}")
    for name in ("sensors", "decide", "initial", "goal"):
        if not hasattr(controller, name):
            raise InvalidStateError("controller", f"must be a controller (with .{name}), got {type(controller).__name__}")
    rng = as_generator(rng)
    m = get_model(model)
    engine = getattr(m, "name", None) == "engine"
    moving = bool(getattr(getattr(m, "features", None), "realisation", False))  # rigid_body rides the recoil arm
    goal = controller.goal
    if engine:
        from ..engine import ImpulseThrow, simulate

        scene, x, k, tilt = _start_engine(part, arm, x0, side0, throw_options)
        settings = throw_options.get("settings")
    else:
        if hasattr(getattr(x0, "scene", x0), "placements"):
            # a dropped part: the analytic models start flat at its nearest rest
            drop = x0
            x0, side0 = float(getattr(drop, "x")), int(getattr(drop, "side"))
        from ..system.starts import check_start

        x, k, _ = check_start(part, arm, x0, side0, 0.0)
        x, k, tilt = float(x), int(k), 0.0
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
        if engine:
            real = noise.realisation_for(w) if noise is not None else ImpulseThrow(w)
            run = simulate(scene, real, settings)
            st = Status(run.statuses[0])
            x, k, tilt = (float(run.states[0][0]), int(run.states[0][1]), float(run.states[0][2]))
            if st == Status.OK:
                scene = run.next_scene()
        else:
            opts = {kk: v for kk, v in throw_options.items()}
            if moving and noise is not None and "realisation" not in opts:
                opts["realisation"] = noise.realisation_for(w)  # the arm's motion, where the model takes one
            try:
                o = m_throw(part, arm, x, k, w, model, opts)
            except InvalidStateError as err:
                status, failure = "invalid_start", f"refused:invalid_start"
                break
            st = Status(o.status)
            x, k, tilt = float(o.x), int(o.side), 0.0
        status = st.label
        if st != Status.OK:
            failure = st.label if st in (Status.OFF_END, Status.BEHIND_JOINT) else f"refused:{st.label}"
            xs.append(x)
            ss.append(k)
            break
        xs.append(x)
        ss.append(k)
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


def m_throw(part, arm, x, side, omega, model, opts):
    """One analytic throw (:func:`throwmap.throw`)."""
    from ..throws.throw import throw

    return throw(part, arm, x, side, omega, model=model, **opts)
