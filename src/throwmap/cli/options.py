"""What every ``throwmap`` command shares: options, parsing, errors and writing.

- Options: :data:`PartOpt`, :data:`HOpt`, … (``Annotated`` Typer options; SI units).
- Parsing: :func:`check_finite`, :func:`parse_floats`, :func:`part_and_arm`.
- Errors: :func:`guard` turns every :class:`~throwmap.errors.ThrowmapError` into exactly
  one line ``error: <field>: <reason>`` on stderr and exit status 2, and prints each
  warning (e.g. :class:`~throwmap.errors.RegimeWarning`) once as ``warning: <message>``.
  Usage errors found by the option parser get the same line (:mod:`throwmap.cli.usage`).
- Writing: :func:`to_json` (strict JSON: non-finite numbers become ``null``), files
  written atomically (:mod:`throwmap.io.files`). Every output path is checked before any
  work (:func:`check_output`, :func:`check_out_dir`, :func:`figure_format`): not a directory
  where a file goes; its folder there and writable (a missing one is refused, never made); an
  ``--out`` directory writable, or missing in a folder that is there (then only DIR is made).

Nothing here imports another ``throwmap.cli`` module; the command modules import this one.
"""

from __future__ import annotations

import dataclasses
import io as _io
import json
import math
import os
import re
import sys
import tempfile
import warnings
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated, Any

import typer

from ..conventions import G
from ..errors import ConfigError, InvalidArmError, InvalidStateError, ThrowmapError, ThrowmapWarning
from ..io.config import resolve_part
from ..io.files import atomic_write_bytes, atomic_write_text, make_directory
from ..serial import json_ready
from ..system.arm import Arm, regime_warnings_once
from ..throws.throw import DEFAULT_MODEL, MODELS

__all__ = ["progress_bar", 
    "BackOpt", "GOpt", "HOpt", "JsonOpt", "LengthOpt", "ModelOpt", "ModelOptionOpt", "MuOpt", "OmegaOpt", "PartOpt",
    "SideOpt", "XOpt", "ForceOpt", "MaxMemoryOpt", "MaxTimeOpt", "AlphaOpt", "WallOpt", "WallMuOpt", "CavityOpt",
    "model_options", "options_doc", "parse_alpha", "system_options", "system_doc",
    "WRITTEN", "arm_dict", "check_directory", "check_finite", "check_out_dir", "check_output", "figure_format",
    "format_value", "guard", "interrupted_line", "kept_line", "make_out_dir", "parse_floats", "part_and_arm",
    "plot_format", "save_figure", "side_value", "stderr_line", "stored_lines", "strict_int", "to_json",
    "write_bytes", "write_text",
]

# ------------------------------------------------------------------ options
PartOpt = Annotated[str, typer.Option("--part", help="Built-in part name or a .toml/.json part file.")]
HOpt = Annotated[float | None, typer.Option("--h", help="Arm surface height h, m (h < 0: below the joint). "
                                                      "Required unless the part file has an \\[arm] section.")]
GOpt = Annotated[float | None, typer.Option("--g", help=f"Gravity, m/s² (default: the file's, or {G}).")]
LengthOpt = Annotated[float | None, typer.Option("--length", help="Arm length, m (default: the file's, or unbounded).")]
MuOpt = Annotated[float | None, typer.Option("--mu", help="Arm–part Coulomb friction μ (default: the file's, or inf = no slip; "
                                               "used by rigid_body, engine and mujoco).")]
BackOpt = Annotated[float | None, typer.Option("--back", help="Arm surface behind the joint, m (default: the file's, "
                                                              "or 0: any contact at x ≤ 0 is behind the joint).")]
XOpt = Annotated[float, typer.Option("--x", help="Resting CM position along the arm, m.")]


def side_value(text: str) -> int | float | str:
    """``--side`` as the Python value the library is given: a whole-number literal
    (``3``, ``-1``) becomes an ``int``, any other number a ``float`` (``1.0``, ``0.5``),
    anything else stays text. The library's one rule (:meth:`throwmap.Part.check_side`:
    an integer index of a stable side) then accepts or refuses it, exactly as it does
    ``throw(part, arm, x, side, ω)`` with that value."""
    text = str(text).strip()
    if re.fullmatch(r"[+-]?[0-9]+", text):
        return int(text)
    try:
        return float(text)
    except ValueError:
        return text


def strict_int(text: str) -> int:
    """An integer option: whole-number literals only (``3``, ``-1``), as the library takes
    ``int`` and refuses ``3.0``; anything else is a usage error naming the option."""
    text = str(text).strip()
    if not re.fullmatch(r"[+-]?[0-9]+", text):
        raise typer.BadParameter("Input should be a valid integer")
    return int(text)


SideOpt = Annotated[int, typer.Option("--side", parser=side_value, metavar="INTEGER",
                                      help="Side the part rests on (index of a stable side, see conventions).")]
OmegaOpt = Annotated[float, typer.Option("--omega", help="Release angular velocity ω, rad/s (≥ 0).")]
ModelOpt = Annotated[str, typer.Option("--model", help=f"Throw model: {', '.join(MODELS)} (default {DEFAULT_MODEL}).")]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print JSON to stdout instead of a table.")]
MaxMemoryOpt = Annotated[float, typer.Option("--max-memory", help="Most memory the command may plan to hold, GB; "
                                                                    "above it the command refuses before starting.")]
MaxTimeOpt = Annotated[float, typer.Option("--max-time", help="Longest the command may plan to run, s (estimated "
                                                              "from throws timed at the start).")]
ForceOpt = Annotated[bool, typer.Option("--force", help="Run even above --max-memory / --max-time.")]
ModelOptionOpt = Annotated[list[str] | None, typer.Option(
    "--model-option", "-O", metavar="KEY=VALUE",
    help="A numerical option of the throw model, repeatable: e.g. -O impact_law=velocity (rigid_body), "
         "-O tol=1e-12, -O max_impacts=50 (the model's options type lists them; unknown keys are refused).")]


AlphaOpt = Annotated[str | None, typer.Option(
    "--alpha", metavar="ANGLE",
    help="Arm rest angle α, counter-clockwise from horizontal (> 0 raises the arm's end): rad, or degrees with a "
         "'deg' suffix (0.05, 5deg, -10deg). Default 0; only models with tilt take it (paper, rigid_body, engine).")]
WallOpt = Annotated[float | None, typer.Option(
    "--wall", help="A wall at the arm's end, its height above the arm surface, m (e.g. 0.05; needs --length). "
                   "Only models with fixtures take it (rigid_body, engine).")]
WallMuOpt = Annotated[float | None, typer.Option(
    "--wall-mu", help="Wall–part Coulomb friction μ (default: the arm's μ; inf = no slip). Needs --wall.")]
CavityOpt = Annotated[Path | None, typer.Option(
    "--cavity", help="A cavity at the arm's end from a .json or .toml file holding profile = \\[\\[s, y], …] in m "
                     "(s back from the arm's end, y ≤ 0 below the surface; see throwmap.Cavity).")]


def parse_alpha(text) -> float:
    """``--alpha`` in rad: a number (rad), or a number with a ``deg`` (or ``°``) suffix (degrees).

    Refused with a one-line error on ``alpha``: anything else, or a non-finite angle."""
    raw = str(text).strip()
    low = raw.lower().replace(" ", "")
    deg = False
    for suffix in ("degrees", "degree", "deg", "°"):
        if low.endswith(suffix):
            low, deg = low[: -len(suffix)], True
            break
    if low.endswith("rad"):
        low = low[:-3]
    try:
        v = float(low)
    except ValueError:
        raise InvalidStateError("alpha", f"must be an angle in rad (0.05) or in degrees with 'deg' (5deg), "
                                         f"got {raw!r}") from None
    if not math.isfinite(v):
        raise InvalidStateError("alpha", f"must be finite, got {raw!r}")
    return math.radians(v) if deg else v


def system_options(alpha: str | None = None, wall: float | None = None, wall_mu: float | None = None,
                   cavity: Path | None = None, arm: Arm | None = None) -> dict:
    """The keywords ``fixtures=`` and ``alpha=`` of :func:`throwmap.throw` from ``--alpha``, ``--wall``,
    ``--wall-mu`` and ``--cavity``, checked before any work; only those given (so that a model
    without tilt or fixtures is not handed them unasked, and refuses them when asked). Fixtures sit
    at the arm's end: with ``arm`` unbounded they are refused on ``arm.length``."""
    from ..system.fixtures import Cavity, Wall

    out: dict = {}
    if alpha is not None:
        out["alpha"] = parse_alpha(alpha)
    fixtures = []
    if wall_mu is not None and wall is None:
        raise InvalidStateError("wall_mu", "needs --wall (the wall's height)")
    if wall is not None:
        if not math.isfinite(wall) or wall <= 0:
            raise InvalidStateError("wall", f"must be a positive height in m, got {wall:g}")
        if wall_mu is not None and (math.isnan(wall_mu) or wall_mu < 0):
            raise InvalidStateError("wall_mu", f"must be a number ≥ 0 (inf: no slip), got {wall_mu:g}")
        fixtures.append(Wall(float(wall), mu=None if wall_mu is None else float(wall_mu)))
    if cavity is not None:
        fixtures.append(Cavity(_cavity_profile(Path(cavity))))
    if fixtures:
        if arm is not None and arm.length is None:
            raise InvalidArmError("arm.length", "a wall or cavity sits at the arm's end: give the arm a length "
                                                "(--length, or length in the part file's [arm])")
        out["fixtures"] = tuple(fixtures)
    return out


def _cavity_profile(path: Path) -> tuple:
    """The ``profile`` of a cavity file (.json or .toml), refused on ``cavity`` if unreadable."""
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise ConfigError("cavity", f"cannot read {path}: {err.strerror or err}") from None
    try:
        if path.suffix.lower() == ".toml":
            import tomllib

            data = tomllib.loads(text)
        else:
            data = json.loads(text)
    except (ValueError, UnicodeDecodeError) as err:
        raise ConfigError("cavity", f"{path} is not valid {path.suffix.lstrip('.').upper() or 'JSON'}: "
                                    f"{str(err).splitlines()[0]}") from None
    prof = _cavity_table(data, path).get("profile") if isinstance(data, dict) else None
    if not isinstance(prof, list):
        raise ConfigError("cavity", f"{path} needs profile = [[s, y], …] (m), at the top or in a [cavity] table")
    return tuple(tuple(p) if isinstance(p, list) else p for p in prof)


_CAVITY_KEYS = ("profile", "kind")  # kind = "cavity": as in the fixture records of Outcome/Orbit JSON


def _cavity_table(data: dict, path: Path) -> dict:
    """The table of a cavity file holding its keys (the top level, or its ``[cavity]`` table alone);
    an unknown key is refused on ``cavity``, named with the allowed keys (and a close match)."""
    from ..errors import shown

    _cavity_keys(data, _CAVITY_KEYS + ("cavity",), "", path)
    if "cavity" in data:
        if not isinstance(data["cavity"], dict):
            raise ConfigError("cavity", f"{path}: cavity must be a table holding profile = [[s, y], …], "
                                        f"got {shown(data['cavity'])}")
        if len(data) > 1:
            raise ConfigError("cavity", f"{path}: give the keys at the top or in a [cavity] table, not both "
                                        f"(got {', '.join(map(str, data))})")
        data = data["cavity"]
        _cavity_keys(data, _CAVITY_KEYS, " in [cavity]", path)
    if data.get("kind", "cavity") != "cavity":
        raise ConfigError("cavity", f"{path}: kind must be 'cavity', got {shown(data['kind'])}")
    return data


def _cavity_keys(table: dict, allowed: tuple, where: str, path: Path) -> None:
    """Refuse the first key of ``table`` not in ``allowed``: ``<path>: unknown key 'profle'<where> (…)``."""
    import difflib

    for key in table:
        if key not in allowed:
            close = difflib.get_close_matches(str(key), allowed, n=1)
            hint = f"did you mean {close[0]!r}? " if close else ""
            raise ConfigError("cavity", f"{path}: unknown key {str(key)!r}{where} "
                                        f"({hint}allowed: {', '.join(allowed)})")


def system_doc(system_kw: dict) -> dict:
    """``{"alpha_rad", "fixtures"}`` of a run for its JSON record (α = 0 and no fixtures: the plain arm)."""
    from ..analysis.maps import fixtures_doc

    return {"alpha_rad": float(system_kw.get("alpha", 0.0)), "fixtures": fixtures_doc(system_kw.get("fixtures", ()))}


def _option_value(text: str):
    """A ``--model-option`` value: an integer, a float (``inf`` too), ``true``/``false``, else the string."""
    low = text.strip().lower()
    if re.fullmatch(r"[+-]?[0-9]+", low):
        return int(low)
    if low in ("true", "false"):
        return low == "true"
    try:
        return float(low)
    except ValueError:
        return text.strip()


def model_options(values, model: str) -> dict:
    """``{"options": <the model's options value>}`` from ``-O KEY=VALUE`` entries, checked before any work.

    The options value goes to the library as ``options=`` (never as loose keywords, so a
    model option such as ``tol`` cannot be mistaken for an analysis keyword of the same name).
    Empty when no entry is given (the model's defaults)."""
    if not values:
        return {}
    from ..models import get_model
    from ..models.base import build_options

    given = {}
    for item in values:
        key, sep, val = str(item).partition("=")
        key = key.strip()
        if not sep or not key or not val.strip():
            raise InvalidStateError("model_option", f"must be KEY=VALUE, got {item!r}")
        if key in given:
            raise InvalidStateError(key, "given twice as --model-option")
        given[key] = _option_value(val)
    return {"options": build_options(get_model(model), None, given)}


def options_doc(opts: dict) -> dict | None:
    """The model options a run used, for its JSON record (None: the model's defaults)."""
    if not opts:
        return None
    return json_ready(dataclasses.asdict(opts["options"]))


# ------------------------------------------------------------------ errors
def stderr_line(text: str) -> None:
    """Write ``text`` as one line on stderr (newlines become spaces)."""
    sys.stderr.write(" ".join(str(text).split("\n")) + "\n")
    sys.stderr.flush()


def compiling_notice(model: str) -> bool:
    """Say on stderr that the kernels of ``model`` compile now, when their cache is empty (the first call on a fresh
    checkout, a minute of silence otherwise); returns whether it did (:func:`throwmap.warmup.cold`)."""
    from ..warmup import cold

    if cold(model):
        stderr_line(f"compiling the {model} kernels, once (a minute or two; `throwmap compile` does it ahead, "
                    "`make` at install)…")
        return True
    return False


@contextmanager
def guard():
    """Turn ThrowmapErrors into one ``error:`` line and exit 2; print warnings one line each (a lost guarantee of
    the paper's regime is warned once per command: :func:`~throwmap.system.arm.regime_warnings_once`)."""
    with warnings.catch_warnings(record=True) as caught, regime_warnings_once():
        warnings.simplefilter("always", ThrowmapWarning)
        try:
            yield
        except ThrowmapError as err:
            stderr_line(f"error: {err}")
            raise typer.Exit(2) from None
    seen = set()
    for w in caught:
        msg = str(w.message)
        if msg not in seen:
            seen.add(msg)
            stderr_line(f"warning: {msg}")


# ------------------------------------------------------------------ parsing
def check_finite(value: float, field: str) -> float:
    """``value``, or :class:`~throwmap.errors.InvalidStateError` on ``field`` if it is not finite."""
    if not math.isfinite(value):
        raise InvalidStateError(field, f"must be finite, got {value}")
    return value


def parse_floats(values: list[str] | str, field: str) -> list[float]:
    """Numbers from repeated options and/or comma lists (``--omega 1,2 --omega 3``)."""
    items = [values] if isinstance(values, str) else list(values)
    out = []
    for item in items:
        for piece in item.split(","):
            piece = piece.strip()
            try:
                v = float(piece)
            except ValueError:
                raise InvalidStateError(field, f"must be numbers separated by commas, got {piece!r}") from None
            out.append(check_finite(v, field))
    return out


def part_and_arm(part: str, h: float | None, g: float | None, length: float | None, mu: float | None = None,
                 back: float | None = None):
    """The part (built-in name or file) and the arm: each option given on the command line
    over the file's ``[arm]`` value, every other field of the file's arm kept as it is."""
    loaded = resolve_part(part)
    base = loaded.arm
    if h is None and base is None:
        raise InvalidArmError("arm.h", "required: give --h, or an [arm] section in the part file")
    given = {k: v for k, v in (("h", h), ("g", g), ("length", length), ("mu", mu), ("back", back)) if v is not None}
    arm = dataclasses.replace(base, **given) if base is not None else Arm(**given)
    return loaded.part, arm


# ------------------------------------------------------------------ output
def to_json(obj: Any) -> str:
    """Strict, indented JSON (non-finite numbers become ``null``)."""
    return json.dumps(json_ready(obj), indent=2, allow_nan=False, ensure_ascii=False)


def arm_dict(arm: Arm) -> dict:
    """The arm for JSON output: every :class:`Arm` field. JSON has no infinity, so ``null`` is
    the field's unbounded value: ``"mu": null`` is μ = ∞ (no slip), ``"length": null`` an
    unbounded arm — as in a part file, where both are left out.
    :func:`throwmap.io.config.arm_from_spec` reads the object back to an equal :class:`Arm`."""
    out = {f.name: getattr(arm, f.name) for f in dataclasses.fields(arm)}
    out["mu"] = arm.mu if math.isfinite(arm.mu) else None
    return out


def format_value(v: Any, spec: str = ".6g") -> str:
    """A table cell: yes/no for booleans, ``—`` for non-finite floats."""
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return format(v, spec) if math.isfinite(v) else "—"
    return str(v)


def _probe_directory(directory: Path, field: str, target: Path) -> None:
    """Refuse ``directory`` unless a file can be created in it (tried: one empty file, removed at once)."""
    try:
        fd, probe = tempfile.mkstemp(prefix=".throwmap-probe-", dir=directory)
    except OSError as err:
        raise ConfigError(field, f"cannot write {target}: directory {directory} is not writable "
                                 f"({err.strerror or err})") from None
    os.close(fd)
    os.unlink(probe)


def _missing_folder(folder: Path, field: str) -> None:
    """Refuse ``folder`` unless it exists: output never creates a missing folder above it."""
    if not folder.exists():
        raise ConfigError(field, f"folder {str(folder)!r} does not exist")


def check_directory(directory: Path, field: str, target: Path | None = None) -> None:
    """Refuse, before any work, a directory that output cannot go into: it is missing, or it exists and
    is not a directory or is not writable. Nothing is created here."""
    target = directory if target is None else target
    directory = Path(directory) if str(directory) else Path(".")
    _missing_folder(directory, field)
    if not directory.is_dir():
        raise ConfigError(field, f"cannot write {target}: {directory} exists and is not a directory")
    _probe_directory(directory, field, target)


def check_output(path: Path, field: str, *, create: bool = True) -> None:
    """Refuse, before any work, an output file that cannot be written: a directory where the
    file should be, or a folder for it that is missing, exists as something else or is not
    writable — the one rule for every output file (figures, result files, animations).
    ``create`` is accepted for older callers and changes nothing."""
    path = Path(path)
    if path.is_dir():
        raise ConfigError(field, f"cannot write {path}: it is a directory")
    parent = path.parent if str(path.parent) else Path(".")
    check_directory(parent, field, path)


def check_out_dir(out: Path | None, field: str = "out") -> None:
    """Refuse, before any work, an output directory (``--out DIR``) that exists as something else or is not
    writable, or that is missing in a folder that is missing (DIR itself is made, never a folder above it)."""
    if out is None:
        return
    out = Path(out)
    if out.exists():
        check_directory(out, field)
        return
    parent = out.parent if str(out.parent) else Path(".")
    check_directory(parent, field, out)


def make_out_dir(out: Path, field: str = "out") -> None:
    """Create the ``--out`` directory, and only it (its folder exists: :func:`check_out_dir`;
    :func:`throwmap.io.files.make_directory`)."""
    make_directory(out, field)


WRITTEN: list[str] = []
"""The files the running command has written (:func:`write_text`, :func:`write_bytes`, :func:`save_figure`): what
a Ctrl-C keeps (:func:`kept_line`). The app's command group empties it before each command."""


def write_text(path: Path, text: str, field: str) -> None:
    """Write ``text`` atomically; an OS error becomes a :class:`~throwmap.errors.ConfigError` on ``field``."""
    try:
        atomic_write_text(path, text)
    except OSError as err:
        raise ConfigError(field, f"cannot write {path}: {err.strerror or err}") from None
    WRITTEN.append(str(path))


def write_bytes(path: Path, data: bytes, field: str) -> None:
    """Write ``data`` atomically; an OS error becomes a :class:`~throwmap.errors.ConfigError` on ``field``."""
    try:
        atomic_write_bytes(path, data)
    except OSError as err:
        raise ConfigError(field, f"cannot write {path}: {err.strerror or err}") from None
    WRITTEN.append(str(path))


def plot_format(path: Path) -> str:
    """The image format of ``path`` (its extension), refused unless Matplotlib can write it."""
    from matplotlib.backend_bases import FigureCanvasBase

    fmt = path.suffix.lower().lstrip(".")
    supported = FigureCanvasBase.get_supported_filetypes()
    if fmt not in supported:
        raise ConfigError("plot", f"unsupported image type {path.suffix or '(no extension)'!r} "
                                  f"(use one of {', '.join('.' + k for k in sorted(supported))})")
    return fmt


def figure_format(path: Path | None, field: str) -> str | None:
    """Check a figure path (its folder there and writable, image type known) before any work; its format."""
    if path is None:
        return None
    check_output(path, field)
    os.environ.setdefault("MPLBACKEND", "Agg")  # files only, never a window
    try:
        return plot_format(path)
    except ThrowmapError as err:
        raise ConfigError(field, err.reason) from None


def save_figure(fig, path: Path, fmt: str, field: str) -> None:
    """Save a Figure (or an Axes' figure) atomically at 130 dpi, then close it."""
    fig = fig if hasattr(fig, "savefig") else fig.figure  # an Axes → its Figure
    buf = _io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=130)
    try:
        atomic_write_bytes(path, buf.getvalue())
        WRITTEN.append(str(path))
    except OSError as err:
        raise ConfigError(field, f"cannot write {path}: {err.strerror or err}") from None
    finally:
        plt = sys.modules.get("matplotlib.pyplot")
        if plt is not None:
            plt.close(fig)


@contextmanager
def stage_bars(console=None, lines: bool = False):
    """Yields ``update(stage, done, total)``: one Rich bar per stage on ``console`` (default: stderr). Off a terminal
    a no-op, or with ``lines`` one line on stderr as each stage starts (a log of a long run). A stage that starts
    with "→" is an outcome, not a stage: printed once as it is (above the bars; off a terminal with ``lines``)."""
    from rich.console import Console

    console = Console(stderr=True) if console is None else console
    if not console.is_terminal:
        started: set = set()

        def line(stage, done, total):
            if lines and stage not in started:
                started.add(stage)
                stderr_line(str(stage) if str(stage).startswith("→") else f"{stage}…")

        yield line
        return
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                  console=console, transient=True) as bar:
        tasks: dict = {}

        def update(stage, done, total):
            if str(stage).startswith("→"):
                bar.console.print(str(stage), markup=False, highlight=False)
                return
            if stage not in tasks:
                tasks[stage] = bar.add_task(str(stage), total=total)
            bar.update(tasks[stage], completed=done, total=total)

        yield update


@contextmanager
def progress_bar(name: str):
    """Yields ``update(done, total)``: a Rich bar ``experiment NAME`` on stderr (a no-op off a terminal)."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

    console = Console(stderr=True)
    if not console.is_terminal:
        yield lambda done, total: None
        return
    with Progress(TextColumn(f"experiment {name}"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                  console=console, transient=True) as bar:
        task = bar.add_task(name, total=None)
        yield lambda done, total: bar.update(task, completed=done, total=total)


def stored_lines(out: Path, pattern: str = "trials.jsonl") -> int:
    """The records kept under ``out``: the non-empty lines of its files matching ``pattern``."""
    k = 0
    for path in sorted(Path(out).glob(pattern)):
        try:
            with open(path, encoding="utf-8") as f:
                k += sum(1 for line in f if line.strip())
        except OSError:
            pass
    return k


def interrupted_line(out: Path | None, what: str = "trial", pattern: str = "trials.jsonl") -> str:
    """The one line a Ctrl-C leaves: how many trials ``out`` keeps (the lines of its files matching ``pattern``,
    its ``trials.jsonl``), or that none are; ``what`` names them (``"trial"``, ``"case"``)."""
    if out is None:
        return f"interrupted: no --out DIR, so no {what} was kept"
    n = stored_lines(out, pattern)
    if n == 0:
        return f"interrupted: no {what} was finished, nothing stored in {str(out)!r}"
    return f"interrupted: {n} {what}(s) stored in {str(out)!r}; the same command resumes from them"


def kept_line() -> str:
    """The one line a Ctrl-C leaves in a command that keeps nothing as it goes: the files it wrote (:data:`WRITTEN`)."""
    if not WRITTEN:
        return "interrupted: nothing was written"
    return f"interrupted: kept {', '.join(repr(p) for p in WRITTEN)}; nothing else was written"
