"""The main job on the built-in example (``make demo`` / ``throwmap demo``).

The paper's part: a uniform 30-60-90 triangle, hypotenuse 0.17 m, on an arm with
h = −0.01 m, thrown at ω = 4.0 rad/s. Writes into ``out_dir``:

``throw_map.png``         T(x) per side with the diagonal (Fig. 2 analogue; model paper);
``orbit.png``             300 throws from (0.12 m, side 0) (Fig. 5/7 analogue; model paper);
``model_comparison.png``  jog-length error of the small-angle models vs "paper";
``model_comparison.txt``  the comparison table (x ≤ 0.6 m, 2000 starts per side, ω = 1…5 rad/s);
``limit_set.png``         the limit set along the arm with r_i, l_i and an orbit of
                          40 throws on it (Fig. 5 analogue; model rigid_body);
``throw_map_limits.png``  T(x) per side with r_i, l_i and the limit set (Fig. 2 analogue);
``basins.png``            basins of attraction on 2000 configurations per side, with the
                          certificate of global attractivity;
``funnels.png``           the funnel graph of ω = 3 and 4 rad/s (arm analysed to 1 m)
                          towards the goal x in [0.50, 0.90] m on any side (Sec. I-A);
``summary.json``          the part's side table, the orbit's bands, two sample
                          throws with their records, the model-comparison table, and
                          the analysis: r_i and l_i (m), the limit set's kind and bands,
                          basin fractions with the certificate, the funnel order.

Every file is written atomically (temp file + rename); :data:`OUTPUTS` names them all, and
:func:`run_demo` checks that it wrote exactly those (README.md's list is tested against it).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..system.arm import Arm
from .compare import compare_models
from ..io.files import atomic_write_text, make_directory
from ..serial import json_ready
from ..throws.orbit import iterate
from ..system.catalogue import triangle_30_60_90
from ..throws.throw import throw

__all__ = ["ANALYSIS", "DEMO", "OUTPUTS", "DemoResult", "run_demo"]

OUTPUTS = ("throw_map.png", "orbit.png", "model_comparison.png", "model_comparison.txt", "limit_set.png",
           "throw_map_limits.png", "basins.png", "funnels.png", "summary.json")
"""Every file :func:`run_demo` writes into its folder, in order."""

DEMO = {"hypotenuse": 0.17, "h": -0.01, "omega": 4.0, "x0": 0.12, "side0": 0, "n_throws": 300, "model": "paper"}
"""Parameters of the built-in example (SI units)."""

ANALYSIS = {"model": "rigid_body", "x_max": 0.6, "basin_grid": 2000, "funnel_omegas": (3.0, 4.0),
            "funnel_x_max": 1.0, "funnel_grid": 400, "goal": "0:0.50-0.90,1:0.50-0.90,2:0.50-0.90", "seed": 0}
"""Parameters of the demo's limit-set, basin and funnel analysis (SI units; grids: points per side)."""


@dataclass(frozen=True, slots=True)
class DemoResult:
    """What :func:`run_demo` did: ``out_dir``, the ``files`` it wrote (paths, in :data:`OUTPUTS` order of writing)
    and the ``summary`` it wrote as ``summary.json`` (see the module docstring)."""

    out_dir: str
    files: tuple
    summary: dict

    def table(self) -> str:
        """The example, the limit set found and the files written, one per line."""
        ex, an = self.summary["example"], self.summary["analysis"]
        lines = [f"demo: {self.summary['part']['name']} on h = {ex['h']:g} m at ω = {ex['omega']:g} rad/s; limit set "
                 f"({an['parameters']['model']}): {an['limit_set']['kind']}; orbit of {ex['n_throws']} throws "
                 f"({ex['model']}): {self.summary['orbit']['status']}"]
        return "\n".join(lines + [f"wrote {f}" for f in self.files])

    def to_dict(self) -> dict:
        """The summary (JSON-ready), as ``summary.json`` holds it."""
        return json_ready(self.summary)


def run_demo(out_dir: Path | str = "out", progress=None) -> DemoResult:
    """Run the built-in example and write its figures and summary; returns a :class:`DemoResult` (its ``to_dict()``
    is the summary).

    ``progress``, if given, is called as ``progress(message)`` before each step.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..throws.samples import throw_map_samples
    from ..viz.style import save_figure

    say = progress or (lambda msg: None)
    out = Path(out_dir)
    make_directory(out, "out")  # only it: a missing folder above it is refused
    part = triangle_30_60_90(DEMO["hypotenuse"])
    arm = Arm(h=DEMO["h"])
    omega = DEMO["omega"]
    files = []

    say("throw map")
    fig = throw_map_samples(part, arm, omega, model=DEMO["model"], x_max=0.6).plot(compact=True)
    files.append(save_figure(fig, out / "throw_map.png"))
    plt.close(fig)

    say("orbit")
    orbit = iterate(part, arm, (DEMO["x0"], DEMO["side0"]), omega, n=DEMO["n_throws"], model=DEMO["model"])
    fig = orbit.plot(part=part, arm=arm)
    files.append(save_figure(fig, out / "orbit.png"))
    plt.close(fig)
    tail = slice(len(orbit.x) // 3, None)  # after the transient
    bands = {}
    for s in part.stable_sides:
        xs = orbit.x[tail][orbit.side[tail] == s]
        if xs.size:
            bands[str(s)] = {"x_min": float(xs.min()), "x_max": float(xs.max()), "visits": int(xs.size)}

    say("model comparison")
    comp = compare_models(part, arm, omegas=(1.0, 2.0, 3.0, 4.0, 5.0), n_x=2000, x_max=0.6)
    fig = comp.plot()
    files.append(save_figure(fig, out / "model_comparison.png"))
    plt.close(fig)

    analysis, more = _analysis(part, arm, omega, out, say, plt)
    files += more

    jog = throw(part, arm, 0.2, 0, omega, model=DEMO["model"])
    flip = throw(part, arm, 0.5, 0, omega, model=DEMO["model"])
    summary = {
        "example": dict(DEMO),
        "part": {
            "name": part.name,
            "mass_kg": part.mass,
            "radius_of_gyration_m": part.radius_of_gyration,
            "sides": [
                {"side": k, "stable": bool(part.stable[k]), "d_m": float(part.d[k]), "u_L_m": float(part.uL[k]),
                 "u_R_m": float(part.uR[k]), "length_m": float(part.length[k])}
                for k in range(part.n_sides)
            ],
        },
        "arm": {"h_m": arm.h, "g_m_s2": arm.g, "length_m": arm.length},
        "orbit": {
            "n_throws": orbit.n_throws,
            "status": orbit.status.label,
            "n_flips": int(sum(o.kind == "flip" for o in orbit.outcomes)),
            "lift_off_fraction": float(np.mean([o.lift_off for o in orbit.outcomes])) if orbit.outcomes else 0.0,
            "bands_after_transient": bands,
            "x_final_m": float(orbit.x[-1]),
            "side_final": int(orbit.side[-1]),
        },
        "sample_throws": {"jog": jog.to_dict(), "flip": flip.to_dict()},
        "model_comparison": comp.to_dict(),
        "analysis": analysis,
        "files": [str(f) for f in files] + [str(out / "model_comparison.txt"), str(out / "summary.json")],
    }
    written = [Path(f).name for f in summary["files"]]
    if sorted(written) != sorted(OUTPUTS):  # the documented list (OUTPUTS, README.md) is the written one
        raise RuntimeError(f"demo: writes {written}, but OUTPUTS lists {list(OUTPUTS)}")
    atomic_write_text(out / "model_comparison.txt", comp.table() + "\n")
    atomic_write_text(out / "summary.json", json.dumps(json_ready(summary), indent=2, allow_nan=False))
    return DemoResult(str(out), tuple(summary["files"]), summary)


def _analysis(part, arm, omega, out: Path, say, plt) -> tuple[dict, list]:
    """Critical points, limit set, basins and funnels of the example (paper Sec. III-D, I-A); figures and summary."""
    from ..analysis import basins, critical_points, funnels, limit_set
    from ..throws.samples import sample_map
    from ..viz.basins import plot_basins
    from ..viz.funnels import plot_funnel_graph
    from ..viz.limit_set import plot_limit_set
    from ..analysis.maps import ThrowMap
    from ..analysis.orbits import orbit_on_attractor
    from ..viz.style import save_figure

    p = ANALYSIS
    model = p["model"]
    files = []

    say("critical points and limit set")
    crit = critical_points(part, arm, omega, model, x_max=p["x_max"])
    limit = limit_set(part, arm, omega, model, x_max=p["x_max"], rng=p["seed"])
    orbit = orbit_on_attractor(part, arm, omega, model, limit)
    fig = plot_limit_set(limit, critical=crit, orbit=orbit)
    files.append(save_figure(fig, out / "limit_set.png"))
    plt.close(fig)
    fig = sample_map(ThrowMap(part, arm, omega, model, p["x_max"])).plot(critical=crit, limit=limit)
    files.append(save_figure(fig, out / "throw_map_limits.png"))
    plt.close(fig)

    say("basins")
    bas = basins(part, arm, omega, model, grid=p["basin_grid"], limit=limit, rng=p["seed"], x_max=p["x_max"])
    fig = plot_basins(bas)
    files.append(save_figure(fig, out / "basins.png"))
    plt.close(fig)

    say("funnels")
    graph = funnels(part, arm, list(p["funnel_omegas"]), model, goal=p["goal"], grid=p["funnel_grid"],
                    x_max=p["funnel_x_max"], rng=p["seed"])
    fig = plot_funnel_graph(graph)
    files.append(save_figure(fig, out / "funnels.png"))
    plt.close(fig)

    cp = crit.to_dict()
    summary = {
        "parameters": {k: (list(v) if isinstance(v, tuple) else v) for k, v in p.items()},
        "critical_points": {"r_m": cp["r_m"], "l_m": cp["l_m"], "next_kind": cp["next_kind"],
                            "flips_beyond": cp["flips_beyond"], "l_method": cp["l_method"]},
        "limit_set": {
            "kind": limit.kind, "unique": limit.unique, "n_starts": limit.n_starts, "escapes": dict(limit.escapes),
            "attractors": [{"id": a.id, "kind": a.kind, "period": a.period, "lyapunov": a.lyapunov,
                            "bands_m": [{"side": s, "lo": lo, "hi": hi} for s, lo, hi in a.bands]}
                           for a in limit.attractors],
            "orbit_drawn": {"x0_m": float(orbit.x[0]), "side0": int(orbit.side[0]), "n_throws": orbit.n_throws},
        },
        "basins": {"n_configs": bas.n_configs, "grid_per_side": p["basin_grid"], "method": bas.method,
                   "fractions": {str(k): v for k, v in bas.fractions.items()}, "escapes": bas.escapes,
                   "certificate": {"unique": bas.certificate.unique, "statement": bas.certificate.statement}},
        "funnels": {
            "omegas_rad_s": list(p["funnel_omegas"]), "goal": p["goal"],
            "funnels": [{"name": f.name, "mouth_fraction": f.mouth_fraction, "priority": graph.rank.get(i)}
                        for i, f in enumerate(graph.funnels)],
            "edges": [{"from": graph.funnels[i].name, "to": graph.funnels[j].name, "share": sh}
                      for i, j, sh in graph.edges],
            "order": [graph.funnels[i].name for i in graph.order],
        },
    }
    return summary, files
