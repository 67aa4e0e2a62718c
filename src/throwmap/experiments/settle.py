"""Experiment ``settle``: drop the part onto the arm from a random pose and see where it rests.

The draft's trials began "with random initial conditions (obtained by dropping the part
onto the arm)" (Sec. IV-B, V-C). This experiment measures that step alone, in the pymunk
engine (:func:`throwmap.experiments.drop.drop_part` with ``max_redraws=0``): a trial
succeeds when the part comes to rest flat on a stable side on the arm, which is the
start every throw needs. Failures by kind: ``off_end`` / ``behind_joint`` (fell off an
end), ``tilted`` (came to rest leaning, which on the bare arm the engine refuses as
unconverged), ``held_tilted`` (at rest, tilted against a fixture), ``refused:<status>``
(the engine gave no answer). Per-trial values give the drop-outcome statistics later
experiments start from: the resting ``x`` (m), ``side`` and ``tilt`` (rad), the draw
(``x0`` m, ``phi0`` rad, ``height`` m), the fall time ``t_fall`` (s) and the trial's ``mu``.
"""

from __future__ import annotations

import math
from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field

from ..system.arm import Arm
from ..system.fixtures import Cavity, Wall
from .base import Trial, seed_of
from .drop import DEFAULT_HEIGHT, drop_part
from .noise import NoiseConfig
from .registry import register_experiment

__all__ = ["SettleConfig", "Settle", "SETTLE"]

Finite = Annotated[float, Field(allow_inf_nan=False)]


class SettleConfig(BaseModel):
    """Config of ``settle`` (SI units). The defaults are the built-in example: the draft's 17 cm
    30-60-90 plexiglas triangle dropped 2–10 cm onto a 40 cm arm (h = −1 cm, μ = 0.8)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    part: str = Field("triangle", description="a built-in part name or a .toml/.json part file")
    h: Finite = Field(-0.01, description="arm surface height, m")
    length: Finite = Field(0.40, gt=0, description="arm length, m")
    mu: float | None = Field(0.8, ge=0, description="arm–part friction (None: ∞, no slip)")
    alpha: Finite = Field(0.0, gt=-math.pi / 2, lt=math.pi / 2, description="arm rest angle, rad")
    x_range: tuple[Finite, Finite] | None = Field(None, description="CM abscissa range of the drop, m (None: the arm)")
    height: tuple[Finite, Finite] = Field(DEFAULT_HEIGHT, description="lowest vertex above the arm at release, m")
    cavity: list[tuple[Finite, Finite]] | None = Field(None, description="Cavity profile (s, y) at the arm's end, m")
    wall_height: Finite | None = Field(None, gt=0, description="a Wall at the arm's end this high, m (None: no wall)")
    noise: NoiseConfig = Field(default_factory=NoiseConfig, description="per-trial μ spread (ω unused here)")


class Settle:
    """Drop the part; success = at rest flat on a stable side on the arm."""

    name = "settle"
    summary = "drop the part from a random pose onto the arm (pymunk); success = at rest flat on a stable side"
    config_type = SettleConfig

    @staticmethod
    def build(cfg: SettleConfig):
        """``(part, arm, fixtures)`` of a config."""
        from ..io.config import resolve_part

        part = resolve_part(cfg.part).part
        arm = Arm(h=cfg.h, length=cfg.length, mu=math.inf if cfg.mu is None else cfg.mu)
        fixtures = []
        if cfg.cavity is not None:
            fixtures.append(Cavity(tuple(cfg.cavity)))
        if cfg.wall_height is not None:
            fixtures.append(Wall(height=cfg.wall_height))
        return part, arm, tuple(fixtures)

    def trial(self, cfg: SettleConfig, index: int, rng) -> Trial:
        from ..engine.rest import FLAT_TILT

        part, arm, fixtures = self.build(cfg)
        arm = cfg.noise.noise().arm(arm, rng)
        d = drop_part(part, arm, rng, fixtures=fixtures, alpha=cfg.alpha, x_range=cfg.x_range, height=cfg.height,
                      max_redraws=0)
        kind = d.kind
        if kind is None and abs(d.tilt) >= FLAT_TILT:
            kind = "held_tilted"
        values = {"x": d.x, "side": d.side, "tilt": d.tilt, "x0": d.start[0], "phi0": d.start[2],
                  "height": d.height, "t_fall": d.t_fall, "mu": arm.mu}
        return Trial(index, seed_of(rng), kind is None, kind, values)

    def parameters(self, cfg: SettleConfig) -> dict:
        part, arm, fixtures = self.build(cfg)
        return {"part": part.name, "part_mass_kg": part.mass, "h_m": arm.h, "length_m": arm.length,
                "mu": None if math.isinf(arm.mu) else arm.mu, "g_m_s2": arm.g, "alpha_rad": cfg.alpha,
                "x_range_m": list(cfg.x_range) if cfg.x_range else [0.0 - arm.back, arm.length],
                "height_m": list(cfg.height), "fixtures": [repr(f) for f in fixtures],
                "noise": cfg.noise.noise().to_dict(), "engine": "pymunk, EngineSettings() defaults",
                "success": "at rest flat (|tilt| < 0.02 rad) on a stable side on the arm"}


SETTLE = register_experiment(Settle())
