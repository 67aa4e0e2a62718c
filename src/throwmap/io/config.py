"""Part and arm files: TOML (or JSON, by extension), validated with pydantic.

Schema (SI units, see :mod:`throwmap.conventions`)::

    [part]
    name = "my part"              # optional (default: the file's stem, plus its lead weights)
    vertices = [[x, y], ...]      # m, a convex polygon in either orientation
    mass = 0.05                   # kg, mass of the uniform plate
    com = [x, y]                  # m, optional (default: computed; written only when overridden)
    radius_of_gyration = 0.04     # m, optional (default: computed; written only when overridden)

    [[part.point_masses]]         # optional, repeatable: lead weights
    mass = 0.01                   # kg
    at = [x, y]                   # m, inside or on the polygon

    [arm]                         # optional section
    h = -0.01                     # m, surface height (below the joint: h < 0)
    g = 9.81                      # m/s², optional
    length = 0.5                  # m, optional (default: unbounded)
    mu = 0.8                      # arm–part friction, optional (default: inf = no slip;
                                  # in JSON, where there is no inf: null or "inf")
    back = 0.0                    # m, surface behind the joint, optional (default 0)

The JSON form is the same document as an object: ``{"part": {...}, "arm": {...}}``.

Every failure raises :class:`~throwmap.errors.ConfigError` whose ``field`` is the
dotted path of the culprit (``part.vertices[2][0]``, ``part.point_masses[0].mass``,
``arm.h``) or ``"file"`` when the file cannot be read or parsed (the reason then
names the path and the parser's line/column). Unknown keys (a typo such as
``mas = 0.05`` is named, with the nearest allowed key), non-numbers, NaN and
infinities (except ``mu = inf``) are refused here; the geometric and physical rules (convexity, CM
inside, positive masses, g > 0…) are those of :class:`~throwmap.Part` and
:class:`~throwmap.Arm`, whose :class:`~throwmap.errors.InvalidPartError` /
:class:`~throwmap.errors.InvalidArmError` propagate unchanged (their fields
already read ``part.…`` / ``arm.…``).
"""

from __future__ import annotations

import dataclasses
import difflib
import json
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from ..system.arm import Arm
from ..errors import ConfigError, InvalidPartError
from .files import atomic_write_text
from .schema import ArmSpec
from ..system.part import Part
from ..system.catalogue import BUILTIN_PARTS, builtin_part, lead_name

__all__ = [
    "LoadedConfig",
    "load_config",
    "part_from_spec",
    "arm_from_spec",
    "resolve_part",
    "part_to_toml",
    "part_document",
    "arm_document",
    "overrides",
    "save_part",
    "save_part_toml",
]

SUFFIXES = (".toml", ".json")
"""File types :func:`load_config` reads, by extension (case-insensitive)."""

# ---------------------------------------------------------------------- schema
FiniteFloat = Annotated[float, Field(strict=True, allow_inf_nan=False)]
"""A finite number (int or float in the file; booleans and strings refused)."""
Point = tuple[FiniteFloat, FiniteFloat]


class _Spec(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class PointMassSpec(_Spec):
    """One lead weight: ``mass`` (kg) at ``at`` (m, body frame)."""

    mass: FiniteFloat
    at: Point


class PartSpec(_Spec):
    """The ``[part]`` table; see :meth:`throwmap.Part.from_vertices` for the meaning."""

    name: Annotated[str, Field(strict=True)] | None = None
    vertices: list[Point]
    mass: FiniteFloat
    com: Point | None = None
    radius_of_gyration: FiniteFloat | None = None
    point_masses: list[PointMassSpec] = []


class FileArmSpec(ArmSpec):
    """The ``[arm]`` table of a part file (:class:`throwmap.io.spec.ArmSpec`, the one schema of an arm), where
    ``h`` is required."""

    h: FiniteFloat


class FileSpec(_Spec):
    """A whole part/arm file."""

    part: PartSpec
    arm: FileArmSpec | None = None


_KEYS_BY_TABLE = {
    "": FileSpec,
    "part": PartSpec,
    "point_masses": PointMassSpec,
    "arm": FileArmSpec,
}


# ----------------------------------------------------------------- error mapping
def _dotted(prefix: str, loc: tuple) -> str:
    out = prefix
    for item in loc:
        if isinstance(item, int):
            out += f"[{item}]"
        else:
            out = f"{out}.{item}" if out else str(item)
    return out


def _short_repr(value: Any, limit: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _config_error(err: ValidationError, prefix: str, source: Path | None = None) -> ConfigError:
    """The first pydantic error as one ``ConfigError(dotted.field, reason)``."""
    errors = err.errors(include_url=False)
    # an unknown key first: a typo (``mas``) also makes the key it meant (``mass``) missing
    errors.sort(key=lambda e: e["type"] != "extra_forbidden")
    first = errors[0]
    loc = tuple(first["loc"])
    field = _dotted(prefix, loc) or "file"
    kind = first["type"]
    value = first.get("input")
    if kind == "missing" and loc and isinstance(loc[-1], int):  # a tuple field given too few entries
        field = _dotted(prefix, loc[:-1]) or "file"
        reason = f"has too few entries (entry {loc[-1]} is missing; a pair such as [low, high] is expected)"
    elif kind == "missing":
        reason = "required key is missing"
    elif kind == "extra_forbidden":
        parent = prefix.split(".")[-1] if prefix else ""
        for item in loc[:-1]:
            if isinstance(item, str):
                parent = item
        model = _KEYS_BY_TABLE.get(parent)
        allowed = ""
        if model is not None:
            close = difflib.get_close_matches(str(loc[-1]), list(model.model_fields), n=1) if loc else []
            hint = f"did you mean {close[0]!r}? " if close else ""
            allowed = f" ({hint}allowed: {', '.join(model.model_fields)})"
        reason = f"unknown key {str(loc[-1]) if loc else ''!r}{allowed}"
    elif kind == "finite_number":
        reason = f"must be a finite number, got {_short_repr(value)}"
    elif kind in ("float_type", "float_parsing"):
        reason = f"must be a number, got {_short_repr(value)}"
    elif kind == "value_error":  # one of the library's rules (io.spec): its reason names the value
        reason = first["msg"].removeprefix("Value error, ")
    elif kind in ("model_type", "dict_type") or (not loc and isinstance(value, (list, str, int, float))):
        reason = f"must be a table of keys, got {_short_repr(value)}"
    else:
        msg = first["msg"]
        if msg.startswith("Input should be"):
            msg = "must be" + msg[len("Input should be"):]
        if kind == "int_from_float":  # pydantic: "... integer, got a number with a fractional part"
            msg = "must be a whole number"
        elif kind == "too_short" and loc and isinstance(value, (list, tuple)):
            msg = "must have 2 entries (low, high)" if len(value) < 2 else msg
        reason = f"{msg[:1].lower()}{msg[1:]}, got {_short_repr(value)}"
    if len(errors) > 1:
        reason += f" (and {len(errors) - 1} more problem{'s' if len(errors) > 2 else ''})"
    if field == "file" and source is not None:
        reason = f"{source}: {reason}"
    return ConfigError(field, reason)


def _validate(model: type[_Spec], data: Any, prefix: str, source: Path | None = None):
    try:
        return model.model_validate(data)
    except ValidationError as err:
        raise _config_error(err, prefix, source) from None


# ----------------------------------------------------------------- build objects
def _build_part(spec: PartSpec, default_name: str | None = None) -> Part:
    """The part of a ``[part]`` table. Without a ``name`` key: ``default_name`` (a file's stem) with
    its lead weights appended (:func:`~throwmap.system.catalogue.lead_name`), or, with no
    ``default_name``, the descriptive default of :meth:`Part.from_vertices`."""
    part = Part.from_vertices(
        spec.vertices,
        mass=spec.mass,
        com=spec.com,
        radius_of_gyration=spec.radius_of_gyration,
        point_masses=[(pm.mass, pm.at) for pm in spec.point_masses],
        name=spec.name,
    )
    if spec.name is None and default_name is not None:
        part = dataclasses.replace(part, name=lead_name(default_name, part.point_masses))
    return part


def _build_arm(spec: ArmSpec) -> Arm:
    """Every key of the ``[arm]`` table is the :class:`Arm` field of that name (``mu`` left out: ∞)."""
    return spec.arm()


def part_from_spec(spec: dict) -> Part:
    """A :class:`Part` from the contents of a ``[part]`` table (a dict).

    Raises :class:`ConfigError` (fields ``part.…``) for schema problems and
    :class:`InvalidPartError` for an invalid part.
    """
    return _build_part(_validate(PartSpec, spec, "part"))


def arm_from_spec(spec: dict) -> Arm:
    """An :class:`Arm` from the contents of an ``[arm]`` table (a dict).

    Reads back the ``"arm"`` object of every ``--json`` output, where JSON's ``null`` stands
    for ``length`` = unbounded and ``mu`` = ∞ (no slip); ``"mu": "inf"`` is read as ∞ too.

    Raises :class:`ConfigError` (fields ``arm.…``) for schema problems and
    :class:`InvalidArmError` for an invalid arm.
    """
    return _build_arm(_validate(FileArmSpec, spec, "arm"))


@dataclass(frozen=True, slots=True)
class LoadedConfig:
    """What a part/arm file holds: the part, and the arm if the file has an ``[arm]`` table.

    ``source`` is the file it came from (``None`` for a built-in part).
    """

    part: Part
    arm: Arm | None = None
    source: Path | None = None

    def __repr__(self) -> str:
        """One line: the file, the part (:meth:`Part.__repr__`) and the arm, if any."""
        src = str(self.source) if self.source is not None else "built-in"
        return f"LoadedConfig({src}: {self.part!r}, arm {self.arm!r})"


def _no_duplicate_keys(pairs):
    out = {}
    for key, value in pairs:
        if key in out:
            raise ConfigError("file", f"duplicate key {key!r}")
        out[key] = value
    return out


def _read_document(path: Path) -> Any:
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        raise ConfigError("file", f"{path}: unsupported file type {suffix or '(no extension)'!r}; use .toml or .json")
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise ConfigError("file", f"{path}: no such file") from None
    except IsADirectoryError:
        raise ConfigError("file", f"{path}: is a directory, not a file") from None
    except OSError as err:
        raise ConfigError("file", f"{path}: cannot read ({err.strerror or err})") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise ConfigError("file", f"{path}: not UTF-8 text (byte {err.start})") from None
    if suffix == ".toml":
        try:
            return tomllib.loads(text)
        except tomllib.TOMLDecodeError as err:
            raise ConfigError("file", f"{path}: malformed TOML: {err}") from None
    try:
        return json.loads(text, object_pairs_hook=_no_duplicate_keys)
    except json.JSONDecodeError as err:
        raise ConfigError("file", f"{path}: malformed JSON: {err}") from None
    except ConfigError as err:
        raise ConfigError("file", f"{path}: malformed JSON: {err.reason}") from None


def load_config(path) -> LoadedConfig:
    """Read and validate a part/arm file (``.toml`` or ``.json``).

    The part's name defaults to the file's stem, with its lead weights appended
    (``"bracket+lead(12 g at (9, 1) cm)"``). Raises :class:`ConfigError`
    (``field="file"`` for unreadable or malformed files, the dotted key path
    otherwise), or the :class:`InvalidPartError` / :class:`InvalidArmError` of an
    invalid part or arm.
    """
    path = Path(path)
    spec = _validate(FileSpec, _read_document(path), "", path)
    part = _build_part(spec.part, default_name=path.stem)
    arm = _build_arm(spec.arm) if spec.arm is not None else None
    return LoadedConfig(part=part, arm=arm, source=path)


def resolve_part(value: str) -> LoadedConfig:
    """A built-in part by name (see :data:`throwmap.system.catalogue.BUILTIN_PARTS`) or a part file.

    A value that names a built-in part wins; otherwise a value with a ``.toml``
    / ``.json`` extension, a path separator, or naming an existing file is read
    with :func:`load_config`.
    """
    if value in BUILTIN_PARTS:
        return LoadedConfig(part=builtin_part(value))
    path = Path(value)
    if path.suffix.lower() in SUFFIXES or "/" in value or "\\" in value or path.exists():
        return load_config(path)
    try:
        return LoadedConfig(part=builtin_part(value))
    except InvalidPartError as err:
        raise InvalidPartError(err.field, f"{err.reason}, or give a .toml/.json part file") from None


# ------------------------------------------------------------------------ write
def _toml_float(v: float) -> str:
    v = float(v)
    if not math.isfinite(v):  # pragma: no cover - parts and arms are finite by construction
        raise ConfigError("file", f"cannot write the non-finite number {v}")
    return repr(v)  # shortest round-trip repr; always valid TOML for finite floats


def _toml_point(p) -> str:
    return f"[{_toml_float(p[0])}, {_toml_float(p[1])}]"


def _toml_string(s: str) -> str:
    out = ['"']
    for ch in s:
        code = ord(ch)
        if ch == '"':
            out.append('\\"')
        elif ch == "\\":
            out.append("\\\\")
        elif ch == "\t":
            out.append("\\t")
        elif ch == "\n":
            out.append("\\n")
        elif code < 0x20 or code == 0x7F:
            out.append(f"\\u{code:04X}")
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def _plate_mass(part: Part) -> float:
    """The plate mass that :meth:`Part.from_vertices` turns back into ``part.mass`` exactly."""
    added = sum(m for m, _ in part.point_masses)
    plate = part.mass - added
    if plate + added == part.mass:
        return plate
    for direction in (math.inf, -math.inf):
        p = plate
        for _ in range(4):
            p = math.nextafter(p, direction)
            if p + added == part.mass:
                return p
    return plate  # pragma: no cover - within one ulp of exact


def overrides(part: Part) -> dict:
    """The mass properties of ``part`` that its vertices, plate mass and point masses do not give:
    ``{"com": (x, y), "radius_of_gyration": ρ}``, each present only when it was an override.

    A part file writes only these, so editing its vertices, mass or point masses moves the CM
    and ρ (paper Sec. V: lead weights move the CM and inertia consistently), while a part built
    with a given ``com`` or ``radius_of_gyration`` still reads back equal. The check repeats the
    loader's own computation (:meth:`Part.from_vertices` on the written numbers), so it is exact.
    """
    vertices, plate = [tuple(v) for v in part.vertices], _plate_mass(part)
    pms = [(m, tuple(at)) for m, at in part.point_masses]
    out = {}
    try:
        computed = Part.from_vertices(vertices, mass=plate, point_masses=pms).com
    except InvalidPartError:  # pragma: no cover - the plate-plus-lead CM of a convex part is a valid CM
        computed = None
    if computed != part.com:
        out["com"] = part.com
    rho = Part.from_vertices(vertices, mass=plate, point_masses=pms, com=part.com).radius_of_gyration
    if rho != part.radius_of_gyration:
        out["radius_of_gyration"] = part.radius_of_gyration
    return out


def part_to_toml(part: Part, arm: Arm | None = None) -> str:
    """The TOML text of a part file that :func:`load_config` reads back to an equal part.

    ``mass`` is the plate mass without the point masses (the part's total mass is their
    sum). ``com`` and ``radius_of_gyration`` are written only when they were overrides
    (:func:`overrides`), so editing the file's vertices, mass or point masses moves them.
    """
    from ..version import __version__

    given = overrides(part)
    lines = [
        f"# throwmap {__version__} part file; SI units (m, kg, s), see throwmap.conventions",
        "",
        "[part]",
        f"name = {_toml_string(part.name)}",
        "vertices = [",
        *(f"    {_toml_point(v)}," for v in part.vertices),
        "]",
        f"mass = {_toml_float(_plate_mass(part))}  # kg, plate only (total {part.mass:.6g} kg)",
    ]
    if "com" in given:
        pms = [(m, tuple(at)) for m, at in part.point_masses]
        computed = Part.from_vertices([tuple(v) for v in part.vertices], mass=_plate_mass(part), point_masses=pms).com
        if math.dist(computed, part.com) < 1e-9:  # the same point but for rounding: kept so the part reads back equal
            lines.append(f"com = {_toml_point(part.com)}  # m, the plate-plus-lead CM to its last digit")
        else:
            lines.append(f"com = {_toml_point(part.com)}  # m, given (not the plate-plus-lead CM)")
    if "radius_of_gyration" in given:
        lines.append(f"radius_of_gyration = {_toml_float(part.radius_of_gyration)}  # m, about the CM, given")
    for m, at in part.point_masses:
        lines += ["", "[[part.point_masses]]", f"mass = {_toml_float(m)}  # kg", f"at = {_toml_point(at)}  # m"]
    if arm is not None:
        lines += ["", "[arm]"]
        for key, value in arm_document(arm).items():
            lines.append(f"{key} = {_toml_float(value)}{_ARM_UNITS.get(key, '')}")
    return "\n".join(lines) + "\n"


_ARM_UNITS = {"h": "  # m", "g": "  # m/s^2", "length": "  # m", "mu": "  # Coulomb friction", "back": "  # m"}


def arm_document(arm: Arm) -> dict:
    """The ``[arm]`` table of ``arm``: every :class:`Arm` field, in its order, except those
    at a default the file cannot spell (``length`` = None: unbounded; ``mu`` = ∞: no slip).

    Driven by the dataclass's fields, so a field added to :class:`Arm` is written at once
    (and refused on reading until :class:`ArmSpec` knows it: the round-trip test sees it).
    """
    out = {}
    for f in dataclasses.fields(Arm):
        value = getattr(arm, f.name)
        if value is None or (isinstance(value, float) and not math.isfinite(value) and value == f.default):
            continue
        out[f.name] = value
    return out


def part_document(part: Part, arm: Arm | None = None) -> dict:
    """The part file as a document (``{"part": {...}, "arm": {...}}``) that :func:`load_config`
    reads back to an equal part and arm; ``mass`` is the plate mass without the point masses,
    ``com`` / ``radius_of_gyration`` are present only when they were overrides (:func:`overrides`)."""
    doc = {"part": {
        "name": part.name,
        "vertices": [list(v) for v in part.vertices],
        "mass": _plate_mass(part),
        **{k: (list(v) if k == "com" else v) for k, v in overrides(part).items()},
        "point_masses": [{"mass": m, "at": list(at)} for m, at in part.point_masses],
    }}
    if arm is not None:
        doc["arm"] = arm_document(arm)
    return doc


def save_part(part: Part, arm: Arm | None, path) -> Path:
    """Write ``part`` (and ``arm``) as a part file, TOML or JSON by the extension, atomically;
    :func:`load_config` reads it back to an equal part and arm. Returns the path."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".toml":
        return save_part_toml(part, arm, path)
    if suffix != ".json":
        raise ConfigError("file", f"{path}: a part file must end in .toml or .json, got {suffix or '(no extension)'!r}")
    text = json.dumps(part_document(part, arm), indent=2, allow_nan=False, ensure_ascii=False)
    return atomic_write_text(path, text + "\n")


def save_part_toml(part: Part, arm: Arm | None, path) -> Path:
    """Write ``part`` (and ``arm``, if given) as a TOML part file, atomically; returns the path.

    :func:`load_config` reads the file back to an equal part and arm.
    """
    path = Path(path)
    if path.suffix.lower() != ".toml":
        raise ConfigError("file", f"{path}: a part file written as TOML must end in .toml")
    return atomic_write_text(path, part_to_toml(part, arm))
