"""A map over two parameters: how many attractors a throw map has, and what share of its starts escape.

Each grid point is a limit set (:func:`~throwmap.analysis.limitset.limit_set`) from ``n_starts`` stratified random
starts per side, whose orbits run until they settle — past the stated horizon when their tails are not yet
stationary, up to 5,000 throws — so its escape share counts late escapes that a continuation (an even grid of
starts, each followed for exactly its horizon, the rest "unresolved") leaves undecided: the triangle at ω = 4.6,
h = −1 cm escapes 100 % here and 71 % (29 % unresolved) in a 150-throw continuation.

:func:`attractor_map` writes the grid as a sweep of the ``limit_set`` target (:mod:`throwmap.sweeps.schema`:
one limit set from ``n_starts`` starts per stable side at every grid point) and runs it on Dask with
:func:`~throwmap.sweeps.run.run_sweep`, so the points are stored in ``out`` as they finish and a second call
computes only those missing. The result (:class:`AttractorMap`) holds, per grid point, the number of attractors
and the share of the starts that escaped (behind the joint, off the end…); the figure draws both as maps.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InvalidStateError, shown
from .schema import jsonable

__all__ = ["AttractorMap", "attractor_map", "limit_set_config", "FIELDS"]

FIELDS = {"omega": "omega", "h": "arm.h", "mu": "arm.mu", "alpha": "alpha", "weight_x": "weight_x",
          "weight_y": "weight_y"}
"""The continuation's parameter names → the ``limit_set`` sweep's config fields."""


@dataclass(frozen=True)
class AttractorMap:
    """Attractor count and escape share on a grid of two parameters: ``params`` (names), ``values`` (the two axes,
    in the parameters' units), ``count`` and ``escape`` (arrays, axis 0 along the first parameter; nan where the
    point was refused — ``errors`` says why — or not computed), ``out`` (the sweep's folder), ``system``."""

    params: tuple
    values: tuple
    count: np.ndarray
    escape: np.ndarray
    errors: dict
    out: str
    system: dict

    @property
    def complete(self) -> bool:
        return bool(np.all(np.isfinite(self.count)) or self.errors)

    def to_dict(self) -> dict:
        def grid(a, kind=float):
            return [[None if not math.isfinite(v) else kind(v) for v in row] for row in a]

        return {"params": list(self.params), "values": [list(map(float, v)) for v in self.values],
                "attractors": grid(self.count, int), "escape_fraction": grid(self.escape), "errors": dict(self.errors),
                "out": self.out, "system": jsonable(dict(self.system))}

    def table(self) -> str:
        """Attractor counts (and escape share, %) as a text grid: rows the first parameter, columns the second."""
        p, q = self.params
        head = f"{p} \\ {q}".ljust(12) + "".join(f"{v:>12.4g}" for v in self.values[1])
        rows = [f"attractors (escape %) over {p} × {q}; stored in {self.out}", head]
        for i, v in enumerate(self.values[0]):
            cells = []
            for j in range(len(self.values[1])):
                c, e = self.count[i, j], self.escape[i, j]
                cells.append(f"{'—' if not math.isfinite(c) else int(c)} ({'—' if not math.isfinite(e) else f'{100 * e:.0f}'})"
                             .rjust(12))
            rows.append(f"{v:<12.4g}" + "".join(cells))
        if self.errors:
            rows.append(f"{len(self.errors)} point(s) refused, e.g. {next(iter(self.errors.values()))}")
        return "\n".join(rows)

    def plot(self, path=None):
        """Two maps over the grid: the number of attractors and the share of starts that escape."""
        from ..viz.style import _plt, layout, save_figure

        plt = _plt()
        fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
        (a, b), (p, q) = self.values, self.params
        ext = [b[0], b[-1], a[0], a[-1]]
        n_max = int(np.nanmax(self.count)) if np.any(np.isfinite(self.count)) else 1
        im = axes[0].imshow(self.count, origin="lower", aspect="auto", extent=ext, cmap=plt.get_cmap("viridis", n_max + 1),
                            vmin=-0.5, vmax=n_max + 0.5, interpolation="nearest")
        fig.colorbar(im, ax=axes[0], ticks=range(n_max + 1), label="attractors")
        im2 = axes[1].imshow(100 * self.escape, origin="lower", aspect="auto", extent=ext, cmap="magma_r", vmin=0,
                             vmax=100, interpolation="nearest")
        fig.colorbar(im2, ax=axes[1], label="starts that escape (%)")
        units = {"omega": "ω (rad/s)", "h": "h (m)", "mu": "μ", "alpha": "α (rad)", "weight_x": "lead weight x (m)",
                 "weight_y": "lead weight y (m)"}
        for ax, what in zip(axes, ("number of attractors", "escape share")):
            ax.set_xlabel(units.get(q, q))
            ax.set_ylabel(units.get(p, p))
            ax.set_title(what, fontsize=9)
        s = self.system
        fig.suptitle(f"{s['part']}, model '{s['model']}', {s['n_starts']} starts per side", fontsize=9)
        layout(fig)
        if path is not None:
            save_figure(fig, path)
        return fig


def limit_set_config(part: str, arm, *, omega=None, model: str = "rigid_body", throw_options=None,
                     n_starts: int = 16, x_max=None, horizon: int = 500) -> dict:
    """The ``limit_set`` target's config (:class:`~throwmap.sweeps.schema.LimitSetConfig`) of a system: ``part`` (a
    built-in part's name or a part file's path: the sweep's workers read it), ``arm`` (:class:`~throwmap.Arm`),
    ``omega`` (rad/s), ``model``, ``throw_options`` (``alpha`` in rad, ``fixtures``: at most one
    :class:`~throwmap.Wall`), ``n_starts`` per stable side, ``x_max`` (m), ``horizon`` (throws: at most 400
    recorded, the rest discarded first)."""
    from ..system.fixtures import Wall

    opts = dict(throw_options or {})
    fixtures = tuple(opts.pop("fixtures", ()))
    alpha = opts.pop("alpha", None)
    if opts:
        raise InvalidStateError(next(iter(opts)), "a two-parameter map takes only the options alpha and fixtures")
    walls = [f for f in fixtures if isinstance(f, Wall)]
    if len(walls) != len(fixtures) or len(walls) > 1:
        raise InvalidStateError("fixtures", "a two-parameter map takes at most one wall (no cavity)")
    n_record = min(400, int(horizon))
    config = {"part": str(part), "model": model, "n_starts": int(n_starts), "transient": int(horizon) - n_record,
              "n_record": n_record, "x_max": x_max, "omega": omega, "alpha": alpha or None,
              "arm": {"h": arm.h, "g": arm.g, "length": math.inf if arm.length is None else arm.length, "mu": arm.mu,
                      "back": arm.back}}  # every field: the target's own arm defaults (a 0.4 m arm) would apply
    if walls:
        config["wall"] = {k: v for k, v in (("height", walls[0].height), ("mu", walls[0].mu)) if v is not None}
    return {k: v for k, v in config.items() if v is not None}


def attractor_map(grid: dict, out, config: dict, *, seed: int = 0, workers: int = 0, client=None, progress=None,
                  limits=None) -> AttractorMap:
    """The attractor count and escape share over two parameters (module docstring), run on Dask into ``out``.

    ``grid``: two entries ``{name: (first, last, n)}`` with names from :data:`FIELDS`; ``config``: the fixed
    system as the ``limit_set`` target's config (:func:`limit_set_config`); ``seed``: the limit sets' seed;
    ``workers``/``client``/``progress``/``limits``: as for :func:`~throwmap.sweeps.run.run_sweep`.
    """
    from .run import run_sweep
    from .schema import Range, parse_sweep
    from .store import read_table

    if not isinstance(grid, dict) or len(grid) != 2:
        raise InvalidStateError("grid", f"must name two parameters, got {shown(grid)}")
    for name, axis in grid.items():
        if name not in FIELDS:
            raise InvalidStateError("param", f"must be one of {', '.join(FIELDS)}, got {name!r}")
        if not (isinstance(axis, (tuple, list)) and len(axis) == 3):
            raise InvalidStateError(name, f"must be (first, last, n), got {shown(axis)}")
    if "omega" not in grid and config.get("omega") is None:
        raise InvalidStateError("omega", "a release rate (rad/s) is required unless omega is a parameter")
    config = {k: v for k, v in config.items() if not (k == "omega" and "omega" in grid)}
    params = {FIELDS[name]: Range(low=float(a), high=float(b), num=int(n)) for name, (a, b, n) in grid.items()}
    doc = {"kind": "grid", "target": "limit_set", "seed": int(seed), "parameters": params, "config": config}
    spec = parse_sweep(json.loads(json.dumps({**doc, "parameters": {k: v.model_dump() for k, v in params.items()}},
                                             default=str)), "continuation map")
    run_sweep(spec, Path(out), client=client, workers=workers, progress=progress, limits=limits)
    table = read_table(out).to_pylist()
    (n1, r1), (n2, r2) = grid.items()
    axes = tuple(np.linspace(a, b, int(n)) for a, b, n in (r1, r2))
    count = np.full((axes[0].size, axes[1].size), np.nan)
    escape = np.full_like(count, np.nan)
    errors = {}
    f1, f2 = FIELDS[n1], FIELDS[n2]
    for row in table:
        i = int(np.argmin(np.abs(axes[0] - float(row[f1]))))
        j = int(np.argmin(np.abs(axes[1] - float(row[f2]))))
        if row.get("error"):
            errors[f"{row[f1]:g}, {row[f2]:g}"] = row["error"]
            continue
        count[i, j] = row["n_attractors"]
        escape[i, j] = sum(v for k, v in json.loads(row["escapes"]).items() if k != "unresolved")
    system = {"part": config["part"], "model": config.get("model", "rigid_body"), "n_starts": config.get("n_starts", 16),
              "arm": dict(config.get("arm", {})), "omega_rad_s": config.get("omega"),
              "horizon_throws": config.get("transient", 200) + config.get("n_record", 400), "seed": int(seed)}
    return AttractorMap((n1, n2), axes, count, escape, errors, str(out), system)
