"""Exact Coulomb contact solves for the steps where Chipmunk's own solver cannot converge.

Why
---
Chipmunk updates a contact's normal and tangential impulse from the same
relative velocity (a Jacobi step inside the contact). While the contact slides,
that multiplies the normal-velocity error by ``μ |K_nt| / K_nn`` per pass and
diverges above 1 (:mod:`.friction`). The old remedy lowered the pair's μ to
``CAP · K_nn/|K_nt|`` in those steps, which changes the model: a pivot at
μ = 2–3 slips earlier and faster and lands 0.5–1.1 mm away from model
"rigid_body" and from an independent ODE reference
(``tests/kernels/test_tilt_landing.py``); at μ = ∞ a sticking contact creeps.

What
----
For a single part (the only dynamic body), in a step where the cap would bind on
one of its arbiters and that arbiter's previous impulses used more than
:data:`TRIGGER` of the cap (or a contact is new, or did not push), the friction
hook arms :class:`ExactSolve` instead of capping. (Below that the solution
sticks inside the capped cone, where the capped problem has the same solution
and Chipmunk's iteration converges: it is left to Chipmunk, which keeps the
cost near the old one: ×1.15 at μ = 1–3, ×1.4 at μ = ∞, measured.) Its velocity-update function (Chipmunk calls it after every arbiter's
pre-step, before the impulses are applied) integrates gravity as Chipmunk does,
then solves the step's contact problem of the part against the kinematic arm and
fixtures exactly: non-penetration ``v_n ≥ 0 ⊥ j_n ≥ 0`` and Coulomb friction with
the pair's true μ (μ = ∞: stick while pushing), by block Gauss–Seidel over the
contacts, each block the exact 2×2 solve of one contact (stick, separate, or
slide at ``|j_t| = μ j_n`` with the normal solved through
``D = K_nn − σ μ K_nt``; μ = ∞ that cannot stick skids with :data:`MU_SKID` as
model "rigid_body" does; contacts at one point of the part, a vertex in a corner of two
shapes, act at their common point: :func:`_merge_points`); where the sweeps cycle (contacts switching each other
on and off), every combination of contact modes (:func:`enumerate_modes`). It writes the new velocities into the body and the
impulses into the contacts' accumulators, and hands Chipmunk a solved problem:
the tangential effective mass is set to 0 (the friction impulse stays) and the
normal target (``bounce``) to minus the solved normal velocity, so Chipmunk's
iterations change nothing but still run its position correction (bias
impulses, which use the normal effective mass only) as in every other step.
The arbiters are marked first-contact for this step so the cached (warm-start)
impulses are not applied twice; the next ordinary step warm-starts from the
exact impulses. The function removes itself after the step, so a step where the
cap does not bind runs through Chipmunk's own code unchanged.

With the engine's C helper (:mod:`.native`) the same solve runs in C (``native/exact.c``, the
arithmetic of :meth:`ExactSolve._solve` and :func:`solve_contact` operation for operation); only
:func:`enumerate_modes` stays in Python, called back from C for the rare steps whose sweeps cycle.
"""

from __future__ import annotations

import math

__all__ = ["ExactSolve", "enumerate_modes", "exact_solver", "solve_contact"]

MU_SKID = 1e6
"""μ of a μ = ∞ contact that cannot stick with a pushing normal impulse: it slides with this μ (the μ → ∞
limit; :data:`throwmap.kernels.rigid_body.modes.MU_SKID`)."""
MAX_SWEEPS = 40
"""Most Gauss–Seidel sweeps over the contacts in one step; then every combination of contact modes is tried
(:func:`enumerate_modes`)."""
TRIGGER = 0.8
"""A contact whose previous impulses used more than TRIGGER × the cap of its friction ratio (or that is new, or did
not push) is solved exactly; below that the capped μ leaves the (sticking) solution unchanged and Chipmunk solves it."""
SAME_POINT = 2e-4
"""Contacts whose points on the part are closer than this (m, each coordinate) act at one point
(:func:`_merge_points`)."""
TOL = 1e-13
"""Sweeps stop once no impulse changes by more than TOL × (largest impulse + m g dt)."""


def solve_contact(wn: float, wt: float, ann: float, ant: float, att: float, mu: float):
    """The impulse ``(j_n, j_t, mode)`` of one contact given its relative velocity without it ``(wn, wt)``
    (normal, tangential), its inverse effective mass ``[[ann, ant], [ant, att]]`` and friction ``mu``
    (``inf``: no slip while it pushes). ``mode``: 0 separate, 1 stick, 2 slide, 3 fallback (no consistent
    Coulomb solution: the frictionless normal impulse). μ = ∞ that cannot stick slides with μ = :data:`MU_SKID`."""
    if wn >= 0.0:
        return 0.0, 0.0, 0
    det = ann * att - ant * ant
    jn = (ant * wt - att * wn) / det
    jt = (ant * wn - ann * wt) / det
    if jn > 0.0 and abs(jt) <= mu * jn:
        return jn, jt, 1
    m = mu if mu <= MU_SKID else MU_SKID  # μ = ∞ slides (normal force → 0) as its μ → ∞ limit, as rigid_body
    s0 = -1.0 if jt > 0.0 else 1.0  # the slip the needed friction opposes
    for s in (s0, -s0):
        d = ann - s * m * ant
        if d > 0.0:
            jn = -wn / d
            jt = -s * m * jn
            vt = wt + ant * jn + att * jt
            if s * vt >= 0.0:
                return jn, jt, 2
    return -wn / ann, 0.0, 3


def enumerate_modes(cons, u0, m_inv: float, i_inv: float, scale: float):
    """The contact impulses ``[(j_n, j_t), …]`` of the step by trying every combination of contact modes
    (separate, stick, slide ±; μ = 0: separate or frictionless; μ = ∞ slides with :data:`MU_SKID`), or None
    where no combination is consistent. ``cons`` as in :meth:`ExactSolve._solve`, ``u0`` the part's velocity
    without contact impulses, ``scale`` an impulse scale for the tolerances. Where several are consistent, the
    one nearest the Gauss–Seidel iterate (``cons[k][9:11]``)."""
    import itertools

    import numpy as np

    k = len(cons)
    G = np.array([row for c in cons for row in (c[1], c[2])], dtype=float)  # 2k × 3, rows n and t
    Minv = np.array([m_inv, m_inv, i_inv])
    A = (G * Minv) @ G.T
    b = G @ np.asarray(u0, dtype=float) + np.array([e for c in cons for e in (c[7], c[8])])
    prev = np.array([v for c in cons for v in (c[9], c[10])])
    tol_j = 1e-9 * scale
    tol_v = 1e-9 * (np.max(np.abs(b)) + np.max(np.abs(A)) * scale)
    choices = []
    for c in cons:
        mu = c[6]
        choices.append((0, 4) if mu == 0.0 else (0, 1, 2, 3))  # separate, stick, slide +, slide −, frictionless
    best = None
    for modes in itertools.product(*choices):
        rows, rhs = [], []
        for i, (c, m) in enumerate(zip(cons, modes)):
            n, t = 2 * i, 2 * i + 1
            e = np.zeros(2 * k)
            if m == 0:  # j_n = j_t = 0
                e[n] = 1.0; rows.append(e.copy()); rhs.append(0.0)
                e[:] = 0.0; e[t] = 1.0; rows.append(e); rhs.append(0.0)
                continue
            rows.append(A[n].copy()); rhs.append(-b[n])  # v_n = 0
            if m == 1:
                rows.append(A[t].copy()); rhs.append(-b[t])  # v_t = 0
            else:
                mu = 0.0 if m == 4 else min(c[6], MU_SKID)
                sg = 1.0 if m == 2 else -1.0
                e[t] = 1.0; e[n] = sg * mu; rows.append(e); rhs.append(0.0)  # j_t = −σ μ j_n
        M, r = np.array(rows), np.array(rhs)
        x = np.linalg.lstsq(M, r, rcond=None)[0]
        if np.max(np.abs(M @ x - r)) > tol_v + tol_j:
            continue
        v = b + A @ x
        ok = True
        for i, (c, m) in enumerate(zip(cons, modes)):
            jn, jt, vn, vt = x[2 * i], x[2 * i + 1], v[2 * i], v[2 * i + 1]
            if m == 0:
                ok = vn >= -tol_v
            elif m == 1:
                ok = jn >= -tol_j and abs(jt) <= c[6] * jn + tol_j
            elif m in (2, 3):
                ok = jn >= -tol_j and (1.0 if m == 2 else -1.0) * vt >= -tol_v
            else:
                ok = jn >= -tol_j
            if not ok:
                break
        if ok:
            d = float(np.max(np.abs(x - prev)))
            if best is None or d < best[0]:
                best = (d, x)
    if best is None:
        return None
    x = best[1]
    return [(max(float(x[2 * i]), 0.0), float(x[2 * i + 1])) for i in range(k)]


class ExactSolve:
    """The exact contact solve of one part's steps where the friction cap would bind (see the module doc).

    ``arm()`` (from the friction hook, in the step's pre-solve) installs the body's velocity-update function for
    that step; counts: ``n_steps`` exact steps, ``n_sweeps`` Gauss–Seidel sweeps, ``n_enumerated`` steps that
    reached :data:`MAX_SWEEPS` and were solved by :func:`enumerate_modes`, ``n_unconverged`` those where no mode
    combination was consistent either (the last iterate is kept), ``n_fallback`` steps whose last sweep had a
    contact without a consistent Coulomb solution."""

    __slots__ = ("lib", "ffi", "body", "m_inv", "i_inv", "armed", "callback", "default", "each", "found", "warm",
                 "n_steps", "n_sweeps", "n_unconverged", "n_fallback", "n_enumerated", "first", "mu_arm", "mu_wall", "fixture")

    def __init__(self, lib, ffi, body, mass: float, moment: float, mu_arm: float, mu_wall: float, fixture: int):
        self.lib, self.ffi, self.body = lib, ffi, body
        self.m_inv, self.i_inv = 1.0 / mass, 1.0 / moment
        self.mu_arm, self.mu_wall, self.fixture = mu_arm, mu_wall, fixture
        self.armed = False
        self.warm = {}
        self.found = []
        self.n_steps = self.n_sweeps = self.n_unconverged = self.n_fallback = self.n_enumerated = 0
        self.first = lib.CP_ARBITER_STATE_FIRST_COLLISION
        self.default = self.callback = self.each = None  # made on the first exact step (most runs have none)

    @staticmethod
    def wanted(arb, cap: float) -> bool:
        """Whether raw arbiter ``arb`` (its impulses still those of the previous step) needs the exact solve at
        friction cap ``cap``: a contact is new or did not push, or its friction ratio exceeded TRIGGER × cap."""
        lim = TRIGGER * cap
        cons = arb.contacts
        for i in range(arb.count):
            c = cons[i]
            jn = c.jnAcc
            if jn <= 0.0 or abs(c.jtAcc) > lim * jn:
                return True
        return False

    def arm(self) -> None:
        """Solve this step's contacts exactly (called by the hook, at most once per step matters)."""
        if not self.armed:
            self.armed = True
            if self.callback is None:
                ffi, lib = self.ffi, self.lib
                self.default = ffi.addressof(lib, "cpBodyUpdateVelocity")
                self.callback = ffi.callback("cpBodyVelocityFunc", self._velocity)
                self.each = ffi.callback("cpBodyArbiterIteratorFunc", self._collect)
            self.lib.cpBodySetVelocityUpdateFunc(self.body, self.callback)

    def _collect(self, body, arb, data):
        self.found.append(arb)

    def _velocity(self, body, gravity, damping, dt):
        lib = self.lib
        lib.cpBodyUpdateVelocity(body, gravity, damping, dt)
        lib.cpBodySetVelocityUpdateFunc(body, self.default)  # one step only: the hook arms the next
        self.armed = False
        try:
            self._solve(body, gravity, dt)
        except Exception:  # pragma: no cover - never let an exception cross the C callback
            import traceback

            traceback.print_exc()

    def _solve(self, body, gravity, dt):
        lib = self.lib
        self.found = []
        lib.cpBodyEachArbiter(body, self.each, self.ffi.NULL)
        arbs = self.found
        m_inv, i_inv = self.m_inv, self.i_inv
        v = lib.cpBodyGetVelocity(body)
        vx, vy, w = v.x, v.y, lib.cpBodyGetAngularVelocity(body)
        # contacts: (con, G rows n and t as (x, y, torque) with the sign of the part's side, A block, mu, e_n, e_t)
        cons = []
        for arb in arbs:
            a, b = arb.body_a, arb.body_b
            part_b = b == body
            other = a if part_b else b
            s = 1.0 if part_b else -1.0
            nx, ny = arb.n.x, arb.n.y
            tx, ty = -ny, nx
            fix = self.fixture
            mu = self.mu_wall if (lib.cpShapeGetCollisionType(arb.a) == fix
                                  or lib.cpShapeGetCollisionType(arb.b) == fix) else self.mu_arm
            arb.u = mu if math.isfinite(mu) else 1.0e30  # (the hook may have capped it before the step was armed)
            ov = lib.cpBodyGetVelocity(other)
            ow = lib.cpBodyGetAngularVelocity(other)
            svr = arb.surface_vr
            for i in range(arb.count):
                c = arb.contacts[i]
                r, ro = (c.r2, c.r1) if part_b else (c.r1, c.r2)
                rx, ry, ox, oy = r.x, r.y, ro.x, ro.y
                # the other body's point velocity, and the pair's relative velocity (b minus a) without the part
                pvx, pvy = ov.x - oy * ow, ov.y + ox * ow
                gn = (s * nx, s * ny, s * (rx * ny - ry * nx))
                gt = (s * tx, s * ty, s * (rx * ty - ry * tx))
                en = -s * (pvx * nx + pvy * ny) + svr.x * nx + svr.y * ny
                et = -s * (pvx * tx + pvy * ty) + svr.x * tx + svr.y * ty
                ann = m_inv * (gn[0] * gn[0] + gn[1] * gn[1]) + i_inv * gn[2] * gn[2]
                ant = m_inv * (gn[0] * gt[0] + gn[1] * gt[1]) + i_inv * gn[2] * gt[2]
                att = m_inv * (gt[0] * gt[0] + gt[1] * gt[1]) + i_inv * gt[2] * gt[2]
                cons.append([c, gn, gt, ann, ant, att, mu, en, et, 0.0, 0.0, arb, rx, ry, gn])
        if not cons:
            return
        if len(cons) > 1:
            _merge_points(cons, m_inv, i_inv)
        self.n_steps += 1
        # warm start from the previous exact step (same contact hash); velocities with those impulses
        warm = self.warm
        ux, uy, uw = vx, vy, w
        for k in cons:
            x = warm.get(k[0].hash)
            if x is not None:
                k[9], k[10] = x
                gn, gt = k[1], k[2]
                ux += m_inv * (gn[0] * x[0] + gt[0] * x[1])
                uy += m_inv * (gn[1] * x[0] + gt[1] * x[1])
                uw += i_inv * (gn[2] * x[0] + gt[2] * x[1])
        scale = abs(math.hypot(gravity.x, gravity.y)) * dt / m_inv
        sweeps = 0
        while True:
            sweeps += 1
            biggest = change = 0.0
            fallback = False
            for k in cons:
                c, gn, gt, ann, ant, att, mu, en, et, jn0, jt0 = k[:11]
                vn = gn[0] * ux + gn[1] * uy + gn[2] * uw + en
                vt = gt[0] * ux + gt[1] * uy + gt[2] * uw + et
                wn = vn - ann * jn0 - ant * jt0
                wt = vt - ant * jn0 - att * jt0
                jn, jt, mode = solve_contact(wn, wt, ann, ant, att, mu)
                djn, djt = jn - jn0, jt - jt0
                if djn != 0.0 or djt != 0.0:
                    ux += m_inv * (gn[0] * djn + gt[0] * djt)
                    uy += m_inv * (gn[1] * djn + gt[1] * djt)
                    uw += i_inv * (gn[2] * djn + gt[2] * djt)
                    k[9], k[10] = jn, jt
                    change = max(change, abs(djn), abs(djt))
                biggest = max(biggest, abs(jn), abs(jt))
                if mode == 3:
                    fallback = True
            if change <= TOL * (biggest + scale):
                break
            if sweeps >= MAX_SWEEPS:  # (a cycle: contacts that switch each other on and off) every mode, exactly
                x = enumerate_modes(cons, (vx, vy, w), m_inv, i_inv, biggest + scale)
                if x is None:
                    self.n_unconverged += 1
                else:
                    self.n_enumerated += 1
                    fallback = False
                    ux, uy, uw = vx, vy, w
                    for k, (jn, jt) in zip(cons, x):
                        k[9], k[10] = jn, jt
                        gn, gt = k[1], k[2]
                        ux += m_inv * (gn[0] * jn + gt[0] * jt)
                        uy += m_inv * (gn[1] * jn + gt[1] * jt)
                        uw += i_inv * (gn[2] * jn + gt[2] * jt)
                break
        self.n_sweeps += sweeps
        if fallback:
            self.n_fallback += 1
        lib.cpBodySetVelocity(body, (ux, uy))
        lib.cpBodySetAngularVelocity(body, uw)
        first = self.first
        self.warm = warm = {}
        for k in cons:
            c, gn, gt, jn, jt, arb = k[0], k[1], k[2], k[9], k[10], k[11]
            arb.state = first  # the impulses are in the velocities already: no cached (warm-start) impulse
            c.jnAcc, c.jtAcc = jn, jt
            c.tMass = 0.0  # the friction impulse stays as solved
            g = k[14]  # the contact's own point (Chipmunk's; a merged one solved at the common point)
            c.bounce = -(g[0] * ux + g[1] * uy + g[2] * uw + k[7])  # Chipmunk's normal update then gives 0
            warm[c.hash] = (jn, jt)


def _merge_points(cons, m_inv: float, i_inv: float) -> None:
    """Give contacts whose points on the part lie within :data:`SAME_POINT` of each other one common point (their
    mean): the torque rows of ``G`` and the blocks ``A`` of ``cons`` (as in :meth:`ExactSolve._solve`, the point
    relative to the part's CM in ``k[12:14]``) are recomputed in place (``k[14]``, the contact's own normal row, is
    kept for Chipmunk's normal target).

    Why: a vertex in a corner of two shapes (the cavity's floor and lip ramp) gets one contact per shape, a few µm
    apart, and Chipmunk's normal of one is often the part's edge normal or a segment end's, not the surface's. With
    friction μ ≳ 1 the two cones then hold opposite directions, and the exact solve finds a jam: a squeeze of
    ~10⁴ × the weight whose couple over those µm holds the part's weight torque, a part resting on one vertex
    (measured, feed trial 0 of seed 0). A point contact has no couple: the merged point takes it away."""
    k = len(cons)
    group = list(range(k))
    for i in range(k):
        for j in range(i + 1, k):
            if abs(cons[i][12] - cons[j][12]) < SAME_POINT and abs(cons[i][13] - cons[j][13]) < SAME_POINT:
                gi, gj = group[i], group[j]
                if gi != gj:
                    group = [gi if g == gj else g for g in group]
    for g in set(group):
        members = [cons[i] for i in range(k) if group[i] == g]
        if len(members) < 2:
            continue
        rx = sum(m[12] for m in members) / len(members)
        ry = sum(m[13] for m in members) / len(members)
        for m in members:
            gn, gt = m[1], m[2]
            nx, ny, tx, ty = gn[0], gn[1], gt[0], gt[1]  # signed with the part's side: the torque is r × (nx, ny)
            gn = (nx, ny, rx * ny - ry * nx)
            gt = (tx, ty, rx * ty - ry * tx)
            m[1], m[2] = gn, gt
            m[3] = m_inv * (gn[0] * gn[0] + gn[1] * gn[1]) + i_inv * gn[2] * gn[2]
            m[4] = m_inv * (gn[0] * gt[0] + gn[1] * gt[1]) + i_inv * gn[2] * gt[2]
            m[5] = m_inv * (gt[0] * gt[0] + gt[1] * gt[1]) + i_inv * gt[2] * gt[2]


def exact_solver(world):
    """An :class:`ExactSolve` for ``world``'s only part, or None (several parts, or no cffi binding)."""
    if world.n != 1:
        return None
    try:
        from pymunk._chipmunk import ffi, lib

        lib.cpBodyEachArbiter, lib.cpBodySetVelocityUpdateFunc, lib.CP_ARBITER_STATE_FIRST_COLLISION  # noqa: B018
        from .world import FIXTURE

        body = world.bodies[0]
        return ExactSolve(lib, ffi, body._body, body.mass, body.moment, world.mu_arm, world.mu_wall, FIXTURE)
    except (ImportError, AttributeError):  # pragma: no cover - another pymunk
        return None
