"""Inverse throws: the release rate that jogs a part to a chosen x (paper Sec. IV, Lemma 4.2).

Lemma 4.2 says that from (x₀, i) any x_f a little beyond x₀ is reached on the same side by one
throw of a suitable rate ω, and that the jog grows with ω. Here that rate is *computed* on any
model, and the monotonicity is *checked*, not assumed:

1. the jog T^ω(x₀, i) is sampled on a grid ω_j = ω_max·j/n (j = 1 … n) and the first rate whose
   throw does not end at rest on side i (a flip, an escape, a refused run) is bracketed and
   bisected: ω_flip, the end of the jog branch;
2. the branch's reach is the range of its landings (jogs go outward for h < 0 in the draft's
   argument; near the joint rigid_body's slow jogs go *inward* — the function takes either); a target outside it is refused with one line naming what the
   faster throws do instead;
3. the first grid interval where T crosses x_f is bisected on ω until |T(ω) − x_f| ≤ ``tol``
   (1 µm by default). A throw inside the bracket that flips counts as "too far".

Lemma 4.2's monotonicity (the jog grows with ω on the branch) is reported as ``monotone`` over
the grid and the bisection's throws; the draft's own statement of it assumes the small-angle
flight. Its lower bound δ on the jog (Lemma 4.1's proof) does not hold near the joint: the jog is
proportional to R + u_L, the support's distance from the joint, and vanishes with it
(:func:`jog_size`; docs/explanation/errata.md).

Units: m, rad/s. Any model registered with :mod:`throwmap.models`; for a realisation that
depends on ω (the engine's recoil arm) pass ``realisation=`` a callable ω → realisation or
``"recoil"`` / ``"impulse"``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown
from ..models import DEFAULT_MODEL
from ..system.arm import regime_warnings_once

__all__ = ["InverseJog", "inverse_jog", "jog_rate", "jog_size", "realisation_factory"]

N_GRID = 48
"""Grid rates on (0, ω_max] sampled before bisecting (the flip and the target)."""
MAX_SPACING = 0.25
"""Largest spacing of those rates, rad/s (more rates for a large ω_max: a coarse grid can step past the end of
the jog branch onto a later return to the same side)."""


def realisation_factory(realisation, *, recoil: float = math.radians(3.0), zeta: float = 0.5):
    """``realisation`` as a callable ω → realisation object, or None (the model's impulse).

    ``None``/``"impulse"``: None (the model's own impulse at ω); ``"recoil"``: the draft's arm,
    :meth:`~throwmap.system.motion.RecoilThrow.for_release_rate` (peak rate ω, recoil
    ``recoil`` rad, damping ``zeta``); a callable is returned as is."""
    if realisation is None or realisation == "impulse":
        return None
    if realisation == "recoil":
        from ..system.motion import RecoilThrow

        return lambda w: RecoilThrow.for_release_rate(float(w), recoil=recoil, zeta=zeta)
    if callable(realisation):
        return realisation
    raise InvalidStateError("realisation", f"must be None, 'impulse', 'recoil' or a callable ω → realisation, "
                                           f"got {shown(realisation)}")


def _finite(value, name: str, *, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)) or not math.isfinite(value):
        raise InvalidStateError(name, f"must be a finite number, got {shown(value)}")
    if positive and value <= 0:
        raise InvalidStateError(name, f"must be > 0, got {shown(value)}")
    return float(value)


@dataclass(frozen=True)
class InverseJog:
    """The answer of :func:`inverse_jog` (SI units).

    ``omega`` (rad/s) jogs ``(x0, side)`` to ``x`` with ``residual`` = |x − x_target| (m);
    ``omega_flip`` is where the jog branch ends (rad/s; ``inf`` when no throw up to
    ``omega_max`` leaves it) and ``beyond`` what the throw there does (e.g. ``"lands on side 1"``,
    ``"escapes (off_end)"``); ``reach`` = (min, max) of the jogs' landings on the branch (m); ``monotone``
    whether the landings at the grid rates ω_j on the branch move one way as ω grows (Lemma 4.2; the
    grid, not the bisection's rates, so that a scattering map's micrometres do not count); ``samples`` the (ω, x) pairs thrown on
    the branch, sorted by ω; ``n_throws`` the throws made; ``scatter`` (m) where the map was not
    continuous at the target's scale (the engine): the rms scatter of its landings about a straight
    line over the local scan that found ``omega`` (nan where bisection sufficed). A rate found on a
    scattering map is exact for that deterministic simulator only: a neighbouring rate lands
    ``scatter`` away.
    """

    omega: float
    x: float
    residual: float
    x0: float
    side: int
    x_target: float
    omega_flip: float
    beyond: str
    reach: tuple
    monotone: bool
    model: str
    n_throws: int
    samples: tuple = field(repr=False, default=())
    scatter: float = math.nan

    def __repr__(self) -> str:
        """One line: the rate, the start, the landing and its residual (:meth:`summary` says all)."""
        return (f"InverseJog(ω = {self.omega:.9g} rad/s: ({self.x0:.6f} m, side {self.side}) → {self.x:.7f} m, "
                f"residual {self.residual * 1e6:.3g} µm, model {self.model}, {self.n_throws} throws)")

    def summary(self) -> str:
        return (f"ω = {self.omega:.9g} rad/s jogs x0 = {self.x0:.6f} m (side {self.side}) to {self.x:.7f} m "
                f"(target {self.x_target:.7f} m, residual {self.residual * 1e6:.3g} µm; model {self.model}; "
                f"jogs reach [{self.reach[0]:.4f}, {self.reach[1]:.4f}] m below ω_flip = {self.omega_flip:.6g} rad/s, "
                f"where the throw {self.beyond}; Lemma 4.2 monotone: {'yes' if self.monotone else 'NO'}; "
                + (f"map scatter {self.scatter * 1e6:.3g} µm; " if math.isfinite(self.scatter) else "") +
                f"{self.n_throws} throws)")


class _Thrower:
    """One throw at ω from the fixed start, counted: ``(x, side, status name)``."""

    def __init__(self, part, arm, x0, side, model, factory, options):
        from ..throws.throw import throw

        self._throw = throw
        self.args = (part, arm, x0, side)
        self.model = model
        self.factory = factory
        self.options = options
        self.n = 0

    def __call__(self, w: float):
        opts = dict(self.options)
        if self.factory is not None:
            opts["realisation"] = self.factory(w)
        self.n += 1
        out = self._throw(*self.args, float(w), self.model, **opts)
        return float(out.x), int(out.side), out.status.name.lower()


ESCAPES = ("behind_joint", "off_end", "no_rest")
"""Status names of a throw that leaves the arm (or never rests); any other non-ok status is a refusal."""


def _below(flip: float, omega_max: float) -> str:
    return f"ω < {flip:.6g} rad/s" if math.isfinite(flip) else f"ω ≤ omega_max = {omega_max:g} rad/s"


def _fate(x, k, status, side) -> str:
    if status == "ok":
        return f"lands on side {k} at x = {x:.4f} m" if k != side else "jogs"
    return f"escapes ({status})" if status in ESCAPES else f"is refused ({status})"


@regime_warnings_once()
def inverse_jog(part, arm, x0: float, side: int, x_target: float, model: str = DEFAULT_MODEL, *,
                omega_max: float = 10.0, tol: float = 1e-6, n_grid: int = N_GRID, realisation=None,
                **throw_options) -> InverseJog:
    """The release rate ω (rad/s) whose throw jogs ``(x0, side)`` to ``x_target`` on the same side (Lemma 4.2).

    Searches ω ∈ (0, ``omega_max``]; ``tol`` (m) is the accepted |T(ω) − x_target|. Raises
    :class:`~throwmap.errors.InvalidStateError` (field ``x_target``) when no jog reaches the target
    — it lies behind the start, or beyond the branch's reach, where faster throws flip or escape —
    and (field ``tol``) when the map is discontinuous at the target so that no rate meets ``tol``.
    ``throw_options`` go to :func:`throwmap.throw` (``fixtures``, ``alpha``, model options).
    """
    x0 = _finite(x0, "x0")
    x_target = _finite(x_target, "x_target")
    omega_max = _finite(omega_max, "omega_max", positive=True)
    tol = _finite(tol, "tol", positive=True)
    if isinstance(n_grid, bool) or not isinstance(n_grid, int) or n_grid < 2:
        raise InvalidStateError("n_grid", f"must be an integer ≥ 2, got {shown(n_grid)}")
    from ..models import get_model

    model = get_model(model).name
    side = part.check_side(side)
    thrower = _Thrower(part, arm, x0, side, model, realisation_factory(realisation), throw_options)
    branch = [(0.0, x0)]  # (ω, T) on the jog branch; T(0) = x0
    grid_rates = {0.0}
    flip_lo, flip_hi, beyond = omega_max, math.inf, "jogs (no flip up to omega_max)"
    n_grid = max(n_grid, math.ceil(omega_max / MAX_SPACING))  # a coarse grid could step over a branch's end
    for j in range(1, n_grid + 1):
        w = omega_max * j / n_grid
        x, k, st = thrower(w)
        if st == "ok" and k == side:
            branch.append((w, x))
            grid_rates.add(w)
            continue
        flip_lo, flip_hi, beyond = branch[-1][0], w, _fate(x, k, st, side)
        break
    if math.isfinite(flip_hi):  # bisect the end of the branch
        lo, hi = flip_lo, flip_hi
        while hi - lo > 1e-9 * hi and hi > 1e-9 * omega_max:  # lo = 0: the first rate already flips
            mid = 0.5 * (lo + hi)
            x, k, st = thrower(mid)
            if st == "ok" and k == side:
                lo = mid
                branch.append((mid, x))
            else:
                hi, beyond = mid, _fate(x, k, st, side)
        flip_lo, flip_hi = lo, hi
    branch.sort()
    ws = np.array([b[0] for b in branch])
    xs = np.array([b[1] for b in branch])
    reach = (float(xs.min()), float(xs.max()))
    if not (reach[0] - tol <= x_target <= reach[1] + tol):
        where = "behind" if x_target < reach[0] else "beyond"
        raise InvalidStateError("x_target", f"no jog from x0 = {x0:.6g} m on side {side} reaches {x_target:.6g} m "
                                            f"({where} the jogs' reach): jogs on side {side} reach [{reach[0]:.6g}, "
                                            f"{reach[1]:.6g}] m for {_below(flip_hi, omega_max)}, where the throw "
                                            f"{beyond} (model {model})")
    # the first sampled interval (from ω = 0 up) whose jog passes the target
    d = xs - x_target
    i = next(j for j in range(len(d)) if abs(d[j]) <= tol or (j > 0 and d[j] * d[0] < 0)) if abs(d[0]) > tol else 0
    w_best, x_best = float(ws[i]), float(xs[i])
    if abs(d[i]) > tol:
        a, b, sa = ws[i - 1], ws[i], math.copysign(1.0, d[i - 1])
        while b - a > 1e-13 * b:
            mid = 0.5 * (a + b)
            x, k, st = thrower(mid)
            if not (st == "ok" and k == side):  # a flip inside the bracket: keep the slower half
                b = mid
                continue
            branch.append((mid, x))
            if abs(x - x_target) < abs(x_best - x_target):
                w_best, x_best = mid, x
            if abs(x - x_target) <= tol:
                break
            if (x - x_target) * sa > 0:
                a = mid
            else:
                b = mid
    scatter = math.nan
    if abs(x_best - x_target) > tol:  # the map jumps over the target at this scale: scan around the bracket
        w_best, x_best, scatter = _polish(thrower, side, branch, w_best, x_best, x_target, POLISH_SPAN, N_POLISH)
        if abs(x_best - x_target) > tol and scatter > POLISH_SPAN / 4:  # wider: a few times the scatter found
            w_best, x_best, scatter = _polish(thrower, side, branch, w_best, x_best, x_target, 3 * scatter,
                                              2 * N_POLISH)
    residual = abs(x_best - x_target)
    branch.sort()
    steps = np.diff(np.array([p[1] for p in branch if p[0] in grid_rates]))  # the grid: the trend, not the scatter
    monotone = bool(np.all(steps > -1e-9) or np.all(steps < 1e-9))
    if residual > tol:
        how = (f"the map scatters by {scatter * 1e6:.3g} µm about a smooth fit there" if scatter < 1e-4 else
               f"the map jumps there (a change of contact mode: landings {scatter * 1e3:.3g} mm rms about a line "
               f"through the jump), so no rate lands on the target")
        raise InvalidStateError("tol", f"the jog map of model {model} is discontinuous at {x_target:.6g} m: the "
                                       f"closest rate, ω = {w_best:.9g} rad/s, lands {residual * 1e6:.3g} µm from it "
                                       f"(tol {tol * 1e6:.3g} µm; {how})")
    return InverseJog(omega=w_best, x=x_best, residual=residual, x0=x0, side=side, x_target=x_target,
                      omega_flip=flip_hi, beyond=beyond, reach=reach, monotone=monotone, model=model,
                      n_throws=thrower.n, samples=tuple(branch), scatter=scatter)


N_POLISH = 64
"""Rates scanned around the answer where bisection meets a jump (a time-stepping engine's map)."""
POLISH_SPAN = 20e-6
"""Half-width of that scan in landing x, m (a few times the engine's scatter)."""


def _polish(thrower, side, branch, w_best, x_best, x_target, span, n):
    """Where the map is not continuous at the target's scale (the engine: contact slop and settling make
    T(ω) scatter by micrometres about a smooth curve), scan ``n`` rates spanning ±``span`` (m) of
    landing around ``w_best`` and keep the closest landing. Returns
    ``(ω, x, scatter)`` with ``scatter`` the rms residual (m) of a straight-line fit over the scan."""
    pts = sorted(branch)
    ws = np.array([p[0] for p in pts])
    xs = np.array([p[1] for p in pts])
    near = np.argsort(np.abs(ws - w_best))[:6]
    if len(near) >= 2 and np.ptp(ws[near]) > 0:
        slope = abs(np.polyfit(ws[near], xs[near], 1)[0])
    else:
        slope = 0.0
    dw = span / slope if slope > 0 else 1e-4 * w_best
    dw = min(max(dw, 1e-9 * w_best), 0.05 * w_best)
    scan = []
    for w in np.linspace(w_best - dw, w_best + dw, n):
        x, k, st = thrower(float(w))
        if st == "ok" and k == side:
            scan.append((float(w), x))
            branch.append((float(w), x))
            if abs(x - x_target) < abs(x_best - x_target):
                w_best, x_best = float(w), x
    if len(scan) >= 3:
        a = np.array(scan)
        fit = np.polyval(np.polyfit(a[:, 0], a[:, 1], 1), a[:, 0])
        scatter = float(np.sqrt(np.mean((a[:, 1] - fit) ** 2)))
    else:
        scatter = math.nan
    return w_best, x_best, scatter


def jog_rate(part, arm, x0: float, side: int, x_target: float, model: str = DEFAULT_MODEL, **kw) -> float:
    """The release rate (rad/s) that jogs ``(x0, side)`` to ``x_target`` (m) on the same side, to 1 µm.

    Just the rate; :func:`inverse_jog` (same arguments) gives the whole answer: the
    branch's reach, where it ends and what happens beyond, the Lemma 4.2 monotonicity check."""
    return inverse_jog(part, arm, x0, side, x_target, model, **kw).omega


@regime_warnings_once()
def jog_size(part, arm, x, side: int, omega: float, model: str = DEFAULT_MODEL, **throw_options) -> np.ndarray:
    """The jog T^ω(x, side) − x (m) at each x (array), nan where the throw does not jog (flip, escape).

    Shows the erratum of Lemma 4.1's proof: the jog has no positive lower bound δ — it shrinks with
    the support's distance from the joint, R + u_L (the draft's small-angle x(t_impact) − R is
    proportional to it)."""
    from ..throws.throw import throw_batch

    x = np.atleast_1d(np.asarray(x, dtype=float))
    out = throw_batch(part, arm, x, side, omega, model, on_invalid="status", **throw_options)
    ok = out.ok & (out.side == side)
    return np.where(ok, out.x - x, np.nan)
