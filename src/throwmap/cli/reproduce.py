"""``throwmap reproduce --out DIR [--quick] [--workers W] [--only KEY,…]``: the draft reproduced in one command.

A thin shell over :func:`throwmap.reproduce.reproduce`: every figure with an analogue, the four experiments
(≥ 200 engine trials each; ``--quick``: 3, a smoke run), ``report.md``/``report.html``/``report.json`` in DIR.
Prints the experiments table and where the reports went; exit 1 if a piece failed (it is in the report with its
reason), 2 on bad input (one ``error: <field>: <reason>`` line). A rerun resumes the experiments' kept trials;
Ctrl-C stops with one line ``interrupted: …`` saying what DIR keeps, and exit 130.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from .options import (check_out_dir, guard, progress_bar, stderr_line, stored_lines,
                      strict_int)

__all__ = ["register", "reproduce_cmd"]


def reproduce_cmd(
    out: Annotated[Path, typer.Option("--out", help="Directory for the figures, the experiments' trials and the "
                                                    "reports.")] = Path("reproduce"),
    quick: Annotated[bool, typer.Option("--quick", help="3 trials per experiment and no engine checks beside the "
                                                        "figures (a smoke run, minutes).")] = False,
    workers: Annotated[int, typer.Option("--workers", parser=strict_int, metavar="INTEGER",
                                         help="Processes for the experiments (0: all cores).")] = 0,
    only: Annotated[str | None, typer.Option("--only", help="Comma list of figure/experiment keys to make "
                                                            "(default: all).")] = None,
) -> None:
    """Reproduce the draft: its figures' analogues and its four experiments (ours vs the draft's) in one report."""
    from ..reproduce import reproduce
    from ..reproduce.report import HEAD, experiment_rows

    with guard():
        check_out_dir(out)
        keys = [k.strip() for k in only.split(",") if k.strip()] if only is not None else None
        if keys == []:
            from ..errors import InvalidStateError

            raise InvalidStateError("only", "is empty: give figure/experiment keys (comma list) or leave it out")
        try:
            with progress_bar("reproduce") as bar:
                def say(msg, done=None, total=None):
                    if done is None:
                        stderr_line(f"reproduce: {msg}…")
                    else:
                        bar(done, total)

                rep = reproduce(out, size="quick" if quick else "full", workers=workers, only=keys, progress=say)
        except KeyboardInterrupt:
            figures = len(list((out / "figures").glob("*.png")))
            stderr_line(f"interrupted: {figures} figure(s) and {stored_lines(out, 'experiments/*/trials.jsonl')} "
                        f"trial(s) stored in {str(out)!r}; the same command resumes the trials")
            raise typer.Exit(130) from None
        typer.echo(f"reproduced ({rep.size}) in {rep.elapsed_s / 60:.1f} min: {len(rep.figures)} figures, "
                   f"{len(rep.experiments)} experiments")
        for row in experiment_rows(rep):
            typer.echo(" | ".join(f"{h}: {c}" for h, c in zip(HEAD, row) if c))
        for name in ("report.md", "report.html", "report.json"):
            typer.echo(f"wrote {out / name}")
        if rep.failed:
            typer.echo(f"failed: {', '.join(rep.failed)} (reasons in the report)", err=True)
    if rep.failed:
        raise typer.Exit(1)


def register(app: typer.Typer) -> None:
    """Add the ``reproduce`` command to ``app``."""
    app.command("reproduce")(reproduce_cmd)
