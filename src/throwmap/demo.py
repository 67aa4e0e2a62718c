"""The main job on the built-in example (``make demo`` / ``throwmap demo``).

The paper's part: a uniform 30-60-90 triangle, hypotenuse 0.17 m, on an arm with
h = −0.01 m, thrown at ω = 4.0 rad/s. Writes into ``out_dir``:

``throw_map.png``         T(x) per side with the diagonal (Fig. 2 analogue);
``orbit.png``             300 throws from (0.12 m, side 0) (Fig. 5/7 analogue);
``model_comparison.png``  jog-length error of the small-angle models vs "paper";
``summary.json``          the part's side table, the orbit's bands, two sample
                          throws with their records, and the model-comparison table.

Every file is written atomically (temp file + rename).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .arm import Arm
from .compare import compare_models
from .io import atomic_write_text, json_ready
from .orbit import iterate
from .parts import triangle_30_60_90
from .throw import throw

__all__ = ["DEMO", "run_demo"]

DEMO = {"hypotenuse": 0.17, "h": -0.01, "omega": 4.0, "x0": 0.12, "side0": 0, "n_throws": 300}
"""Parameters of the built-in example (SI units)."""


def run_demo(out_dir: Path | str = "out", progress=None) -> dict:
    """Run the built-in example and write its figures and summary; returns the summary.

    ``progress``, if given, is called as ``progress(message)`` before each step.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .plotting import plot_throw_map, save_figure

    say = progress or (lambda msg: None)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    part = triangle_30_60_90(DEMO["hypotenuse"])
    arm = Arm(h=DEMO["h"])
    omega = DEMO["omega"]
    files = []

    say("throw map")
    fig = plot_throw_map(part, arm, omega, x_max=0.6)
    files.append(save_figure(fig, out / "throw_map.png"))
    plt.close(fig)

    say("orbit")
    orbit = iterate(part, arm, (DEMO["x0"], DEMO["side0"]), omega, n=DEMO["n_throws"])
    fig = orbit.plot(part=part)
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

    jog = throw(part, arm, 0.2, 0, omega)
    flip = throw(part, arm, 0.5, 0, omega)
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
        "files": [str(f) for f in files] + [str(out / "model_comparison.txt"), str(out / "summary.json")],
    }
    atomic_write_text(out / "model_comparison.txt", comp.table() + "\n")
    atomic_write_text(out / "summary.json", json.dumps(json_ready(summary), indent=2, allow_nan=False))
    return summary
