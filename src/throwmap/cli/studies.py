"""``throwmap compare``, ``throwmap validate``, ``throwmap demo``, ``throwmap compile``: the studies on the command
line, and compiling the kernels ahead (:mod:`throwmap.warmup`).

A thin shell over :mod:`throwmap.studies`: :func:`~throwmap.studies.compare.compare_models`
(small-angle models against the exact ``paper`` model),
:func:`~throwmap.studies.validation.validate` (analytic models against rigid-body
simulation) and :func:`~throwmap.studies.demo.run_demo` (the paper's triangle, figures
and summary). Errors follow :mod:`throwmap.cli.options`: one ``error: <field>: <reason>``
line on stderr, exit 2.

The validation commands (``validate``, ``validate-fixtures``, ``validate-recoil``) print their tables; they
write their JSON and Markdown, and keep their cases for a resume, only in the directory given as ``--out DIR``
(without it nothing is written, as ``throwmap experiment`` without ``--out``).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Annotated, Any

import typer

from ..version import __version__
from ..errors import ConfigError, InvalidStateError
from ..system.starts import check_omega
from ..io.config import resolve_part
from ..throws.throw import check_model
from .options import (BackOpt, GOpt, HOpt, JsonOpt, LengthOpt, ModelOptionOpt, MuOpt, PartOpt, arm_dict, check_finite,
                      check_out_dir, check_output, guard, make_out_dir, model_options, parse_floats, part_and_arm,
                      interrupted_line, progress_bar, stderr_line,
                      strict_int, to_json, write_text)
from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, cli_limits as work_limits
from ..studies.study import StudyRun
from .options import ForceOpt, MaxMemoryOpt, MaxTimeOpt

__all__ = ["register", "demo_cmd", "compile_cmd", "compare_cmd", "validate_cmd", "validate_fixtures_cmd", "validate_recoil_cmd",
           "ENGINES"]

ENGINES = ("pymunk", "mujoco")
"""Engines ``validate`` can use; pymunk is the reference and always runs."""



# ------------------------------------------------------------------ demo
def demo_cmd(
    out: Annotated[Path, typer.Option("--out", help="Directory for the figures and summary.")] = Path("out"),
) -> None:
    """Run the built-in example (the paper's triangle) and write its figures and summary."""
    from ..studies import demo

    with guard():
        check_out_dir(out)
        _compile_if_cold("demo: ")
        try:
            result = demo.run_demo(out, progress=lambda msg: stderr_line(f"demo: {msg}…"))
        except OSError as err:
            raise ConfigError("out", f"cannot write into {out}: {err.strerror or err}") from None
        for f in getattr(result, "files", ()):
            typer.echo(f"wrote {f}")


def _compile_if_cold(prefix: str = "", force: bool = False) -> None:
    """Compile the kernels in parallel processes when their cache is empty (or ``force``), saying so on stderr."""
    from ..warmup import GROUPS, cold, compile_kernels

    if not (force or cold("rigid_body") or cold("paper")):
        return
    stderr_line(f"{prefix}compiling the kernels, once ({len(GROUPS)} groups in parallel processes, two minutes or "
                f"more)…")
    compile_kernels(progress=lambda name, done, total: stderr_line(f"{prefix}compiled {name} ({done}/{total})"))


def compile_cmd() -> None:
    """Compile the numerical kernels now (they are kept on disk): later commands start in seconds."""
    import time

    with guard():
        t = time.perf_counter()
        _compile_if_cold(force=True)
        typer.echo(f"kernels ready ({time.perf_counter() - t:.0f} s)")


# ------------------------------------------------------------------ compare
def _compare_kwargs(omegas: str | None, n_x: int | None, models: str | None, x_min: float | None = None,
                    x_max: float | None = None) -> dict[str, Any]:
    """The options of :func:`~throwmap.studies.compare.compare_models` given on the command line."""
    kwargs: dict[str, Any] = {}
    for name, value in (("x_min", x_min), ("x_max", x_max)):
        if value is not None:
            kwargs[name] = check_finite(value, name)
    if omegas is not None:
        oms = parse_floats(omegas, "omegas")
        kwargs["omegas"] = tuple(check_omega(w, "omegas") for w in oms)
    if n_x is not None:
        if n_x < 1:
            raise InvalidStateError("n_x", f"must be a positive integer, got {n_x}")
        kwargs["n_x"] = n_x
    if models is not None:
        kwargs["models"] = tuple(check_model(m.strip()) for m in models.split(","))
    return kwargs


def compare_cmd(
    part: PartOpt,
    h: HOpt = None,
    g: GOpt = None,
    length: LengthOpt = None,
    mu: MuOpt = None,
    back: BackOpt = None,
    omegas: Annotated[str | None, typer.Option("--omegas", help="Release rates, rad/s, comma list "
                                                                "(default: the library's).")] = None,
    n_x: Annotated[int | None, typer.Option("--n-x", parser=strict_int, metavar="INTEGER",
                                            help="Start positions per stable side.")] = None,
    models: Annotated[str | None, typer.Option("--models", help="Models to compare with 'paper', comma list "
                                                                "(default: the library's).")] = None,
    x_min: Annotated[float | None, typer.Option("--x-min", help="Starts from x > max(this, the side's smallest "
                                                                "resting x), m (default: the side's).")] = None,
    x_max: Annotated[float | None, typer.Option("--x-max", help="Starts up to this x, m (default: the arm length, "
                                                                "else the library's).")] = None,
    as_json: JsonOpt = False,
    out: Annotated[Path | None, typer.Option("--out", help="Also write the result: JSON if FILE ends in .json, "
                                                           "else the table as text.")] = None,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Accuracy of the small-angle models against the exact 'paper' model."""
    from ..studies import compare

    with guard():
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        kwargs = _compare_kwargs(omegas, n_x, models, x_min, x_max)
        limits = work_limits(max_memory, max_time, force)
        if out is not None:
            check_output(out, "out")
        result = compare.compare_models(the_part, arm, **kwargs, limits=limits)
        doc = {**result.to_dict(), "arm": arm_dict(arm), "version": __version__}
        if out is not None:
            write_text(out, to_json(doc) + "\n" if out.suffix.lower() == ".json" else result.table() + "\n", "out")
        typer.echo(to_json(doc) if as_json else result.table())


# ------------------------------------------------------------------ the studies on the runner
ResumeOpt = Annotated[bool, typer.Option("--resume/--no-resume", help="Reuse the cases stored in --out by an "
                                                                      "earlier (or interrupted) run of the same study.")]
WorkersOpt = Annotated[int, typer.Option("--workers", parser=strict_int, metavar="INTEGER",
                                         help="Processes (0: one per core).")]

AGREEMENT_HEADING = "## Agreement"
"""The heading of the agreement section that the studies' Markdown files end with."""


def _agreement_section(table: str) -> str:
    """The agreement section appended to a study's Markdown (after its own tables, which it leaves unchanged)."""
    from ..studies.agreement import DEFINITION

    return f"\n{AGREEMENT_HEADING}\n\n{DEFINITION[0].upper() + DEFINITION[1:]}.\n\n{table}\n" if table else ""


def _run_study(name: str, out: Path | None, call):
    """``call(update)`` with a progress bar on stderr; a Ctrl-C leaves one line saying how many cases ``out`` keeps
    (the same command resumes from them; None: that none was kept) and exits 130, as ``throwmap experiment`` does."""
    try:
        with progress_bar(name) as update:
            return call(update)
    except KeyboardInterrupt:
        stderr_line(interrupted_line(out, "case"))
        raise typer.Exit(130) from None


# ------------------------------------------------------------------ validate
def _validate_settings(n: int, grid: bool, engines: str, models: str, mu: float, realisations: int):
    """Check ``validate``'s numbers; the engines (pymunk first) and analytic models to run."""
    if n < 0:
        raise InvalidStateError("n", f"must be ≥ 0, got {n}")
    if realisations < 0:
        raise InvalidStateError("realisations", f"must be ≥ 0, got {realisations}")
    if n == 0 and not grid:
        raise InvalidStateError("n", "nothing to throw: give --n > 0 or --grid")
    eng = tuple(e.strip() for e in engines.split(",") if e.strip())
    for e in eng:
        if e not in ENGINES:
            raise InvalidStateError("engines", f"unknown engine {e!r} (choose from {', '.join(ENGINES)})")
    if "pymunk" not in eng:
        eng = ("pymunk",) + eng
    mods = tuple(check_model(m.strip()) for m in models.split(",") if m.strip())
    if "engine" in mods:
        raise InvalidStateError("models", "'engine' is the reference; list analytic models only")
    check_finite(mu, "mu")
    if mu < 0:
        raise InvalidStateError("mu", f"must be ≥ 0, got {mu:g}")
    return eng, mods


def _validation_parts(names: list[str] | None):
    """The parts named on the command line (validation set names, built-in names or files); ``None``: the default set."""
    from ..studies.validation import default_parts

    if not names:
        return None
    builtin = default_parts()
    return {name: builtin[name] if name in builtin else resolve_part(name).part for name in names}


def validate_cmd(
    part: Annotated[list[str] | None, typer.Option("--part", help="Part(s) to validate (repeatable; default: "
                                                                   "triangle, triangle+lead, rectangle+lead, square, "
                                                                   "pentagon).")] = None,
    n: Annotated[int, typer.Option("--n", parser=strict_int, metavar="INTEGER",
                                   help="Random throws in all (spread over the parts), besides the grid.")] = 400,
    grid: Annotated[bool, typer.Option("--grid/--no-grid", help="Also throw a grid per part.")] = True,
    engines: Annotated[str, typer.Option("--engines", help="Engines, comma list: pymunk (reference), mujoco.")] = "pymunk",
    models: Annotated[str, typer.Option("--models", help="Analytic models, comma list.")] = "paper,small_angle,rigid_body",
    mu: Annotated[float, typer.Option("--mu", help="Arm–part friction μ of the validation set.")] = 1.5,
    seed: Annotated[int, typer.Option("--seed", parser=strict_int, metavar="INTEGER",
                                      help="Seed of the random cases.")] = 0,
    workers: Annotated[int, typer.Option("--workers", parser=strict_int, metavar="INTEGER",
                                         help="Engine processes (0: one per core).")] = 0,
    realisations: Annotated[int, typer.Option("--realisations", parser=strict_int, metavar="INTEGER",
                                              help="Also compare finite arm motions with the "
                                                   "impulse on this many throws (0: skip).")] = 40,
    out: Annotated[Path | None, typer.Option("--out", help="Directory for validation.json and validation.md, and "
                                                           "the study's trials (a rerun resumes); without it nothing "
                                                           "is written.")] = None,
    resume: ResumeOpt = True,
    as_json: JsonOpt = False,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Analytic models against full rigid-body simulation: side agreement, |Δx|, where assumptions fail."""
    from ..studies.validation import validate

    with guard():
        if seed < 0:
            raise InvalidStateError("seed", f"must be a non-negative integer, got {seed}")
        eng, mods = _validate_settings(n, grid, engines, models, mu, realisations)
        limits = work_limits(max_memory, max_time, force)
        check_out_dir(out)
        parts = _validation_parts(part)
        if "mujoco" in eng:
            import importlib.util

            if importlib.util.find_spec("mujoco") is None:
                raise ConfigError("engines", "MuJoCo is not installed: pip install 'throwmap[mujoco]'")
        report = _run_study("validate", out, lambda update: validate(
            parts, n=n, seed=seed, grid=grid, models=mods, engines=eng, mu=mu, n_realisations=realisations,
            run=StudyRun(workers=workers, out=out, resume=resume, progress=update, limits=limits)))
        doc = {**report.to_dict(), "version": __version__}
        if out is not None:
            make_out_dir(out)
            write_text(out / "validation.json", to_json(doc) + "\n", "out")
            md = (f"# throwmap validation ({report.settings['n_throws']} throws, seed {seed}, μ = {mu:g})\n\n"
                  + report.table() + "\n\n" + "\n".join(f"- {g}" for g in report.goal_lines()) + "\n"
                  + ("\n" + report.realisation_table() + "\n" if report.realisation_rows else "")
                  + _agreement_section(report.agreement_table()))
            write_text(out / "validation.md", md, "out")
        if as_json:
            typer.echo(to_json(doc))
            return
        typer.echo(report.table())
        for line in report.goal_lines():
            typer.echo(line)
        if report.realisation_rows:
            typer.echo("")
            typer.echo(report.realisation_table())
        typer.echo("")
        typer.echo(report.agreement_table())
        if out is not None:
            typer.echo(f"wrote {out / 'validation.json'}, {out / 'validation.md'}")


# ------------------------------------------------------------------ validate-fixtures
def validate_fixtures_cmd(
    part: Annotated[list[str] | None, typer.Option("--part", help="Part(s) thrown (repeatable; default: the validate "
                                                                   "set).")] = None,
    n: Annotated[int, typer.Option("--n", parser=strict_int, metavar="INTEGER",
                                   help="Random throws per condition (each compared with the engine).")] = 500,
    seed: Annotated[int, typer.Option("--seed", parser=strict_int, metavar="INTEGER",
                                      help="Seed of the random throws (one child stream per condition).")] = 0,
    conditions: Annotated[str | None, typer.Option("--conditions", help="Conditions, comma list (default all): "
                                                   "'tilt, μ = ∞', 'tilt', 'wall, μ_w = 0', 'wall, μ_w = μ' — "
                                                   "or their short names tilt-inf, tilt, wall-0, wall-mu.")] = None,
    model_option: ModelOptionOpt = None,
    fixed_point: Annotated[bool, typer.Option("--fixed-point/--no-fixed-point",
                                              help="Also find the fixed point at the wall with limit_set and "
                                                   "check its multiplier.")] = True,
    workers: WorkersOpt = 0,
    out: Annotated[Path | None, typer.Option("--out", help="Directory for tilt_wall.json and tilt_wall.md, and the "
                                                           "study's trials (a rerun resumes); without it nothing is "
                                                           "written.")] = None,
    resume: ResumeOpt = True,
    as_json: JsonOpt = False,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Tilted arms and walls: rigid_body and paper against the engine, and the fixed point at the wall."""
    from ..studies.tilt_wall import CONDITIONS, validate_tilt_wall

    with guard():
        if n < 1:
            raise InvalidStateError("n", f"must be a positive integer, got {n}")
        if seed < 0:
            raise InvalidStateError("seed", f"must be a non-negative integer, got {seed}")
        conds = None
        if conditions is not None:
            short = {"tilt-inf": "tilt, μ = ∞", "tilt": "tilt", "wall-0": "wall, μ_w = 0", "wall-mu": "wall, μ_w = μ"}
            conds = []
            for c in (p.strip() for p in conditions.split(",") if p.strip()):
                c = short.get(c, c)
                if c not in CONDITIONS:
                    raise InvalidStateError("conditions", f"unknown condition {c!r} (choose from "
                                                          f"{', '.join(short)})")
                conds.append(c)
            if not conds:
                raise InvalidStateError("conditions", "is empty")
        rb = dataclasses.asdict(model_options(model_option, "rigid_body")["options"]) if model_option else {}
        limits = work_limits(max_memory, max_time, force)
        check_out_dir(out)
        parts = _validation_parts(part)
        report = _run_study("validate-fixtures", out, lambda update: validate_tilt_wall(
            parts, n=n, seed=seed, conditions=conds, rigid_body_options=rb, fixed_point=fixed_point,
            run=StudyRun(workers=workers, out=out, resume=resume, progress=update, limits=limits)))
        doc = {**report.to_dict(), "version": __version__}
        lines = [report.table(), "", *(f"- {g}" for g in report.goal_lines()), "",
                 *(f"- {c}" for c in report.cap_lines()), "",
                 *(f"- {w}" for w in report.refusal_lines()), "", *report.fixed_point_lines()]
        if out is not None:
            make_out_dir(out)
            write_text(out / "tilt_wall.json", to_json(doc) + "\n", "out")
            md = (f"# throwmap validate-fixtures ({n} throws per condition, seed {seed})\n\n" + "\n".join(lines)
                  + "\n" + _agreement_section(report.agreement_table()))
            write_text(out / "tilt_wall.md", md, "out")
        if as_json:
            typer.echo(to_json(doc))
            return
        for line in lines + ["", report.agreement_table()]:
            typer.echo(line)
        if out is not None:
            typer.echo(f"wrote {out / 'tilt_wall.json'}, {out / 'tilt_wall.md'}")


# ------------------------------------------------------------------ validate-recoil
def validate_recoil_cmd(
    n: Annotated[int, typer.Option("--n", parser=strict_int, metavar="INTEGER",
                                   help="Random recoil throws (each thrown by rigid_body and the engine).")] = 200,
    seed: Annotated[int, typer.Option("--seed", parser=strict_int, metavar="INTEGER",
                                      help="Seed of the random throws.")] = 0,
    impact_law: Annotated[str, typer.Option("--impact-law", help="rigid_body's impact law: velocity (the engine's) "
                                                                "or routh.")] = "velocity",
    engine_refine: Annotated[int, typer.Option("--engine-refine", parser=strict_int, metavar="INTEGER",
                                               help="The reference engine's steps are its defaults divided by this "
                                                    "(16: converged on impacts against the moving arm).")] = 16,
    workers: WorkersOpt = 0,
    out: Annotated[Path | None, typer.Option("--out", help="Directory for recoil_validation.json and .md, and the "
                                                           "study's trials (a rerun resumes); without it nothing is "
                                                           "written.")] = None,
    resume: ResumeOpt = True,
    as_json: JsonOpt = False,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """rigid_body on the moving arm (RecoilThrow, 3° recoil, ζ ∈ {0.2, 0.5}) against the engine, and against the impulse."""
    from ..studies.recoil_validation import recoil_table, validate_recoil

    with guard():
        if n < 1:
            raise InvalidStateError("n", f"must be a positive integer, got {n}")
        if impact_law not in ("routh", "velocity"):
            raise InvalidStateError("impact_law", f"must be 'routh' or 'velocity', got {impact_law!r}")
        if engine_refine < 1:
            raise InvalidStateError("engine_refine", f"must be a positive integer, got {engine_refine}")
        if seed < 0:
            raise InvalidStateError("seed", f"must be a non-negative integer, got {seed}")
        limits = work_limits(max_memory, max_time, force)
        check_out_dir(out)
        report = _run_study("validate-recoil", out, lambda update: validate_recoil(
            n=n, seed=seed, impact_law=impact_law, engine_refine=engine_refine,
            run=StudyRun(workers=workers, out=out, resume=resume, progress=update, limits=limits)))
        doc = {**report.to_dict(), "version": __version__}
        if out is not None:
            make_out_dir(out)
            write_text(out / "recoil_validation.json", to_json(doc) + "\n", "out")
            md = (f"# throwmap validate-recoil ({n} throws, seed {seed}, impact law {impact_law}, engine steps / "
                  f"{engine_refine})\n\n" + recoil_table(report) + "\n"
                  + _agreement_section(report.agreement_table()))
            write_text(out / "recoil_validation.md", md, "out")
        if as_json:
            typer.echo(to_json(doc))
            return
        typer.echo(recoil_table(report))
        typer.echo("")
        typer.echo(report.agreement_table())
        if out is not None:
            typer.echo(f"wrote {out / 'recoil_validation.json'}, {out / 'recoil_validation.md'}")


def register(app: typer.Typer) -> None:
    """Add the ``demo``, ``compile``, ``compare``, ``validate``, ``validate-fixtures`` and ``validate-recoil`` commands to ``app``."""
    app.command("demo")(demo_cmd)
    app.command("compile")(compile_cmd)
    app.command("compare")(compare_cmd)
    app.command("validate")(validate_cmd)
    app.command("validate-fixtures")(validate_fixtures_cmd)
    app.command("validate-recoil")(validate_recoil_cmd)
