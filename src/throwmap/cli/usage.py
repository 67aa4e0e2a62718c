"""Usage errors as one line: the option parser's errors in the CLI's own format.

The option parser (Typer's Click) refuses a non-number for ``--h``, an unknown option,
a missing option or an unknown command before any ``throwmap`` code runs, and would
print a usage box. :class:`ThrowmapGroup` (the app's command group) catches those
errors and prints the same single line every other bad input gets,
``error: <field>: <reason>`` on stderr, with exit status 2. The field is the option's
name as the library spells its fields (``h``, ``side``, ``x_max`` for ``--x-max``), ``option`` for an unknown option, ``command``
for an unknown command, ``arguments`` for anything else.

A Ctrl-C that reaches the group (a command that keeps nothing as it goes) gets one line too,
``interrupted: …`` naming the files the command had written, and exit status 130.
"""

from __future__ import annotations

import difflib
import sys
from collections.abc import Sequence
from typing import Any

import typer
from typer.core import TyperGroup

try:  # Typer ≥ 0.25 ships its own copy of Click
    from typer._click import exceptions as _cx
except ImportError:  # pragma: no cover - older Typer on Click
    from click import exceptions as _cx

from .options import WRITTEN, kept_line, stderr_line

__all__ = ["ThrowmapGroup", "usage_line"]


def _flags_show_no_type() -> None:
    """Help pages list a flag (``--json``, ``--force``) without a type: Typer's Rich help shows ``<bool>`` beside it,
    which reads as if the flag took a value. Options that take one keep theirs."""
    from typer.core import TyperOption

    shown = getattr(TyperOption, "display_type_rich", None)
    if shown is None or getattr(shown, "_throwmap", False):  # an older Typer, or done already
        return

    def display_type_rich(self, ctx):
        return None if self.is_flag else shown(self, ctx)

    display_type_rich._throwmap = True
    TyperOption.display_type_rich = display_type_rich


_flags_show_no_type()


class UnknownCommand(_cx.UsageError):
    """A command name the app does not have (``name``; ``commands``: those it has)."""

    def __init__(self, name: str, commands: Sequence[str], ctx=None):
        super().__init__(f"No such command {name!r}.", ctx)
        self.name = name
        self.commands = tuple(commands)


def _field(opts: Sequence[str]) -> str:
    """An option's name as the library's fields spell it, from its longest spelling
    (``-n/--n`` → ``n``, ``--x-max`` → ``x_max``)."""
    return max(opts, key=len).lstrip("-").replace("-", "_") if opts else "arguments"


def _given(args: Sequence[str], opts: Sequence[str]) -> str | None:
    """The last value given on the command line for one of ``opts`` (``--h x`` or ``--h=x``)."""
    value = None
    args = list(args)
    for i, arg in enumerate(args):
        if arg == "--":
            break
        for opt in opts:
            if arg == opt and i + 1 < len(args):
                value = args[i + 1]
            elif arg.startswith(opt + "="):
                value = arg[len(opt) + 1:]
    return value


def _tidy(message: str) -> str:
    """The parser's own message as a reason: one line, ``must be …``, no trailing period."""
    text = " ".join(str(message).split())
    if text.startswith("Input should be"):
        text = "must be" + text[len("Input should be"):]
    text = text[:1].lower() + text[1:]
    return text.rstrip(".")


def _bad_value(err, args: Sequence[str]) -> tuple[str, str]:
    param = getattr(err, "param", None)
    opts = list(getattr(param, "opts", None) or [])
    field = _field(opts) if opts else (getattr(param, "name", None) or "arguments")
    raw = _given(args, opts) if opts else None
    message = str(err.message)
    low = message.lower()
    got = f", got {raw!r}" if raw is not None else ""
    if "valid integer" in low or "valid int" in low:
        return field, f"must be an integer{got}"
    if "valid number" in low or "valid float" in low:
        return field, f"must be a number{got}"
    if "valid bool" in low:
        return field, f"must be true or false{got}"
    return field, _tidy(message) + (got if raw is not None and repr(raw) not in message else "")


SUGGEST_CUTOFF = 0.6
"""Least :class:`difflib.SequenceMatcher` ratio, on option names without their dashes, for a suggestion."""


def _close_options(name: str, candidates) -> list[str]:
    """The options of ``candidates`` close to the unknown ``name``, compared without the leading
    dashes (the parser's own matching counts them, so ``--bogus`` would suggest ``--g``)."""
    bare = str(name).lstrip("-").lower()
    ratio = {c: difflib.SequenceMatcher(None, bare, str(c).lstrip("-").lower()).ratio() for c in candidates}
    return sorted((c for c, r in ratio.items() if r >= SUGGEST_CUTOFF), key=lambda c: (-ratio[c], c))


def usage_line(err, args: Sequence[str] = (), prog: str = "throwmap") -> tuple[str, str]:
    """``(field, reason)`` for a usage error of the option parser; ``args``: the command line."""
    ctx = getattr(err, "ctx", None)
    path = ctx.command_path if ctx is not None else prog
    if isinstance(err, UnknownCommand):
        close = difflib.get_close_matches(err.name, err.commands, n=1)
        hint = f"did you mean {close[0]!r}? " if close else ""
        return "command", f"unknown command {err.name!r} ({hint}commands: {', '.join(err.commands)})"
    if isinstance(err, _cx.MissingParameter):
        param = err.param
        opts = list(getattr(param, "opts", None) or [])
        field = _field(opts) if opts else (getattr(param, "name", None) or "arguments")
        spelled = f"option {max(opts, key=len)}" if opts else "argument"
        return field, f"required {spelled} is missing (see '{path} --help')"
    if isinstance(err, _cx.BadParameter):
        return _bad_value(err, args)
    if isinstance(err, _cx.NoSuchOption):
        name = err.option_name
        close = _close_options(name, err.possibilities or ())
        hint = f"did you mean {' or '.join(close)}? " if close else ""
        return "option", f"unknown option {name!r} for '{path}' ({hint}see '{path} --help')"
    if isinstance(err, _cx.BadOptionUsage):
        name = err.option_name
        reason = _tidy(err.message)
        if "requires an argument" in reason:
            reason = f"{name} needs a value"
        return _field([name]), reason
    return "arguments", f"{_tidy(err.format_message())} (see '{path} --help')"


class ThrowmapGroup(TyperGroup):
    """The app's command group: usage errors become one ``error: <field>: <reason>`` line, exit 2; a Ctrl-C
    one ``interrupted:`` line, exit 130."""

    def resolve_command(self, ctx, args):
        name = args[0] if args else None
        if name is not None and not name.startswith("-") and self.get_command(ctx, name) is None:
            raise UnknownCommand(name, self.list_commands(ctx), ctx)
        return super().resolve_command(ctx, args)

    def invoke(self, ctx):
        """Run the command; a Ctrl-C that no command handles itself (those keeping work as they go say what
        they keep) leaves one line on what was written and exit 130, never a traceback."""
        WRITTEN.clear()
        try:
            return super().invoke(ctx)
        except KeyboardInterrupt:
            stderr_line(kept_line())
            raise typer.Exit(130) from None

    def main(self, args: Sequence[str] | None = None, prog_name: str | None = None, complete_var: str | None = None,
             standalone_mode: bool = True, **extra: Any) -> Any:
        argv = list(sys.argv[1:] if args is None else args)
        try:
            rv = super().main(args=argv, prog_name=prog_name, complete_var=complete_var, standalone_mode=False,
                              **extra)
        except _cx.NoArgsIsHelpError:  # `throwmap` alone: the parser's own help, as before
            return super().main(args=argv, prog_name=prog_name, complete_var=complete_var,
                                standalone_mode=standalone_mode, **extra)
        except _cx.UsageError as err:
            field, reason = usage_line(err, argv, prog_name or "throwmap")
            stderr_line(f"error: {field}: {reason}")
            if not standalone_mode:
                return 2
            sys.exit(2)
        except typer.Abort:  # end of input at a prompt
            stderr_line("error: input: aborted")
            if not standalone_mode:
                return 1
            sys.exit(1)
        except _cx.ClickException as err:  # pragma: no cover - no command raises these
            stderr_line(f"error: {_tidy(err.format_message())}")
            if not standalone_mode:
                return err.exit_code
            sys.exit(err.exit_code)
        if not standalone_mode:
            return rv
        sys.exit(rv if isinstance(rv, int) else 0)
