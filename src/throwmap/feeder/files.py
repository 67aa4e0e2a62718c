"""A screened feeder as files: the part file and the ``feed`` experiment config that runs it.

``DIR/part.toml`` is the part with its lead weight (:func:`throwmap.io.config.save_part_toml`);
``DIR/feeder.toml`` the :class:`~throwmap.experiments.feed.FeedConfig` of the closed variant: the
target side, ω and h, the arm's μ, a pocket ``POCKET_DEPTH_M`` deep ending in an end wall at the
screened end stop, its floor and wall lined with a low-friction facing (μ ``LINING_MU``, a PTFE sheet:
a lean against an unlined wall can rest and be flipped out by the next throw), drops over the
screen's drop zone, and the noise the experiment throws with (σ of ω jitter, ± arm μ, the recoil
arm). ``throwmap experiment feed DIR/feeder.toml`` runs it as it is (the part is looked for next to
the config).
"""

from __future__ import annotations

import math
from pathlib import Path

from ..errors import InvalidStateError
from .arrival import DROP_X, Arrival, pocket_clearance

__all__ = ["feeder_files", "feeder_config_text", "POCKET_DEPTH_M", "LINING_MU", "MAX_THROWS", "ENGINE_SETTINGS"]

POCKET_DEPTH_M = 0.01
"""The pocket's floor below the arm's surface, m."""
LINING_MU = 0.2
"""Friction of the pocket's lining (floor and end wall; PTFE on plastic, upper value)."""
MAX_THROWS = 100
"""Throws a part is given to reach the pocket."""
ENGINE_SETTINGS = {"agreement": 0.005, "retries": 4, "refine": 2}
"""Engine checks of the feeding runs: a half-step rerun must agree to 5 mm (the pocket's clearance), and where it
does not the step is halved twice more until two steps agree (measured on two candidates, 20 trials each: refusals
5 → 1 and 9 → 0; the fed share 15 → 19 of 20); a lost contact is retried 4 times."""


def feeder_config_text(found: Arrival, *, part_file: str = "part.toml", mu: float = 1.0, g: float = 9.81,
                       sigma: float = 0.03, mu_rel: float = 0.1, recoil_deg: float = 3.0, zeta: float = 0.2) -> str:
    """The TOML text of the ``feed`` config of a screened feeder (SI units; see the module docstring)."""
    if not (found.predicted > 0 and math.isfinite(found.X)):
        raise InvalidStateError("candidate", f"side {found.side} at ω = {found.omega:g} rad/s has no end stop where "
                                             "it arrives first and holds: nothing to feed with")
    lines = [
        "# A feeder found by throwmap.feeder.design: the part (part.toml, with its lead weight) thrown by the",
        "# recoiling arm with ω jitter into a lined pocket at the arm's end. Run it in the engine with",
        "#   throwmap experiment feed feeder.toml --n 200 --seed 7",
        f'part = "{part_file}"  # next to this file',
        f"side = {found.side}",
        f"omega = {found.omega!r}",
        f"x_range = {list(DROP_X)!r}  # drops: CM abscissa, m (a chute onto the inner arm)",
        f"max_throws = {MAX_THROWS}",
        "settings = { " + ", ".join(f"{k} = {v!r}" for k, v in ENGINE_SETTINGS.items()) + " }",
        "",
        "[arm]",
        f"h = {found.h!r}",
        f"g = {float(g)!r}",
        f"mu = {float(mu)!r}" if math.isfinite(mu) else 'mu = "inf"',
        "",
        "[cavity]",
        f"length = {found.X!r}  # end wall, m: " + _wall_note(found),
        f"depth = {POCKET_DEPTH_M!r}",
        f"clearance = {round(pocket_clearance(found.variant.part, found.side), 6)!r}  # floor beyond side "
        f"{found.side}'s length: the part's overhang past its ends + 5 mm, m",
        f"wall_mu = {LINING_MU!r}",
        "lined = true  # the floor faced like the end wall",
        "window = false  # the search placed the end wall: no throw map of the floor is computed to place it",
        "",
        "[noise]",
        f"omega_rel = {float(sigma)!r}",
        f"mu_rel = {float(mu_rel)!r}",
        'realisation = "recoil"',
        f"recoil = {math.radians(recoil_deg)!r}",
        f"zeta = {float(zeta)!r}",
        "",
    ]
    return "\n".join(lines)


def _wall_note(found: Arrival) -> str:
    """Where the end wall's screened share comes from: this wall, or the screened stop it was moved from."""
    stop = float(found.best.get(found.side, (found.X,))[0]) if found.best else found.X
    share = f"{100 * found.predicted:.1f} % of screened chains"
    there = "at the pocket's lip before it" if found.lip else "there"  # the share is counted where a side is caught
    if not math.isfinite(stop) or abs(stop - found.X) < 1e-9:
        return f"side {found.side} arrives {there} first in {share}"
    return (f"moved {100 * (found.X - stop):+.1f} cm from the screened stop at {stop:g} m, where side {found.side} "
            f"arrives {'at the lip ' if found.lip else ''}first in {share}")


def feeder_files(found: Arrival, out, **kw) -> Path:
    """Write ``out/part.toml`` and ``out/feeder.toml`` (atomically) for a screened feeder; returns the config's path.
    ``kw``: ``mu``, ``g``, ``sigma``, ``mu_rel``, ``recoil_deg``, ``zeta`` of :func:`feeder_config_text`."""
    from ..io.config import save_part_toml
    from ..io.files import atomic_write_text

    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InvalidStateError("out", f"{str(out)!r} is a file, not a folder")
    out.mkdir(parents=True, exist_ok=True)
    text = feeder_config_text(found, **kw)
    save_part_toml(found.variant.part, None, out / "part.toml")
    return atomic_write_text(out / "feeder.toml", text)
