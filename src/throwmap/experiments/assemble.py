"""Experiment ``assemble``: sensor-switched self-assembly of two triangles at the wall (paper Sec. VI, Fig. 11).

The draft put two same-handed 17 cm 30-60-90 triangles on one arm with a frictionless vertical wall at
its end, threw them with high throws until a one-bit vision sensor saw part *a* resting on its longer
leg wholly left of part *b* resting on its hypotenuse, then lowered the arm to α = −10° and threw low
until *b* jogged to the wall and *a* slid under it: 14/20 = 70 %, failing by a wrong switch and by the
tilt disturbing the parts. One trial here (pymunk engine, both parts in one scene):

1. **drop** both parts from random non-overlapping poses (φ uniform, CM x uniform over ``x_range``, lowest
   vertex 2–10 cm up) and let them settle together (:func:`drop_pair`; redrawn, at most 20 times, until
   both rest on the arm);
2. **randomise** (arm at α = 0): look with the pair sensor (:class:`throwmap.control.pair_sensors.PairSensor`;
   ``confirm`` readings "ready" in a row switch, a look costs no throw; a pair already assembled switches
   too); else throw at a rate uniform over ``omega_high`` (3 % ω jitter, the recoil arm), below ``near_cap``
   while a part's CM is within ``near_x`` of the joint, a ``kick`` that marches a flat hypotenuse out from
   within ``kick_x``; and break the arm's two sinks when a throw left the pair unchanged (to 1 cm): a part
   standing on its shorter leg at the wall (CM ≥ ``wall_x``) gets an **escape** throw (tilt to
   ``escape_alpha``, throw at ``escape_omega``, tilt back), a part within ``slide_x`` of the joint a
   **slide** (tilt to −``slide_alpha``, past the friction angle, and back: both slide to the wall);
3. **switch**: tilt the arm to ``alpha`` at ``tilt_rate`` (:class:`throwmap.engine.TiltTo`);
4. **assemble**: throw at ``omega_low`` until the pair is assembled (:func:`~throwmap.control.pair_sensors.is_assembled`:
   each CM within ``pos_tol`` and each angle within ``ang_tol`` of :func:`throwmap.statics.assembly.assembled_pair`),
   at an ``approach`` rung's rate while the leftmost part is short of its x; when ``stall_low`` throws in a
   row move no CM more than ``still_m`` (a wrong stack), tilt back to 0 and randomise again (at most
   ``resets`` times); then ``hold`` more low throws (retention after 1 and after ``hold``).

**Success** = assembled within ``max_high`` randomising + ``max_low`` assembling throws. Failures (first
that applies): ``no_switch`` (the sensor never fired), ``wrong_switch`` (it fired while the pair was not
ready), ``disrupted_by_tilt`` (ready before the tilt, not after), ``ejected`` (a part left the arm: off the
end over the wall, or behind the joint), ``wrong_orientation`` (low throws ended with a part off its
assembly side: *a* not on its longer leg or *b* neither flat on its hypotenuse nor assembled),
``not_assembled`` (right sides, not within tolerance), ``refused:<status>`` (an engine run refused:
penetration, unconverged, timeout; ``refused:drop`` when no drop came to rest).

Values: ``throws_high``, ``throws_low``, ``throws``, ``looks``, ``held_1``, ``held_hold`` (1/0, nan when
not assembled), ``pos_err_m``/``ang_err_rad`` at the end, ``mu``, ``drop_redraws``, ``lost``
(``off_end``/``behind_joint`` for an ejection, else ""), ``escapes``, ``slides``, ``resets``, ``phase``
(where the trial ended: drop, high, tilt, low, hold).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field

from ..conventions import G
from ..errors import InvalidStateError, ThrowmapError
from .base import Trial, seed_of
from .drop import DEFAULT_HEIGHT, Spread, drop_kind, drop_parts
from ..io.spec import ArmSpec, Heights, NoiseSpec, Range, RateRange, Spec, WallSpec
from .registry import register_experiment

__all__ = ["ASSEMBLE", "Assemble", "AssembleConfig", "PairSensorConfig", "drop_pair", "lean_bound"]

Finite = Annotated[float, Field(allow_inf_nan=False)]
Rate = Annotated[float, Field(ge=0, lt=1, allow_inf_nan=False)]


class PairSensorConfig(BaseModel):
    """The pair sensor's errors (independent at every read)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    false_positive: Rate = Field(0.0, description="P(reads 'ready' | not ready) per read")
    false_negative: Rate = Field(0.0, description="P(reads 'not ready' | ready) per read")
    confirm: int = Field(1, ge=1, le=100, description="readings 'ready' in a row needed to switch (extra looks)")


class AssembleConfig(Spec):
    """Config of ``assemble`` (SI units, rad). The defaults are the built-in example, with the values the draft
    leaves blank chosen as follows:

    * ``length`` 0.5 m, ``h`` −1 cm, μ = 1 ± 10 % (the draft's arm, measured μ > 1 "for our system"): room for
      both 17 cm triangles (assembled they fill [L − 0.147, L]) and for *a* wholly left of *b*;
    * ``wall_height`` 0.80 m: above the energy bound of the fastest throw, a kick, ω²L²/2g = 0.70 m at 7.4 rad/s,
      so no part flies over it; ``wall_mu`` 0 (the draft's frictionless wall, Fig. 13);
    * randomising at α = 0 with ``omega_high`` uniform over 3–6 rad/s (one fixed rate has a limit set that
      avoids the hypotenuse: at 3 rad/s no "ready" pair in 480 throws), ``near_cap`` 4 rad/s while a CM is
      within ``near_x`` = 22 cm of the joint (side 2 at 12–18 cm lands behind the joint from 5.5–6.5 rad/s).
      One part's throw here is almost deterministic (engine, sides × 13 x × 21 rates × 3 noisy repeats): a
      flip moves a part 6–8 cm *in*, a jog 0–3 cm *out*, so the arm has two sinks: near the joint (side 0
      at 12–15 cm stays on it at every rate ≤ 7.5 rad/s, jogging +1 / +3 cm at 7 rad/s from 12 / 15 cm, none at
      ≤ 4) and at the wall (a part standing on its shorter leg with CM ≥ 39 cm stays there at every rate).
      Hence ``kick`` 7 rad/s for a flat hypotenuse within ``kick_x`` = 20 cm (it marches out: +3 cm from 15,
      +5 from 18 cm), only when the other CM is ``kick_clear`` = 12 cm farther out and no shorter leg is within
      ``near_x`` (kicks with the other part leaning on the kicked one, or at 9.8 cm tilted, threw a part
      behind the joint in 2 trials); an **escape** when a throw left a part standing at the wall
      (CM ≥ ``wall_x`` = 40 cm): tilt to ``escape_alpha`` = +5° (at 1 rad/s), throw at ``escape_omega``
      = 4 rad/s, tilt back — single part at 47 cm, +5°: 3 / 4 / 5 / 6 rad/s land it on the hypotenuse at
      31 / 28 / 25 / 21 cm, 7 behind the joint; an escape at +6°, 6.5 rad/s threw the *other* part behind the
      joint in 4 of 6 trials, at +5°, 4 rad/s those 4 trials assembled; a **slide** whenever a CM is
      within ``slide_x`` = 13 cm (no side flips there, and a hypotenuse creeps in: 10.1 → 9.8 cm, then lost): tilt to −55° at 2 rad/s (past the friction angle, atan 1.1 = 48°), both
      slide to the wall, and back (a leaning pair at 10–16 cm crept 1 mm a throw over the joint; with the
      slide that trial assembled). Uniform rates alone (this low phase): 10/20, ``no_switch`` 5, ``ejected`` 5;
    * the switch (``rectangle``): "ready" also when the pair is already the assembled rectangle anywhere on the
      arm (:func:`~throwmap.control.pair_sensors.is_rectangle`): high throws at α = 0 make it (4 of the 10
      successes above were assembled during randomising; in a no_switch trial it formed away from the wall 4
      throws running), and the low throws carry it to the wall: 6/6 hand-placed rectangles shifted 5 / 15 /
      25 cm in (μ 0.9, 1.1) assembled in 3 / 12 / 26–27 throws. ``a_min_x`` 15 cm: *a* nearer the joint
      needed a rung (12 cm, 3.2 rad/s) that makes *b* lean and flip at the wall (4 of 100 trials refused as
      unconverged, 4 wrong_orientation after 150 low throws in a previous version);
    * ``alpha`` −10° (the draft's); ``tilt_rate`` 0.1 rad/s: lowering at rate ṙ drops the arm away from a part
      at radius r at r·ṙ, which it hits at that speed — 4.5 cm/s at r = 0.45 m, a tenth of a low throw;
    * ``omega_low`` 1.9 rad/s, between two engine limits: the assembled pair at the wall (α = −10°) holds
      under 20 throws at 2.0 rad/s (3 % jitter) but tips *b* over after 3–4 throws at 2.2 and 2.4 rad/s; and
      *a* must still jog in from near the joint (at 2.0 rad/s 1.3 mm from 15 cm, 9 mm from 25 cm: 8/8
      hand-placed ready pairs assembled in 22–77 throws; at 1.6 rad/s 0.6 / 5 mm). Leaning is no limit here:
      *b* flat on its hypotenuse at the wall leans at most 0.05 rad in a throw at 2.1 rad/s (engine, μ = 1.1),
      far below β* = 0.43 rad, the least lean it can hold (Fig. 13, :func:`throwmap.statics.lean_free_beta`
      at μ = 1.1, α = −10°; the draft's "β < 0.25 rad"); :func:`lean_bound` (all of a throw's kinetic energy
      at r = L into the lean) allows 1.76 rad/s and is only sufficient; ``max_low`` 150;
    * ``approach`` rung (25 cm, 2.4 rad/s): *a* left near the joint barely moves at 1.9 rad/s (3 of the first 6
      trials of a run without it ended with *a* parked 30 cm short); with it 7/8 hand-placed ready pairs with *a*
      at 10–22 cm assembled in 15–81 throws (a rung (20 cm, 3 rad/s) was refused as unconverged in 4/8);
      *b* alone at the wall leans 0.37 rad at 3.7 rad/s and sticks leaning at 4.2 (0.79 rad), so no faster;
    * ``stall_low`` 8 throws moving no CM more than ``still_m`` 1 mm, then tilt back and randomise (``resets``
      3): the wrong stacks the low throws cannot undo (*b* on *a*'s hypotenuse on its longer leg, 150 throws
      without a change) are static;
    * ``mu_parts`` 0.5 (the engine's default part–part μ); tolerances 5 mm and 0.05 rad;
    * the drop and the randomising throws run without half-step verification (``verify_high``: two parts
      colliding are chaotic, the rerun at half the step lands them millimetres apart — a test of determinism,
      not of validity; their outcome only has to be a plausible random state), without exact-flight leaps
      (``exact_flight_high``: a leap let the two parts fly into each other, refused for 4–24 mm part–part
      penetration in 13 of 57 trials of a first run; the same throw stepped sinks 0.33 mm: an engine fault
      since fixed: leaps measured part-part distances on stale shape vertices, see
      :mod:`throwmap.engine.pymunk.stepping`; the setting is kept as measured) and with
      ``penetration_tol_high`` 2 mm; the tilt (half-step agreement ``tilt_agreement``) and the low throws
      use the engine's defaults (verified).
    """

    model_config = ConfigDict(extra="forbid", frozen=True)

    part: str = Field("triangle", description="a built-in part name or a .toml/.json part file (a right triangle)")
    arm: ArmSpec = Field(default_factory=lambda: ArmSpec(h=-0.01, length=0.50, mu=1.0),
                         description="the arm (its length is the wall's face), nominal μ")
    mu_parts: Finite = Field(0.5, ge=0, description="part–part friction")
    wall: WallSpec = Field(default_factory=lambda: WallSpec(height=0.80, mu=0.0), description="the end wall")
    omega_high: RateRange = Field((3.0, 6.0), description="randomising release rate, uniform over "
                                                                       "(low, high) per throw, rad/s")
    near_x: Finite = Field(0.22, ge=0, description="a part's CM within this of the joint: randomise below near_cap, m")
    near_cap: Finite = Field(4.0, gt=0, description="highest randomising rate with a part near the joint, rad/s")
    tilted_cap: Finite = Field(4.5, gt=0, description="highest randomising rate with a part tilted, rad/s")
    kick: Finite = Field(7.0, gt=0, description="release rate of a kick, rad/s")
    kick_x: Finite = Field(0.20, ge=0, description="a part flat on its hypotenuse within this of the joint: kick, m")
    kick_clear: Finite = Field(0.12, ge=0, description="kick only with the other CM this much farther out, m")
    wall_x: Finite = Field(0.40, description="a part standing on its shorter leg with its CM beyond this is stuck "
                                            "at the wall: escape throw, m")
    escape_alpha: Finite = Field(math.radians(5.0), gt=0, lt=0.5, description="arm angle of an escape throw, rad")
    escape_omega: Finite = Field(4.0, gt=0, description="release rate of an escape throw, rad/s")
    slide_x: Finite = Field(0.13, ge=0, description="a part's CM within this of the joint: slide both to the "
                                                   "wall (0: never), m")
    slide_alpha: Finite = Field(math.radians(55.0), gt=0, lt=1.5, description="arm angle of a slide, rad")
    slide_rate: Finite = Field(2.0, gt=0, description="tilt rate of a slide, rad/s")
    penetration_tol_high: Finite = Field(0.002, gt=0, description="engine penetration_tol of the drop and the "
                                                                 "randomising throws, m")
    omega_low: Finite = Field(1.9, gt=0, description="assembling release rate, rad/s")
    approach: list[tuple[Finite, Finite]] = Field(default_factory=lambda: [(0.25, 2.4)],
                                                  description="rungs (x m, ω rad/s): the leftmost part's CM short "
                                                              "of x: assembling throws at ω")
    alpha: Finite = Field(math.radians(-10.0), gt=-math.pi / 4, lt=0, description="assembly rest angle, rad")
    tilt_rate: Finite = Field(0.1, gt=0, description="rate the arm is lowered at, rad/s")
    tilt_agreement: Finite = Field(0.002, gt=0, le=0.005, description="the tilt's half-step agreement, m (the low "
                                   "throws keep the engine's 0.5 mm): a faster tilt jolts both parts into a slide "
                                   "whose end moves ~1 mm with the step (0.3 rad/s: 10 of 25 tilts refused at "
                                   "0.5 mm); 2 mm is well inside the 5 mm the assembled test allows")
    sensor: PairSensorConfig = Field(default_factory=PairSensorConfig)
    noise: NoiseSpec = Field(default_factory=lambda: NoiseSpec(omega_rel=0.03, mu_rel=0.1, realisation="recoil"))
    height: Heights = Field(DEFAULT_HEIGHT, description="drop height of the lowest vertex, m")
    x_range: Range = Field((0.12, 0.40), description="CM abscissa range of the drop, m")
    gap: Finite = Field(0.005, ge=0, description="least clearance between the dropped parts at release, m")
    max_high: int = Field(150, ge=0, le=100_000, description="randomising throws allowed")
    max_low: int = Field(150, ge=1, le=100_000, description="assembling throws allowed")
    hold: int = Field(5, ge=1, le=1000, description="low throws after assembly (retention)")
    pos_tol: Finite = Field(0.005, gt=0, description="assembled: CM within this of assembled_pair, m")
    ang_tol: Finite = Field(0.05, gt=0, description="assembled: angle within this of assembled_pair, rad")
    rectangle: bool = Field(True, strict=True, description="the sensor also reads 'ready' for a rectangle away from the wall")
    a_min_x: Finite = Field(0.15, ge=0, description="ready: a's CM at least this from the joint, m")
    stall_low: int = Field(8, ge=1, le=1000, description="low throws moving no CM more than still_m: tilt back "
                                                         "and randomise again")
    still_m: Finite = Field(0.001, gt=0, description="a low throw moving no CM more than this is still, m")
    resets: int = Field(3, ge=0, le=100, description="tilts back to randomising allowed")
    verify_high: bool = Field(False, strict=True, description="half-step verification of the drop and the randomising throws")
    exact_flight_high: bool = Field(False, strict=True, description="exact-flight leaps in the drop and the randomising throws")
    settings: dict | None = Field(None, description="EngineSettings fields to override")


def lean_bound(part, *, alpha: float, mu: float, length: float, h: float = 0.0, g: float = G) -> dict:
    """The release rate below which part *b* cannot lean against the wall (Fig. 13): β* =
    :func:`~throwmap.statics.lean_free_beta` (the least lean it can hold), the CM's rise to lean β* from flat
    along −g (m), and ω = √(2 g rise) / ``length`` (``g`` m/s²) (rad/s; a throw gives a point at r ≤ L at most (ωL)²/2 of
    kinetic energy per unit mass)."""
    from ..statics import edge_frame_cm, lean_free_beta, leaning_bodies

    a, b, _ = edge_frame_cm(part)
    beta = lean_free_beta(a, b, alpha, mu)
    if beta >= math.pi / 2:
        return {"beta_star_rad": beta, "rise_m": math.inf, "omega_rad_s": math.inf}
    (lean,), _ = leaning_bodies(part, beta, length=length, h=h, mu_arm=mu)
    (flat,), _ = leaning_bodies(part, 1e-9, length=length, h=h, mu_arm=mu)
    rise = (lean.y - flat.y) * math.cos(alpha) + (lean.x - flat.x) * math.sin(alpha)
    return {"beta_star_rad": float(beta), "rise_m": float(rise), "omega_rad_s": math.sqrt(2 * g * rise) / length}


def _setup(cfg: AssembleConfig):
    from ..io.config import resolve_part
    from ..statics.assembly import legs

    try:
        part = resolve_part(cfg.part).part
        legs(part)
    except ThrowmapError as err:
        raise InvalidStateError("config.part", err.reason) from None
    arm = cfg.arm.arm(field="config.arm.h")
    if arm.length is None:
        raise InvalidStateError("config.arm.length", "required: the wall stands at the arm's end")
    lo, hi = cfg.x_range
    if not (lo < hi and hi > 0 and lo < arm.length):
        raise InvalidStateError("config.x_range", f"must be (low, high), low < high, on the arm [0, {arm.length:g}] m")
    return part, arm, cfg.wall.wall()


def _settings(cfg: AssembleConfig):
    """``(high, low)`` EngineSettings: the overrides, the high ones without half-step verification unless asked."""
    import dataclasses

    from ..engine.settings import EngineSettings
    from .feed import _settings as feed_settings

    base = feed_settings(cfg) or EngineSettings()
    high = dataclasses.replace(base, penetration_tol=cfg.penetration_tol_high, exact_flight=cfg.exact_flight_high)
    return (high if cfg.verify_high else dataclasses.replace(high, verify=False)), base


def _kind(status, message: str = "", values=None) -> str:
    if values is not None and status.label in ("off_end", "behind_joint"):
        values["lost"] = status.label
    return "ejected" if status.label in ("off_end", "behind_joint") else (drop_kind(status, 0.0, message)
                                                                          or f"refused:{status.label}")


def _coarse(run) -> tuple:
    """The pair's rest state: CM abscissae to 1 cm and sides, sorted (unchanged by a throw: stuck)."""
    return tuple(sorted((round(float(x), 2), int(k)) for x, k, _ in run.states))


def _uniform_rate(cfg: AssembleConfig, run, rng) -> float:
    """The randomising rate: uniform over ``omega_high``, capped at ``near_cap`` while a part's CM is within
    ``near_x`` of the joint and at ``tilted_cap`` while a part is tilted (leaning on the wall or the other
    part); a ``kick`` while a part lies flat on its hypotenuse at ``slide_x``–``kick_x`` from the joint, the
    other part flat, its CM ``kick_clear`` or more farther out, and no shorter leg within ``near_x``."""
    near = min(s[0] for s in run.states) < cfg.near_x
    tilted = any(abs(t) >= 0.02 for _, _, t in run.states)
    top = min(cfg.omega_high[1], cfg.near_cap) if near else cfg.omega_high[1]
    top = min(top, cfg.tilted_cap) if tilted else top
    nominal = float(rng.uniform(cfg.omega_high[0], max(top, cfg.omega_high[0])))
    (x0, k0, _), (x1, _, _) = sorted(((float(x), int(k), float(t)) for x, k, t in run.states), key=lambda q: q[0])
    if (k0 == 0 and not tilted and cfg.slide_x <= x0 < cfg.kick_x and x1 - x0 >= cfg.kick_clear
            and not any(k == 2 and x < cfg.near_x for x, k, _ in run.states)):
        nominal = cfg.kick  # the hypotenuse creeps inward near the joint at lower rates: march it out
    return nominal


def _stuck_at_wall(cfg: AssembleConfig, run) -> bool:
    """A part standing flat on its shorter leg with its CM at ``wall_x`` or beyond (no throw at α = 0 moves it)."""
    return any(k == 2 and abs(t) < 0.02 and x >= cfg.wall_x for x, k, t in run.states)


def _throw_low(cfg: AssembleConfig, run, noise, rng, advance, settings, phase: str):
    """One assembling throw at ``omega_low`` or an ``approach`` rung's rate, from where ``run`` ended."""
    x_left, nominal = min(s[0] for s in run.states), cfg.omega_low
    for x, w in cfg.approach:
        if x_left < x:
            nominal = w
            break
    return advance(noise.throw(nominal, rng), settings, phase, nominal)

class Assemble:
    """Drop two triangles, randomise until the pair sensor fires, tilt, assemble at the wall with low throws."""

    name = "assemble"
    summary = ("two same-handed triangles on an arm with a wall at its end: high throws until a one-bit sensor sees "
               "a on its longer leg left of b on its hypotenuse, tilt to alpha, low throws; success = assembled "
               "(Sec. VI)")
    config_type = AssembleConfig

    def trial(self, cfg: AssembleConfig, index: int, rng, *, observer=None) -> Trial:
        """One trial. ``observer(phase, run, omega)``, if given, is called after every engine run, ``phase`` one
        of ``"drop"``, ``"high"``, ``"escape"`` (the arm tilted to ``escape_alpha`` before an escape throw, which
        is a ``"high"`` run, and back to 0 after it), ``"slide"`` (the arm tilted to −``slide_alpha`` and back),
        ``"tilt"``, ``"low"``, ``"reset"`` (the arm tilted back to 0 after a stalled assembly, before randomising
        again), ``"hold"``; ``omega`` the nominal rate (rad/s; 0 for the drop and the tilts); with an observer the
        runs record their trajectories (``run.trajectory``)."""
        from ..control.pair_sensors import LONG_LEG, PairSensor, assembled_error, is_assembled
        from ..system.motion import TiltTo
        from ..system.pose import state_from_pose
        from ..throws.session import open_session

        session = None

        def advance(throw, settings, phase="high", omega=0.0):
            """The session's next engine run: ``throw`` = ``(ω, motion)`` of a throw, or a :class:`TiltTo`."""
            record = observer is not None
            if isinstance(throw, TiltTo):
                step = session.move(throw, settings=settings, record=record)
            else:
                step = session.throw(throw[0], throw[1], settings=settings, record=record)
            if observer is not None:
                observer(phase, step.run, omega)
            return step.run

        part, arm, wall = _setup(cfg)
        noise = cfg.noise.noise()
        high, low = _settings(cfg)
        tilt_settings = dataclasses.replace(low, agreement=cfg.tilt_agreement)
        arm = noise.arm(arm, rng)
        sensor = PairSensor(cfg.sensor.false_positive, cfg.sensor.false_negative, cfg.a_min_x,
                            arm.h if cfg.rectangle else None)
        L, h = arm.length, arm.h
        v = {"mu": arm.mu, "drop_redraws": 0, "throws_high": 0, "throws_low": 0, "throws": 0, "looks": 0,
             "held_1": math.nan, "held_hold": math.nan, "pos_err_m": math.nan, "ang_err_rad": math.nan,
             "lost": "", "escapes": 0, "slides": 0, "resets": 0, "phase": "drop"}

        def done(success, failure, run=None):
            if run is not None:
                v["pos_err_m"], v["ang_err_rad"] = assembled_error(part, run.poses, length=L, h=h)
            v["throws"] = v["throws_high"] + v["throws_low"]
            return Trial(index, seed_of(rng), success, failure, dict(v))

        def ok(r):
            return is_assembled(part, r.poses, length=L, h=h, pos_tol=cfg.pos_tol, ang_tol=cfg.ang_tol)

        def ready(poses):
            return sensor.truth(part, poses)

        run, v["drop_redraws"] = drop_parts((part, part), arm, rng, spread=Spread(cfg.x_range, cfg.height, cfg.gap),
                                            fixtures=(wall,), mu_parts=cfg.mu_parts, settings=high,
                                            record=observer is not None)
        if observer is not None:
            observer("drop", run, 0.0)
        if int(run.status) != 0:
            return done(False, "refused:drop")
        session = open_session((part, part), arm, run, ENGINE)  # each run starts where the last one ended
        while True:
            # -- randomise until the sensor says "ready" confirm times in a row (or the pair is assembled already)
            v["phase"] = "high"
            switched, key = False, None
            while True:
                if ok(run):
                    switched = True
                    break
                streak = 0
                for _ in range(cfg.sensor.confirm):
                    v["looks"] += 1
                    if not sensor.read(part, run.poses, rng):
                        break
                    streak += 1
                if streak == cfg.sensor.confirm:
                    switched = True
                    break
                if v["throws_high"] >= cfg.max_high:
                    break
                if cfg.slide_x > 0 and min(x for x, _, _ in run.states) < cfg.slide_x:
                    # near the joint no throw moves the parts out (they creep in): slide them to the wall
                    for turn in (-cfg.slide_alpha, cfg.slide_alpha):
                        run = advance(TiltTo(turn, cfg.slide_rate), high, "slide")
                        if int(run.status) != 0:
                            return done(False, _kind(run.status, run.message, v))
                    v["slides"] += 1
                    key = None
                    continue
                if _stuck_at_wall(cfg, run) and _coarse(run) == key:
                    # escape: tilt up, throw, tilt back (at alpha = 0 no rate moves a part standing at the wall)
                    run = advance(TiltTo(cfg.escape_alpha, cfg.tilt_rate * 10), high, "escape")
                    if int(run.status) != 0:
                        return done(False, _kind(run.status, run.message, v))
                    nominal = cfg.escape_omega
                    v["escapes"] += 1
                else:
                    nominal = _uniform_rate(cfg, run, rng)
                key = _coarse(run)
                run = advance(noise.throw(nominal, rng), high, "high", nominal)
                v["throws_high"] += 1
                if int(run.status) != 0:
                    return done(False, _kind(run.status, run.message, v))
                if run.alpha != 0.0:
                    run = advance(TiltTo(-run.alpha, cfg.tilt_rate * 10), high, "escape")
                    if int(run.status) != 0:
                        return done(False, _kind(run.status, run.message, v))
            if not switched:
                return done(False, "no_switch", run)
            if not ok(run) and not ready(run.poses):
                return done(False, "wrong_switch", run)
            # -- tilt to alpha
            v["phase"] = "tilt"
            run = advance(TiltTo(cfg.alpha - run.alpha, cfg.tilt_rate), tilt_settings, "tilt")
            if int(run.status) != 0:
                return done(False, _kind(run.status, run.message, v), run)
            if not ok(run) and not ready(run.poses):
                return done(False, "disrupted_by_tilt", run)
            # -- low throws until assembled, or until the pair stalls (then tilt back and randomise again)
            v["phase"] = "low"
            assembled, still = ok(run), 0
            while not assembled and v["throws_low"] < cfg.max_low and still < cfg.stall_low:
                before = run.poses
                run = _throw_low(cfg, run, noise, rng, advance, low, "low")
                v["throws_low"] += 1
                if int(run.status) != 0:
                    return done(False, _kind(run.status, run.message, v), run)
                assembled = ok(run)
                moved = max(math.hypot(q[0] - p[0], q[1] - p[1]) for p, q in zip(before, run.poses))
                still = still + 1 if moved < cfg.still_m else 0
            if assembled:
                break
            if still >= cfg.stall_low and v["resets"] < cfg.resets and v["throws_high"] < cfg.max_high:
                v["resets"] += 1
                run = advance(TiltTo(-run.alpha, cfg.tilt_rate), tilt_settings, "reset")
                if int(run.status) != 0:
                    return done(False, _kind(run.status, run.message, v), run)
                continue
            st = [state_from_pose(part, q) for q in run.poses]
            on_sides = sorted(k for _, k, _ in st) == [0, LONG_LEG] and any(
                k == LONG_LEG and abs(t) < 0.05 for _, k, t in st)
            return done(False, "not_assembled" if on_sides else "wrong_orientation", run)
        # -- retention (not part of success; a refused hold throw counts as not held)
        v["phase"] = "hold"
        end, held = run, []
        for _ in range(cfg.hold):
            r = _throw_low(cfg, end, noise, rng, advance, low, "hold")
            good = int(r.status) == 0 and ok(r)
            held.append(good)
            if int(r.status) != 0:
                break
            end = r
        held += [False] * (cfg.hold - len(held))
        v["held_1"], v["held_hold"] = float(held[0]), float(all(held))
        return done(True, None, run)

    def parameters(self, cfg: AssembleConfig) -> dict:
        part, arm, wall = _setup(cfg)
        hi_mu = arm.mu * (1 + 2 * cfg.noise.mu_rel) if cfg.noise.mu_range is None else cfg.noise.mu_range[1]
        return {"part": part.name, "part_mass_kg": part.mass, "h_m": arm.h, "length_m": arm.length, "mu": arm.mu,
                "mu_parts": cfg.mu_parts, "wall": {"height_m": wall.height, "mu": wall.mu},
                "omega_high_rad_s": list(cfg.omega_high), "near": {"x_m": cfg.near_x, "cap_rad_s": cfg.near_cap},
                "tilted_cap_rad_s": cfg.tilted_cap,
                "kick": {"x_m": [cfg.slide_x, cfg.kick_x], "clear_m": cfg.kick_clear, "omega_rad_s": cfg.kick},
                "escape": {"wall_x_m": cfg.wall_x, "alpha_rad": cfg.escape_alpha, "omega_rad_s": cfg.escape_omega},
                "slide": {"x_m": cfg.slide_x, "alpha_rad": -cfg.slide_alpha, "rate_rad_s": cfg.slide_rate},
                "switch": {"rectangle": cfg.rectangle, "a_min_x_m": cfg.a_min_x},
                "low_stall": {"throws": cfg.stall_low, "still_m": cfg.still_m, "resets": cfg.resets},
                "omega_low_rad_s": cfg.omega_low, "approach": [list(r) for r in cfg.approach], "alpha_rad": cfg.alpha, "tilt_rate_rad_s": cfg.tilt_rate,
                "lean_bound": lean_bound(part, alpha=cfg.alpha, mu=min(hi_mu, arm.mu * 1.1), length=arm.length,
                                         h=arm.h, g=arm.g),
                "sensor": dict(cfg.sensor.model_dump()), "noise": cfg.noise.noise().to_dict(),
                "drop": {"height_m": list(cfg.height), "x_range_m": list(cfg.x_range), "gap_m": cfg.gap},
                "max_high": cfg.max_high, "max_low": cfg.max_low, "hold": cfg.hold,
                "tolerance": {"pos_m": cfg.pos_tol, "ang_rad": cfg.ang_tol},
                "engine": {"verify_high": cfg.verify_high, "exact_flight_high": cfg.exact_flight_high, "penetration_tol_high_m": cfg.penetration_tol_high,
                           "tilt_agreement_m": cfg.tilt_agreement,
                           "overrides": cfg.settings or {}},
                "success": "assembled (both parts within tolerance of assembled_pair) within max_high + max_low throws"}


ASSEMBLE = register_experiment(Assemble())


ENGINE = "engine"
"""The model of the assembly trials: two parts leaning on each other and the wall keep their poses (engine runs)."""
