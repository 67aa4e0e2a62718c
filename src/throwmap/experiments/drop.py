"""Random initial conditions by *dropping* the part onto the arm in the engine.

The draft's experiments started each trial by dropping the part by hand onto the arm
(Sec. V-C). :func:`drop_part` does the same in the pymunk engine: it draws

* an orientation φ uniform in [0, 2π) (rad, arm frame),
* a CM abscissa x uniform over ``x_range`` (m, arm frame; default the arm's surface
  [−back, length]),
* a height: the part's lowest vertex ``height`` (m) above the arm's surface y = h,
  uniform over ``height`` = (low, high) (default 2–10 cm). Where the drawn pose would
  overlap a :class:`~throwmap.system.fixtures.Wall`, the height is counted from the
  wall's top instead, so that no drop starts inside a fixture,

releases the part at rest there and simulates the fall (:func:`throwmap.engine.simulate`
with ``ImpulseThrow(0.0)``: the arm does not move) until the part settles. The result
is the engine :class:`~throwmap.engine.Scene` with the part where it settled
(:meth:`throwmap.engine.EngineRun.next_scene`), ready for the next throw.

Re-draws: a drop whose part does not end at rest on the arm (it fell off an end,
settled tilted on the bare arm, or the engine refused the run) is drawn again from the
same generator, at most ``max_redraws`` times (default :data:`MAX_REDRAWS`);
:attr:`DropResult.redraws` counts them and :attr:`DropResult.rejected` says why each
was rejected. With ``max_redraws=0`` every drop is reported as it fell — the
``settle`` experiment uses this to measure the drop outcomes themselves. If every draw
fails, the last one is returned (``ok`` False, its status and message).
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown
from ..rng import as_generator
from ..system.arm import Arm
from ..system.fixtures import Wall
from ..system.part import Part
from ..records.outcome import Status
from ..system.pose import world_vertices

__all__ = ["Spread", "drop_parts", "DropResult", "drop_part", "drop_kind", "MAX_REDRAWS", "DEFAULT_HEIGHT"]

MAX_REDRAWS = 20
"""Default re-draws of a drop that does not end at rest on the arm."""
DEFAULT_HEIGHT = (0.02, 0.10)
"""m: range of the lowest vertex's height above the arm's surface at release."""

_REFUSED = {Status.TIMEOUT: "refused:timeout", Status.PENETRATION: "refused:penetration",
            Status.UNRESOLVED: "refused:unresolved", Status.UNCONVERGED: "refused:unconverged"}


def drop_kind(status: Status, tilt: float, message: str = "") -> str | None:
    """The outcome kind of a drop: None when at rest on the arm (``ok``), else ``"off_end"``,
    ``"behind_joint"``, ``"tilted"`` (came to rest leaning on the bare arm, |tilt| ≥
    :data:`throwmap.engine.rest.FLAT_TILT`, which only a moving part can do: the engine refuses it as
    unconverged), or ``"refused:<status>"`` (timeout, penetration, unresolved, unconverged)."""
    from ..engine.rest import FLAT_TILT

    status = Status(status)
    if status == Status.OK:
        return None
    if status in (Status.OFF_END, Status.BEHIND_JOINT):
        return status.label
    if status == Status.UNCONVERGED and "disagrees" not in message and abs(tilt) >= FLAT_TILT:
        return "tilted"
    return _REFUSED.get(status, f"refused:{status.label}")


@dataclass(frozen=True, slots=True)
class DropResult:
    """Where a dropped part came to rest (SI units, arm frame).

    ``scene``: the engine :class:`~throwmap.engine.Scene` after the fall (part at its
    settled ``pose`` (x, y, φ), the arm at rest angle ``alpha``); ``x`` (m), ``side``
    and ``tilt`` (rad) the nearest resting configuration
    (:func:`throwmap.system.pose.state_from_pose`); ``status`` the engine's
    (``ok``: at rest on the arm — flat on a stable side, or held by a fixture);
    ``kind`` None when ok else the failure kind (:func:`drop_kind`); ``message`` the
    engine's message; ``start`` the accepted draw ``(x0, y0, φ0)`` (m, m, rad);
    ``height`` its lowest vertex above the surface (m); ``t_fall`` the simulated time to
    settle (s); ``redraws`` the draws rejected before this one and ``rejected`` their
    kinds with counts.
    """

    scene: object
    x: float
    side: int
    tilt: float
    pose: tuple
    status: Status
    kind: str | None
    message: str
    start: tuple
    height: float
    t_fall: float
    redraws: int = 0
    rejected: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return self.status == Status.OK


def _range(value, field: str, default) -> tuple[float, float]:
    if value is None:
        value = default
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise InvalidStateError(field, f"must be a pair (low, high) in metres, got {shown(value)}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
        raise InvalidStateError(field, f"must be finite with low ≤ high, got {shown(value)}")
    return lo, hi


def drop_part(part: Part, arm: Arm, rng=None, *, fixtures=(), alpha: float = 0.0, x_range=None,
              height=DEFAULT_HEIGHT, settings=None, friction=None, max_redraws: int = MAX_REDRAWS) -> DropResult:
    """Drop ``part`` onto ``arm`` from a random pose and let it settle in the pymunk engine.

    See the module docstring for the distribution of the draw and the re-draws.
    ``rng``: Generator, int seed or None (:func:`throwmap.rng.as_generator`);
    ``fixtures``/``alpha`` (rad) as :class:`throwmap.engine.Scene`; ``settings``:
    :class:`~throwmap.engine.EngineSettings`; ``friction``: :class:`~throwmap.engine.Friction`.
    """
    from ..engine import Friction, ImpulseThrow, Placement, Scene, simulate

    if not isinstance(part, Part):
        raise InvalidStateError("part", f"must be a Part, got {type(part).__name__}")
    if not isinstance(arm, Arm):
        raise InvalidStateError("arm", f"must be an Arm, got {type(arm).__name__}")
    rng = as_generator(rng)
    if x_range is None and arm.length is None:
        raise InvalidStateError("x_range", "an unbounded arm (length None) needs an explicit x_range (m)")
    x_lo, x_hi = _range(x_range, "x_range", (0.0 - arm.back, arm.length))
    h_lo, h_hi = _range(height, "height", DEFAULT_HEIGHT)
    if h_lo < 0:
        raise InvalidStateError("height", f"must be ≥ 0 m above the arm, got {shown(height)}")
    if isinstance(max_redraws, bool) or not isinstance(max_redraws, (int, np.integer)) or max_redraws < 0:
        raise InvalidStateError("max_redraws", f"must be an integer ≥ 0, got {shown(max_redraws)}")
    fixtures = tuple(fixtures)
    friction = Friction() if friction is None else friction
    walls = [f for f in fixtures if isinstance(f, Wall)]
    rejected: Counter = Counter()
    for attempt in range(int(max_redraws) + 1):
        phi = float(rng.uniform(0.0, 2.0 * math.pi))
        x0 = float(rng.uniform(x_lo, x_hi))
        lift = float(rng.uniform(h_lo, h_hi))
        V = world_vertices(part, (x0, 0.0, phi))
        base = arm.h
        for w in walls:  # the drawn pose above a wall: count the height from the wall's top
            if np.any(V[:, 0] >= arm.length - 1e-9) and V[:, 0].min() <= arm.length + w.thickness:
                base = max(base, arm.h + w.height)
        y0 = base - float(V[:, 1].min()) + lift
        scene = Scene(arm, (Placement(part, pose=(x0, y0, phi)),), fixtures, alpha, friction)
        run = simulate(scene, ImpulseThrow(0.0), settings)
        x, side, tilt = run.states[0]
        status = Status(run.statuses[0])
        kind = drop_kind(status, tilt, run.message)
        last = DropResult(run.next_scene(), float(x), int(side), float(tilt), tuple(run.poses[0]), status, kind,
                          run.message, (x0, y0, phi), lift + (base - arm.h), float(run.t_end), attempt,
                          dict(rejected))
        if kind is None:
            return last
        rejected[kind] += 1
    return last


@dataclass(frozen=True, slots=True)
class Spread:
    """Where several parts are dropped from (m): each CM abscissa uniform over ``x_range``, each lowest vertex
    uniform over ``height`` above the arm surface, every pair at least ``gap`` apart at release."""

    x_range: tuple = (0.0, 0.25)
    height: tuple = DEFAULT_HEIGHT
    gap: float = 0.005

    def __post_init__(self):
        object.__setattr__(self, "x_range", _range(self.x_range, "x_range", None))
        object.__setattr__(self, "height", _range(self.height, "height", None))
        if self.height[0] < 0:
            raise InvalidStateError("height", f"must be ≥ 0 m above the arm, got {shown(self.height)}")
        g = self.gap
        if isinstance(g, bool) or not isinstance(g, (int, float)) or not math.isfinite(g) or g < 0:
            raise InvalidStateError("gap", f"must be a finite number ≥ 0 (m), got {shown(g)}")


MAX_DRAWS = 1000
"""Poses drawn for one drop of several parts before the spread is refused as too tight."""


def drop_parts(parts, arm: Arm, rng, *, spread: Spread = Spread(), fixtures=(), alpha: float = 0.0, fixed=(),
               mu_parts: float = 0.5, settings=None, max_redraws: int = MAX_REDRAWS, record: bool = False):
    """Drop ``parts`` together from random poses (φ uniform; CM and height over ``spread``, each at least
    ``spread.gap`` from the others and from the ``fixed`` ``(part, pose)`` already on the arm, none past its end) and
    let them settle with the fixed ones in the engine: ``(EngineRun, redraws)`` — the first run with every part at
    rest on the arm, else the last one. Placements are ordered fixed first, then ``parts``; ``fixtures``, ``alpha``
    (rad) as :class:`~throwmap.engine.Scene`; ``mu_parts`` the part–part friction; ``record`` keeps the run's
    trajectory."""
    from ..engine import Friction, ImpulseThrow, Placement, Scene, simulate
    from ..system.geometry import overlap_depth

    rng = as_generator(rng)
    base = [world_vertices(p, q) for p, q in fixed]
    run = None
    for attempt in range(max_redraws + 1):
        poses, verts = [], list(base)
        tries = 0
        while len(poses) < len(parts) and tries < MAX_DRAWS:
            tries += 1
            part = parts[len(poses)]
            phi = float(rng.uniform(0.0, 2.0 * math.pi))
            x0 = float(rng.uniform(*spread.x_range))
            V = world_vertices(part, (x0, 0.0, phi))
            y0 = arm.h - float(V[:, 1].min()) + float(rng.uniform(*spread.height))
            V = world_vertices(part, (x0, y0, phi))
            if float(V[:, 0].max()) >= arm.length or any(overlap_depth(U, V) > -spread.gap for U in verts):
                continue  # past the end (the wall) or too near another part: draw this part again
            poses.append((x0, y0, phi))
            verts.append(V)
        if len(poses) < len(parts):
            raise InvalidStateError("config.x_range", f"no room to drop the parts apart there ({MAX_DRAWS} draws)")
        pl = tuple(Placement(p, pose=q) for p, q in fixed) + tuple(Placement(p, pose=q) for p, q in zip(parts, poses))
        run = simulate(Scene(arm, pl, tuple(fixtures), alpha, Friction(part_part=mu_parts)), ImpulseThrow(0.0),
                       settings, record=record)
        if int(run.status) == 0:
            return run, attempt
    return run, max_redraws
