"""Experiment ``position``: feedback throwing to a chosen rest with one-bit sensors (paper Sec. IV-A).

The draft threw its 17 cm 30-60-90 triangle with "a relatively large release velocity" until a
one-bit sensor saw the wanted side, then with a low one that jogged it until a second sensor saw it
within ε of x_f; "within 1 cm of the desired position … in the correct orientation" in 20/20 drops.
One trial here:

1. **drop** the part onto the arm (:func:`~throwmap.experiments.drop.drop_part`; the trial's arm μ
   drawn by the noise model), over ``x_range``;
2. run the **controller** (:mod:`throwmap.control`) from where it settled, every throw with its
   own jittered ω and (engine) the Flatland recoil arm: :func:`throwmap.control.closed_loop` —
   in the engine each run starts from the previous run's end; the analytic models (``rigid_body``,
   ``paper``: the impulse) start from the drop's nearest flat rest;
3. **success** = the controller stopped within ``max_throws`` throws with the part at rest on
   ``side`` within ``eps`` of ``x_f``. Failures: ``not_stopped``, ``stopped_off_goal``,
   ``stopped_wrong_side``, ``off_end`` / ``behind_joint`` (left the arm), ``refused:<status>``
   (an engine or model refusal; ``refused:drop`` when no drop came to rest), never a success.

Controllers (``controller``): ``"paper"`` (:class:`~throwmap.control.PaperController`: side, goal
and overshoot sensors, ``approach`` rungs) or ``"inverse"``
(:class:`~throwmap.control.InverseJogController`, a position estimate and the ``rigid_body``
inverse jog). Per-trial values: ``throws``, ``looks``, ``switches``, ``throws_to_side`` (first
throw after which it rested on ``side``; 0 if dropped there, nan if never), final ``x``, ``side``,
``error_m`` (|x − x_f| on ``side``, else nan), ``stopped``, the drop (``release_x`` the CM abscissa at release;
``drop_x``, ``drop_side`` where it settled; ``drop_redraws``), ``mu`` and the extreme ω thrown. :func:`throws_summary` gives the median and
90th percentile of the throws of the successful trials.
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field

from ..errors import InvalidStateError, ThrowmapError
from ..models import options_taken
from .base import Trial, seed_of
from .drop import DEFAULT_HEIGHT, drop_part
from ..io.spec import ArmSpec, Heights, NoiseSpec, Number, Point, Rate, SystemSpec
from .registry import register_experiment

__all__ = ["POSITION", "Position", "PositionConfig", "SensorConfig", "InverseConfig", "throws_summary", "low_rate"]

Finite = Number
Probability = Annotated[float, Field(ge=0, lt=1, allow_inf_nan=False)]


class SensorConfig(BaseModel):
    """The one-bit sensors' errors (every sensor of the paper controller shares them)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    false_positive: Probability = Field(0.0, description="P(reads 1 | truth 0) per read")
    false_negative: Probability = Field(0.0, description="P(reads 0 | truth 1) per read")
    hysteresis: Finite = Field(0.0, ge=0, description="position sensors' hysteresis, m")
    sigma: Finite = Field(0.0, ge=0, description="blur of the abscissa the position sensors threshold, m")
    confirm: int = Field(1, ge=1, le=100, description="consecutive readings needed for a mode change (extra looks)")
    overshoot: bool = Field(True, strict=True, description="a 'beyond x_f + eps' sensor sends the part back to high throws")


class InverseConfig(BaseModel):
    """The inverse-jog controller (``controller = "inverse"``)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    omega_min: Finite = Field(0.5, gt=0, description="least jog rate, rad/s")
    omega_max: Finite = Field(3.0, gt=0, description="largest jog rate (a jog all the way to x_f on side), rad/s")
    gain: Finite = Field(0.7, gt=0, le=2, description="aim at x + gain·(x_f − x)")
    model: str = Field("rigid_body", description="the model the inverse jog is computed on")
    sigma: Finite = Field(0.0005, ge=0, description="position estimate's σ, m")
    side_error: Probability = Field(0.0, description="P(the side is read wrong)")
    margin: Finite | None = Field(None, ge=0, description="stop within eps − margin of x_f, m (None: 2·sigma)")


class PositionConfig(SystemSpec):
    """Config of ``position`` (SI units): the system (:class:`~throwmap.io.spec.SystemSpec`: ``part``, ``[arm]``,
    ``alpha``, ``[wall]``, ``[noise]``), the goal, the controller and the drop. The defaults are the built-in
    example: the draft's 17 cm triangle on a 60 cm arm (h = −1 cm, μ = 1 ± 10 %), goal 48 cm on side 1 within
    1 cm, ω_high = 5 rad/s, approach rungs (20 cm, 4.5 rad/s) and (43 cm, 3 rad/s), ω_low = 1.8 rad/s, 3 % ω
    jitter, the recoil arm (3°, ζ = 0.5), kick rung (13 cm, 6 rad/s) off side 1 near the joint, drops over
    [0.18, 0.30] m; the engine."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    arm: ArmSpec = Field(default_factory=lambda: ArmSpec(h=-0.01, length=0.60, mu=1.0))
    side: int = Field(1, ge=0, strict=True, description="goal side")
    x_f: Finite = Field(0.48, gt=0, description="goal CM abscissa, m")
    eps: Finite = Field(0.01, gt=0, description="goal radius ε, m")
    omega_high: Rate = Field(5.0, description="high release rate (reaches the goal side), rad/s")
    omega_low: Rate = Field(1.8, description="low release rate (jogs by less than ε near x_f), rad/s")
    approach: list[tuple[Finite, Finite]] = Field(default_factory=lambda: [(0.20, 4.5), (0.43, 3.0)],
                                                  description="rungs (x m, ω rad/s): on side, short of x, throw ω")
    kick: list[tuple[Finite, Finite]] = Field(default_factory=lambda: [(0.13, 6.0)],
                                              description="rungs (x m, ω rad/s): off the goal side, short of x, "
                                                          "throw ω instead of omega_high")
    controller: Literal["paper", "inverse"] = Field("paper", description="'paper' (one-bit sensors) or 'inverse'")
    sensors: SensorConfig = Field(default_factory=SensorConfig)
    inverse: InverseConfig = Field(default_factory=InverseConfig)
    model: str = Field("engine", description="'engine' (pymunk, chained runs) or an analytic model name")
    noise: NoiseSpec = Field(default_factory=lambda: NoiseSpec(omega_rel=0.03, mu_rel=0.1, realisation="recoil"))
    height: Heights = Field(DEFAULT_HEIGHT, description="drop height of the lowest vertex, m")
    x_range: Point | None = Field((0.18, 0.30), description="CM abscissa range of the drop, m (None: the whole arm)")
    max_throws: int = Field(300, ge=1, le=100_000, description="throws allowed")
    settings: dict | None = Field(None, description="EngineSettings fields to override")


def _setup(cfg: PositionConfig):
    """``(part, arm, controller)`` of a config."""
    from ..control import Goal
    from ..models import get_model

    part = cfg.build_part()
    try:
        get_model(cfg.model)
    except ThrowmapError as err:
        raise InvalidStateError("config.model", err.reason) from None
    side = part.check_side(cfg.side, field="config.side")
    arm = cfg.build_arm()
    if arm.length is None:
        raise InvalidStateError("config.arm.length", "required: the goal and the drop lie on a bounded arm")
    if cfg.x_f + float(part.uR[side]) >= arm.length:
        raise InvalidStateError("config.x_f", f"the part on side {side} at x_f = {cfg.x_f:g} m reaches past the arm's "
                                              f"end ({arm.length:g} m)")
    if cfg.x_range is not None and not cfg.x_range[0] < cfg.x_range[1]:
        raise InvalidStateError("config.x_range", f"must be (low, high) with low < high, got {list(cfg.x_range)}")
    goal = Goal(cfg.x_f, side, cfg.eps)
    return part, arm, CONTROLLERS[cfg.controller](cfg, part, arm, goal)


def _paper_controller(cfg: PositionConfig, part, arm, goal):
    """The draft's two-rate controller with one-bit sensors (:class:`~throwmap.control.PaperController`)."""
    from ..control import PaperController

    s = cfg.sensors
    return PaperController(goal, cfg.omega_high, cfg.omega_low, tuple(tuple(r) for r in cfg.approach),
                           s.false_positive, s.false_negative, s.hysteresis, s.sigma, s.confirm, s.overshoot,
                           tuple(tuple(r) for r in cfg.kick))


def _inverse_controller(cfg: PositionConfig, part, arm, goal):
    """Inverse jogs read off a position sensor (:class:`~throwmap.control.InverseJogController`)."""
    from ..control import InverseJogController, PositionSensor
    from ..system.arm import Arm

    iv = cfg.inverse
    if iv.omega_min > iv.omega_max:
        raise InvalidStateError("config.inverse.omega_min", f"must be ≤ omega_max = {iv.omega_max:g} rad/s")
    sensor = PositionSensor(iv.sigma, iv.side_error, part.n_sides if hasattr(part, "n_sides") else 3)
    return InverseJogController(goal, part, Arm(h=arm.h, length=arm.length, mu=arm.mu), cfg.omega_high,
                                iv.omega_min, iv.omega_max, sensor, iv.gain, iv.model, cfg.sensors.confirm,
                                margin=min(2.0 * iv.sigma if iv.margin is None else iv.margin, 0.5 * cfg.eps),
                                kick=tuple(tuple(r) for r in cfg.kick))


CONTROLLERS = {"paper": _paper_controller, "inverse": _inverse_controller}
"""The ``controller`` kinds of a config and how each is built."""


def _settings(cfg: PositionConfig):
    from .feed import _settings as feed_settings

    return feed_settings(cfg)  # the same override rules and messages (config.settings.<key>)


def throws_summary(trials) -> dict:
    """Median and 90th percentile (nearest rank) of ``throws`` over the successful trials, with their count."""
    import numpy as np

    t = sorted(float(tr.values["throws"]) for tr in trials if tr.success and "throws" in tr.values)
    if not t:
        return {"median": None, "p90": None, "max": None, "count": 0}
    a = np.asarray(t)
    return {"median": float(np.median(a)), "p90": float(a[max(0, math.ceil(0.9 * a.size) - 1)]),
            "max": float(a[-1]), "count": int(a.size)}


def low_rate(cfg: PositionConfig, eps: float | None = None, *, grid=None) -> float:
    """The largest ω on ``grid`` (default 0.5, 0.6 … 3.0 rad/s) whose throw from ``(x_f − ε, side)`` on the
    config's model (engine: its noise's realisation, nominal μ, no jitter) jogs by less than ``ε``: the
    draft's rule for the low rate ("chosen sufficiently low"). Jogs shorter than ε at every grid rate are not
    guaranteed (the recoil arm's jog does not shrink below ≈ 0.9 mm, measured): then the grid's least rate."""
    import numpy as np

    from ..throws.throw import throw

    part, arm, ctl = _setup(cfg)
    eps = cfg.eps if eps is None else float(eps)
    grid = np.round(np.arange(0.5, 3.0001, 0.1), 6) if grid is None else np.asarray(grid, dtype=float)
    x0, side = cfg.x_f - eps, ctl.goal.side
    best = float(grid[0])
    for w in grid:
        kw = {}
        if _moving(cfg.model):
            kw["realisation"] = cfg.noise.noise().realisation_for(float(w))
        o = throw(part, arm, x0, side, float(w), model=cfg.model, **kw)
        if int(o.status) != 0 or o.side != side or not (o.x - x0) < eps:
            break
        best = float(w)
    return best


class Position:
    """Drop, then throw under feedback until the controller stops; success = stopped within ε of x_f on side."""

    name = "position"
    summary = ("drop the draft's triangle, throw it under feedback (high ω until a side sensor fires, low ω until "
               "a goal sensor fires; recoil arm, 3 % ω jitter); success = stopped within ε of x_f on the goal side")
    config_type = PositionConfig

    def trial(self, cfg: PositionConfig, index: int, rng) -> Trial:
        drop, arm, ep = self._run(cfg, rng)
        values = {"mu": arm.mu if math.isfinite(arm.mu) else None, "release_x": drop.start[0], "drop_x": drop.x,
                  "drop_side": drop.side, "drop_redraws": drop.redraws, "throws": 0, "looks": 0, "switches": 0, "throws_to_side": math.nan,
                  "x": drop.x, "side": drop.side, "error_m": math.nan, "stopped": False,
                  "omega_min": math.nan, "omega_max": math.nan}
        if ep is None:
            return Trial(index, seed_of(rng), False, "refused:drop", values)
        oms = [s.omega for s in ep.steps if s.action == "throw"]
        values.update(throws=ep.throws, looks=ep.looks, switches=ep.switches,
                      throws_to_side=math.nan if ep.first_on_side is None else ep.first_on_side,
                      x=float(ep.x[-1]), side=int(ep.side[-1]), error_m=float(ep.error), stopped=ep.stopped,
                      omega_min=min(oms) if oms else math.nan, omega_max=max(oms) if oms else math.nan)
        return Trial(index, seed_of(rng), ep.success, ep.failure, values)

    def episode(self, cfg: PositionConfig, index: int, seed: int):
        """Trial ``index`` of a run seeded ``seed`` as its full :class:`~throwmap.control.Episode` (for figures):
        the same draws as :meth:`trial`; None where the drop was refused."""
        from .base import trial_generator

        return self._run(cfg, trial_generator(seed, index))[2]

    @staticmethod
    def _run(cfg: PositionConfig, rng):
        """One trial's draws: ``(drop, the trial's arm, Episode or None when the drop was refused)``. The drop
        brings the system's wall and α to a model that keeps poses; the others are given them."""
        from ..control import closed_loop
        from ..models import get_model

        part, arm, ctl = _setup(cfg)
        noise = cfg.noise.noise()
        settings = _settings(cfg)
        arm = noise.arm(arm, rng)
        fixtures = cfg.fixtures()
        drop = drop_part(part, arm, rng, fixtures=fixtures, alpha=cfg.alpha, x_range=cfg.x_range, height=cfg.height,
                         settings=settings)
        if not drop.ok:
            return drop, arm, None
        opts = options_taken(cfg.model, settings=settings)
        if not get_model(cfg.model).features.pose and (fixtures or cfg.alpha):
            opts.update(fixtures=fixtures, alpha=cfg.alpha)
        return drop, arm, closed_loop(part, arm, ctl, drop, model=cfg.model, noise=noise, max_throws=cfg.max_throws,
                                      rng=rng, **opts)

    def parameters(self, cfg: PositionConfig) -> dict:
        part, arm, ctl = _setup(cfg)
        return {"part": part.name, "part_mass_kg": part.mass, "part_com_m": list(part.com), "h_m": arm.h,
                "length_m": arm.length, "mu": None if math.isinf(arm.mu) else arm.mu, "g_m_s2": arm.g,
                "goal": {"x_m": cfg.x_f, "side": ctl.goal.side, "eps_m": cfg.eps}, "controller": ctl.to_dict(),
                "model": cfg.model, "noise": cfg.noise.noise().to_dict()
                if _moving(cfg.model) else dict(cfg.noise.noise().to_dict(), realisation="impulse (analytic model)"),
                "drop_height_m": list(cfg.height),
                "drop_x_range_m": list(cfg.x_range) if cfg.x_range else [0.0 - arm.back, arm.length],
                "max_throws": cfg.max_throws,
                "engine": "pymunk, EngineSettings() defaults" if not cfg.settings else {"pymunk overrides": cfg.settings},
                "success": "the controller stopped within max_throws with the part at rest on the goal side within "
                           "eps of x_f"}


POSITION = register_experiment(Position())


def _moving(model: str) -> bool:
    """Whether ``model`` takes the arm's realisation (the engine; rigid_body rides the recoil arm)."""
    from ..models import get_model

    return bool(get_model(model).features.realisation)
