"""The throw map T^ω(x, side): one throw or a batch, by model (paper Sec. III-D).

Models
------
``"paper"``        exact within the paper's assumptions (Sec. III, Eqs. 1–4), no
                   small-angle approximation (:mod:`throwmap.kernels.paper`).
``"small_angle"``  the draft's first-order closed forms of Sec. IV–V, corrected
                   (:mod:`throwmap.kernels.small_angle`).
``"small_angle2"`` the same closed forms kept consistently to second order in ω t*.
``"rigid_body"``   the exact rigid-body hybrid dynamics of one polygon on the arm line
                   with Coulomb friction ``arm.mu``: lift-off, sliding impacts and
                   sliding pivots (:mod:`throwmap.kernels.rigid_body`).
``"engine"``       a full pymunk simulation (:mod:`throwmap.engine`): fixtures, arm
                   rest angle and finite arm motions are available only here.
"""

from __future__ import annotations

import math

import numpy as np

from ..system.arm import Arm, warn_if_outside_regime
from ..errors import InvalidStateError
from ..kernels import codes as C
from ..kernels.paper import throw_many, throw_one
from ..kernels.small_angle import throw_many_small_angle, throw_one_small_angle
from .outcome import BatchOutcome, ThrowOutcome
from ..system.part import Part

__all__ = ["MODELS", "throw", "throw_batch"]

MODELS = ("paper", "small_angle", "small_angle2", "rigid_body", "engine")
ANALYTIC_MODELS = ("paper", "small_angle", "small_angle2", "rigid_body")

DEFAULT_TOL = 1e-14
"""Contact tolerance of the first-contact search, m."""
DEFAULT_MAX_ITER = 100_000
"""Cap on first-contact search steps."""
DEFAULT_MAX_IMPACTS = 10_000
"""Cap on plastic impacts in one throw (status NO_REST beyond)."""
DEFAULT_N_SAMPLES = 16
"""Points per pivot swing at which the friction demand is sampled."""


_ENGINE_KEYS = ("settings", "fixtures", "alpha", "realisation", "friction", "workers", "progress")
_NO_TRAJ = np.empty((0, 4))


def _check_engine_options(model: str, options: dict) -> None:
    for key in options:
        if key not in _ENGINE_KEYS:
            raise InvalidStateError(key, f"unknown keyword (engine keywords: {', '.join(_ENGINE_KEYS)})")
        if model != "engine":
            raise InvalidStateError(key, f"only the \"engine\" model takes {key!r} (model is {model!r})")


def check_model(model: str) -> str:
    if model not in MODELS:
        raise InvalidStateError("model", f"unknown model {model!r} (choose from {', '.join(MODELS)})")
    return model


def _check_scalar(value, field: str) -> float:
    if isinstance(value, bool):
        raise InvalidStateError(field, f"must be a number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InvalidStateError(field, f"must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise InvalidStateError(field, f"must be finite, got {v}")
    return v


def check_start(part: Part, arm: Arm, x: float, side: int, omega: float) -> tuple[float, int, float]:
    """Validate a throw's start; returns ``(x, side, omega)`` as Python scalars."""
    k = part.check_side(side)
    x = _check_scalar(x, "x")
    omega = _check_scalar(omega, "omega")
    if omega < 0:
        raise InvalidStateError("omega", f"must be ≥ 0 (the arm throws upward), got {omega}")
    x_min = -float(part.uL[k])
    if x <= x_min:
        raise InvalidStateError(
            "x", f"the left support vertex is behind the joint: on side {k} x must exceed {x_min:.6g} m, got {x:.6g}"
        )
    if arm.length is not None and x > arm.length:
        raise InvalidStateError("x", f"the CM is beyond the arm's end ({arm.length:g} m), got {x:.6g}")
    return x, k, omega


def throw(
    part: Part,
    arm: Arm,
    x: float,
    side: int,
    omega: float,
    model: str = "paper",
    *,
    tol: float = DEFAULT_TOL,
    max_iter: int = DEFAULT_MAX_ITER,
    max_impacts: int = DEFAULT_MAX_IMPACTS,
    n_samples: int = DEFAULT_N_SAMPLES,
    **engine_options,
) -> ThrowOutcome:
    """Throw ``part`` resting at ``(x, side)`` on ``arm`` with release rate ``omega`` (rad/s).

    Returns a :class:`ThrowOutcome` (new ``x``, ``side``, ``status`` and the record).
    Raises :class:`~throwmap.errors.InvalidStateError` for an inadmissible start:
    unknown or unstable side, a left support vertex at x ≤ 0, negative ω.

    ``model="engine"`` accepts the keywords of :func:`throwmap.engine.engine_throw`
    (``settings``, ``fixtures``, ``alpha``, ``realisation``, ``friction``).
    """
    check_model(model)
    _check_engine_options(model, engine_options)
    x0, k, om = check_start(part, arm, x, side, omega)
    warn_if_outside_regime(part, arm)
    if model == "engine":
        from ..engine import engine_throw

        return engine_throw(part, arm, x0, k, om, **engine_options)
    rec = np.empty(C.NREC)
    L = arm.length_or_inf
    rho2 = part.radius_of_gyration**2
    if model == "rigid_body":
        from ..kernels.rigid_body import throw_one_rigid_body

        xn, kn, st = throw_one_rigid_body(x0, k, om, arm.h, arm.g, L, rho2, arm.mu, part.w, part.beta, part.d,
                                          part.uL, part.uR, part.ell, part.stable, tol, max_iter, max_impacts, rec,
                                          _NO_TRAJ, 1.0)
    elif model == "paper":
        xn, kn, st = throw_one(x0, k, om, arm.h, arm.g, L, rho2, part.w, part.beta, part.d, part.uL, part.uR,
                               part.ell, part.stable, tol, max_iter, max_impacts, n_samples, rec)
    else:
        xn, kn, st = throw_one_small_angle(x0, k, om, arm.h, arm.g, L, rho2, part.d, part.uL, part.uR, part.ell,
                                           part.length, part.stable, 1 if model == "small_angle" else 2, rec)
    return ThrowOutcome.from_record(part, x0, k, om, model, xn, kn, st, rec)


def throw_batch(
    part: Part,
    arm: Arm,
    x,
    side,
    omega,
    model: str = "paper",
    *,
    on_invalid: str = "raise",
    tol: float = DEFAULT_TOL,
    max_iter: int = DEFAULT_MAX_ITER,
    max_impacts: int = DEFAULT_MAX_IMPACTS,
    n_samples: int = DEFAULT_N_SAMPLES,
    **engine_options,
) -> BatchOutcome:
    """Many independent throws; ``x``, ``side`` and ``omega`` broadcast against each other.

    ``on_invalid="raise"`` refuses the batch at its first inadmissible start (the
    error names the index); ``"status"`` marks such entries ``INVALID_START`` and
    throws the rest. Runs the compiled kernels in parallel over the entries;
    ``model="engine"`` takes the keywords of :func:`throwmap.engine.engine_batch`
    (``workers`` processes, ``progress``, and the engine keywords of :func:`throw`).
    """
    check_model(model)
    _check_engine_options(model, engine_options)
    if on_invalid not in ("raise", "status"):
        raise InvalidStateError("on_invalid", f"must be 'raise' or 'status', got {on_invalid!r}")
    xb, sb, ob = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(side), np.asarray(omega, dtype=float))
    shape = xb.shape
    xf = np.ascontiguousarray(xb, dtype=float).ravel()
    of = np.ascontiguousarray(ob, dtype=float).ravel()
    sraw = np.asarray(sb).ravel()
    if sraw.size and not np.issubdtype(sraw.dtype, np.integer):
        if not np.all(np.isfinite(sraw.astype(float))) or np.any(sraw.astype(float) != np.round(sraw.astype(float))):
            raise InvalidStateError("side", "must be integer side indices")
    sf = sraw.astype(np.int64)
    n = part.n_sides
    in_range = (sf >= 0) & (sf < n)
    stable = np.zeros(sf.shape, dtype=bool)
    stable[in_range] = part.stable[sf[in_range]]
    uL = np.where(in_range, part.uL[np.clip(sf, 0, n - 1)], np.nan)
    L = arm.length_or_inf
    valid = stable & np.isfinite(xf) & np.isfinite(of) & (of >= 0) & (xf + uL > 0) & (xf <= L)
    if on_invalid == "raise" and not np.all(valid):
        i = int(np.flatnonzero(~valid)[0])
        idx = np.unravel_index(i, shape) if shape else ()
        try:
            check_start(part, arm, xf[i], int(sf[i]) if in_range[i] else int(sf[i]), of[i])
        except InvalidStateError as err:
            raise InvalidStateError(f"{err.field}[{', '.join(map(str, idx))}]", err.reason) from None
        raise InvalidStateError(f"x[{i}]", "inadmissible start")  # pragma: no cover - defensive
    if np.any(valid):
        warn_if_outside_regime(part, arm)
    sf_safe = np.where(in_range, sf, 0)
    m = xf.size
    x_out = np.empty(m)
    side_out = np.empty(m, dtype=np.int64)
    status_out = np.empty(m, dtype=np.int64)
    rec_out = np.empty((m, C.NREC))
    rho2 = part.radius_of_gyration**2
    if model == "engine":
        from ..engine import engine_batch

        res = engine_batch(part, arm, xf, sf_safe, of, valid=valid, **engine_options)
        x_out, side_out, status_out, rec_out = res.x, res.side, res.status, res.records
    elif model == "rigid_body":
        from ..kernels.rigid_body import throw_many_rigid_body

        throw_many_rigid_body(xf, sf_safe, of, valid, arm.h, arm.g, L, rho2, arm.mu, part.w, part.beta, part.d,
                              part.uL, part.uR, part.ell, part.stable, tol, max_iter, max_impacts, x_out, side_out,
                              status_out, rec_out)
    elif model == "paper":
        throw_many(xf, sf_safe, of, valid, arm.h, arm.g, L, rho2, part.w, part.beta, part.d, part.uL, part.uR,
                   part.ell, part.stable, tol, max_iter, max_impacts, n_samples, x_out, side_out, status_out, rec_out)
    else:
        throw_many_small_angle(xf, sf_safe, of, valid, arm.h, arm.g, L, rho2, part.d, part.uL, part.uR, part.ell,
                               part.length, part.stable, 1 if model == "small_angle" else 2, x_out, side_out,
                               status_out, rec_out)
    side_out[~valid] = sf[~valid]
    return BatchOutcome(
        x=x_out.reshape(shape),
        side=side_out.reshape(shape),
        status=status_out.reshape(shape),
        records=rec_out.reshape(shape + (C.NREC,)),
        model=model,
    )
