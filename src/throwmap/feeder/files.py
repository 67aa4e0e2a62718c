"""A screened feeder as files: the part file and the ``feed`` experiment config that runs it.

``DIR/part.toml`` is the part (:func:`throwmap.io.config.save_part_toml`); ``DIR/feeder.toml`` the
:class:`~throwmap.experiments.feed.FeedConfig` of the closed variant: the candidate's side, ω and h, the
arm's μ, a pocket of the candidate's depth ending in an end wall at the candidate's L, and the noise
the experiment throws with (σ of ω jitter, ± arm μ, the recoil arm). ``throwmap experiment feed
DIR/feeder.toml`` runs it as it is (the part is looked for next to the config).
"""

from __future__ import annotations

import math
from pathlib import Path

from ..errors import InvalidStateError
from .screen import Candidate, Screen

__all__ = ["feeder_files", "feeder_config_text"]


def feeder_config_text(candidate: Candidate, screen: Screen, *, part_file: str = "part.toml",
                       mu_rel: float = 0.1, recoil_deg: float = 3.0, zeta: float = 0.2) -> str:
    """The TOML text of the ``feed`` config of ``candidate`` (SI units; see the module docstring)."""
    if candidate.window is None:
        raise InvalidStateError("candidate", f"side {candidate.side} at ω = {candidate.omega:g} rad/s has no "
                                             "end-wall window: nothing to feed with")
    mu = screen.mu
    lines = [
        "# A feeder found by throwmap.feeder.screen (exact impulse model); run it in the engine with",
        "#   throwmap experiment feed feeder.toml --n 200 --seed 7",
        f'part = "{part_file}"  # next to this file',
        f"side = {candidate.side}",
        f"omega = {candidate.omega!r}",
        "",
        "[arm]",
        f"h = {candidate.h!r}",
        f"g = {screen.g!r}",
        f"mu = {mu!r}" if math.isfinite(mu) else 'mu = "inf"',
        "",
        "[cavity]",
        f"depth = {candidate.depth!r}",
        f"length = {candidate.length!r}  # the middle of the window [{candidate.window[0]!r}, {candidate.window[1]!r}] m",
        "",
        "[noise]",
        f"omega_rel = {screen.sigma!r}",
        f"mu_rel = {float(mu_rel)!r}",
        'realisation = "recoil"',
        f"recoil = {math.radians(recoil_deg)!r}",
        f"zeta = {float(zeta)!r}",
        "",
    ]
    return "\n".join(lines)


def feeder_files(candidate: Candidate, screen: Screen, out, **noise) -> Path:
    """Write ``out/part.toml`` and ``out/feeder.toml`` (atomically) for ``candidate``; returns the config's path.
    ``noise``: ``mu_rel``, ``recoil_deg``, ``zeta`` of :func:`feeder_config_text`."""
    from ..io.config import save_part_toml
    from ..io.files import atomic_write_text

    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InvalidStateError("out", f"{str(out)!r} is a file, not a folder")
    out.mkdir(parents=True, exist_ok=True)
    text = feeder_config_text(candidate, screen, **noise)
    save_part_toml(screen.part, None, out / "part.toml")
    return atomic_write_text(out / "feeder.toml", text)
