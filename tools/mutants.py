"""Hand-made mutation pass over the kernels and the analysis (issue 10, item 3).

Each mutant is one plausible one-line slip: a file under ``src/throwmap``, an exact
snippet that must occur there exactly once, its replacement and a short
description. The mutants are applied one at a time to the checkout this script
lives in (run it in a scratch git worktree, never in a tree others are editing),
each followed by its targeted test subset (``pytest -x``, a per-mutant timeout),
and the file is restored afterwards (also on Ctrl-C). A mutant is *killed* when
the subset fails (or times out), *survives* when it passes.

Numba: every run gets a fresh ``NUMBA_CACHE_DIR`` for a kernel mutant (the
package-wide digest of :mod:`throwmap.kernels.numba_cache` would also refuse a
stale entry; the fresh directory makes that independent of it), analysis mutants
share one directory warmed by the baseline. Python byte code goes to a private
``PYTHONPYCACHEPREFIX`` and is not written, so a restored source never meets a
mutant's ``.pyc``. Each run is ``nice -n 10``, one at a time.

Mutants marked ``equivalent`` (no observable behaviour change, reason given)
are listed but not run and not counted.

Usage::

    git worktree add --detach /tmp/mut main
    cd /tmp/mut && PYTHONPATH=src python tools/mutants.py            # all mutants
    python tools/mutants.py --only K03 A07 --timeout 300            # a few
    python tools/mutants.py --list                                   # the catalogue
    python tools/mutants.py --json out.json --markdown out.md        # save the table

The score is killed / (killed + survived) over the non-equivalent mutants.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SRC = ROOT / "src" / "throwmap"

CLOSED_FORMS = "tests/kernels/test_closed_forms.py"  # the kill tests this pass added, each naming its mutants
PIVOT_CASCADE = "tests/kernels/test_pivot_cascade.py"
SYNTHETIC_MAPS = "tests/analysis/test_synthetic_maps.py"
# the kill tests of the N block (the oracle, the contact kernels, the input checks, the success rules)
ORACLE_RULES = "tests/models/test_engine_oracle_rules.py"
STATICS_EDGES = "tests/statics/test_documented_range_edges.py"
GOAL_SETS = "tests/stochastic/test_goal_sets_and_starts.py"
START_RANGE = "tests/control/test_start_range.py"
CONFIG_BOUNDS = "tests/experiments/test_config_bounds_inclusive.py"
FEED_SUCCESS = "tests/design/test_feed_success_rule.py"
NEGATIVE_SLIPS = "tests/system/test_negative_unit_slips.py"
SNAPSHOT_CAPTIONS = "tests/reproduce/test_snapshot_captions.py"
CONTACT_WINDOWS = "tests/kernels/test_contact_windows_after_impulses.py"
ADDED_BY_THE_PASS = (CLOSED_FORMS, PIVOT_CASCADE, SYNTHETIC_MAPS, ORACLE_RULES, STATICS_EDGES, GOAL_SETS, START_RANGE,
                     CONFIG_BOUNDS, FEED_SUCCESS, NEGATIVE_SLIPS, SNAPSHOT_CAPTIONS, CONTACT_WINDOWS)
WALL_CONTACT = ("tests/kernels/test_wall_contact_holds.py", "tests/kernels/test_wall_modes.py",
                "tests/kernels/test_wall.py", CONTACT_WINDOWS)
TESTS = (  # (path prefix under src/throwmap, test subset run for a mutant there: first match wins)
    ("kernels/rigid_body/foot.py", WALL_CONTACT),  # the N block's kernels: before the generic kernels/rigid_body/
    ("kernels/rigid_body/flight.py", WALL_CONTACT),
    ("kernels/rigid_body/wall", WALL_CONTACT),
    ("kernels/small_angle.py", ("tests/kernels/test_small_angle.py", "tests/kernels/test_mu_zero.py", CLOSED_FORMS)),
    ("kernels/rigid_body/", ("tests/kernels/test_rigid_body.py", "tests/kernels/test_impact_process.py",
                             "tests/kernels/test_rigid_body_stick.py", "tests/kernels/test_mu_zero.py", CLOSED_FORMS)),
    ("kernels/", ("tests/kernels/test_throw_physics.py", "tests/kernels/test_paper_record.py",
                  "tests/kernels/test_contact_scale.py", "tests/kernels/test_mu_zero.py", CLOSED_FORMS,
                  PIVOT_CASCADE)),
    ("analysis/critical.py", ("tests/analysis/test_critical.py", SYNTHETIC_MAPS)),
    ("analysis/basins.py", ("tests/analysis/test_basins_funnels.py", "tests/analysis/test_budget.py", SYNTHETIC_MAPS)),
    ("analysis/cellmap.py", ("tests/analysis/test_basins_funnels.py", SYNTHETIC_MAPS)),
    ("analysis/funnels.py", ("tests/analysis/test_basins_funnels.py", "tests/analysis/test_funnel_ranges.py", SYNTHETIC_MAPS)),
    ("analysis/sets.py", ("tests/analysis/test_basins_funnels.py", SYNTHETIC_MAPS)),
    ("analysis/", ("tests/analysis/test_maps_limitset.py", "tests/analysis/test_recurrence_verified.py",
                   "tests/analysis/test_results.py", "tests/analysis/test_orbits.py",
                   "tests/analysis/test_ranges_reprs.py", SYNTHETIC_MAPS)),
    ("models/engine", ("tests/engine/test_engine_oracle.py", ORACLE_RULES)),
    ("statics/", ("tests/statics/test_input_checks.py", "tests/statics/test_rest_lp.py",
                  "tests/statics/test_results.py", STATICS_EDGES)),
    ("stochastic/", ("tests/stochastic/test_chain_input.py", "tests/stochastic/test_chain.py",
                     "tests/stochastic/test_build.py", "tests/stochastic/test_mc_curve.py", GOAL_SETS)),
    ("control/planner.py", ("tests/control/test_plan_input.py", "tests/control/test_planner.py", START_RANGE)),
    ("io/", ("tests/experiments/test_config_ranges.py", "tests/io/test_spec.py", "tests/io/test_config.py",
             CONFIG_BOUNDS)),
    ("experiments/", ("tests/experiments/test_config_ranges.py", CONFIG_BOUNDS)),
    ("design/api.py", ("tests/design/test_design_honesty.py", FEED_SUCCESS)),
    ("errors.py", ("tests/system/test_scale_warnings.py", NEGATIVE_SLIPS)),
    ("system/", ("tests/system/test_scale_warnings.py", "tests/system/test_part.py", NEGATIVE_SLIPS)),
    ("reproduce/", ("tests/reproduce/test_captions.py", "tests/reproduce/test_reproduce.py", SNAPSHOT_CAPTIONS)),
)
"""Each mutant runs the test files that mirror its module, then this tool's own kill tests *last*:
with ``-x`` the "caught by" column then names an existing test whenever one catches the
mutant, so one pass gives the score before the kill tests (caught by an existing test)
and after (caught by any)."""
PYTEST_ARGS = ("-x", "-q", "-p", "no:cacheprovider")


@dataclass(frozen=True)
class Mutant:
    """One slip: ``old`` (exactly once in ``path``, relative to src/throwmap) becomes ``new``."""

    id: str
    path: str
    old: str
    new: str
    what: str
    equivalent: str = ""  # non-empty: why no test can see it (not run, not counted)

    @property
    def tests(self) -> tuple[str, ...]:
        return next(t for prefix, t in TESTS if self.path.startswith(prefix))


def M(id, path, old, new, what, equivalent=""):
    return Mutant(id, path, old, new, what, equivalent)


MUTANTS: tuple[Mutant, ...] = (
    # ------------------------------------------------------------------ kernels/flight.py
    M("K01", "kernels/flight.py", "return -(h + d) * omega, x0 * omega, omega",
      "return -(h - d) * omega, x0 * omega, omega", "release v_x: h + d → h − d"),
    M("K02", "kernels/flight.py", "v[j] = sb * w[j, 0] + cb * w[j, 1]", "v[j] = sb * w[j, 0] - cb * w[j, 1]",
      "rest_offsets: rotation sign of v"),
    M("K03", "kernels/flight.py", "dg = vy - g * t + w * (ru[j] * (1.0 + cm1) - rv[j] * s)",
      "dg = vy - g * t + w * (ru[j] * (1.0 + cm1) + rv[j] * s)", "gap rate (Newton polish): sign of the v_j term"),
    M("K04", "kernels/flight.py", "    for it in range(3):\n        if it > 0:",
      "    for it in range(0):\n        if it > 0:", "no Newton polish after the guarded search"),
    M("K05", "kernels/flight.py", "disc = math.sqrt(dg * dg + 2.0 * M * gp)", "disc = math.sqrt(dg * dg + 0.5 * M * gp)",
      "lower-bound step: 2M → M/2 (steps may pass a root)"),
    M("K06", "kernels/flight.py", "M = g_pos + w * w * ell[j]", "M = g_pos + w * ell[j]",
      "curvature bound ω²ℓ → ωℓ (units)"),
    M("K07", "kernels/flight.py", "if gj <= tol_j and (t > 0.0 or dg <= 0.0):",
      "if gj <= tol_j and (t >= 0.0 or dg <= 0.0):", "a vertex on the line leaving it at t = 0 counts as contact"),
    M("K08", "kernels/flight.py", "b[j] = vy + w * ru[j]", "b[j] = vy - w * ru[j]", "first_contact: gap rate sign"),
    M("K09", "kernels/flight.py", "c = dy + rv[j]", "c = dy - rv[j]", "gap constants: dy − v_j"),
    # ------------------------------------------------------------------ kernels/impact.py
    M("K10", "kernels/impact.py", "wp = H / (rho2 + rx * rx + ry * ry)", "wp = H / (rho2 + rx * rx)",
      "Eq. 4: |r|² → r_x²"),
    M("K11", "kernels/impact.py", "H = rho2 * w + ry * vx - rx * vy", "H = rho2 * w - ry * vx - rx * vy",
      "Eq. 4: sign of r_y v_x"),
    M("K12", "kernels/impact.py", "return ry * wp, -rx * wp, wp", "return -ry * wp, -rx * wp, wp",
      "post-impact v_x sign"),
    # ------------------------------------------------------------------ kernels/paper.py
    M("K13", "kernels/paper.py", "(x0 * x0 + (h + dk) * (h + dk) + rho2) + g * dk",
      "(x0 * x0 + (h + dk) * (h + dk)) + g * dk", "release energy drops the spin term ρ²ω²"),
    M("K14", "kernels/paper.py", "yc = h + dk + vy0 * t - 0.5 * gn * t * t", "yc = h + dk + vy0 * t + 0.5 * gn * t * t",
      "CM height at impact: sign of gravity"),
    M("K15", "kernels/paper.py", "        if x + uL[k] <= -back:\n            status = C.BEHIND_JOINT",
      "        if x - uL[k] <= -back:\n            status = C.BEHIND_JOINT", "final behind-joint test: x − u_L",
      "the cascade already returns BEHIND_JOINT whenever its pivot or landing vertex (the two support "
      "vertices of the final side) is at x ≤ −back (kernels/roll.py, guard leave_arm), so an OK result has "
      "x + u_L > −back and x − u_L > 0 > −back: this final check never fires either way"),
    M("K16", "kernels/paper.py", "rec[C.MU_IMPACT] = abs(jx) / jy", "rec[C.MU_IMPACT] = jx / jy",
      "impact friction ratio without abs"),
    M("K17", "kernels/paper.py", "b[j] = omega * (x0 + pu[j])", "b[j] = omega * (x0 - pu[j])",
      "gap rates at release: x0 − u_j"),
    # ------------------------------------------------------------------ kernels/roll.py
    M("K18", "kernels/roll.py", "    k = (j - 1) % n\n    return math.atan2(d[k], -uL[k])",
      "    k = j % n\n    return math.atan2(d[k], -uL[k])", "θa_j uses side j, not j − 1"),
    M("K19", "kernels/roll.py", "s_star = min(max(e / 3.0, s_lo), s_hi)", "s_star = min(max(e / 2.0, s_lo), s_hi)",
      "minimum of N at s = e/2 instead of e/3"),
    M("K20", "kernels/roll.py", "f_max = k * math.sqrt(max(1.0 - s_lo * s_lo, 0.0))",
      "f_max = k * math.sqrt(max(1.0 - s_hi * s_hi, 0.0))", "friction bound uses the smallest cos (skips samples)"),
    M("K21", "kernels/roll.py", "s, c = s * cd + c * sd, c * cd - s * sd", "s, c = s * cd - c * sd, c * cd - s * sd",
      "arc-sample rotation recurrence: sign"),
    M("K22", "kernels/roll.py", "elif math.sin(end) > math.sin(theta):", "elif math.sin(end) < math.sin(theta):",
      "reach_end: barrier when the end lies lower"),
    M("K23", "kernels/roll.py", "return math.asin(s_turn) if dirn > 0 else math.pi - math.asin(s_turn)",
      "return math.asin(s_turn) if dirn < 0 else math.pi - math.asin(s_turn)", "turning angle on the wrong branch"),
    M("K24", "kernels/roll.py", "w2 = 2.0 * (E - g * lj * math.sin(end)) / I",
      "w2 = 1.0 * (E - g * lj * math.sin(end)) / I", "landing speed: factor 2 dropped"),
    M("K25", "kernels/roll.py", "w_new = thdot * (rho2 + uA * uB + dk * dk) / IB",
      "w_new = thdot * (rho2 + uA * uB + dk * dk) / IA", "side landing: divide by I_A, not I_B"),
    M("K26", "kernels/roll.py", "lifts = (w_new > 0.0) if land_dir > 0 else (w_new < 0.0)",
      "lifts = (w_new > 0.0) if land_dir > 0 else (w_new > 0.0)", "lift test ignores the landing sense"),
    M("K27", "kernels/roll.py", "return k_after < min(g * (lA - dk), g * (lB - dk))",
      "return k_after < max(g * (lA - dk), g * (lB - dk))", "rocking rest below either barrier (max for min)"),
    M("K28", "kernels/roll.py", "        return j, x_cm + uL[k], theta_a(j, n, d, uL)",
      "        return j, x_cm - uL[k], theta_a(j, n, d, uL)", "tip_over pivot x: x − u_L"),
    M("K29", "kernels/roll.py", "theta = ta_j[j] if land_dir > 0 else tb_j[j]",
      "theta = tb_j[j] if land_dir > 0 else ta_j[j]", "pivot on B starts at the wrong end angle"),
    M("K30", "kernels/roll.py", "if rec[C.N_IMPACTS] > max_impacts:", "if rec[C.N_IMPACTS] >= max_impacts:",
      "impact cap off by one"),
    # ------------------------------------------------------------------ kernels/small_angle.py
    M("K31", "kernels/small_angle.py", "t = 2.0 * omega * (x0 + u) / g  # 1.", "t = 2.0 * omega * (x0 - u) / g  # 1.",
      "first-order flight time: R − u_L"),
    M("K32", "kernels/small_angle.py", "geff = g - dk * omega * omega", "geff = g + dk * omega * omega",
      "second order: effective gravity sign"),
    M("K33", "kernels/small_angle.py", "cph = 1.0 if order == 1 else 1.0 - 0.5 * phi * phi",
      "cph = 1.0 if order == 1 else 1.0 + 0.5 * phi * phi", "second order: cos φ ≈ 1 + φ²/2"),
    M("K34", "kernels/small_angle.py", "if wp > 0.0 and K + U - U_crit > 0.0:", "if wp > 0.0 or K + U - U_crit > 0.0:",
      "flip test: and → or"),
    M("K35", "kernels/small_angle.py", "x = p - uR[k]", "x = p + uR[k]", "flip rest position: p + u_R"),
    M("K36", "kernels/small_angle.py", "U_crit = g * math.sqrt(u * u + dk * dk)", "U_crit = g * (u * u + dk * dk)",
      "critical energy without the square root (units)"),
    M("K37", "kernels/small_angle.py", "p -= elen[k]", "p += elen[k]", "rolling over unstable sides: sign"),
    # ------------------------------------------------------------------ kernels/rigid_body/
    M("K38", "kernels/rigid_body/impact.py", "Knn = 1.0 + rx * rx / rho2", "Knn = 1.0 + ry * ry / rho2",
      "inverse-inertia K_nn uses r_y"),
    M("K39", "kernels/rigid_body/impact.py", "if jn0 >= 0.0 and abs(jt0) <= mu * jn0:",
      "if jn0 >= 0.0 and jt0 <= mu * jn0:", "sticking-impact cone test without abs"),
    M("K40", "kernels/rigid_body/impact.py", "at = Ktn - mu * sig * Ktt", "at = Ktn + mu * sig * Ktt",
      "Routh: du_t/dp sign of friction"),
    M("K41", "kernels/rigid_body/impact.py", "if p_n <= p_t:", "if p_n >= p_t:",
      "Routh: which event ends the slide phase"),
    M("K42", "kernels/rigid_body/impact.py", "wp = w + (rx * Pn - ry * Pt) / rho2", "wp = w + (rx * Pn + ry * Pt) / rho2",
      "spin change from the impulse: sign of r_y P_t"),
    M("K43", "kernels/rigid_body/impact.py", "pt_stop = -ut / Ktt", "pt_stop = -ut / Knn",
      "μ = ∞ limit: K_nn for K_tt"),
    M("K44", "kernels/rigid_body/impact.py", "            if abs(lam) <= mu:", "            if lam <= mu:",
      "stick after slip stops: test without abs"),
    M("K45", "kernels/rigid_body/impact.py", "        r = abs(pt) / pn", "        r = pt / pn",
      "record_impact friction ratio without abs"),
    M("K46", "kernels/rigid_body/flat.py", "dist = 0.5 * vx * vx / dec", "dist = vx * vx / dec",
      "flat slide distance v²/(μg), not v²/(2μg)"),
    M("K47", "kernels/rigid_body/landing.py", "jt = -mu * jn if vxm > 0.0 else mu * jn",
      "jt = mu * jn if vxm > 0.0 else -mu * jn", "flat landing: friction along the slip"),
    M("K48", "kernels/rigid_body/landing.py", "vxm = va - thdot * dk", "vxm = va + thdot * dk",
      "side landing: CM v_x sign of ω d"),
    M("K49", "kernels/rigid_body/landing.py", "return arc_ok(th_A, E_B, lA, rho2 + lA * lA, g, mu, -land_dir)",
      "return arc_ok(th_A, E_B, lA, rho2 + lA * lA, g, mu, land_dir)", "rocking-rest swing back about A: sense"),
    M("K50", "kernels/rigid_body/slide.py", "    sig = -1.0 if f_stick > 0.0 else 1.0\n    for _ in range(2):",
      "    sig = 1.0 if f_stick > 0.0 else -1.0\n    for _ in range(2):", "slip start: first sense tried along F"),
    M("K51", "kernels/rigid_body/slide.py", "if not from_slip and nf > 0.0 and abs(ff) <= mu * nf:",
      "if not from_slip and nf > 0.0 and ff <= mu * nf:", "stick test of the contact LCP without abs"),
    M("K52", "kernels/rigid_body/stick.py", "if abs(f0) > mu * n0:", "if f0 > mu * n0:",
      "sticking phase slip test without abs"),
    M("K53", "kernels/rigid_body/swing.py", "if max(abs(dx), abs(dy), abs(dz)) < 1e-3:",
      "if max(abs(dx), abs(dy), abs(dz)) < 1e-1:", "Carlson R_F: series started too early"),
    M("K54", "kernels/rigid_body/swing.py", "qq = -0.5 * (q1 + r) if q1 >= 0.0 else -0.5 * (q1 - r)",
      "qq = -0.5 * (q1 - r) if q1 >= 0.0 else -0.5 * (q1 + r)", "stable quadratic formula: wrong branch",
      "both branches give the same two roots of P'' (Vieta); only the rounding of a near-zero root differs, and "
      "those roots only split the interval for bisecting P'"),
    # ------------------------------------------------------------------ analysis/recurrence.py
    M("A01", "analysis/recurrence.py", "for p in range(1, max_period + 1):", "for p in range(1, max_period):",
      "longest period never tested"),
    M("A02", "analysis/recurrence.py", "if abs(b.min() - a.min()) > gap or abs(b.max() - a.max()) > gap:",
      "if abs(b.min() - a.min()) > gap and abs(b.max() - a.max()) > gap:", "stationarity: or → and"),
    M("A03", "analysis/recurrence.py", "return bool(np.any((b < 0.5 * a) & (a > tol)))",
      "return bool(np.any((b < 0.5 * a) | (a > tol)))", "converging test: & → |"),
    M("A04", "analysis/cycles.py", "all(a[0] == b[0] and abs(a[1] - b[1]) <= 10 * tol",
      "all(a[0] == b[0] or abs(a[1] - b[1]) <= 10 * tol", "same cycle points: and → or"),
    M("A05", "analysis/cycles.py", "max(q[1] for q in pts) - min(q[1] for q in pts) <= 10 * tol:",
      "max(q[1] for q in pts) - min(q[1] for q in pts) <= 1e4 * tol:", "collapse a cycle to a point at 1e4 tol",
      "a true cycle never satisfies |T(x) − x| ≤ tol, so the fixed-point search from its point fails and the cycle "
      "is kept: the threshold only decides where that search is tried (work, not results)"),
    M("A06", "analysis/recurrence.py", "p[0] == q[0] and p[1] <= q[2] + gap and q[1] <= p[2] + gap",
      "p[0] == q[0] and p[1] <= q[2] + gap or q[1] <= p[2] + gap", "band overlap: and → or"),
    M("A27", "analysis/cycles.py", "return (st == C.OK) & (sn == back_s) & (np.abs(xn - back_x) <= tol)",
      "return (st == C.OK) & (np.abs(xn - back_x) <= tol)", "closing test ignores the side"),
    M("A28", "analysis/cycles.py", "if int(st[0]) != C.OK or int(s[0]) != int(want_s):",
      "if int(st[0]) != C.OK and int(s[0]) != int(want_s):", "cycle residual: or → and",
      "the residual re-throws points of tails recorded resting on those sides; a deterministic map repeats them, "
      "so an escape or a side change with the other test passing cannot occur"),
    M("A29", "analysis/cycles.py", "if not res <= tol:", "if not res <= 1e3 * tol:", "cycle confirmed at 1000 tol",
      "closing() has already required |T(x_last) − x_(last−p)| ≤ tol on the same tails, which is the residual's "
      "last term, and its other terms are exact re-throws of recorded states (or ≤ tol by the fixed-point search)"),
    M("A07", "analysis/recurrence.py", "lyap = float(np.mean(np.log(np.abs(sl)))) if finite",
      "lyap = float(np.mean(np.log(sl))) if finite", "cycle Lyapunov exponent without abs"),
    M("A08", "analysis/recurrence.py", "fate_step[alive[bad]] = t + 1", "fate_step[alive[bad]] = t",
      "escape step off by one"),
    # ------------------------------------------------------------------ analysis/attractors.py
    M("A09", "analysis/attractors.py", "return bool(abs(self.multiplier) < 1.0)", "return bool(self.multiplier < 1.0)",
      "stability without abs"),
    M("A10", "analysis/attractors.py", "out |= (side == s) & (x >= lo - tol) & (x <= hi + tol)",
      "out |= (side == s) & (x >= lo + tol) & (x <= hi + tol)", "contains: lower end shrinks by tol"),
    M("A11", "analysis/attractors.py", "cut = np.flatnonzero(np.diff(xs) > gap)", "cut = np.flatnonzero(np.diff(xs) >= 0)",
      "band split at every point"),
    # ------------------------------------------------------------------ analysis/sets.py
    M("A12", "analysis/sets.py", "out |= (side == s) & (x >= lo - tol) & (x <= hi + tol)",
      "out |= (side == s) & (x > lo - tol) & (x <= hi + tol)", "contains: open at the lower end"),
    M("A13", "analysis/sets.py", "or hi < lo:", "or hi <= lo:", "a one-point interval refused"),
    # ------------------------------------------------------------------ analysis/critical.py
    M("A14", "analysis/critical.py", "open_ = [s for s in todo if todo[s][1] - todo[s][0] > xtol]",
      "open_ = [s for s in todo if todo[s][1] - todo[s][0] > 1e3 * xtol]", "r bracket refined to 1000 xtol only"),
    M("A15", "analysis/critical.py", "outward = np.all(xn[jog] > X[jog])", "outward = np.any(xn[jog] > X[jog])",
      "hull: outward if any jog moves out"),
    M("A16", "analysis/critical.py", "abs(new[s][0] - iv[s][0]) <= xtol and abs(new[s][1] - iv[s][1]) <= 2 * spacing",
      "abs(new[s][0] - iv[s][0]) <= xtol or abs(new[s][1] - iv[s][1]) <= 2 * spacing", "hull converged: and → or"),
    M("A17", "analysis/critical.py", "box[j] = [i_src, float(grid[max(k - 1, 0)])", "box[j] = [i_src, float(grid[max(k, 0)])",
      "next-point bracket: lower end off by one"),
    # ------------------------------------------------------------------ analysis/cellmap.py
    M("A18", "analysis/cellmap.py", "throws[active[bad]] = t + 1", "throws[active[bad]] = t",
      "escape throw count off by one"),
    M("A19", "analysis/cellmap.py", "return all(p[0] == q[0] and abs(p[1] - q[1]) <= tol",
      "return all(p[0] == q[0] and p[1] - q[1] <= tol", "same attractor without abs"),
    M("A20", "analysis/cellmap.py", "j = np.where(np.abs(xs[j - 1] - xo[m]) <= np.abs(xs[j] - xo[m]), j - 1, j)",
      "j = np.where(np.abs(xs[j - 1] - xo[m]) <= np.abs(xs[j] - xo[m]), j, j - 1)", "nearest cell: the farther one"),
    M("A21", "analysis/cellmap.py", "throws[i] = throws[j] + 1", "throws[i] = throws[j]", "cell throw count: + 1 dropped"),
    M("A22", "analysis/cellmap.py", "tol = max(reach_tol, 0.5 * v)", "tol = max(reach_tol, 5.0 * v)", "on-attractor radius 5 cells"),
    # ------------------------------------------------------------------ analysis/basins.py
    M("A23", "analysis/basins.py", "unique = check_ok and exc <= trap_tol", "unique = check_ok or exc <= trap_tol",
      "certificate: and → or"),
    M("A24", "analysis/basins.py", "j = np.where(np.abs(xs[j - 1] - x[m]) <= np.abs(xs[j] - x[m]), j - 1, j)",
      "j = np.where(np.abs(xs[j - 1] - x[m]) <= np.abs(xs[j] - x[m]), j, j - 1)", "nearest grid point: the farther one"),
    # ------------------------------------------------------------------ analysis/funnels.py
    M("A25", "analysis/funnels.py", "if share >= containment:", "if share > containment:",
      "funnel edge needs more than the containment share"),
    M("A26", "analysis/funnels.py", "if np.all(goal.contains(xs, ss, 1e-12)):", "if np.any(goal.contains(xs, ss, 1e-12)):",
      "spout inside the goal if any sample is"),
    # ================================================================== N: code since the last pass
    # ------------------------------------------------------------------ models/engine_oracle.py, models/engine.py
    M("N01", "models/engine_oracle.py", "(int(ka) != int(kb) or not abs(", "(int(ka) != int(kb) and not abs(",
      "disagrees: another side at the same x agrees (or → and)"),
    M("N02", "models/engine_oracle.py", "not abs(float(xa) - float(xb)) <= tol", "abs(float(xa) - float(xb)) > tol",
      "disagrees: comparison turned round, a NaN rest agrees"),
    M("N03", "models/engine_oracle.py", "o.friction.arm_part is not None or o.friction.wall_part is not None",
      "o.friction.arm_part is not None and o.friction.wall_part is not None",
      "oracle_options: off only when both pair frictions are set by hand"),
    M("N04", "models/engine_oracle.py", "runs.append((s.dt / f, rerun(s.dt / f, max(s.coarse_dt / f, s.dt / f))))",
      "runs.append((s.dt / f, rerun(s.dt / f, max(s.coarse_dt, s.dt / f))))",
      "settle: the finer reruns keep the coarse step"),
    M("N05", "models/engine_oracle.py",
      "if not disagrees(runs[1][1][:3], runs[2][1][:3], tol) and not disagrees(first[:3], runs[1][1][:3], tol):",
      "if not disagrees(first[:3], runs[2][1][:3], tol):", "settle: the quarter step compared with the first run"),
    M("N06", "models/engine.py", "if oracle is None or run.verified or int(out.status) not in ENDED:",
      "if oracle is None or run.verified or int(out.status) in ENDED:",
      "outcome: the oracle asked only where the engine did not end"),
    M("N07", "models/engine.py", "if first[2] not in ENDED or int(ex.status[i]) not in ENDED:",
      "if first[2] not in ENDED and int(ex.status[i]) not in ENDED:",
      "batch: an exact throw that did not end still compared (or → and)"),
    # ------------------------------------------------------------------ kernels/rigid_body: foot, rearm windows, slack
    M("N08", "kernels/rigid_body/foot.py", "if not walled or px < length or va != 0.0:",
      "if not walled or px <= length or va != 0.0:", "foot_holds: a pivot exactly at the wall is not at the foot"),
    M("N09", "kernels/rigid_body/foot.py", "th1 = thdot - lj * s * va / I", "th1 = thdot + lj * s * va / I",
      "foot_impact: sign of the slide's angular momentum about the foot"),
    M("N10", "kernels/rigid_body/flight.py", "un = vy + om * rx", "un = vy - om * rx",
      "rearm_window: sign of the spin's share of the vertex's normal velocity"),
    M("N11", "kernels/rigid_body/wall.py", "un = -(vx - om * ay)  # the vertex's velocity away from the face",
      "un = (vx - om * ay)  # the vertex's velocity away from the face",
      "rearm_wall_window (face): velocity into the face taken as leaving"),
    M("N12", "kernels/rigid_body/wall.py", "return max(h - yk, 0.0) + SINK_TOL * size",
      "return max(yk - h, 0.0) + SINK_TOL * size", "sink_slack: height above the line instead of depth below"),
    M("N13", "kernels/rigid_body/wall_lean.py",
      "un = nrm[i, 0] * (vx - om * qy) + nrm[i, 1] * (vy + om * qx)  # the gap's rate",
      "un = -(nrm[i, 0] * (vx - om * qy) + nrm[i, 1] * (vy + om * qx))  # the gap's rate",
      "_dispatch: the corner's opening rate with its sign flipped back"),
    # ------------------------------------------------------------------ statics
    M("N14", "statics/rest.py", 'g = positive_float(g, "g")', "g = float(g)", "analyse_rest: g unchecked"),
    M("N15", "statics/leaning.py", "or math.isnan(mu) or mu < 0:", "or math.isnan(mu) or mu <= 0:",
      "lean_free_beta: a frictionless arm (μ = 0) refused"),
    M("N16", "statics/leaning.py", "            lo = mid\n    return lo", "            lo = mid\n    return hi",
      "lean_free_beta: the bisection returns its lean end"),
    M("N17", "statics/rest.py", "if steps > MAX_BISECTIONS:", "if steps >= MAX_BISECTIONS:",
      "least_mu: the bisection cap one step early"),
    # ------------------------------------------------------------------ stochastic (chains, goals)
    M("N18", "stochastic/chain.py", "not 0 <= int(s) < self.n:", "not 0 <= int(s) <= self.n:",
      "goal state index n accepted (off by one)"),
    M("N19", "stochastic/chain.py", "out[k] = w[held].sum() + nxt[newly].sum()",
      "out[k] = w[held].sum() + w[newly].sum()",
      "p_goal_by: a goal stop counted at its own step, not the throw before"),
    M("N20", "stochastic/montecarlo.py", "if not self.lo <= self.hi:", "if not self.lo < self.hi:",
      "GoalSet: a one-point goal [x, x] refused"),
    M("N21", "stochastic/montecarlo.py", "or np.any(w < 0) or w.sum() <= 0:", "or np.any(w < 0) or w.sum() < 0:",
      "open_loop_trials: all-zero start weights accepted"),
    # ------------------------------------------------------------------ control/planner.py
    M("N22", "control/planner.py", "if tol <= 0:", "if tol < 0:", "plan_throws: tol = 0 accepted"),
    M("N23", "control/planner.py", "if xm <= 0:", "if xm < 0:", "x_max = 0 accepted"),
    M("N24", "control/planner.py", "if arm.length is not None and xm > arm.length:",
      "if arm.length is not None and xm >= arm.length:", "x_max at the arm's end refused"),
    # ------------------------------------------------------------------ experiment configs (io/schema.py, experiments)
    M("N25", "io/schema.py", "    if lo > hi:\n", "    if lo >= hi:\n", "ordered range: low = high refused"),
    M("N26", "io/schema.py", "Rate = Annotated[Omega, Field(gt=0, le=MAX_RATE)]",
      "Rate = Annotated[Omega, Field(gt=0, lt=MAX_RATE)]", "experiment rate: ω = 100 rad/s refused"),
    M("N27", "experiments/sequential.py", "x_range_second: Range = Field(",
      "x_range_second: tuple[Finite, Finite] = Field(", "serial: the wedge's drop range not checked for order"),
    # ------------------------------------------------------------------ design/api.py
    M("N28", "design/api.py", "if escaped > MAX_ESCAPE:", "if escaped >= MAX_ESCAPE:",
      "success: exactly 10 % escaping refused"),
    M("N29", "design/api.py", "escaped = float(sum(ls.escapes.values()))",
      "escaped = float(max(ls.escapes.values(), default=0.0))",
      "success: the largest escape kind, not all escapes, against 10 %"),
    M("N30", "design/api.py", "if weight_mass > MAX_WEIGHT:", "if weight_mass >= MAX_WEIGHT:",
      "a 10 kg lead weight refused"),
    # ------------------------------------------------------------------ ScaleWarning (errors.py, system/part.py)
    M("N31", "errors.py", "big = abs(float(value)) > limit", "big = float(value) > limit",
      "ScaleWarning: a large negative value not warned"),
    M("N32", "system/part.py", 'warn_scale("part.vertices", float(np.max(np.abs(v))), "length")',
      'warn_scale("part.vertices", float(np.max(v)), "length")',
      "ScaleWarning: vertices far out at negative x, y not warned"),
    # ------------------------------------------------------------------ reproduce: failed pieces, captions
    M("N33", "reproduce/run.py", 'if row["numbers"].get("success") is False:', 'if not row["numbers"].get("success"):',
      "a figure without a success number counted as failed"),
    M("N34", "reproduce/figures.py", "{'s' if len(shots) != 1 else ''}", "{'s' if len(shots) > 1 else ''}",
      "snapshots caption: '0 panel' in the singular"),
)


def apply(m: Mutant) -> tuple[Path, str]:
    """Write the mutant; returns the file and its original text. Raises if the snippet is not there exactly once."""
    f = SRC / m.path
    text = f.read_text()
    n = text.count(m.old)
    if n != 1:
        raise ValueError(f"{m.id}: snippet occurs {n} times in {m.path}")
    f.write_text(text.replace(m.old, m.new))
    return f, text


def _env(cache: str, pyc: str) -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "src") + os.pathsep + env.get("PYTHONPATH", "")
    env["NUMBA_CACHE_DIR"] = cache
    env["PYTHONPYCACHEPREFIX"] = pyc
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    env.setdefault("CI", "1")  # fixed Hypothesis examples (tests/conftest.py)
    env.setdefault("MPLBACKEND", "Agg")
    return env


def run_tests(tests, cache: str, pyc: str, timeout: float) -> tuple[str, str, float]:
    """Run ``tests`` (pytest -x); returns (result, detail, seconds): result killed/survived/timeout/error."""
    missing = [t for t in tests if not (ROOT / t.split("::")[0]).exists()]
    if missing:  # never fall back to pytest's default paths (the whole suite) for a mistyped entry
        raise SystemExit(f"error: tests: no such test file {missing[0]!r} (paths relative to the repository)")
    paths = list(tests)
    cmd = ["nice", "-n", "10", sys.executable, "-m", "pytest", *PYTEST_ARGS, *paths]
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, cwd=ROOT, env=_env(cache, pyc), capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timeout", f"> {timeout:g} s", time.monotonic() - t0
    dt = time.monotonic() - t0
    out = p.stdout + p.stderr
    if p.returncode == 0:
        return "survived", "", dt
    hit = re.search(r"^(FAILED|ERROR) (\S+)", out, re.M)
    if p.returncode == 1 and hit:
        return "killed", hit.group(2), dt
    return "error", f"pytest rc {p.returncode}: " + (out.strip().splitlines() or [""])[-1][:120], dt


def run(mutants, timeout: float, log=print, warm: str | None = None, baseline: bool = True, on_row=None,
        tests=None) -> list[dict]:
    """Baseline (each test subset must pass unmutated), then every non-equivalent mutant; returns rows.

    ``tests``: test paths to run for every mutant instead of its own subset.
    ``warm``: numba cache directory for the unmutated kernels (kept between runs; default a
    temporary one). ``on_row(rows)`` is called after each mutant (e.g. to save progress).
    """
    work = Path(tempfile.mkdtemp(prefix="throwmap-mutants-"))
    warm = warm or str(work / "numba-warm")
    pyc = str(work / "pyc")
    rows = []
    try:
        for subset in sorted({tests or m.tests for m in mutants if not m.equivalent}) if baseline else ():
            res, detail, dt = run_tests(subset, warm, pyc, 4 * timeout)
            log(f"baseline {' '.join(subset)}: {res} {detail} ({dt:.0f} s)")
            if res != "survived":
                raise SystemExit(f"baseline fails: {detail}")
        for m in mutants:
            row = dict(id=m.id, file=m.path, what=m.what)
            if m.equivalent:
                row.update(result="equivalent", detail=m.equivalent, seconds=0.0)
                rows.append(row)
                log(f"{m.id} equivalent: {m.equivalent}")
                continue
            kernel = m.path.startswith("kernels/")
            cache = str(work / f"numba-{m.id}") if kernel else warm
            try:
                f, text = apply(m)
            except ValueError as e:  # the code moved on: the snippet needs updating, nothing was run
                row.update(result="stale", detail=str(e), seconds=0.0)
                rows.append(row)
                log(f"{m.id} stale: {e}")
                continue
            try:
                res, detail, dt = run_tests(tests or m.tests, cache, pyc, timeout)
            finally:
                f.write_text(text)
                if kernel:
                    shutil.rmtree(cache, ignore_errors=True)
            row.update(result=res, detail=detail, seconds=round(dt, 1))
            rows.append(row)
            log(f"{m.id} {res:9s} {dt:6.1f} s  {m.what}  {detail}")
            if on_row:
                on_row(rows)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return rows


def score(rows, before: bool = False) -> tuple[int, int, float]:
    """(caught, decided, share caught) over the non-equivalent mutants that were decided.

    Caught: a test failed (or errored); a timeout is *undecided* (on a loaded machine it
    says nothing) and is left out. ``before``: only tests other than the kill files count.
    """
    counted = [r for r in rows if r["result"] in ("killed", "error", "survived")]
    kills = tuple(Path(k).name for k in ADDED_BY_THE_PASS)
    caught = sum(r["result"] != "survived" and not (before and any(k in r["detail"] for k in kills)) for r in counted)
    return caught, len(counted), (caught / len(counted) if counted else float("nan"))


def markdown(rows) -> str:
    lines = ["| mutant | file | slip | result | caught by | s |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['id']} | {r['file']} | {r['what']} | {r['result']} | {r['detail']} | {r['seconds']:.0f} |")
    c0, n, s0 = score(rows, before=True)
    c, n, s = score(rows)
    undecided = sum(r["result"] == "timeout" for r in rows)
    equivalent = sum(r["result"] == "equivalent" for r in rows)
    lines.append("")
    lines.append(f"Score without the kill tests: {c0}/{n} ({100 * s0:.1f} %); with them: {c}/{n} ({100 * s:.1f} %) "
                 f"of the decided non-equivalent mutants; {undecided} timed out (undecided), {equivalent} equivalent.")
    return "\n".join(lines)


def _term(signum, frame):
    raise KeyboardInterrupt  # unwinds through run()'s finally: the mutated file is restored


def main(argv=None) -> int:
    import signal
    signal.signal(signal.SIGTERM, _term)
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="*", help="mutant ids to run (default: all)")
    ap.add_argument("--timeout", type=float, default=400.0, help="seconds per mutant (default 400)")
    ap.add_argument("--list", action="store_true", help="print the catalogue and exit")
    ap.add_argument("--check", action="store_true", help="check every snippet occurs exactly once, run nothing")
    ap.add_argument("--json", help="write the rows to this JSON file")
    ap.add_argument("--markdown", help="write the table to this Markdown file")
    ap.add_argument("--warm-cache", help="numba cache directory for the unmutated code, kept between runs")
    ap.add_argument("--no-baseline", action="store_true", help="skip the unmutated runs of the test subsets")
    ap.add_argument("--tests", nargs="*", help="run these test paths for every mutant instead of its subset")
    a = ap.parse_args(argv)
    by_id = {m.id: m for m in MUTANTS}
    unknown = [i for i in a.only or () if i not in by_id]
    if unknown:
        ap.error(f"unknown mutant ids: {' '.join(unknown)}")
    chosen = [by_id[i] for i in dict.fromkeys(a.only)] if a.only else list(MUTANTS)  # in the order given
    if a.list or a.check:
        bad = 0
        for m in chosen:
            n = (SRC / m.path).read_text().count(m.old)
            bad += n != 1
            flag = "" if n == 1 else f"  !! snippet occurs {n} times"
            print(f"{m.id}  {m.path:34s} {m.what}{'  [equivalent: ' + m.equivalent + ']' if m.equivalent else ''}{flag}")
        return 1 if bad else 0
    def save(rows):
        if a.json:
            Path(a.json).write_text(json.dumps(rows, indent=1, ensure_ascii=False))
        if a.markdown:
            Path(a.markdown).write_text(markdown(rows) + "\n")

    rows = run(chosen, a.timeout, log=lambda s: print(s, flush=True), warm=a.warm_cache,
               baseline=not a.no_baseline, on_row=save, tests=tuple(a.tests) if a.tests else None)
    save(rows)
    print(markdown(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
