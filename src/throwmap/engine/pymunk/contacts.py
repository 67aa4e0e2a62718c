"""Contact bookkeeping of a run: pymunk's begin/separate callbacks, impacts, hops, flips, first-impact records.

Per part (:class:`PartTrack`): the number of shapes it touches, whether it has
been released (out of contact since the start) and has touched anything since,
and its record (:mod:`throwmap.kernels.codes`, per unit mass). The first touch
after release is the impact of paper Sec. III-C: time of flight, contact vertex
and x, and the velocities just before and one step after (``record_post``). A
separation lasting at least :data:`HOP_MIN` is a hop (``N_LIFTOFFS``), and the
touch that ends it an impact (``N_IMPACTS``).
"""

from __future__ import annotations

import math

import numpy as np

from ...kernels import codes as C
from ...records.outcome import Status
from .friction import NativeCap, attach_raw, install_friction_cap
from .world import World

__all__ = ["HOP_MIN", "PartTrack", "Contacts", "nearest_side"]

HOP_MIN = 1e-3
"""s a part must stay out of contact for a separation to count as a hop."""


def nearest_side(betas, phi):
    """(side, tilt) of the resting orientation nearest to body angle ``phi`` (rad, arm frame)."""
    best, kb = math.inf, 0
    for k, b in enumerate(betas):
        d = (phi - b + math.pi) % (2.0 * math.pi) - math.pi
        if abs(d) < abs(best):
            best, kb = d, k
    return kb, best


class PartTrack:
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


class _Clock:
    """The run's clock where there is no C helper (:class:`.native.NativeRun` is the clock otherwise)."""

    __slots__ = ("now", "stop")

    def __init__(self):
        self.now = 0.0
        self.stop = 0


class Contacts:
    """The callbacks of one run and what they record.

    ``now`` is the simulated time (s) at the end of the step being taken (kept by ``clock``, which the C helper's
    step loop advances; a first impact sets ``clock.stop`` so that the loop returns after its step);
    ``last_begin`` the time the latest contact began; ``need_post`` is set when a
    first impact waits for its post-impact state; ``events`` the run's
    ``(t, text)`` log; ``finished`` silences the callbacks once the run is over.
    ``n_touching`` counts the parts touching something (a part removed from the
    space keeps its count); ``n_fell``/``n_fell_touching`` the removed parts and
    those of them that were touching when removed.
    """

    __slots__ = ("world", "tracks", "clock", "last_begin", "need_post", "finished", "events", "n_touching", "n_fell",
                 "n_fell_touching", "_one", "friction_cap")

    def __init__(self, world: World):
        self.world = world
        self.tracks = [PartTrack() for _ in world.bodies]
        self.clock = _Clock() if world.native is None else world.native.ptr
        self.now = 0.0
        self.last_begin = -math.inf
        self.need_post = False
        self.finished = False
        self.events = []
        self.n_touching = self.n_fell = self.n_fell_touching = 0
        self._one = (0,) if world.n == 1 else None  # every contact involves the only part
        arm_angle = world.arm.angle
        for i, b in enumerate(world.bodies):
            self.tracks[i].last_side = nearest_side(world.betas[i], b.angle - arm_angle)[0]
            p, tr = world.parts[i], self.tracks[i]
            v = b.velocity
            s0, c0 = math.sin(arm_angle), math.cos(arm_angle)
            y_arm = -s0 * b.position.x + c0 * b.position.y
            tr.rec[C.E_RELEASE] = (0.5 * (v.x**2 + v.y**2 + p.radius_of_gyration**2 * b.angular_velocity**2)
                                   + world.g * (y_arm - world.h))
        self.friction_cap = cap = install_friction_cap(world)
        native = isinstance(cap, NativeCap)
        world.space.on_collision(begin=self._begin, separate=self._separate, pre_solve=None if native else cap)
        if cap is not None and not native:
            attach_raw(world.space, cap)
        if world.native is not None:  # the C hook (where it is one) and C begin/separate calling begin_parts etc.
            world.native.attach(world.space, self)

    @property
    def now(self) -> float:
        """Simulated time at the end of the step being taken, s."""
        return self.clock.now

    @now.setter
    def now(self, t: float) -> None:
        self.clock.now = t

    def _parts(self, arbiter):
        if self._one is not None:
            return self._one
        index = self.world.index
        return [index[id(b)] for b in arbiter.bodies if id(b) in index]

    def _begin(self, arbiter, space_, data):
        self._begun(self._parts(arbiter), arbiter, self._first_point)

    def _first_point(self, arbiter, i):
        """The first contact point ``(x, y)`` of pymunk ``arbiter`` on part i's body (None: it has none)."""
        pts = arbiter.contact_point_set.points
        if not pts:
            return None
        p = pts[0].point_a if arbiter.shapes[0].body is self.world.bodies[i] else pts[0].point_b
        return (p.x, p.y)

    def begin_parts(self, ia: int, ib: int, arb):
        """A contact began between the bodies of parts ``ia`` and ``ib`` (-1: not a part) on raw arbiter ``arb``
        (the C helper's begin callback)."""
        parts = self._one if self._one is not None else [i for i in (ia, ib) if i >= 0]
        self._begun(parts, arb, self.world.native.contact_point)

    def _begun(self, parts, arbiter, point):
        t = self.now
        self.last_begin = t
        for i in parts:
            tr = self.tracks[i]
            if tr.n_contacts == 0 and tr.armed:
                if not tr.ever:
                    self._first_impact(i, tr, point(arbiter, i), t)
                elif tr.t_sep is not None and (tr.t_sep == -math.inf or t - tr.t_sep >= HOP_MIN):
                    tr.rec[C.N_IMPACTS] += 1.0
                tr.t_sep = None
            if tr.n_contacts == 0:
                self.n_touching += 1
            tr.n_contacts += 1

    def _first_impact(self, i, tr, p, t):
        """Part i's first touch after release at ``t`` (s), ``p`` its first contact point (world frame, m; None: the
        arbiter has none)."""
        w = self.world
        b = w.bodies[i]
        tr.ever = True
        tr.rec[C.T_FLIGHT] = t
        tr.pre = (tuple(b.velocity), b.angular_velocity, b.angle, tuple(b.position))
        tr.need_post = True
        self.need_post = True
        self.clock.stop = 1  # (the C step loop returns after this step, for record_post)
        if p is not None:
            aa = w.arm.angle
            ca, sa = math.cos(aa), math.sin(aa)
            tr.rec[C.CONTACT_X] = ca * p[0] + sa * p[1]
            lv = b.world_to_local(p)
            part = w.parts[i]
            dist = np.hypot(part.w[:, 0] - lv[0], part.w[:, 1] - lv[1])
            tr.rec[C.CONTACT_VERTEX] = float(np.argmin(dist))
            self.events.append((t, f"impact v{int(part.user_index[int(np.argmin(dist))])}"))
        tr.rec[C.N_IMPACTS] += 1.0

    def _separate(self, arbiter, space_, data):
        if self.finished or arbiter.is_removal:
            return
        self._separated(self._parts(arbiter))

    def separate_parts(self, ia: int, ib: int):
        """A contact between the bodies of parts ``ia`` and ``ib`` (-1: not a part) ended (the C helper's separate
        callback; not called for removals)."""
        if not self.finished:
            self._separated(self._one if self._one is not None else [i for i in (ia, ib) if i >= 0])

    def _separated(self, parts):
        for i in parts:
            tr = self.tracks[i]
            if tr.n_contacts == 1:
                self.n_touching -= 1
            tr.n_contacts = max(tr.n_contacts - 1, 0)
            if tr.n_contacts == 0 and tr.ever:
                tr.t_sep = self.now

    def record_post(self, step: float):
        """Write the post-impact state of every part whose first impact happened in the step just taken (s)."""
        self.need_post = False
        for i, tr in enumerate(self.tracks):
            if tr.need_post:
                self._record_post(i, tr, step)

    def _record_post(self, i, tr, step):
        w = self.world
        b, g = w.bodies[i], w.g
        (vx0, vy0), w0, _, _ = tr.pre
        aa = w.arm.angle
        ca, sa = math.cos(aa), math.sin(aa)
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
        rho2 = w.parts[i].radius_of_gyration**2
        r[C.K_PRE] = 0.5 * (vx0**2 + vy0**2 + rho2 * w0**2)
        r[C.K_POST] = 0.5 * (v.x**2 + v.y**2 + rho2 * b.angular_velocity**2)
        r[C.U_IMPACT] = g * (-sa * b.position.x + ca * b.position.y - w.h)
        tr.need_post = False

    def after_steps(self, t: float):
        """Release parts out of contact and count finished hops, at time ``t`` (s) after a block of steps."""
        for tr in self.tracks:
            if tr.n_contacts == 0:
                tr.armed = True
                if tr.t_sep is not None and tr.t_sep > -math.inf and t - tr.t_sep >= HOP_MIN:
                    tr.rec[C.N_LIFTOFFS] += 1.0  # a hop: out of contact for ≥ HOP_MIN after touching
                    self.events.append((tr.t_sep, "lift-off"))
                    tr.t_sep = -math.inf  # counted; the next begin counts the re-impact

    def fell(self, i: int, t: float, status: Status):
        """Part i left the arm at ``t`` (s) with ``status``; it is taken out of the space."""
        tr = self.tracks[i]
        tr.fell = t
        tr.status = status
        self.n_fell += 1
        self.n_fell_touching += tr.n_contacts > 0
        self.events.append((t, f"escape: {status.name.lower()}"))
        w = self.world
        w.space.remove(w.bodies[i], w.shapes[i])
        if w.native is not None:
            w.native.fell(i)

    def all_free(self) -> bool:
        """No part touches anything."""
        return self.n_touching == 0

    def all_touching(self) -> bool:
        """Every part still on the arm touches something."""
        return self.n_touching - self.n_fell_touching == len(self.tracks) - self.n_fell
