"""Closed-form sticking swing of model "rigid_body": path, guard roots and elapsed time.

While the pivot sticks the part is a compound pendulum, I θ̈ = −g ℓ cos θ
(:mod:`~throwmap.kernels.roll`), so E = ½ I θ̇² + g ℓ sin θ is conserved and the
swing is decided by E and the sense of θ̇ alone: it reaches the end ahead or
turns back where sin θ = e = E/(g ℓ) and sweeps back to the other end
(:func:`swing_pieces`, with the guards of :mod:`~throwmap.kernels.roll`). On each piece sin θ is monotone, and the guards are
functions of s = sin θ alone (k = ℓ²/I, forces in units of m g):

* ``lift_off``: N(s) = 1 − k + 3k s² − 2k e s = 0, a quadratic;
* ``slip``: μ²N² − F² = 0 with F² = k² (1 − s²)(3s − 2e)², a quartic P(s)
  whose first root along the piece is isolated exactly by its critical points
  (:func:`first_quartic_root`).

The time to sweep θ1 → θ2 is t = ∫ dθ/θ̇ with θ̇² = 2c(e − sin θ), c = g ℓ/I.
With z = sin(θ/2 − π/4), sin θ = 1 − 2z² and

    t = √(2/c) ∫ dz / √((1 − z²)(e − 1 + 2z²)),

an incomplete elliptic integral, evaluated with Carlson's R_F (DLMF 19.16.1):
for e < 1 (turning swings) by DLMF 19.29.4 with the four linear factors
(1 ∓ z)(z ∓ q), q² = (1 − e)/2, exact at the turning point z = q; for e > 1
(over the peak) as G(z) = z R_F(p², p²(1 − z²), p² + z²), p² = (e − 1)/2,
t = (G(z2) − G(z1))/√c (:func:`swing_time`).
"""

import math

from numba import njit

from ..roll import reach_end, turn_back
from .modes import HALF_PI

QUARTER_PI = 0.25 * math.pi


@njit(cache=True)
def carlson_rf(x, y, z):
    """Carlson's symmetric elliptic integral R_F(x, y, z) (DLMF 19.16.1), x, y, z ≥ 0, at most one 0.

    Duplication (DLMF 19.26.18) until the arguments agree to 1e-3, then the
    fifth-order series (DLMF 19.36.1): relative error below 1e-16.
    """
    for _ in range(64):
        a = (x + y + z) / 3.0
        dx = 1.0 - x / a
        dy = 1.0 - y / a
        dz = 1.0 - z / a
        if max(abs(dx), abs(dy), abs(dz)) < 1e-3:
            break
        sx = math.sqrt(x)
        sy = math.sqrt(y)
        sz = math.sqrt(z)
        lam = sx * sy + sy * sz + sz * sx
        x = 0.25 * (x + lam)
        y = 0.25 * (y + lam)
        z = 0.25 * (z + lam)
    e2 = dx * dy - dz * dz
    e3 = dx * dy * dz
    return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / math.sqrt(a)


@njit(cache=True)
def swing_time(th1, th2, e, c):
    """Time (s) the sticking swing at energy e = E/(g ℓ) takes between θ1 and θ2 (rad), c = g ℓ/I (1/s²).

    The swing must move monotonically between them (θ̇² = 2c(e − sin θ) > 0 inside);
    an end may be a turning point (sin θ = e).
    """
    if th1 == th2:
        return 0.0
    z1 = math.sin(0.5 * th1 - QUARTER_PI)
    z2 = math.sin(0.5 * th2 - QUARTER_PI)
    if e <= 1.0:
        # both ends on one side of the peak; by symmetry use |z| ≥ q
        q = math.sqrt(0.5 * (1.0 - e))
        x = max(max(abs(z1), abs(z2)), q)
        y = max(min(abs(z1), abs(z2)), q)
        if x <= y:
            return 0.0
        X1 = math.sqrt(1.0 - x)
        X2 = math.sqrt(1.0 + x)
        X3 = math.sqrt(x - q)
        X4 = math.sqrt(x + q)
        Y1 = math.sqrt(1.0 - y)
        Y2 = math.sqrt(1.0 + y)
        Y3 = math.sqrt(y - q)
        Y4 = math.sqrt(y + q)
        dxy = x - y
        U12 = (X1 * X2 * Y3 * Y4 + Y1 * Y2 * X3 * X4) / dxy
        U13 = (X1 * X3 * Y2 * Y4 + Y1 * Y3 * X2 * X4) / dxy
        U14 = (X1 * X4 * Y2 * Y3 + Y1 * Y4 * X2 * X3) / dxy
        # √(2/c) · (1/√2) · 2 R_F(U12², U13², U14²)
        return 2.0 * carlson_rf(U12 * U12, U13 * U13, U14 * U14) / math.sqrt(c)
    p2 = 0.5 * (e - 1.0)
    g1 = z1 * carlson_rf(p2, p2 * (1.0 - z1 * z1), p2 + z1 * z1)
    g2 = z2 * carlson_rf(p2, p2 * (1.0 - z2 * z2), p2 + z2 * z2)
    return abs(g2 - g1) / math.sqrt(c)


@njit(cache=True)
def swing_pieces(theta, dirn, ta, tb, E, g, lj):
    """The path of a sticking swing from θ in sense ``dirn`` at energy E (J/kg), as pieces with monotone sin θ.

    As :func:`~throwmap.kernels.roll.roll_to_rest`: guard ``reach_end`` — it reaches
    the end ahead (θb for dirn = +1, θa for −1), split at the peak π/2 if it
    crosses it; otherwise guard ``turn_back`` — it turns back where sin θ = E/(g ℓ)
    and sweeps to the other end. Returns ``(n, θ0, θ1, θ2, d0, d1)``: n = 1 or 2
    pieces θ0 → θ1 (sense d0) and θ1 → θ2 (sense d1).
    """
    if reach_end(theta, dirn, ta, tb, E, g, lj):
        end = tb if dirn > 0 else ta
        if min(theta, end) < HALF_PI < max(theta, end):
            return 2, theta, HALF_PI, end, dirn, dirn
        return 1, theta, end, end, dirn, dirn
    return 2, theta, turn_back(E, g, lj, dirn), (ta if dirn > 0 else tb), dirn, -dirn


@njit(cache=True)
def theta_on_piece(s, a, b):
    """The angle with sin θ = s on the piece between θ = a and b (left of the peak: asin s, right: π − asin s)."""
    s = min(max(s, -1.0), 1.0)
    th = math.asin(s)
    if 0.5 * (a + b) > HALF_PI:
        th = math.pi - th
    return min(max(th, min(a, b)), max(a, b))


@njit(cache=True)
def n_roots(e, k):
    """Roots s1 ≤ s2 of N(s) = 1 − k + 3k s² − 2k e s (N < 0 between them); NaN if N has none."""
    disc = e * e - 3.0 * (1.0 - k) / k
    if disc < 0.0:
        return math.nan, math.nan
    r = math.sqrt(disc)
    return (e - r) / 3.0, (e + r) / 3.0


@njit(cache=True)
def slip_quartic(e, k, mu):
    """Coefficients (p0 … p4) of P(s) = μ² N(s)² − F(s)², F² = k² (1 − s²)(3s − 2e)²: P ≤ 0 ⇔ |F| ≥ μN (N ≥ 0)."""
    a0 = 1.0 - k
    a1 = -2.0 * k * e
    a2 = 3.0 * k
    m2 = mu * mu
    k2 = k * k
    p0 = m2 * a0 * a0 - k2 * 4.0 * e * e
    p1 = m2 * 2.0 * a0 * a1 + k2 * 12.0 * e
    p2 = m2 * (a1 * a1 + 2.0 * a0 * a2) - k2 * (9.0 - 4.0 * e * e)
    p3 = m2 * 2.0 * a1 * a2 - k2 * 12.0 * e
    p4 = m2 * a2 * a2 + k2 * 9.0
    return p0, p1, p2, p3, p4


@njit(cache=True)
def _poly4(s, p0, p1, p2, p3, p4):
    return p0 + s * (p1 + s * (p2 + s * (p3 + s * p4)))


@njit(cache=True)
def _dpoly4(s, p1, p2, p3, p4):
    return p1 + s * (2.0 * p2 + s * (3.0 * p3 + s * 4.0 * p4))


@njit(cache=True)
def _bisect_dpoly(lo, hi, p1, p2, p3, p4):
    """Root of the monotone P' between lo and hi (a sign change), to rounding."""
    flo = _dpoly4(lo, p1, p2, p3, p4)
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        fm = _dpoly4(mid, p1, p2, p3, p4)
        if (fm > 0.0) == (flo > 0.0):
            lo = mid
            flo = fm
        else:
            hi = mid
    return 0.5 * (lo + hi)


@njit(cache=True)
def _dpoly_roots(lo, hi, p1, p2, p3, p4):
    """Roots of the cubic P' in (lo, hi), sorted: ``(m, r1, r2, r3)`` (m of them; unused ones NaN).

    The roots of the quadratic P'' split (lo, hi) into at most three intervals on
    which P' is monotone; a sign change of P' on one is bisected.
    """
    q2 = 12.0 * p4
    q1 = 6.0 * p3
    q0 = 2.0 * p2
    c1 = math.nan
    c2 = math.nan
    if q2 != 0.0:
        disc = q1 * q1 - 4.0 * q2 * q0
        if disc >= 0.0:
            r = math.sqrt(disc)
            qq = -0.5 * (q1 + r) if q1 >= 0.0 else -0.5 * (q1 - r)
            if qq != 0.0:
                c1 = qq / q2
                c2 = q0 / qq
                if c2 < c1:
                    c1, c2 = c2, c1
            else:
                c1 = 0.0
    elif q1 != 0.0:
        c1 = -q0 / q1
    if not lo < c1 < hi:
        c1 = math.nan
    if not lo < c2 < hi or c2 == c1:
        c2 = math.nan
    if math.isnan(c1):
        c1, c2 = c2, math.nan
    m = 0
    r1 = math.nan
    r2 = math.nan
    r3 = math.nan
    u = lo
    du = _dpoly4(u, p1, p2, p3, p4)
    for i in range(3):
        v = c1 if i == 0 else (c2 if i == 1 else hi)
        if math.isnan(v):
            continue
        dv = _dpoly4(v, p1, p2, p3, p4)
        if (du > 0.0 and dv < 0.0) or (du < 0.0 and dv > 0.0):
            r = _bisect_dpoly(u, v, p1, p2, p3, p4)
            if m == 0:
                r1 = r
            elif m == 1:
                r2 = r
            else:
                r3 = r
            m += 1
        u = v
        du = dv
    return m, r1, r2, r3


@njit(cache=True)
def first_quartic_root(s_from, s_to, p0, p1, p2, p3, p4):
    """First s from ``s_from`` towards ``s_to`` at which P(s) ≤ 0 (the quartic of :func:`slip_quartic`); NaN if none.

    P(s_from) > 0 is expected (the phase starts inside the friction cone); a start
    on the boundary counts as a root unless P grows along the motion.

    Exact isolation: P is monotone between consecutive roots of P' (:func:`_dpoly_roots`);
    the first such piece, in the direction of motion, whose far end has P ≤ 0
    holds the root, found by bisection.
    """
    up = s_to > s_from
    if _poly4(s_from, p0, p1, p2, p3, p4) <= 0.0:
        # on the boundary (to rounding): slips at once unless P is growing along the motion
        dp = _dpoly4(s_from, p1, p2, p3, p4)
        if s_from == s_to or (dp <= 0.0 if up else dp >= 0.0):
            return s_from
    if s_from == s_to:
        return math.nan
    m, r1, r2, r3 = _dpoly_roots(min(s_from, s_to), max(s_from, s_to), p1, p2, p3, p4)
    u = s_from
    for i in range(m + 1):
        # far end of the i-th monotone piece in the direction of motion
        if i == m:
            v = s_to
        elif up:
            v = r1 if i == 0 else (r2 if i == 1 else r3)
        else:
            v = r3 if (m - 1 - i) == 2 else (r2 if (m - 1 - i) == 1 else r1)
        if _poly4(v, p0, p1, p2, p3, p4) > 0.0:
            u = v
            continue
        # P(u) > 0 ≥ P(v) and P monotone between: bisection
        for _ in range(100):
            mid = 0.5 * (u + v)
            if mid == u or mid == v:
                break
            if _poly4(mid, p0, p1, p2, p3, p4) > 0.0:
                u = mid
            else:
                v = mid
        return v
    return math.nan
