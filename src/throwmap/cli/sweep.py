"""``throwmap sweep``: a grid or random design over an experiment's or an analysis's parameters, on Dask.

::

    throwmap sweep SWEEP.toml [--out DIR] [--scheduler ADDRESS] [--workers N] [--status] [--json]
                   [--stop-after K] [--connect-timeout S] [--max-time S] [--max-memory GB] [--force]

A thin shell over :func:`throwmap.sweeps.run_sweep`. ``SWEEP.toml`` is validated first
(:class:`throwmap.sweeps.SweepSpec`; every design point's config too), then the points missing from
``--out`` (default: ``runs/SWEEP.parquet/`` in the current folder, never beside the sweep file) are computed on a local Dask cluster of
``--workers`` processes (0: all cores) or on the cluster whose scheduler is at ``--scheduler``, one
Parquet part per chunk of points. Run it again after an interruption: only the missing points are
computed; Ctrl-C stops a run with one line ``interrupted: N rows stored …`` and exit 130. ``--status`` prints what is stored and missing and computes nothing. The last line (or, with
``--json``, one JSON object) gives the rows before, the points computed now and the rows after.
Before ``--out`` is written or a cluster started, the missing points' memory and time are estimated (a sample
of them timed in this process); above ``--max-memory`` / ``--max-time`` the sweep is refused unless ``--force``.
Errors: one ``error: <field>: <reason>`` line on stderr, exit 2.
"""

from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path
from typing import Annotated

import typer

from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, cli_limits
from .options import (ForceOpt, JsonOpt, MaxMemoryOpt, MaxTimeOpt, check_out_dir, guard, stderr_line, strict_int,
                      to_json)

__all__ = ["register", "sweep_cmd"]


@contextmanager
def _bar(label: str):
    """``update(done, total)`` drawing a Rich bar on stderr (a no-op off a terminal)."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

    console = Console(stderr=True)
    if not console.is_terminal:
        yield lambda done, total: None
        return
    with Progress(TextColumn(label), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(), console=console,
                  transient=True) as bar:
        task = bar.add_task(label, total=None)
        yield lambda done, total: bar.update(task, completed=done, total=total)


def sweep_cmd(
    sweep: Annotated[Path, typer.Argument(help="The sweep file (.toml; .json also read).", show_default=False)],
    out: Annotated[Path | None, typer.Option("--out", help="Directory of the Parquet parts and the manifest "
                                                           "(default: runs/SWEEP.parquet in the current folder).")] = None,
    scheduler: Annotated[str | None, typer.Option("--scheduler", metavar="ADDRESS",
                                                  help="A running Dask scheduler (tcp://host:8786); default: a "
                                                       "local cluster started for this run.")] = None,
    workers: Annotated[int, typer.Option("--workers", parser=strict_int, metavar="INTEGER",
                                         help="Local cluster: worker processes (0: all cores).")] = 0,
    status: Annotated[bool, typer.Option("--status", help="Print the rows stored and missing; compute nothing.")] = False,
    stop_after: Annotated[int | None, typer.Option("--stop-after", parser=strict_int, metavar="INTEGER",
                                                   help="Write at most this many parts, then stop (the rest stays "
                                                        "missing for a later run).")] = None,
    connect_timeout: Annotated[float, typer.Option("--connect-timeout", help="Seconds to wait for --scheduler.")] = 20.0,
    as_json: JsonOpt = False,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Run a sweep (grid or random design) of an experiment or an analysis on Dask; results as Parquet."""
    from ..errors import InvalidStateError
    from ..sweeps import read_sweep, run_sweep, sweep_status

    with guard():
        limits = cli_limits(max_memory, max_time, force)
        spec, _ = read_sweep(sweep)
        target = out if out is not None else Path("runs") / f"{sweep.stem}.parquet"  # a run folder, not the config's
        if scheduler is not None and not scheduler.strip():
            raise InvalidStateError("scheduler", "give an address (tcp://host:8786)")
        if status:
            st = sweep_status(spec, target)
            typer.echo(to_json(st.to_dict()) if as_json else st.table())
            return
        if out is None:
            target.parent.mkdir(exist_ok=True)  # the default run folder is made; a --out's parent must exist
        check_out_dir(target)
        try:
            with _bar(f"sweep {sweep.name}") as update:
                run = run_sweep(spec, target, scheduler=scheduler, workers=workers, progress=update,
                                stop_after=stop_after, connect_timeout=connect_timeout, limits=limits)
        except KeyboardInterrupt:
            from ..sweeps.store import count_rows

            try:
                rows = count_rows(target)
            except Exception:  # noqa: BLE001 - a part being written at the moment: say nothing wrong
                rows = "?"
            stderr_line(f"interrupted: {rows} rows stored in {str(target)!r}, rerun to resume")
            raise typer.Exit(130) from None
        typer.echo(to_json(run.to_dict()) if as_json else run.summary())


def register(app: typer.Typer) -> None:
    """Add the ``sweep`` command to ``app``."""
    app.command("sweep")(sweep_cmd)
