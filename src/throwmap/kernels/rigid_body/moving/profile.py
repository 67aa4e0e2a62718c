"""The arm's motion θ(t), θ̇(t), θ̈(t) of a throw realisation, with the times where it is not smooth.

θ (rad, CCW +) is the arm's angle about its rest angle α, t (s) from the start of the
run (:mod:`throwmap.system.motion`). The moving-arm phase (:mod:`.phase`) needs θ̈
(rad/s²) for the Euler force −m θ̈ × r; it takes it in closed form where the realisation
is closed form (:class:`~throwmap.system.motion.RecoilThrow`: a half-cosine ramp, the
underdamped PD step θ_s + a₀ e^{−ζω_nτ}(cos ω_dτ + ζ/√(1−ζ²) sin ω_dτ), a half-cosine return;
:class:`~throwmap.system.motion.FiniteThrow`: constant rate), from the spline's own
second derivative for :class:`~throwmap.system.motion.SampledThrow`, and by a central
difference (step 1e-5 s, error O(1e-10 θ'''')) for any other object with ``angle``/``rate``.

:attr:`ArmMotion.breaks` lists the times at which θ̈ (or θ̇) jumps: the integrator steps onto
them, so that each RK4 step sees a smooth field. :meth:`ArmMotion.rate_jump` gives the jump of
θ̇ at such a time (FiniteThrow starts and stops at once: +ω at t = 0, −ω at Δt); a jump of the
frame's rate changes the part's arm-frame velocity by −Δθ̇ ẑ × r and its arm-frame spin by −Δθ̇.
"""

from __future__ import annotations

import math

__all__ = ["ArmMotion", "arm_motion"]

FD_STEP = 1e-5
"""Central-difference step (s) for θ̈ of a realisation without a closed form."""


class ArmMotion:
    """θ, θ̇, θ̈ of one realisation (rad, rad/s, rad/s²) at time t (s); ``duration`` (s): the arm is at
    rest at θ = 0 from then on; ``breaks``: increasing times in [0, duration] where θ̈ or θ̇ jumps."""

    def __init__(self, state, duration: float, breaks, jumps=None):
        self._state = state
        self.duration = float(duration)
        self.breaks = tuple(sorted({float(b) for b in breaks if 0.0 <= b <= duration} | {0.0, float(duration)}))
        self._jumps = dict(jumps or {})

    def state(self, t: float) -> tuple[float, float, float]:
        """(θ, θ̇, θ̈) at ``t`` (s); right-continuous at breaks; (0, 0, 0) from ``duration`` on."""
        if t >= self.duration:
            return 0.0, 0.0, 0.0
        return self._state(t)

    def rate_jump(self, t: float) -> float:
        """θ̇(t⁺) − θ̇(t⁻) (rad/s) at a break time ``t`` (0 where θ̇ is continuous)."""
        return self._jumps.get(float(t), 0.0)


def _recoil(r) -> ArmMotion:
    z, wn, wd = r.zeta, r.omega_n, r.omega_d
    sq = math.sqrt(1.0 - z * z)
    sp = r.setpoint
    a0 = -r.recoil - sp
    t_rec = r.t_recoil
    t_ret = r.t_peak + r.hold
    t_end = t_ret + r.t_return
    th0 = r._pd(t_ret - t_rec)[0]
    k_rec = math.pi / t_rec
    k_ret = math.pi / r.t_return

    def state(t):
        if t < 0.0:
            return 0.0, 0.0, 0.0
        if t < t_rec:  # θ = −θ_r/2 (1 − cos πt/T)
            u = k_rec * t
            return (-0.5 * r.recoil * (1.0 - math.cos(u)), -0.5 * r.recoil * k_rec * math.sin(u),
                    -0.5 * r.recoil * k_rec * k_rec * math.cos(u))
        if t < t_ret:  # the PD step response
            tau = t - t_rec
            e = math.exp(-z * wn * tau)
            c, s = math.cos(wd * tau), math.sin(wd * tau)
            return (sp + a0 * e * (c + z / sq * s), -a0 * e * wn / sq * s,
                    -a0 * e * wn / sq * (wd * c - z * wn * s))
        if t < t_end:  # θ = θ₀/2 (1 + cos π(t − t_ret)/T_r)
            u = k_ret * (t - t_ret)
            return (0.5 * th0 * (1.0 + math.cos(u)), -0.5 * th0 * k_ret * math.sin(u),
                    -0.5 * th0 * k_ret * k_ret * math.cos(u))
        return 0.0, 0.0, 0.0

    # the PD's rate at t_ret is dropped at once to the return's 0: a jump of θ̇
    return ArmMotion(state, t_end, (0.0, t_rec, t_ret, t_end), {float(t_ret): -r._pd(t_ret - t_rec)[1]})


def _finite(r) -> ArmMotion:
    w, dt = r.omega, r.duration

    def state(t):
        if 0.0 <= t < dt:
            return -w * (dt - t), w, 0.0
        return 0.0, 0.0, 0.0

    return ArmMotion(state, dt, (0.0, dt), {0.0: w, float(dt): -w})


def _sampled(r) -> ArmMotion:
    sp = r.spline
    d1, d2 = sp.derivative(1), sp.derivative(2)
    t_end = float(r.t[-1])

    def state(t):
        if t < 0.0:
            return float(sp(0.0)), 0.0, 0.0
        return float(sp(t)), float(d1(t)), float(d2(t))

    return ArmMotion(state, t_end, tuple(float(v) for v in r.t))


def _generic(r) -> ArmMotion:
    h = FD_STEP

    def state(t):
        th, thd = r.angle(t), r.rate(t)
        a = max(t - h, 0.0)
        b = min(t + h, r.duration)
        return th, thd, (r.rate(b) - r.rate(a)) / (b - a) if b > a else 0.0

    return ArmMotion(state, r.duration, (0.0, r.duration))


def arm_motion(r) -> ArmMotion:
    """The :class:`ArmMotion` of realisation ``r`` (not an impulse: those need no moving phase), by the
    closed form its ``profile`` names (:mod:`throwmap.system.motion`; a central difference otherwise)."""
    return _BY_PROFILE.get(getattr(r, "profile", "generic"), _generic)(r)


_BY_PROFILE = {"recoil": _recoil, "finite": _finite, "sampled": _sampled}
