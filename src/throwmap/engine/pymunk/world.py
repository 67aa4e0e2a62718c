"""The pymunk space of a :class:`~throwmap.engine.Scene`: arm, fixtures and parts, ready to step.

The arm is a kinematic body turning about the joint (the origin), built from
convex solid pieces under its surface profile (:func:`throwmap.system.fixtures.arm_solids`);
fixtures are kinematic pieces on the same body. Parts are convex polygons with
their own mass, CM and inertia. Restitution is zero on every shape; friction is
set per pair of bodies (:class:`~throwmap.engine.Friction`): pymunk multiplies the
two shapes' values, so arm and wall shapes carry the pair's μ and part shapes
carry 1 (part–part μ is set in a ``pre_solve`` hook, :mod:`.contacts`).

Chipmunk is called through :class:`Chipmunk`: pymunk's own cffi functions on the
raw C handles (``pymunk._chipmunk``), a few times faster than pymunk's Python
wrappers, which build a ``Vec2d`` or a query object per call; where that binding
is missing (another pymunk), the public API with the same results.
"""

from __future__ import annotations

import functools
import math
from operator import attrgetter

import numpy as np

from ...errors import ThrowmapError
from ...system.fixtures import Cavity, arm_solids
from ..settings import engine_mu

__all__ = ["ARM", "FIXTURE", "PART", "Chipmunk", "World", "build_world", "load_pymunk"]

ARM, FIXTURE, PART = 1, 2, 3
"""pymunk collision types of arm pieces, fixture pieces and parts."""
BOX_TOL = 1e-7
"""m added to every bounding-box test that skips a shape query (:func:`.checks.inspect`; rounding of the
arm-frame transform is ~1e-16 m)."""


def load_pymunk():
    """Import pymunk, or say how to install it."""
    try:
        import pymunk
    except ImportError:  # pragma: no cover - pymunk is a dependency
        raise ThrowmapError("engine", "pymunk is not installed: pip install pymunk") from None
    return pymunk


class Chipmunk:
    """The Chipmunk calls of the run loop, on handles from :meth:`body`/:meth:`shape`/:meth:`space`.

    ``raw=True`` (when pymunk's cffi binding is there): handles are C pointers and
    the calls are Chipmunk's (``position(b).x``, ``distance(s, p, NULL)``, …);
    ``raw=False``: handles are the pymunk objects and the calls pymunk's public API.
    Both give bit-identical runs (``tests/engine/test_engine_layout.py``).
    """

    __slots__ = ("raw", "NULL", "position", "angle", "velocity", "spin", "to_world", "distance", "step",
                 "set_position", "set_angle", "set_velocity", "set_spin")

    def __init__(self, pm, raw: bool = True):
        lib = None
        if raw:
            try:
                from pymunk._chipmunk import ffi, lib
                lib.cpSpaceStep, lib.cpShapePointQuery, lib.cpBodyLocalToWorld  # noqa: B018
            except (ImportError, AttributeError):
                lib = None
        self.raw = lib is not None
        if self.raw:
            self.NULL = ffi.NULL
            self.position, self.angle = lib.cpBodyGetPosition, lib.cpBodyGetAngle
            self.velocity, self.spin = lib.cpBodyGetVelocity, lib.cpBodyGetAngularVelocity
            self.to_world, self.distance, self.step = lib.cpBodyLocalToWorld, lib.cpShapePointQuery, lib.cpSpaceStep
            self.set_position, self.set_angle = lib.cpBodySetPosition, lib.cpBodySetAngle
            self.set_velocity, self.set_spin = lib.cpBodySetVelocity, lib.cpBodySetAngularVelocity
        else:
            B = pm.Body
            self.NULL = None
            self.position, self.angle = attrgetter("position"), attrgetter("angle")
            self.velocity, self.spin = attrgetter("velocity"), attrgetter("angular_velocity")
            self.to_world, self.step = B.local_to_world, pm.Space.step
            self.distance = lambda s, p, _null: s.point_query(p).distance
            self.set_position, self.set_angle = B.position.fset, B.angle.fset
            self.set_velocity, self.set_spin = B.velocity.fset, B.angular_velocity.fset

    def body(self, b):
        return b._body if self.raw else b

    def shape(self, s):
        return s._shape if self.raw else s

    def space(self, s):
        return s._space if self.raw else s


class World:
    """A scene in pymunk: bodies, shapes, their Chipmunk handles and the geometry the checks use (SI, world frame).

    ``arm`` is the kinematic arm body (fixtures on it), ``bodies``/``shapes``/
    ``parts`` per part; ``*_h`` are the matching :class:`Chipmunk` handles.
    ``L`` is the simulated arm length, ``back`` the surface's extent behind the
    joint (:attr:`throwmap.Arm.back`, m; the arm spans −back ≤ x ≤ L),
    ``thickness`` the arm solid's depth below the surface (m), ``margin`` the
    flight margin (m), ``corners`` the arm pieces' corners in the
    arm frame and ``reach`` their largest distance from the joint,
    ``rho2[i]`` part i's squared radius of gyration (m²), ``R[i]`` part
    i's largest vertex distance from its CM, ``others_h[i]`` the handles of every
    shape part i can touch, ``names[i]`` what each of them is (``"the arm"``, ``"the wall"``, ``"part j"``: for
    messages), and ``boxes[i]`` their bounding boxes ``(x0, x1, y0, y1)``
    in the arm frame (m; None for another part's shape, which moves; ``boxes_tol`` the same
    inflated by :data:`.checks.BOX_TOL`), ``clear_hint[i]``
    the pair that gave part i's last clearance (:func:`.checks.clearance`). ``plain_arm``: one part and no fixtures (the
    penetration check then reads depth below the flat surface directly).
    ``arm_w`` is the arm's angular velocity as last set, rad/s. ``settle``: ``(settle_speed, settle_spin)``;
    ``end_wall``: a wall stands at the arm's end; ``arm_thickness``: :attr:`EngineSettings.arm_thickness` (for
    :func:`.checks.escape`). ``native``: the run's state in the C helper
    (:class:`.native.NativeRun`; None where the helper is unavailable or the run uses pymunk's public API).
    """

    __slots__ = ("pm", "cp", "space", "space_h", "arm", "arm_h", "arm_w", "bodies", "bodies_h", "shapes", "shapes_h",
                 "parts", "static_shapes", "corners", "reach", "L", "h", "g", "betas", "R", "wlists", "others_h", "names",
                 "plain_arm", "index", "mu_pp", "mu_arm", "mu_wall", "back", "thickness", "margin", "rho2", "boxes",
                 "boxes_tol", "clear_hint", "settle", "end_wall", "arm_thickness", "native")

    @property
    def n(self) -> int:
        return len(self.bodies)


def _geometry_cache(compute):
    """``compute`` memoised on its (hashable) arguments; unhashable ones are computed every time."""
    @functools.lru_cache(maxsize=64)
    def cached(signs, *args):  # (the signs keep -0.0 and 0.0 apart: they hash and compare equal)
        return compute(*args)

    def get(*args):
        try:
            return cached(tuple(math.copysign(1.0, a) for a in args if isinstance(a, float)), *args)
        except TypeError:  # an unhashable argument
            return compute(*args)

    return get


@_geometry_cache
def _static_geometry(h: float, L: float, thickness: float, fixtures: tuple, back: float):
    """The arm's solid pieces as built for pymunk, and what the checks read off them (SI, arm frame):
    ``(pieces, thickness, boxes, corners, reach, n_arm)``, ``pieces`` as ``(vertices, is_fixture)``, ``thickness``
    the solid's depth below the surface, ``boxes`` each piece's ``(x0, x1, y0, y1)``, ``corners`` every
    piece's vertices, ``reach`` their largest distance from the joint (computed once per geometry), ``n_arm`` how
    many of the pieces, the first ones, are the arm's own (a cavity's floor included); the rest are the wall's."""
    arm_pieces, fixture_pieces = arm_solids(h, L, thickness, fixtures)
    if back > 0.0:  # the surface continues behind the joint to x = -back (Arm.back): widen the first piece
        first = np.array(arm_pieces[0], dtype=float)
        first[first[:, 0] <= 0.0, 0] = -back
        arm_pieces = [first] + list(arm_pieces[1:])
    depth = float(h - min(float(np.min(np.asarray(p)[:, 1])) for p in arm_pieces))
    # a lined cavity's floor (the pieces whose top is at the full depth) gets the fixture's μ (Cavity.lined)
    floor = [h + min(y for _, y in f.profile) for f in fixtures if isinstance(f, Cavity) and f.lined]
    lined = [bool(floor) and float(p[2][1]) == floor[0] and float(p[3][1]) == floor[0] for p in arm_pieces]
    pieces, boxes, corners = [], [], []
    for piece, fixture in [(p, f) for p, f in zip(arm_pieces, lined)] + [(p, True) for p in fixture_pieces]:
        piece = tuple(tuple(v) for v in piece.tolist())
        xs, ys = [x for x, _ in piece], [y for _, y in piece]
        boxes.append((min(xs), max(xs), min(ys), max(ys)))
        pieces.append((piece, fixture))
        corners.extend(piece)
    reach = float(np.max(np.hypot(*np.array(corners).T))) if corners else math.nan
    return tuple(pieces), depth, tuple(boxes), tuple(corners), reach, len(arm_pieces)


@_geometry_cache
def _part_geometry(part):
    """``(R, vertices, betas)`` of a part: its largest vertex distance from the CM (m), its vertices about
    the CM as tuples (m) and its resting angles (rad), computed once per part."""
    R = float(np.max(np.hypot(part.w[:, 0], part.w[:, 1])))
    return R, tuple(tuple(v) for v in part.w.tolist()), tuple(part.beta.tolist())


def build_world(scene, realisation, settings, *, raw: bool = True, length: float | None = None) -> World:
    """Build the space of ``scene`` at t = 0: arm at α + θ(0), parts at their poses with their start velocities.

    ``length``: the simulated arm's length (m); None: :meth:`Scene.length <throwmap.engine.Scene.length>`.

    An impulsive realisation gives each part the velocity of the arm point at its
    CM, ω × r, and spin ω (paper Sec. III-B); otherwise parts start with their
    placement's arm-frame velocity.
    """
    pm = load_pymunk()
    cp = Chipmunk(pm, raw)
    w = World()
    w.pm, w.cp = pm, cp
    arm = scene.arm
    w.h, w.g = arm.h, arm.g
    w.L = L = scene.length(settings.default_length, realisation, settings.t_max) if length is None else float(length)
    space = pm.Space()
    space.gravity = (0.0, -arm.g)
    space.iterations = int(settings.iterations)
    space.collision_slop = settings.collision_slop
    space.damping = 1.0

    arm_body = pm.Body(body_type=pm.Body.KINEMATIC)
    arm_body.position = (0.0, 0.0)
    a0 = scene.alpha + realisation.angle(0.0)
    arm_body.angle = a0
    back = arm.back
    pieces, thickness, static_boxes, corners, arm_reach, n_arm = _static_geometry(arm.h, L, settings.arm_thickness,
                                                                          tuple(scene.fixtures), back)
    w.back = back
    w.thickness = thickness
    w.margin = settings.flight_margin
    mu_arm = engine_mu(scene.mu("arm"))
    mu_wall = engine_mu(scene.mu("wall"))
    static_shapes = []
    for piece, fixture in pieces:
        s = pm.Poly(arm_body, list(piece))
        s.friction = mu_wall if fixture else mu_arm
        s.elasticity = 0.0
        s.collision_type = FIXTURE if fixture else ARM
        static_shapes.append(s)
    space.add(arm_body, *static_shapes)

    bodies, shapes, parts = [], [], []
    c0, s0 = math.cos(a0), math.sin(a0)
    for i, pl in enumerate(scene.placements):
        part = pl.part
        m = part.mass
        body = pm.Body(m, m * part.radius_of_gyration**2)
        x, y, phi = pl.arm_pose(arm.h)
        body.position = (c0 * x - s0 * y, s0 * x + c0 * y)
        body.angle = phi + a0
        vx, vy, om = pl.velocity
        if realisation.impulsive and realisation.omega > 0:
            # paper Sec. III-B: the part leaves with the arm point's velocity ω × r and spin ω
            w_arm = realisation.omega
            px, py = body.position
            vx, vy, om = vx - w_arm * py, vy + w_arm * px, om + w_arm
        else:
            vx, vy = c0 * vx - s0 * vy, s0 * vx + c0 * vy
        body.velocity = (vx, vy)
        body.angular_velocity = om
        shp = pm.Poly(body, list(_part_geometry(part)[1]))
        shp.friction = 1.0
        shp.elasticity = 0.0
        shp.collision_type = PART
        shp.filter = pm.ShapeFilter(group=i + 1)
        space.add(body, shp)
        bodies.append(body)
        shapes.append(shp)
        parts.append(part)

    w.space, w.arm, w.arm_w = space, arm_body, 0.0
    w.bodies, w.shapes, w.parts, w.static_shapes = bodies, shapes, parts, static_shapes
    w.space_h, w.arm_h = cp.space(space), cp.body(arm_body)
    w.bodies_h = [cp.body(b) for b in bodies]
    w.shapes_h = [cp.shape(s) for s in shapes]
    static_h = [cp.shape(s) for s in static_shapes]
    w.others_h = [static_h + [w.shapes_h[j] for j in range(len(shapes)) if j != i] for i in range(len(shapes))]
    static_names = ["the arm"] * n_arm + ["the wall"] * (len(static_shapes) - n_arm)
    w.names = [static_names + [f"part {j}" for j in range(len(shapes)) if j != i] for i in range(len(shapes))]
    w.boxes = [list(static_boxes) + [None] * (len(shapes) - 1) for _ in shapes]
    tol = 0.0 + BOX_TOL  # as checks.inspect inflates them for horizon 0
    w.boxes_tol = [[None if bx is None else (bx[0] - tol, bx[1] + tol, bx[2] - tol, bx[3] + tol)
                    for bx in boxes] for boxes in w.boxes]
    w.clear_hint = [None] * len(shapes)
    w.corners = corners
    w.reach = arm_reach if corners else L
    w.rho2 = [p.radius_of_gyration**2 for p in parts]
    geometry = [_part_geometry(p) for p in parts]
    w.R = [g[0] for g in geometry]
    w.wlists = [g[1] for g in geometry]
    w.betas = [g[2] for g in geometry]
    w.plain_arm = not scene.fixtures and len(parts) == 1
    w.index = {id(b): i for i, b in enumerate(bodies)}
    w.mu_pp = scene.mu("part")
    w.mu_arm, w.mu_wall = scene.mu("arm"), scene.mu("wall")
    w.settle = (settings.settle_speed, settings.settle_spin)
    # a wall at the arm's end: a vertex "below the surface beyond L" is one pressed into the wall's foot (within
    # penetration_tol), not a part that left the arm; one that flew over the wall is caught by its CM (escape)
    w.end_wall = any(type(f).__name__ == "Wall" for f in scene.fixtures)
    w.arm_thickness = settings.arm_thickness
    w.native = None
    if cp.raw:
        from .native import NativeRun, load

        module = load()
        if module is not None:
            w.native = NativeRun(module, w, settings, BOX_TOL)
    return w
