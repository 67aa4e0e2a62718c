"""Ctrl-C during an engine run: deferred to a safe point between pymunk steps.

pymunk calls Python from C (collision callbacks, the friction hook); an exception raised inside such a callback is
printed ("Exception ignored from cffi callback") and dropped, so a KeyboardInterrupt that Python's default SIGINT
handler raises there was lost and a long Monte Carlo run went on to the end. While a run is in progress
:func:`deferred_interrupts` replaces the default handler by one that only sets a flag; :func:`check` (called by the
stepping loop after every batch of steps) raises KeyboardInterrupt at a safe point, and leaving the block raises it
if it is still pending. Nothing changes where SIGINT is not Python's default (worker processes that ignore it, a
program's own handler) or off the main thread.
"""

from __future__ import annotations

import signal
import threading
from contextlib import contextmanager

__all__ = ["deferred_interrupts", "check"]

_PENDING = [False]


def _defer(signum, frame) -> None:
    _PENDING[0] = True


def check() -> None:
    """Raise KeyboardInterrupt if a Ctrl-C arrived during the run (and clear it)."""
    if _PENDING[0]:
        _PENDING[0] = False
        raise KeyboardInterrupt


@contextmanager
def deferred_interrupts():
    """Defer SIGINT to :func:`check` for the block (main thread with Python's default handler only)."""
    if threading.current_thread() is not threading.main_thread() or \
            signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        yield
        return
    previous = signal.signal(signal.SIGINT, _defer)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
    check()
