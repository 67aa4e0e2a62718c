"""Throwing sessions: a scene thrown again and again, validated once (STYLE §14).

:func:`open_session` looks the model up, builds the :class:`~throwmap.system.system.System` and
the model's options, and checks the start — once. The session it returns then only throws
(:class:`~throwmap.models.base.ThrowSession`): :func:`~throwmap.throws.orbit.iterate`, closed-loop
control, the experiments, the cavity checks and the chain builders all drive one, and none of
them branches on which model is underneath; they ask its ``features``.

* A model whose state between throws is a whole pose (the engine: ``Features.pose``) provides its
  own session (``model.session``).
* Every other model gets :class:`MapSession`: one part, its state the rest ``(x, side)`` of the
  throw map T^ω (paper Sec. III-D), each throw one call of the model's ``throw_one``.
* :class:`MapEnsemble`: many independent one-part scenes of such a model thrown together, each
  step one batch call (``throw_batch``), for estimates over many starts (the stochastic chains).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..errors import InvalidStateError, shown
from ..kernels import codes as C
from ..models import DEFAULT_MODEL, get_model, model_names
from ..records.outcome import BatchOutcome, Status, ThrowOutcome
from ..records.session import PartState, SessionStep
from ..system.arm import Arm, warn_if_outside_regime
from ..system.part import Part
from ..system.starts import check_omega, check_start, tilted_rest_reason, wall_start_reason
from .throw import _in_system, _invalid_outcome, prepare, run_batch

__all__ = ["open_session", "open_ensemble", "MapSession", "MapEnsemble", "RESTART_REASON"]

RESTART_REASON = "the last throw's rest is not a start of the map ({}): the part leans, e.g. on a wall"
"""Why a rest left by a throw cannot start the next one (a part at rest leaning on a wall reports its CM's x
and the nearest side, which may lie past the last flat start)."""


def _parts(parts) -> tuple:
    if isinstance(parts, Part):
        return (parts,)
    try:
        out = tuple(parts)
    except TypeError:
        raise InvalidStateError("part", f"must be a Part or a sequence of Parts, got {type(parts).__name__}") from None
    if not out:
        raise InvalidStateError("part", "at least one part is needed")
    for i, p in enumerate(out):
        if not isinstance(p, Part):
            raise InvalidStateError(f"part[{i}]", f"must be a Part (e.g. throwmap.triangle_30_60_90()), got "
                                                  f"{type(p).__name__}")
    return out


def _rests(start, n: int) -> tuple:
    """``start`` as n rests ``(x, side)``: one pair for one part, a sequence of pairs for several."""
    try:
        if n == 1:
            x, k = start
            return ((x, k),)
        pairs = tuple(start)
        if len(pairs) != n:
            raise ValueError
        return tuple((x, k) for x, k in pairs)
    except (TypeError, ValueError):
        what = "a pair (x, side)" if n == 1 else f"{n} pairs (x, side), one per part"
        raise InvalidStateError("state", f"must be {what}, got {shown(start)}") from None


def open_session(part, arm: Arm, state, model: str = DEFAULT_MODEL, *, fixtures=(), alpha: float = 0.0,
                 options=None, **option_kw):
    """A :class:`~throwmap.models.base.ThrowSession` of ``part`` (a Part, or a sequence of them where the model
    holds several: ``features.parts``) on ``arm``, starting from ``state``.

    ``state``: the rest ``(x, side)`` (m; one pair per part for several parts), or — for a model that keeps
    poses (``features.pose``, the engine) — an engine :class:`~throwmap.engine.Scene` holding these parts on this
    arm (or an object with a ``scene``, e.g. a :class:`~throwmap.experiments.drop.DropResult`, or an
    :class:`~throwmap.engine.EngineRun`, from whose end it goes on), whose fixtures and α it brings. ``model``, ``fixtures``, ``alpha`` (rad), ``options`` and further keywords (the model's
    options) as :func:`throwmap.throw`; all are validated here, once. Raises
    :class:`~throwmap.errors.InvalidStateError` naming the field for an inadmissible start.
    """
    parts = _parts(part)
    if hasattr(state, "next_scene"):  # an engine run: the session goes on from where it ended
        state = state.next_scene()
    scene = getattr(state, "scene", state)
    if hasattr(scene, "placements"):  # an engine Scene: fixtures and alpha come with it
        m = get_model(model)
        if not m.features.pose:
            able = [n for n in model_names() if get_model(n).features.pose]
            raise InvalidStateError("state", f"an engine Scene is a start for model{'s' if len(able) > 1 else ''} "
                                             f"{', '.join(repr(n) for n in able)} only (those that keep poses; model "
                                             f"is {m.name!r}): start from a rest (x, side)")
        if fixtures not in ((), None) or alpha != 0.0:
            raise InvalidStateError("fixtures", "a start Scene brings its own fixtures and alpha: do not pass them")
        fixtures, alpha = scene.fixtures, scene.alpha
        if option_kw.get("friction") is None and "friction" in option_kw:
            option_kw.pop("friction")
    m, system, opts = prepare(model, arm, fixtures, alpha, options, option_kw)
    most = m.features.parts
    if most and len(parts) > most:
        many = "one part" if most == 1 else f"{most} parts"
        raise InvalidStateError("part", f"model {m.name!r} throws {many} at a time, got {len(parts)} (models taking "
                                        f"several: those with features.parts = 0)")
    if hasattr(scene, "placements"):
        if scene.parts != parts or scene.arm != arm:
            n = len(parts)
            raise InvalidStateError("state", f"the engine Scene must hold {'this one part' if n == 1 else 'these parts'} "
                                             f"on this arm")
        return m.session(parts, system, scene, opts)
    rests = tuple(check_start(p, arm, x, k, 0.0)[:2] for p, (x, k) in zip(parts, _rests(state, len(parts))))
    for p in parts:  # the paper's guarantees (jogs outward, flips inward) a start from rest relies on
        warn_if_outside_regime(p, arm)
    factory = getattr(m, "session", None)
    if factory is not None:
        return factory(parts, system, rests, opts)
    (x, k), = rests
    return MapSession(m, parts[0], system, opts, x, k)


class MapSession:
    """One part thrown again and again by a model of the throw map: the state is the rest ``(x, side)``.

    Made by :func:`open_session` (model, System, options and start validated there). Each throw starts
    from the rest the last one ended at: the start rules that depend on the rest are checked per throw
    (a rest that leans into a wall, or past the last flat start: ``invalid_start``, and the session ends);
    everything else was checked once.
    """

    def __init__(self, model, part: Part, system, options, x: float, side: int):
        self.model = model
        self.part = part
        self.parts = (part,)
        self.system = system
        self.options = options
        self.features = model.features
        self.status = Status.OK
        self.n_throws = 0
        self._x, self._side = float(x), int(side)
        self._own = getattr(model, "outcome", None)
        self._reason = getattr(model, "unresolved_reason", "")

    @property
    def states(self) -> tuple:
        return (PartState(self._x, self._side),)

    @property
    def ended(self) -> bool:
        return self.status != Status.OK

    def _options(self, motion, options):
        opts = self.options if options is None else options
        if options is not None and not isinstance(options, self.model.options_type):
            raise InvalidStateError("options", f"model {self.model.name!r} takes {self.model.options_type.__name__}, "
                                               f"got {type(options).__name__}")
        if motion is not None:
            if not self.features.realisation:
                raise InvalidStateError("motion", f"model {self.model.name!r} throws the paper's impulse only: it "
                                                  f"follows no arm motion (features.realisation)")
            opts = dataclasses.replace(opts, realisation=motion)
        return opts

    def rest_reason(self, omega: float = 0.0) -> str:
        """Why the current rest cannot start a throw (``""`` if it can): past the flat starts (after a throw
        that left the part leaning), into a wall, or not at rest on the tilted arm."""
        part, arm, system = self.part, self.system.arm, self.system
        x, k = self._x, self._side
        if self.n_throws:
            try:
                check_start(part, arm, x, k, omega)
            except InvalidStateError as err:
                return RESTART_REASON.format(err.reason)
        reason = wall_start_reason(part, arm, k, x, system.fixtures) if system.fixtures else ""
        if not reason and system.alpha != 0.0:
            reason = tilted_rest_reason(part, arm, k, system.alpha, self.features.friction)
        return reason

    def throw(self, omega: float, motion=None, *, options=None, record: bool = False) -> SessionStep:
        """One throw from the current rest (see :class:`~throwmap.models.base.ThrowSession`)."""
        if self.ended:
            raise InvalidStateError("session", f"the scene has ended ({self.status.label}): it takes no more throws")
        w = check_omega(omega)
        opts = self._options(motion, options)
        m, part, system = self.model, self.part, self.system
        x, k = self._x, self._side
        traj = None
        reason = self.rest_reason(w)
        if reason:
            out = _in_system(_invalid_outcome(part, x, k, w, m.name, reason), system)
        elif record and self.features.trajectory:
            from ..records.trajectory import DEFAULT_DT, check_dt

            dt = DEFAULT_DT if record is True else check_dt(record)
            out, traj = m.trajectory(part, system, x, k, w, opts, dt)
            out = _in_system(out, system)
        elif self._own is not None:
            out = _in_system(self._own(part, system, x, k, w, opts), system)
        else:
            xn, kn, st, rec = m.throw_one(part, system, x, k, w, opts)
            out = _in_system(ThrowOutcome.from_record(part, x, k, w, m.name, xn, kn, st, rec, self._reason), system)
        self.n_throws += 1
        if out.status == Status.OK:
            self._x, self._side = float(out.x), int(out.side)
        else:
            self.status = out.status
        return SessionStep("throw", w, motion, out.status, (out,), (PartState(float(out.x), int(out.side)),),
                           float(system.alpha), out.message, None, traj)

    def move(self, motion, *, options=None, record: bool = False) -> SessionStep:
        raise InvalidStateError("motion", f"model {self.model.name!r} keeps rests, not poses: the arm cannot move "
                                          f"between its throws (features.moves)")

    def __repr__(self) -> str:
        return (f"MapSession(model={self.model.name!r}, (x={self._x:.4g} m, side {self._side}), "
                f"{self.n_throws} throws, {self.status.label})")


def open_ensemble(part: Part, arm: Arm, x, side, model: str = DEFAULT_MODEL, *, fixtures=(), alpha: float = 0.0,
                  options=None, **option_kw) -> "MapEnsemble":
    """A :class:`MapEnsemble` of independent scenes of ``part`` on ``arm`` starting at the rests ``(x, side)``
    (arrays that broadcast; m), for a model that throws ensembles (``features.ensemble``). Model, fixtures,
    α, options as :func:`open_session`; validated once."""
    m, system, opts = prepare(model, arm, fixtures, alpha, options, option_kw)
    if not m.features.ensemble:
        raise InvalidStateError("model", f"model {m.name!r} does not throw ensembles (features.ensemble): "
                                         f"open one session per scene")
    if not isinstance(part, Part):
        raise InvalidStateError("part", f"must be a Part (e.g. throwmap.triangle_30_60_90()), got {type(part).__name__}")
    xb, sb = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(side))
    return MapEnsemble(m, part, system, opts, xb.ravel().copy(), sb.ravel().astype(np.int64))


class MapEnsemble:
    """Independent one-part scenes of a throw-map model thrown together, one batch call a step.

    ``x`` (m) and ``side``: each scene's rest; ``alive``: the scenes still at rest on the arm (a scene whose
    throw did not end at rest keeps where it ended and is not thrown again); ``status``: each scene's last
    status code (:class:`~throwmap.records.outcome.Status`).
    """

    def __init__(self, model, part: Part, system, options, x: np.ndarray, side: np.ndarray):
        self.model, self.part, self.system, self.options = model, part, system, options
        self.features = model.features
        self.x, self.side = x, side
        self.status = np.full(x.shape, int(Status.OK), dtype=np.int64)
        self.n_throws = 0

    @property
    def alive(self) -> np.ndarray:
        return self.status == Status.OK

    def throw(self, omega, motion=None, *, options=None) -> BatchOutcome:
        """One throw of every live scene at ``omega`` (rad/s, one value or one per scene); ``motion``: one arm
        motion for all, or a callable ``omega -> motion`` (one per throw), where the model follows one. Starts
        that are not admissible rests get ``invalid_start`` (and end). Returns the step's
        :class:`~throwmap.records.outcome.BatchOutcome` over all scenes (ended ones carry their last result)."""
        w = np.broadcast_to(np.asarray(omega, dtype=float), self.x.shape)
        opts = self.options if options is None else options
        if motion is not None:
            if not self.features.realisation:
                raise InvalidStateError("motion", f"model {self.model.name!r} throws the paper's impulse only: it "
                                                  f"follows no arm motion (features.realisation)")
            opts = dataclasses.replace(opts, realisation=motion)
        live = self.alive
        x_out, s_out = self.x.copy(), self.side.copy()
        st_out = self.status.copy()
        rec = np.full(self.x.shape + (C.NREC,), np.nan)
        if np.any(live):
            b = run_batch(self.model, self.system, opts, self.part, self.x[live], self.side[live], w[live],
                          on_invalid="status")
            x_out[live], s_out[live], st_out[live], rec[live] = b.x, b.side, b.status, b.records
        self.n_throws += 1
        ok = st_out == Status.OK
        self.x = np.where(ok, x_out, self.x)
        self.side = np.where(ok, s_out, self.side)
        self.status = st_out
        return BatchOutcome(x=x_out, side=s_out, status=st_out, records=rec, model=self.model.name,
                            alpha=float(self.system.alpha), fixtures=tuple(self.system.fixtures))

    def __repr__(self) -> str:
        return (f"MapEnsemble(model={self.model.name!r}, {self.x.size} scenes, {int(self.alive.sum())} at rest, "
                f"{self.n_throws} throws)")
