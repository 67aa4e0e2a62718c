"""The cavity at the arm's end that turns the designed limit set into a fixed point (paper Sec. V-C, Fig. 9(b)).

The draft's cavity "captures the part in a unique configuration … deep enough that subsequent throws do
not eject the part"; its one failure in 20: "the part hit the wall of the cavity … when its center of
mass is very close to the end of the arm before it falls in".

What holds the part (checked in the engine)
-------------------------------------------
Every throw throws the captured part again: from the floor at CM abscissa x it leaves at ≈ x ω
(1.4 m/s at x = 28 cm, ω = 4.9 rad/s: a 10 cm rise) and turns ≈ 2 ω² x / g (1.4 rad). No
practical depth keeps it in, and a part that reached the cavity beyond its side's critical point
r_k (what "only side k reaches the cavity" needs) is flipped out by the next throw. So the cavity
holds by the throw map: jogs move a part outward (Sec. III-D) until it rests against the end wall
with its CM at x_i = L − u_R(i) (u_R: CM → outer support vertex); it stays iff the throw from
there is a jog. The designed limit set (r_k far beyond the other sides' r_j) leaves a window of
arm ends L in which only side k jogs at the wall, for every ω in [ω(1 − z_release σ),
ω(1 + z_hold σ)] (σ the ω jitter). :func:`jog_map` evaluates the throw map on the cavity's floor
(h − depth) on a 5 mm grid — the exact model (``rigid_body``) for the impulse, the engine for the
recoil arm, whose map differs (with ζ = 0.5 side 2 jogs again beyond 32 cm: no window) — and
:func:`design_cavity` puts L in the middle of the widest window.

The other numbers
-----------------
* floor ℓ_k + clearance (side k lies flat on it); lip ramp steeper than the friction angle (a
  vertex landing on the lip slides in rather than catching on its edge).
* end wall (a :class:`~throwmap.system.fixtures.Wall`) high enough by energy: after release the
  part has at most the kinetic energy of the arm point under its CM, ½ m ω_hi² (x² + y²), and
  only gravity works in flight, so its CM rises at most Δ = ω_hi² (x² + y²)/(2g); a wall top above
  that keeps the CM inside x < L (beyond L and below the top it would be inside the wall).
* the draft's failure, reproduced: a part whose jog is cut short by the end wall swings its outer
  vertex into it and, with friction there, comes to rest leaning on it (0.4–0.9 rad, μ_wall = 1),
  from where the next throw flips it out. Hence a low-friction wall (μ 0) and a flush floor: the
  part resting against the wall cannot start its turn (its outer vertex would move into the wall),
  so it hops in place; with a gap before the wall it turns, jogs 6–8 cm and lands leaning.
* a lined floor (``lined``: the floor faced with the wall's material, μ ``wall_mu``): with the true
  μ (the exact engine) a frictionless wall alone is not enough — a hop can still land leaning on it
  (0.50–0.87 rad for the recoil feeder), and that lean rests whenever the floor's μ ≥ (x_CM − x_floor
  vertex)/(wall contact height) = 0.45–1.11, inside μ = 1 ± 10 %. On a μ 0.2 floor (PTFE) no lean
  flatter than 1.1 rad rests; the recoil feeder is fed 199/200 lined against 18/30 unlined.

Checks (:class:`Check`: name, pass/fail, figure): ``window``, ``hold``, ``release_<j>``,
``fits``, ``wall_energy`` (``end_gap`` with a gap), and with ``verify`` the engine's
``engine_capture``, ``engine_hold`` and ``engine_release_<j>``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown
from ..system.arm import Arm
from ..system.fixtures import Cavity, Wall
from ..system.noise import Noise
from ..system.part import Part
from .checks import Check

__all__ = [
    "CAPTURE_TILT",
    "CavityDesign",
    "Pocket",
    "Check",
    "JogMap",
    "design_cavity",
    "evaluate_cavity",
    "jog_map",
    "outward_sweep",
]

CAPTURE_TILT = 0.05
"""rad: a part in the cavity within this angle of the target side's resting orientation lies on it."""


def _realisation(kind: str, omega: float, recoil: float, zeta: float):
    from ..system.motion import ImpulseThrow, RecoilThrow

    w = float(omega)
    return RecoilThrow.for_release_rate(w, recoil=recoil, zeta=zeta) if kind == "recoil" else ImpulseThrow(w)


@dataclass(frozen=True, slots=True, eq=False)
class JogMap:
    """Whether a throw from rest on the cavity's floor is a jog: ``jog[a, j, i]`` True when the throw at
    ``omegas[a]`` (rad/s) from side ``sides[j]`` at CM abscissa ``x[i]`` (m) lands on the same side
    (False for a flip, any other landing, or where the side cannot rest, x + u_L ≤ 0)."""

    x: np.ndarray
    omegas: tuple
    sides: tuple
    jog: np.ndarray

    def margin(self, side: int, x: float, want: bool) -> float:
        """Distance (m) from ``x`` to the nearest grid point of ``side`` where some ω gives the other
        answer than ``want`` (jog True / flip False); negative when ``x``'s own cell is wrong."""
        j = self.sides.index(side)
        step = float(self.x[1] - self.x[0]) if self.x.size > 1 else 0.0
        if not (self.x[0] - 0.5 * step <= x <= self.x[-1] + 0.5 * step):
            return -math.inf  # off the grid: unknown
        ok = np.all(self.jog[:, j, :] == want, axis=0)
        bad = self.x[~ok]
        if bad.size == 0:
            return math.inf
        dist = float(np.min(np.abs(bad - x)))
        return -dist if dist < 0.5 * step else dist


def jog_map(part: Part, arm: Arm, omegas, *, realisation: str = "impulse", recoil: float = math.radians(3.0),
            zeta: float = 0.5, x_lo: float = 0.05, x_hi: float = 0.5, step: float = 0.005) -> JogMap:
    """The :class:`JogMap` of ``part`` on the plain, unbounded ``arm`` (the cavity's floor) at ``omegas``:
    the exact model (``rigid_body``) for the impulse, the engine (pymunk, one process) for the recoil arm."""
    import warnings

    from ..errors import RegimeWarning
    from ..models.engine import EngineOptions
    from ..records.outcome import Status
    from ..throws.throw import throw_batch

    plain = Arm(h=arm.h, g=arm.g, length=None, mu=arm.mu, back=arm.back)
    x = np.arange(x_lo, x_hi + 0.5 * step, step)
    sides = tuple(part.stable_sides)
    jog = np.zeros((len(omegas), len(sides), x.size), dtype=bool)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        for a, w in enumerate(omegas):
            for j, s in enumerate(sides):
                valid = x + float(part.uL[s]) > 0
                if not valid.any():
                    continue
                if realisation == "impulse":
                    res = throw_batch(part, plain, x[valid], s, float(w), "rigid_body")
                else:
                    res = throw_batch(part, plain, x[valid], s, float(w), "engine",
                                      options=EngineOptions(realisation=_realisation("recoil", w, recoil, zeta)))
                jog[a, j, valid] = (np.asarray(res.status) == int(Status.OK)) & (np.asarray(res.side) == s)
    return JogMap(x, tuple(float(w) for w in omegas), sides, jog)


def _windows(jm: JogMap, part: Part, side: int, gap: float) -> list:
    """Intervals (lo, hi) of the arm's end L (m) where side ``side`` jogs at the wall at every ω and every other
    side flips there at every ω (on the grid, one grid step of margin on each side)."""
    step = float(jm.x[1] - jm.x[0])
    good = []
    Ls = np.arange(jm.x[0] + 0.02, jm.x[-1], 0.5 * step)
    for L in Ls:
        ok = jm.margin(side, L - gap - float(part.uR[side]), True) >= step
        ok = ok and all(jm.margin(j, L - gap - float(part.uR[j]), False) >= step for j in jm.sides if j != side)
        good.append(ok)
    runs, start = [], None
    for i, ok in enumerate(good):
        if ok and start is None:
            start = i
        if start is not None and (not ok or i == len(good) - 1):
            runs.append((float(Ls[start]), float(Ls[i if ok else i - 1])))
            start = None
    return runs


@dataclass(frozen=True, slots=True, eq=False)
class CavityDesign:
    """A cavity (and its end wall) for ``part`` on ``side`` at release rate ``omega`` (SI units).

    ``arm`` has the designed length L (the end wall's face); ``cavity`` and ``wall`` are the
    fixtures (:attr:`fixtures`); ``numbers`` every figure of the design (m, rad, rad/s, m/s);
    ``reasons`` one line per choice; ``checks`` the named pass/fails; ``success`` all passed
    (``message`` names those that did not); ``captured_pose`` the arm-frame pose (x, y, φ) of
    the part at rest in the cavity after the engine's capture check (None without ``verify``).
    ``realisation`` says how the arm moves (``kind``, ``recoil`` rad, ``zeta``; ``sigma`` the
    relative ω jitter designed for).
    """

    part: Part
    arm: Arm
    omega: float
    side: int
    cavity: Cavity
    wall: Wall
    realisation: dict
    numbers: dict
    reasons: tuple
    checks: tuple
    captured_pose: tuple | None = None
    jogs: JogMap | None = None
    success: bool = field(init=False)
    message: str = field(init=False)

    def __post_init__(self):
        bad = [c.name for c in self.checks if not c.passed]
        object.__setattr__(self, "success", not bad)
        object.__setattr__(self, "message", "all checks passed" if not bad else "failed: " + ", ".join(bad))

    fixtures = property(lambda self: (self.cavity, self.wall))
    length = property(lambda self: float(self.arm.length), doc="The arm's end L, m.")

    @property
    def lip_x(self) -> float:
        """Where the cavity begins (arm frame, m)."""
        return self.length - self.cavity.span

    @property
    def floor_y(self) -> float:
        return self.arm.h - self.cavity.depth

    def check(self, name: str) -> Check:
        return next(c for c in self.checks if c.name == name)

    def where(self, pose) -> str:
        """Where a part at rest at arm-frame ``pose`` (x, y, φ) is: ``"target"`` (in the cavity, flat
        on the target side within :data:`CAPTURE_TILT`), ``"other"`` (in the cavity otherwise) or
        ``"outside"`` (its CM short of the lip or its lowest vertex above half the cavity's depth)."""
        from ..system.pose import state_from_pose, world_vertices

        V = world_vertices(self.part, pose)
        inside = pose[0] > self.lip_x and float(V[:, 1].min()) < self.arm.h - 0.5 * self.cavity.depth
        if not inside:
            return "outside"
        _, k, tilt = state_from_pose(self.part, pose)
        return "target" if (k == self.side and abs(tilt) < CAPTURE_TILT) else "other"

    def table(self) -> str:
        n = self.numbers
        lines = [(f"Cavity for {self.part.name or 'the part'} on side {self.side}, ω = {self.omega:.4g} rad/s "
                 f"({self.realisation['kind']}), σ_ω = {100 * self.realisation['sigma']:.3g} %: {self.message}"),
                 (f"  arm end (end wall) L = {100 * self.length:.2f} cm, lip at {100 * self.lip_x:.2f} cm, "
                 f"depth {100 * self.cavity.depth:.2f} cm, floor {100 * n['floor_m']:.2f} cm, "
                 f"ramp {100 * n['ramp_m']:.2f} cm, wall {100 * self.wall.height:.2f} cm (μ {self.wall.mu:g})"
                 + (", floor lined (the wall's μ)" if self.cavity.lined else "")),
                 ((f"  window for L: [{100 * n['L_lo_m']:.2f}, {100 * n['L_hi_m']:.2f}] cm" if n["n_windows"] else
                   "  window for L: none") + f" at ω ∈ [{n['omega_lo']:.4g}, {n['omega_hi']:.4g}] rad/s")]
        lines += [f"  {c}" for c in self.checks]
        lines += [f"  why: {r}" for r in self.reasons]
        return "\n".join(lines)

    def __repr__(self) -> str:
        return f"CavityDesign(side {self.side}, L={self.length:.4g} m, wall={self.wall.height:.3g} m; {self.message})"

    def to_dict(self) -> dict:
        def fin(v):
            return v if not isinstance(v, float) or math.isfinite(v) else None

        return {"part": self.part.name, "side": self.side, "omega_rad_s": self.omega, "success": self.success,
                "message": self.message, "arm": {"h_m": self.arm.h, "length_m": self.length, "mu": fin(self.arm.mu)},
                "cavity_profile_m": [list(p) for p in self.cavity.profile], "cavity_lined": self.cavity.lined,
                "wall": {"height_m": self.wall.height, "thickness_m": self.wall.thickness, "mu": self.wall.mu},
                "realisation": dict(self.realisation), "numbers": {k: fin(v) for k, v in self.numbers.items()},
                "checks": [c.to_dict() for c in self.checks], "reasons": list(self.reasons),
                "captured_pose": None if self.captured_pose is None else list(self.captured_pose)}

    def plot(self, ax=None, path=None):
        """The captured part at rest in the cavity, with the arm, cavity and wall (:mod:`throwmap.viz.capture`)."""
        from ..viz.capture import plot_capture

        return plot_capture(self, ax=ax, path=path)


def outward_sweep(part: Part, side: int, x: float, y: float, omega: float, g: float) -> float:
    """How far (m) beyond its resting outer support vertex any vertex of ``part`` moves outward during
    the flight of an impulsive throw from rest on ``side`` with its CM at arm-frame ``(x, y)`` (m) at
    rate ``omega`` (rad/s): CM (x − y ω t, y + x ω t − ½ g t²), turned by ω t (paper Eq. 1), until
    the CM is back at its resting height."""
    t_f = max(0.0, 2.0 * x * omega / g)
    t = np.linspace(0.0, t_f, 400)
    phi = float(part.beta[side]) + omega * t
    W = np.asarray(part.w)
    vx = (x - y * omega * t)[:, None] + np.cos(phi)[:, None] * W[None, :, 0] - np.sin(phi)[:, None] * W[None, :, 1]
    return float(max(0.0, vx.max() - (x + float(part.uR[side]))))


def _num(v, name: str, *, lo=None, hi=None, positive=False) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) or not math.isfinite(v):
        raise InvalidStateError(name, f"must be a finite number, got {shown(v)}")
    if (positive and v <= 0) or (lo is not None and v < lo) or (hi is not None and v > hi):
        rng = "> 0" if positive and hi is None else f"in [{lo if lo is not None else 0}, {hi}]" if hi is not None else f"≥ {lo}"
        raise InvalidStateError(name, f"must be {rng}, got {shown(v)}")
    return float(v)


@dataclass(frozen=True, slots=True)
class Pocket:
    """The pocket's design inputs (m, rad): ``depth`` below the arm surface, ``clearance`` (floor beyond the target
    side's length), ``ramp_angle`` (the lip), ``end_gap`` (0: the floor runs to the wall; > 0: it ends that short of
    it in a ramp at ``end_angle``), ``wall_mu`` (the end wall's μ), ``lined`` (the floor faced with the wall's
    material: its μ is ``wall_mu``, :attr:`Cavity.lined <throwmap.system.fixtures.Cavity.lined>`), ``wall_margin``
    (wall top above the energy bound), ``place`` (where in the widest window the arm's end L goes, 0: its low end)
    or ``length`` (L itself, m; None: designed); ``window`` (False: with ``length`` given, the throw map on the
    cavity's floor that places L and checks it is not computed — 3–12 s of engine throws a design on the recoil arm
    spends on a report — and the window, hold and release checks are left out)."""

    depth: float = 0.02
    clearance: float = 0.005
    ramp_angle: float = math.radians(60.0)
    end_gap: float = 0.0
    end_angle: float = math.radians(60.0)
    wall_mu: float = 0.0
    lined: bool = False
    wall_margin: float = 0.01
    place: float = 0.5
    length: float | None = None
    window: bool = True

    def __post_init__(self):
        depth = _num(self.depth, "depth", positive=True)
        end_angle = _num(self.end_angle, "end_angle", lo=1e-6, hi=math.pi / 2)
        checked = {"depth": depth, "clearance": _num(self.clearance, "clearance", lo=0.0),
                   "ramp_angle": _num(self.ramp_angle, "ramp_angle", lo=1e-6, hi=math.pi / 2), "end_angle": end_angle,
                   "end_gap": _num(self.end_gap, "end_gap", lo=0.0, hi=depth / math.tan(end_angle) + 1e-12),
                   "wall_mu": _num(self.wall_mu, "wall_mu", lo=0.0), "wall_margin": _num(self.wall_margin, "wall_margin", lo=0.0),
                   "place": _num(self.place, "place", lo=0.0, hi=1.0), "lined": bool(self.lined),
                   "length": None if self.length is None else _num(self.length, "length", positive=True),
                   "window": bool(self.window)}
        if not checked["window"] and checked["length"] is None:
            raise InvalidStateError("window", "may be false only with the length given: the window places L")
        for name, value in checked.items():
            object.__setattr__(self, name, value)


DEFAULT_NOISE = Noise(omega_rel=0.03)
"""The throw-to-throw jitter a pocket is designed for by default: 3 % of ω, the paper's impulse."""


def design_cavity(part: Part, arm: Arm, omega: float, side: int, *, pocket: Pocket | None = None,
                  noise: Noise = DEFAULT_NOISE, z_hold: float = 3.0, z_release: float = 1.0, verify: bool = True,
                  settings=None) -> CavityDesign:
    """Design the cavity at the arm's end that holds ``part`` on ``side`` (see the module docstring).

    ``arm`` gives h, μ, g (its length becomes the designed L); ``omega`` rad/s; ``noise`` the arm the
    experiment throws with (:class:`~throwmap.system.noise.Noise`: its ``omega_rel`` σ is the relative ω jitter,
    its ``realisation`` ``"impulse"`` or ``"recoil"`` with ``recoil`` rad and ``zeta``): side k must jog at the
    wall for ω from ω(1 − ``z_release`` σ) to ω(1 + ``z_hold`` σ) and the other sides flip there; L goes
    ``pocket.place`` of the way through the widest window (or is ``pocket.length``, m). ``pocket``: the geometry
    (:class:`Pocket`; None: its defaults). ``verify``: engine checks. Returns a :class:`CavityDesign`
    (``success`` False, naming the failed checks, when there is no window or a check fails).
    """
    if not isinstance(part, Part) or not isinstance(arm, Arm):
        bad = "part" if not isinstance(part, Part) else "arm"
        raise InvalidStateError(bad, f"must be a {bad.title()}, got {type(part if bad == 'part' else arm).__name__}")
    pocket = Pocket() if pocket is None else pocket
    for name, value, kind in (("pocket", pocket, Pocket), ("noise", noise, Noise)):
        if not isinstance(value, kind):
            raise InvalidStateError(name, f"must be a {kind.__name__}, got {type(value).__name__}")
    sigma, realisation, recoil, zeta = noise.omega_rel, noise.realisation, noise.recoil, noise.zeta
    depth, clearance, ramp_angle, end_gap, end_angle = (pocket.depth, pocket.clearance, pocket.ramp_angle,
                                                        pocket.end_gap, pocket.end_angle)
    wall_mu, lined, wall_margin, place, length = (pocket.wall_mu, pocket.lined, pocket.wall_margin, pocket.place,
                                                  pocket.length)
    omega, side = _num(omega, "omega", positive=True), part.check_side(side)
    w_hi = omega * (1.0 + _num(z_hold, "z_hold", lo=0.0) * sigma)
    w_lo = omega * max(0.05, 1.0 - _num(z_release, "z_release", lo=0.0) * sigma)
    floor_arm = Arm(h=arm.h - depth, g=arm.g, mu=wall_mu if lined else arm.mu, back=arm.back)
    jm = (jog_map(part, floor_arm, (w_lo, omega, w_hi), realisation=realisation, recoil=recoil, zeta=zeta)
          if pocket.window else None)
    uR = {j: float(part.uR[j]) for j in part.stable_sides}
    runs = _windows(jm, part, side, end_gap) if jm is not None else []
    L_lo, L_hi = max(runs, key=lambda r: r[1] - r[0]) if runs else (math.nan, math.nan)
    if length is not None:
        L = length
    elif runs:
        L = L_lo + place * (L_hi - L_lo)
    else:  # no window: the largest L at which side k still jogs at every ω; the release checks fail
        jogs_k = jm.x[np.all(jm.jog[:, jm.sides.index(side), :], axis=0)]
        if jogs_k.size == 0:
            raise InvalidStateError("side", f"side {side} never jogs on the cavity's floor for ω in "
                                            f"[{w_lo:.4g}, {w_hi:.4g}] rad/s: nothing can hold it")
        L = float(jogs_k.max()) + uR[side] + end_gap - 0.005
    floor, ramp = float(part.length[side]) + clearance, depth / math.tan(ramp_angle)
    top = min(0.0, -depth + end_gap * math.tan(end_angle)) if end_gap > 0 else -depth
    prof = ((floor + end_gap + ramp, 0.0), (floor + end_gap, -depth), (end_gap, -depth))
    cavity = Cavity(prof + ((0.0, top),) if end_gap > 0 else prof, lined=bool(lined))
    x_c, y_c = L - end_gap - uR[side], arm.h - depth + float(part.d[side])
    rise = w_hi**2 * (x_c**2 + y_c**2) / (2.0 * arm.g)
    H = float(part.d[side]) - depth + rise + wall_margin
    wall = Wall(height=H, mu=wall_mu)
    sweep = outward_sweep(part, side, x_c, y_c, w_hi, arm.g)
    numbers = {"L_m": L, "L_lo_m": L_lo, "L_hi_m": L_hi, "n_windows": len(runs), "omega_lo": w_lo, "omega_hi": w_hi,
               "floor_m": floor, "ramp_m": ramp, "depth_m": depth, "end_gap_m": end_gap, "end_angle_rad": end_angle,
               "lip_x_m": L - cavity.span, "x_hold_m": x_c, "y_hold_m": y_c, "rise_bound_m": rise, "wall_height_m": H,
               "drift_speed_m_s": -y_c * omega, "sweep_m": sweep}
    if jm is None:
        placed = f"L = {100 * L:.2f} cm as given (the window on the floor's throw map not computed)"
    elif length is not None and runs:
        placed = (f"L = {100 * L:.2f} cm as given, {'inside' if L_lo <= L <= L_hi else 'OUTSIDE'} the widest window "
                  f"[{100 * L_lo:.2f}, {100 * L_hi:.2f}] cm")
    else:
        placed = "L in the middle of the widest window" if place == 0.5 else f"L at {place:g} of the widest window"
    where = (placed if jm is None else
             (f"{placed} where only side {side} stays at the end wall: there the throw is a jog "
              f"for every ω in [{w_lo:.3g}, {w_hi:.3g}] rad/s (−{z_release:g}σ … +{z_hold:g}σ) and a flip for every other side "
              f"(the throw map on the cavity's floor, {realisation}, 5 mm grid, one step of margin)")
             if runs else
             f"NO window ({realisation}): L only where side {side}'s last jog on the floor ends (check 'window' fails)")
    reasons = (
        where,
        f"floor = side {side}'s length + {100 * clearance:.2f} cm: it lies flat against the wall",
        (f"lip ramp at {math.degrees(ramp_angle):.0f}° (friction angle {math.degrees(math.atan(arm.mu)):.0f}°): a vertex "
        "landing on it slides into the cavity"),
        f"end wall {100 * H:.1f} cm: after a throw the CM rises at most ω_hi²(x²+y²)/2g = {100 * rise:.1f} cm",
        (f"end wall and pocket floor lined (μ {wall_mu:g}): a part leaning on the wall slides flat (a lean needs floor "
         "friction ≥ 0.45, docs: how-to/feeding) instead of resting against it (the draft's failure)") if lined else
        f"end wall μ = {wall_mu:g}: a part swung into it slides down instead of resting against it (the draft's failure)",
        (f"floor ends {100 * end_gap:.2f} cm short of the end wall in a {math.degrees(end_angle):.0f}° ramp: the part "
         "turns in flight without touching the wall") if end_gap > 0 else
        (f"floor runs to the end wall: side {side} resting there cannot start its turn (its outer vertex would move "
         f"{100 * sweep:.2f} cm into the wall), so it hops in place; with a gap it turns, jogs 6–8 cm and lands leaning"),
    )
    design = CavityDesign(part, Arm(h=arm.h, g=arm.g, length=L, mu=arm.mu, back=arm.back), omega, side, cavity, wall,
                          {"kind": realisation, "recoil": recoil, "zeta": zeta, "sigma": sigma}, numbers, reasons, (),
                          jogs=jm)
    return evaluate_cavity(design, verify=verify, settings=settings)


def evaluate_cavity(design: CavityDesign, *, verify: bool = True, settings=None, n_hold: int = 3,
                    n_capture: int = 15) -> CavityDesign:
    """``design`` with its checks (re)computed for its own cavity and wall (any geometry: a design
    whose cavity or wall was replaced — too shallow, too narrow — is judged the same way).

    The window checks use ``design.jogs`` (the throw map on the cavity's floor; None: not computed, and the window,
    hold and release checks are left out); the engine
    checks (``verify``) throw the part: ``engine_capture`` from side k short of the lip at ω, up
    to ``n_capture`` throws; ``engine_hold`` ``n_hold`` throws at ω_hi from the wall;
    ``engine_release_<j>`` one throw at ω_lo from the wall on side j.
    """
    import dataclasses

    d, part, k, n = design, design.part, design.side, dict(design.numbers)
    L, depth = d.length, d.cavity.depth
    gap = n.get("end_gap_m", 0.0)
    prof = d.cavity.profile
    floor_len = (prof[1][0] - prof[2][0]) if len(prof) >= 3 else d.cavity.span
    x_c = L - gap - float(part.uR[k])
    jm = d.jogs
    width = n["L_hi_m"] - n["L_lo_m"]
    checks = [Check("window", math.isfinite(width) and width > 0, width if math.isfinite(width) else 0.0,
                    "width of the widest window for L: > 0")] if jm is not None else []  # None: not computed
    if jm is not None:
        step = float(jm.x[1] - jm.x[0])
        m = jm.margin(k, x_c, True)
        checks.append(Check("hold", m >= step, min(m, 1.0),
                            f"side {k} at the wall (CM at L − u_R) jogs for every ω in [ω_lo, ω_hi]: distance to the "
                            f"nearest non-jog ≥ one grid step ({100 * step:.1f} cm)"))
        for j in part.stable_sides:
            if j != k:
                xj = L - gap - float(part.uR[j])
                m = jm.margin(j, xj, False)
                checks.append(Check(f"release_{j}", m >= step, min(m, 1.0),
                                    f"side {j} at the wall flips for every ω in [ω_lo, ω_hi]: distance to the "
                                    f"nearest jog ≥ one grid step"))
    checks.append(Check("fits", floor_len >= float(part.length[k]), floor_len - float(part.length[k]),
                        f"cavity floor − side {k}'s length ≥ 0"))
    y_h = d.arm.h - depth + float(part.d[k])
    sweep = outward_sweep(part, k, x_c, y_h, n["omega_hi"], d.arm.g)
    n["sweep_m"] = sweep
    if gap > 0:
        checks.append(Check("end_gap", gap >= sweep, gap - sweep,
                            f"end gap − side {k}'s outward sweep in flight at ω_hi (impulse): ≥ 0, the wall is not touched"))
    y_c = d.arm.h - depth + float(part.d[k])
    rise = n["omega_hi"] ** 2 * (x_c**2 + y_c**2) / (2.0 * d.arm.g)
    top = d.arm.h + d.wall.height
    checks.append(Check("wall_energy", top > y_c + rise, top - (y_c + rise),
                        "end wall top − highest CM after a throw, ω_hi²(x²+y²)/2g above rest: > 0"))
    pose = None
    if verify:
        extra, pose = _engine_checks(d, settings, n_hold, n_capture)
        checks += extra
    return dataclasses.replace(d, numbers=n, checks=tuple(checks), captured_pose=pose)


def _engine_checks(d: CavityDesign, settings, n_hold: int, n_capture: int):
    from ..engine import Placement, Scene
    from ..system.pose import pose_at_rest
    from ..throws.session import open_session

    part, k, L = d.part, d.side, d.length
    real = d.realisation

    def session(placement):
        """The part thrown again and again in the engine from ``placement`` in the cavity's scene."""
        return open_session(part, d.arm, Scene(d.arm, (placement,), d.fixtures), ENGINE, settings=settings)

    def throw(sess, w):
        return sess.throw(w, _realisation(real["kind"], w, real["recoil"], real["zeta"]))

    def at_wall(j):
        x = L - d.numbers.get("end_gap_m", 0.0) - float(part.uR[j]) - 1e-4
        if x + float(part.uL[j]) > d.lip_x:  # lies on the floor
            return Placement(part, pose=pose_at_rest(part, d.floor_y, x, j))
        return None

    out, pose = [], None
    # capture: side k with its outer vertex 1 cm short of the lip, or — where it does not fit there —
    # flat on the cavity's floor with its joint-side vertex 2 mm past the lip ramp, thrown at ω until
    # it is captured (or something else)
    x0 = d.lip_x - float(part.uR[k]) - 0.01
    if x0 + float(part.uL[k]) >= 0.005:
        start = Placement(part, x=x0, side=k)
    else:
        x0 = d.lip_x + d.numbers["ramp_m"] + 0.002 - float(part.uL[k])
        start = Placement(part, pose=pose_at_rest(part, d.floor_y, x0, k))
    where, n_throws = "outside", 0
    if x0 + float(part.uR[k]) < L:
        sess = session(start)
        for n_throws in range(1, n_capture + 1):
            step = throw(sess, d.omega)
            if not step.ok:
                where = f"{step.status.label}"
                break
            where = d.where(step.poses[0])
            if where == "target":
                pose = tuple(step.poses[0])
                break
    out.append(Check("engine_capture", where == "target", float(n_throws),
                     f"side {k} thrown at ω from short of the lip (or the cavity's joint end) ends flat on "
                     f"side {k} in the cavity within {n_capture} throws (throws used; ended: {where})", unit="throws"))
    # hold: at the wall on side k, n_hold throws at ω_hi
    placement, held, why = at_wall(k), 0, "does not fit on the floor"
    if placement is not None:
        why = "held"
        sess = session(placement)
        for _ in range(n_hold):
            step = throw(sess, d.numbers["omega_hi"])
            w = d.where(step.poses[0]) if step.ok else step.status.label
            if w != "target":
                why = w
                break
            held += 1
    out.append(Check("engine_hold", held == n_hold, float(held),
                     f"side {k} at the wall stays flat on side {k} in the cavity through {n_hold} throws at ω_hi "
                     f"(ended: {why})", unit="throws"))
    for j in part.stable_sides:
        if j == k:
            continue
        placement = at_wall(j)
        if placement is None:
            out.append(Check(f"engine_release_{j}", True, 0.0, f"side {j} cannot lie on the floor", unit="throws"))
            continue
        step = throw(session(placement), d.numbers["omega_lo"])
        stays = step.ok and step.states[0].side == j
        out.append(Check(f"engine_release_{j}", not stays, 1.0, f"side {j} at the wall leaves side {j} in one throw "
                                                                  f"at ω_lo ({'stayed' if stays else step.status.label})",
                         unit="throws"))
    return out, pose


ENGINE = "engine"
"""The model of the cavity's checks in full physics: the part keeps its pose from throw to throw."""
