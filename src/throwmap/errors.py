"""Exception and warning hierarchy.

Every error raised for bad user input names the offending field and the rule it
breaks, as ``"<field>: <reason>"``; the CLI prints exactly that line and exits 2.
"""

from __future__ import annotations

__all__ = [
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
        self.field = field
        self.reason = reason
        super().__init__(f"{field}: {reason}")


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
