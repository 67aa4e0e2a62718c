"""The throw map T^ω(x, side): one throw or a batch, by model (paper Sec. III-D).

Validates the start once, builds the :class:`~throwmap.system.system.System`
(arm + ``fixtures`` + rest angle ``alpha``) and the model's options from keywords,
and hands flat arrays to the model found in the registry (:mod:`throwmap.models`:
``"rigid_body"`` by default, ``"paper"``, ``"small_angle"``, ``"small_angle2"``,
``"engine"``, ``"mujoco"``). No model is named here.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from ..errors import InvalidStateError
from ..kernels import codes as C
from ..models import DEFAULT_MODEL, build_options, check_model, get_model, model_names
from ..system.arm import Arm, warn_if_outside_regime
from ..system.part import Part
from ..system.starts import check_start, start_interval, tilted_rest_reason, wall_reach, wall_start_reason
from ..system.system import System
from ..records.outcome import BatchOutcome, ThrowOutcome

__all__ = ["MODELS", "DEFAULT_MODEL", "throw", "throw_batch", "check_model", "check_start", "prepare",
           "start_interval", "tilted_rest_reason"]

MODELS = model_names()
"""The registered model names at import (see :func:`throwmap.models.model_names` for later registrations)."""

_FEATURE_OF = {"fixtures": "fixtures", "alpha": "tilt"}


def _only(key: str, able: list, model: str) -> InvalidStateError:
    names = ", ".join(repr(n) for n in able)
    verb = "take" if len(able) > 1 else "takes"
    return InvalidStateError(key, f"only the {names} model{'s' if len(able) > 1 else ''} {verb} {key!r} (model is {model!r})")


@functools.lru_cache(maxsize=256)
def _plain_system(arm: Arm) -> System:
    """The paper's plain arm as a System, made once per arm (values are frozen)."""
    return System(arm)


def _is_plain(fixtures, alpha) -> bool:
    return (fixtures is None or (isinstance(fixtures, tuple) and not fixtures)) and type(alpha) in (int, float) \
        and alpha == 0.0


def prepare(model, arm: Arm, fixtures=(), alpha: float = 0.0, options=None, option_kw=None):
    """The model, the :class:`System` and the options value for a call, validated.

    A System feature the model does not support (fixtures, a tilted arm) is refused
    naming the keyword and the models that take it; so is an option keyword of another
    model, and any unknown keyword.
    """
    m = get_model(model)
    system = _plain_system(arm) if _is_plain(fixtures, alpha) and isinstance(arm, Arm) else System(arm, fixtures, alpha)
    for key, value in (("fixtures", system.fixtures), ("alpha", system.alpha)):
        feature = _FEATURE_OF[key]
        if value and not getattr(m.features, feature):
            raise _only(key, [n for n in model_names() if getattr(get_model(n).features, feature)], m.name)
    if option_kw:
        own = {f.name for f in dataclasses.fields(m.options_type)}
        for key in option_kw:
            if key not in own:
                able = [n for n in model_names() if key in {f.name for f in dataclasses.fields(get_model(n).options_type)}]
                if able:
                    raise _only(key, able, m.name)
    return m, system, build_options(m, options, option_kw)


def _invalid_outcome(part, x0, k, om, model, reason) -> ThrowOutcome:
    """A start that was not thrown: status INVALID_START, the start kept, the record nan, ``message`` the reason."""
    rec = np.full(C.NREC, np.nan)
    out = ThrowOutcome.from_record(part, x0, k, om, model, x0, k, C.INVALID_START, rec)
    return out.replace(message=reason)


def throw(
    part: Part,
    arm: Arm,
    x: float,
    side: int,
    omega: float,
    model: str = DEFAULT_MODEL,
    *,
    fixtures=(),
    alpha: float = 0.0,
    options=None,
    **option_kw,
) -> ThrowOutcome:
    """Throw ``part`` resting at ``(x, side)`` on ``arm`` with release rate ``omega`` (rad/s).

    Returns a :class:`ThrowOutcome` (new ``x``, ``side``, ``status`` and the record).
    Raises :class:`~throwmap.errors.InvalidStateError` for an inadmissible start:
    unknown or unstable side, a left support vertex at x ≤ −arm.back (x ≤ 0 by default), a right
    support vertex beyond ``arm.length``, negative ω (:func:`start_interval` gives the admissible x).
    On a tilted arm (``alpha`` ≠ 0) a start that is not at rest there (it tips, or it slides:
    :func:`tilted_rest_reason`) is not thrown: the outcome has status INVALID_START and
    ``message`` says why.

    ``model`` is a registered model name (default ``"rigid_body"``, see
    :mod:`throwmap.models`). ``fixtures`` and ``alpha`` (rad) describe the
    :class:`~throwmap.system.system.System`; models that do not support them refuse
    them. Further keywords are the model's options (e.g. ``tol``, ``max_impacts`` for
    "paper"; ``settings``, ``realisation``, ``friction`` for "engine"), or pass
    ``options=`` an instance of its options dataclass.
    """
    m, system, opts = prepare(model, arm, fixtures, alpha, options, option_kw)
    x0, k, om = check_start(part, arm, x, side, omega)
    reason = wall_start_reason(part, arm, k, x0, system.fixtures)
    if reason:
        return _in_system(_invalid_outcome(part, x0, k, om, m.name, reason), system)
    if system.alpha != 0.0:
        reason = tilted_rest_reason(part, arm, k, system.alpha, m.features.friction)
        if reason:
            return _in_system(_invalid_outcome(part, x0, k, om, m.name, reason), system)
    warn_if_outside_regime(part, arm)
    own = getattr(m, "outcome", None)
    if own is not None:
        return _in_system(own(part, system, x0, k, om, opts), system)
    xn, kn, st, rec = m.throw_one(part, system, x0, k, om, opts)
    return _in_system(ThrowOutcome.from_record(part, x0, k, om, m.name, xn, kn, st, rec,
                                                 getattr(m, "unresolved_reason", "")), system)


def _in_system(out, system):
    """``out`` stamped with the system's α and fixtures (unchanged on a level, bare arm)."""
    if system.alpha == 0.0 and not system.fixtures:
        return out
    return out.replace(alpha=float(system.alpha), fixtures=tuple(system.fixtures))


_KINDS = {"U": "text", "S": "bytes", "O": "object", "c": "complex", "M": "date", "m": "time-delta", "V": "record"}


def throw_batch(
    part: Part,
    arm: Arm,
    x,
    side,
    omega,
    model: str = DEFAULT_MODEL,
    *,
    on_invalid: str = "raise",
    fixtures=(),
    alpha: float = 0.0,
    options=None,
    progress=None,
    **option_kw,
) -> BatchOutcome:
    """Many independent throws; ``x``, ``side`` and ``omega`` broadcast against each other.

    ``on_invalid="raise"`` refuses the batch at its first inadmissible start (the
    error names the index); ``"status"`` marks such entries ``INVALID_START`` and
    throws the rest. Model, ``fixtures``, ``alpha`` and options as :func:`throw`;
    the analytic models run their compiled kernels in parallel over the entries,
    the engine in ``workers`` processes. ``progress(done, total)``, where a model
    reports progress, is called as throws finish. On a tilted arm a start on a side
    where the part does not rest (:func:`tilted_rest_reason`) is inadmissible: refused
    with that reason (``"raise"``) or marked INVALID_START (``"status"``).
    """
    m, system, opts = prepare(model, arm, fixtures, alpha, options, option_kw)
    return run_batch(m, system, opts, part, x, side, omega, on_invalid=on_invalid, progress=progress)


def run_batch(m, system, opts, part: Part, x, side, omega, *, on_invalid: str = "raise", progress=None) -> BatchOutcome:
    """:func:`throw_batch` on an already validated model ``m``, :class:`System` and options value (see
    :func:`prepare`): checks the starts and throws them (sessions call this once per step)."""
    arm = system.arm
    if on_invalid not in ("raise", "status"):
        raise InvalidStateError("on_invalid", f"must be 'raise' or 'status', got {on_invalid!r}")
    if not isinstance(part, Part):
        raise InvalidStateError("part", f"must be a Part (e.g. throwmap.triangle_30_60_90()), got {type(part).__name__}")
    arrays = []
    for name, value, dtype in (("x", x, float), ("side", side, None), ("omega", omega, float)):
        a = np.asarray(value)
        if a.dtype.kind not in "biuf":
            raise InvalidStateError(name, f"must be numbers, got {_KINDS.get(a.dtype.kind, 'non-numeric')} values")
        arrays.append(a.astype(dtype) if dtype is not None else a)
    try:
        xb, sb, ob = np.broadcast_arrays(*arrays)
    except ValueError:
        raise InvalidStateError("x", f"x, side and omega must broadcast together, got shapes "
                                     f"{', '.join(str(a.shape) for a in arrays)}") from None
    shape = xb.shape
    xf = np.array(xb, dtype=float).ravel()
    of = np.array(ob, dtype=float).ravel()
    sraw = np.asarray(sb).ravel()
    if sraw.size and (sraw.dtype.kind == "b" or not np.issubdtype(sraw.dtype, np.integer)):
        # the rule of :meth:`Part.check_side` (one throw): sides are integers, not 1.0 nor True
        kind = {"b": "boolean", "f": "floating-point", "c": "complex"}.get(sraw.dtype.kind, "non-integer")
        raise InvalidStateError("side", f"must be integer side indices, got {kind} values")
    sf = sraw.astype(np.int64)
    n = part.n_sides
    in_range = (sf >= 0) & (sf < n)
    stable = np.zeros(sf.shape, dtype=bool)
    stable[in_range] = part.stable[sf[in_range]]
    uL = np.where(in_range, part.uL[np.clip(sf, 0, n - 1)], np.nan)
    uR = np.where(in_range, part.uR[np.clip(sf, 0, n - 1)], np.nan)
    L = arm.length_or_inf
    valid = stable & np.isfinite(xf) & np.isfinite(of) & (of >= 0) & (xf + uL > -arm.back) & (xf + uR <= L)
    from ..system.fixtures import Wall

    for f in system.fixtures:  # starts that overlap a wall (wall_start_reason)
        if isinstance(f, Wall) and arm.length is not None:
            for k in part.stable_sides:
                valid &= ~((sf == int(k)) & (xf + wall_reach(part, int(k), f.height) > arm.length + 1e-9))
    tilt_reason = {}
    if system.alpha != 0.0:
        for k in part.stable_sides:
            r = tilted_rest_reason(part, arm, int(k), system.alpha, m.features.friction)
            if r:
                tilt_reason[int(k)] = r
                valid &= sf != k
    if on_invalid == "raise" and not np.all(valid):
        i = int(np.flatnonzero(~valid)[0])
        idx = np.unravel_index(i, shape) if shape else ()
        if in_range[i] and stable[i] and np.isfinite(xf[i]) and np.isfinite(of[i]) and of[i] >= 0 \
                and xf[i] + uL[i] > -arm.back and xf[i] + uR[i] <= L:  # an admissible start but for the wall
            r = wall_start_reason(part, arm, int(sf[i]), float(xf[i]), system.fixtures)
            if r:
                raise InvalidStateError(f"x[{', '.join(map(str, idx))}]", r)
        if in_range[i] and int(sf[i]) in tilt_reason and stable[i]:
            try:
                check_start(part, arm, xf[i], int(sf[i]), of[i])
            except InvalidStateError as err:
                raise InvalidStateError(f"{err.field}[{', '.join(map(str, idx))}]", err.reason) from None
            raise InvalidStateError(f"side[{', '.join(map(str, idx))}]",
                                    f"not at rest on the tilted arm: {tilt_reason[int(sf[i])]}")
        try:
            check_start(part, arm, xf[i], int(sf[i]) if in_range[i] else int(sf[i]), of[i])
        except InvalidStateError as err:
            raise InvalidStateError(f"{err.field}[{', '.join(map(str, idx))}]", err.reason) from None
        raise InvalidStateError(f"x[{i}]", "inadmissible start")  # pragma: no cover - defensive
    if np.any(valid):
        warn_if_outside_regime(part, arm)
    sf_safe = np.where(in_range, sf, 0)
    res = m.throw_batch(part, system, xf, sf_safe, of, valid, opts, progress)
    side_out = np.asarray(res.side, dtype=np.int64).copy()
    side_out[~valid] = sf[~valid]
    return BatchOutcome(
        x=np.asarray(res.x, dtype=float).reshape(shape),
        side=side_out.reshape(shape),
        status=np.asarray(res.status, dtype=np.int64).reshape(shape),
        records=np.asarray(res.records, dtype=float).reshape(shape + (C.NREC,)),
        model=m.name,
        alpha=float(system.alpha),
        fixtures=tuple(system.fixtures),
    )
