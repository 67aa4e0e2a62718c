"""One-bit sensors for feedback throwing (paper Sec. IV-A).

The draft's controller needs two one-bit sensors — "the part is on side i_f" and "the part is
within ε of x_f" — which its camera provided. Here a sensor is an immutable value that, given the
part's true resting configuration ``(x, side)`` (m, side index) and a generator, returns one bit:

* :class:`SideSensor` ``(side)``: the part rests on side ``side``;
* :class:`BeyondSensor` ``(x)``: the CM abscissa is beyond ``x`` (m);
* :class:`WithinSensor` ``(x_f, eps)``: the CM abscissa is within ``eps`` of ``x_f`` (m);
* :class:`PositionSensor` ``(sigma)``: not one bit — an estimate ``(x + σ N(0, 1), side)`` for the
  model-based controllers (:class:`~throwmap.control.controllers.InverseJogController`,
  :class:`~throwmap.control.controllers.FunnelController`).

Errors: a one-bit sensor reads 1 where the truth is 0 with probability ``false_positive`` and 0
where it is 1 with probability ``false_negative``, independently at every read (a fresh look of
the camera). Position sensors may also blur the abscissa they threshold, ``sigma`` (m), and have
``hysteresis`` (m): once a :class:`BeyondSensor` has read 1 it keeps reading 1 until the part is
``hysteresis`` short of ``x``; a :class:`WithinSensor` that read 1 widens its window by
``hysteresis`` (a Schmitt trigger). The previous reading is passed in as ``last`` (None: none).
A side sensor has no hysteresis (its truth is discrete).

Every read draws exactly one uniform and one normal from ``rng``, whatever the rates, so the stream a
trial uses does not depend on the sensor settings.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown

__all__ = ["SideSensor", "BeyondSensor", "WithinSensor", "PositionSensor", "SENSOR_TYPES"]


def _rate(value, field: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value) or not 0.0 <= value < 1.0:
        raise InvalidStateError(field, f"must be a probability in [0, 1), got {shown(value)}")
    return float(value)


def _length(value, field: str, *, positive: bool = False, signed: bool = False) -> float:
    ok = not isinstance(value, bool) and isinstance(value, (int, float, np.integer, np.floating)) \
        and math.isfinite(value)
    if ok and not signed:
        ok = value > 0 if positive else value >= 0
    if not ok:
        rule = "a finite length (m)" if signed else ("a finite length > 0 (m)" if positive else "a finite length ≥ 0 (m)")
        raise InvalidStateError(field, f"must be {rule}, got {shown(value)}")
    return float(value)


def _side(value, field: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
        raise InvalidStateError(field, f"must be a side index (integer ≥ 0), got {shown(value)}")
    return int(value)


def _check_bits(sensor, rates: tuple, lengths: tuple) -> None:
    """Validate (and store as floats) a sensor's error rates and its lengths ≥ 0 (m), naming ``sensor.<field>``."""
    for name in rates:
        object.__setattr__(sensor, name, _rate(getattr(sensor, name), f"sensor.{name}"))
    for name in lengths:
        object.__setattr__(sensor, name, _length(getattr(sensor, name), f"sensor.{name}"))


def _flip(truth: bool, u: float, fp: float, fn: float) -> bool:
    """The bit a sensor reports for ``truth`` given the uniform draw ``u``."""
    return (u >= fn) if truth else (u < fp)


@dataclass(frozen=True, slots=True)
class SideSensor:
    """"The part rests on side ``side``" (one bit), with ``false_positive``/``false_negative`` rates."""

    side: int
    false_positive: float = 0.0
    false_negative: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "side", _side(self.side, "sensor.side"))
        _check_bits(self, ("false_positive", "false_negative"), ())

    @property
    def label(self) -> str:
        return f"side {self.side}"

    def truth(self, x: float, side: int, last: bool | None = None) -> bool:
        return int(side) == self.side

    def read(self, x: float, side: int, rng, last: bool | None = None) -> bool:
        """One reading at the true rest ``(x, side)``; ``last`` is ignored (no hysteresis)."""
        u = float(rng.random())
        rng.standard_normal()  # the stream's use does not depend on the sensor kind
        return _flip(self.truth(x, side), u, self.false_positive, self.false_negative)


@dataclass(frozen=True, slots=True)
class BeyondSensor:
    """"The CM abscissa is beyond ``x``" (m), with error rates, a blur ``sigma`` (m) of the abscissa it
    thresholds and ``hysteresis`` (m): after a 1 it reads 1 down to ``x − hysteresis``."""

    x: float
    false_positive: float = 0.0
    false_negative: float = 0.0
    hysteresis: float = 0.0
    sigma: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "x", _length(self.x, "sensor.x", signed=True))
        _check_bits(self, ("false_positive", "false_negative"), ("hysteresis", "sigma"))

    @property
    def label(self) -> str:
        return f"x > {100 * self.x:.4g} cm"

    def truth(self, x: float, side: int, last: bool | None = None) -> bool:
        return float(x) > self.x - (self.hysteresis if last else 0.0)

    def read(self, x: float, side: int, rng, last: bool | None = None) -> bool:
        u = float(rng.random())
        seen = float(x) + self.sigma * float(rng.standard_normal())
        return _flip(self.truth(seen, side, last), u, self.false_positive, self.false_negative)


@dataclass(frozen=True, slots=True)
class WithinSensor:
    """"The CM abscissa is within ``eps`` of ``x_f``" (m), with error rates, blur ``sigma`` (m) and
    ``hysteresis`` (m): after a 1 the window is ``eps + hysteresis`` wide on each side."""

    x_f: float
    eps: float
    false_positive: float = 0.0
    false_negative: float = 0.0
    hysteresis: float = 0.0
    sigma: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "x_f", _length(self.x_f, "sensor.x_f", signed=True))
        object.__setattr__(self, "eps", _length(self.eps, "sensor.eps", positive=True))
        _check_bits(self, ("false_positive", "false_negative"), ("hysteresis", "sigma"))

    @property
    def label(self) -> str:
        return f"|x − {100 * self.x_f:.4g} cm| ≤ {1000 * self.eps:.3g} mm"

    def truth(self, x: float, side: int, last: bool | None = None) -> bool:
        return abs(float(x) - self.x_f) <= self.eps + (self.hysteresis if last else 0.0)

    def read(self, x: float, side: int, rng, last: bool | None = None) -> bool:
        u = float(rng.random())
        seen = float(x) + self.sigma * float(rng.standard_normal())
        return _flip(self.truth(seen, side, last), u, self.false_positive, self.false_negative)


@dataclass(frozen=True, slots=True)
class PositionSensor:
    """A position estimate for model-based controllers: ``(x + sigma·N(0, 1), side)``; with probability
    ``side_error`` the side read is another stable side (the next one, k + 1 mod ``n_sides``)."""

    sigma: float = 0.0
    side_error: float = 0.0
    n_sides: int = 3

    def __post_init__(self):
        object.__setattr__(self, "sigma", _length(self.sigma, "sensor.sigma"))
        object.__setattr__(self, "side_error", _rate(self.side_error, "sensor.side_error"))
        if isinstance(self.n_sides, bool) or not isinstance(self.n_sides, (int, np.integer)) or self.n_sides < 1:
            raise InvalidStateError("sensor.n_sides", f"must be an integer ≥ 1, got {shown(self.n_sides)}")
        object.__setattr__(self, "n_sides", int(self.n_sides))

    @property
    def label(self) -> str:
        return f"position (σ = {1000 * self.sigma:.3g} mm)"

    def read(self, x: float, side: int, rng, last=None) -> tuple[float, int]:
        u = float(rng.random())
        xe = float(x) + self.sigma * float(rng.standard_normal())
        k = int(side)
        if u < self.side_error and self.n_sides > 1:
            k = (k + 1) % self.n_sides
        return xe, k


SENSOR_TYPES = (SideSensor, BeyondSensor, WithinSensor, PositionSensor)
