"""The "rigid_body" hybrid automaton: one throw as a loop over modes (see :mod:`throwmap.kernels.rigid_body`).

FLIGHT --touch--> impact --> SELECT --> PIVOT_STICK | PIVOT_SLIDE | FLIGHT
PIVOT_STICK --slip--> PIVOT_SLIDE --stick--> PIVOT_STICK   (slip_start / stick_start)
PIVOT_* --lift_off--> FLIGHT (lift) --land--> land_side --> REST | FLAT_SLIDE | pivot on B | FLIGHT
any contact --leave_arm--> BEHIND_JOINT / OFF_END;  PIVOT_SLIDE --painleve--> INCONSISTENT.
With a wall (``wall_h`` > 0, :mod:`.wall`): FLIGHT --wall_touch/corner_touch--> wall_impact --> FLIGHT;
PIVOT_* --wall_reach--> pivot wall reset --> FLIGHT | REST (leaning) | PIVOT (swing back);
land_side's flat slides --> settle_walled --> REST | PIVOT on the corner vertex; else UNRESOLVED.

:func:`run_throw` takes the sticking phase as its first argument (a jitted
function with the signature of :func:`~throwmap.kernels.rigid_body.stick.pivot_stick`),
so the closed-form phase (:func:`throw_one_rigid_body`) and the RK4 reference
(:func:`throw_one_rigid_body_rk4`) share every other line.

Arm rest angle ``alpha`` (rad, CCW +, |α| < π/2; draft Sec. VI, :mod:`~.tilt`): the
automaton runs in the arm frame with gravity (−g sin α, −g cos α). α = 0 runs the
horizontal code unchanged (bit for bit); α ≠ 0 uses the tilted sticking phase
:func:`~.tilt.pivot_stick_tilted` for both sticking-phase variants, and the tilted
flat slide / rest :func:`~.flat.settle`.
"""

import math

import numpy as np
from numba import njit

from .. import codes as C
from ..roll import theta_a, theta_b
from ..flight import UNRESOLVED_J, departure_window, gap_constants, release_state, rest_offsets
from ..rows import start_record
from .flat import nearest_side, rest, settle
from .flight import flight_frame, fly, leave_arm, lift, rearm_window, refresh_frame
from .impact import coulomb_impact, record_first_contact, record_first_impact, record_impact
from .landing import land_side
from .modes import (EV_BEHIND_JOINT, EV_INCONSISTENT, EV_LAND_A, EV_LAND_B, EV_LIFT_OFF, EV_NONE, EV_OFF_END, EV_SLIP,
                    EV_STEP_CAP, EV_STICK, EV_WALL, IMP_INCONSISTENT, IMP_SEPARATE, IMP_STICK, MODE_FLIGHT, MODE_REST,
                    MODE_LEAN, MODE_SELECT, MODE_SLIDE, MODE_STICK, MU_SKID, WC_ARM, WC_CAP, WC_FACE, WC_FLIGHT,
                    WC_INCONSISTENT, WHY_CORNER, WHY_EVENT_CAP, WHY_SLIDE_WALL, WHY_WALL_SLIDE, WHY_WALL_TOP, refuse)
from .slide import pivot_slide, pivot_slide_walled, select_contact_mode
from .foot import foot_holds, foot_impact
from .stick import pivot_stick
from .stick_exact import pivot_stick_exact
from .tilt import pivot_stick_tilted
from .trajectory import _put, _put_final, clear
from .wall import (corner_inside, fill_wall_vertices, fly_walled, rearm_wall_window, wall_contact_angle,
                   wall_hit_in_flight)
from .wall_corner import corner_contact
from .wall_lean import (LN_BEHIND, LN_CAP, LN_CORNER, LN_FLIGHT, LN_INCONSISTENT, LN_PIVOT, LN_REST, LN_WALL, lean,
                        offsets)
from .wall_slide import wall_contact


@njit(cache=True)
def follow(wj, ce, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, mu_w, h, top, L, arm_skip, arm_skip_until, max_steps,
           max_events, wv, traj, ts, rec):
    """:func:`~.wall_slide.wall_contact` for face vertex ``wj`` ≥ 0, else :func:`~.wall_corner.corner_contact` for corner edge ``ce``."""
    if wj >= 0:
        return wall_contact(wj, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, mu_w, h, top, L, arm_skip, arm_skip_until,
                            max_steps, max_events, wv, traj, ts, rec)
    return corner_contact(ce, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, mu_w, h, top, L, arm_skip, arm_skip_until,
                          max_steps, max_events, traj, ts)


@njit(cache=True, inline='always')
def run_throw(stick_phase, x0, side, omega, part, arm, lim, rec, traj, traj_dt, start):
    """One throw of model "rigid_body" with ``stick_phase`` as mode PIVOT_STICK; see :func:`throw_one_rigid_body`.
    A non-empty ``start`` replaces the release by a handed-over state (:func:`throw_from_state`)."""
    rho2, w, beta, d, uL, uR, ell, stable = part
    h, g, alpha, length, back, mu, law, wall_h, wall_mu = arm
    tol, max_iter, max_events = lim
    n = w.shape[0]
    start_record(rec)
    ts = np.zeros(3)
    clear(traj, ts, traj_dt)
    sample = traj.shape[0] > 0
    dk = d[side]
    tilted = alpha != 0.0
    gn = g * math.cos(alpha)  # gravity normal to the arm and along it (−gt): (−g sin α, −g cos α)
    gt = g * math.sin(alpha)
    if tilted:
        rec[C.E_RELEASE] = 0.5 * omega * omega * (x0 * x0 + (h + dk) * (h + dk) + rho2) + gn * dk + gt * x0
    else:
        rec[C.E_RELEASE] = 0.5 * omega * omega * (x0 * x0 + (h + dk) * (h + dk) + rho2) + g * dk
    if sample:
        _put(traj, ts, 0.0, x0, h + dk, beta[side])
        ts[1] = ts[2]
    if omega == 0.0:
        rec[C.N_MIN] = 1.0
        if tilted:
            x, k, st, _t = settle(x0, 0.0, 0.0, side, mu, g, alpha, h, d, uL, uR, beta, length, back, beta[side], traj,
                                  ts, rec)
            return x, k, st
        return rest(x0, side, 0.0, h, g, d, uL, uR, beta, length, back, beta[side], traj, ts, rec)
    # ------------------------------------------------------------------ reset release (Eq. 1)
    vx, vy, om = release_state(x0, dk, h, omega)
    x = x0
    y = h + dk
    phi = beta[side]
    ru, rv = rest_offsets(w, phi)  # flight frame: vertex offsets and their gaps (support vertices: exactly 0)
    c0 = np.empty(n)
    gap_constants(dk, rv, ell, c0)
    t = 0.0
    excl_j = -1  # a vertex that just left the line, and how long it provably stays above it
    excl_t = 0.0
    mode = MODE_FLIGHT
    last_side = side
    first = True
    n_events = 0
    # contact state: pivot vertex jp at x = px, angle θ of pivot→CM, rates θ̇ and slip velocity v_A, φ = θ + phi_off
    jp = -1
    px = 0.0
    theta = 0.0
    thdot = 0.0
    va = 0.0
    phi_off = 0.0
    sig = 0.0
    mu_s = MU_SKID if math.isinf(mu) else mu
    ev = EV_NONE
    walled = wall_h > 0.0  # a Wall at x = length, wall_h (m) high, μ_w = wall_mu (wall.py)
    gx = -g * math.sin(alpha)  # gravity along the arm
    cw = np.empty(n)
    wv = np.zeros((n, 3))  # the sliding pivot's watched vertices (ℓ_j, δ_j) and the wall's height (slide.py)
    wv[:, 2] = wall_h if wall_h > 0.0 else math.inf
    off = np.zeros(n)  # vertices that passed the wall's plane above its top in this flight
    cexcl_e = -1  # an edge that just left the wall's top corner, and until when it provably stays off it
    cexcl_until = 0.0
    wexcl_j = -1  # a vertex that just left the wall, and until when (absolute time, s) it provably stays off it
    wexcl_until = 0.0
    lref = math.sqrt(rho2) + ell.max()
    wj = -1  # WALL_CONTACT: a vertex pressed on the wall's face (wall_follow.py), −1 none
    ce = -1  # CORNER: an edge pressed on the wall's top corner (wall_corner.py), −1 none
    ln_a = -1  # MODE_LEAN: the vertex on the arm, the one on the face, and whether their impact is still to come
    ln_p = -1
    ln_impact = False
    if start.shape[0] > 0:
        # a state handed over by the moving-arm phase (moving/handover.py): FLIGHT (0) or a pivot (1, SELECT)
        t = start[1]
        x = start[2]
        y = start[3]
        vx = start[4]
        vy = start[5]
        om = start[6]
        phi = start[7]
        last_side = int(start[8])
        first = start[13] != 0.0
        if start[0] == 0.0:
            refresh_frame(phi, y, h, w, ell, ru, rv, c0)
        else:
            jp = int(start[9])
            px = start[10]
            theta = start[11]
            thdot = om
            va = start[12]
            phi_off = phi - theta
            mode = MODE_SELECT
    while True:
        n_events += 1
        if n_events > max_events:
            return x, last_side, refuse(rec, WHY_EVENT_CAP)
        if mode == MODE_LEAN:
            # ---------------------------------------------------------- on the arm and the wall (wall_lean.py)
            (res, why, t, x, y, vx, vy, phi, om, ka, kp, win_a, win_p, v_a, kc,
             win_c) = lean(ln_a, ln_p, ln_impact, t, x, y, vx, vy, phi, om, w, rho2, mu, wall_mu, gx, gn, h, wall_h,
                         length, back, lref, max_iter, max_events, traj, ts)
            if res == LN_REST:
                rec[C.E_FINAL] = gn * (y - h) - gx * x
                rec[C.T_REST] = t
                _put_final(traj, ts, t, x, y, phi)
                return x, nearest_side(phi, beta), C.OK
            if res == LN_PIVOT:
                rx, ry = offsets(phi, w, ka)
                jp = ka
                px = x + rx
                theta = math.atan2(-ry, -rx)
                thdot = om
                phi_off = phi - theta
                va = v_a
                mode = MODE_SELECT
                continue
            if res == LN_WALL or res == LN_FLIGHT or res == LN_CORNER:
                wj = kp if res == LN_WALL else -1
                ce = kp if res == LN_CORNER else -1
                excl_j = ka
                excl_t = win_a if ka >= 0 else 0.0
                wexcl_j = kp if res == LN_FLIGHT else -1
                wexcl_until = t + win_p
                cexcl_e = kc
                cexcl_until = t + win_c
                off[:] = 0.0
                refresh_frame(phi, y, h, w, ell, ru, rv, c0)
                mode = MODE_FLIGHT
                continue
            if res == LN_CAP:
                rec[C.CAP_HIT] = 1.0
            return x, last_side, (C.BEHIND_JOINT if res == LN_BEHIND else C.INCONSISTENT if res == LN_INCONSISTENT
                                  else C.UNRESOLVED if res == LN_CAP else refuse(rec, why))
        if mode == MODE_FLIGHT:
            # ---------------------------------------------------------- FLIGHT until guard touch
            if wj >= 0 or ce >= 0:
                # ------------------------------------------------------ WALL_CONTACT / CORNER (wall_follow.py)
                t_seg = t
                (res, jc, t, x, y, vx, vy, phi, om, rx, ry, wex,
                 why) = follow(wj, ce, t, x, y, vx, vy, phi, om, w, rho2, gx, gn, wall_mu, h, wall_h, length, excl_j,
                               t + excl_t, max_iter, max_events, wv, traj, ts, rec)
                excl_t = max(excl_t - (t - t_seg), 0.0)
                if res == WC_FLIGHT:
                    wexcl_j, wexcl_until = (wj, t + wex) if wj >= 0 else (wexcl_j, wexcl_until)
                    cexcl_e, cexcl_until = (ce, t + wex) if ce >= 0 else (cexcl_e, cexcl_until)
                    wj = ce = -1
                    refresh_frame(phi, y, h, w, ell, ru, rv, c0)
                    continue
                if res == WC_CAP or res == WC_INCONSISTENT:
                    rec[C.CAP_HIT] = 1.0 if res == WC_CAP else rec[C.CAP_HIT]
                    return x, last_side, C.UNRESOLVED if res == WC_CAP else C.INCONSISTENT
                if res == WC_FACE or res == WC_ARM:  # a second contact while on the wall: LEAN (both at once)
                    ln_a = jc if res == WC_ARM else -1
                    ln_p = jc if res == WC_FACE else wj
                    ln_impact = True
                    mode = MODE_LEAN
                    wj = ce = -1
                    continue
                return x, last_side, refuse(rec, why)
            elif walled:
                t_seg = t
                (where, jc, t, x, y, vx, vy, phi, rx, ry, nx,
                 ny) = fly_walled(t, x, y, vx, vy, phi, om, c0, ru, rv, gx, gn, ell, excl_j, excl_t, wexcl_j,
                                  wexcl_until - t, cexcl_e, cexcl_until - t, length, wall_h, h, tol, max_iter, cw, off,
                                  traj, ts)
                if where == -2:
                    rec[C.CAP_HIT] = 1.0
                    return x, last_side, C.UNRESOLVED
                if where >= 1:
                    # ------------------------------------------------------ reset wall_impact (wall.py)
                    k_pre = 0.5 * (vx * vx + vy * vy + rho2 * om * om)
                    vxp, vyp, wp, pt, pn, kind, wex, why = wall_hit_in_flight(vx, vy, om, rx, ry, nx, ny, where == 2,
                                                                              rho2, wall_mu, law, gx, gn,
                                                                              math.hypot(rx, ry))
                    rec[C.N_IMPACTS] += 1.0
                    if why == WHY_WALL_SLIDE:  # it stays pressed on the face (WALL_CONTACT) or the corner (CORNER)
                        wj, ce = (jc, -1) if where == 1 else (-1, jc)
                    elif why != 0:
                        return x, last_side, refuse(rec, why)
                    if kind == IMP_INCONSISTENT:
                        return x, last_side, C.INCONSISTENT
                    rec[C.N_IMPACTS] -= 1.0
                    record_impact(pt, pn, k_pre, 0.5 * (vxp * vxp + vyp * vyp + rho2 * wp * wp), rec)
                    if kind != IMP_STICK:
                        rec[C.N_SLIPS] += 1.0
                    vx, vy, om = vxp, vyp, wp
                    if wj >= 0 or ce >= 0:
                        pass
                    elif where == 1:
                        wexcl_j = jc
                        wexcl_until = t + wex
                    else:
                        cexcl_e = jc
                        cexcl_until = t + wex
                    if excl_j >= 0:
                        # the wall's impulse voids the window the vertex got when it left the arm
                        excl_t = rearm_window(y, vx, vy, phi, om, w, excl_j, h, gn, gx, 1e-9 * lref)
                        if excl_t < 0.0:  # pressed back onto the arm: both contacts at once (LEAN)
                            ln_a = excl_j
                            ln_p = wj
                            ln_impact = True
                            wj = ce = -1
                            excl_j = -1
                            excl_t = 0.0
                            mode = MODE_LEAN
                            continue
                        if excl_t == 0.0:
                            excl_j = -1
                    refresh_frame(phi, y, h, w, ell, ru, rv, c0)
                    continue
            else:
                jc, t, x, y, vy, phi, rx, ry, vx = fly(t, x, y, vx, vy, phi, om, c0, ru, rv, gn, ell, excl_j, excl_t,
                                                       tol, max_iter, traj, ts, gt)
            if jc < 0:
                if jc != UNRESOLVED_J:
                    rec[C.CAP_HIT] = 1.0  # max_iter steps without contact: not resolved, not a missed contact
                return x, last_side, C.UNRESOLVED
            pxc = x + rx
            k_pre = 0.5 * (vx * vx + vy * vy + rho2 * om * om)
            if first:
                record_first_contact(rec, t, jc, pxc, vx, vy, om, k_pre, y - h, gn)
                if tilted:
                    rec[C.U_IMPACT] += gt * x
            status = leave_arm(pxc, back, length)
            if status != C.OK:
                return x, last_side, status
            # ---------------------------------------------------------- reset impact
            vxp, vyp, wp, pt, pn, kind, jt0, jn0 = coulomb_impact(vx, vy, om, rx, ry, rho2, mu, law)
            if jn0 < 0.0:
                rec[C.N_PULL] += 1.0
            if kind == IMP_INCONSISTENT:
                rec[C.N_IMPACTS] += 1.0
                return x, last_side, C.INCONSISTENT
            k_post = 0.5 * (vxp * vxp + vyp * vyp + rho2 * wp * wp)
            record_impact(pt, pn, k_pre, k_post, rec)
            if kind != IMP_STICK:
                rec[C.N_SLIPS] += 1.0
            if first:
                first = False
                record_first_impact(rec, vxp, vyp, wp, pt, pn, jt0, jn0, k_post)
            vx, vy, om = vxp, vyp, wp
            if kind == IMP_SEPARATE:
                # the vertex leaves at once: flight again, this vertex excluded for a while
                un = vy + om * rx
                excl_j = jc
                # a departing normal velocity at rounding level (relative to the motion's speed) gets the window
                vscale = max(1.0, abs(vx) + abs(vy) + abs(om) * ell[jc])
                excl_t = departure_window(rx, ry, om, gn, ell[jc], gn) if un <= 1e-12 * vscale else 0.0
                flight_frame(phi, y, h, w, ru, rv, c0, jc)
                # the arm's impulse voids the windows a vertex (an edge) got when it left the wall
                if walled and wexcl_j >= 0 and wexcl_until > t:
                    win = rearm_wall_window(False, x, y, vx, vy, phi, om, w, wexcl_j, length, h, wall_h, gx, gn,
                                            1e-9 * lref)
                    if win < 0.0:  # pressed back on the face: both contacts at once (LEAN)
                        ln_a, ln_p, ln_impact = jc, wexcl_j, True
                        wexcl_j = cexcl_e = -1
                        mode = MODE_LEAN
                        continue
                    wexcl_j, wexcl_until = (wexcl_j, t + win) if win > 0.0 else (-1, 0.0)
                if walled and cexcl_e >= 0 and cexcl_until > t:
                    win = rearm_wall_window(True, x, y, vx, vy, phi, om, w, cexcl_e, length, h, wall_h, gx, gn,
                                            1e-9 * lref)
                    if win < 0.0:  # pressed back on the corner
                        ln_a, ln_p, ln_impact = jc, -1, True
                        wexcl_j = cexcl_e = -1
                        mode = MODE_LEAN
                        continue
                    cexcl_e, cexcl_until = (cexcl_e, t + win) if win > 0.0 else (-1, 0.0)
                continue
            jp = jc
            px = pxc
            theta = math.atan2(-ry, -rx)
            thdot = om
            phi_off = phi - theta
            va = 0.0 if kind == IMP_STICK else vx - om * ry  # contact slip velocity
            mode = MODE_SELECT
            continue
        # ============================================================== contact modes on vertex jp
        lj = ell[jp]
        I = rho2 + lj * lj
        ta = theta_a(jp, n, d, uL)
        tb = theta_b(jp, d, uR)
        theta = min(max(theta, ta), tb)
        ev = EV_NONE
        ta_w = ta  # the pivot angle's lower bound: side j−1 lands, or a vertex meets the wall (guard wall_reach)
        wcx = wcy = wnx = wny = 0.0
        if walled:
            th_w, _c, _j, wcx, wcy, wnx, wny = wall_contact_angle(px, length, wall_h, theta, theta + phi_off, w, jp)
            if th_w > ta:
                ta_w = min(th_w, tb)
                if theta < ta_w:
                    theta = ta_w
        if walled and ta_w > ta and theta <= ta_w and (thdot < 0.0 if va == 0.0 else
                                                       (va - thdot * wcy) * wnx + thdot * wcx * wny
                                                       < -1e-9 * (abs(va) + abs(thdot) * lj)):
            # (a sliding pivot's contact on the wall approaches it only if its velocity points into the wall;
            # one that slides along it at rounding level, as a ladder whose wall force fell to 0, leaves)
            ev = EV_WALL  # a vertex is on the wall and the part turns into it
        elif mode == MODE_SELECT and foot_holds(walled, px, length, va, theta, thdot, lj, I, g, mu, alpha):
            mode = MODE_STICK  # at the wall's foot, pressed towards the wall: the wall holds it
        elif mode == MODE_SELECT:
            mode, sig = select_contact_mode(theta, thdot, va, lj, rho2, g, mu, mu_s, False, alpha)
            if mode < 0:
                return px + lj * math.cos(theta), last_side, C.INCONSISTENT
            if mode == MODE_SLIDE and va == 0.0:
                rec[C.N_SLIPS] += 1.0  # (a sliding impact was counted already)
            if mode == MODE_FLIGHT:
                ev = EV_LIFT_OFF
        if ev == EV_WALL:
            pass
        elif mode == MODE_STICK:
            if tilted or (walled and px >= length):
                ev, theta, thdot, t = pivot_stick_tilted(theta, thdot, ta_w, tb, lj, I, g, mu, t, px, h, phi_off, traj,
                                                         ts, rec, alpha, walled and px >= length)
            else:
                ev, theta, thdot, t = stick_phase(theta, thdot, ta_w, tb, lj, I, g, mu, t, max_iter, px, h, phi_off,
                                                  traj, ts, rec)
            va = 0.0
        elif mode == MODE_SLIDE:
            if walled and sig > 0.0 and px >= length:
                return px + lj * math.cos(theta), last_side, refuse(rec, WHY_CORNER)
            if walled:
                fill_wall_vertices(theta, theta + phi_off, w, jp, wv)
                ev, px, theta, va, thdot, t = pivot_slide_walled(px, theta, va, thdot, sig, ta, tb, lj, rho2, g, mu_s,
                                                                 length, back, t, max_iter, h, phi_off, traj, ts, rec,
                                                                 alpha, length, wv)
            else:
                ev, px, theta, va, thdot, t = pivot_slide(px, theta, va, thdot, sig, ta, tb, lj, rho2, g, mu_s, length,
                                                          back, t, max_iter, h, phi_off, traj, ts, rec, alpha)
            if ev == EV_INCONSISTENT:
                return px + lj * math.cos(theta), last_side, C.INCONSISTENT
            if ev == EV_BEHIND_JOINT:
                return px + lj * math.cos(theta), last_side, C.BEHIND_JOINT
            if ev == EV_OFF_END and walled:
                # ---------------------------------------------------------- reset foot: slid into the wall's foot
                ok, thdot, pt, pn, k_pre, k_post = foot_impact(theta, thdot, va, lj, rho2)
                if not ok:
                    return px + lj * math.cos(theta), last_side, refuse(rec, WHY_CORNER)
                record_impact(pt, pn, k_pre, k_post, rec)  # (the wall takes the tangential impulse: pt = 0)
                px = length
                va = 0.0
                mode = MODE_SELECT
                continue
            if ev == EV_OFF_END:
                return px + lj * math.cos(theta), last_side, C.OFF_END
            if walled and ev != EV_WALL and corner_inside(px, h, theta, theta + phi_off, w, jp, length, wall_h):
                # an edge slid onto the wall's top corner (the sliding phase watches vertices only)
                return px + lj * math.cos(theta), last_side, refuse(rec, WHY_SLIDE_WALL)
        if ev == EV_SLIP or ev == EV_LIFT_OFF or ev == EV_STICK:
            # ---------------------------------------------------------- resets slip_start / stick_start / lift
            new_mode, sig = select_contact_mode(theta, thdot, va, lj, rho2, g, mu, mu_s, ev != EV_STICK, alpha)
            if new_mode < 0:
                return px + lj * math.cos(theta), last_side, C.INCONSISTENT
            if new_mode == MODE_SLIDE:
                if walled and sig > 0.0 and px >= length:
                    if ev != EV_SLIP and foot_holds(walled, px, length, 0.0, theta, thdot, lj, I, g, mu, alpha):
                        mode = MODE_STICK
                        continue
                    return px + lj * math.cos(theta), last_side, refuse(rec, WHY_CORNER)
                rec[C.N_SLIPS] += 1.0
                mode = MODE_SLIDE
                continue
            if new_mode == MODE_STICK:
                mode = MODE_STICK
                continue
            ev = EV_LIFT_OFF
        if ev == EV_STEP_CAP:
            rec[C.CAP_HIT] = 1.0  # max_iter integration steps in one contact mode: not resolved
            return px + lj * math.cos(theta), last_side, C.UNRESOLVED
        phi = theta + phi_off
        if ev == EV_WALL or (ev == EV_LAND_A and ta_w > ta and mode == MODE_STICK):
            # -------------------------------------------------------------- guard wall_reach: reset (wall.py)
            # the contact where the bound was reached (evaluated just before it, so that it is found)
            th_c, w_corner, w_j, _cx, _cy, _nx, _ny = wall_contact_angle(px, length, wall_h, theta + 1e-9,
                                                                         phi + 1e-9, w, jp)
            if not abs(th_c - theta) <= 1e-7:
                # the vertex that reached the wall's plane is above its top (watched by a sliding pivot)
                return px + lj * math.cos(theta), last_side, refuse(rec, WHY_WALL_TOP)
            # the pivot and the wall (face or corner) at once: the two-contact impact of LEAN (wall_lean.py)
            rec[C.N_IMPACTS] += 1.0
            x = px + lj * math.cos(theta)
            y = h + lj * math.sin(theta)
            vx = va - thdot * lj * math.sin(theta)
            vy = thdot * lj * math.cos(theta)
            om = thdot
            ln_a = jp
            ln_p = -1 if w_corner else w_j
            ln_impact = True
            off[:] = 0.0
            sig = 0.0
            mode = MODE_LEAN
            continue
        if ev == EV_LIFT_OFF:
            # ---------------------------------------------------------- reset lift
            rec[C.N_LIFTOFFS] += 1.0
            x, y, vx, vy, om, excl_t = lift(px, h, lj, theta, thdot, va, phi, gn, w, ru, rv, c0, jp)
            if excl_t <= 0.0:
                # N = 0 with a friction force that only infinite friction supplies and a free
                # motion that would sink the vertex: no consistent contact (μ = ∞ only)
                return x, last_side, C.INCONSISTENT
            excl_j = jp
            wexcl_j = -1
            cexcl_e = -1
            off[:] = 0.0
            sig = 0.0
            mode = MODE_FLIGHT
            continue
        # -------------------------------------------------------------- guard land: reset land_side
        land_dir = 1 if ev == EV_LAND_B else -1
        (mode, status, x, y, vx, vy, om, phi, t, jp, px, theta, thdot, va, phi_off, j_ex, t_ex,
         last_side) = land_side(land_dir, jp, px, thdot, va, phi, t, last_side, part, arm, ta, tb, ru, rv, c0, traj,
                                ts, rec)
        if mode == MODE_REST:
            return x, last_side, status
        if mode == MODE_LEAN:  # a flat slide met the wall's top corner with an edge
            ln_a = jp
            ln_p = -1
            ln_impact = True
            continue
        if mode == MODE_FLIGHT:
            excl_j = j_ex
            excl_t = t_ex
            wexcl_j = -1
            cexcl_e = -1
            off[:] = 0.0


@njit(cache=True)
def throw_one_rigid_body(x0, side, omega, part, arm, lim, rec, traj, traj_dt):
    """One throw from rest at ``(x0, side)`` with release rate ``omega`` (rad/s), model "rigid_body".

    ``part``, ``arm`` and ``lim`` are the records of :mod:`~.inputs` (:class:`~.inputs.PartArrays`,
    :class:`~.inputs.ArmArrays`, :class:`~.inputs.RunLimits`). Fills ``rec`` (layout :mod:`~throwmap.kernels.codes`)
    and ``traj`` (see :mod:`throwmap.kernels.rigid_body`; rows not written are NaN) and returns
    ``(x, side, status)``. ``arm.g`` (m/s²) is gravity's magnitude and ``arm.alpha`` (rad, CCW +,
    |α| < π/2) the arm's rest angle: gravity is (−g sin α, −g cos α) in the arm frame
    (:mod:`~.tilt`; ``part.stable`` must be the table for α, :func:`~.tilt.tilted_stable`).
    ``arm.length`` (m, inf: unbounded) and ``arm.back`` (m, ``Arm.back``)
    bound the arm's surface: a contact at x ≤ −back is BEHIND_JOINT, beyond length
    OFF_END. ``arm.mu`` is the Coulomb coefficient (``inf``: no slip, 0: frictionless),
    ``arm.law`` the impact law of resets ``impact`` and ``land_side`` (:data:`~.impact.LAW_ROUTH`,
    the default of the model, or :data:`~.impact.LAW_VELOCITY`; :func:`~.impact.coulomb_impact`),
    ``lim.max_iter`` caps the contact-search and integration steps of one mode,
    ``lim.max_events`` the mode changes (beyond: status UNRESOLVED, reason WHY_EVENT_CAP). The caller has
    checked the start. The sticking phase is closed form (:func:`~.stick_exact.pivot_stick_exact`).
    ``arm.wall_h`` (m, > 0) puts a :class:`~throwmap.system.fixtures.Wall` that high at x = ``length``
    (finite) with Coulomb ``arm.wall_mu`` (:mod:`~.wall`); 0: no wall.
    """
    return run_throw(pivot_stick_exact, x0, side, omega, part, arm, lim, rec, traj, traj_dt, np.empty(0))


@njit(cache=True)
def throw_one_rigid_body_rk4(x0, side, omega, part, arm, lim, rec, traj, traj_dt):
    """:func:`throw_one_rigid_body` with the RK4 sticking phase (:func:`~.stick.pivot_stick`): the reference it is checked against."""
    return run_throw(pivot_stick, x0, side, omega, part, arm, lim, rec, traj, traj_dt, np.empty(0))


@njit(cache=True)
def throw_from_state(start, part, arm, lim, rec, traj, traj_dt):
    """The automaton of :func:`throw_one_rigid_body` from a handed-over arm-frame state instead of the release.

    ``start`` = (kind, t, x, y, v_x, v_y, ω, φ, side, j, p_x, θ, v_A, first): kind 0 FLIGHT (CM at (x, y) m,
    velocity (v_x, v_y) m/s, spin ω rad/s, orientation φ rad, every vertex above the line), kind 1 a pivot on
    vertex j at p_x (θ the angle of pivot → CM, v_A its slip velocity; the contact mode is selected);
    ``side`` the last side rested on; ``first`` 1: the first contact is still to come (its record is written).
    Used by the moving-arm phase (:mod:`.moving`) once the arm has stopped; no wall."""
    return run_throw(pivot_stick_exact, start[2], int(start[8]), 1.0, part, arm, lim, rec, traj, traj_dt, start)
