"""Experiments ``assemble-sequential`` and ``assemble-serial``: the draft's sequential assembly (Sec. V-D, Fig. 10).

The draft threw its designed triangle and a four-sided part on one arm until both lay in the cavity at its end,
the four-sided part "perfectly matching the sides of the cavity and the top of the triangle": 11/20 = 55 %, and
assembled parts stayed assembled after the next throw 17/20 = 85 %; its failures were the second part ejected
from the assembled state and stuck in the cavity in a wrong orientation, and it suggested handling the parts
separately (serially). Here (pymunk engine, :mod:`throwmap.design.stack` for the design):

* the first part is the recoil feeder (``experiment feed``'s built-in example: triangle + 80 g lead,
  side 0, the 1 cm pocket ending at the end wall, L = 0.38 m, ω = 4.56 rad/s, 3 % jitter, the recoil arm);
* the second is the wedge of :func:`~throwmap.design.stack.design_stack` (the slot between the captured triangle's
  short leg and the end wall), ``[wedge]`` in the config;
* ``assemble-sequential``: both parts are dropped together (random non-overlapping poses, CM x over ``x_range``,
  lowest vertex 2–10 cm up) and thrown at ω until assembled (:meth:`StackDesign.assembled`), at most
  ``max_throws``, with the *recovery* below (``recover.enabled = false``: open loop, as the draft);
* ``assemble-serial`` (the draft's suggestion): the triangle alone is dropped and thrown until captured in the
  pocket (at most ``max_first``), then the wedge is dropped onto the arm (``x_range_second``) and both are thrown
  at ``omega_second`` until assembled (at most ``max_second``).

The recovery (:class:`RecoverConfig`, measured): open loop, 24–34 % of trials ended in one *trap* —
the wedge, faster outward than the triangle, reaches the wall first and lies flat on its leg side on the pocket
floor; the triangle arriving then leans 30° on it, and rocks there ±8 mm a throw at every rate from 3.5 to 5.5
rad/s. A one-bit sensor (both CMs past the lip and neither moved more than 1 cm since the last throw: "stuck")
switches in a recovery throw: tilt the arm up 10° at 1 rad/s, throw there at 4.56 rad/s, tilt back. On 24 traps
collected from open-loop runs one recovery and 30 ordinary throws assembled 8 (tilting alone: +20° 5, −40° 2;
a 6.5 rad/s throw 5 and one loss; tilted +10° at 5.5 rad/s 7 and 4 losses; +20° at 4.56 rad/s 6 and 11 losses);
repeated at every "stuck" reading it frees most traps. Drops are within [0.10, 0.25] m of the joint: nearer,
6 of 60 trials lost a part behind the joint within 6 throws (the two parts collide there).

Then ``hold`` more throws: ``held_1`` (assembled after the next throw), ``held_k`` (after each of them). Success
= assembled within the caps (retention is reported, not part of success, as in ``assemble``). Failures (first
that applies): ``ejected`` (a part left the arm: off the end or behind the joint; ``lost`` says which and how),
``wrong_orientation`` (at the cap a part is in the cavity's end, past the lip, but the pair is not assembled:
the triangle off its target side or the wedge stuck otherwise), ``not_assembled`` (neither in the cavity's end),
``refused:<status>`` (an engine run refused; ``refused:drop`` when no drop came to rest) — never dropped.

Values: ``throws``, ``recoveries`` (recovery throws, counted in ``throws``), ``throws_to_assemble`` (nan if never), ``triangle_at``/``wedge_at`` (first throw after which
the triangle was captured / the wedge's CM past the lip, counted from the start of the trial), ``order``
(``triangle_first``, ``wedge_first``, ``same_throw``, ``none``), ``held_1``, ``held_k``, ``hold_breaks``, the end's
``pos_err_m``/``ang_err_rad`` (the wedge from its assembled pose), each part's ``<part>_x``, ``_y``, ``_side``,
``_tilt`` there (arm frame, m, rad; side as :func:`~throwmap.system.pose.state_from_pose`), ``mu``, ``drop_redraws``, ``lost``; serial:
``throws_first``, ``throws_second``.
"""

from __future__ import annotations

import functools
import math
from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field

from ..errors import InvalidStateError
from .base import Trial, seed_of
from .drop import DEFAULT_HEIGHT, Spread, drop_parts
from ..io.spec import Friction, Heights, NoiseSpec, Range, Rate
from .registry import register_experiment

__all__ = ["SEQUENTIAL", "SERIAL", "RecoverConfig", "SequentialAssembly", "SequentialConfig", "WedgeConfig", "build_stack",
           "drop_parts"]

Finite = Annotated[float, Field(allow_inf_nan=False)]


class WedgeConfig(BaseModel):
    """The second part (:func:`throwmap.design.stack.stack_part`; m, kg)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    top: Finite = Field(0.02, gt=0, le=0.1, description="top of the wedge above the triangle's apex, m")
    clearance: Finite = Field(0.001, ge=0, le=0.005, description="gap to the triangle's leg and the end wall, m")
    lead_mass: Finite = Field(0.05, ge=0, le=1.0, description="lead in the tip, kg (0: none)")
    lead_at: tuple[Finite, Finite] = Field((-0.005, 0.03), description="lead from the wedge's tip (x, y), m")


class RecoverConfig(BaseModel):
    """The recovery (closed loop, a one-bit sensor as the draft's Sec. VI). The sensor reads "stuck" after a throw
    that leaves the pair not assembled, both parts' CMs past the pocket's lip, and each part within ``still`` (m,
    its CM; and 10 × ``still`` rad) of where the throw found it — the *trap* of the module docstring, or the wedge
    leaning on the triangle's long leg. After ``confirm`` such readings in a row, tilt the arm by ``alpha`` (rad,
    + raises the end) at ``rate``, throw at ``omega`` there, and tilt back; then go on at the assembly rate.
    ``enabled`` false: open loop, the draft's experiment."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    enabled: bool = Field(True, strict=True, description="use the trap recovery (false: open loop)")
    alpha: Finite = Field(math.radians(10.0), gt=-0.8, lt=0.8, description="arm angle of the recovery throw, rad")
    omega: Finite = Field(4.56, gt=0, le=10, description="release rate of the recovery throw, rad/s")
    rate: Finite = Field(1.0, gt=0, le=10, description="tilt rate to and from alpha, rad/s")
    still: Finite = Field(0.01, gt=0, le=0.1, description="the sensor's 'did not move' tolerance, m (× 10: rad)")
    confirm: int = Field(1, ge=1, le=100, description="throws in a row the sensor must read 'trap'")
    false_positive: Finite = Field(0.0, ge=0, le=1, description="P(sensor reads 'trap' when it is not)")
    false_negative: Finite = Field(0.0, ge=0, le=1, description="P(sensor misses a trap)")


class SequentialConfig(BaseModel):
    """Config of ``assemble-sequential`` / ``assemble-serial`` (SI units). The pocket and the first part are
    ``experiment feed``'s built-in example (the recoil feeder); see the module docstring. The defaults are the
    built-in example, chosen as follows (serial, 12 trials each, seed 0):

    * the wedge: top 2 cm above the apex, 50 g of lead 0.5 cm in from the wall and 3 cm up from the tip — with
      115 g (lead at 0.37/4.35 cm) 6/12 assembled, with 50 g 9/12, with 30 g 8/12, with the 50 g 1.5 cm higher
      7/12; 50 g held the assembled pair 30 throws of 30 in two runs;
    * the pocket: the recoil feeder's as it was when this design was made (end wall μ 0, floor unlined, the arm's
      μ). The feeder's pocket is now lined (PTFE, μ 0.2 on wall and floor, ``experiment feed``); on it this design
      did worse (sequential 14 of the first 42 trials, serial 0 of the first 4: the wedge leans on the triangle's
      long leg or slides under the triangle), so it is pinned here;
    * drops 10 cm or more from the joint (``x_range`` [0.10, 0.25] m, the serial wedge's ``x_range_second``
      [0.10, 0.18] m): the wedge on its top (side 3) within 8 cm of the joint is thrown behind it (its throw map,
      engine and rigid_body alike: 4 of 94 serial trials were lost so), and two parts dropped together near the
      joint collide there (6 of 60 sequential trials lost a part within 6 throws with drops from 0 m);
    * the recovery (``recover``, see the module docstring) on: open loop the same design assembled 60/100
      (sequential) and 59/100 (serial), 58 of the 65 wrong orientations the trap;
    * ω the feeder's for both phases (``omega_second`` 4.3 rad/s: 6/12), μ_parts 0.5 (the engine's default;
      0.8 gave 9/12 as well);
    * ``settings``: no half-step rerun (``verify`` false). With it 6 of 12 trials of the first serial runs were
      refused as unconverged: two parts colliding are chaotic, the rerun lands them millimetres apart (a test of
      determinism, not of validity; as ``assemble``'s randomising throws); the penetration check stays (1 mm).
    """

    model_config = ConfigDict(extra="forbid", frozen=True)

    wedge: WedgeConfig = Field(default_factory=WedgeConfig)
    recover: RecoverConfig = Field(default_factory=RecoverConfig)
    omega: Rate | None = Field(None, description="release rate, rad/s (None: the feeder's 4.56)")
    omega_second: Rate | None = Field(None, description="serial: rate once the triangle is captured, "
                                                                 "rad/s (None: omega)")
    mu: Friction = Field(1.0, description="nominal arm–part friction of the pocket's arm (its h and length are the "
                                          "design's)")
    mu_parts: Finite = Field(0.5, ge=0, description="part–part friction")
    noise: NoiseSpec = Field(default_factory=lambda: NoiseSpec(omega_rel=0.03, mu_rel=0.1, realisation="recoil",
                                                                   zeta=0.2))
    height: Heights = Field(DEFAULT_HEIGHT, description="drop height of the lowest vertex, m")
    x_range: Range = Field((0.10, 0.25), description="CM abscissa range of the drops, m")
    x_range_second: Range = Field((0.10, 0.18), description="serial: the wedge's drop range, m")
    gap: Finite = Field(0.005, ge=0, description="least clearance between the dropped parts at release, m")
    max_throws: int = Field(150, ge=1, le=100_000, description="sequential: throws allowed until assembled")
    max_first: int = Field(100, ge=1, le=100_000, description="serial: throws allowed until the triangle is captured")
    max_second: int = Field(150, ge=1, le=100_000, description="serial: throws allowed until assembled")
    hold: int = Field(5, ge=1, le=1000, description="throws after assembly (retention after 1 and after hold)")
    pos_tol: Finite = Field(0.01, gt=0, description="assembled: wedge CM within this of its assembled pose, m")
    ang_tol: Finite = Field(0.1, gt=0, description="assembled: wedge angle within this of its assembled pose, rad")
    settings: dict | None = Field(default_factory=lambda: {"agreement": 0.005, "retries": 4, "verify": False},
                                  description="EngineSettings fields to override (feed's 5 mm agreement and 4 "
                                              "retries; no half-step rerun: see the class docstring)")


@functools.lru_cache(maxsize=4)
def _stack_cached(wedge_json: str, mu: float):
    from ..design.stack import design_stack
    from .feed import FEED, build_design

    w = WedgeConfig.model_validate_json(wedge_json)
    feeder = FEED.example()  # the recoil feeder; its pocket pinned as this design was made and measured on:
    pocket = feeder.cavity.model_copy(update={"wall_mu": 0.0, "lined": False})  # (feed's lined PTFE pocket: below)
    cavity = build_design(feeder.model_copy(update={"mu": mu, "cavity": pocket}))
    return design_stack(cavity, top=w.top, clearance=w.clearance, lead_mass=w.lead_mass, lead_at=w.lead_at)


def build_stack(cfg: SequentialConfig):
    """The :class:`~throwmap.design.stack.StackDesign` of a config (computed once per process)."""
    from ..errors import ThrowmapError

    try:
        return _stack_cached(cfg.wedge.model_dump_json(), float(cfg.mu))
    except ThrowmapError as err:
        raise InvalidStateError(f"config.wedge.{err.field.split('.')[-1]}", err.reason) from None


def _check(cfg: SequentialConfig, arm=None) -> None:
    """The config's ranges; with the design's ``arm`` (None: before the design is built) also against its length."""
    for name in ("x_range", "x_range_second", "height"):
        lo, hi = getattr(cfg, name)
        if not lo < hi:
            raise InvalidStateError(f"config.{name}", f"must be (low, high) with low < high, got {[lo, hi]}")
    if cfg.height[0] < 0:
        raise InvalidStateError("config.height", f"must be ≥ 0 m above the arm, got {list(cfg.height)}")
    for name in ("x_range", "x_range_second"):
        lo, hi = getattr(cfg, name)
        if lo < 0 or (arm is not None and hi > arm.length):
            where = "from x = 0 m (the joint) on" if arm is None else f"within [0, {arm.length:g}] m"
            raise InvalidStateError(f"config.{name}", f"must lie on the arm, {where} (CM abscissae of the drops), "
                                                      f"got {[lo, hi]}")


class SequentialAssembly:
    """The triangle and the wedge thrown into the pocket (``variant`` "sequential": together; "serial": one by one)."""

    config_type = SequentialConfig

    def __init__(self, variant: str):
        self.variant = variant
        self.name = "assemble-sequential" if variant == "sequential" else "assemble-serial"
        self.summary = (("the designed triangle and a four-sided wedge dropped together and thrown at the feeder's "
                         "rate until the wedge sits on the triangle in the pocket, a tilted recovery throw whenever "
                         "a one-bit sensor sees the pair stuck (recover.enabled = false: open loop, as the draft; "
                         "Sec. V-D)")
                        if variant == "sequential" else
                        ("the draft's serial variant of Sec. V-D: the triangle thrown alone until captured in the "
                         "pocket, then the wedge dropped and thrown until it sits on it"))

    def setup(self, cfg: SequentialConfig):
        """``(design, omega, omega_second)``."""
        from .feed import FEED

        _check(cfg)  # (before the design step: a bad range is refused at once)
        d = build_stack(cfg)
        _check(cfg, d.arm)
        w = FEED.example().omega if cfg.omega is None else cfg.omega
        return d, float(w), float(w if cfg.omega_second is None else cfg.omega_second)

    def trial(self, cfg: SequentialConfig, index: int, rng) -> Trial:
        from ..system.motion import TiltTo
        from ..system.pose import state_from_pose
        from ..throws.session import open_session
        from .feed import _settings

        d, omega, omega2 = self.setup(cfg)
        noise = cfg.noise.noise()
        settings = _settings(cfg)
        arm = noise.arm(d.arm, rng)
        tri, wedge = d.parts
        v = {"mu": arm.mu, "drop_redraws": 0, "throws": 0, "throws_to_assemble": math.nan, "triangle_at": math.nan,
             "wedge_at": math.nan, "order": "none", "held_1": math.nan, "held_k": math.nan, "hold_breaks": 0,
             "pos_err_m": math.nan, "ang_err_rad": math.nan, "lost": "", "recoveries": 0}
        if self.variant == "serial":
            v.update(throws_first=0, throws_second=0)

        def done(failure, run=None):
            if run is not None:
                for name, part, pose in zip(("triangle", "wedge"), d.parts, run.poses):
                    x, k, tilt = state_from_pose(part, pose)
                    v.update({f"{name}_x": x, f"{name}_y": float(pose[1]), f"{name}_side": k, f"{name}_tilt": tilt})
                if len(run.poses) == 2:
                    v["pos_err_m"], v["ang_err_rad"] = d.wedge_error(run.poses[1])
            v["order"] = _order(v["triangle_at"], v["wedge_at"])
            return Trial(index, seed_of(rng), failure is None, failure, dict(v))

        def lost(run):
            who = [f"{n}:{s.label}" for n, s in zip(("triangle", "wedge"), run.statuses) if s.label in
                   ("off_end", "behind_joint")]
            if who:
                v["lost"] = ",".join(who)
                return "ejected"
            return f"refused:{run.status.label}"

        sessions = []

        def spread(x_range):
            return Spread(x_range, cfg.height, cfg.gap)

        def start(run):
            """Throw the parts of ``run`` again and again from where it ended (one engine session)."""
            sessions.append(open_session(run.scene.parts, arm, run, ENGINE, settings=settings))
            return run

        def throw(run, w_nominal):
            return sessions[-1].throw(*noise.throw(w_nominal, rng)).run

        def tilt(motion):
            return sessions[-1].move(motion).run

        def note(run):
            t = v["throws"]
            if math.isnan(v["triangle_at"]) and d.triangle_captured(run.poses[0]):
                v["triangle_at"] = t
            if len(run.poses) == 2 and math.isnan(v["wedge_at"]) and d.in_cavity(1, run.poses[1]):
                v["wedge_at"] = t

        def at_cap(run):
            if len(run.poses) == 2 and d.in_cavity(1, run.poses[1]):
                return "wrong_orientation"
            if d.in_cavity(0, run.poses[0]) and not d.triangle_captured(run.poses[0]):
                return "wrong_orientation"
            return "not_assembled"

        if self.variant == "sequential":
            run, v["drop_redraws"] = drop_parts((tri, wedge), arm, rng, spread=spread(cfg.x_range),
                                                fixtures=d.fixtures, mu_parts=cfg.mu_parts, settings=settings)
            if int(run.status) != 0:
                return done("refused:drop")
            start(run)
            cap, w_assemble = cfg.max_throws, omega
        else:
            run, v["drop_redraws"] = drop_parts((tri,), arm, rng, spread=spread(cfg.x_range), fixtures=d.fixtures,
                                                mu_parts=cfg.mu_parts, settings=settings)
            if int(run.status) != 0:
                return done("refused:drop")
            start(run)
            while not d.triangle_captured(run.poses[0]):
                if v["throws"] >= cfg.max_first:
                    return done(at_cap(run), run)
                run = throw(run, omega)
                v["throws"] += 1
                v["throws_first"] = v["throws"]
                if int(run.status) != 0:
                    return done(lost(run), run)
                note(run)
            run, r2 = drop_parts((wedge,), arm, rng, spread=spread(cfg.x_range_second), fixtures=d.fixtures,
                                 fixed=((tri, tuple(run.poses[0])),), mu_parts=cfg.mu_parts, settings=settings)
            v["drop_redraws"] += r2
            if int(run.status) != 0:
                return done("refused:drop")
            start(run)
            cap, w_assemble = cfg.max_second, omega2
        n0 = v["throws"]
        rec, seen, before = cfg.recover, 0, None
        while not d.assembled(run.poses, pos_tol=cfg.pos_tol, ang_tol=cfg.ang_tol):
            if v["throws"] - n0 >= cap:
                return done(at_cap(run), run)
            if rec.enabled and before is not None:
                seen = seen + 1 if _reads_stuck(d, before, run.poses, rec, rng) else 0
            before = run.poses
            if seen >= rec.confirm:  # tilt, throw there, tilt back (one throw)
                seen, before = 0, None
                v["recoveries"] += 1
                run = tilt(TiltTo(rec.alpha, rec.rate))
                if int(run.status) == 0:
                    run = throw(run, rec.omega)
                if int(run.status) == 0:
                    run = tilt(TiltTo(-run.alpha, rec.rate))
            else:
                run = throw(run, w_assemble)
            v["throws"] += 1
            if self.variant == "serial":
                v["throws_second"] = v["throws"] - n0
            if int(run.status) != 0:
                return done(lost(run), run)
            note(run)
        v["throws_to_assemble"] = v["throws"]
        end, held = run, []
        for _ in range(cfg.hold):
            r = throw(end, w_assemble)
            good = int(r.status) == 0 and d.assembled(r.poses, pos_tol=cfg.pos_tol, ang_tol=cfg.ang_tol)
            held.append(good)
            if int(r.status) != 0:
                break
            end = r
        held += [False] * (cfg.hold - len(held))
        v["held_1"], v["held_k"], v["hold_breaks"] = float(held[0]), float(all(held)), int(held.count(False))
        return done(None, run)

    def parameters(self, cfg: SequentialConfig) -> dict:
        d, omega, omega2 = self.setup(cfg)
        out = {"variant": self.variant, "design": d.to_dict(), "omega_rad_s": omega, "mu": cfg.mu,
               "mu_parts": cfg.mu_parts, "noise": cfg.noise.noise().to_dict(),
               "drop": {"height_m": list(cfg.height), "x_range_m": list(cfg.x_range), "gap_m": cfg.gap},
               "recover": cfg.recover.model_dump(), "hold": cfg.hold, "tolerance": {"pos_m": cfg.pos_tol, "ang_rad": cfg.ang_tol},
               "engine": {"pymunk overrides": cfg.settings or {}},
               "success": ("the triangle flat on side 0 in the pocket and the wedge within tolerance of its assembled "
                           "pose within the throw caps")}
        if self.variant == "serial":
            out.update(omega_second_rad_s=omega2, max_first=cfg.max_first, max_second=cfg.max_second,
                       x_range_second_m=list(cfg.x_range_second))
        else:
            out["max_throws"] = cfg.max_throws
        return out


def _reads_stuck(d, before, after, rec: RecoverConfig, rng) -> bool:
    """The recovery's one-bit sensor (:class:`RecoverConfig`; read while the pair is not assembled): both parts'
    CMs past the lip ``after`` a throw and neither moved from ``before`` by more than ``rec.still`` (m; × 10 rad), read with the
    configured error rates."""
    from ..design.stack import wrap

    stuck = (d.in_cavity(0, after[0]) and d.in_cavity(1, after[1])
             and all(math.hypot(a[0] - b[0], a[1] - b[1]) <= rec.still
                     and abs(wrap(a[2] - b[2])) <= 10.0 * rec.still for a, b in zip(after, before)))
    if stuck:
        return not (rec.false_negative > 0 and rng.random() < rec.false_negative)
    return bool(rec.false_positive > 0 and rng.random() < rec.false_positive)


def _order(a: float, b: float) -> str:
    if math.isnan(a) and math.isnan(b):
        return "none"
    if math.isnan(b) or (not math.isnan(a) and a < b):
        return "triangle_first"
    if math.isnan(a) or b < a:
        return "wedge_first"
    return "same_throw"


SEQUENTIAL = register_experiment(SequentialAssembly("sequential"))
SERIAL = register_experiment(SequentialAssembly("serial"))


ENGINE = "engine"
"""The model of the sequential trials: the pair in the pocket keeps its poses from throw to throw (engine runs)."""
