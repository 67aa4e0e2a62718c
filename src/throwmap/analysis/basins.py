"""Basins of attraction over all initial configurations, and global attractivity (paper Sec. I-A, III-D).

:func:`basins` labels every configuration of a grid (x on every stable side) with
the attractor its orbit ends on (1, 2, … or −1, see
:mod:`throwmap.analysis.attractors`), the throws it takes to reach it, basin
fractions, and a :class:`Certificate` saying whether one limit set is unique and
globally attractive on the arm.

Two methods
-----------
``"orbits"``  Every configuration is iterated exactly (batch kernels, one batch per
              throw) until it lies on a known attractor (within ``reach_tol``),
              escapes, or ``max_throws`` pass. Attractors are first found by
              :func:`~throwmap.analysis.limitset.limit_set` on a stratified sample;
              orbits that reach none of them are searched for new ones.
``"cells"``   Cell-to-cell mapping (Hsu's method) for dense grids: every grid
              configuration is thrown **once**, exactly; its image is replaced by
              the nearest grid configuration on the landing side, and labels and
              throw counts propagate back along this discrete graph. Images that
              leave the grid, and chains that end on no attractor, are finished
              with exact orbits. ``n_check`` configurations drawn with ``rng`` are
              also mapped exactly and the agreement is reported
              (:attr:`Basins.check`). With 10⁶ configurations the grid spacing is
              about a micrometre and the exact check agrees on ≥ 99.9 % in our runs.

``method="auto"`` uses cells above 20 000 configurations, orbits below. The algorithms
live in :mod:`throwmap.analysis.cellmap`; this module holds the results and the driver.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown
from ..rng import as_generator
from ..system.arm import regime_warnings_once
from .attractors import (LABEL_ESCAPE, Attractor, attractor_table, domain_of, domain_text, escape_fractions, map_short,
                         range_short)
from .caps import RecurrenceCaps, check_int, check_length, resolve_caps, split_options
from .budget import Limits, guard_work
from .cellmap import basin_grid, cell_map, exact_with_discovery, grid_size, map_to_attractors, trap_excursion
from .limitset import limit_set
from .maps import DEFAULT_MODEL, ConfigMap, ThrowMap, as_map

__all__ = ["Basins", "Certificate", "basins", "map_to_attractors"]

AUTO_CELLS_ABOVE = 20_000
"""``method="auto"`` switches to cell mapping above this many configurations."""
BYTES_PER_CONFIG = 160
"""Memory a basin map plans per configuration: the result's five arrays (40 B), the cell graph and labels
in flight (≈ 40 B), and working copies (the rest); the throws themselves go in chunks."""


@dataclass(frozen=True, slots=True)
class Certificate:
    """Whether one limit set is unique and globally attractive on the arm, and the evidence.

    ``unique`` is True when every grid configuration reaches the same attractor (no −1),
    the exact-orbit check agreed on every sampled configuration, and the attractor's
    region is trapping (its sampled configurations map into it to within ``trap_tol``).
    It is a numerical certificate at the grid's resolution (``grid_spacing``, m per
    side), not a proof. ``statement`` says it in one sentence.
    """

    unique: bool
    attractor: int | None
    n_configs: int
    grid_spacing: dict
    max_throws_to_reach: int
    check_agreement: float
    trap_excursion: float
    trap_tol: float
    statement: str
    range_text: str = ""

    def __repr__(self) -> str:
        att = "-" if self.attractor is None else f"#{self.attractor}"
        return (f"Certificate(unique={self.unique}, attractor {att}, {self.n_configs} configs, "
                f"{self.range_text or 'range not recorded'})")

    def table(self) -> str:
        """The evidence, one line each (lengths in m), then the statement."""
        spacing = ", ".join(f"side {k}: {v:.3g}" for k, v in sorted(self.grid_spacing.items()))
        rows = [("unique and globally attractive", "yes" if self.unique else "no"),
                ("for", self.range_text or "-"),
                ("attractor", "-" if self.attractor is None else f"#{self.attractor}"),
                ("configurations", str(self.n_configs)), ("grid spacing (m)", spacing),
                ("most throws to reach it", str(self.max_throws_to_reach)),
                ("exact-orbit check agreement", f"{100 * self.check_agreement:.2f} %"),
                ("trap excursion (m)", f"{self.trap_excursion:.3g} (tolerance {self.trap_tol:.3g})")]
        return "\n".join(f"{k:<29} {v}" for k, v in rows) + "\n" + self.statement

    def to_dict(self) -> dict:
        return {"unique": self.unique, "attractor": self.attractor, "n_configs": self.n_configs,
                "grid_spacing_m": {str(k): float(v) for k, v in self.grid_spacing.items()},
                "max_throws_to_reach": self.max_throws_to_reach, "check_agreement": self.check_agreement,
                "trap_excursion_m": None if not math.isfinite(self.trap_excursion) else self.trap_excursion,
                "trap_tol_m": self.trap_tol, "statement": self.statement, "range": self.range_text}

    @classmethod
    def from_dict(cls, d: dict) -> "Certificate":
        te = d["trap_excursion_m"]
        return cls(unique=bool(d["unique"]), attractor=None if d["attractor"] is None else int(d["attractor"]),
                   n_configs=int(d["n_configs"]), grid_spacing={int(k): float(v) for k, v in d["grid_spacing_m"].items()},
                   max_throws_to_reach=int(d["max_throws_to_reach"]), check_agreement=float(d["check_agreement"]),
                   trap_excursion=math.nan if te is None else float(te), trap_tol=float(d["trap_tol_m"]),
                   statement=str(d["statement"]), range_text=str(d.get("range", "")))


@dataclass(frozen=True, slots=True, eq=False)
class Basins:
    """A basin map: per grid configuration its attractor label, fate and throws to reach it.

    Arrays (flat, grid order: side by side, x ascending): ``x`` (m), ``side``,
    ``labels`` (attractor id, −1 = no attractor on the arm), ``fates`` (0 attracted,
    else the escape status code, −1 unresolved) and ``throws`` (map steps until the
    orbit lies on its attractor, or until it escaped). ``fractions`` maps each label
    to its share of the grid; ``attractors`` carry basin fractions.
    """

    x: np.ndarray
    side: np.ndarray
    labels: np.ndarray
    fates: np.ndarray
    throws: np.ndarray
    attractors: tuple
    certificate: Certificate
    method: str
    check: dict
    caps: dict
    map_info: dict

    def __repr__(self) -> str:
        shares = ", ".join(f"#{a.id} {a.kind} {100 * a.fraction:.1f} %" for a in self.attractors[:3])
        more = f", … {len(self.attractors)} attractors" if len(self.attractors) > 3 else ""
        esc = sum(v for v in self.escapes.values())
        return (f"Basins({map_short(self.map_info)}, {range_short(self.map_info)}, {self.n_configs} configs, "
                f"{self.method}: {shares or 'no attractor'}{more}; -1 {100 * esc:.1f} %; "
                f"unique={getattr(self.certificate, 'unique', None)})")

    @property
    def n_configs(self) -> int:
        return int(self.x.size)

    @property
    def fractions(self) -> dict:
        """``{label: share of the grid}``, −1 included when present."""
        labs, counts = np.unique(self.labels, return_counts=True)
        return {int(k): float(c) / max(1, self.n_configs) for k, c in zip(labs, counts)}

    @property
    def escapes(self) -> dict:
        """``{fate label: share of the grid}`` for configurations labelled −1."""
        return escape_fractions(self.fates, self.labels)

    def label_at(self, x, side) -> np.ndarray:
        """Labels of arbitrary configurations, read off the nearest grid configuration on their side."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        side = np.broadcast_to(np.atleast_1d(np.asarray(side)), x.shape)
        out = np.full(x.shape, LABEL_ESCAPE, dtype=np.int64)
        for s in np.unique(self.side):
            m = side == s
            if not np.any(m):
                continue
            g = np.flatnonzero(self.side == s)
            xs = self.x[g]
            j = np.clip(np.searchsorted(xs, x[m]), 1, xs.size - 1)
            j = np.where(np.abs(xs[j - 1] - x[m]) <= np.abs(xs[j] - x[m]), j - 1, j)
            inside = (x[m] > xs[0] - (xs[1] - xs[0])) & (x[m] <= xs[-1] + (xs[1] - xs[0]))
            out[m] = np.where(inside, self.labels[g[j]], LABEL_ESCAPE)
        return out

    def summary(self) -> str:
        lines = [f"basins of {self.map_info.get('label', 'map')}: {self.n_configs} configurations, "
                 f"method {self.method}"]
        for a in self.attractors:
            m = self.labels == a.id
            t = self.throws[m]
            lines.append(f"  {a.describe()}  basin {100 * a.fraction:.2f} %, throws to reach: median "
                         f"{np.median(t) if t.size else math.nan:g}, max {t.max() if t.size else 0}")
        for k, v in self.escapes.items():
            lines.append(f"  -1 {k}: {100 * v:.2f} %")
        if self.check:
            lines.append(f"  exact-orbit check: {self.check['n']} configurations, labels agree on "
                         f"{100 * self.check['agreement']:.2f} %")
        lines.append(f"  certificate: {self.certificate.statement}")
        return "\n".join(lines)

    def table(self) -> str:
        """The range of the grid, one row per attractor (basin share) and per escape fate, then the
        certificate's statement."""
        return (f"grid over the {self.range_text} (not beyond)\n"
                + attractor_table(self.attractors, self.escapes, share="basin %") + "\n" + self.certificate.statement)

    @property
    def range_text(self) -> str:
        """The configurations the grid covers, in words (e.g. ``"valid starts with x ≤ 0.600 m"``)."""
        dom, valid = domain_of(self.map_info)
        if dom:
            return domain_text(dom, valid)
        return self.certificate.range_text or "analysed grid (range not recorded)"

    def to_dict(self, arrays: bool = True) -> dict:
        d = {
            "n_configs": self.n_configs, "method": self.method,
            "attractors": [a.to_dict() for a in self.attractors],
            "fractions": {str(k): v for k, v in self.fractions.items()},
            "escapes": self.escapes, "certificate": self.certificate.to_dict(), "check": dict(self.check),
            "caps": dict(self.caps), "map": dict(self.map_info),
            "label_meaning": {"-1": "the orbit did not end on an attractor on the arm (see escapes)"},
        }
        if arrays:
            d["grid"] = {"x_m": self.x.tolist(), "side": self.side.tolist(), "label": self.labels.tolist(),
                         "fate": self.fates.tolist(), "throws": self.throws.tolist()}
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "Basins":
        if "grid" not in d:
            raise InvalidStateError("grid", "this basin record was written without its arrays")
        g = d["grid"]
        return cls(x=np.asarray(g["x_m"], dtype=float), side=np.asarray(g["side"], dtype=np.int64),
                   labels=np.asarray(g["label"], dtype=np.int64), fates=np.asarray(g["fate"], dtype=np.int64),
                   throws=np.asarray(g["throws"], dtype=np.int64),
                   attractors=tuple(Attractor.from_dict(a) for a in d["attractors"]),
                   certificate=Certificate.from_dict(d["certificate"]), method=str(d["method"]),
                   check=dict(d["check"]), caps=dict(d["caps"]), map_info=dict(d["map"]))

    def plot(self, ax=None, **kwargs):
        """The basin map; see :func:`throwmap.viz.basins.plot_basins`."""
        from ..viz.basins import plot_basins

        return plot_basins(self, ax=ax, **kwargs)



def _certificate(cmap, x, labels, fates, throws, spacing, attractors, check, trap_samples, trap_tol,
                 where: str) -> Certificate:
    """Unique and globally attractive at grid resolution: one attractor reached, no −1, check agrees, trapping.

    ``where`` names the range the grid covers (e.g. "valid starts with x ≤ 0.600 m"):
    the statement holds there only — beyond it a map may have other attractors.
    """
    reached = [a for a in attractors if a.fraction > 0]
    no_escape = not np.any(labels == LABEL_ESCAPE)
    check_ok = (not check) or check["agreement"] == 1.0
    if len(reached) == 1 and no_escape:
        a = reached[0]
        exc = trap_excursion(cmap, a, trap_samples, trap_tol)
        unique = check_ok and exc <= trap_tol
        tmax = int(throws.max())
        dx = max(spacing.values())
        why = "" if unique else (" — but the exact check disagreed" if not check_ok else
                                 f" — but its region is not trapping (images leave it by {exc:.3g} m)")
        statement = (f"{'unique and globally attractive' if unique else 'one attractor reached'} for the {where} "
                     f"(not beyond), at grid resolution: all {x.size} configurations (spacing ≤ {dx:.3g} m) reach "
                     f"attractor "
                     f"#{a.id} ({a.kind}) within {tmax} throws" + (
                         f"; {check['n']} exact orbits agree on {100 * check['agreement']:.2f} %" if check else "")
                     + f"; its region maps into itself to {exc:.2g} m{why}")
        return Certificate(unique=unique, attractor=a.id, n_configs=int(x.size), grid_spacing=spacing,
                           max_throws_to_reach=tmax, check_agreement=float(check.get("agreement", 1.0)),
                           trap_excursion=exc, trap_tol=trap_tol, statement=statement, range_text=where)
    parts = [f"#{a.id} {a.kind} {100 * a.fraction:.2f} %" for a in reached]
    esc = escape_fractions(fates, labels)
    parts += [f"-1 {fate} {100 * v:.2f} %" for fate, v in esc.items()]
    statement = (f"not unique for the {where}: {len(reached)} attractor(s) and escapes share the grid: "
                 + ", ".join(parts))
    return Certificate(unique=False, attractor=None, n_configs=int(x.size), grid_spacing=spacing,
                       max_throws_to_reach=int(throws.max()) if throws.size else 0,
                       check_agreement=float(check.get("agreement", 1.0)), trap_excursion=math.nan,
                       trap_tol=trap_tol, statement=statement, range_text=where)


def _check_cells(cmap, x, s, labels, throws, attractors, reach_tol, max_throws, n_check, gen, n_exact) -> dict:
    """``n_check`` grid configurations drawn with ``gen`` mapped by exact orbits; agreement with the cell labels."""
    pick = np.sort(gen.choice(x.size, size=min(n_check, x.size), replace=False))
    l3, f3, t3 = map_to_attractors(cmap, x[pick], s[pick], attractors, reach_tol, max_throws)
    agree = l3 == labels[pick]
    return {"n": int(pick.size), "agreement": float(np.mean(agree)),
            "throws_mean_abs_diff": float(np.mean(np.abs(t3[agree] - throws[pick][agree])))
            if np.any(agree) else math.nan,
            "disagreeing_x_m": x[pick][~agree][:20].tolist(),
            "disagreeing_side": s[pick][~agree][:20].tolist(), "n_exact_finish": int(n_exact)}


@regime_warnings_once()
def basins(part, arm=None, omega=None, model: str = DEFAULT_MODEL, *, grid=1000, method: str = "auto", limit=None,
           n_seeds: int = 64, reach_tol: float = 1e-6, max_throws: int = 500, n_check: int = 1000,
           max_discover: int = 256, trap_samples: int = 400, trap_tol: float = 5e-4, rng=0, x_max=None,
           caps: RecurrenceCaps = RecurrenceCaps(), progress=None, limits: Limits | None = None,
           **overrides) -> Basins:
    """Label every configuration of a grid with the attractor its orbit reaches (paper Sec. III-D).

    Parameters
    ----------
    part, arm, omega, model
        The throw map (default ``"rigid_body"``; ``omega`` may be a sequence, the
        composed map), or a :class:`~throwmap.analysis.maps.ConfigMap` as ``part``.
    grid
        Points per stable side, evenly spaced over (x_lo, x_max] (default 1000), or
        ``{side: x values}`` in m.
    method
        ``"orbits"``, ``"cells"`` or ``"auto"`` (see the module docstring).
    limit
        A :class:`~throwmap.analysis.limitset.LimitSet` whose attractors to use;
        default: found by :func:`limit_set` from ``n_seeds`` starts per side.
    reach_tol
        An orbit has reached a cycle or band when it lies within this many metres of it
        (default 1 µm; the cell method uses at least half a grid cell).
    max_throws
        Throw cap per orbit (default 500); orbits still unresolved get label −1, fate
        ``"unresolved"``.
    n_check
        Configurations (drawn with ``rng``) mapped by exact orbits to check the cell
        method (default 1000; 0 to skip).
    max_discover
        Unresolved orbits searched for new attractors (default 256).
    trap_samples, trap_tol
        Samples per attractor interval, and the tolerance (m), of the trapping test.
    rng
        Seed or Generator for the seeds and the check sample (same seed, same basins).
    caps
        Caps of the recurrence test (:class:`~throwmap.analysis.caps.RecurrenceCaps`),
        for the limit set and for attractors discovered later.
    progress
        ``progress(stage, done, total)``.
    limits
        Work guard (:class:`~throwmap.budget.Limits`; None: 2 GB, 1800 s): the grid's memory (≈ 160 bytes
        per configuration) and time (one throw per configuration for cells, the mean throws
        to reach an attractor of a sample for orbits, at the time per throw measured
        now) are estimated before the work; above the limits the call is refused with one
        line, unless ``limits.force``.
    overrides
        Any cap by name (``transient=50``), merged into ``caps``; with a part, other
        keywords are throw options for :func:`throwmap.throw_batch`.
    """
    cap_overrides, throw_options = split_options(overrides, not isinstance(part, ConfigMap))
    cmap = as_map(part, arm, omega, model, x_max=x_max, **throw_options)
    caps = resolve_caps(caps, cap_overrides)
    for name, v, lo in (("n_seeds", n_seeds, 1), ("max_throws", max_throws, 1), ("n_check", n_check, 0),
                        ("max_discover", max_discover, 1), ("trap_samples", trap_samples, 2)):
        check_int(name, v, lo)
    for name, v in (("reach_tol", reach_tol), ("trap_tol", trap_tol)):
        check_length(name, v)
    if method not in ("auto", "orbits", "cells"):
        raise InvalidStateError("method", f"must be 'auto', 'orbits' or 'cells', got {shown(method)}")
    limits = Limits.of(limits)
    gen = as_generator(rng)
    n_planned = grid_size(cmap, grid)
    planned = "cells" if method == "cells" or (method == "auto" and n_planned > AUTO_CELLS_ABOVE) else "orbits"
    guard_work(f"basins ({planned})", "grid", n_planned, BYTES_PER_CONFIG, limits,
               throws_per_config=1.0, cmap=cmap, timed_above=0, hint="a coarser --grid")
    x, s, spacing = basin_grid(cmap, grid)
    method = planned

    def stage(name):
        return None if progress is None else (lambda d, t: progress(name, d, t))

    caps_record = caps.to_dict()
    if limit is None:
        seed = int(gen.integers(0, 2**31))
        limit = limit_set(cmap, caps=caps, n_starts=n_seeds, rng=seed, progress=stage("limit set"))
        caps_record = dict(limit.caps)
    attractors = tuple(limit.attractors)
    check = {}
    if method == "orbits" and not limits.force and x.size > 64:
        pick = np.linspace(0, x.size - 1, 64).astype(int)
        _, _, t_sample = map_to_attractors(cmap, x[pick], s[pick], attractors, reach_tol, max_throws)
        guard_work("basins (orbits)", "grid", x.size, BYTES_PER_CONFIG, limits,
                   throws_per_config=max(1.0, float(np.mean(t_sample))), cmap=cmap, timed_above=0,
                   hint="a coarser --grid or --method cells")
    if method == "orbits":
        attractors, labels, fates, throws = exact_with_discovery(
            cmap, x, s, attractors, caps, reach_tol, max_throws, max_discover, stage("orbits"))
    else:
        labels, fates, throws, rest = cell_map(cmap, x, s, spacing, attractors, reach_tol, max_throws,
                                               stage("cells"))
        if rest.size:
            attractors, l2, f2, t2 = exact_with_discovery(cmap, x[rest], s[rest], attractors, caps, reach_tol,
                                                          max_throws, max_discover, stage("exact"))
            labels[rest], fates[rest], throws[rest] = l2, f2, t2
        if n_check:
            check = _check_cells(cmap, x, s, labels, throws, attractors, reach_tol, max_throws, n_check, gen,
                                 rest.size)
    # basin fractions on the attractors
    n = max(1, x.size)
    attractors = tuple(a.with_fraction(float(np.sum(labels == a.id)) / n) for a in attractors)
    info = cmap.describe()
    info["label"] = cmap.label
    info["grid"] = "grid" if not isinstance(grid, dict) else "given"
    if isinstance(grid, dict):
        where = "configurations of the given grid (" + ", ".join(
            f"side {k}: {x[s == k].min():.4g}–{x[s == k].max():.4g} m" for k in np.unique(s)) + ")"
    else:
        where = domain_text(cmap.domain(), isinstance(cmap, ThrowMap))
    cert = _certificate(cmap, x, labels, fates, throws, spacing, attractors, check, trap_samples, trap_tol, where)
    caps_out = dict(caps_record, reach_tol=reach_tol, max_throws=max_throws, n_seeds=n_seeds, n_check=n_check,
                    rng=rng if isinstance(rng, (int, np.integer)) and not isinstance(rng, bool) else None)
    return Basins(x=x, side=s, labels=labels, fates=fates, throws=throws, attractors=attractors, certificate=cert,
                  method=method, check=check, caps=caps_out, map_info=info)
