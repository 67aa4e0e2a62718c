"""How the arm throws: the impulse idealisation and finite arm motions (paper Sec. III-B, IV-A).

Each realisation gives the arm's angle about its rest angle α as a function of
time, θ(t) (rad, CCW +), and its rate θ̇(t) (rad/s); t = 0 is the start of the run.

* :class:`ImpulseThrow` — the paper's idealisation (Sec. III-B): at t = 0 every
  resting part is given the velocity of the arm point at its CM, ω × r, and spin
  ω; the arm itself never moves.
* :class:`FiniteThrow` — the arm turns at constant ω for Δt and stops at α. It
  starts ωΔt below α (the parts resting on it), so Δt → 0 recovers the impulse.
* :class:`RecoilThrow` — the Flatland arm of Sec. IV-A: it recoils a few degrees
  (a smooth ramp down to −θ_r), then a PD loop drives it to a set point θ_s < 0
  chosen so that the first overshoot peaks exactly at the horizontal; the part
  leaves the arm when the arm decelerates faster than gravity can follow. After
  the ringing the arm eases back to α. :meth:`RecoilThrow.for_release_rate`
  picks the loop's natural frequency so that the arm's peak rate equals ω.
* :class:`SampledThrow` — a measured or designed arm motion: samples θ(t_i), interpolated by a
  cubic spline clamped at rest (θ̇ = 0) at both ends; the arm ends at its rest angle (θ = 0).
* :class:`TiltTo` — no throw: the arm turns from its rest angle to a new one at a
  given rate (Sec. VI: lowering the arm to α < 0 before assembly).

Each finite motion names its ``profile`` (``"finite"``, ``"recoil"``, ``"sampled"``, ``"generic"``):
the closed form :mod:`throwmap.kernels.rigid_body.moving.profile` uses for θ̈ (any other object
with ``angle``/``rate`` gets a central difference).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

from ..errors import InvalidStateError, shown

__all__ = ["ImpulseThrow", "FiniteThrow", "RecoilThrow", "SampledThrow", "TiltTo", "angle_function", "check_realisation"]


def _pos(value, field: str, *, allow_zero=False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InvalidStateError(field, f"must be a finite number, got {shown(value)}")
    if value < 0 or (value == 0 and not allow_zero):
        raise InvalidStateError(field, f"must be {'≥' if allow_zero else '>'} 0, got {shown(value)}")
    return float(value)


@dataclass(frozen=True, slots=True)
class ImpulseThrow:
    """The paper's impulsive release at rate ``omega`` (rad/s ≥ 0)."""

    omega: float

    def __post_init__(self):
        object.__setattr__(self, "omega", _pos(self.omega, "omega", allow_zero=True))

    impulsive = True
    start_angle = 0.0

    @property
    def duration(self) -> float:
        return 0.0

    def angle(self, t: float) -> float:
        return 0.0

    def rate(self, t: float) -> float:
        return 0.0


@dataclass(frozen=True, slots=True)
class FiniteThrow:
    """The arm turns at ``omega`` (rad/s) for ``duration`` Δt (s), ending at its rest angle."""

    omega: float
    duration: float = 0.01

    impulsive = False
    profile = "finite"

    def __post_init__(self):
        object.__setattr__(self, "omega", _pos(self.omega, "omega", allow_zero=True))
        object.__setattr__(self, "duration", _pos(self.duration, "duration"))
        if self.omega * self.duration > 0.5:
            raise InvalidStateError("duration", f"ω·Δt = {self.omega * self.duration:.3g} rad is too large (≤ 0.5 rad)")

    @property
    def start_angle(self) -> float:
        return -self.omega * self.duration

    def angle(self, t: float) -> float:
        if t >= self.duration:
            return 0.0
        return -self.omega * (self.duration - max(t, 0.0))

    def rate(self, t: float) -> float:
        return self.omega if 0.0 <= t < self.duration else 0.0


@dataclass(frozen=True, slots=True)
class RecoilThrow:
    """Recoil by ``recoil`` (rad) over ``t_recoil`` (s), then a PD step (damping ratio
    ``zeta``, natural frequency ``omega_n`` rad/s) whose first overshoot peaks at the
    horizontal; after ``hold`` (s) past the peak the arm eases back to α over ``t_return`` (s).
    """

    omega_n: float
    recoil: float = math.radians(3.0)
    zeta: float = 0.5
    t_recoil: float = 0.05
    hold: float = 0.03
    t_return: float = 0.05

    impulsive = False
    profile = "recoil"
    start_angle = 0.0

    def __post_init__(self):
        for name in ("omega_n", "recoil", "t_recoil", "hold", "t_return"):
            object.__setattr__(self, name, _pos(getattr(self, name), name))
        z = _pos(self.zeta, "zeta")
        if z >= 1.0:
            raise InvalidStateError("zeta", f"must be < 1 (an underdamped loop overshoots), got {z}")
        object.__setattr__(self, "zeta", z)

    @staticmethod
    @functools.lru_cache(maxsize=64)
    def _shape(zeta: float) -> tuple[float, float, float]:
        """(M, set point per unit recoil, peak-rate factor f): peak rate = (θ_s + θ_r) ω_n f."""
        sq = math.sqrt(1.0 - zeta * zeta)
        M = math.exp(-zeta * math.pi / sq)
        # rate ∝ e^{-ζ ω_n τ} sin(ω_d τ)/sq, maximal at ω_d τ* = atan(sq/ζ)
        phase = math.atan2(sq, zeta)
        f = math.exp(-zeta * phase / sq) * math.sin(phase) / sq
        return M, -M / (1.0 + M), f

    @classmethod
    def for_release_rate(cls, omega: float, recoil: float = math.radians(3.0), zeta: float = 0.5, **kw) -> "RecoilThrow":
        """The profile whose peak arm rate is ``omega`` (rad/s)."""
        omega = _pos(omega, "omega")
        recoil = _pos(recoil, "recoil")
        M, sp, f = cls._shape(zeta)
        step = recoil * (1.0 + sp)  # θ_s − (−θ_r)
        return cls(omega_n=omega / (step * f), recoil=recoil, zeta=zeta, **kw)

    @property
    def setpoint(self) -> float:
        return self.recoil * self._shape(self.zeta)[1]

    @property
    def omega_d(self) -> float:
        return self.omega_n * math.sqrt(1.0 - self.zeta**2)

    @property
    def t_peak(self) -> float:
        """Time of the overshoot peak at the horizontal, s from the start."""
        return self.t_recoil + math.pi / self.omega_d

    @property
    def peak_rate(self) -> float:
        M, sp, f = self._shape(self.zeta)
        return self.recoil * (1.0 + sp) * self.omega_n * f

    @property
    def duration(self) -> float:
        return self.t_peak + self.hold + self.t_return

    def _pd(self, tau: float) -> tuple[float, float]:
        z, wn, wd = self.zeta, self.omega_n, self.omega_d
        sq = math.sqrt(1.0 - z * z)
        a0 = -self.recoil - self.setpoint
        e = math.exp(-z * wn * tau)
        c, s = math.cos(wd * tau), math.sin(wd * tau)
        th = self.setpoint + a0 * e * (c + z / sq * s)
        thd = -a0 * e * wn / sq * s
        return th, thd

    def angle(self, t: float) -> float:
        return self._eval(t)[0]

    def rate(self, t: float) -> float:
        return self._eval(t)[1]

    def _eval(self, t: float) -> tuple[float, float]:
        if t <= 0.0:
            return 0.0, 0.0
        if t < self.t_recoil:
            u = math.pi * t / self.t_recoil
            return -0.5 * self.recoil * (1.0 - math.cos(u)), -0.5 * self.recoil * math.pi / self.t_recoil * math.sin(u)
        t_ret = self.t_peak + self.hold
        if t < t_ret:
            return self._pd(t - self.t_recoil)
        th0, _ = self._pd(t_ret - self.t_recoil)
        if t < t_ret + self.t_return:
            u = math.pi * (t - t_ret) / self.t_return
            return th0 * 0.5 * (1.0 + math.cos(u)), -th0 * 0.5 * math.pi / self.t_return * math.sin(u)
        return 0.0, 0.0


@dataclass(frozen=True)
class SampledThrow:
    """A sampled arm motion: angles ``theta`` (rad, about α) at times ``t`` (s, strictly increasing,
    t[0] = 0, at least 4 samples), interpolated by a cubic spline with θ̇ = 0 at both ends (the arm
    is at rest before and after); the last angle must be 0 (the arm ends at its rest angle α).
    ``duration`` = t[-1]; the parts rest on the arm at θ(0) at the start."""

    t: tuple
    theta: tuple

    impulsive = False
    profile = "sampled"

    def __post_init__(self):
        import numpy as np

        try:
            t = np.asarray(self.t, dtype=float).ravel()
            th = np.asarray(self.theta, dtype=float).ravel()
        except (TypeError, ValueError):
            raise InvalidStateError("t", "t and theta must be sequences of numbers") from None
        if t.size < 4 or th.size != t.size:
            raise InvalidStateError("t", f"needs ≥ 4 samples and as many angles (got {t.size} times, {th.size} angles)")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(th))):
            raise InvalidStateError("t", "times and angles must be finite")
        if t[0] != 0.0 or np.any(np.diff(t) <= 0.0):
            raise InvalidStateError("t", "must start at 0 and increase strictly")
        if abs(th[-1]) > 1e-12:
            raise InvalidStateError("theta", f"the arm must end at its rest angle (θ = 0), got {th[-1]:.3g} rad")
        if np.max(np.abs(th)) >= 0.5 * math.pi:
            raise InvalidStateError("theta", "|θ| must stay below π/2")
        th[-1] = 0.0
        object.__setattr__(self, "t", tuple(float(v) for v in t))
        object.__setattr__(self, "theta", tuple(float(v) for v in th))

    @functools.cached_property
    def spline(self):
        """The clamped cubic spline θ(t) (scipy ``CubicSpline``)."""
        from scipy.interpolate import CubicSpline

        return CubicSpline(self.t, self.theta, bc_type="clamped")

    @property
    def duration(self) -> float:
        return self.t[-1]

    @property
    def start_angle(self) -> float:
        return self.theta[0]

    @functools.cached_property
    def peak_rate(self) -> float:
        """Largest |θ̇| (rad/s), sampled 20 times per interval."""
        import numpy as np

        tt = np.linspace(0.0, self.t[-1], 20 * len(self.t) + 1)
        return float(np.max(np.abs(self.spline(tt, 1))))

    def angle(self, t: float) -> float:
        if t <= 0.0:
            return self.theta[0]
        if t >= self.t[-1]:
            return 0.0
        return float(self.spline(t))

    def rate(self, t: float) -> float:
        if t <= 0.0 or t >= self.t[-1]:
            return 0.0
        return float(self.spline(t, 1))

    @classmethod
    def of(cls, r, n: int = 400) -> "SampledThrow":
        """``n`` + 1 samples of realisation ``r``'s θ(t) over its duration (e.g. to test the spline)."""
        import numpy as np

        tt = np.linspace(0.0, r.duration, n + 1)
        return cls(tuple(tt), tuple(r.angle(float(v)) for v in tt[:-1]) + (0.0,))


@dataclass(frozen=True, slots=True)
class TiltTo:
    """Turn the arm by ``delta`` (rad, from its current rest angle) at ``rate`` (rad/s > 0)."""

    delta: float
    rate_: float = 0.5

    impulsive = False
    profile = "generic"
    start_angle = 0.0
    omega = 0.0

    def __post_init__(self):
        d = self.delta
        if isinstance(d, bool) or not isinstance(d, (int, float)) or not math.isfinite(d):
            raise InvalidStateError("delta", f"must be a finite angle in rad, got {shown(d)}")
        object.__setattr__(self, "delta", float(d))
        object.__setattr__(self, "rate_", _pos(self.rate_, "rate"))

    @property
    def duration(self) -> float:
        return abs(self.delta) / self.rate_

    def angle(self, t: float) -> float:
        if t <= 0.0:
            return 0.0
        if t >= self.duration:
            return self.delta
        return math.copysign(self.rate_ * t, self.delta)

    def rate(self, t: float) -> float:
        return math.copysign(self.rate_, self.delta) if 0.0 <= t < self.duration else 0.0


def _recoil_angle(r: RecoilThrow):
    """θ(t) of ``r`` as a closure over its constants: the same floating-point operations as
    :meth:`RecoilThrow.angle` in the same order (bit-identical), without its per-call property look-ups."""
    cos, sin, exp, pi = math.cos, math.sin, math.exp, math.pi
    z, wn, wd = r.zeta, r.omega_n, r.omega_d
    sq = math.sqrt(1.0 - z * z)
    setpoint = r.setpoint
    a0 = -r.recoil - setpoint
    k_e, z_sq = -z * wn, z / sq
    t_rec, half_rec = r.t_recoil, -0.5 * r.recoil
    t_ret = r.t_peak + r.hold
    th0_half = r._pd(t_ret - t_rec)[0] * 0.5
    t_end, t_return = t_ret + r.t_return, r.t_return

    def angle(t: float) -> float:
        if t <= 0.0:
            return 0.0
        if t < t_rec:
            return half_rec * (1.0 - cos(pi * t / t_rec))
        if t < t_ret:
            tau = t - t_rec
            return setpoint + a0 * exp(k_e * tau) * (cos(wd * tau) + z_sq * sin(wd * tau))
        if t < t_end:
            return th0_half * (1.0 + cos(pi * (t - t_ret) / t_return))
        return 0.0

    return angle


def angle_function(r):
    """θ(t) (rad) of realisation ``r`` as a plain callable, equal bit for bit to ``r.angle`` (the run loop
    calls it once per step while the arm moves; :class:`RecoilThrow`'s is a closure over its constants)."""
    return _recoil_angle(r) if isinstance(r, RecoilThrow) else r.angle


def check_realisation(r):
    if not isinstance(r, (ImpulseThrow, FiniteThrow, RecoilThrow, SampledThrow, TiltTo)):
        hint = (" (a name is taken by throwmap.control's functions; to throw, pass an object, e.g. "
                 "RecoilThrow.for_release_rate(omega))") if isinstance(r, str) else ""
        raise InvalidStateError("realisation", f"unknown throw realisation {shown(r)}{hint}")
    return r
