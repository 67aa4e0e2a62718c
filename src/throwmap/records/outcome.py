"""Result types of a throw: :class:`Status`, :class:`ThrowOutcome`, :class:`BatchOutcome`."""

from __future__ import annotations

import math

import dataclasses
import enum
from dataclasses import dataclass

import numpy as np

from ..errors import shown
from ..serial import fields_equal
from ..kernels import codes as C

__all__ = ["Status", "ThrowOutcome", "ThrowStart", "ThrowEnd", "ThrowRecord", "ThrowSystem", "BatchOutcome", "FLAT_FIELDS"]


class Status(enum.IntEnum):
    """How a throw ended (integer codes shared with the kernels).

    ``OK``: at rest on a stable side on the arm. ``BEHIND_JOINT``: a contact, or a
    resting support vertex, at x ≤ −arm.back (x ≤ 0 by default). ``OFF_END``: a
    contact beyond the arm's length, or a resting support vertex beyond it (x + u_R > length,
    the rule of :func:`~throwmap.system.starts.start_interval`). ``NO_REST``: the
    impact cap was reached ("paper"; rigid_body refuses that as ``UNRESOLVED``, the contacts chatter), or
    (rigid_body, μ = 0 on an unbounded arm) the part slides outward for ever and never comes to rest.
    ``INVALID_START``: not thrown (batch with ``on_invalid="status"``).
    ``NO_CONTACT``: retired, no model returns it (kept so that the codes stay fixed); a
    contact search that runs out of steps is ``UNRESOLVED`` with ``cap_hit``.
    ``TIMEOUT``: an engine run did not settle within its time limit.
    ``PENETRATION``: an engine lost a contact (a vertex sank deeper than the
    tolerance); the engine's result is refused, not returned.
    ``INCONSISTENT``: rigid-body Coulomb contact has no consistent solution there
    (Painlevé's paradox); the model says so instead of giving a number.
    ``UNRESOLVED``: the model cannot resolve the throw and refuses it rather than give a
    wrong number: the flight leaves the range it resolves (a spin angle at first contact
    beyond double precision, or small_angle2 with g ≤ d ω²), or (paper, rigid_body) a
    contact search or integration used its ``max_iter`` steps
    (:attr:`ThrowOutcome.cap_hit`; raise ``max_iter``). ``UNCONVERGED``: an engine run disagreed with its
    half-step rerun; its result is refused.

    ``str(status)`` and ``f"{status}"`` give the label (``ok``, ``behind_joint``…);
    ``int(status)`` the code.
    """

    OK = C.OK
    BEHIND_JOINT = C.BEHIND_JOINT
    OFF_END = C.OFF_END
    NO_REST = C.NO_REST
    INVALID_START = C.INVALID_START
    NO_CONTACT = C.NO_CONTACT
    TIMEOUT = C.TIMEOUT
    PENETRATION = C.PENETRATION
    INCONSISTENT = C.INCONSISTENT
    UNRESOLVED = C.UNRESOLVED
    UNCONVERGED = C.UNCONVERGED

    @property
    def label(self) -> str:
        return self.name.lower()

    def __str__(self) -> str:
        return self.label

    def __format__(self, spec: str) -> str:
        if spec and spec[-1] in "bcdoxXn":  # an integer format asks for the code
            return int.__format__(int(self), spec)
        return format(self.label, spec)

    @classmethod
    def from_label(cls, label: str) -> "Status":
        """The status called ``label`` (as :attr:`label` writes it)."""
        try:
            return cls[str(label).upper()]
        except KeyError:
            raise ValueError(f"status: unknown status {shown(label)}") from None


_STATUS = tuple(Status(c) for c in range(len(Status)))


def _why(status: int, cap_hit: bool, why: float = math.nan, reason: str = "") -> str:
    """The reason for an UNRESOLVED throw ("" for every other status): the record's reason code
    (:data:`throwmap.kernels.codes.WHY`, e.g. a walled throw rigid_body cannot follow), a search that used its
    ``max_iter`` steps, else ``reason`` (the model's own text) or the spin-angle limit every exact flight has.
    ``INCONSISTENT`` and ``NO_REST`` say what they mean; ``ok`` and the escapes say nothing."""
    if status == C.INCONSISTENT:
        return ("rigid-body Coulomb contact has no consistent solution here (Painlevé's paradox: the contact can "
                "neither stick, slide nor lift): no number is given (use model 'engine')")
    if status == C.NO_REST:
        return ("the part does not come to rest: it slides or rolls outward for ever on an unbounded arm, or "
                "(\"paper\") its impacts reached max_impacts")
    if status != C.UNRESOLVED:
        return ""
    if why == why and why > 0:
        from ..kernels.rigid_body.modes import WHY_MESSAGES

        return WHY_MESSAGES.get(int(why), f"refused by the model (reason code {int(why)})")
    if cap_hit:
        return ("a contact search or integration used all its max_iter steps without an event: "
                "not resolved (raise the model option max_iter)")
    return reason or spin_reason()


def spin_reason() -> str:
    """The generic reason for an UNRESOLVED flight: the spin angle at first contact is beyond what double
    precision resolves (:data:`throwmap.kernels.flight.MAX_SPIN_ANGLE`)."""
    from ..kernels.flight import MAX_SPIN_ANGLE

    return (f"the spin angle ω t at first contact passes {MAX_SPIN_ANGLE:g} rad, beyond what double "
            "precision resolves")


def _why_code(message: str) -> float:
    """The reason code (:data:`throwmap.kernels.codes.WHY`) of a refusal message; 0 for the generic ones."""
    from ..kernels.rigid_body.modes import WHY_MESSAGES

    return float(next((k for k, m in WHY_MESSAGES.items() if m == message), 0))


def _count(v: float) -> int:
    return int(v) if v == v else 0


@dataclass(frozen=True, slots=True)
class ThrowStart:
    """Where a throw started: the rest ``(x, side)`` (m) and the release rate ``omega`` (rad/s)."""

    x: float
    side: int
    omega: float


@dataclass(frozen=True, slots=True)
class ThrowEnd:
    """How a throw ended: ``status``, and the rest ``(x, side)`` it came to (for an escape: the CM's x and the
    side at the moment the part left the arm); ``message``: why the result was refused or what limited it."""

    x: float
    side: int
    status: Status
    message: str = ""


@dataclass(frozen=True, slots=True)
class ThrowRecord:
    """The physics of one throw, as a kernel or an engine recorded it (SI units; see :class:`ThrowOutcome`)."""

    t_flight: float
    contact_vertex: int
    contact_x: float
    v_pre: tuple
    v_post: tuple
    impulse: tuple
    friction_ratio_impact: float
    friction_ratio_max: float
    energy_release: float
    kinetic_pre: float
    kinetic_post: float
    potential_impact: float
    energy_final: float
    max_impact_energy_gain: float
    n_impacts: int
    n_flips: int
    min_normal_force: float
    lift_off: bool
    pull_impulse: bool
    n_lift_offs: int = 0
    n_slips: int = 0
    slip_distance: float = 0.0
    t_rest: float = float("nan")
    penetration_max: float = 0.0
    cap_hit: bool = False


@dataclass(frozen=True, slots=True)
class ThrowSystem:
    """What a throw was made with: the ``model``'s name, the arm's rest angle ``alpha`` (rad) and the
    ``fixtures`` (Wall/Cavity) standing on it."""

    model: str
    alpha: float = 0.0
    fixtures: tuple = ()


_START = tuple(f.name for f in dataclasses.fields(ThrowStart))
_RECORD = tuple(f.name for f in dataclasses.fields(ThrowRecord))
FLAT_FIELDS = ("x", "side", "status", "x0", "side0", "omega", "model") + _RECORD + ("message", "alpha", "fixtures")
"""The fields of an outcome as one flat table (its ``to_dict`` keys, in order, before ``kind``)."""
_WHERE = {**{"x0": ("start", "x"), "side0": ("start", "side"), "omega": ("start", "omega")},
          **{k: ("end", k) for k in ("x", "side", "status", "message")},
          **{k: ("system", k) for k in ("model", "alpha", "fixtures")},
          **{k: ("record", k) for k in _RECORD}}


@dataclass(frozen=True, slots=True)
class ThrowOutcome:
    """One throw, read as four parts: its ``start`` (:class:`ThrowStart`), its ``end`` (:class:`ThrowEnd`), the
    ``record`` of how it went (:class:`ThrowRecord`) and the ``system`` it was made in (:class:`ThrowSystem`).

    Each part's fields read through as the outcome's own (``outcome.x``, ``outcome.x0``, ``outcome.t_flight``,
    ``outcome.model``); :meth:`replace` changes any of them by name. Below, every field by name (SI units).

    ``x``/``side`` are the new resting configuration when ``status`` is OK; for an
    escape they are the CM x and side at the moment the part left the arm.

    Record (first impact unless stated): ``t_flight`` (s); ``contact_vertex``, the
    user's index of the vertex that touched first; ``contact_x`` (m); ``v_pre`` and
    ``v_post``, (ẋ, ẏ, φ̇) of the CM in m/s, m/s, rad/s around the impact (Eq. 4);
    ``impulse`` (N·s); ``friction_ratio_impact`` = |J_x|/J_y that no-slip needs;
    ``friction_ratio_max`` over every impact and pivot swing; energies in J
    (potential from the arm line): ``energy_release``, ``kinetic_pre``,
    ``kinetic_post``, ``potential_impact``, ``energy_final``; ``max_impact_energy_gain``
    (J, ≤ 0 for a physical impact law); ``n_impacts``, ``n_flips`` (landings on a side other than the previous one);
    ``min_normal_force`` while pivoting, in units of m g; validity flags
    ``lift_off`` (the pivot would need a pulling normal force: the part hops) and
    ``pull_impulse`` (an impact's normal impulse would have to pull).
    Models that resolve them also fill ``n_lift_offs`` (contact phases ended by a
    vanishing normal force), ``n_slips`` (sliding impacts and sliding phases),
    ``slip_distance`` (m), ``t_rest`` (s from release to rest; nan where not
    resolved) and ``penetration_max`` (m, engines). ``cap_hit``: the throw is
    ``unresolved`` because a search or integration used its ``max_iter`` steps
    (record ``CAP_HIT``). ``message``: why the result was refused or what limited it
    (``unresolved``, and the engines' ``unconverged``, ``penetration``, ``timeout``…);
    ``""`` when there is nothing to say. ``alpha`` (rad) and ``fixtures`` (Wall/Cavity) are the
    system the throw was made in (the arm's rest angle and what stands on it).
    """

    start: ThrowStart
    end: ThrowEnd
    record: ThrowRecord
    system: ThrowSystem

    def __getattr__(self, name: str):
        where = _WHERE.get(name)
        if where is None:
            raise AttributeError(f"'ThrowOutcome' object has no attribute {name!r}")
        part, field = where
        return getattr(object.__getattribute__(self, part), field)

    def replace(self, **changes) -> "ThrowOutcome":
        """This outcome with fields changed by name (e.g. ``status=``, ``message=``, ``alpha=``, ``fixtures=``)."""
        parts = {}
        for name, value in changes.items():
            where = _WHERE.get(name)
            if where is None:
                raise TypeError(f"ThrowOutcome has no field {name!r}")
            parts.setdefault(where[0], {})[where[1]] = value
        return ThrowOutcome(**{part: dataclasses.replace(getattr(self, part), **kw) if part in parts
                               else getattr(self, part) for part, kw in
                               (("start", parts.get("start")), ("end", parts.get("end")),
                                ("record", parts.get("record")), ("system", parts.get("system")))})

    @classmethod
    def of(cls, **fields) -> "ThrowOutcome":
        """An outcome from its fields by name (as :data:`FLAT_FIELDS`; record fields with defaults may be left out)."""
        return cls(ThrowStart(fields.pop("x0"), fields.pop("side0"), fields.pop("omega")),
                   ThrowEnd(fields.pop("x"), fields.pop("side"), fields.pop("status"), fields.pop("message", "")),
                   ThrowRecord(**{k: fields.pop(k) for k in _RECORD if k in fields}),
                   ThrowSystem(fields.pop("model"), fields.pop("alpha", 0.0), fields.pop("fixtures", ())))

    def __repr__(self) -> str:
        end = (f"(x={self.x:.4g} m, side {self.side}), {self.kind}" if self.ok
               else f"{self.status.label} at x={self.x:.4g} m")
        return (f"ThrowOutcome(model={self.model!r}, omega={self.omega:g} rad/s{_system_text(self)}, "
                f"(x={self.x0:.4g} m, side {self.side0}) → {end}, {self.n_impacts} impacts)")

    @property
    def ok(self) -> bool:
        return self.status == Status.OK

    @property
    def kind(self) -> str:
        """``"jog"`` (lands on the side it rested on without turning over), ``"tumble"`` (on the same side after
        landing on another: over and back), ``"flip"`` (another side) or the escape status."""
        if self.status != Status.OK:
            return self.status.label
        if self.side != self.side0:
            return "flip"
        return "tumble" if self.n_flips > 0 else "jog"

    @property
    def assumptions_hold(self) -> bool:
        """Whether the paper's contact assumptions are self-consistent for this throw."""
        return not (self.lift_off or self.pull_impulse)

    @classmethod
    def from_record(cls, part, x0, side0, omega, model, x, side, status, rec, reason: str = "") -> "ThrowOutcome":
        """Build from a kernel record (per unit mass) — the hot path of :func:`throwmap.throws.throw`.

        ``reason``: the model's own text for an ``unresolved`` throw whose record carries no reason code
        (e.g. the small-angle closed forms'); the spin-angle limit by default."""
        m = part.mass
        r = rec.tolist()
        cv = int(r[C.CONTACT_VERTEX]) if r[C.CONTACT_VERTEX] == r[C.CONTACT_VERTEX] else -1
        n_min = r[C.N_MIN]
        n_imp = r[C.N_IMPACTS]
        n_flip = r[C.N_FLIPS]
        return cls(
            ThrowStart(float(x0), int(side0), float(omega)),
            ThrowEnd(float(x), int(side), _STATUS[int(status)], _why(int(status), r[C.CAP_HIT] == 1.0, r[C.WHY], reason)),
            ThrowRecord(
                r[C.T_FLIGHT],
                part.user_index[cv] if cv >= 0 else -1,
                r[C.CONTACT_X],
                (r[C.VX_PRE], r[C.VY_PRE], r[C.W_PRE]),
                (r[C.VX_POST], r[C.VY_POST], r[C.W_POST]),
                (m * r[C.JX], m * r[C.JY]),
                r[C.MU_IMPACT],
                r[C.MU_MAX],
                m * r[C.E_RELEASE],
                m * r[C.K_PRE],
                m * r[C.K_POST],
                m * r[C.U_IMPACT],
                m * r[C.E_FINAL],
                m * r[C.K_MAX_IMPACT_GAIN],
                int(n_imp) if n_imp == n_imp else 0,
                int(n_flip) if n_flip == n_flip else 0,
                n_min,
                n_min < 0.0 or _count(r[C.N_LIFTOFFS]) > 0,
                r[C.N_PULL] > 0,
                _count(r[C.N_LIFTOFFS]),
                _count(r[C.N_SLIPS]),
                r[C.SLIP_DISTANCE],
                r[C.T_REST],
                r[C.PENETRATION_MAX],
                r[C.CAP_HIT] == 1.0,
            ),
            ThrowSystem(model),
        )

    def to_record(self, part) -> np.ndarray:
        """The kernel record row (per unit mass, :mod:`throwmap.kernels.codes`) this outcome was built from."""
        m = part.mass
        r = np.full(C.NREC, np.nan)
        cv = self.contact_vertex
        r[C.CONTACT_VERTEX] = int(np.flatnonzero(np.asarray(part.user_index) == cv)[0]) if cv >= 0 else -1
        r[C.T_FLIGHT], r[C.CONTACT_X] = self.t_flight, self.contact_x
        r[C.VX_PRE], r[C.VY_PRE], r[C.W_PRE] = self.v_pre
        r[C.VX_POST], r[C.VY_POST], r[C.W_POST] = self.v_post
        r[C.JX], r[C.JY] = self.impulse[0] / m, self.impulse[1] / m
        r[C.MU_IMPACT], r[C.MU_MAX] = self.friction_ratio_impact, self.friction_ratio_max
        r[C.E_RELEASE], r[C.K_PRE], r[C.K_POST] = self.energy_release / m, self.kinetic_pre / m, self.kinetic_post / m
        r[C.U_IMPACT], r[C.E_FINAL] = self.potential_impact / m, self.energy_final / m
        r[C.K_MAX_IMPACT_GAIN] = self.max_impact_energy_gain / m
        r[C.N_IMPACTS], r[C.N_FLIPS], r[C.N_MIN] = self.n_impacts, self.n_flips, self.min_normal_force
        r[C.N_PULL] = 1.0 if self.pull_impulse else 0.0
        r[C.N_LIFTOFFS], r[C.N_SLIPS], r[C.SLIP_DISTANCE] = self.n_lift_offs, self.n_slips, self.slip_distance
        r[C.T_REST], r[C.PENETRATION_MAX] = self.t_rest, self.penetration_max
        r[C.CAP_HIT] = 1.0 if self.cap_hit else 0.0
        r[C.WHY] = _why_code(self.message) if self.status == C.UNRESOLVED else 0.0
        return r

    def to_dict(self) -> dict:
        """JSON-ready dict (SI units; non-finite numbers become ``None``)."""
        from ..serial import json_ready

        from ..system.fixtures import fixture_to_dict

        out = {name: getattr(self, name) for name in FLAT_FIELDS}
        out["status"] = self.status.label
        out["kind"] = self.kind
        out["fixtures"] = [fixture_to_dict(f) for f in self.fixtures]
        return json_ready(out)

    @classmethod
    def from_dict(cls, d: dict) -> "ThrowOutcome":
        """Inverse of :meth:`to_dict` (non-finite numbers, written as ``None``, come back as nan; a field written
        before it existed, e.g. ``cap_hit``, takes its default)."""
        defaults = {f.name: f.default for f in dataclasses.fields(ThrowRecord) if f.default is not dataclasses.MISSING}
        defaults.update(message="", alpha=0.0, fixtures=())
        kw = {}
        for name in FLAT_FIELDS:
            if name not in d and name in defaults:
                continue
            v = d[name]
            if name == "status":
                v = Status.from_label(v)
            elif name == "fixtures":
                from ..system.fixtures import fixture_from_dict

                v = tuple(fixture_from_dict(f) for f in v)
            elif isinstance(v, list):
                v = tuple(float("nan") if e is None else e for e in v)
            elif v is None:
                v = float("nan")
            kw[name] = v
        return cls.of(**kw)

    def table(self) -> str:
        """A few lines for people: the throw, where it ended, and the first impact."""
        om = f"{self.omega:g} rad/s"
        head = f"model {self.model}: (x = {self.x0:.6g} m, side {self.side0}), ω = {om} → "
        head += (f"(x = {self.x:.6g} m, side {self.side}), {self.kind}" if self.ok
                 else f"{self.status.label} at x = {self.x:.6g} m")
        first = (f"  first impact: t = {self.t_flight:.6g} s, vertex {self.contact_vertex}, x = {self.contact_x:.6g} m"
                 if self.contact_vertex >= 0 or self.omega == 0.0 else "  first impact: none resolved")
        if self.alpha or self.fixtures:
            head += f" [{_system_text(self).lstrip(', ')}]"
        lines = [head, first,
                 f"  impacts {self.n_impacts}, flips {self.n_flips}, lift-offs {self.n_lift_offs}, slips {self.n_slips},"
                 f" friction needed {self.friction_ratio_max:.3g}"]
        if self.message:
            lines.append(f"  reason: {self.message}")
        return "\n".join(lines)


@dataclass(frozen=True, slots=True, eq=False)
class BatchOutcome:
    """Results of :func:`throwmap.throw_batch`: arrays in the broadcast shape of the inputs.

    ``x`` (m), ``side`` (int), ``status`` (int codes of :class:`Status`) and
    ``records`` (shape + (NREC,), per-unit-mass record, see :mod:`throwmap.kernels.codes`);
    ``alpha`` (rad) and ``fixtures`` the system the throws were made in.
    """

    x: np.ndarray
    side: np.ndarray
    status: np.ndarray
    records: np.ndarray
    model: str
    alpha: float = 0.0
    fixtures: tuple = ()

    def __eq__(self, other):
        """Equal when every array and field holds the same values (NaN equal to NaN)."""
        return fields_equal(self, other)

    __hash__ = None

    def __repr__(self) -> str:
        counts = ", ".join(f"{k} {v}" for k, v in self.counts().items()) or "none"
        return (f"BatchOutcome(model={self.model!r}{_system_text(self)}, {int(self.status.size)} throws, shape "
                f"{tuple(self.x.shape)}: {counts})")

    @property
    def ok(self) -> np.ndarray:
        return self.status == Status.OK

    def record(self, name: str) -> np.ndarray:
        """A record column by its name in :mod:`throwmap.kernels.codes` (e.g. ``"T_FLIGHT"``)."""
        return self.records[..., getattr(C, name.upper())]

    def counts(self) -> dict:
        """How many throws ended in each status (labels), e.g. ``{"ok": 998, "behind_joint": 2}``."""
        codes, n = np.unique(self.status, return_counts=True)
        return {Status(int(c)).label: int(k) for c, k in zip(codes, n)}

    def table(self) -> str:
        """Throws per status, with the share of each."""
        total = int(self.status.size)
        lines = [f"model {self.model}: {total} throws"]
        for label, k in self.counts().items():
            lines.append(f"  {label:<14}{k:>10d}  {100.0 * k / max(total, 1):6.2f} %")
        return "\n".join(lines)

    def to_dict(self) -> dict:
        """JSON-ready arrays (records as rows of the kernel layout, :mod:`throwmap.kernels.codes`)."""
        from ..serial import json_ready

        from ..system.fixtures import fixture_to_dict

        return json_ready({"model": self.model, "alpha": self.alpha,
                           "fixtures": [fixture_to_dict(f) for f in self.fixtures], "shape": list(self.x.shape),
                           "x": self.x.ravel().tolist(), "side": self.side.ravel().tolist(),
                           "status": self.status.ravel().tolist(), "records": self.records.reshape(-1, C.NREC).tolist()})

    @classmethod
    def from_dict(cls, d: dict) -> "BatchOutcome":
        shape = tuple(d["shape"])
        rec = np.array([[np.nan if v is None else v for v in row] for row in d["records"]], dtype=float)
        if rec.ndim == 2 and rec.shape[1] < C.NREC:  # written before later record columns (e.g. CAP_HIT) existed
            rec = np.hstack([rec, np.full((rec.shape[0], C.NREC - rec.shape[1]), np.nan)])
        return cls(x=np.array([np.nan if v is None else v for v in d["x"]], dtype=float).reshape(shape),
                   side=np.array(d["side"], dtype=np.int64).reshape(shape),
                   status=np.array(d["status"], dtype=np.int64).reshape(shape),
                   records=rec.reshape(shape + (C.NREC,)), model=d["model"], alpha=float(d.get("alpha", 0.0)),
                   fixtures=_fixtures_from(d.get("fixtures", ())))


def _system_text(o) -> str:
    """``", α=5°, fixtures Wall(…)"`` for an outcome made on a tilted arm or with fixtures, else ``""``."""
    parts = []
    if o.alpha:
        parts.append(f"α={math.degrees(o.alpha):.4g}°")
    if o.fixtures:
        parts.append("fixtures " + ", ".join(type(f).__name__ for f in o.fixtures))
    return "".join(", " + p for p in parts)


def _fixtures_from(items) -> tuple:
    from ..system.fixtures import fixture_from_dict

    return tuple(fixture_from_dict(f) for f in items)
