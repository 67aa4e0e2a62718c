"""The fixed point a wall at the arm's end makes, found and checked.

With a :class:`~throwmap.Wall` at the arm's end a jog that would carry the part past
the wall stops against it: T(x) = x* = length − u_R for every x just below x* on that
side. :func:`wall_fixed_point` finds that fixed point with :func:`~throwmap.analysis.limit_set`
and checks the multiplier limit_set reports (0) against finite differences of the map.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ThrowmapError
from ..kernels import codes as C
from ..records.outcome import Status
from ..system.arm import Arm
from ..system.fixtures import Wall
from ..system.part import Part
from ..system.starts import start_interval
from ..throws.throw import throw_batch

__all__ = ["WallFixedPoint", "wall_fixed_point"]

_INFO = ("model", "part", "side", "omega_rad_s", "length_m", "h_m", "mu", "alpha_deg", "wall_mu", "x_wall_m",
         "fd_steps_m")
_FOUND = ("x_star_m", "gap_m", "multiplier", "residual_m", "fraction", "n_starts", "range", "fd_left", "free_slope",
          "n_at_wall", "reference", "limit_set")


@dataclass(frozen=True, slots=True)
class WallFixedPoint:
    """The answer of :func:`wall_fixed_point` (SI units; ``alpha_deg`` in degrees).

    The system: ``model``, ``part`` (its name), ``side``, ``omega_rad_s``, ``length_m``, ``h_m``, ``mu``,
    ``alpha_deg``, ``wall_mu``; ``x_wall_m`` = length − u_R; ``fd_steps_m`` the steps h of the left differences.
    ``found``: whether limit_set found the fixed point at the wall (else ``message`` says why, and ``range`` the
    starts analysed where limit_set ran). Found: ``x_star_m`` (the map's own fixed point), ``gap_m`` = x_w − x*,
    limit_set's ``multiplier``, ``residual_m``, ``fraction`` of ``n_starts`` starts that reach it, ``fd_left``
    the left difference quotients (T(x*) − T(x* − h))/h per step (nan where a throw did not rest on the side),
    ``free_slope`` the same without the wall at the smallest step, ``n_at_wall`` the fixed points at the wall,
    ``reference`` (a dict: the reference model's images of x_w, x_w − 1 mm, x_w − 5 mm, or None) and
    ``limit_set`` (:meth:`LimitSet.summary`).
    """

    model: str
    part: str
    side: int
    omega_rad_s: float
    length_m: float
    h_m: float
    mu: float
    alpha_deg: float
    wall_mu: float
    x_wall_m: float
    fd_steps_m: tuple
    found: bool
    message: str = ""
    range: str | None = None
    x_star_m: float = math.nan
    gap_m: float = math.nan
    multiplier: float = math.nan
    residual_m: float = math.nan
    fraction: float = math.nan
    n_starts: int = 0
    fd_left: tuple = ()
    free_slope: float = math.nan
    n_at_wall: int = 0
    reference: dict | None = None
    limit_set: dict | None = None

    def to_dict(self) -> dict:
        """As a JSON-ready dict: the system's keys, ``found``, then ``message`` (and ``range`` where limit_set
        ran) when not found, else every number of the fixed point."""
        out = {k: getattr(self, k) for k in _INFO}
        out["fd_steps_m"] = list(self.fd_steps_m)
        if not self.found:
            out.update(found=False, message=self.message)
            if self.range is not None:
                out["range"] = self.range
            return out
        out["found"] = True
        out.update({k: getattr(self, k) for k in _FOUND})
        out["fd_left"] = list(self.fd_left)
        return out

    @classmethod
    def from_dict(cls, d: dict) -> "WallFixedPoint":
        """The inverse of :meth:`to_dict`."""
        kw = {k: d[k] for k in _INFO}
        kw["fd_steps_m"] = tuple(d["fd_steps_m"])
        kw.update({k: d[k] for k in ("found", "message", "range") if k in d})
        if d.get("found"):
            kw.update({k: d[k] for k in _FOUND if k in d})
            kw["fd_left"] = tuple(_nan(v) for v in d.get("fd_left", ()))
            kw["free_slope"] = _nan(d.get("free_slope"))
        return cls(**kw)

    def lines(self) -> list[str]:
        """The fixed point in words: x*, its gap below x_w, the multiplier, the left difference quotients and the
        reference's images (or why it was not found)."""
        if not self.found:
            return [f"wall fixed point ({self.model}, {self.part}, side {self.side}): NOT found — {self.message}"]
        fd = ", ".join(f"h = {h:g} m: {v:+.3g}" for h, v in zip(self.fd_steps_m, self.fd_left))
        ref = self.reference or {}
        imgs = "; ".join(f"T(x_w {1e3 * g['start_offset_m']:+g} mm) − x_w = {1e6 * g['dx_from_x_wall_m']:+.3g} µm "
                         f"(side {g['side']}, {Status(g['status']).label})" for g in ref.get("images", ()))
        free = "—" if self.free_slope is None or not math.isfinite(self.free_slope) else format(self.free_slope, "+.3g")
        return [f"wall fixed point ({self.model}, {self.part}, ω = {self.omega_rad_s:g} rad/s, L = "
                f"{self.length_m:g} m, μ = {_mu(self.mu)}, α = {self.alpha_deg:g}°, wall μ {_mu(self.wall_mu)}): "
                f"x* = {self.x_star_m:.6f} m on side {self.side} ({1e6 * self.gap_m:.3g} µm below x_w = length − u_R "
                f"= {self.x_wall_m:.6f} m), multiplier "
                f"{self.multiplier:+.3g}, residual {self.residual_m:.3g} m, reached from {100 * self.fraction:.1f} % "
                f"of {self.n_starts} starts ({self.range}; {self.n_at_wall} fixed point(s) at the wall in all)",
                f"  left difference quotients (T(x*) − T(x* − h))/h: {fd}; the map without the wall at x*: slope "
                f"{free}"] + ([f"  {ref['model']}: {imgs}"] if imgs else [])

    def table(self) -> str:
        """:meth:`lines` as text."""
        return "\n".join(self.lines())

    def plot(self, ax=None):
        """The left difference quotients against the step h, with limit_set's multiplier
        (:func:`throwmap.viz.wall.plot_wall_fixed_point`)."""
        from ..viz.wall import plot_wall_fixed_point

        return plot_wall_fixed_point(self, ax=ax)


def _nan(v):
    return math.nan if v is None else v


def _mu(v) -> str:
    return "∞" if v is None or math.isinf(v) else f"{v:g}"


def wall_fixed_point(part: Part, arm: Arm, omega: float, side: int, *, wall: Wall | None = None, alpha: float = 0.0,
                     model: str = "rigid_body", n_starts: int = 16, rng=0, fd_steps=(1e-3, 1e-4, 1e-5, 1e-6),
                     reference: str | None = None, **options) -> WallFixedPoint:
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
    (``"reference"``: each start's offset from x_w, x' − x_w and side, m). Returns a :class:`WallFixedPoint`
    (``to_dict()``: JSON-ready).
    """
    from .limitset import limit_set

    wall = Wall(0.05, mu=0.0) if wall is None else wall
    kw = {"fixtures": (wall,), "alpha": alpha, **options}
    k = part.check_side(side)
    x_wall = start_interval(part, arm, k)[1]
    info = {"model": model, "part": part.name, "side": k, "omega_rad_s": float(omega), "length_m": arm.length,
            "h_m": arm.h, "mu": arm.mu, "alpha_deg": math.degrees(alpha), "wall_mu": wall.mu, "x_wall_m": x_wall,
            "fd_steps_m": tuple(fd_steps)}
    try:
        ls = limit_set(part, arm, omega, model, n_starts=n_starts, rng=rng, **kw)
    except ThrowmapError as err:
        return WallFixedPoint(**info, found=False, message=str(err))
    fps = [a for a in ls.attractors if a.kind == "fixed_point" and ls.wall_points.get(a.id, (None,))[0] == k]
    if not fps:
        return WallFixedPoint(**info, found=False, message=f"limit_set found {ls.kind}: " + "; ".join(
            a.describe() for a in ls.attractors) + f"; escapes {ls.escapes}", range=ls.range_text)
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
    return WallFixedPoint(**info, found=True, x_star_m=xs, gap_m=x_wall - xs, multiplier=a.multiplier,
                          residual_m=a.residual, fraction=a.fraction, n_starts=ls.n_starts, range=ls.range_text,
                          fd_left=tuple(left(kw, xs)), free_slope=free[-1] if free else math.nan,
                          n_at_wall=len(ls.wall_points), reference=ref, limit_set=ls.summary())
