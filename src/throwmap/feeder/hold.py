"""Whether a feeder's pocket keeps what it captured: the engine's in-pocket hold check.

The screens of :mod:`throwmap.feeder.arrival` run on the plain arm; in the pocket the part meets the end wall at
every throw, and a wall contact above or below the centre of mass turns the part: a side that jogs on the plain
arm can flip in the pocket onto a neighbour that leans on the wall, and stay there (measured: a pentagon captured
flat on its target side within 2–12 throws, then flipped onto a near-unstable neighbour in every trial). So before
a candidate's feeding trials, :func:`pocket_hold` lays the part flat on the target side in the config's pocket,
its outermost point against the end wall, and throws it ``throws`` times at each of ω·(1 + zσ), z in ``z_levels``
(the recoil arm the trials use, the config's nominal μ): the candidate is kept only if it stays flat on the target
side in the pocket through all of them. A failed check costs a few engine throws (≈ 1 s each) instead of trials
that run to ``max_throws``.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Hold", "pocket_hold", "HOLD_Z", "HOLD_THROWS"]

HOLD_Z = (-3.0, 0.0, 3.0)
"""ω levels of the hold check, in units of the jitter σ."""
HOLD_THROWS = 2
"""Throws at each level."""


@dataclass(frozen=True, slots=True)
class Hold:
    """The hold check's outcome: ``held``, the ``throws`` it survived, how the failing throw ``ended`` (the
    cavity's ``where``: ``"other"``, ``"outside"``, or an engine status), and at which ``z`` (None when held)."""

    held: bool
    throws: int
    ended: str
    z: float | None

    def to_dict(self) -> dict:
        return {"held": self.held, "throws": self.throws, "ended": self.ended, "z": self.z}


def pocket_hold(cfg, *, z_levels=HOLD_Z, throws: int = HOLD_THROWS) -> Hold:
    """Lay the part of the ``feed`` config ``cfg`` (:class:`~throwmap.experiments.feed.FeedConfig`, fixture
    ``"cavity"``) flat on its target side against the pocket's end wall and throw it (see the module docstring)."""
    from ..design.cavity import _realisation
    from ..engine import Placement, Scene
    from ..experiments.feed import ENGINE, Feed, _settings
    from ..system.pose import pose_at_rest, world_vertices
    from ..throws.session import open_session

    part, _arm, _fixtures, omega, side, d = Feed().setup(cfg)
    reach = float(world_vertices(part, pose_at_rest(part, d.floor_y, 0.0, side))[:, 0].max())
    x = d.length - float(d.numbers.get("end_gap_m", 0.0)) - reach - 1e-4
    placement = Placement(part, pose=pose_at_rest(part, d.floor_y, x, side))
    settings = _settings(cfg)
    noise, done = cfg.noise, 0
    for z in z_levels:
        w = omega * (1.0 + float(z) * noise.omega_rel)
        sess = open_session(part, d.arm, Scene(d.arm, (placement,), d.fixtures), ENGINE, settings=settings)
        for _ in range(throws):
            step = sess.throw(w, _realisation(noise.realisation, w, noise.recoil, noise.zeta))
            where = d.where(step.poses[0]) if step.ok else step.status.label
            if where != "target":
                return Hold(False, done, str(where), float(z))
            done += 1
    return Hold(True, done, "target", None)
