"""The ``throwmap`` console script: the command line, where a Ctrl-C at any moment ends the run with one line
on stderr and exit status 130, never a traceback, while its modules are still being imported too.

This module sits outside the ``throwmap`` package on purpose: importing anything from the package first runs the
package's ``__init__`` (NumPy, SciPy, the models), which takes most of the start-up time, so the ``try`` has to
begin before that import. It imports only :mod:`sys` and :mod:`signal` itself. Once the command line runs, its
own handlers say what each command kept (:mod:`throwmap.cli.usage`); an interruption outside them (before the
command starts, or as it exits) gets the same one-line form here.
"""

from __future__ import annotations

import signal
import sys

__all__ = ["main", "INTERRUPTED"]

INTERRUPTED = 130
"""Exit status after a Ctrl-C (128 + SIGINT), as a shell reports it."""


def _interrupted() -> None:
    """Leave one ``interrupted:`` line and exit 130; a second Ctrl-C meanwhile is ignored."""
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    except (ValueError, OSError):  # pragma: no cover - not the main thread
        pass
    options = sys.modules.get("throwmap.cli.options")  # what the command wrote, if it got that far (never imported here)
    try:
        line = options.kept_line() if options is not None else "interrupted: nothing was written"
    except Exception:  # noqa: BLE001 - a half-imported module: say the plain thing
        line = "interrupted: nothing was written"
    try:
        sys.stderr.write(line + "\n")
        sys.stderr.flush()
    except (OSError, ValueError):  # pragma: no cover - stderr closed
        pass
    raise SystemExit(INTERRUPTED)


def main(argv: list[str] | None = None) -> None:
    """Console entry point (``throwmap``): import the command line and run it with ``argv`` (None: the process's
    arguments); a Ctrl-C at any moment exits 130 with one line."""
    try:
        from throwmap.cli.app import main as cli_main

        cli_main(argv)
    except KeyboardInterrupt:
        _interrupted()


if __name__ == "__main__":  # pragma: no cover
    main()
