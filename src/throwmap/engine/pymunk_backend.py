"""Full rigid-body simulation of throws in pymunk (Chipmunk2D): the "engine" model.

The arm is a kinematic body turning about the joint (the origin), built from
convex solid pieces under its surface profile (:func:`throwmap.system.fixtures.arm_solids`);
fixtures are kinematic pieces on the same motion. Parts are convex polygons with
their own mass, CM and inertia (lead weights included). Restitution is zero on
every shape; friction is set per pair of bodies (:class:`Friction`): pymunk
multiplies the two shapes' values, so arm and wall shapes carry the pair's μ and
part shapes carry 1, and part–part contacts get their μ in a ``pre_solve`` hook.

Stepping
--------
While any part is in or near contact the space advances by the fixed step
``dt`` (0.125 ms by default, the converged value). While every part is clear of
everything by more than ``flight_margin``, the parts are advanced by the exact
ballistic solution, in leaps short enough that no vertex can reach any shape
(a bound on relative vertex speeds); this removes pymunk's free-flight drift of
g·t·dt/2 and most of the steps.

Checks
------
* penetration: every millisecond, each part vertex is tested against the arm,
  fixtures and other parts; deeper than ``penetration_tol`` → status
  ``penetration`` (pymunk can lose grazing high-friction contacts: zero impulse,
  a vertex sinking millimetres into the arm) — that result is refused.
* settling: after the arm has stopped, every part slower than ``settle_speed``
  and ``settle_spin`` for ``settle_hold`` → status ``ok``; ``t_max`` → ``timeout``.
* escape: a part whose CM drops below the arm's underside has left the arm:
  ``behind_joint`` if it is behind the joint, else ``off_end``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import ThrowmapError
from ..system.fixtures import arm_solids
from ..kernels import codes as C
from ..throws.outcome import Status, ThrowOutcome
from ..throws.trajectory import Trajectory, state_from_pose
from .realisation import ImpulseThrow, check_realisation
from .scene import Placement, Scene
from .settings import EngineSettings, engine_mu

__all__ = ["EngineRun", "simulate"]

_ARM, _FIXTURE, _PART = 1, 2, 3
_HOP_MIN = 1e-3  # s a part must stay out of contact for a separation to count as a hop
_CHECK_EVERY = 1e-3  # s between penetration/clearance checks while stepping


def _pymunk():
    try:
        import pymunk
    except ImportError:  # pragma: no cover - pymunk is a dependency
        raise ThrowmapError("engine", "pymunk is not installed: pip install pymunk") from None
    return pymunk


@dataclass(frozen=True, slots=True)
class EngineRun:
    """The result of :func:`simulate` (SI units, arm frame unless stated).

    ``status`` is the run's overall status (the first part's failure, else ok);
    ``statuses``/``states``/``poses`` are per part: ``states[i] = (x, side, tilt)``
    read in the arm frame at the end (see :func:`throwmap.throws.trajectory.state_from_pose`),
    ``poses[i]`` the arm-frame pose ``(x, y, φ)``. ``records`` is (P, NREC) per
    unit mass (see :mod:`throwmap.kernels.codes`; entries an engine cannot
    measure are nan). ``alpha`` is the arm's rest angle at the end.
    """

    scene: Scene
    status: Status
    statuses: tuple
    states: tuple
    poses: tuple
    records: np.ndarray
    t_end: float
    n_steps: int
    n_leaps: int
    penetration_max: float
    alpha: float
    trajectory: Trajectory | None = None
    message: str = ""
    retries: int = 0

    def outcome(self, i: int = 0, *, x0=None, side0=None, omega=0.0, model="engine") -> ThrowOutcome:
        """Part ``i``'s result as a :class:`~throwmap.ThrowOutcome`."""
        part = self.scene.placements[i].part
        pl = self.scene.placements[i]
        if x0 is None:
            x0, side0, _ = state_from_pose(part, pl.arm_pose(self.scene.arm.h))
        x, side, _ = self.states[i]
        return ThrowOutcome.from_record(part, x0, side0, omega, model, x, side, self.statuses[i], self.records[i])

    def next_scene(self, **changes) -> Scene:
        """A scene starting from this run's end (final poses at rest, arm at ``alpha``)."""
        pls = tuple(Placement(p.part, pose=pose) for p, pose in zip(self.scene.placements, self.poses))
        kw = dict(arm=self.scene.arm, placements=pls, fixtures=self.scene.fixtures, alpha=self.alpha,
                  friction=self.scene.friction)
        kw.update(changes)
        return Scene(**kw)


class _PartTrack:
    """Per-part bookkeeping of contacts and events during a run."""

    __slots__ = ("n_contacts", "armed", "ever", "t_sep", "rec", "last_side", "pre", "need_post", "fell", "status")

    def __init__(self):
        self.n_contacts = 0
        self.armed = False  # the part has been out of contact since the start (released)
        self.ever = False  # it has touched something since release
        self.t_sep = None
        self.rec = np.full(C.NREC, math.nan)
        for k in (C.N_IMPACTS, C.N_FLIPS, C.N_LIFTOFFS, C.N_PULL):
            self.rec[k] = 0.0
        self.rec[C.PENETRATION_MAX] = 0.0
        self.last_side = None
        self.pre = None
        self.need_post = False
        self.fell = None
        self.status = Status.OK


def _nearest_side(betas, phi):
    """(side, tilt) of the resting orientation nearest to body angle ``phi`` (arm frame)."""
    best, kb = math.inf, 0
    for k, b in enumerate(betas):
        d = (phi - b + math.pi) % (2.0 * math.pi) - math.pi
        if abs(d) < abs(best):
            best, kb = d, k
    return kb, best


def _rot(a):
    c, s = math.cos(a), math.sin(a)
    return c, s


def simulate(scene: Scene, realisation=None, settings: EngineSettings | None = None, *, record: bool = False,
             progress=None, run_for: float | None = None) -> EngineRun:
    """Simulate one throw (or arm motion) of every part in ``scene`` until all settle.

    ``realisation``: :class:`ImpulseThrow` (default ω = 0: just settle),
    :class:`FiniteThrow`, :class:`RecoilThrow` or :class:`TiltTo`. With
    ``record=True`` the run's :class:`~throwmap.throws.trajectory.Trajectory` is kept.
    ``progress(t, t_max)`` is called every simulated 10 ms if given.
    ``run_for`` (s): simulate exactly this long instead of stopping once settled.

    A run that loses a contact (status ``penetration``) is repeated with half the
    step, up to ``settings.retries`` times; if it still fails, the failure is
    returned (with its message), never the result.
    """
    settings = EngineSettings() if settings is None else settings
    if not isinstance(settings, EngineSettings):
        raise ThrowmapError("settings", "must be an EngineSettings")
    run = _simulate_once(scene, realisation, settings, record, progress, run_for)
    tries = 0
    while run.status == Status.PENETRATION and tries < settings.retries:
        tries += 1
        finer = replace(settings, dt=settings.dt / 2**tries, settle_hold=max(settings.settle_hold, 4 * settings.dt))
        first = run.message
        run = _simulate_once(scene, realisation, finer, record, progress, run_for)
        run = replace(run, message=(run.message + "; " if run.message else "")
                      + f"retried at dt = {finer.dt:g} s after: {first}", retries=tries)
    return run


def _simulate_once(scene, realisation, settings, record, progress, run_for) -> EngineRun:
    pm = _pymunk()
    if not isinstance(scene, Scene):
        raise ThrowmapError("scene", "must be a Scene")
    realisation = ImpulseThrow(0.0) if realisation is None else check_realisation(realisation)
    t_max = settings.t_max
    if run_for is not None:
        if isinstance(run_for, bool) or not isinstance(run_for, (int, float)) or not run_for > 0 \
                or not math.isfinite(run_for):
            raise ThrowmapError("run_for", f"must be a positive number of seconds, got {run_for!r}")
        t_max = float(run_for)
    arm = scene.arm
    h, g = arm.h, arm.g
    L = scene.length(settings.default_length)
    dt = settings.dt
    alpha = scene.alpha
    end_alpha = alpha + (realisation.delta if hasattr(realisation, "delta") else 0.0)

    space = pm.Space()
    space.gravity = (0.0, -g)
    space.iterations = int(settings.iterations)
    space.collision_slop = settings.collision_slop
    space.damping = 1.0

    arm_body = pm.Body(body_type=pm.Body.KINEMATIC)
    arm_body.position = (0.0, 0.0)
    a0 = alpha + realisation.angle(0.0)
    arm_body.angle = a0
    arm_pieces, fixture_pieces = arm_solids(h, L, settings.arm_thickness, scene.fixtures)
    mu_arm = engine_mu(scene.mu("arm"))
    mu_wall = engine_mu(scene.mu("wall"))
    static_shapes = []
    corners_local = []
    for piece, ctype, mu in [(p, _ARM, mu_arm) for p in arm_pieces] + [(p, _FIXTURE, mu_wall) for p in fixture_pieces]:
        s = pm.Poly(arm_body, [tuple(v) for v in piece])
        s.friction = mu
        s.elasticity = 0.0
        s.collision_type = ctype
        static_shapes.append(s)
        corners_local.extend(tuple(v) for v in piece)
    space.add(arm_body, *static_shapes)
    corners_local = np.array(corners_local)

    bodies, shapes, tracks, parts = [], [], [], []
    c0, s0 = _rot(a0)
    for i, pl in enumerate(scene.placements):
        part = pl.part
        m = part.mass
        body = pm.Body(m, m * part.radius_of_gyration**2)
        x, y, phi = pl.arm_pose(h)
        body.position = (c0 * x - s0 * y, s0 * x + c0 * y)
        body.angle = phi + a0
        vx, vy, w = pl.velocity
        if realisation.impulsive and realisation.omega > 0:
            # paper Sec. III-B: the part leaves with the arm point's velocity ω × r and spin ω
            om = realisation.omega
            px, py = body.position
            vx, vy, w = vx - om * py, vy + om * px, w + om
        else:
            vx, vy = c0 * vx - s0 * vy, s0 * vx + c0 * vy
        body.velocity = (vx, vy)
        body.angular_velocity = w
        shp = pm.Poly(body, [tuple(v) for v in part.w])
        shp.friction = 1.0
        shp.elasticity = 0.0
        shp.collision_type = _PART
        shp.filter = pm.ShapeFilter(group=i + 1)
        space.add(body, shp)
        bodies.append(body)
        shapes.append(shp)
        tracks.append(_PartTrack())
        parts.append(part)
    index = {id(b): i for i, b in enumerate(bodies)}
    betas = [tuple(float(v) for v in p.beta) for p in parts]
    for i, b in enumerate(bodies):
        tracks[i].last_side = _nearest_side(betas[i], b.angle - arm_body.angle)[0]
    mu_pp = engine_mu(scene.mu("part"))
    now = [0.0]
    finished = [False]
    need_post = [False]
    last_begin = [-math.inf]

    def _pp_friction(arbiter, space_, data):
        arbiter.friction = mu_pp

    space.on_collision(_PART, _PART, pre_solve=_pp_friction)

    def _begin(arbiter, space_, data):
        last_begin[0] = now[0]
        for b in arbiter.bodies:
            i = index.get(id(b))
            if i is None:
                continue
            tr = tracks[i]
            if tr.n_contacts == 0 and tr.armed:
                t = now[0]
                if not tr.ever:
                    tr.ever = True
                    tr.rec[C.T_FLIGHT] = t
                    tr.pre = (tuple(b.velocity), b.angular_velocity, b.angle, tuple(b.position))
                    tr.need_post = True
                    need_post[0] = True
                    pts = arbiter.contact_point_set.points
                    if pts:
                        p = pts[0].point_a if arbiter.shapes[0].body is b else pts[0].point_b
                        p = (p.x, p.y)
                        ca, sa = _rot(arm_body.angle)
                        tr.rec[C.CONTACT_X] = ca * p[0] + sa * p[1]
                        lv = b.world_to_local(p)
                        dist = np.hypot(parts[i].w[:, 0] - lv[0], parts[i].w[:, 1] - lv[1])
                        tr.rec[C.CONTACT_VERTEX] = float(np.argmin(dist))
                        events.append((t, f"impact v{int(parts[i].user_index[int(np.argmin(dist))])}"))
                    tr.rec[C.N_IMPACTS] += 1.0
                elif tr.t_sep is not None and (tr.t_sep == -math.inf or t - tr.t_sep >= _HOP_MIN):
                    tr.rec[C.N_IMPACTS] += 1.0
                tr.t_sep = None
            tr.n_contacts += 1

    def _separate(arbiter, space_, data):
        if finished[0] or arbiter.is_removal:
            return
        for b in arbiter.bodies:
            i = index.get(id(b))
            if i is None:
                continue
            tr = tracks[i]
            tr.n_contacts = max(tr.n_contacts - 1, 0)
            if tr.n_contacts == 0 and not arbiter.is_removal and tr.ever:
                tr.t_sep = now[0]

    space.on_collision(begin=_begin, separate=_separate)

    # ------------------------------------------------------------------ helpers
    all_other = {i: [s for s in static_shapes] + [shapes[j] for j in range(len(shapes)) if j != i]
                 for i in range(len(shapes))}
    R = [float(np.max(np.hypot(p.w[:, 0], p.w[:, 1]))) for p in parts]
    for i, (b, p) in enumerate(zip(bodies, parts)):
        tr = tracks[i]
        v = b.velocity
        y_arm = -s0 * b.position.x + c0 * b.position.y
        tr.rec[C.E_RELEASE] = 0.5 * (v.x**2 + v.y**2 + p.radius_of_gyration**2 * b.angular_velocity**2) + g * (y_arm - h)

    def world_vertices(i):
        return [bodies[i].local_to_world(tuple(v)) for v in parts[i].w]

    wlists = [[(float(a), float(b)) for a, b in p.w] for p in parts]
    plain_arm = not scene.fixtures and len(parts) == 1

    def penetration(i):
        """Deepest penetration (m) of part i's vertices into the arm, fixtures or other parts."""
        deepest = 0.0
        if plain_arm:  # fast path: depth below the flat surface line, in the arm frame
            b = bodies[i]
            ca, sa = _rot(arm_body.angle)
            c, s = _rot(b.angle)
            px, py = b.position
            for wx, wy in wlists[i]:
                X = px + c * wx - s * wy
                Y = py + s * wx + c * wy
                xa = ca * X + sa * Y
                if 0.0 <= xa <= L:
                    d = h - (-sa * X + ca * Y)
                    if d > deepest:
                        deepest = d
            return deepest
        for v in world_vertices(i):
            for s in all_other[i]:
                d = s.point_query(v).distance
                if d < -deepest:
                    deepest = -d
        return deepest

    def clearance(i):
        """Lower bound of the distance (m) from part i to every other shape."""
        best = math.inf
        for v in world_vertices(i):
            for s in all_other[i]:
                d = s.point_query(v).distance
                if d < best:
                    best = d
        ca, sa = _rot(arm_body.angle)
        shp = shapes[i]
        for cx, cy in corners_local:
            d = shp.point_query((ca * cx - sa * cy, sa * cx + ca * cy)).distance
            if d < best:
                best = d
        for j in range(len(shapes)):
            if j != i:
                for v in world_vertices(j):
                    d = shp.point_query(v).distance
                    if d < best:
                        best = d
        return best

    reach = float(np.max(np.hypot(corners_local[:, 0], corners_local[:, 1]))) if len(corners_local) else L

    def _record_post(i, tr, step):
        b = bodies[i]
        (vx0, vy0), w0, _, _ = tr.pre
        ca, sa = _rot(arm_body.angle)
        v = b.velocity
        pre = (ca * vx0 + sa * vy0, -sa * vx0 + ca * vy0, w0)
        post = (ca * v.x + sa * v.y, -sa * v.x + ca * v.y, b.angular_velocity)
        r = tr.rec
        r[C.VX_PRE], r[C.VY_PRE], r[C.W_PRE] = pre
        r[C.VX_POST], r[C.VY_POST], r[C.W_POST] = post
        # the step also applied gravity for one step; the impulse is the rest of the change
        r[C.JX] = post[0] - pre[0] + sa * g * step
        r[C.JY] = post[1] - pre[1] + ca * g * step
        r[C.MU_IMPACT] = abs(r[C.JX]) / r[C.JY] if r[C.JY] > 0 else math.inf
        rho2 = parts[i].radius_of_gyration**2
        r[C.K_PRE] = 0.5 * (vx0**2 + vy0**2 + rho2 * w0**2)
        r[C.K_POST] = 0.5 * (v.x**2 + v.y**2 + rho2 * b.angular_velocity**2)
        r[C.U_IMPACT] = g * (-sa * b.position.x + ca * b.position.y - h)
        tr.need_post = False

    # ------------------------------------------------------------------ recording
    samples_t, samples_a, samples_p, samples_c, events = [], [], [], [], []

    def sample(t):
        samples_t.append(t)
        samples_a.append(arm_body.angle)
        samples_p.append([(b.position.x, b.position.y, b.angle) for b in bodies])
        pts = []
        for b in bodies:
            def _collect(arb, out=pts):
                for cp in arb.contact_point_set.points:
                    out.append((cp.point_a.x, cp.point_a.y))
            b.each_arbiter(_collect)
        samples_c.append(np.array(pts).reshape(-1, 2))

    # ------------------------------------------------------------------ main loop
    t = 0.0
    n_steps = 0
    n_leaps = 0
    next_check = 0.0
    next_flight_check = 0.0
    next_sample = 0.0
    next_progress = 0.0
    still_since = None
    arm_stop = realisation.duration
    status = Status.OK
    message = ""
    pen_max = 0.0
    done = False
    omega_arm_bound = abs(getattr(realisation, "omega", 0.0)) + abs(getattr(realisation, "peak_rate", 0.0)) \
        + abs(getattr(realisation, "rate_", 0.0))
    while not done:
        if record and t >= next_sample - 1e-12:
            sample(t)
            next_sample += settings.record_dt
        if progress is not None and t >= next_progress:
            progress(t, t_max)
            next_progress += 0.01
        if t >= t_max - 1e-12:
            if run_for is not None:
                break
            status = Status.TIMEOUT
            message = f"not settled after {settings.t_max:g} s"
            for tr in tracks:
                if tr.fell is None:
                    tr.status = Status.TIMEOUT
            break
        arm_moving = t < arm_stop
        # -------------------------------------------- exact free flight when every part is clear
        leapt = False
        if settings.exact_flight and t >= next_flight_check and all(tr.n_contacts == 0 for tr in tracks):
            next_flight_check = t + _CHECK_EVERY
            gaps = [clearance(i) if tracks[i].fell is None else math.inf for i in range(len(bodies))]
            gap = min(gaps)
            if gap > settings.flight_margin:
                vmax = 0.0
                for i, b in enumerate(bodies):
                    if tracks[i].fell is None:
                        vmax = max(vmax, math.hypot(*b.velocity) + abs(b.angular_velocity) * R[i])
                vmax += 2.0 * omega_arm_bound * reach if arm_moving else 0.0
                usable = gap - 0.5 * settings.flight_margin
                # vmax τ + g τ² ≤ usable (the g term bounds the speed gained during the leap)
                tau = 2.0 * usable / (vmax + math.sqrt(vmax * vmax + 4.0 * g * usable))
                tau = min(tau, 0.05, t_max - t)
                if record:
                    tau = min(tau, max(next_sample - t, dt))
                if tau > 4 * dt:
                    for i, b in enumerate(bodies):
                        (px, py), (vx, vy) = b.position, b.velocity
                        b.position = (px + vx * tau, py + vy * tau - 0.5 * g * tau * tau)
                        b.velocity = (vx, vy - g * tau)
                        b.angle = b.angle + b.angular_velocity * tau
                    t += tau
                    now[0] = t
                    arm_body.angle = alpha + realisation.angle(t)
                    arm_body.angular_velocity = 0.0
                    space.reindex_shapes_for_body(arm_body)
                    n_leaps += 1
                    leapt = True
        if leapt:
            continue
        # -------------------------------------------- fixed steps up to the next check
        coarse = (not arm_moving and settings.coarse_dt > dt and t - last_begin[0] >= settings.impact_window
                  and all(tr.fell is not None or tr.n_contacts > 0 for tr in tracks))
        h_step = settings.coarse_dt if coarse else dt
        n_inner = max(1, int(math.ceil((min(next_check, t_max) - t) / h_step - 1e-9)))
        for _ in range(n_inner):
            if arm_moving:
                a_now = alpha + realisation.angle(t)
                arm_body.angle = a_now
                arm_body.angular_velocity = (alpha + realisation.angle(t + h_step) - a_now) / h_step
                arm_moving = t + h_step < arm_stop
            elif arm_body.angular_velocity != 0.0:
                arm_body.angle = end_alpha
                arm_body.angular_velocity = 0.0
            now[0] = t + h_step
            space.step(h_step)
            t += h_step
            n_steps += 1
            if need_post[0]:
                need_post[0] = False
                for i, tr in enumerate(tracks):
                    if tr.need_post:
                        _record_post(i, tr, h_step)
        for tr in tracks:
            if tr.n_contacts == 0:
                tr.armed = True
                if tr.t_sep is not None and tr.t_sep > -math.inf and t - tr.t_sep >= _HOP_MIN:
                    tr.rec[C.N_LIFTOFFS] += 1.0  # a hop: out of contact for ≥ _HOP_MIN after touching
                    events.append((tr.t_sep, "lift-off"))
                    tr.t_sep = -math.inf  # counted; the next begin counts the re-impact
        # -------------------------------------------- periodic checks
        if t >= next_check:
            next_check = t + (_CHECK_EVERY if h_step == dt else 4.0 * h_step)
            ca, sa = _rot(arm_body.angle)
            for i, b in enumerate(bodies):
                tr = tracks[i]
                if tr.fell is not None:
                    continue
                pen = penetration(i)
                if pen > tr.rec[C.PENETRATION_MAX]:
                    tr.rec[C.PENETRATION_MAX] = pen
                pen_max = max(pen_max, pen)
                if pen > settings.penetration_tol:
                    tr.status = Status.PENETRATION
                    status = Status.PENETRATION
                    message = (f"part {i}: a vertex sank {pen * 1e3:.2f} mm into a shape at t = {t:.4f} s "
                               f"(> penetration_tol {settings.penetration_tol * 1e3:g} mm); result refused")
                    done = True
                    break
                xa = ca * b.position.x + sa * b.position.y
                ya = -sa * b.position.x + ca * b.position.y
                if ya < h - settings.arm_thickness - 3.0 * R[i] or (ya < h and (xa < -R[i] or xa > L + R[i])):
                    tr.fell = t
                    events.append((t, f"escape: {'behind_joint' if xa < 0.5 * L else 'off_end'}"))
                    tr.status = Status.BEHIND_JOINT if xa < 0.5 * L else Status.OFF_END
                    space.remove(b, shapes[i])
                # flips: the side the part lies on whenever it is in contact and nearly flat
                if tr.n_contacts > 0:
                    k, tilt = _nearest_side(betas[i], b.angle - arm_body.angle)
                    if abs(tilt) < 0.02 and tr.ever:
                        if k != tr.last_side:
                            tr.rec[C.N_FLIPS] += 1.0
                            events.append((t, f"flip {tr.last_side}→{k}"))
                        tr.last_side = k
            if done:
                break
            if all(tr.fell is not None for tr in tracks):
                break
            # settling
            if t >= arm_stop:
                slow = all(tr.fell is not None or (math.hypot(*b.velocity) < settings.settle_speed
                                                   and abs(b.angular_velocity) < settings.settle_spin)
                           for b, tr in zip(bodies, tracks))
                if slow:
                    if still_since is None:
                        still_since = t
                    elif t - still_since >= settings.settle_hold and run_for is None:
                        done = True
                else:
                    still_since = None
    if status == Status.OK and still_since is not None:
        events.append((still_since, "rest"))
    if record:
        sample(t)
    finished[0] = True
    # ------------------------------------------------------------------ results
    ca, sa = _rot(arm_body.angle)
    final_alpha = arm_body.angle
    states, poses, statuses = [], [], []
    for i, (b, part, tr) in enumerate(zip(bodies, parts, tracks)):
        pose_w = (b.position.x, b.position.y, b.angle)
        xa = ca * pose_w[0] + sa * pose_w[1]
        ya = -sa * pose_w[0] + ca * pose_w[1]
        pose_a = (xa, ya, pose_w[2] - final_alpha)
        x, k, tilt = state_from_pose(part, pose_w, final_alpha)
        st = tr.status
        if st == Status.OK and status == Status.OK:
            if x + part.uL[k] <= 0.0 and abs(tilt) < 0.05:
                st = Status.BEHIND_JOINT
            elif x > L:
                st = Status.OFF_END
        statuses.append(st)
        states.append((x, k, tilt))
        poses.append(pose_a)
        tr.rec[C.E_FINAL] = g * (ya - h)
        tr.rec[C.T_REST] = (still_since if still_since is not None and st == Status.OK else math.nan)
    overall = status
    if overall == Status.OK:
        for st in statuses:
            if st != Status.OK:
                overall = st
                break
    traj = None
    if record:
        traj = Trajectory(np.array(samples_t), np.array(samples_a), np.array(samples_p), tuple(parts), h, L,
                          scene.fixtures, tuple(samples_c), tuple(events), "engine:pymunk")
    return EngineRun(scene, overall, tuple(statuses), tuple(states), tuple(poses), np.array([tr.rec for tr in tracks]),
                     t, n_steps, n_leaps, pen_max, final_alpha, traj, message)
