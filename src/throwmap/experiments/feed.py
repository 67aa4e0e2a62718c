"""Experiment ``feed``: the draft's feeding experiment (Sec. V-C, Fig. 9), in the pymunk engine.

The draft dropped its designed triangle onto the arm 20 times and threw it until it lay in the
cavity at the arm's end on side 2: 19/20 = 95 %. Here one trial is:

1. **drop** the part onto the arm from a random pose and height (:func:`~throwmap.experiments.drop.drop_part`,
   with the cavity and its end wall in place; the trial's arm μ drawn by the noise model);
2. **throw** it again and again from where it settled, each throw with its own jittered ω and
   the chosen arm motion (:class:`~throwmap.system.noise.Noise`: 3 % ω jitter and the
   Flatland recoil by default), every engine run starting from the previous run's end
   (:meth:`throwmap.engine.EngineRun.next_scene`: the part is never restarted flat);
3. variant ``"closed"`` (the cavity of :func:`throwmap.design.cavity.design_cavity`): **captured**
   when, at rest after a throw, it lies flat on the target side in the cavity
   (:meth:`~throwmap.design.cavity.CavityDesign.where`) within ``max_throws`` throws; then
   ``hold_throws`` more throws; **success** = still captured on the target side after them.
   Failures: ``not_captured`` (never captured within ``max_throws``), ``wrong_side_captured``
   (in the cavity on another side at the end), ``tilted_in_cavity`` (in the cavity on the target
   side but not flat, e.g. across the lip), ``ejected`` (captured, then outside the cavity or
   off the arm at the end), ``off_arm`` (left the arm before being captured), ``refused:<status>``
   (an engine run refused — timeout, penetration, unconverged, unresolved — or every drop refused:
   never counted as a success).
   Variant ``"open"`` (no cavity, no wall; the arm ``open_length`` long): the part is thrown until
   it leaves over the end; **success** = it was resting on the target side when the throw that
   carried it off began. ``purity`` (the experiment's reading) is the share of the parts that
   left over the end that left on the target side: successes / (successes + ``wrong_side``).
   Failures: ``wrong_side`` (left over the end from another side), ``behind_joint``,
   ``not_fed`` (still on the arm after ``max_throws``), ``refused:<status>``.

Options of the closed variant (measured, none beats the designed cavity; docs/how-to/feeding.md "The cavity and the
feeding experiment"): ``fixture = "wall"`` replaces the cavity by a plain end wall
(:func:`build_wall`, :class:`EndWall`: "target" = flat on the target side with its outermost vertex
within ``wall.zone`` of the wall); ``clear_every``/``clear_factor`` make every ``clear_every``-th
throw a clearing throw at ω·``clear_factor`` (it frees side 2 flush at the wall of the feeder
design for factors 1.55–1.6; the design's wall is raised to that throw's energy bound).

Per-trial values: ``throws_to_capture`` (closed; nan if never), ``hold_breaks`` (hold throws
after which the part was not captured on the target side: 0 = held at every throw),
``throws``, final ``x``/``y``/``phi`` (arm frame, m, rad), ``side`` (the side nearest the arm in that last pose:
for a part that left the arm, ``off_arm``, the pose it was last seen in) and ``tilt`` (rad), ``where``,
the drop (``release_x``: the CM abscissa it was released at, in ``x_range``; ``drop_x``, ``drop_side``: where it
settled, which a bounce or a roll can put up to about 10 cm further; ``drop_redraws``), the trial's ``mu``, the extreme ω used
(``omega_min``, ``omega_max``, clearing throws included), and in the open variant ``side_before``/``side_exit``.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from ..errors import InvalidStateError, ThrowmapError
from .base import Trial, seed_of
from .drop import DEFAULT_HEIGHT, drop_part
from ..io.spec import ArmSpec, Heights, NoiseSpec, Range, Rate, Spec
from .registry import register_experiment

__all__ = ["FEED", "CavityConfig", "EndWall", "Feed", "FeedConfig", "WallConfig", "build_design", "build_wall",
           "open_length"]

Finite = Annotated[float, Field(allow_inf_nan=False)]

ENGINE = "engine"
"""The model every feeding trial runs on: the drop and the throws are engine runs (the part keeps its pose)."""


class CavityConfig(BaseModel):
    """The cavity's design inputs (:func:`throwmap.design.cavity.design_cavity`; SI units, rad)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    depth: Finite = Field(0.02, gt=0, description="cavity depth below the arm surface, m")
    clearance: Finite = Field(0.005, ge=0, description="floor length beyond the target side's length, m")
    ramp_angle: Finite = Field(math.radians(60.0), gt=0, le=math.pi / 2, description="lip ramp angle, rad")
    end_gap: Finite = Field(0.0, ge=0, description="floor ends this short of the end wall, in a ramp, m (0: flush)")
    end_angle: Finite = Field(math.radians(60.0), gt=0, le=math.pi / 2, description="end ramp angle, rad")
    wall_mu: Finite = Field(0.0, ge=0, description="end wall friction (0: a low-friction facing)")
    lined: bool = Field(False, strict=True, description="pocket floor faced with the end wall's material (its μ is wall_mu)")
    wall_margin: Finite = Field(0.01, ge=0, description="end wall height above the energy bound, m")
    z_hold: Finite = Field(3.0, ge=0, description="σ of ω jitter up to which the target side is held")
    z_release: Finite = Field(1.0, ge=0, description="σ of ω jitter down to which the other sides leave")
    place: Finite = Field(0.5, ge=0, le=1, description="where in the window for the arm's end L (0: low end)")
    length: Finite | None = Field(None, gt=0, description="override the designed arm end L, m (None: designed)")
    window: bool = Field(True, strict=True, description="compute the window on the floor's throw map (false: only "
                                                        "with length given; its exact checks are then left out)")

    @model_validator(mode="after")
    def _window_needs_length(self):
        if not self.window and self.length is None:
            raise ValueError("window may be false only with the length given: the window places the arm's end")
        return self


class WallConfig(BaseModel):
    """The plain end wall (fixture ``"wall"``: no cavity, a :class:`~throwmap.system.fixtures.Wall`
    at the arm's end; SI units)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    length: Finite | None = Field(None, gt=0, description="arm end (wall face) L, m (None: the middle of the feeder "
                                                          "design's end-wall window)")
    mu: Finite = Field(0.0, ge=0, description="wall friction (0: a low-friction facing)")
    margin: Finite = Field(0.01, ge=0, description="wall height above the energy bound ω_hi²(x²+y²)/2g, m")
    zone: Finite = Field(0.02, gt=0, description="'at the end': the part's outermost vertex within this of the wall, m")


@dataclasses.dataclass(frozen=True)
class EndWall:
    """A plain end wall holding the part at the arm's end (fixture ``"wall"``): ``arm`` (its length
    = the wall face L, m), ``wall``, target ``side``, ``zone`` (m), ``numbers`` (m, rad/s)."""

    part: object
    arm: object
    wall: object
    side: int
    zone: float
    numbers: dict

    fixtures = property(lambda self: (self.wall,))

    def where(self, pose) -> str:
        """``"target"`` (outermost vertex within ``zone`` of the wall, flat on the target side within
        :data:`~throwmap.design.cavity.CAPTURE_TILT`), ``"other"`` (at the wall otherwise) or ``"outside"``."""
        from ..design.cavity import CAPTURE_TILT
        from ..system.pose import state_from_pose, world_vertices

        if float(world_vertices(self.part, pose)[:, 0].max()) < self.arm.length - self.zone:
            return "outside"
        _, k, tilt = state_from_pose(self.part, pose)
        return "target" if (k == self.side and abs(tilt) < CAPTURE_TILT) else "other"

    def to_dict(self) -> dict:
        return {"fixture": "wall", "length_m": self.arm.length, "height_m": self.wall.height, "mu": self.wall.mu,
                "zone_m": self.zone, **{k: v for k, v in self.numbers.items()}}


class FeedConfig(Spec):
    """Config of ``feed`` (SI units). The field defaults (the built-in example is :meth:`Feed.example` instead)
    are the feeder design of
    :func:`throwmap.design.examples.feeder_design` (17 cm plexiglas triangle + 50 g lead, side 0),
    arm μ = 1 ± 10 %, 3 % ω jitter, the Flatland recoil (3°, ζ = 0.2), the designed cavity,
    drops of 2–10 cm anywhere over the arm, at most 60 throws to capture, then 50 more."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    part: str = Field("feeder", description="'feeder' (the feeder design) or a built-in part name / part file")
    side: int | None = Field(None, ge=0, strict=True, description="target side (None: the feeder design's)")
    omega: Rate | None = Field(None, description="nominal release rate, rad/s (None: the feeder design's)")
    arm: ArmSpec = Field(default_factory=lambda: ArmSpec(mu=1.0), description="the arm: h (None: the feeder "
                                                                               "design's), nominal μ")
    variant: Literal["closed", "open"] = Field("closed", description="'closed': held at the end; 'open': thrown off it")
    fixture: Literal["cavity", "wall"] = Field("cavity", description="closed variant: the designed cavity or a plain "
                                                                     "end wall")
    cavity: CavityConfig = Field(default_factory=CavityConfig)
    wall: WallConfig = Field(default_factory=WallConfig)
    open_length: Finite | None = Field(None, gt=0, description="arm length of the open variant, m (None: from the "
                                                                    "feeder design's limit set)")
    noise: NoiseSpec = Field(default_factory=lambda: NoiseSpec(omega_rel=0.03, mu_rel=0.1, realisation="recoil",
                                                                   zeta=0.2))
    height: Heights = Field(DEFAULT_HEIGHT, description="drop height of the lowest vertex, m")
    x_range: Range | None = Field(None, description="CM abscissa range of the drop, m (None: the arm)")
    clear_every: int = Field(0, ge=0, le=100_000, description="every this many throws (throw t with t % clear_every "
                                                               "== 0) is a clearing throw (0: none)")
    clear_factor: Finite = Field(1.55, gt=0, description="clearing throw's nominal ω / omega (jittered like the others)")
    max_throws: int = Field(60, ge=1, le=100_000, description="throws allowed until captured (open: until fed)")
    hold_throws: int = Field(50, ge=0, le=100_000, description="throws after capture the part must stay")
    settings: dict | None = Field(None, description="EngineSettings fields to override (e.g. {'t_max': 5.0})")


def _base(cfg: FeedConfig):
    """``(part, arm without length, omega, side, feeder or None)``."""

    fd = None
    if cfg.part == "feeder":
        from ..design.examples import feeder_design

        fd = feeder_design()
        part = fd.part
        h = fd.arm.h
        omega = fd.omega if cfg.omega is None else cfg.omega
        side = fd.target_side if cfg.side is None else cfg.side
    else:
        from ..io.config import resolve_part

        try:
            part = resolve_part(cfg.part).part
        except ThrowmapError as err:  # name the config key; a file error says where a relative path was looked for
            where = (" (a relative path is looked for in the working directory, then next to the config file)"
                     if err.field == "file" else "")
            if err.field in ("file", "part"):
                raise type(err)("config.part", err.reason + where) from None
            raise type(err)(err.field, f"{err.reason} (in config.part = {cfg.part!r})") from None
        for name in ("omega", "side"):
            if getattr(cfg, name) is None:
                raise InvalidStateError(f"config.{name}", f"must be given for part {cfg.part!r} (only 'feeder' has defaults)")
        h, omega, side = None, cfg.omega, cfg.side
    if cfg.arm.length is not None:
        raise InvalidStateError("config.arm.length", "the feeder's arm ends where its cavity or wall is designed "
                                                     "([cavity] length, [wall] length)")
    arm = cfg.arm.arm(field="config.arm.h", h=h)
    return part, arm, float(omega), part.check_side(side, field="config.side"), fd


@functools.lru_cache(maxsize=8)
def _design_cached(key: str):
    cfg = FeedConfig.model_validate_json(key)
    from ..design.cavity import Pocket, design_cavity

    part, arm, omega, side, _ = _base(cfg)
    c, nz = cfg.cavity, cfg.noise
    pocket = Pocket(**c.model_dump(exclude={"z_hold", "z_release"}))
    d = design_cavity(part, arm, omega, side, pocket=pocket, noise=nz.noise(), z_hold=c.z_hold, z_release=c.z_release,
                      verify=False)
    return _clearing_wall(d, cfg)


def _clearing_wall(d, cfg: FeedConfig):
    """``d`` with its end wall raised to the energy bound of the clearing throw, ω·clear_factor·(1 + 3σ)
    (the wall of the design covers ω(1 + z_hold σ) only)."""
    import dataclasses as dc

    f = cfg.clear_factor if cfg.clear_every else 1.0
    if f <= 1.0:
        return d
    H = d.wall.height + (f * f - 1.0) * d.numbers["rise_bound_m"]
    n = dict(d.numbers, wall_height_m=H, rise_bound_m=f * f * d.numbers["rise_bound_m"], clear_factor=f)
    return dc.replace(d, wall=dc.replace(d.wall, height=H), numbers=n)


def build_design(cfg: FeedConfig):
    """The :class:`~throwmap.design.cavity.CavityDesign` a config uses (computed once per process)."""
    keep = {"part", "side", "omega", "arm", "cavity", "noise", "clear_every", "clear_factor"}
    return _design_cached(FeedConfig(**{k: getattr(cfg, k) for k in keep}).model_dump_json())


def build_wall(cfg: FeedConfig) -> EndWall:
    """The plain end wall of a config (fixture ``"wall"``): at ``wall.length`` or the middle of the
    feeder design's end-wall window (plain arm, impulse, ω ± 6 %), as high as the energy bound at
    ω(1 + 3σ) plus ``wall.margin``."""
    from ..system.arm import Arm
    from ..system.fixtures import Wall

    part, arm, omega, side, fd = _base(cfg)
    w = cfg.wall
    if w.length is not None:
        L = float(w.length)
    elif fd is not None:
        L = 0.5 * (fd.wall_window[0] + fd.wall_window[1])
    else:
        raise InvalidStateError("config.wall.length", f"must be given for part {cfg.part!r}")
    w_hi = omega * (1.0 + 3.0 * cfg.noise.omega_rel) * max(1.0, cfg.clear_factor if cfg.clear_every else 1.0)
    x_c, y_c = L - float(part.uR[side]), arm.h + float(part.d[side])
    rise = w_hi**2 * (x_c**2 + y_c**2) / (2.0 * arm.g)
    H = float(part.d[side]) + rise + w.margin
    numbers = {"omega_hi": w_hi, "rise_bound_m": rise, "x_hold_m": x_c}
    if fd is not None:
        numbers.update(window_lo_m=float(fd.wall_window[0]), window_hi_m=float(fd.wall_window[1]))
    arm = Arm(h=arm.h, g=arm.g, length=L, mu=arm.mu, back=arm.back)
    return EndWall(part, arm, Wall(height=H, mu=w.mu), side, float(w.zone), numbers)


def open_length(cfg: FeedConfig) -> float:
    """The open variant's arm length, m: ``open_length``, else midway between the farthest outer vertex
    of the other sides' limit set and the target side's (the feeder design's exact-model band tops)."""
    if cfg.open_length is not None:
        return float(cfg.open_length)
    part, _, _, side, fd = _base(cfg)
    if fd is None:
        raise InvalidStateError("config.open_length", f"must be given for part {cfg.part!r}")
    lo = max(fd.tops[j] + float(part.uR[j]) for j in fd.tops if j != side)
    hi = fd.tops[side] + float(part.uR[side])
    return 0.5 * (lo + hi)


def _settings(cfg: FeedConfig):
    """The config's EngineSettings overrides (None: the defaults), refused on ``config.settings.<key>``."""
    import difflib

    from ..engine.settings import EngineSettings

    if not cfg.settings:
        return None
    allowed = [f.name for f in dataclasses.fields(EngineSettings)]
    for key in cfg.settings:
        if key not in allowed:
            close = difflib.get_close_matches(str(key), allowed, n=1)
            hint = f"did you mean {close[0]!r}? " if close else ""
            raise InvalidStateError(f"config.settings.{key}",
                                    f"unknown EngineSettings field ({hint}allowed: {', '.join(allowed)})")
    try:
        return EngineSettings(**cfg.settings)
    except InvalidStateError as err:  # EngineSettings names its own field "settings.<key>"
        raise InvalidStateError(f"config.{err.field}", err.reason) from None


def _check_x_range(cfg: FeedConfig, arm) -> None:
    """``x_range`` (the drop's CM abscissa, m) must be increasing and overlap the arm [−back, length]."""
    if cfg.x_range is None:
        return
    lo, hi = cfg.x_range
    if not lo < hi:
        raise InvalidStateError("config.x_range", f"must be (low, high) with low < high, got {list(cfg.x_range)}")
    if hi <= -arm.back or lo >= arm.length:
        raise InvalidStateError("config.x_range", f"must overlap the arm [{-arm.back:g}, {arm.length:g}] m, got "
                                                  f"{list(cfg.x_range)}")


class Feed:
    """Drop, then throw until captured in the cavity on the target side and held (see the module docstring)."""

    name = "feed"
    summary = ("drop the designed part, throw it (3 % ω jitter, recoil) until it lies in the cavity on the target "
               "side, then hold it for 50 more throws (variant 'open': fed off the end, orientation purity); "
               "without CONFIG the ≥ 99 % recoil feeder (examples/feed_recoil.toml)")
    config_type = FeedConfig

    def example(self) -> FeedConfig:
        """The built-in example (no CONFIG): the recoil feeder, ``throwmap/data/feed_recoil.toml`` (the same
        file as ``examples/feed_recoil.toml``; its part ``data/recoil_feeder.toml``). The config's field
        defaults are the Sec. V feeder design instead (impulse-designed; docs/how-to/feeding.md, "The impulse
        feeder design's cavity")."""
        from importlib import resources

        from .base import read_config

        with resources.as_file(resources.files("throwmap").joinpath("data/feed_recoil.toml")) as path:
            return read_config(self, path)

    def setup(self, cfg: FeedConfig):
        """``(part, arm with its length, fixtures, omega, side, design or None)`` of a config."""
        part, arm, omega, side, _ = _base(cfg)
        if cfg.variant == "open":
            out = part, dataclasses.replace(arm, length=open_length(cfg)), (), omega, side, None
        else:
            d = build_design(cfg) if cfg.fixture == "cavity" else build_wall(cfg)
            out = part, d.arm, d.fixtures, omega, side, d
        _check_x_range(cfg, out[1])
        return out

    def trial(self, cfg: FeedConfig, index: int, rng) -> Trial:
        return self._run(cfg, index, rng)

    def replay(self, cfg: FeedConfig, seed: int, index: int, *, hold: int = 3):
        """Trial ``index`` of a run seeded ``seed`` again, its throws recorded: ``(trial, trajectory)``, the
        trajectory the throws from the settled drop until ``hold`` throws after the capture (or the trial's end)
        joined (:meth:`~throwmap.records.trajectory.Trajectory.concat`; None when no throw ran). The replay's
        trial stops there, so it carries the capture, not the hold's verdict."""
        from .base import trial_generator

        runs: list = []
        trial = self._run(cfg, index, trial_generator(seed, index), record=runs, stop_after=hold)
        traj = None
        for tr in runs:
            traj = tr if traj is None else traj.concat(tr)
        return trial, traj

    def _run(self, cfg: FeedConfig, index: int, rng, record: list | None = None, stop_after: int | None = None) -> Trial:
        from ..records.outcome import Status
        from ..throws.session import open_session

        part, arm, fixtures, omega, side, design = self.setup(cfg)
        noise = cfg.noise.noise()
        settings = _settings(cfg)
        arm = noise.arm(arm, rng)
        drop = drop_part(part, arm, rng, fixtures=fixtures, x_range=cfg.x_range, height=cfg.height, settings=settings)
        values = {"mu": arm.mu if math.isfinite(arm.mu) else None, "release_x": drop.start[0], "drop_x": drop.x,
                  "drop_side": drop.side,
                  "drop_redraws": drop.redraws, "throws": 0, "throws_to_capture": math.nan, "hold_breaks": 0,
                  "omega_min": math.nan, "omega_max": math.nan}
        if not drop.ok:
            return self._end(index, rng, "refused:drop", values, drop.pose, drop.x, drop.side, drop.tilt, "dropped")
        session = open_session(part, arm, drop, ENGINE, settings=settings)  # each throw from where the last ended
        state, pose = (drop.x, drop.side, drop.tilt), drop.pose
        w_min, w_max = math.inf, -math.inf
        captured_at = None
        total = cfg.max_throws + (cfg.hold_throws if cfg.variant == "closed" else 0)
        for t in range(1, total + 1):
            clearing = cfg.variant == "closed" and cfg.clear_every > 0 and t % cfg.clear_every == 0
            w, real = noise.throw(omega * cfg.clear_factor if clearing else omega, rng)
            w_min, w_max = min(w_min, w), max(w_max, w)
            values.update(throws=t, omega_min=w_min, omega_max=w_max)
            step = session.throw(w, real, record=record is not None)
            if record is not None and step.trajectory is not None:
                record.append(step.trajectory)
            st = step.status
            before = state
            after = step.states[0]
            pose, state = after.pose, (after.x, after.side, after.tilt)
            if cfg.variant == "open":
                if st == Status.OFF_END:
                    values.update(side_before=int(before[1]), side_exit=int(state[1]))
                    ok = int(before[1]) == side
                    return self._end(index, rng, None if ok else "wrong_side", values, pose, *state, "off_end")
                if st == Status.BEHIND_JOINT:
                    return self._end(index, rng, "behind_joint", values, pose, *state, "behind_joint")
                if st != Status.OK:
                    return self._end(index, rng, f"refused:{st.label}", values, pose, *state, st.label)
                continue
            if st in (Status.OFF_END, Status.BEHIND_JOINT):
                kind = "off_arm" if captured_at is None else "ejected"
                return self._end(index, rng, kind, values, pose, *state, st.label)
            if st != Status.OK:
                return self._end(index, rng, f"refused:{st.label}", values, pose, *state, st.label)
            where = design.where(pose)
            if captured_at is None:
                if where == "target":
                    captured_at = t
                    values["throws_to_capture"] = t
                elif t >= cfg.max_throws:
                    kind = self._other(state, side) if where == "other" else "not_captured"
                    return self._end(index, rng, kind, values, pose, *state, where)
            else:
                if where != "target":
                    values["hold_breaks"] += 1
                if stop_after is not None and t - captured_at >= stop_after:
                    return self._end(index, rng, None if where == "target" else "replay_stopped", values, pose,
                                     *state, where)
            if captured_at is not None and t - captured_at >= cfg.hold_throws:
                kind = None if where == "target" else (self._other(state, side) if where == "other" else "ejected")
                return self._end(index, rng, kind, values, pose, *state, where)
        if cfg.variant == "open":
            return self._end(index, rng, "not_fed", values, pose, *state, "on_arm")
        raise AssertionError("unreachable: the closed loop ends by its caps")  # pragma: no cover

    @staticmethod
    def _other(state, side: int) -> str:
        """The failure of a part left in the fixture but not flat on the target side."""
        return "tilted_in_cavity" if int(state[1]) == side else "wrong_side_captured"

    @staticmethod
    def _end(index, rng, failure, values, pose, x, k, tilt, where) -> Trial:
        values = dict(values, x=float(pose[0]), y=float(pose[1]), phi=float(pose[2]), side=int(k), tilt=float(tilt),
                      where=str(where))
        return Trial(index, seed_of(rng), failure is None, failure, values)

    def parameters(self, cfg: FeedConfig) -> dict:
        part, arm, _fixtures, omega, side, design = self.setup(cfg)
        out = {"variant": cfg.variant, "part": part.name, "part_mass_kg": part.mass, "part_com_m": list(part.com),
               "part_vertices_m": [list(v) for v in part.vertices], "target_side": side, "omega_rad_s": omega,
               "h_m": arm.h, "length_m": arm.length, "mu": None if math.isinf(arm.mu) else arm.mu, "g_m_s2": arm.g,
               "noise": cfg.noise.noise().to_dict(), "drop_height_m": list(cfg.height),
               "drop_x_range_m": list(cfg.x_range) if cfg.x_range else [0.0 - arm.back, arm.length],
               "max_throws": cfg.max_throws, "hold_throws": cfg.hold_throws if cfg.variant == "closed" else 0,
               "engine": "pymunk, EngineSettings() defaults" if not cfg.settings else {"pymunk overrides": cfg.settings}}
        if isinstance(design, EndWall):
            out["wall"] = design.to_dict()
            out["success"] = ("at rest flat (|tilt| < 0.05 rad) on the target side with its outermost vertex within "
                              "wall.zone of the end wall within max_throws throws, and so again after hold_throws more")
        elif design is not None:
            cav = design.to_dict()  # the design's small-model checks are a forecast, not this run's verdict
            cav["exact_checks"] = {"passed": cav.pop("success"), "message": cav.pop("message"),
                                   "meaning": "the cavity's design checks on the exact model (window, hold, release "
                                              "of each other side); the trials, not these, measure the feed"}
            out["cavity"] = cav
            out["success"] = ("at rest flat (|tilt| < 0.05 rad) on the target side in the cavity within max_throws "
                              "throws, and so again after hold_throws more")
        else:
            out["success"] = "left over the arm's end from a rest on the target side (purity = successes / parts fed)"
        return out


FEED = register_experiment(Feed())
