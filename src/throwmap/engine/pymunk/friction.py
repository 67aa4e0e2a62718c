"""Friction as Chipmunk can solve it: the per-contact cap that keeps its solver convergent.

Root cause
----------
Chipmunk's solver (sequential impulses) updates each contact's normal and
tangential impulse together from the same relative velocity, each with its own
diagonal effective mass: ``Δj_n = −v_n / K_nn``, ``Δj_t = −v_t / K_tt``, the
tangential one clamped to ``|j_t| ≤ μ j_n``. While the contact slides, ``j_t``
follows ``μ j_n``, so one update changes the normal velocity by
``(K_nn ± μ K_nt) Δj_n`` instead of ``K_nn Δj_n``: the iteration multiplies the
normal-velocity error by ``μ |K_nt| / K_nn`` each pass and diverges once
``μ |K_nt| > K_nn`` (the same ratio as Painlevé's condition,
D = K_nn − μ |K_nt| of :mod:`throwmap.kernels.rigid_body`). It then stops on
an arbitrary iterate, usually ``j_n = 0``, and the vertex sinks into the arm
(a part pivoting towards a landing, where the no-slip friction ratio grows
without bound as the normal force falls). With μ = ∞ given to pymunk as 10⁴
this happened in 37 of 40 long throws.

Fix
---
Before every solve (a ``pre_solve`` hook) each arbiter's friction is set to
``min(μ, CAP · min_c K_nn,c / |K_nt,c|)`` over its contacts c (``K`` the
contact's 2×2 inverse effective mass, both bodies; kinematic bodies add
nothing), so the iteration contracts by at least ``CAP`` per pass. A contact
whose friction ratio stays below the cap (sticking or sliding) is solved exactly
as before; one that would need more slides at the cap instead. That happens
where the no-slip friction ratio grows without bound (a pivot whose normal force
falls towards lift-off) and changes final x by ≲ 2 mm against model
"rigid_body" at μ = 3…∞ (tests/engine/test_engine_friction.py); results move by
< 0.3 mm between CAP = 0.7 and 0.9, by up to 8 mm at 0.5. ``n_capped`` counts
the solves where the cap was below the pair's μ.

One part: the exact solve
-------------------------
The cap is a change of model, not a discretisation error: a pivot at μ = 2–3 on a
tilted arm slipped earlier and faster and landed 0.5–1.1 mm away from "rigid_body"
and from an independent reference (tests/kernels/test_tilt_landing.py), and a
μ = ∞ pivot crept. With one part (:data:`EXACT`), a step where the cap binds on
an arbiter whose previous impulses came near the cap (or a new contact) is solved
exactly with the pair's μ instead (:mod:`.exact`); below that the capped μ
leaves the sticking solution unchanged and Chipmunk solves it as before. A run
where the cap never binds, and every run of several parts, is unchanged bit for
bit (tests/engine/test_high_friction.py).

In C
----
Where the engine's C helper is built (:mod:`.native`), the hook is :class:`NativeCap`: the
arithmetic of the raw hooks below (``native/friction.c``) and of the exact solve
(``native/exact.c``), operation for operation, without a call into Python per contact per step;
the Python hooks remain the reference it is tested against (tests/engine/test_native.py).
"""

from __future__ import annotations

import math

__all__ = ["CAP", "EXACT", "FrictionCap", "NativeCap", "attach_raw", "cap_bound", "install_friction_cap"]

EXACT = True
"""One part: solve the steps where the cap would bind exactly (:mod:`.exact`) instead of capping μ (read when a
run's hook is installed; False: the cap alone, without the exact solve)."""
CAP = 0.7
"""Largest μ |K_nt| / K_nn allowed: the solver's error shrinks by at least this factor per iteration."""


def cap_bound(part) -> float:
    """Smallest friction cap part ``part`` alone can meet against a fixed body (dimensionless).

    For a vertex at distance ℓ from the CM and radius of gyration ρ, at angle θ
    to the normal, K_nn/|K_nt| = (ρ² + ℓ² sin²θ)/(ℓ² |sinθ cosθ|); its minimum
    over θ (a quadratic in tan θ) is 2 √(a (1 + a)) with a = ρ²/ℓ². A pair μ at
    or below ``CAP`` times the minimum over the vertices never needs the hook.
    """
    rho2 = part.radius_of_gyration**2
    best = math.inf
    for wx, wy in part.w.tolist():
        l2 = wx * wx + wy * wy
        if l2 <= 0.0:
            continue
        a = rho2 / l2
        best = min(best, 2.0 * math.sqrt(a * (1.0 + a)))
    return CAP * best


class FrictionCap:
    """The ``pre_solve`` hook of one run: sets each arbiter's friction to the convergent value.

    ``mu_of(shapes)`` gives the pair's Coulomb μ (may be ``inf``) from the arbiter's two shapes; ``inv``
    maps ``id(body)`` to ``(1/m, 1/I)`` of each dynamic body (absent: kinematic).
    """

    __slots__ = ("inv", "mu_of", "n_capped", "exact")

    def __init__(self, inv: dict, mu_of):
        self.inv = inv
        self.mu_of = mu_of
        self.n_capped = 0
        self.exact = None  # one part: its exact solver (.exact), which replaces the cap

    def __call__(self, arbiter, space_, data):
        shapes = arbiter.shapes  # one call for the pair's μ and its bodies (each arbiter property is a C round trip)
        mu = self.mu_of(shapes)
        cps = arbiter.contact_point_set
        n = cps.normal
        nx, ny = n.x, n.y
        inv = self.inv
        bodies = (shapes[0].body, shapes[1].body)
        cap = math.inf
        for c in cps.points:
            knn = knt = 0.0
            for b, p in zip(bodies, (c.point_a, c.point_b)):
                im = inv.get(id(b))
                if im is None:
                    continue
                q = b.position
                rx, ry = p.x - q.x, p.y - q.y
                rn = rx * ny - ry * nx
                rt = rx * nx + ry * ny
                knn += im[0] + rn * rn * im[1]
                knt += rn * rt * im[1]
            if knt != 0.0:
                cap = min(cap, CAP * knn / abs(knt))
        if cap < mu:
            self.n_capped += 1
            if self.exact is None or not self.exact.wanted(arbiter._arbiter, cap):
                arbiter.friction = cap
            else:  # the step is solved exactly with the pair's μ (.exact)
                self.exact.arm()
                arbiter.friction = mu if math.isfinite(mu) else 1.0e30
        else:
            arbiter.friction = mu if math.isfinite(mu) else 1.0e30


def install_friction_cap(world) -> FrictionCap | None:
    """The friction hook of ``world``'s space (its ``n_capped`` counts capped solves), or None.

    Returns None where no pair needs it: one part, and arm and fixture μ at most
    what the part meets uncapped (:func:`cap_bound`). Otherwise the caller sets
    the hook as the space's wildcard ``pre_solve`` (a pair-specific handler
    would replace the wildcard ``begin``/``separate`` bookkeeping of
    :mod:`.contacts`); part–part pairs always need it (pymunk would multiply the
    shapes' values).
    """
    from .world import FIXTURE, PART

    inv = {id(b): (1.0 / b.mass, 1.0 / b.moment) for b in world.bodies}
    mu_arm, mu_wall, mu_pp = world.mu_arm, world.mu_wall, world.mu_pp

    def mu_of(shapes):
        ta, tb = shapes[0].collision_type, shapes[1].collision_type
        if ta == PART and tb == PART:
            return mu_pp
        return mu_wall if FIXTURE in (ta, tb) else mu_arm

    bound = min(cap_bound(p) for p in world.parts)
    if world.n == 1 and not any(s.collision_type == FIXTURE for s in world.static_shapes):
        if mu_arm <= bound:
            return None
        fast = _native_hook(world, 1, mu_arm, mu_wall, mu_pp) or _single_part_hook(world, mu_arm)
        if fast is not None:
            return _with_exact(fast, world)
    elif world.n == 1 and not (mu_arm <= bound and mu_wall <= bound):
        fast = _native_hook(world, 2, mu_arm, mu_wall, mu_pp) \
            or _single_part_fixture_hook(world, mu_arm, mu_wall, FIXTURE)
        if fast is not None:
            return _with_exact(fast, world)
    if world.n == 1 and mu_arm <= bound and mu_wall <= bound:
        return None
    hook = (_native_hook(world, 3, mu_arm, mu_wall, mu_pp) or _multi_part_hook(world, mu_arm, mu_wall, mu_pp)) \
        if world.n > 1 else None
    if hook is None:
        hook = FrictionCap(inv, mu_of)
    return _with_exact(hook, world)


def _with_exact(hook, world):
    """``hook`` with its exact solver (:mod:`.exact`) where :data:`EXACT` is on."""
    if isinstance(hook, NativeCap):
        if EXACT and world.n == 1:
            hook.solve_exactly()
        return hook
    if EXACT:
        from .exact import exact_solver

        hook.exact = exact_solver(world)
    return hook


class NativeCap:
    """The friction hook in the engine's C helper (:mod:`.native`, ``friction.c``): the arithmetic of
    :class:`_SinglePartCap` (``kind`` 1), :class:`_SinglePartFixtureCap` (2) or :class:`_MultiPartCap` (3), operation for
    operation, and one part's exact solve (``exact.c``, the arithmetic of :class:`.exact.ExactSolve`), without a call
    into Python per contact per step. ``exact`` is True once the exact solve is on (else None), ``n_capped`` as theirs."""

    __slots__ = ("run", "exact")

    def __init__(self, run, kind: int, mu_arm: float, mu_wall: float, mu_pp: float):
        from ..settings import engine_mu
        from .world import FIXTURE

        u_arm, u_fix = engine_mu(mu_arm), engine_mu(mu_wall)
        run.set_hook(kind, CAP, mu_arm, mu_wall, FIXTURE, not (u_arm == u_fix and mu_arm != mu_wall), u_arm, u_fix,
                     mu_pp)
        self.run = run
        self.exact = None

    def solve_exactly(self) -> None:
        """Solve one part's steps where the cap binds exactly (:mod:`.exact`)."""
        from . import exact as X

        self.run.solve_exactly(X.TRIGGER, X.MAX_SWEEPS, X.TOL, X.SAME_POINT, X.MU_SKID, X.enumerate_modes)
        self.exact = True

    @property
    def n_capped(self) -> int:
        return self.run.n_capped


def _native_hook(world, kind: int, mu_arm: float, mu_wall: float, mu_pp: float):
    """The C hook (:class:`NativeCap`) where ``world`` runs with the C helper, else None."""
    return None if world.native is None else NativeCap(world.native, kind, mu_arm, mu_wall, mu_pp)


class _SinglePartCap:
    """:class:`FrictionCap` for one part on a bare arm on Chipmunk's raw calls (same values, ~5× cheaper)."""

    __slots__ = ("lib", "body", "rho2", "mu", "n_capped", "callback", "exact")

    def __init__(self, lib, body, rho2: float, mu: float):
        self.lib, self.body, self.rho2, self.mu = lib, body, rho2, mu
        self.n_capped = 0
        self.callback = None
        self.exact = None

    def __call__(self, arbiter, space_, data):
        self.raw(arbiter._arbiter, None, None)

    def raw(self, arb, space_, data):
        """The hook on the raw ``cpArbiter *`` (:func:`attach_raw`)."""
        _set_capped(self, arb, self.lib.cpArbiterGetPointA, self.mu)


def _set_capped(hook, arb, point, mu: float) -> None:
    """Set raw arbiter ``arb``'s friction to min(μ, the cap over the part's contact points ``point(arb, i)``)
    (one part: ``hook.body``, ``hook.rho2``); count a capped solve in ``hook.n_capped``."""
    lib = hook.lib
    n = lib.cpArbiterGetNormal(arb)
    nx, ny = n.x, n.y
    q = lib.cpBodyGetPosition(hook.body)
    rho2 = hook.rho2
    cap = math.inf
    for i in range(lib.cpArbiterGetCount(arb)):
        p = point(arb, i)
        rx, ry = p.x - q.x, p.y - q.y
        rn = rx * ny - ry * nx
        rt = rx * nx + ry * ny
        if rn * rt != 0.0:  # per unit mass: K_nn = 1 + rn²/ρ², K_nt = rn rt/ρ²
            cap = min(cap, CAP * (rho2 + rn * rn) / abs(rn * rt))
    if cap < mu:
        hook.n_capped += 1
        if hook.exact is None or not hook.exact.wanted(arb, cap):
            lib.cpArbiterSetFriction(arb, cap)
        else:  # the step is solved exactly with the pair's μ (.exact)
            hook.exact.arm()
            lib.cpArbiterSetFriction(arb, mu if math.isfinite(mu) else 1.0e30)
    else:
        lib.cpArbiterSetFriction(arb, mu if math.isfinite(mu) else 1.0e30)


def _single_part_hook(world, mu: float):
    """The raw-call hook for one part on a bare arm, or None where pymunk's cffi binding is missing.

    Used whatever ``world.cp.raw`` says, so runs through pymunk's public API stay
    bit-identical to raw ones (``tests/engine/test_engine_layout.py``)."""
    try:
        from pymunk._chipmunk import lib

        lib.cpArbiterGetPointA, lib.cpArbiterSetFriction  # noqa: B018
        body = world.bodies[0]._body
    except (ImportError, AttributeError):  # pragma: no cover - another pymunk
        return None
    return _SinglePartCap(lib, body, world.rho2[0], mu)


class _SinglePartFixtureCap:
    """:class:`FrictionCap` for one part on an arm with fixtures, on Chipmunk's raw calls (the same formula:
    the part's contact point, μ of the arm or of the fixture the other shape belongs to; ~3× cheaper).

    Fast path (``by_u``): the pair's μ is read back from the arbiter, whose friction Chipmunk resets every step
    to the product of its shapes' (arm or fixture shape: :func:`~throwmap.engine.settings.engine_mu` of the
    pair's μ; part shape: 1.0, so the product is that value exactly), and the contact points and normal come
    from one ``cpArbiterGetContactPointSet`` call: four C calls instead of nine, the same numbers (its
    ``pointA`` is the point of the body ``cpArbiterGetBodies`` names first). ``by_u`` is None (the shape
    look-up instead) where two different μ map to the same engine value (∞ and :data:`NO_SLIP_MU`)."""

    __slots__ = ("lib", "body", "rho2", "mu", "mu_fix", "fix", "sa", "sb", "ba", "bb", "by_u", "n_capped", "callback",
                 "raw", "exact")

    def __init__(self, lib, ffi, body, rho2: float, mu: float, mu_fix: float, fix: int):
        from ..settings import engine_mu

        self.lib, self.body, self.rho2, self.mu, self.mu_fix, self.fix = lib, body, rho2, mu, mu_fix, fix
        self.sa, self.sb = ffi.new("cpShape *[1]"), ffi.new("cpShape *[1]")
        self.ba, self.bb = ffi.new("cpBody *[1]"), ffi.new("cpBody *[1]")
        u_arm, u_fix = engine_mu(mu), engine_mu(mu_fix)
        self.by_u = None if (u_arm == u_fix and mu != mu_fix) else {u_arm: mu, u_fix: mu_fix}
        self.n_capped = 0
        self.callback = None
        self.exact = None
        self.raw = self._slow if self.by_u is None else self._fast()

    def __call__(self, arbiter, space_, data):
        self.raw(arbiter._arbiter, None, None)

    def _slow(self, arb, space_=None, data=None):
        """The hook on the raw ``cpArbiter *``, μ and the part's body from the arbiter's shapes."""
        lib = self.lib
        lib.cpArbiterGetShapes(arb, self.sa, self.sb)
        a, b = self.sa[0], self.sb[0]
        fix = self.fix
        mu = self.mu_fix if (lib.cpShapeGetCollisionType(a) == fix or lib.cpShapeGetCollisionType(b) == fix) \
            else self.mu
        point = lib.cpArbiterGetPointA if lib.cpShapeGetBody(a) == self.body else lib.cpArbiterGetPointB
        _set_capped(self, arb, point, mu)

    def _fast(self):
        """The hook on the raw ``cpArbiter *`` (``self.raw``, :func:`attach_raw`) as a closure over its
        constants: μ read back from the arbiter (``by_u``), the points from its contact point set; the same
        arithmetic as :func:`_set_capped`, so the same friction bit for bit."""
        lib, hook, slow = self.lib, self, self._slow
        get_u = lib.cpArbiterGetFriction
        # engine value -> (μ, the friction set where the cap does not bind: μ, or 1e30 for ∞)
        by_u = {u: (mu, mu if math.isfinite(mu) else 1.0e30) for u, mu in self.by_u.items()}.get
        get_bodies, ba, bb, body = lib.cpArbiterGetBodies, self.ba, self.bb, self.body
        get_points, get_position, set_u = lib.cpArbiterGetContactPointSet, lib.cpBodyGetPosition, lib.cpArbiterSetFriction
        rho2, inf = self.rho2, math.inf

        def raw(arb, space_=None, data=None):
            u = get_u(arb)
            found = by_u(u)
            if found is None:  # pragma: no cover - an arbiter whose friction another hook changed
                return slow(arb)
            mu, uncapped = found
            get_bodies(arb, ba, bb)
            part_a = ba[0] == body
            cps = get_points(arb)
            n = cps.normal
            nx, ny = n.x, n.y
            q = get_position(body)
            qx, qy = q.x, q.y
            cap = inf
            pts = cps.points
            for i in range(cps.count):
                c = pts[i]
                p = c.pointA if part_a else c.pointB
                rx, ry = p.x - qx, p.y - qy
                rn = rx * ny - ry * nx
                rt = rx * nx + ry * ny
                if rn * rt != 0.0:  # per unit mass: K_nn = 1 + rn²/ρ², K_nt = rn rt/ρ² (min(cap, v) as an if)
                    v = CAP * (rho2 + rn * rn) / abs(rn * rt)
                    if v < cap:
                        cap = v
            if cap < mu:
                hook.n_capped += 1
                exact = hook.exact
                if exact is None or not exact.wanted(arb, cap):
                    set_u(arb, cap)
                else:  # the step is solved exactly with the pair's μ (.exact)
                    exact.arm()
                    if uncapped != u:
                        set_u(arb, uncapped)
            elif uncapped != u:  # (finite μ: the arbiter already holds it)
                set_u(arb, uncapped)

        return raw


def _single_part_fixture_hook(world, mu_arm: float, mu_fix: float, fix: int):
    """The raw-call hook for one part on an arm with fixtures, or None where pymunk's cffi binding is missing."""
    try:
        from pymunk._chipmunk import ffi, lib

        lib.cpArbiterGetShapes, lib.cpShapeGetCollisionType, lib.cpShapeGetBody  # noqa: B018
        lib.cpArbiterGetBodies, lib.cpArbiterGetFriction, lib.cpArbiterGetContactPointSet  # noqa: B018
        body = world.bodies[0]._body
    except (ImportError, AttributeError):  # pragma: no cover - another pymunk
        return None
    return _SinglePartFixtureCap(lib, ffi, body, world.rho2[0], mu_arm, mu_fix, fix)


class _MultiPartCap:
    """:class:`FrictionCap` for several parts on Chipmunk's raw calls: the same arithmetic in the same order (so
    the same friction bit for bit), without pymunk's wrappers (an :class:`pymunk.Arbiter`, two shapes, a contact
    point set and two bodies' positions built per contact per step; two-part runs spent ¾ of their time in the
    Python hook, now ~¼). ``inv`` maps a raw ``cpBody *`` (cffi pointers hash by address) to ``(1/m, 1/I)`` of a
    dynamic body; a body absent from it (the arm, kinematic) adds nothing.

    The pair's μ: two dynamic bodies are two parts (μ_pp); otherwise the arbiter's friction, which Chipmunk resets
    every step to the product of its shapes' (part shape 1.0, arm or fixture shape the engine value of its μ),
    names arm or fixture (``by_u``), or, where arm and fixture share an engine value but not a μ, the shapes'
    collision types do. A pair of μ = 0 (the frictionless wall) can never be capped and is left as it is."""

    __slots__ = ("n_capped", "callback", "exact", "raw")

    def __init__(self, lib, ffi, inv: dict, mu_arm: float, mu_wall: float, mu_pp: float, part: int, fix: int):
        from ..settings import engine_mu

        self.n_capped = 0
        self.callback = None
        self.exact = None
        sa, sb = ffi.new("cpShape *[1]"), ffi.new("cpShape *[1]")
        ba, bb = ffi.new("cpBody *[1]"), ffi.new("cpBody *[1]")
        get_shapes, get_type, get_bodies = lib.cpArbiterGetShapes, lib.cpShapeGetCollisionType, lib.cpArbiterGetBodies
        get_points, get_position, set_u = lib.cpArbiterGetContactPointSet, lib.cpBodyGetPosition, lib.cpArbiterSetFriction
        get_u = lib.cpArbiterGetFriction
        inv_of, inf, hook = inv.get, math.inf, self
        u_arm, u_fix = engine_mu(mu_arm), engine_mu(mu_wall)

        def pair(mu):  # (μ, the friction set where the cap does not bind)
            return mu, (mu if math.isfinite(mu) else 1.0e30)

        by_u = None if (u_arm == u_fix and mu_arm != mu_wall) else {u_arm: pair(mu_arm), u_fix: pair(mu_wall)}.get
        arm_pair, fix_pair, pp_pair = pair(mu_arm), pair(mu_wall), pair(mu_pp)

        def raw(arb, space_=None, data=None):
            get_bodies(arb, ba, bb)
            body_a, body_b = ba[0], bb[0]
            im_a, im_b = inv_of(body_a), inv_of(body_b)
            if im_a is not None and im_b is not None:
                mu, uncapped = pp_pair
            else:
                found = None if by_u is None else by_u(get_u(arb))
                if found is None:
                    get_shapes(arb, sa, sb)
                    found = fix_pair if (get_type(sa[0]) == fix or get_type(sb[0]) == fix) else arm_pair
                mu, uncapped = found
                if mu == 0.0:  # never capped, and the arbiter already holds 0
                    return
            cps = get_points(arb)
            n = cps.normal
            nx, ny = n.x, n.y
            cap = inf
            pts = cps.points
            if im_b is None or im_a is None:  # a part and the arm: one body's terms (0.0 + x is x: the same bits)
                if im_b is None:
                    q, m0, m1, on_a = get_position(body_a), im_a[0], im_a[1], True
                else:
                    q, m0, m1, on_a = get_position(body_b), im_b[0], im_b[1], False
                qx, qy = q.x, q.y
                for i in range(cps.count):
                    p = pts[i].pointA if on_a else pts[i].pointB
                    rx, ry = p.x - qx, p.y - qy
                    rn = rx * ny - ry * nx
                    knt = rn * (rx * nx + ry * ny) * m1
                    if knt != 0.0:
                        v = CAP * (m0 + rn * rn * m1) / abs(knt)
                        if v < cap:
                            cap = v
                if cap < mu:
                    hook.n_capped += 1
                    set_u(arb, cap)
                else:
                    set_u(arb, uncapped)
                return
            qa = get_position(body_a)
            qb = get_position(body_b)
            for i in range(cps.count):
                c = pts[i]
                knn = knt = 0.0
                if im_a is not None:
                    p = c.pointA
                    rx, ry = p.x - qa.x, p.y - qa.y
                    rn = rx * ny - ry * nx
                    rt = rx * nx + ry * ny
                    knn += im_a[0] + rn * rn * im_a[1]
                    knt += rn * rt * im_a[1]
                if im_b is not None:
                    p = c.pointB
                    rx, ry = p.x - qb.x, p.y - qb.y
                    rn = rx * ny - ry * nx
                    rt = rx * nx + ry * ny
                    knn += im_b[0] + rn * rn * im_b[1]
                    knt += rn * rt * im_b[1]
                if knt != 0.0:
                    v = CAP * knn / abs(knt)
                    if v < cap:
                        cap = v
            if cap < mu:
                hook.n_capped += 1
                set_u(arb, cap)
            else:
                set_u(arb, uncapped)

        self.raw = raw

    def __call__(self, arbiter, space_, data):
        self.raw(arbiter._arbiter, None, None)


def _multi_part_hook(world, mu_arm: float, mu_wall: float, mu_pp: float):
    """The raw-call hook for several parts, or None where pymunk's cffi binding is missing (then
    :class:`FrictionCap`, the same values through pymunk's API)."""
    from .world import FIXTURE, PART

    try:
        from pymunk._chipmunk import ffi, lib

        lib.cpArbiterGetShapes, lib.cpShapeGetCollisionType, lib.cpArbiterGetBodies  # noqa: B018
        lib.cpArbiterGetContactPointSet, lib.cpBodyGetPosition, lib.cpArbiterSetFriction  # noqa: B018
        lib.cpArbiterGetFriction  # noqa: B018
        inv = {b._body: (1.0 / b.mass, 1.0 / b.moment) for b in world.bodies}
    except (ImportError, AttributeError):  # pragma: no cover - another pymunk
        return None
    return _MultiPartCap(lib, ffi, inv, mu_arm, mu_wall, mu_pp, PART, FIXTURE)


def attach_raw(space, hook) -> bool:
    """Point ``space``'s wildcard handler (set by ``space.on_collision(pre_solve=hook)``) straight at
    ``hook.raw``, a cffi callback on the raw ``cpArbiter *``: the same hook without pymunk's per-call
    wrapper (a handle look-up, an :class:`pymunk.Arbiter` and a dict look-up per contact per step).
    The callback is kept on ``hook.callback`` (it lives as long as the space's handler holds ``hook``).
    Returns False, changing nothing, where ``hook`` has no raw entry or cffi cannot make the callback."""
    raw = getattr(hook, "raw", None)
    if raw is None:
        return False
    try:
        from pymunk._chipmunk import ffi

        handler = space._handlers[(None, None)]
        if handler.pre_solve is not hook:
            return False
        callback = ffi.callback("cpCollisionPreSolveFunc", raw)
        handler._handler.preSolveFunc = callback
    except Exception:  # pragma: no cover - another pymunk, or no executable memory for callbacks
        return False
    hook.callback = callback
    return True
