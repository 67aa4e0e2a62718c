"""The draft's design function F = K + U − U_crit (paper Sec. V-A), corrected, as a fast first guess.

For a part resting at R on side i (u_L, d = d_i, ρ), thrown at ω from an arm at height h,
first order in ω t* (the corrected forms of :mod:`throwmap.kernels.small_angle`, per unit mass):

    t* = 2 ω (R + u_L) / g,   φ* = ω t*
    r  = (u_L + d φ*,  −d + u_L φ*)                     contact vertex from the CM at impact
    ẋ⁻ = −ω (h + d),  ẏ⁻ = ω R − g t*                    CM velocity before impact (Eq. 1)
    H  = ρ² ω + r_y ẋ⁻ − r_x ẏ⁻                        angular momentum about the contact (Eq. 4)
    K  = H² / (2 (ρ² + |r|²))                           kinetic energy after impact
    U  = −g r_y                                         potential energy (from the arm line)
    F  = K + U − U_crit,   U_crit = g √(u_L² + d²)

and side i flips iff H > 0 (turning towards side i + 1) and F > 0. r_i is the first R above
the first jog where that holds (:func:`energy_critical_points`), found by bisection to 1 nm.

Notes
-----
Corrections to the draft's Sec. V-A (each pinned in the kernel's tests; errata 1, 4, 5, 7 in docs/explanation/errata.md):
t* is positive (the draft's −2θ̇_r(R + u_L)/g comes from a signed g); φ̇⁺ has no extra factor
θ̇_r and uses the contact vector rotated by φ*; K is m H²/(2(ρ² + |r|²)) (the draft adds ρ,
a length, to m|r|², a moment of inertia); U is m g (−r_y) (the draft squares lengths and drops
g); the flip test also needs H > 0 (the draft's F > 0 is blind to the sense of rotation).
Like the draft, it ignores the other vertices, slip, rocking and escapes; on the exact map the
switch moves by centimetres, which is why the design is finished on the exact model
(:func:`throwmap.design.design`) and this one only gives the starting point and a comparison.
"""

from __future__ import annotations

import math

import numpy as np

from ..system.starts import start_interval
from .radii import SideRadii

__all__ = ["energy_terms", "energy_critical_points"]


def energy_terms(R, omega: float, h: float, g: float, rho2: float, d: float, uL: float):
    """``(H, K, U, U_crit, F)`` per unit mass at rests R (m; array) — the corrected Sec. V-A forms."""
    R = np.asarray(R, dtype=float)
    t = 2.0 * omega * (R + uL) / g
    phi = omega * t
    rx = uL + d * phi
    ry = -d + uL * phi
    vx = -omega * (h + d)
    vy = omega * R - g * t
    H = rho2 * omega + ry * vx - rx * vy
    Ir = rho2 + rx * rx + ry * ry
    K = 0.5 * H * H / Ir
    U = -g * ry
    Uc = g * math.sqrt(uL * uL + d * d)
    return H, K, U, Uc, K + U - Uc


def _flips(R, *args):
    H, _, _, _, F = energy_terms(R, *args)
    return (H > 0) & (F > 0)


def energy_critical_points(part, arm, omega: float, *, x_max=None, n_grid: int = 512, xtol: float = 1e-9) -> SideRadii:
    """r_i per stable side from the corrected energy test (m; nan if every R up to ``x_max`` jogs), as a
    :class:`~throwmap.design.radii.SideRadii` (``.r``: side → m; method ``"energy test"``).

    The domain of each side is :func:`~throwmap.system.starts.start_interval` cut at ``x_max``
    (default: the arm's length, else 0.6 m), sampled at ``n_grid`` points; the first flip
    above the first jog is refined by bisection to ``xtol``.
    """
    if x_max is None:
        x_max = arm.length if arm.length is not None else 0.6
    out = {}
    rho2 = part.radius_of_gyration ** 2
    for s in part.stable_sides:
        lo, hi = start_interval(part, arm, s)
        hi = min(hi, x_max)
        args = (float(omega), arm.h, arm.g, rho2, float(part.d[s]), float(part.uL[s]))
        if not hi > lo:
            out[s] = math.nan
            continue
        xs = np.linspace(lo, hi, n_grid + 1)[1:]
        fl = _flips(xs, *args)
        jog = np.flatnonzero(~fl)
        if jog.size == 0:
            out[s] = math.nan
            continue
        i0 = int(jog[0])
        after = np.flatnonzero(fl[i0:])
        if after.size == 0:
            out[s] = math.nan
            continue
        i1 = i0 + int(after[0])
        a, b = float(xs[i1 - 1]), float(xs[i1])
        while b - a > xtol:
            c = 0.5 * (a + b)
            if bool(_flips(np.array([c]), *args)[0]):
                b = c
            else:
                a = c
        out[s] = b
    return SideRadii(out, "energy test", part.name, float(omega))
