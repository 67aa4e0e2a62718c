"""How much the engine's answer depends on its friction cap: where the reference itself is uncertain.

pymunk's solver needs the per-contact friction cap min(μ, CAP K_nn/|K_nt|) (:mod:`throwmap.engine.pymunk.friction`,
CAP = 0.7) to converge; where a contact slides at the cap while the true μ would hold it, the engine answers for
a lower friction than the part has. :func:`cap_sensitive` measures that with the engine alone: it throws again
with CAP = :data:`CAP_ALT` and marks the throws whose answer moves by more than :data:`MOVED` (or changes side or
status). Those throws are no 0.5 mm reference for an exact model; :func:`~throwmap.studies.tilt_wall.compare_rows`
reports agreement with and without them.
"""

from __future__ import annotations

import contextlib

import numpy as np

CAP_ALT = 0.9
"""The relaxed cap of the second engine run (the solver still converges at 0.9; it diverges as CAP → 1)."""
MOVED = 0.25e-3
"""An engine answer that moves by more than this (m; half the 0.5 mm agreement) when its cap is relaxed is cap-bound."""

__all__ = ["CAP_ALT", "MOVED", "cap_sensitive", "friction_cap"]


@contextlib.contextmanager
def friction_cap(value: float):
    """The engine's friction cap set to ``value`` inside the block (this process only), restored after it."""
    from ..engine.pymunk import friction

    old = friction.CAP
    friction.CAP = float(value)
    try:
        yield
    finally:
        friction.CAP = old


def cap_sensitive(ref: dict, alt: dict) -> np.ndarray:
    """Throw by throw: whether the engine's answer ``ref`` (CAP 0.7) and ``alt`` (CAP :data:`CAP_ALT`) differ — a
    different status or side, or |Δx| > :data:`MOVED`; an ``alt`` run that was refused counts as sensitive (the
    reference there is not shown to be stable). ``ref``/``alt``: dicts of arrays ``x``, ``side``, ``status``."""
    same = (ref["status"] == alt["status"]) & (ref["side"] == alt["side"])
    moved = np.abs(np.asarray(ref["x"], float) - np.asarray(alt["x"], float)) > MOVED
    return ~same | moved
