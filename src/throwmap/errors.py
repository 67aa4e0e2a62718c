"""Exception and warning hierarchy.

Every error raised for bad user input names the offending field and the rule it
breaks, as ``"<field>: <reason>"``; the CLI prints exactly that line and exits 2.
"""

from __future__ import annotations

import math
import re

__all__ = [
    "shown",
    "ThrowmapError",
    "InvalidPartError",
    "InvalidArmError",
    "InvalidStateError",
    "ConfigError",
    "ThrowmapWarning",
    "RegimeWarning",
]


class ThrowmapError(Exception):
    """Base class of every error throwmap raises on purpose.

    ``field`` names the input at fault (``"part.vertices"``, ``"x"``…) and
    ``reason`` says which rule it broke; ``str(err)`` is ``"field: reason"``.
    """

    def __init__(self, field: str, reason: str):
        self.field = str(field)
        self.reason = _plain(str(reason))
        super().__init__(f"{self.field}: {self.reason}")

    def __reduce__(self):
        """Pickle as ``(type, (field, reason))``: an error raised in a worker process reaches the
        parent as itself (the default would call ``__init__`` with the message alone and fail)."""
        return (type(self), (self.field, self.reason))


def shown(value, limit: int = 80) -> str:
    """``value`` as an error message shows it: NumPy scalars as plain Python numbers
    (``1.5``, not ``np.float64(1.5)``), arrays as lists, strings quoted; at most
    ``limit`` characters. Use it instead of ``{value!r}`` for anything a user passed in.
    """
    if isinstance(value, (str, bytes)):
        text = repr(str(value) if isinstance(value, str) else bytes(value))
    elif getattr(value, "ndim", None) == 0 and type(value).__module__ == "numpy":
        text = str(value)  # NumPy's str of a scalar is the plain number: 1.5, 3, True, nan
    elif hasattr(value, "tolist"):
        try:
            text = _plain(repr(value.tolist()))
        except (TypeError, ValueError):  # pragma: no cover - exotic array-likes
            text = _plain(repr(value))
    else:
        text = _plain(repr(value))
    return text if len(text) <= limit else text[: limit - 1] + "…"


# NumPy's reprs (NumPy ≥ 2): np.float64(1.5), np.int64(3), np.True_, np.str_('a'), array([...])
_NP_STR = re.compile(r"np\.(?:str_|bytes_)\((?P<q>'(?:[^'\\]|\\.)*'|\"(?:[^\"\\]|\\.)*\")\)")
_NP_SCALAR = re.compile(r"np\.(?:float|int|uint|complex|longdouble|clongdouble|half|single|double)\w*"
                        r"\((?P<v>[^()]*)\)")
_NP_BOOL = re.compile(r"np\.(?P<v>True|False)_")
_NP_ARRAY = re.compile(r"\barray\((?P<v>\[[^()]*\])(?:, dtype=\w+)?\)")


def _plain(text: str) -> str:
    """``text`` with NumPy scalar and array reprs written as plain Python values.

    A safety net under :class:`ThrowmapError`: a reason built with ``{value!r}`` on a
    NumPy value reads ``got 1.5``, never ``got np.float64(1.5)``.
    """
    if "np." not in text and "array(" not in text:
        return text
    text = _NP_STR.sub(lambda m: m.group("q"), text)
    text = _NP_SCALAR.sub(lambda m: m.group("v"), text)
    text = _NP_BOOL.sub(lambda m: m.group("v"), text)
    return _NP_ARRAY.sub(lambda m: " ".join(m.group("v").split()), text)


class InvalidPartError(ThrowmapError, ValueError):
    """A part description that is not a valid convex rigid polygon."""


class InvalidArmError(ThrowmapError, ValueError):
    """An arm description that cannot be used (non-finite h, g ≤ 0…)."""


class InvalidStateError(ThrowmapError, ValueError):
    """A resting configuration or throw input that is not admissible."""


class ConfigError(ThrowmapError, ValueError):
    """A part/arm file that cannot be read or does not validate."""


class ThrowmapWarning(UserWarning):
    """Base class of throwmap's warnings."""


class RegimeWarning(ThrowmapWarning):
    """The arm is outside the paper's regime 0 > h > -min_i d_i (Sec. III-D)."""


class ScaleWarning(ThrowmapWarning):
    """A value far outside what a hand-sized part on a one-joint arm has: most likely a unit slip (cm for m,
    g for kg, degrees for rad, deg/s for rad/s). The value is used as given."""


SCALES = {"length": (2.0, "m", "cm typed as m?"), "mass": (10.0, "kg", "g typed as kg?"),
          "omega": (30.0, "rad/s", "deg/s or rpm typed as rad/s?"), "alpha": (math.radians(60.0), "rad",
                                                                              "degrees typed as rad? write e.g. 10deg")}
"""Plausible magnitudes: a value above these (in SI) gets a :class:`ScaleWarning` naming the field."""


def warn_scale(field: str, value: float, kind: str) -> None:
    """Warn (:class:`ScaleWarning`) when ``|value|`` exceeds the plausible magnitude of ``kind`` (:data:`SCALES`)."""
    limit, unit, hint = SCALES[kind]
    try:
        big = abs(float(value)) > limit
    except (TypeError, ValueError):
        return
    if big:
        import warnings

        warnings.warn(f"{field} = {float(value):g} {unit} is over {limit:g} {unit}: {hint}", ScaleWarning, stacklevel=3)
