"""The system a throw happens in, as a config declares it: one schema, validated once.

:class:`SystemSpec` — the part, the arm (``[arm]``), the arm's rest angle ``alpha``, a wall (``[wall]``) and noise
(``[noise]``) — is derived by every config with a whole system (the experiments ``settle`` and ``position``, the
sweeps' ``throw`` and ``limit_set`` targets); configs whose system is partly designed embed its pieces
(:mod:`throwmap.io.schema`: :class:`ArmSpec`, :class:`WallSpec`, :class:`NoiseSpec`). The field types and their
rules (μ, lengths, α, ω: each the library's own check) are :mod:`throwmap.io.schema`'s, re-exported here.
"""

from __future__ import annotations

from pydantic import Field

from ..errors import ThrowmapError
from ..system.arm import Arm
from ..system.noise import Noise
from .schema import (INF_WORDS, MAX_RATE, Angle, ArmSpec, Friction, Heights, Length, NoiseSpec, Number, Omega, Point,
                     Range, Rate, RateRange, Spec, WallSpec)

__all__ = ["SystemSpec", "Number", "Omega", "Rate", "RateRange", "MAX_RATE", "Friction", "Length", "Angle", "Point",
           "Range", "Heights", "Spec", "ArmSpec", "WallSpec", "NoiseSpec", "INF_WORDS"]


class SystemSpec(Spec):
    """Part, arm, wall, rest angle and noise of a config. Configs with a whole system derive from it and give their
    own defaults (configs whose system is partly designed embed its pieces: :class:`ArmSpec`, :class:`WallSpec`,
    :class:`NoiseSpec`); an ``[arm]`` or ``[wall]`` table in a file overrides only the keys it names.

    ``part``: a built-in part name or a ``.toml``/``.json`` part file; ``arm``: :class:`ArmSpec`; ``alpha``: the
    arm's rest angle (rad); ``wall``: :class:`WallSpec` or None; ``noise``: :class:`NoiseSpec`.
    """

    part: str = Field("triangle", description="a built-in part name or a .toml/.json part file")
    arm: ArmSpec = Field(default_factory=lambda: ArmSpec(h=-0.01))
    alpha: Angle = Field(0.0, description="the arm's rest angle, rad")
    wall: WallSpec | None = Field(None, description="a wall at the arm's end (None: none)")
    noise: NoiseSpec = Field(default_factory=NoiseSpec)

    def build_part(self):
        """The :class:`~throwmap.Part` named by ``part`` (errors name ``config.part``)."""
        from .config import resolve_part  # (io.config reads part files; it does not import this module)

        try:
            return resolve_part(self.part).part
        except ThrowmapError as err:
            if err.field in ("file", "part"):
                raise type(err)("config.part", err.reason) from None
            raise type(err)(err.field, f"{err.reason} (in config.part = {self.part!r})") from None

    def build_arm(self, **defaults) -> Arm:
        """The :class:`~throwmap.Arm` (``defaults`` fill what the config leaves None, e.g. a design's ``h``)."""
        return self.arm.arm(field="config.arm.h", **defaults)

    def fixtures(self) -> tuple:
        """The fixtures the config declares: its wall, if any."""
        return () if self.wall is None else (self.wall.wall(),)

    def noise_model(self) -> Noise:
        return self.noise.noise()
