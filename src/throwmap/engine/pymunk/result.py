"""The result of an engine run (:class:`EngineRun`), its recorded motion and how both are read off the space."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...kernels import codes as C
from ...records.outcome import Status, ThrowOutcome
from ...records.trajectory import Trajectory
from ...system.pose import state_from_pose
from ..rest import FLAT_TILT, UNCONVERGED, clamp_to_arm, rest_status, tilted_message
from ..scene import Placement, Scene
from .contacts import Contacts
from .world import World

__all__ = ["EngineRun", "Recorder", "finish"]


@dataclass(frozen=True, slots=True)
class EngineRun:
    """The result of :func:`~throwmap.engine.simulate` (SI units, arm frame unless stated).

    ``status`` is the run's overall status (the first part's failure, else ok);
    ``statuses``/``states``/``poses`` are per part: ``states[i] = (x, side, tilt)``
    read in the arm frame at the end (see :func:`throwmap.system.pose.state_from_pose`),
    ``poses[i]`` the arm-frame pose ``(x, y, φ)``. ``records`` is (P, NREC) per
    unit mass (see :mod:`throwmap.kernels.codes`; entries an engine cannot
    measure are nan). ``alpha`` is the arm's rest angle at the end.

    The run's cost: ``n_steps`` pymunk steps (``n_coarse`` of them at
    ``coarse_dt``), ``n_leaps`` exact-flight leaps, ``n_checks`` rounds of the
    periodic checks (penetration, escape, flips, settling) and ``n_clearance``
    clearance evaluations (exact flight); ``n_capped`` contact solves where
    the friction cap of :mod:`.friction` would bind (below the pair's μ): one part (:data:`.friction.EXACT`), each
    was solved exactly with the true μ (:mod:`.exact`) or, its previous impulses well inside the capped cone,
    by Chipmunk at the cap with the same (sticking) solution; several parts, its friction was capped.
    ``energy_gain`` (J/kg) is the largest rise of any part's mechanical energy after the arm stopped (several parts: of
    their total per unit total mass; a blow-up if large), ``dt`` the step the run used (s) and ``verified`` whether a
    half-step rerun was made and agreed (:func:`~throwmap.engine.simulate`).
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
    n_coarse: int = 0
    n_checks: int = 0
    n_clearance: int = 0
    n_capped: int = 0
    energy_gain: float = 0.0
    dt: float = float("nan")
    verified: bool = False

    def outcome(self, i: int = 0, *, x0=None, side0=None, omega=0.0, model="engine") -> ThrowOutcome:
        """Part ``i``'s result as a :class:`~throwmap.ThrowOutcome` (with the run's ``message`` when
        part ``i`` was refused, once ThrowOutcome has that field)."""
        part = self.scene.placements[i].part
        pl = self.scene.placements[i]
        if x0 is None:
            x0, side0, _ = state_from_pose(part, pl.arm_pose(self.scene.arm.h))
        x, side, _ = self.states[i]
        out = ThrowOutcome.from_record(part, x0, side0, omega, model, x, side, self.statuses[i], self.records[i])
        if self.message and self.statuses[i] != Status.OK:
            out = out.replace(message=self.message)  # why the result was refused (unconverged, unresolved, …)
        return out

    def next_scene(self, **changes) -> Scene:
        """A scene starting from this run's end (final poses at rest, arm at ``alpha``)."""
        pls = tuple(Placement(p.part, pose=pose) for p, pose in zip(self.scene.placements, self.poses))
        kw = dict(arm=self.scene.arm, placements=pls, fixtures=self.scene.fixtures, alpha=self.alpha,
                  friction=self.scene.friction)
        kw.update(changes)
        return Scene(**kw)


class Recorder:
    """Samples of a run for its :class:`~throwmap.records.trajectory.Trajectory`: time, arm angle, world poses, contact points."""

    __slots__ = ("world", "t", "arm", "poses", "contacts")

    def __init__(self, world: World):
        self.world = world
        self.t, self.arm, self.poses, self.contacts = [], [], [], []

    def sample(self, t: float):
        w = self.world
        self.t.append(t)
        self.arm.append(w.arm.angle)
        self.poses.append([(b.position.x, b.position.y, b.angle) for b in w.bodies])
        pts = []
        for b in w.bodies:
            def _collect(arb, out=pts):
                for cp in arb.contact_point_set.points:
                    out.append((cp.point_a.x, cp.point_a.y))
            b.each_arbiter(_collect)
        self.contacts.append(np.array(pts).reshape(-1, 2))

    def trajectory(self, scene: Scene, events) -> Trajectory:
        w = self.world
        return Trajectory(np.array(self.t), np.array(self.arm), np.array(self.poses), tuple(w.parts), w.h, w.L,
                          scene.fixtures, tuple(self.contacts), tuple(events), "engine:pymunk")


def finish(scene: Scene, w: World, contacts: Contacts, status: Status, message: str, t: float, still_since,
           counts: dict, pen_max: float, recorder: Recorder | None) -> EngineRun:
    """Read the final poses and states off the space and assemble the :class:`EngineRun`.

    A part that settled is ``ok`` only where :func:`throwmap.throw` would accept
    its rest as a start (:func:`throwmap.engine.rest.rest_status`): flat on a
    stable side with both support vertices on the arm, as the analytic models
    count it; else ``behind_joint``/``off_end`` (or ``unconverged`` tilted on a plain arm).
    """
    g, h, L, back = w.g, w.h, w.L, w.back
    final_alpha = w.arm.angle
    ca, sa = math.cos(final_alpha), math.sin(final_alpha)
    states, poses, statuses = [], [], []
    for b, part, tr in zip(w.bodies, w.parts, contacts.tracks):
        pose_w = (b.position.x, b.position.y, b.angle)
        xa = ca * pose_w[0] + sa * pose_w[1]
        ya = -sa * pose_w[0] + ca * pose_w[1]
        pose_a = (xa, ya, pose_w[2] - final_alpha)
        x, k, tilt = state_from_pose(part, pose_w, final_alpha)
        st = tr.status
        if st == Status.OK and status == Status.OK:
            st = rest_status(part, pose_a, x, k, tilt, h, L, back, w.plain_arm)
            if st == Status.OK and not w.plain_arm and abs(tilt) < FLAT_TILT:
                x = clamp_to_arm(part, x, k, L, back)
            if st == UNCONVERGED:
                message = (message + "; " if message else "") + tilted_message(len(statuses), tilt, k)
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
    traj = recorder.trajectory(scene, contacts.events) if recorder is not None else None
    return EngineRun(scene, overall, tuple(statuses), tuple(states), tuple(poses),
                     np.array([tr.rec for tr in contacts.tracks]), t, counts["steps"], counts["leaps"], pen_max,
                     final_alpha, traj, message, n_coarse=counts["coarse"], n_checks=counts["checks"],
                     n_clearance=counts["clearance"], n_capped=counts["capped"], energy_gain=counts["energy_gain"],
                     dt=counts["dt"])
