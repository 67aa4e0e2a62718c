"""The cavity at the arm's end that turns the designed limit set into a fixed point (paper Sec. V-C, Fig. 9(b)).

The draft adds "a cavity at the end of the arm … to capture the part in a unique configuration.
Because of the shaped limit set, the part only reaches the cavity on side 2 … The cavity is deep
enough that subsequent throws do not eject the part", and reports one failure in 20 because "the
part hit the wall of the cavity … when its center of mass is very close to the end of the arm
before it falls in".

What holds a part in a cavity (our reading, checked in the engine)
-------------------------------------------------------------------
A part resting in a cavity is thrown again by every throw: from the cavity's floor at CM
abscissa x it leaves at |ω × r| ≈ x ω (≈ 1.4 m/s at x = 28 cm, ω = 4.9 rad/s, a 10 cm rise) and
turns by ω t ≈ 2 ω² x / g (≈ 1.4 rad) before it lands. No practical depth keeps it from rising
out, and a part that reached the cavity *beyond* its side's critical point r_k (as "only side k
reaches the cavity" needs: the other sides' limit sets end below r_k's flips) is flipped out
again by the next throw. The cavity therefore does not hold the part by depth but by the throw
map: jogs move a part outward (paper Sec. III-D), so a part on side i ends against the end
wall with its CM at x_i = L − u_R(i) (L: the arm's end, u_R: CM → outer support vertex), and it
stays there iff the throw from there is a jog, x_i < r_i; it is thrown away iff x_i > r_i. The
designed limit set — r_k far beyond the other sides' r_j — leaves a window of L,

    max_{j≠k} [r_j(ω_lo) + u_R(j)]  <  L  <  r_k(ω_hi) + u_R(k),

in which side k alone is held, for every ω between ω_lo = ω(1 − z_release σ) (the other sides
still leave) and ω_hi = ω(1 + z_hold σ) (side k still stays), σ the relative ω jitter. r_i are
taken on the cavity's floor (h − depth) with the arm's motion of the experiment: the exact
model (``rigid_body``) for the impulse, the engine for the recoil arm (its r_i differ).

The cavity's other numbers
--------------------------
* **floor** ℓ_k + clearance: the target side lies flat on it against the end wall.
* **lip**: a ramp at ``ramp_angle`` (steeper than the friction angle, so a part whose joint-side
  vertex lands on it slides down into the cavity instead of resting on the lip's edge).
* **end wall** (a :class:`~throwmap.system.fixtures.Wall` at L, low friction): its height bounds
  the escape by energy. After release a part has at most the kinetic energy of the arm point
  under its CM, ½ m ω_hi² (x² + y²) (x, y its CM in the arm frame), and gravity is the only force
  doing work in flight, so its CM rises at most Δ = ω_hi² (x² + y²) / (2g). A wall whose top is
  above the CM's highest point keeps the CM on the inner side of x = L (a CM beyond L below the
  wall's top would be inside the wall): H ≥ d_k − depth + Δ + margin above the arm surface.
* **the draft's failure**: a jog that would carry the part past the end swings its outer vertex
  into the end wall; with friction there the part comes to rest leaning on the wall (measured in
  the engine: 0.4–0.9 rad tilts with μ_wall = μ_arm = 1), from where the next throw flips it out —
  "the part hit the wall of the cavity when its CM is very close to the end". The design gives
  the end wall a low-friction facing (``wall_mu`` 0: it slides down to the floor) and the lip a
  ramp; the engine checks below throw the part into the cavity and hold it there.

Checks (:class:`Check`, each a named pass/fail with its figure): ``window``, ``hold`` (side k at
the wall jogs up to ω_hi), ``release_<j>`` (side j at the wall flips down to ω_lo), ``fits``,
``wall_energy``, and with ``verify`` the engine's ``engine_capture`` (a part on side k short of
the lip is thrown into the cavity), ``engine_hold`` (held through throws at ω_hi) and
``engine_release_<j>``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown
from ..system.arm import Arm
from ..system.fixtures import Cavity, Wall
from ..system.part import Part

__all__ = ["Check", "CavityDesign", "design_cavity", "evaluate_cavity", "outward_sweep", "switch_points", "CAPTURE_TILT"]

CAPTURE_TILT = 0.05
"""rad: a part in the cavity within this angle of the target side's resting orientation lies on it."""


@dataclass(frozen=True, slots=True)
class Check:
    """One named pass/fail of a design with the figure it was decided on (SI, ``unit``)."""

    name: str
    passed: bool
    value: float
    requirement: str
    unit: str = "m"

    def __str__(self) -> str:
        v = f"{100 * self.value:.2f} cm" if self.unit == "m" else f"{self.value:.4g} {self.unit}".strip()
        return f"{'PASS' if self.passed else 'FAIL'} {self.name}: {v} ({self.requirement})"

    def to_dict(self) -> dict:
        v = self.value
        return {"name": self.name, "passed": bool(self.passed), "value": v if math.isfinite(v) else None,
                "unit": self.unit, "requirement": self.requirement}


def _realisation(kind: str, omega: float, recoil: float, zeta: float):
    from ..engine.realisation import ImpulseThrow, RecoilThrow

    if kind == "recoil":
        return RecoilThrow.for_release_rate(float(omega), recoil=recoil, zeta=zeta)
    return ImpulseThrow(float(omega))


class _OnlyR:
    """Stands in for a LimitSet in :func:`throwmap.critical_points` so that only r_i is computed."""

    def l(self, side):  # noqa: E741 - the paper's l_i
        return math.nan


def switch_points(part: Part, arm: Arm, omega: float, *, realisation: str = "impulse", recoil: float = math.radians(3.0),
                  zeta: float = 0.5, x_max: float = 0.6) -> dict:
    """r_i (m) of every stable side on the plain, unbounded ``arm`` at rate ``omega`` (rad/s).

    The impulse on the exact model (``rigid_body``, 1 µm); the recoil arm
    (:class:`~throwmap.engine.RecoilThrow` with ``recoil`` rad, ``zeta``) in the engine, 24
    grid points per side to 0.5 mm (:func:`throwmap.critical_points`: the first x above the
    first jog whose throw is not a jog).
    """
    import warnings

    from ..analysis.critical import critical_points
    from ..errors import RegimeWarning

    with warnings.catch_warnings():  # a cavity's floor may lie below −min d: r_i are still the map's
        warnings.simplefilter("ignore", RegimeWarning)
        return _switch_points(critical_points, part, arm, omega, realisation, recoil, zeta, x_max)


def _switch_points(critical_points, part, arm, omega, realisation, recoil, zeta, x_max) -> dict:
    plain = Arm(h=arm.h, g=arm.g, length=None, mu=arm.mu, back=arm.back)
    if realisation == "impulse":
        return dict(critical_points(part, plain, omega, "rigid_body", x_max=x_max, limit=_OnlyR()).r)
    if realisation != "recoil":
        raise InvalidStateError("realisation", f"must be 'impulse' or 'recoil', got {shown(realisation)}")
    real = _realisation("recoil", omega, recoil, zeta)
    cp = critical_points(part, plain, omega, "engine", x_max=x_max, realisation=real, n_grid=24, n_split=4, xtol=5e-4,
                         limit=_OnlyR())
    return dict(cp.r)


@dataclass(frozen=True, slots=True, eq=False)
class JogMap:
    """Whether a throw from rest on the cavity's floor is a jog, on a grid (SI).

    ``jog[a, j, i]`` is True when the throw at rate ``omegas[a]`` (rad/s) from side ``sides[j]``
    at CM abscissa ``x[i]`` (m) lands on the same side, False for a flip (or any other landing),
    and stays False where the side cannot rest (x + u_L ≤ 0).
    """

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
    from ..throws.outcome import Status
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
    for L, ok in zip(Ls, good):
        if ok and start is None:
            start = L
        if not ok and start is not None:
            runs.append((float(start), float(prev)))
            start = None
        prev = L
    if start is not None:
        runs.append((float(start), float(prev)))
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

    @property
    def fixtures(self) -> tuple:
        return (self.cavity, self.wall)

    @property
    def length(self) -> float:
        return float(self.arm.length)

    @property
    def lip_x(self) -> float:
        """Where the cavity begins (arm frame, m)."""
        return self.length - self.cavity.span

    @property
    def floor_y(self) -> float:
        return self.arm.h - self.cavity.depth

    def check(self, name: str) -> Check:
        for c in self.checks:
            if c.name == name:
                return c
        raise KeyError(name)

    def where(self, pose) -> str:
        """Where a part at rest at arm-frame ``pose`` (x, y, φ) is: ``"target"`` (in the cavity, flat
        on the target side within :data:`CAPTURE_TILT`), ``"other"`` (in the cavity otherwise) or
        ``"outside"`` (its CM short of the lip or its lowest vertex above half the cavity's depth)."""
        from ..throws.trajectory import state_from_pose, world_vertices

        V = world_vertices(self.part, pose)
        inside = pose[0] > self.lip_x and float(V[:, 1].min()) < self.arm.h - 0.5 * self.cavity.depth
        if not inside:
            return "outside"
        _, k, tilt = state_from_pose(self.part, pose)
        return "target" if (k == self.side and abs(tilt) < CAPTURE_TILT) else "other"

    def table(self) -> str:
        n = self.numbers
        lines = [f"Cavity for {self.part.name or 'the part'} on side {self.side}, ω = {self.omega:.4g} rad/s "
                 f"({self.realisation['kind']}), σ_ω = {100 * self.realisation['sigma']:.3g} %: {self.message}",
                 f"  arm end (end wall) L = {100 * self.length:.2f} cm, lip at {100 * self.lip_x:.2f} cm, "
                 f"depth {100 * self.cavity.depth:.2f} cm, floor {100 * n['floor_m']:.2f} cm, "
                 f"ramp {100 * n['ramp_m']:.2f} cm, wall {100 * self.wall.height:.2f} cm (μ {self.wall.mu:g})",
                 f"  window for L: [{100 * n['L_lo_m']:.2f}, {100 * n['L_hi_m']:.2f}] cm at ω ∈ "
                 f"[{n['omega_lo']:.4g}, {n['omega_hi']:.4g}] rad/s"]
        lines += [f"  {c}" for c in self.checks]
        lines += [f"  why: {r}" for r in self.reasons]
        return "\n".join(lines)

    def __repr__(self) -> str:
        return (f"CavityDesign(side {self.side}, L={self.length:.4g} m, depth={self.cavity.depth:.3g} m, "
                f"floor={self.numbers['floor_m']:.4g} m, wall={self.wall.height:.3g} m; {self.message})")

    def to_dict(self) -> dict:
        def fin(v):
            return v if not isinstance(v, float) or math.isfinite(v) else None

        return {"part": self.part.name, "side": self.side, "omega_rad_s": self.omega, "success": self.success,
                "message": self.message, "arm": {"h_m": self.arm.h, "length_m": self.length, "mu": fin(self.arm.mu)},
                "cavity_profile_m": [list(p) for p in self.cavity.profile],
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


def _num(v, name: str, *, lo=None, positive=False) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) or not math.isfinite(v):
        raise InvalidStateError(name, f"must be a finite number, got {shown(v)}")
    if positive and v <= 0:
        raise InvalidStateError(name, f"must be > 0, got {shown(v)}")
    if lo is not None and v < lo:
        raise InvalidStateError(name, f"must be ≥ {lo}, got {shown(v)}")
    return float(v)


def _inputs(part, arm, omega, side, realisation):
    if not isinstance(part, Part):
        raise InvalidStateError("part", f"must be a Part, got {type(part).__name__}")
    if not isinstance(arm, Arm):
        raise InvalidStateError("arm", f"must be an Arm, got {type(arm).__name__}")
    omega = _num(omega, "omega", positive=True)
    side = part.check_side(side)
    if realisation not in ("impulse", "recoil"):
        raise InvalidStateError("realisation", f"must be 'impulse' or 'recoil', got {shown(realisation)}")
    return omega, side


def design_cavity(part: Part, arm: Arm, omega: float, side: int, *, sigma: float = 0.03, z_hold: float = 3.0,
                  z_release: float = 1.0, realisation: str = "impulse", recoil: float = math.radians(3.0),
                  zeta: float = 0.5, depth: float = 0.02, clearance: float = 0.005, ramp_angle: float = math.radians(60.0),
                  end_gap: float | None = 0.0, end_angle: float = math.radians(60.0), wall_mu: float = 0.0,
                  wall_margin: float = 0.01, place: float = 0.5, length: float | None = None, verify: bool = True,
                  settings=None) -> CavityDesign:
    """Design the cavity at the arm's end that holds ``part`` on ``side`` (see the module docstring).

    ``arm``: h, μ, g of the arm (its length is replaced by the designed L); ``omega`` the
    release rate (rad/s); ``sigma`` the relative ω jitter; the window for L is taken at
    ω_hi = ω(1 + ``z_hold`` σ) for the target side and ω_lo = ω(1 − ``z_release`` σ) for the
    others, and L placed at ``place`` of the way from its low to its high end (or set to ``length``, m). ``depth`` (m),
    ``clearance`` (m, floor beyond the target side's length), ``ramp_angle`` (rad, lip),
    ``end_gap`` (m; default 0: the floor runs to the end wall; None: the target side's outward sweep
    in flight, :func:`outward_sweep`, + 3 mm) and ``end_angle`` (rad): with a gap the floor ends
    ``end_gap`` short of the end wall in a ramp rising at ``end_angle`` (the outer vertex rests at its
    foot and the part turns freely in flight). The default, a flush wall, is the engine's choice:
    a part resting against it cannot start its turn (its outer vertex would move into the wall),
    so side k hops in place; with a gap it turns, jogs 6–8 cm outward and lands leaning on the
    wall, from where the next throw flips it out (README, evidence). ``wall_mu`` (end wall friction), ``wall_margin``
    (m above the energy bound).
    ``realisation`` ``"impulse"`` or ``"recoil"`` (``recoil`` rad, ``zeta``) — how the arm moves
    in the experiment. ``verify`` runs the engine checks. Returns a :class:`CavityDesign`
    (``success`` False, with the failed checks named, when the window is empty or a check fails).
    """
    omega, side = _inputs(part, arm, omega, side, realisation)
    sigma = _num(sigma, "sigma", lo=0.0)
    depth = _num(depth, "depth", positive=True)
    clearance = _num(clearance, "clearance", lo=0.0)
    ramp_angle = _num(ramp_angle, "ramp_angle", positive=True)
    if ramp_angle > math.pi / 2:
        raise InvalidStateError("ramp_angle", f"must be in (0, π/2] rad, got {shown(ramp_angle)}")
    end_angle = _num(end_angle, "end_angle", positive=True)
    if end_angle > math.pi / 2:
        raise InvalidStateError("end_angle", f"must be in (0, π/2] rad, got {shown(end_angle)}")
    gap_max = depth / math.tan(end_angle) if end_angle < math.pi / 2 else 0.0
    if end_gap is not None:
        end_gap = _num(end_gap, "end_gap", lo=0.0)
        if end_gap > gap_max + 1e-12:
            raise InvalidStateError("end_gap", f"the end ramp ({100 * end_gap:.3g} cm at {math.degrees(end_angle):.3g}°) "
                                               f"must not rise above the arm surface (depth {100 * depth:.3g} cm)")
    place = _num(place, "place", lo=0.0)
    if place > 1:
        raise InvalidStateError("place", f"must be in [0, 1], got {shown(place)}")
    w_hi = omega * (1.0 + _num(z_hold, "z_hold", lo=0.0) * sigma)
    w_lo = omega * max(0.05, 1.0 - _num(z_release, "z_release", lo=0.0) * sigma)
    floor_arm = Arm(h=arm.h - depth, g=arm.g, mu=arm.mu, back=arm.back)
    if end_gap is None:  # the sweep at the hold position barely depends on L: estimate it at r_k(ω)
        r0 = switch_points(part, floor_arm, omega, realisation="impulse").get(side, math.nan)
        sweep0 = outward_sweep(part, side, r0, arm.h - depth + float(part.d[side]), w_hi, arm.g) if math.isfinite(r0) else 0.0
        end_gap = min(gap_max, sweep0 + 0.003)
    jm = jog_map(part, floor_arm, (w_lo, omega, w_hi), realisation=realisation, recoil=recoil, zeta=zeta)
    uR = {j: float(part.uR[j]) for j in part.stable_sides}
    runs = _windows(jm, part, side, end_gap)
    L_lo, L_hi = max(runs, key=lambda r: r[1] - r[0]) if runs else (math.nan, math.nan)
    if length is not None:
        L = _num(length, "length", positive=True)
    elif runs:
        L = L_lo + place * (L_hi - L_lo)
    else:  # no window: the largest L at which side k still jogs at every ω; the release checks fail
        jogs_k = jm.x[np.all(jm.jog[:, jm.sides.index(side), :], axis=0)]
        if jogs_k.size == 0:
            raise InvalidStateError("side", f"side {side} never jogs on the cavity's floor for ω in "
                                            f"[{w_lo:.4g}, {w_hi:.4g}] rad/s: nothing can hold it")
        L = float(jogs_k.max()) + uR[side] + end_gap - 0.005
    floor = float(part.length[side]) + clearance
    ramp = depth / math.tan(ramp_angle)
    top = -depth + end_gap * math.tan(end_angle) if end_gap > 0 else -depth
    cavity = Cavity(((floor + end_gap + ramp, 0.0), (floor + end_gap, -depth), (end_gap, -depth), (0.0, min(0.0, top))))
    x_c = L - end_gap - uR[side]
    y_c = arm.h - depth + float(part.d[side])
    rise = w_hi**2 * (x_c**2 + y_c**2) / (2.0 * arm.g)
    H = float(part.d[side]) - depth + rise + _num(wall_margin, "wall_margin", lo=0.0)
    wall = Wall(height=H, mu=_num(wall_mu, "wall_mu", lo=0.0))
    numbers = {"L_m": L, "L_lo_m": L_lo, "L_hi_m": L_hi, "omega_lo": w_lo, "omega_hi": w_hi, "floor_m": floor,
               "ramp_m": ramp, "depth_m": depth, "end_gap_m": end_gap, "end_angle_rad": end_angle, "lip_x_m": L - cavity.span, "x_hold_m": x_c, "y_hold_m": y_c,
               "rise_bound_m": rise, "wall_height_m": H,
               "drift_speed_m_s": -y_c * omega}
    numbers["n_windows"] = len(runs)
    reasons = (
        f"L in the window where side {side} alone is held against the end wall: the throw from there is a jog "
        f"for every ω in [{w_lo:.3g}, {w_hi:.3g}] rad/s (−{z_release:g}σ … +{z_hold:g}σ), and for every other side a "
        f"flip (the throw map on the cavity's floor, {realisation}, on a 5 mm grid with one step of margin)",
        f"floor = side {side}'s length {100 * part.length[side]:.2f} cm + {100 * clearance:.2f} cm: it lies flat against the wall",
        f"lip ramp at {math.degrees(ramp_angle):.0f}° (friction angle {math.degrees(math.atan(arm.mu)):.0f}°): a vertex "
        "landing on it slides into the cavity",
        f"end wall {100 * H:.1f} cm: the CM rises at most ω_hi²(x²+y²)/2g = {100 * rise:.1f} cm after a throw, so it can "
        "never pass the wall's top",
        f"end wall μ = {wall_mu:g}: a part swung into it slides down instead of resting against it (the draft's failure)",
        (f"floor ends {100 * end_gap:.2f} cm short of the end wall in a {math.degrees(end_angle):.0f}° ramp: the outer vertex "
         "rests at its foot and the part turns in flight without touching the wall") if end_gap > 0 else
        (f"floor runs to the end wall: side {side} resting against it cannot start its turn (its outer vertex would move "
         f"{100 * outward_sweep(part, side, x_c, y_c, w_hi, arm.g):.2f} cm into the wall), so it hops in place; a gap "
         "lets it turn, jog 6–8 cm outward and land leaning on the wall (measured in the engine)"),
        f"L at {place:.0%} of the window (middle: the margins of holding and releasing balanced)",
    )
    numbers["sweep_m"] = outward_sweep(part, side, x_c, y_c, w_hi, arm.g)
    design = CavityDesign(part, Arm(h=arm.h, g=arm.g, length=L, mu=arm.mu, back=arm.back), omega, side, cavity, wall,
                          {"kind": realisation, "recoil": recoil, "zeta": zeta, "sigma": sigma}, numbers, reasons, (),
                          jogs=jm)
    return evaluate_cavity(design, verify=verify, settings=settings)


def evaluate_cavity(design: CavityDesign, *, verify: bool = True, settings=None, n_hold: int = 3,
                    n_capture: int = 15) -> CavityDesign:
    """``design`` with its checks (re)computed for its own cavity and wall (any geometry: a design
    whose cavity or wall was replaced — too shallow, too narrow — is judged the same way).

    The window checks use ``design.jogs`` (the throw map on the cavity's floor); the engine
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
                    "width of the widest window for L: > 0")]
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
    from ..engine import Placement, Scene, simulate
    from ..throws.outcome import Status
    from ..throws.trajectory import pose_at_rest

    part, k, L = d.part, d.side, d.length
    real = d.realisation

    def throw(scene, w):
        return simulate(scene, _realisation(real["kind"], w, real["recoil"], real["zeta"]), settings)

    def at_wall(j):
        x = L - d.numbers.get("end_gap_m", 0.0) - float(part.uR[j]) - 1e-4
        if x + float(part.uL[j]) > d.lip_x:  # lies on the floor
            return Scene(d.arm, (Placement(part, pose=pose_at_rest(part, d.floor_y, x, j)),), d.fixtures)
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
        scene = Scene(d.arm, (start,), d.fixtures)
        for n_throws in range(1, n_capture + 1):
            run = throw(scene, d.omega)
            if run.status != Status.OK:
                where = f"{run.status.label}"
                break
            where = d.where(run.poses[0])
            if where == "target":
                pose = tuple(run.poses[0])
                break
            scene = run.next_scene()
    out.append(Check("engine_capture", where == "target", float(n_throws),
                     f"side {k} thrown at ω from short of the lip (or the cavity's joint end) ends flat on "
                     f"side {k} in the cavity within {n_capture} throws (throws used; ended: {where})", unit="throws"))
    # hold: at the wall on side k, n_hold throws at ω_hi
    scene, held, why = at_wall(k), 0, "does not fit on the floor"
    if scene is not None:
        why = "held"
        for _ in range(n_hold):
            run = throw(scene, d.numbers["omega_hi"])
            w = d.where(run.poses[0]) if run.status == Status.OK else run.status.label
            if w != "target":
                why = w
                break
            held += 1
            scene = run.next_scene()
    out.append(Check("engine_hold", held == n_hold, float(held),
                     f"side {k} at the wall stays flat on side {k} in the cavity through {n_hold} throws at ω_hi "
                     f"(ended: {why})", unit="throws"))
    for j in part.stable_sides:
        if j == k:
            continue
        scene = at_wall(j)
        if scene is None:
            out.append(Check(f"engine_release_{j}", True, 0.0, f"side {j} cannot lie on the floor", unit="throws"))
            continue
        run = throw(scene, d.numbers["omega_lo"])
        from ..throws.trajectory import state_from_pose

        stays = run.status == Status.OK and state_from_pose(part, run.poses[0])[1] == j
        out.append(Check(f"engine_release_{j}", not stays, 1.0, f"side {j} at the wall leaves side {j} in one throw "
                                                                  f"at ω_lo ({'stayed' if stays else run.status.label})",
                         unit="throws"))
    return out, pose
