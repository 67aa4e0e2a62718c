"""The caps of the recurrence test, as one value (paper Sec. III-D; Attractors.jl's documented keywords).

:class:`RecurrenceCaps` holds every safety cap and tolerance of the search for
forward limit sets (:mod:`throwmap.analysis.recurrence`) with its default and unit.
The analysis functions take it as ``caps=`` and, for existing code, also accept the
same names as keywords (``limit_set(..., transient=50)``), merged with
:func:`dataclasses.replace`; a keyword given as ``None`` keeps the default.

:func:`split_options` separates those cap keywords from the throw options of a
:class:`~throwmap.analysis.maps.ThrowMap` and refuses anything else.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown

__all__ = ["RecurrenceCaps", "DEFAULT_CAPS", "check_caps", "resolve_caps", "split_options", "check_int",
           "check_length"]


def check_int(name: str, v, lo: int) -> int:
    """``v`` as an int ≥ ``lo``; bools and floats refused with a one-line error naming ``name``."""
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
        raise InvalidStateError(name, f"must be an integer ≥ {lo}, got {shown(v)}")
    return int(v)


def check_length(name: str, v) -> float:
    """``v`` as a positive length in m (int or float; bools, nan and inf refused)."""
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
        raise InvalidStateError(name, f"must be a positive length in m, got {shown(v)}")
    return float(v)


def _pos_cap(name: str, v) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) or not (
        math.isfinite(float(v)) and float(v) > 0
    ):
        raise InvalidStateError(name, f"must be a positive finite length in m, got {shown(v)}")
    return float(v)


@dataclass(frozen=True, slots=True)
class RecurrenceCaps:
    """Every cap of the recurrence test, with its default (see :mod:`throwmap.analysis.recurrence`).

    Attributes
    ----------
    transient : int
        Throws (map steps) discarded before recording, and per extension block (200).
    max_transient : int
        Most throws discarded in all while the recorded tails are not yet stationary,
        still converging or leaking (5000); at least ``transient``. When ``transient`` is
        given without it (:meth:`replace`, so every ``transient=`` keyword and the CLI's
        ``--transient``), it becomes ``max(5000, 3 × transient + 2 × n_record)``: room for
        two extension blocks after the first transient.
    n_record : int
        Throws recorded per orbit (400); at least 2 × ``max_period``.
    tol : float
        Recurrence and cycle-identity tolerance, m (1e-8).
    max_period : int
        Longest cycle looked for, throws (32).
    cell : float
        Band orbits sharing a cell of this size on a side are one attractor, m (1e-3).
    band_gap : float
        A band's recorded points further apart than this start a new interval, m (2e-3).
    fd_step : float
        Finite-difference step for slopes (multipliers, Lyapunov exponents), m (1e-6).
    n_fill : int
        Throws per round that fill a band's sampling gaps with images of its intervals (2000).
    fill_rounds : int
        Such rounds (2).

    Invalid values raise :class:`~throwmap.errors.InvalidStateError` naming the cap.
    """

    transient: int = 200
    max_transient: int = 5000
    n_record: int = 400
    tol: float = 1e-8
    max_period: int = 32
    cell: float = 1e-3
    band_gap: float = 2e-3
    fd_step: float = 1e-6
    n_fill: int = 2000
    fill_rounds: int = 2

    def __post_init__(self):
        put = object.__setattr__
        put(self, "transient", check_int("transient", self.transient, 0))
        put(self, "n_record", check_int("n_record", self.n_record, 2))
        put(self, "max_period", check_int("max_period", self.max_period, 1))
        put(self, "max_transient", check_int("max_transient", self.max_transient, self.transient))
        put(self, "n_fill", check_int("n_fill", self.n_fill, 0))
        put(self, "fill_rounds", check_int("fill_rounds", self.fill_rounds, 0))
        if self.n_record < 2 * self.max_period:
            raise InvalidStateError("n_record", f"must be at least 2 × max_period = {2 * self.max_period}, "
                                                f"got {self.n_record}")
        for k in ("tol", "cell", "band_gap", "fd_step"):
            put(self, k, _pos_cap(k, getattr(self, k)))

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The caps' names, in field order."""
        return tuple(f.name for f in dataclasses.fields(cls))

    def replace(self, **overrides) -> "RecurrenceCaps":
        """A copy with ``overrides`` (``None`` keeps the current value); unknown names refused."""
        names = self.names()
        for k in overrides:
            if k not in names:
                raise InvalidStateError(k, f"unknown cap (caps: {', '.join(names)})")
        given = {k: v for k, v in overrides.items() if v is not None}
        if "transient" in given and "max_transient" not in given:
            # raising the transient raises its ceiling with it, leaving room for two extension
            # blocks (transient + n_record each) as the defaults do; invalid values are refused below
            t, r = given["transient"], given.get("n_record", self.n_record)
            if all(not isinstance(v, bool) and isinstance(v, (int, np.integer)) for v in (t, r)):
                given["max_transient"] = max(self.max_transient, 3 * int(t) + 2 * int(r))
        return dataclasses.replace(self, **given) if given else self

    def to_dict(self) -> dict:
        """``{name: value}`` in field order (plain ints and floats, JSON-ready)."""
        return {k: getattr(self, k) for k in self.names()}

    @classmethod
    def from_dict(cls, d: Mapping) -> "RecurrenceCaps":
        """From :meth:`to_dict` (or a result's ``caps`` record: ``transient_used`` is ignored)."""
        return cls().replace(**{k: v for k, v in d.items() if k != "transient_used"})


DEFAULT_CAPS = RecurrenceCaps().to_dict()
"""Every cap of the recurrence test with its default, as a dict (see :class:`RecurrenceCaps`)."""


def check_caps(**caps) -> dict:
    """Validate the recurrence caps (defaults from :data:`DEFAULT_CAPS`); one-line errors name the cap."""
    caps.pop("transient_used", None)  # a record of a past run, not a cap
    return RecurrenceCaps().replace(**caps).to_dict()


def resolve_caps(caps, overrides: Mapping | None = None) -> RecurrenceCaps:
    """``caps`` (a :class:`RecurrenceCaps`, a mapping of caps, or None for the defaults) with ``overrides`` merged."""
    if caps is None:
        caps = RecurrenceCaps()
    elif isinstance(caps, Mapping):
        caps = RecurrenceCaps.from_dict(caps)
    elif not isinstance(caps, RecurrenceCaps):
        raise InvalidStateError("caps", f"must be a RecurrenceCaps, got {type(caps).__name__}")
    return caps.replace(**overrides) if overrides else caps


def split_options(options: Mapping, takes_throw_options: bool) -> tuple[dict, dict]:
    """Split keywords into recurrence caps and throw options.

    Returns ``(cap_overrides, throw_options)``. When the map is given ready-made
    (``takes_throw_options`` False) any keyword that is not a cap is refused, naming it;
    otherwise it is left to :func:`throwmap.throw_batch` to accept or refuse.
    """
    names = RecurrenceCaps.names()
    caps = {k: v for k, v in options.items() if k in names}
    rest = {k: v for k, v in options.items() if k not in names}
    if rest and not takes_throw_options:
        k = next(iter(rest))
        raise InvalidStateError(k, f"unknown keyword: not a recurrence cap ({', '.join(names)}), and a "
                                   "configuration map given as the part takes no throw options")
    return caps, rest
