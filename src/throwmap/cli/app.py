"""The ``throwmap`` command line: a thin shell over the library.

Each subcommand parses its options, builds the part and arm, calls one library
function and prints (or writes) the result; there is no physics here.

Errors: bad input ends with exactly one line ``error: <field>: <reason>`` on
stderr and exit status 2 (every :class:`~throwmap.errors.ThrowmapError`); usage
errors found by the option parser keep its own message and status 2. Warnings
(e.g. :class:`~throwmap.errors.RegimeWarning`) are printed once each as
``warning: <message>`` on stderr. JSON output is strict JSON (non-finite numbers
become ``null``); files are written atomically (:mod:`throwmap.io.files`).
"""

from __future__ import annotations

import io as _io
import json
import math
import os
import sys
import warnings
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated, Any

import typer

from .. import __version__
from ..system.arm import Arm
from ..io.config import resolve_part
from ..conventions import G
from ..errors import ConfigError, InvalidArmError, InvalidStateError, ThrowmapError, ThrowmapWarning
from ..io.files import atomic_write_bytes, atomic_write_text, json_ready
from ..throws.orbit import Orbit, iterate
from ..throws.throw import MODELS, check_model, throw

__all__ = ["app", "main"]

PROGRESS_THRESHOLD = 200
"""``iterate`` shows a progress bar (on stderr) for more throws than this."""

app = typer.Typer(
    name="throwmap",
    help="Throw maps of planar parts on a one-joint throwing arm (SI units: m, kg, s, rad).",
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
)


# ------------------------------------------------------------------ plumbing
def _stderr_line(text: str) -> None:
    sys.stderr.write(" ".join(str(text).split("\n")) + "\n")
    sys.stderr.flush()


@contextmanager
def _guard():
    """Turn ThrowmapErrors into one ``error:`` line and exit 2; print warnings one line each."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ThrowmapWarning)
        try:
            yield
        except ThrowmapError as err:
            _stderr_line(f"error: {err}")
            raise typer.Exit(2) from None
    seen = set()
    for w in caught:
        msg = str(w.message)
        if msg not in seen:
            seen.add(msg)
            _stderr_line(f"warning: {msg}")


def _to_json(obj: Any) -> str:
    return json.dumps(json_ready(obj), indent=2, allow_nan=False, ensure_ascii=False)


def _finite(value: float, field: str) -> float:
    if not math.isfinite(value):
        raise InvalidStateError(field, f"must be finite, got {value}")
    return value


def _floats(values: list[str] | str, field: str) -> list[float]:
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
            out.append(_finite(v, field))
    return out


def _part_and_arm(part: str, h: float | None, g: float | None, length: float | None, mu: float | None = None):
    """The part (built-in name or file) and the arm: command line over the file's [arm]."""
    loaded = resolve_part(part)
    base = loaded.arm
    if h is None and base is None:
        raise InvalidArmError("arm.h", "required: give --h, or an [arm] section in the part file")
    arm = Arm(
        h=h if h is not None else base.h,
        g=g if g is not None else (base.g if base is not None else G),
        length=length if length is not None else (base.length if base is not None else None),
        mu=mu if mu is not None else (base.mu if base is not None else math.inf),
    )
    return loaded.part, arm


def _arm_dict(arm: Arm) -> dict:
    return {"h": arm.h, "g": arm.g, "length": arm.length, "mu": arm.mu if math.isfinite(arm.mu) else None}


def _fmt(v: Any, spec: str = ".6g") -> str:
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return format(v, spec) if math.isfinite(v) else "—"
    return str(v)


def _check_output(path: Path, field: str) -> None:
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise ConfigError(field, f"cannot write {path}: directory {parent} does not exist")
    if path.is_dir():
        raise ConfigError(field, f"cannot write {path}: it is a directory")


def _write_text(path: Path, text: str, field: str) -> None:
    try:
        atomic_write_text(path, text)
    except OSError as err:
        raise ConfigError(field, f"cannot write {path}: {err.strerror or err}") from None


def _plot_format(path: Path) -> str:
    from matplotlib.backend_bases import FigureCanvasBase

    fmt = path.suffix.lower().lstrip(".")
    supported = FigureCanvasBase.get_supported_filetypes()
    if fmt not in supported:
        raise ConfigError("plot", f"unsupported image type {path.suffix or '(no extension)'!r} "
                                  f"(use one of {', '.join('.' + k for k in sorted(supported))})")
    return fmt


def _save_figure(fig, path: Path, fmt: str, field: str) -> None:
    fig = fig if hasattr(fig, "savefig") else fig.figure  # an Axes → its Figure
    buf = _io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=130)
    try:
        atomic_write_bytes(path, buf.getvalue())
    except OSError as err:
        raise ConfigError(field, f"cannot write {path}: {err.strerror or err}") from None
    finally:
        plt = sys.modules.get("matplotlib.pyplot")
        if plt is not None:
            plt.close(fig)


# ------------------------------------------------------------------ options
PartOpt = Annotated[str, typer.Option("--part", help="Built-in part name or a .toml/.json part file.")]
HOpt = Annotated[float | None, typer.Option("--h", help="Arm surface height h, m (h < 0: below the joint). "
                                                      "Required unless the part file has an \\[arm] section.")]
GOpt = Annotated[float | None, typer.Option("--g", help=f"Gravity, m/s² (default: the file's, or {G}).")]
LengthOpt = Annotated[float | None, typer.Option("--length", help="Arm length, m (default: the file's, or unbounded).")]
MuOpt = Annotated[float | None, typer.Option("--mu", help="Arm–part Coulomb friction μ (default: the file's, or inf = no slip; "
                                               "used by rigid_body and engine).")]
XOpt = Annotated[float, typer.Option("--x", help="Resting CM position along the arm, m.")]
SideOpt = Annotated[int, typer.Option("--side", help="Side the part rests on (index, see conventions).")]
ModelOpt = Annotated[str, typer.Option("--model", help=f"Throw model: {', '.join(MODELS)}.")]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print JSON to stdout instead of a table.")]


def _version_callback(value: bool) -> None:
    if value:
        typer.echo(f"throwmap {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[bool, typer.Option("--version", callback=_version_callback, is_eager=True,
                                          help="Print the version and exit.")] = False,
) -> None:
    """Throw maps of planar parts on a one-joint throwing arm (SI units: m, kg, s, rad)."""


# ------------------------------------------------------------------ throw
@app.command("throw")
def throw_cmd(
    part: PartOpt,
    omega: Annotated[float, typer.Option("--omega", help="Release angular velocity ω, rad/s (≥ 0).")],
    x: XOpt,
    side: SideOpt,
    h: HOpt = None,
    g: GOpt = None,
    length: LengthOpt = None,
    mu: MuOpt = None,
    model: ModelOpt = "paper",
    as_json: JsonOpt = False,
) -> None:
    """One throw from rest at (x, side): where the part lands and how."""
    with _guard():
        check_model(model)
        the_part, arm = _part_and_arm(part, h, g, length, mu)
        _finite(x, "x")
        _finite(omega, "omega")
        out = throw(the_part, arm, x, side, omega, model=model)
        if as_json:
            doc = {**out.to_dict(), "part": the_part.name, "arm": _arm_dict(arm), "version": __version__}
            typer.echo(_to_json(doc))
            return
        from rich.console import Console
        from rich.markup import escape
        from rich.table import Table

        console = Console()
        console.print(escape(f"{the_part.name}: throw from x = {_fmt(x)} m, side {side}, ω = {_fmt(omega)} rad/s "
                             f"(model {model!r})"), soft_wrap=True)
        table = Table()
        table.add_column("quantity")
        table.add_column("value", justify="right")
        rows = [
            ("new x (m)", _fmt(out.x)),
            ("side", _fmt(out.side)),
            ("status", out.status.label),
            ("kind", out.kind),
            ("flight time (s)", _fmt(out.t_flight)),
            ("contact vertex", _fmt(out.contact_vertex)),
            ("impacts", _fmt(out.n_impacts)),
            ("flips", _fmt(out.n_flips)),
            ("friction ratio needed", _fmt(out.friction_ratio_max, ".4g")),
            ("lift-off", _fmt(out.lift_off)),
        ]
        for name, value in rows:
            table.add_row(name, value)
        console.print(table)


# ------------------------------------------------------------------ iterate
def _iterate_with_progress(part, arm, state, omegas: list[float], model: str) -> Orbit:
    """:func:`throwmap.iterate` with a Rich progress bar on stderr."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

    with Progress(TextColumn("throwing"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                  console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task("throwing", total=len(omegas))
        return iterate(part, arm, state, omegas, model=model,
                       progress=lambda done: bar.update(task, completed=done))


def _orbit_summary(orbit: Orbit, requested: int) -> dict:
    import numpy as np

    kinds = orbit.kinds
    per_side = {}
    for s in np.unique(orbit.side):
        xs = orbit.x[orbit.side == s]
        per_side[str(int(s))] = {"x_min": float(xs.min()), "x_max": float(xs.max()), "visits": int(xs.size)}
    return {
        "throws_requested": requested,
        "throws_done": orbit.n_throws,
        "status": orbit.status.label,
        "jogs": sum(k == "jog" for k in kinds),
        "flips": sum(k == "flip" for k in kinds),
        "final": {"x": float(orbit.x[-1]), "side": int(orbit.side[-1])},
        "escape": orbit.outcomes[-1].to_dict() if orbit.escaped else None,
        "per_side": per_side,
    }


@app.command("iterate")
def iterate_cmd(
    part: PartOpt,
    omega: Annotated[list[str], typer.Option("--omega", help="Release rate ω, rad/s: one value (with -n), or "
                                                             "one per throw (repeat the option or give a comma list).")],
    x: XOpt,
    side: SideOpt,
    n: Annotated[int | None, typer.Option("-n", "--n", help="Number of throws (required with a single ω).")] = None,
    h: HOpt = None,
    g: GOpt = None,
    length: LengthOpt = None,
    mu: MuOpt = None,
    model: ModelOpt = "paper",
    as_json: JsonOpt = False,
    plot: Annotated[Path | None, typer.Option("--plot", help="Write a figure of the orbit (e.g. orbit.png).")] = None,
) -> None:
    """Repeated throws from (x, side): an orbit of the throw map."""
    with _guard():
        check_model(model)
        the_part, arm = _part_and_arm(part, h, g, length, mu)
        _finite(x, "x")
        omegas = _floats(omega, "omega")
        if len(omegas) == 1:
            if n is None:
                raise InvalidStateError("n", "give -n/--n, the number of throws, with a single --omega")
            if n < 0:
                raise InvalidStateError("n", f"must be a non-negative integer, got {n}")
            omegas = omegas * n
        elif n is not None and n != len(omegas):
            raise InvalidStateError("n", f"got n = {n} but {len(omegas)} omegas")
        fmt = None
        if plot is not None:
            _check_output(plot, "plot")
            os.environ.setdefault("MPLBACKEND", "Agg")  # files only, never a window
            fmt = _plot_format(plot)
        if len(omegas) > PROGRESS_THRESHOLD:
            orbit = _iterate_with_progress(the_part, arm, (x, side), omegas, model)
        else:
            orbit = iterate(the_part, arm, (x, side), omegas, model=model)
        summary = _orbit_summary(orbit, len(omegas))
        if plot is not None:
            _save_figure(orbit.plot(part=the_part), plot, fmt, "plot")
        if as_json:
            doc = {**orbit.to_dict(), "summary": summary, "part": the_part.name, "arm": _arm_dict(arm),
                   "plot": str(plot) if plot is not None else None, "version": __version__}
            typer.echo(_to_json(doc))
            return
        from rich.console import Console
        from rich.markup import escape
        from rich.table import Table

        console = Console()
        console.print(escape(f"{the_part.name}: orbit from x = {_fmt(x)} m, side {side} (model {model!r})"),
                      soft_wrap=True)
        table = Table()
        table.add_column("quantity")
        table.add_column("value", justify="right")
        table.add_row("throws done", f"{summary['throws_done']} of {summary['throws_requested']}")
        table.add_row("status", summary["status"])
        table.add_row("jogs / flips", f"{summary['jogs']} / {summary['flips']}")
        table.add_row("final state", f"x = {_fmt(summary['final']['x'])} m, side {summary['final']['side']}")
        for s, band in summary["per_side"].items():
            table.add_row(f"side {s}: x min … max (m)",
                          f"{_fmt(band['x_min'])} … {_fmt(band['x_max'])} ({band['visits']} visits)")
        if plot is not None:
            table.add_row("figure", str(plot))
        console.print(table)


# ------------------------------------------------------------------ demo
@app.command("demo")
def demo_cmd(
    out: Annotated[Path, typer.Option("--out", help="Directory for the figures and summary.")] = Path("out"),
) -> None:
    """Run the built-in example (the paper's triangle) and write its figures and summary."""
    from ..studies import demo
    with _guard():
        if out.exists() and not out.is_dir():
            raise ConfigError("out", f"{out} exists and is not a directory")
        try:
            summary = demo.run_demo(out, progress=lambda msg: _stderr_line(f"demo: {msg}…"))
        except OSError as err:
            raise ConfigError("out", f"cannot write into {out}: {err.strerror or err}") from None
        files = summary.get("files", []) if isinstance(summary, dict) else []
        for f in files:
            typer.echo(f"wrote {f}")


# ------------------------------------------------------------------ compare
@app.command("compare")
def compare_cmd(
    part: PartOpt,
    h: HOpt = None,
    g: GOpt = None,
    length: LengthOpt = None,
    mu: MuOpt = None,
    omegas: Annotated[str | None, typer.Option("--omegas", help="Release rates, rad/s, comma list "
                                                                "(default: the library's).")] = None,
    n_x: Annotated[int | None, typer.Option("--n-x", help="Start positions per stable side.")] = None,
    models: Annotated[str | None, typer.Option("--models", help="Models to compare with 'paper', comma list "
                                                                "(default: the library's).")] = None,
    as_json: JsonOpt = False,
    out: Annotated[Path | None, typer.Option("--out", help="Also write the result: JSON if FILE ends in .json, "
                                                           "else the table as text.")] = None,
) -> None:
    """Accuracy of the small-angle models against the exact 'paper' model."""
    from ..studies import compare
    with _guard():
        the_part, arm = _part_and_arm(part, h, g, length, mu)
        kwargs: dict[str, Any] = {}
        if omegas is not None:
            oms = _floats(omegas, "omegas")
            for w in oms:
                if w < 0:
                    raise InvalidStateError("omegas", f"must be ≥ 0 (the arm throws upward), got {w:g}")
            kwargs["omegas"] = tuple(oms)
        if n_x is not None:
            if n_x < 1:
                raise InvalidStateError("n_x", f"must be a positive integer, got {n_x}")
            kwargs["n_x"] = n_x
        if models is not None:
            kwargs["models"] = tuple(check_model(m.strip()) for m in models.split(","))
        if out is not None:
            _check_output(out, "out")
        result = compare.compare_models(the_part, arm, **kwargs)
        doc = {**result.to_dict(), "arm": _arm_dict(arm), "version": __version__}
        if out is not None:
            _write_text(out, _to_json(doc) + "\n" if out.suffix.lower() == ".json" else result.table() + "\n", "out")
        typer.echo(_to_json(doc) if as_json else result.table())


# ------------------------------------------------------------------ validate
@app.command("validate")
def validate_cmd(
    part: Annotated[list[str] | None, typer.Option("--part", help="Part(s) to validate (repeatable; default: "
                                                                   "triangle, triangle+lead, rectangle+lead, square, "
                                                                   "pentagon).")] = None,
    n: Annotated[int, typer.Option("--n", help="Random throws in all (spread over the parts), besides the grid.")] = 400,
    grid: Annotated[bool, typer.Option("--grid/--no-grid", help="Also throw a grid per part.")] = True,
    engines: Annotated[str, typer.Option("--engines", help="Engines, comma list: pymunk (reference), mujoco.")] = "pymunk",
    models: Annotated[str, typer.Option("--models", help="Analytic models, comma list.")] = "paper,small_angle,rigid_body",
    mu: Annotated[float, typer.Option("--mu", help="Arm–part friction μ of the validation set.")] = 1.5,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the random cases.")] = 0,
    workers: Annotated[int, typer.Option("--workers", help="Engine processes (0: one per core).")] = 0,
    realisations: Annotated[int, typer.Option("--realisations", help="Also compare finite arm motions with the "
                                                                     "impulse on this many throws (0: skip).")] = 40,
    out: Annotated[Path, typer.Option("--out", help="Directory for validation.json and validation.md.")] = Path("out"),
    as_json: JsonOpt = False,
) -> None:
    """Analytic models against full rigid-body simulation: side agreement, |Δx|, where assumptions fail."""
    from ..studies.validation import default_parts, validate

    with _guard():
        if n < 0:
            raise InvalidStateError("n", f"must be ≥ 0, got {n}")
        if realisations < 0:
            raise InvalidStateError("realisations", f"must be ≥ 0, got {realisations}")
        if n == 0 and not grid:
            raise InvalidStateError("n", "nothing to throw: give --n > 0 or --grid")
        eng = tuple(e.strip() for e in engines.split(",") if e.strip())
        for e in eng:
            if e not in ("pymunk", "mujoco"):
                raise InvalidStateError("engines", f"unknown engine {e!r} (choose from pymunk, mujoco)")
        if "pymunk" not in eng:
            eng = ("pymunk",) + eng
        mods = tuple(check_model(m.strip()) for m in models.split(",") if m.strip())
        if "engine" in mods:
            raise InvalidStateError("models", "'engine' is the reference; list analytic models only")
        _finite(mu, "mu")
        if mu < 0:
            raise InvalidStateError("mu", f"must be ≥ 0, got {mu:g}")
        if out.exists() and not out.is_dir():
            raise ConfigError("out", f"{out} exists and is not a directory")
        if part:
            parts = {}
            builtin = default_parts()
            for name in part:
                parts[name] = builtin[name] if name in builtin else resolve_part(name).part
        else:
            parts = None
        if "mujoco" in eng:
            import importlib.util

            if importlib.util.find_spec("mujoco") is None:
                raise ConfigError("engines", "MuJoCo is not installed: pip install 'throwmap[mujoco]'")
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

        with Progress(TextColumn("engine throws"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                      console=Console(stderr=True), transient=True) as bar:
            task = bar.add_task("engine", total=None)
            report = validate(parts, n=n, seed=seed, grid=grid, models=mods, engines=eng, mu=mu, workers=workers,
                              progress=lambda done, total: bar.update(task, completed=done, total=total),
                              n_realisations=realisations)
        try:
            out.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise ConfigError("out", f"cannot create {out}: {err.strerror or err}") from None
        doc = {**report.to_dict(), "version": __version__}
        _write_text(out / "validation.json", _to_json(doc) + "\n", "out")
        md = (f"# throwmap validation ({report.settings['n_throws']} throws, seed {seed}, μ = {mu:g})\n\n"
              + report.table() + "\n\n" + "\n".join(f"- {g}" for g in report.goal_lines()) + "\n"
              + ("\n" + report.realisation_table() + "\n" if report.realisation_rows else ""))
        _write_text(out / "validation.md", md, "out")
        if as_json:
            typer.echo(_to_json(doc))
            return
        typer.echo(report.table())
        for line in report.goal_lines():
            typer.echo(line)
        if report.realisation_rows:
            typer.echo("")
            typer.echo(report.realisation_table())
        typer.echo(f"wrote {out / 'validation.json'}, {out / 'validation.md'}")


from .animate import register as _register_animate  # noqa: E402  (`throwmap animate` lives in its own module)

_register_animate(app)

from .analysis import register as _register_analysis  # noqa: E402  (`limitset`, `basins`, `funnels`)

_register_analysis(app)


# ------------------------------------------------------------------ entry
def main(argv: list[str] | None = None) -> None:
    """Console entry point (``throwmap``, ``python -m throwmap``)."""
    app(args=argv, prog_name="throwmap")


if __name__ == "__main__":  # pragma: no cover
    main()
