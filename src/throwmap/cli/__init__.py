"""The command line: ``throwmap …`` (Typer + Rich), a thin shell over the library.

:mod:`~throwmap.cli.app` builds the app from the command modules
(:mod:`~throwmap.cli.throws`, :mod:`~throwmap.cli.studies`, :mod:`~throwmap.cli.animate`,
:mod:`~throwmap.cli.analysis`), which share :mod:`~throwmap.cli.options`.
"""

from .app import app, main

__all__ = ["app", "main"]
