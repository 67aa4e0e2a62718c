"""The pieces of a system as a file declares them — arm, wall, noise — and the field types with their rules.

Every config that names an arm, a wall, the arm's rest angle α or noise — the part files
(``[arm]``), every experiment, the sweeps' targets — declares them with these models (the whole
system: :class:`throwmap.io.spec.SystemSpec`). Each rule is the library's own,
stated once and applied here as a validator: μ (:func:`throwmap.system.arm.check_mu`), arm length
(:func:`~throwmap.system.arm.check_length`), α (:func:`throwmap.system.system.check_alpha`), ω
(:func:`throwmap.system.starts.check_omega`).

Spellings (SI units, rad):

* **μ = ∞** (a contact that never slips) is ``inf`` — TOML's infinity, or the text ``"inf"`` in JSON, which has
  none; ``null``, as JSON results write every non-finite number, reads as ∞ too.
* **An unbounded arm**: ``length`` left out, ``inf`` or ``"inf"`` (``null`` too).
* Numbers are numbers: booleans and strings are refused (no silent coercion).

An ``[arm]`` or ``[wall]`` table in a file overrides only the keys it names: ``[arm]`` with ``mu = 0.5`` keeps
the config's own ``h`` and ``length`` (:class:`Spec` merges them over the config's defaults; other tables, such as
``[noise]``, replace the default whole, their missing keys at the table's own defaults).
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import AfterValidator, BaseModel, BeforeValidator, ConfigDict, Field, PlainSerializer, model_validator

from ..conventions import G
from ..errors import InvalidArmError, ThrowmapError
from ..system.arm import Arm, check_back, check_g, check_length, check_mu
from ..system.fixtures import Wall
from ..system.noise import Noise
from ..system.starts import check_omega
from ..system.system import check_alpha

__all__ = ["Number", "Omega", "Rate", "Friction", "Length", "Angle", "Point", "Spec", "ArmSpec", "WallSpec",
           "NoiseSpec", "INF_WORDS"]

INF_WORDS = ("inf", "+inf", "infinity")
"""The texts read as infinity (μ = ∞, an unbounded arm)."""


def _rule(check):
    """An after-validator applying one of the library's rules; its reason becomes the field's error."""

    def validate(value):
        try:
            return check(value)
        except ThrowmapError as err:
            raise ValueError(err.reason) from None

    return AfterValidator(validate)


def _infinite_text(value):
    """``null`` and the texts of :data:`INF_WORDS` as ∞."""
    if value is None:
        return math.inf
    if isinstance(value, str) and value.strip().lower() in INF_WORDS:
        return math.inf
    return value


def _unbounded_text(value):
    """``inf`` (or a text of :data:`INF_WORDS`) and ``null`` as None: an unbounded arm."""
    value = _infinite_text(value)
    return None if isinstance(value, float) and math.isinf(value) and value > 0 else value


Number = Annotated[float, Field(strict=True, allow_inf_nan=False)]
"""A finite number (an integer or a float; booleans and strings refused)."""
Omega = Annotated[float, Field(strict=True), _rule(check_omega)]
"""A release rate ω, rad/s: finite and ≥ 0 (the arm throws upward)."""
MAX_RATE = 100.0
"""The largest release rate an experiment config takes, rad/s (a 0.5 m arm's end at 50 m/s): far above any
throw that rests a part on the arm; a larger one is a unit slip (deg/s, rpm)."""
Rate = Annotated[Omega, Field(gt=0, le=MAX_RATE)]
"""A nominal release rate of an experiment, rad/s: an :data:`Omega` > 0 and ≤ :data:`MAX_RATE`."""
Friction = Annotated[float, BeforeValidator(_infinite_text), Field(strict=True), _rule(check_mu),
                     PlainSerializer(lambda v: "inf" if math.isinf(v) else v, return_type=float | str, when_used="json")]
"""Coulomb friction μ ≥ 0; ``inf`` (or ``"inf"``, ``null``): the contact never slips. Written ``"inf"`` in JSON."""
Length = Annotated[Annotated[float, Field(strict=True)] | None, BeforeValidator(_unbounded_text), _rule(check_length)]
"""An arm length, m: positive and finite, or unbounded (left out, ``inf``, ``"inf"``, ``null``)."""
Angle = Annotated[float, Field(strict=True), _rule(check_alpha)]
"""The arm's rest angle α, rad (counter-clockwise +): finite, |α| < π/2."""
Point = tuple[Number, Number]
"""A point or a pair (low, high) of finite numbers."""


def _ordered(pair):
    lo, hi = pair
    if lo > hi:
        raise ValueError(f"must be (low, high) with low ≤ high, got ({lo:g}, {hi:g})")
    return pair


Range = Annotated[Point, AfterValidator(_ordered)]
"""A range (low, high) of finite numbers, low ≤ high."""
RateRange = Annotated[tuple[Rate, Rate], AfterValidator(_ordered)]
"""A range (low, high) of release rates (:data:`Rate`, rad/s), low ≤ high."""
Heights = Annotated[tuple[Annotated[Number, Field(ge=0)], Annotated[Number, Field(ge=0)]], AfterValidator(_ordered)]
"""A range (low, high) of drop heights above the arm, m: both ≥ 0, low ≤ high."""


_NESTED = ("arm", "wall")


class Spec(BaseModel):
    """Base of every schema here and of the configs that embed them: unknown keys refused, values frozen, and an
    ``[arm]`` or ``[wall]`` table in a file overriding only the keys it names over the config's own default."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    @model_validator(mode="before")
    @classmethod
    def _merge_tables(cls, data):
        if not isinstance(data, dict):
            return data
        out = data
        for name in _NESTED:
            given = data.get(name)
            field = cls.model_fields.get(name)
            if not isinstance(given, dict) or field is None:
                continue
            default = field.get_default(call_default_factory=True)
            if isinstance(default, BaseModel):
                out = {**out, name: {**default.model_dump(), **given}}
        return out


class ArmSpec(Spec):
    """The arm (``[arm]``; :class:`throwmap.Arm`): ``h`` (m; None where the config's design or defaults give it),
    ``g`` (m/s²), ``length`` (m; unbounded by default), ``mu`` (∞ by default: no slip), ``back`` (m)."""

    h: Number | None = None
    g: Annotated[float, Field(strict=True), _rule(check_g)] = G
    length: Length = None
    mu: Friction = math.inf
    back: Annotated[float, Field(strict=True), _rule(check_back)] = 0.0

    def arm(self, *, field: str = "arm.h", **defaults) -> Arm:
        """The :class:`~throwmap.Arm`: fields given here over ``defaults`` (e.g. a design's ``h``); ``h`` must come
        from one of them (else :class:`~throwmap.errors.InvalidArmError` on ``field``)."""
        given = {k: getattr(self, k) for k in ("h", "g", "length", "mu", "back")}
        if given["h"] is None:
            given.pop("h")
        kw = {**defaults, **given}
        if kw.get("h") is None:
            raise InvalidArmError(field, "required: the arm's surface height h (m)")
        return Arm(**kw)

    @classmethod
    def of(cls, arm: Arm) -> "ArmSpec":
        """The spec of an :class:`~throwmap.Arm`."""
        return cls(h=arm.h, g=arm.g, length=arm.length, mu=arm.mu, back=arm.back)


class WallSpec(Spec):
    """A wall at the arm's end (``[wall]``; :class:`throwmap.Wall`): ``height`` above the arm surface (m) and its
    ``mu`` (None: the arm's)."""

    height: Annotated[Number, Field(gt=0)]
    mu: Friction | None = None

    def wall(self) -> Wall:
        return Wall(height=self.height, mu=self.mu)


class NoiseSpec(Spec):
    """:class:`~throwmap.system.noise.Noise` (``[noise]``): ω jitter per throw, the arm's μ per trial, the arm's
    motion (SI units, rad)."""

    omega_rel: float = Field(0.0, ge=0, allow_inf_nan=False, description="relative σ of each throw's ω")
    mu_rel: float = Field(0.0, ge=0, allow_inf_nan=False, description="relative σ of the trial's arm μ")
    mu_range: tuple[float, float] | None = Field(None, description="uniform arm μ per trial (overrides mu_rel)")
    realisation: Literal["impulse", "recoil"] = "impulse"
    recoil: float = Field(math.radians(3.0), gt=0, allow_inf_nan=False, description="recoil depth, rad")
    zeta: float = Field(0.5, gt=0, lt=1, description="recoil loop damping ratio")

    @model_validator(mode="after")
    def _noise_rules(self):
        try:
            self.noise()
        except ThrowmapError as err:
            raise ValueError(f"{err.field}: {err.reason}") from None
        return self

    def noise(self) -> Noise:
        return Noise(self.omega_rel, self.mu_rel, self.mu_range, self.realisation, self.recoil, self.zeta)


def _number_kind(annotation):
    """``"number"`` when a field holds a plain number (float or int, maybe optional or annotated) with no
    reading of texts of its own (a before-validator such as :data:`Friction`'s); a pydantic model class when
    it holds a table; else None."""
    import typing

    args = typing.get_args(annotation)
    origin = typing.get_origin(annotation)
    if origin is Annotated:
        if any(isinstance(m, BeforeValidator) for m in annotation.__metadata__):
            return None
        return _number_kind(args[0])
    if isinstance(annotation, type):
        if issubclass(annotation, BaseModel):
            return annotation
        if annotation in (float, int):
            return "number"
        return None
    if args and origin is not Literal:  # X | None, Optional[X]: a number only if every member is one (or None)
        kinds = [_number_kind(a) for a in args if a is not type(None)]
        if kinds and all(k == "number" for k in kinds):
            return "number"
        models = [k for k in kinds if isinstance(k, type)]
        return models[0] if len(models) == 1 and len(kinds) == 1 else None
    return None


def coerced_number(model, data, prefix: str = "config"):
    """The first ``(field, value)`` of ``data`` (a config's table for pydantic ``model``) where a number goes and
    a boolean or a text stands — pydantic's lax mode would turn ``true`` into 1 and ``"4.5"`` into 4.5 — with the
    field dotted from ``prefix``; None when there is none. Fields that read texts themselves (μ, length: ``"inf"``)
    are left to their validators."""
    if not isinstance(data, dict) or not (isinstance(model, type) and issubclass(model, BaseModel)):
        return None
    fields = model.model_fields
    for key, value in data.items():
        info = fields.get(key) if isinstance(key, str) else None
        if info is None:
            continue
        annotation = info.annotation
        if info.metadata and not any(isinstance(m, BeforeValidator) for m in info.metadata):
            annotation = Annotated[(annotation, *info.metadata)]
        elif info.metadata:
            continue
        kind = _number_kind(annotation)
        if kind == "number" and isinstance(value, (bool, str)):
            return f"{prefix}.{key}", value
        if isinstance(kind, type):
            found = coerced_number(kind, value, f"{prefix}.{key}")
            if found:
                return found
    return None


def refuse_coerced_numbers(model, data, prefix: str = "config") -> None:
    """Raise :class:`~throwmap.errors.ConfigError` naming the first field of :func:`coerced_number`."""
    found = coerced_number(model, data, prefix)
    if found:
        from ..errors import ConfigError

        field, value = found
        raise ConfigError(field, f"must be a number, got {value!r}")
