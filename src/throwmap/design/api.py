"""Limit-set design on the exact models (paper Sec. V-A/B, corrected): :func:`design`, :func:`design_critical_points`.

The draft's algorithm (Sec. V-A): choose p; compute the features of the limit set; check that
∂F/∂p has full rank; take damped Newton steps until the features hit the targets. Here the
features come from the exact map of a registered model (default ``"rigid_body"``) — r_i from
:func:`throwmap.analysis.critical_points` to ``xtol``, band tops/bottoms from
:func:`throwmap.analysis.limit_set` — or, with ``model="small_angle_F"``, from the corrected
first-order energy test of :mod:`throwmap.design.small_angle` (the draft's F, fast). The
solver is :func:`throwmap.design.solver.damped_lm`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, ThrowmapError, shown
from ..models import check_model
from ..system.arm import Arm
from ..system.part import Part
from .result import DesignResult, DesignStep
from .small_angle import energy_critical_points
from .solver import LMSettings, damped_lm
from .space import DEFAULT_STEPS, PARAMETERS, DesignSpace
from .targets import Evaluation, Separation, Target, WallWindow, as_targets, evaluate

__all__ = ["design", "design_critical_points", "SpaceOptions", "SolveOptions", "SMALL_ANGLE_F", "DEFAULT_MARGIN", "DEFAULT_TOL"]

SMALL_ANGLE_F = "small_angle_F"
"""``model`` name of the corrected first-order energy test F = K + U − U_crit (r-targets only)."""

DEFAULT_MARGIN = 0.008
"""The weight's centre stays 8 mm inside every edge of the plate (a lead disc of 8 mm radius), m."""

DEFAULT_TOL = 1e-4
"""Success when every targeted feature is within 0.1 mm of its target, m."""

LIMIT_SET_NOISE = 1e-4
"""How precisely a band top/bottom is found from orbits (m), for the rank threshold."""

LIMIT_SET_STEP_FACTOR = 10.0
"""With band top/bottom or separation targets the default difference steps are this many times
:data:`~throwmap.design.space.DEFAULT_STEPS` (5 mm, 0.05 rad/s…), so that a step moves a band's end
by ≫ :data:`LIMIT_SET_NOISE`."""


def _check_float(name, v, *, lo=None):
    if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or not math.isfinite(v):
        raise InvalidStateError(name, f"must be a finite number, got {shown(v)}")
    if lo is not None and v < lo:
        raise InvalidStateError(name, f"must be ≥ {lo}, got {v}")
    return float(v)


def _weight_at(plate: Part, weight_at):
    if weight_at is None:
        from ..system.geometry import polygon_mass_properties

        _, c, _ = polygon_mass_properties(np.asarray(plate.vertices))
        return float(c[0]), float(c[1])
    try:
        x, y = weight_at
    except (TypeError, ValueError):
        raise InvalidStateError("weight_at", f"must be a pair (x, y) in m, got {shown(weight_at)}") from None
    return _check_float("weight_at", x), _check_float("weight_at", y)


@dataclass(frozen=True)
class SpaceOptions:
    """The design space around the varied parameters (:class:`~throwmap.design.space.DesignSpace`): ``bounds``
    (name → (lo, hi), over :data:`~throwmap.design.space.DEFAULT_BOUNDS`), ``margin`` (the weight stays this far
    inside every edge of the plate, m; default 8 mm), ``scales`` and ``steps`` (name → typical size and
    finite-difference half-step; steps × :data:`LIMIT_SET_STEP_FACTOR` by default when a target needs the limit set),
    ``com`` (the start CM (x, y), m, for the draft's ``com_x``/``com_y``; default the plate's)."""

    bounds: dict | None = None
    margin: float = DEFAULT_MARGIN
    scales: dict | None = None
    steps: dict | None = None
    com: tuple | None = None


@dataclass(frozen=True)
class SolveOptions:
    """How the targets are solved for: success when every feature is within ``tol`` of its target (m; default
    0.1 mm); r_i found to ``xtol`` (m; default 0.1 µm, ≪ every FD step × |∂r/∂p|); ``n_grid`` and ``x_max``
    passed to :func:`~throwmap.analysis.critical_points` (grid per side; searched domain, m); ``max_iter`` outer
    Levenberg–Marquardt iterations (:class:`~throwmap.design.solver.LMSettings`); ``limit_options`` passed to
    :func:`~throwmap.analysis.limit_set` for top/bottom/separation targets (default 32 starts per side, seed 0)."""

    tol: float = DEFAULT_TOL
    xtol: float = 1e-7
    n_grid: int = 128
    x_max: float | None = None
    max_iter: int = 40
    limit_options: dict | None = None


MAX_ESCAPE = 0.10
"""A design succeeds only if its limit set holds the part on the arm: at most this share of the starts over the
searched range may escape (behind the joint or off the end) — a limit set that does not exist feeds nothing."""
MAX_WEIGHT = 10.0
"""The heaviest lead weight a design takes, kg (a heavier one is a unit slip: grams typed as kg)."""
N_GRID_RANGE = (8, 100_000)
"""The critical points' grid per side a design accepts (:func:`~throwmap.analysis.critical_points`)."""


def _holds_on_arm(st, model, reach, limit_options) -> tuple[bool, str]:
    """Whether the designed part keeps a limit set on the arm over the starts ``0 < x ≤ reach`` (m): at least one
    attractor, and at most :data:`MAX_ESCAPE` of the starts escaping. Returns ``(holds, what the limit set is)``."""
    from ..analysis.limitset import limit_set

    ls_model = "rigid_body" if model == SMALL_ANGLE_F else model
    opts = {"n_starts": 32, "rng": 0, **dict(limit_options or {})}
    try:
        ls = limit_set(st.part, st.arm, st.omega, ls_model, x_max=reach, **opts)
    except ThrowmapError as err:
        return False, f"its limit set could not be found ({err})"
    escaped = float(sum(ls.escapes.values()))
    fates = ", ".join(f"{k} {100 * v:.1f} %" for k, v in ls.escapes.items()) or "none"
    if not ls.attractors:
        return False, f"no attractor on the arm: every orbit escapes ({fates} of the starts, x ≤ {reach:g} m)"
    if escaped > MAX_ESCAPE:
        return False, (f"{100 * escaped:.1f} % of the starts escape ({fates}, x ≤ {reach:g} m; at most "
                       f"{100 * MAX_ESCAPE:.0f} % may)")
    return True, f"{len(ls.attractors)} attractor(s) on the arm, escapes {fates} (x ≤ {reach:g} m)"


def design(plate: Part, arm: Arm, omega: float, target, *, weight_mass: float = 0.0, weight_at=None,
           vary=("weight_x", "weight_y", "omega"), model: str = "rigid_body", alpha=None,
           space: SpaceOptions = SpaceOptions(), solve: SolveOptions = SolveOptions()) -> DesignResult:
    """Choose the varied parameters so that the limit set's features hit ``target`` (paper Sec. V).

    Parameters
    ----------
    plate : Part
        The bare plate (its vertices and plate mass; lead weights it already has stay fixed).
    arm : Arm
        The arm; ``h`` (m) varies if ``"h"`` is in ``vary``.
    omega : float
        Release rate ω (rad/s), start value if varied.
    target
        ``{side: r_i}`` (m), or a sequence of :class:`~throwmap.design.targets.Target`
        (``"r"``, ``"top"``, ``"bottom"``) and at most one :class:`~throwmap.design.targets.Separation`.
    weight_mass : float
        Lead weight, kg (start value if varied; 0: no weight).
    weight_at : (x, y)
        The weight's (start) place in the frame of the plate's vertices, m (default: the
        plate's centroid).
    vary : sequence of str
        Any of ``weight_x``, ``weight_y``, ``weight_mass``, ``omega``, ``h``, ``alpha``, or the
        draft's ``com_x``, ``com_y`` (:mod:`throwmap.design.space`).
    model : str
        A registered model (default ``"rigid_body"``) or :data:`SMALL_ANGLE_F`.
    alpha : float, optional
        Arm rest angle, rad (start value if varied); passed to the model as ``alpha=``.
    space : SpaceOptions
        Bounds, the weight's margin, scales, difference steps, the start CM (:class:`SpaceOptions`).
    solve : SolveOptions
        Tolerances, the critical points' grid and range, iterations, the limit set's options
        (:class:`SolveOptions`).

    Returns
    -------
    DesignResult
        ``success`` False with a ``message`` when the targets are not reached, or when they are but the
        designed part keeps no limit set on the arm (no attractor, or more than :data:`MAX_ESCAPE` of the starts
        over the searched range escape: a limit set that does not exist feeds nothing). Raises only on invalid
        input.
    """
    if not isinstance(plate, Part):
        raise InvalidStateError("part", f"must be a Part, got {type(plate).__name__}")
    if not isinstance(arm, Arm):
        raise InvalidStateError("arm", f"must be an Arm, got {type(arm).__name__}")
    for name, value, kind in (("space", space, SpaceOptions), ("solve", solve, SolveOptions)):
        if not isinstance(value, kind):
            raise InvalidStateError(name, f"must be a {kind.__name__}, got {type(value).__name__}")
    com, bounds, margin, scales, steps = space.com, space.bounds, space.margin, space.scales, space.steps
    tol, xtol, n_grid, x_max, max_iter = solve.tol, solve.xtol, solve.n_grid, solve.x_max, solve.max_iter
    limit_options = solve.limit_options
    if model != SMALL_ANGLE_F:
        try:
            check_model(model)
        except InvalidStateError as err:
            raise InvalidStateError("model", f"{err.reason[:-1]}, or {SMALL_ANGLE_F})") from None
    omega = _check_float("omega", omega, lo=0.0)
    weight_mass = _check_float("weight_mass", weight_mass, lo=0.0)
    wx, wy = _weight_at(plate, weight_at)
    tol = _check_float("tol", tol)
    xtol = _check_float("xtol", xtol)
    if not tol > 0 or not xtol > 0:
        raise InvalidStateError("tol", f"tol and xtol must be > 0, got {tol}, {xtol}")
    if isinstance(max_iter, bool) or not isinstance(max_iter, int) or max_iter < 1:
        raise InvalidStateError("max_iter", f"must be an integer ≥ 1, got {shown(max_iter)}")
    lo_g, hi_g = N_GRID_RANGE
    if isinstance(n_grid, bool) or not isinstance(n_grid, (int, np.integer)) or not lo_g <= n_grid <= hi_g:
        raise InvalidStateError("n_grid", f"must be an integer from {lo_g} to {hi_g:,} (grid points per side), "
                                          f"got {shown(n_grid)}")
    if x_max is not None:
        x_max = _check_float("x_max", x_max)
        if not x_max > 0:
            raise InvalidStateError("x_max", f"must be > 0 m, got {x_max}")
        if arm.length is not None and x_max > arm.length:
            raise InvalidStateError("x_max", f"{x_max:g} m is beyond the arm's end at {arm.length:g} m")
    if weight_mass > MAX_WEIGHT:
        raise InvalidStateError("weight_mass", f"{weight_mass:g} kg is over {MAX_WEIGHT:g} kg: give the lead weight "
                                               f"in kg (30 g is 0.03)")
    unknown = sorted(set(dict(bounds or {})) - set(PARAMETERS))
    if unknown:
        raise InvalidStateError("bounds", f"unknown parameter {unknown[0]!r} (bounds are given for "
                                          f"{', '.join(PARAMETERS)})")
    targets = as_targets(target)
    start = {"weight_x": wx, "weight_y": wy, "weight_mass": weight_mass, "omega": omega, "h": arm.h,
             "alpha": None if alpha is None else _check_float("alpha", alpha)}
    if com is not None:
        start["com_x"], start["com_y"] = (_check_float("com", v) for v in com)
    need_ls = any(isinstance(t, Separation) or (isinstance(t, Target) and t.kind != "r") for t in targets)
    if need_ls:  # band tops/bottoms are found to ~0.1 mm: ten times longer difference steps
        steps = {**{k: LIMIT_SET_STEP_FACTOR * v for k, v in DEFAULT_STEPS.items()}, **dict(steps or {})}
    space = DesignSpace(plate=plate, arm=arm, start=start, vary=tuple(vary) if not isinstance(vary, str) else (vary,),
                        bounds=dict(bounds or {}), margin=_check_float("margin", margin, lo=0.0),
                        scales=dict(scales or {}), steps=dict(steps or {}))
    for t in targets:
        if t.side not in range(plate.n_sides):
            raise InvalidStateError("target", f"side {t.side} does not exist (the part has sides 0..{plate.n_sides - 1})")
        if isinstance(t, Target):  # a position the searched range cannot hold is bad input, not a failed design
            reach = x_max if x_max is not None else (arm.length if arm.length is not None else 0.6)
            if not 0.0 < t.value <= reach:
                raise InvalidStateError("target", f"{t.label} = {t.value:g} m is outside the searched range "
                                                  f"0 < x ≤ {reach:g} m (the arm length, or x_max)")
        if model == SMALL_ANGLE_F and not (isinstance(t, Target) and t.kind == "r"):
            raise InvalidStateError("target", f"model {SMALL_ANGLE_F!r} gives r_i only, not {t.label}")
    # fixed rows: the separation's rows cover every side of the plate
    labels, inequality = [], []
    for t in targets:
        rows = [f"sep_{j}" for j in range(plate.n_sides)] if isinstance(t, Separation) else [t.label]
        labels += rows
        inequality += [isinstance(t, (Separation, WallWindow))] * len(rows)
    noise = max(xtol, LIMIT_SET_NOISE) if need_ls else (1e-9 if model == SMALL_ANGLE_F else xtol)
    cache: dict = {}

    def features(p):
        key = tuple(np.round(np.asarray(p, dtype=float), 15))
        if key in cache:
            return cache[key]
        try:
            st = space.setup(p)
            if model == SMALL_ANGLE_F:
                r = energy_critical_points(st.part, st.arm, st.omega, x_max=x_max).r
                ev = Evaluation(r=r, top={}, bottom={}, next_kind={},
                                residual={t.label: r.get(t.side, math.nan) - t.value for t in targets})
            else:
                ev = evaluate(st, targets, model, x_max=x_max, xtol=xtol, n_grid=n_grid, limit_options=limit_options)
        except ThrowmapError as err:  # e.g. a CM on an edge: no part there
            st, ev = None, Evaluation({}, {}, {}, {}, {"error": str(err)})
        vec = np.array([ev.residual.get(lb, math.nan) for lb in labels], dtype=float)
        cache[key] = (vec, (st, ev))
        return cache[key]

    rep = damped_lm(features, space.p0, project=space.project, scale=space.scale, step=space.step, tol=tol,
                    noise=noise, labels=labels, inequality=inequality, settings=LMSettings(max_iter=max_iter))
    hist = []
    for itr in rep.iterates:
        st, ev = itr.info
        hist.append(_step(space, itr.p, st, ev, targets, labels, itr.residual, itr.norm, itr.bounds_hit))
    st, ev = rep.info
    if st is None:
        st = space.setup(rep.p)
    final = hist[-1]
    jac = rep.jacobian_end
    j0 = rep.jacobian_start
    v = st.values
    success, message, what = bool(rep.success), rep.message, ""
    if success:
        reach = x_max if x_max is not None else (st.arm.length if st.arm.length is not None else 0.6)
        holds, what = _holds_on_arm(st, model, reach, limit_options)
        if not holds:
            success, message = False, f"targets reached, but the design feeds nothing: {what}"
        else:
            message = f"{message}; limit set: {what}"
    return DesignResult(
        success=success, message=message, part=st.part, arm=st.arm, omega=st.omega,
        weight_at=(v["weight_x"], v["weight_y"]), weight_mass=v["weight_mass"], alpha=v.get("alpha"),
        achieved={t.side: final.achieved[t.label] for t in targets if isinstance(t, Target) and t.kind == "r"},
        features=dict(final.achieved), targets=targets, vary=space.vary,
        bounds={k: space.bounds[k] for k in space.vary if k in space.bounds},
        jacobian_rank=jac.rank if jac else 0, condition=jac.condition if jac else math.inf,
        jacobian_rank_start=j0.rank if j0 else 0, condition_start=j0.condition if j0 else math.inf,
        jacobian=jac.matrix if jac else np.zeros((len(labels), len(space.vary))),
        singular_values=jac.singular_values if jac else (), rank_tol=jac.rank_tol if jac else math.nan,
        scales={k: space.scales[k] for k in space.vary}, history=tuple(hist), model=model, tol=tol, xtol=xtol,
        n_evaluations=len(cache), margin=space.margin, x_max=x_max, targets_reached=bool(rep.success),
        limit_set_note=what)


def _step(space, p, st, ev, targets, labels, residual, norm, hits) -> DesignStep:
    v = space.values(p)
    ach = {}
    for t in targets:
        if isinstance(t, Separation):
            ach.update({f"top_{s}": u for s, u in sorted(ev.top.items())})
        elif isinstance(t, WallWindow):
            ach[t.label] = (ev.wall or {}).get(t.label, math.nan)
        else:
            ach[t.label] = residual.get(t.label, math.nan) + t.value
    part = st.part if st is not None else space.plate
    return DesignStep(values=v, part=part, achieved=ach, r=dict(ev.r), residual=dict(residual), norm=norm,
                      bounds_hit=tuple(hits))


def design_critical_points(part: Part, arm: Arm, omega: float, *, weight_mass: float, weight_at, target: dict,
                           vary=("weight_x", "weight_y", "omega"), model: str = "rigid_body", **options) -> DesignResult:
    """Place a lead weight (and set ω) so that the critical points r_i hit ``target`` (paper Sec. V-B).

    ``part`` is the bare plate, ``weight_mass`` the weight (kg), ``weight_at`` its starting
    (x, y) in the frame of the part's vertices (m), ``target`` ``{side: r_i}`` (m). ``vary``
    any of :data:`~throwmap.design.space.PARAMETERS` (default the draft's three: the weight's
    place — i.e. the CM, with the inertia that goes with it — and ω). Other keywords go to
    :func:`design`. Returns a :class:`~throwmap.design.result.DesignResult`.
    """
    if not isinstance(target, dict):
        raise InvalidStateError("target", f"must be a dict {{side: r_i in m}}, got {shown(target)}")
    return design(part, arm, omega, target, weight_mass=weight_mass, weight_at=weight_at, vary=vary, model=model,
                  **options)
