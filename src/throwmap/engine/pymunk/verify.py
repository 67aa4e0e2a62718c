"""Does an engine run's result hold at half the step? Flags for hard runs and the comparison.

pymunk resolves an impact in one velocity solve per step; on hard contacts (a
landing that drives a vertex deep into the arm, a part that flips from side to
side, a run that gains energy) the result can depend on the step: another side,
centimetres off, or a blow-up. Such runs are *flagged* (:func:`flags`) and
rerun at half ``dt`` and ``coarse_dt``; the result stands only if the rerun
agrees (:func:`disagreement`): the same status per part and, for parts at rest,
the same side and x within ``EngineSettings.agreement``. Otherwise the run is
refused with status ``unconverged`` and the reason in its message.

Cost: on 310 random parts, arms, μ ∈ {0.6, 1, 3, ∞} and ω ∈ [3, 9] rad/s about a
third of the throws are flagged (each rerun costs about twice the first run, so
the batch about 1.7×); rerunning every throw found 3 disagreements, all among
the flagged ones.
"""

from __future__ import annotations

from ...records.outcome import Status

__all__ = ["flags", "disagreement", "PEN_FLAG", "FLIPS_FLAG"]

PEN_FLAG = 0.25
"""A run whose deepest penetration exceeds this fraction of ``penetration_tol`` is rerun."""
FLIPS_FLAG = 2
"""A run in which a part changed side this often (landings on another side) is rerun."""

_FLIPS = 18  # kernels.codes.N_FLIPS


def energy_tolerance(run, settings) -> float:
    """Largest energy gain (J/kg) position correction explains: g × 2 × ``penetration_tol``."""
    return run.scene.arm.g * 2.0 * settings.penetration_tol


def flags(run, settings) -> list[str]:
    """Why ``run`` must be checked at half the step (empty: it need not)."""
    why = []
    if run.status == Status.TIMEOUT:
        why.append("timed out")
    if run.penetration_max > PEN_FLAG * settings.penetration_tol:
        why.append(f"a vertex {run.penetration_max * 1e3:.2f} mm deep")
    flips = max((int(r[_FLIPS]) for r in run.records if r[_FLIPS] == r[_FLIPS]), default=0)
    if flips >= FLIPS_FLAG:
        why.append(f"{flips} side changes")
    if run.energy_gain > energy_tolerance(run, settings):
        why.append(f"gained {run.energy_gain:.3g} J/kg")
    return why


def disagreement(run, again, settings) -> str:
    """How ``again`` (the half-step rerun) contradicts ``run``, or ``""`` where they agree."""
    tol_e = energy_tolerance(run, settings)
    if run.energy_gain > tol_e and again.energy_gain > tol_e:
        return f"gains energy at both steps ({run.energy_gain:.3g}, {again.energy_gain:.3g} J/kg)"
    for i, (a, b) in enumerate(zip(run.statuses, again.statuses)):
        (xa, ka, _), (xb, kb, _) = run.states[i], again.states[i]
        if a != b:
            return f"part {i}: {a.label} at dt = {run.dt:g} s, {b.label} at {again.dt:g} s"
        if a == Status.OK and (ka != kb or abs(xa - xb) > settings.agreement):
            return (f"part {i}: x = {xa:.5f} m on side {ka} at dt = {run.dt:g} s, {xb:.5f} m on side {kb} at "
                    f"{again.dt:g} s (agreement {settings.agreement * 1e3:g} mm)")
    return ""
