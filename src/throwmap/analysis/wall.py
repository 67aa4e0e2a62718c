"""The fixed point a wall at the arm's end makes, found and checked (issue 11, item 2).

With a :class:`~throwmap.Wall` at the arm's end a jog that would carry the part past
the wall stops against it: T(x) = x* = length − u_R for every x just below x* on that
side. :func:`wall_fixed_point` finds that fixed point with :func:`~throwmap.analysis.limit_set`
and checks the multiplier limit_set reports (0) against finite differences of the map.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ThrowmapError
from ..kernels import codes as C
from ..system.arm import Arm
from ..system.fixtures import Wall
from ..system.part import Part
from ..system.starts import start_interval
from ..throws.throw import throw_batch

__all__ = ["wall_fixed_point"]


def wall_fixed_point(part: Part, arm: Arm, omega: float, side: int, *, wall: Wall | None = None, alpha: float = 0.0,
                     model: str = "rigid_body", n_starts: int = 16, rng=0, fd_steps=(1e-3, 1e-4, 1e-5, 1e-6),
                     reference: str | None = None, **options) -> dict:
    """The fixed point at the wall, x* = length − u_R on ``side``, found by :func:`throwmap.limit_set`.

    Found means a fixed point on ``side`` that :attr:`LimitSet.wall_points` calls against the
    wall (within :data:`~throwmap.analysis.limitset.WALL_TOL` below length − u_R; ``gap_m``
    says how far below). Its ``x_star_m`` is the map's own fixed point.

    A jog that would carry the part past the wall stops against it, so T(x) = x* for
    every x near x* on that side: x* is a fixed point with multiplier 0 (superstable:
    reached in finitely many throws). The map is defined only for x ≤ x* (x + u_R ≤
    length), so its derivative there is one-sided: the left difference quotient
    (T(x*) − T(x* − h))/h, computed here for each h in ``fd_steps`` (m), must be 0, and
    limit_set's multiplier (:func:`throwmap.analysis.recurrence._slopes`, one-sided
    where the right neighbour is no valid start) must agree. ``free_slope`` is the
    same quotient of the map without the wall, for comparison. ``reference`` (e.g.
    ``"engine"``) also throws x_w = length − u_R, x_w − 1 mm and x_w − 5 mm in that model
    (``"reference"``: each start's offset from x_w, x' − x_w and side, m). Returns a dict (JSON-ready).
    """
    from .limitset import limit_set

    wall = Wall(0.05, mu=0.0) if wall is None else wall
    kw = {"fixtures": (wall,), "alpha": alpha, **options}
    k = part.check_side(side)
    x_wall = start_interval(part, arm, k)[1]
    info = {"model": model, "part": part.name, "side": k, "omega_rad_s": float(omega), "length_m": arm.length,
            "h_m": arm.h, "mu": arm.mu, "alpha_deg": math.degrees(alpha), "wall_mu": wall.mu, "x_wall_m": x_wall,
            "fd_steps_m": list(fd_steps)}
    try:
        ls = limit_set(part, arm, omega, model, n_starts=n_starts, rng=rng, **kw)
    except ThrowmapError as err:
        return {**info, "found": False, "message": str(err)}
    fps = [a for a in ls.attractors if a.kind == "fixed_point" and ls.wall_points.get(a.id, (None,))[0] == k]
    if not fps:
        return {**info, "found": False, "message": f"limit_set found {ls.kind}: " + "; ".join(
            a.describe() for a in ls.attractors) + f"; escapes {ls.escapes}", "range": ls.range_text}
    a = fps[0]
    xs = a.points[0][1]

    def left(extra: dict, x0: float) -> list:
        xa = np.array([x0] + [x0 - h for h in fd_steps])
        b = throw_batch(part, arm, xa, k, omega, model=model, on_invalid="status", **extra)
        ok = (b.status == C.OK) & (b.side == b.side[0])
        return [float((b.x[0] - b.x[j + 1]) / h) if ok[0] and ok[j + 1] else math.nan for j, h in enumerate(fd_steps)]

    free = left({kk: v for kk, v in kw.items() if kk != "fixtures"}, xs)
    ref = None
    if reference is not None:
        offsets = (0.0, -1e-3, -5e-3)
        b = throw_batch(part, arm, np.array([x_wall + d for d in offsets]), k, omega, model=reference,
                        on_invalid="status", fixtures=(wall,), alpha=alpha)
        ref = {"model": reference, "images": [{"start_offset_m": d, "dx_from_x_wall_m": float(b.x[j] - x_wall),
                                               "side": int(b.side[j]), "status": int(b.status[j])}
                                              for j, d in enumerate(offsets)]}
    return {**info, "found": True, "x_star_m": xs, "gap_m": x_wall - xs, "multiplier": a.multiplier, "residual_m": a.residual,
            "fraction": a.fraction, "n_starts": ls.n_starts, "range": ls.range_text, "fd_left": left(kw, xs),
            "free_slope": free[-1] if free else math.nan, "n_at_wall": len(ls.wall_points), "reference": ref,
            "limit_set": ls.summary()}
