"""Continuation of limit sets: how a throw map's attractors change along one parameter (paper Sec. III-D, continued).

At each value of the parameter — the release rate ω, the arm's height h, its rest angle α, its friction μ, or
the place of the part's lead weight along x or y on the plate — every start of a stated grid (``starts`` per
stable side, evenly over (x_lo, x_max]) is labelled with the attractor its orbit reaches within ``horizon``
throws, or with its escape (:func:`~throwmap.analysis.basins.basins`). Attractors are matched between
neighbouring values by the distance between their sets (:mod:`throwmap.analysis.matching`), so each keeps its
id along the curve.

Where the structure changes between two values — an attractor appears, vanishes, merges or splits, or the share
of starts that escape becomes positive (``escape_onset``) or zero (``escape_end``), or an attractor's set jumps
(grows or shrinks at once by more than the matching's threshold: ``jump``) — the interval is halved,
evaluating the middle value, until it is at most ``tol`` wide; the changes found between the final neighbours are
the events, at the interval's middle ± half its width. A fixed point matched to a period-2 cycle, or whose
multiplier passes −1, is a period doubling: located by bisection on the multiplier of the fixed point itself,
solved as a root of T(x) − x (it is unstable past the doubling, so no orbit finds it), to ``tol``. A fixed point
that vanishes with its multiplier near +1 is a ``fold``.

Every statement holds for the stated starts and horizon: an attractor whose basin misses every start, and a change
that comes and goes between two values of the grid, are not seen (the grid's step says how fine).
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings
from dataclasses import dataclass

from ..errors import InvalidStateError, ThrowmapError, ThrowmapWarning, shown
from ..system.arm import Arm
from ..system.part import Part
from .attractors import domain_text
from .basins import basins
from .budget import Limits
from .maps import DEFAULT_MODEL, ThrowMap
from .bifurcation import Continuation, ContinuationPoint, Event, Resolution
from .doubling import doublings as _doublings
from .matching import match

__all__ = ["PARAMS", "Resolution", "Event", "ContinuationPoint", "Continuation", "continuation", "system_at"]

PARAMS = {"omega": ("rad/s", "ω"), "h": ("m", "h"), "alpha": ("rad", "α"), "mu": ("", "μ"),
          "weight_x": ("m", "lead weight x"), "weight_y": ("m", "lead weight y")}
"""The parameters continued: name → (unit, symbol). ``weight_x``/``weight_y`` move the part's first lead weight
along x or y of the part's frame (m), the other coordinate kept."""

FOLD_MULTIPLIER = 0.9
"""A fixed point that vanishes with a multiplier above this is reported as a fold (multiplier → +1)."""

def _jump_text(a, b) -> str:
    """Where an attractor's set jumped: the side whose hull moved most (or that it gained or lost), in cm."""
    ha, hb = {}, {}
    for h, att in ((ha, a), (hb, b)):
        for s, lo, hi in att.bands:
            l0, h0 = h.get(int(s), (math.inf, -math.inf))
            h[int(s)] = (min(l0, float(lo)), max(h0, float(hi)))
    gained, lost = sorted(set(hb) - set(ha)), sorted(set(ha) - set(hb))
    if gained or lost:
        return ", ".join(t for t in (f"gained side(s) {gained}" if gained else "", f"lost side(s) {lost}" if lost else "")
                         if t) + " at once"
    s = max(ha, key=lambda k: max(abs(ha[k][0] - hb[k][0]), abs(ha[k][1] - hb[k][1])))
    return (f"side {s}: x range [{100 * ha[s][0]:.2f}, {100 * ha[s][1]:.2f}] → [{100 * hb[s][0]:.2f}, "
            f"{100 * hb[s][1]:.2f}] cm at once")


def _first_weight(part: Part, field_name: str):
    if not part.point_masses:
        raise InvalidStateError(field_name, f"part {part.name!r} has no lead weight to move: give one in its part file "
                                            "([[part.point_masses]])")
    return part.point_masses[0]


def system_at(part: Part, arm: Arm, omega, param: str, value: float, throw_options: dict):
    """``(part, arm, omega, throw_options)`` with ``param`` set to ``value`` (SI units; see :data:`PARAMS`)."""
    value = float(value)
    opts = dict(throw_options)
    if param == "omega":
        if not value > 0:
            raise InvalidStateError("omega", f"must be a release rate > 0 rad/s, got {value:g}")
        return part, arm, value, opts
    if param == "h":
        return part, dataclasses.replace(arm, h=value), omega, opts
    if param == "mu":
        if value < 0:
            raise InvalidStateError("mu", f"must be ≥ 0, got {value:g}")
        return part, dataclasses.replace(arm, mu=value), omega, opts
    if param == "alpha":
        opts["alpha"] = value
        return part, arm, omega, opts
    m, (wx, wy) = _first_weight(part, param)
    at = (value, wy) if param == "weight_x" else (wx, value)
    added = sum(float(pm[0]) for pm in part.point_masses)
    try:
        moved = Part.from_vertices(part.vertices, float(part.mass) - added, point_masses=((m, at),) + tuple(part.point_masses[1:]),
                                   name=part.name)
    except ThrowmapError as err:
        raise InvalidStateError(param, f"{value:g} m puts the lead weight at ({at[0]:g}, {at[1]:g}) m: {err.reason}") \
            from None
    return moved, arm, omega, opts


@dataclass(frozen=True, slots=True)
class _State:
    value: float
    attractors: tuple  # as basins found them (ids local to this value)
    escape_fraction: float
    unresolved_fraction: float
    escapes: dict
    r: dict


class _Evaluator:
    """Evaluates the map at a parameter value (basins over the starts), counting and collecting warnings.
    ``family(value)`` gives the map (a :class:`~throwmap.analysis.maps.ConfigMap`)."""

    def __init__(self, family, res: Resolution, rng):
        self.family, self.res, self.rng = family, res, rng
        self.count = 0
        self.notes: dict = {}

    def cmap(self, value):
        return self.family(float(value))

    def __call__(self, value: float, critical: bool = False) -> _State:
        self.count += 1
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always", ThrowmapWarning)
            cmap = self.cmap(value)
            b = basins(cmap, grid=self.res.starts, max_throws=self.res.horizon, n_check=0, rng=self.rng,
                       limits=Limits(force=True))
            r = {}
            if critical:
                from .critical import critical_points

                cp = critical_points(cmap, n_grid=64, xtol=1e-5, limits=Limits(force=True))
                r = {int(s): float(v) for s, v in cp.r.items()}
        for w in seen:
            if issubclass(w.category, ThrowmapWarning):
                self.notes.setdefault(" ".join(str(w.message).split()), None)
            else:
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
        esc = {k: float(v) for k, v in b.escapes.items()}
        unresolved = esc.pop("unresolved", 0.0)
        reached = _one_per_set([a for a in b.attractors if a.fraction > 0])  # one no start reaches is not followed
        return _State(float(value), reached, float(sum(esc.values())), float(unresolved), esc, r)


SAME_SET = 1e-3
"""Attractors found at one value whose sets lie this close (m, :func:`~throwmap.analysis.matching.set_distance`,
on the same sides) are one: a cycle and the "band" traced by orbits still converging slowly onto it."""


def _one_per_set(attractors) -> tuple:
    """``attractors`` with those on the same set (:data:`SAME_SET`) made one: the most specific kind kept (fixed
    point, then cycle, then band), the basin fractions added."""
    from .matching import set_distance

    rank = {"fixed_point": 0, "cycle": 1, "band": 2}
    out: list = []
    for a in sorted(attractors, key=lambda a: rank[a.kind]):
        for k, b in enumerate(out):
            if set(a.sides) == set(b.sides) and set_distance(a, b) <= SAME_SET:
                out[k] = b.with_fraction(b.fraction + a.fraction)
                break
        else:
            out.append(a)
    return tuple(sorted(out, key=lambda a: a.id))


class _Pairs:
    """The matching of neighbouring states (cached: the refinement and the final pass ask for the same pairs):
    fixed points of the earlier state that double into the later one are paired first (:func:`_doublings`)."""

    def __init__(self, ev, tol: float, ptol: float):
        self.ev, self.tol, self.ptol = ev, tol, ptol
        self.cache: dict = {}

    def __call__(self, a: _State, b: _State):
        """``(to_before, changes, doublings)``: the matching, its changes, and ``[(i, j, value, half width)]``."""
        key = (a.value, b.value)
        if key not in self.cache:
            dbl = _doublings(self.ev, a, b, self.tol, self.ptol)
            to_before, changes = match(a.attractors, b.attractors, self.tol, forced=[(i, j) for i, j, _, _ in dbl])
            self.cache[key] = (to_before, changes, dbl)
        return self.cache[key]

    def changed(self, a: _State, b: _State) -> bool:
        """Whether the structure changes between ``a`` and ``b`` (matching, or the escape share's sign)."""
        return bool(self(a, b)[1]) or (a.escape_fraction > 0) != (b.escape_fraction > 0)


def continuation(part, arm=None, param: str = "omega", values=None, *, omega=None, model: str = DEFAULT_MODEL,
                 resolution: Resolution = Resolution(), rng=0, progress=None, limits: Limits | None = None,
                 **throw_options) -> Continuation:
    """Follow the attractors of ``part`` on ``arm`` along ``param`` over ``values`` (module docstring).

    ``param``: one of :data:`PARAMS`; ``values``: the grid (ascending, ≥ 2 values, in the parameter's unit);
    ``omega``: the release rate (rad/s) where ω is not the parameter; ``model``: the throw model; ``resolution``:
    :class:`Resolution` (starts, horizon, tolerances); ``rng``: the seed of the limit-set search at every value (the
    same at each, so that values differ only by the parameter); ``progress(stage, done, total)``; ``limits``: the
    work guard (the first value is timed and the whole estimated, refused above ``limits.max_seconds`` unless
    forced); ``throw_options``: as for :func:`~throwmap.analysis.basins.basins` (``fixtures``, ``alpha`` …).

    ``part`` may instead be a family of maps, ``part(value)`` → a :class:`~throwmap.analysis.maps.ConfigMap`
    (``arm`` None, ``param`` any name, no ``omega``, ``model`` or ``throw_options``; ``resolution.x_max`` unused):
    the same continuation on any map, e.g. a synthetic one with known bifurcations. A
    :class:`~throwmap.analysis.maps.FunctionMap` is the shortest way: ``f(x, side)`` returns ``(x', side',
    status)`` arrays, ``status`` integer codes of :class:`throwmap.records.outcome.Status` (0, ``Status.OK``: at rest
    on the arm; e.g. ``Status.OFF_END``, ``Status.BEHIND_JOINT``: it left)::

        def family(r):
            def f(x, side):
                y = r * x * (1 - x)
                ok = (y > 0) & (y <= 1)
                return np.where(ok, y, x), side, np.where(ok, Status.OK, Status.OFF_END)
            return FunctionMap(f, {0: (0.0, 0.999)}, deterministic=True)

        continuation(family, None, "r", np.linspace(2.8, 3.2, 9))
    """
    t0 = time.perf_counter()
    if not isinstance(resolution, Resolution):
        raise InvalidStateError("resolution", f"must be a Resolution, got {type(resolution).__name__}")
    try:
        grid = [float(v) for v in values]
    except (TypeError, ValueError):
        raise InvalidStateError("values", f"must be a sequence of numbers, got {shown(values)}") from None
    if len(grid) < 2 or not all(math.isfinite(v) for v in grid) or any(b <= a for a, b in zip(grid, grid[1:])):
        raise InvalidStateError("values", f"must be ≥ 2 finite values in ascending order, got {shown(values)}")
    res = resolution
    if callable(part) and not isinstance(part, Part):
        if arm is not None or omega is not None or throw_options:
            raise InvalidStateError("arm", "a family of maps takes no arm, omega or throw options")
        if not (isinstance(param, str) and param):
            raise InvalidStateError("param", f"must name the family's parameter, got {shown(param)}")
        family, unit = part, ""
        model = getattr(part, "__name__", type(part).__name__)
        sys_doc = {"family": model}
    else:
        if param not in PARAMS:
            raise InvalidStateError("param", f"must be one of {', '.join(PARAMS)}, got {shown(param)}")
        if not isinstance(part, Part):
            raise InvalidStateError("part", f"must be a Part or a family of maps, got {type(part).__name__}")
        if not isinstance(arm, Arm):
            raise InvalidStateError("arm", f"must be an Arm, got {type(arm).__name__}")
        if param != "omega" and omega is None:
            raise InvalidStateError("omega", f"a release rate (rad/s) is required when the parameter is {param}")
        if param == "omega" and omega is not None:
            raise InvalidStateError("omega", "is the parameter: give its values, not omega")
        if param.startswith("weight"):
            _first_weight(part, param)
        if param == "mu":
            from ..models import get_model

            if not get_model(model).features.friction:
                raise InvalidStateError("param", f"mu: model {model!r} does not use the arm's friction (it assumes no "
                                                 "slip): continue μ with a model that does, e.g. rigid_body")

        def family(value):
            p, a, w, opts = system_at(part, arm, omega, param, value, throw_options)
            return ThrowMap(p, a, w, model, res.x_max, opts)

        for v in (grid[0], grid[-1]):
            family(v)  # a bad end value is refused before any work
        unit = PARAMS[param][0]
        sys_doc = {"part": part.name, "h_m": arm.h, "mu": arm.mu if math.isfinite(arm.mu) else "inf", "g_m_s2": arm.g,
                   "omega_rad_s": omega, "alpha_rad": float(throw_options.get("alpha", 0.0)),
                   "fixtures": [type(f).__name__ for f in throw_options.get("fixtures", ())],
                   "lead_weights": [{"mass_kg": float(m), "at_m": [float(x), float(y)]}
                                    for m, (x, y) in part.point_masses], "model": model}
    ev = _Evaluator(family, res, rng)

    def tick(stage, done, total):
        if progress is not None:
            progress(stage, done, total)

    limits = Limits.of(limits)
    states = [ev(grid[0], res.critical)]
    tick("values", 1, len(grid))
    per = time.perf_counter() - t0
    need = per * len(grid)
    if need > limits.max_seconds and not limits.force:
        raise InvalidStateError("values", f"{len(grid)} values need ≈ {need:.0f} s ({per:.1f} s measured on the first), "
                                          f"over the limit of {limits.max_seconds:.0f} s: fewer values or starts, "
                                          "or force it")
    for k, v in enumerate(grid[1:], 2):
        states.append(ev(v, res.critical))
        tick("values", k, len(grid))

    # locate structural changes: halve every interval that has one until it is at most tol wide
    pairs = _Pairs(ev, res.match_tol, res.tol)
    refined: list = []
    todo = [(states[k], states[k + 1]) for k in range(len(states) - 1)]
    while todo:
        a, b = todo.pop()
        if b.value - a.value <= 2 * res.tol or not pairs.changed(a, b):
            continue
        if len(refined) >= res.max_refine:
            break
        m = ev(0.5 * (a.value + b.value))
        refined.append(m)
        tick("locating events", len(refined), len(refined) + len(todo) + 1)
        todo += [(a, m), (m, b)]
    everything = sorted(states + refined, key=lambda s: s.value)
    grid_values = set(grid)

    # ids along the curve, and the events between neighbours
    points, events = [], []
    ids: list = []
    next_id = 1
    for k, s in enumerate(everything):
        if k == 0:
            ids = list(range(1, len(s.attractors) + 1))
            next_id = len(ids) + 1
        else:
            p = everything[k - 1]
            to_before, changes, doublings = pairs(p, s)
            new_ids = []
            for j in range(len(s.attractors)):
                if j in to_before:
                    new_ids.append(ids[to_before[j]])
                else:
                    new_ids.append(next_id)
                    next_id += 1
            mid, half = 0.5 * (p.value + s.value), 0.5 * (s.value - p.value)
            fine = s.value - p.value <= 2 * res.tol * (1 + 1e-9) or not (p.value in grid_values and s.value in grid_values)
            for c in changes:
                before = [ids[i] for i in c.before]
                after = [new_ids[j] for j in c.after]
                kind, detail = c.kind, ""
                if kind == "vanish":
                    a = p.attractors[c.before[0]]
                    if a.kind == "fixed_point" and math.isfinite(a.multiplier) and a.multiplier >= FOLD_MULTIPLIER:
                        kind, detail = "fold", f"fixed point's multiplier {a.multiplier:+.3f} before it vanished"
                    else:
                        detail = f"{a.kind} on sides {list(a.sides)} vanished"
                elif kind == "appear":
                    detail = f"{s.attractors[c.after[0]].kind} on sides {list(s.attractors[c.after[0]].sides)} appeared"
                elif kind == "merge":
                    detail = f"#{before[0]} merged into #{before[1]}"
                elif kind == "jump":
                    detail = _jump_text(p.attractors[c.before[0]], s.attractors[c.after[0]])
                else:
                    detail = f"#{after[1]} split off #{before[0]}"
                if not fine:
                    detail += " (not located: the refinement cap was reached)"
                events.append(Event(kind, mid, half, tuple(before + [i for i in after if i not in before]), detail))
            if (p.escape_fraction > 0) != (s.escape_fraction > 0):
                kind = "escape_onset" if s.escape_fraction > 0 else "escape_end"
                events.append(Event(kind, mid, half, (), f"escape share {100 * p.escape_fraction:.2f} % → "
                                                        f"{100 * s.escape_fraction:.2f} % of the starts"))
            for i, j, value, width in doublings:
                fp = p.attractors[i]
                events.append(Event("period_doubling", value, width, (ids[i],),
                                    f"fixed point at {100 * fp.points[0][1]:.2f} cm on side {fp.points[0][0]}: its "
                                    f"multiplier passes −1 (the attractor after it: {s.attractors[j].kind})"))
            ids = new_ids
        atts = tuple(a.with_fraction(a.fraction, ident) for a, ident in zip(s.attractors, ids))
        points.append(ContinuationPoint(s.value, atts, s.escape_fraction, s.unresolved_fraction, s.escapes, s.r,
                                        refined=s.value not in grid_values))
    events.sort(key=lambda e: e.value)
    first = ev.cmap(grid[0])
    rng_doc = {"starts_per_side": res.starts, "x_max_m": res.x_max, "horizon_throws": res.horizon,
               "domain_at_first_value": {str(s): list(v) for s, v in first.domain().items()},
               "text": f"{res.starts} per stable side over " + domain_text(first.domain())
               + f", {res.horizon} throws"}
    return Continuation(param, unit, tuple(grid), tuple(points), tuple(events), rng_doc, sys_doc, model,
                        res, tuple(ev.notes), time.perf_counter() - t0, ev.count)
