"""The ``throwmap`` command line: a thin shell over the library.

This module only builds the Typer app: the ``--version`` option and the command groups,
each in its own module and each registering its commands here:

================================  ==============================================
:mod:`throwmap.cli.throws`        ``throw``, ``iterate``
:mod:`throwmap.cli.studies`       ``demo``, ``compare``, ``validate``
:mod:`throwmap.cli.animate`       ``animate``
:mod:`throwmap.cli.analysis`      ``limitset``, ``basins``, ``funnels``
:mod:`throwmap.cli.continuation`  ``continuation``
================================  ==============================================

Each subcommand parses its options, builds the part and arm, calls one library
function and prints (or writes) the result; there is no physics here. What the
commands share (options, parsing, the one-line ``error: <field>: <reason>`` with exit
status 2, strict JSON and atomic writes) is in :mod:`throwmap.cli.options`; the option
parser's own usage errors (a non-number, an unknown option or command, a missing
option) get the same one line through :class:`~throwmap.cli.usage.ThrowmapGroup`.
Imports point one way: ``app`` → command modules → ``options`` → the library.
"""

from __future__ import annotations

from typing import Annotated

import typer

from ..version import __version__
from . import analysis, animate, assemble, chain, continuation, control, design, experiment, feeder, plan, reproduce, statics, studies, sweep, throws, view
from .usage import ThrowmapGroup

__all__ = ["app", "main"]

app = typer.Typer(
    name="throwmap",
    cls=ThrowmapGroup,  # usage errors as one `error: <field>: <reason>` line, exit 2
    help="Throw maps of planar parts on a one-joint throwing arm (SI units: m, kg, s, rad).",
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
)


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


for _group in (throws, studies, animate, analysis, continuation, experiment, design, feeder, control, plan, statics, assemble, reproduce, view, sweep, chain):  # the order of `throwmap --help`
    _group.register(app)


def main(argv: list[str] | None = None) -> None:
    """Run the command line on ``argv`` (None: the process's arguments). The ``throwmap`` console script and
    ``python -m throwmap`` call it through :func:`_throwmap_entry.main`, which also turns a Ctrl-C that comes while
    this module is still being imported into one line and exit status 130."""
    app(args=argv, prog_name="throwmap")


if __name__ == "__main__":  # pragma: no cover
    main()
