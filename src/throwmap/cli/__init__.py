"""The command line: ``throwmap …`` (Typer + Rich), a thin shell over the library."""

from .app import app, main

__all__ = ["app", "main"]
