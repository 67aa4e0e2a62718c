"""One engine run: the loop that leaps, steps and checks until every part settles (:func:`simulate`)."""

from __future__ import annotations

import math
from dataclasses import replace
from functools import partial

from ...errors import InvalidStateError, shown
from ...kernels import codes as C
from ...records.outcome import Status
from ..reach import lengths, unbounded_message
from ...system.motion import ImpulseThrow, angle_function, check_realisation
from ..rest import UNCONVERGED
from ..scene import Scene
from ..settings import EngineSettings
from .checks import GONE, clearance, probe, sunk_into
from .contacts import Contacts
from .interrupt import check as check_interrupt
from .interrupt import deferred_interrupts
from .result import EngineRun, Recorder, finish
from .stepping import fixed_steps, leap, leap_length, vertex_speed_bound
from .verify import disagreement, flags
from .world import build_world

__all__ = ["CHECK_EVERY", "simulate"]

CHECK_EVERY = 1e-3
"""s between penetration/clearance checks while stepping at ``dt``."""
FLIP_TILT = 0.02
CONFINED_MOVE = 5e-4
"""m. Several parts: after the arm stopped, parts that stay within this of a reference position (CM, world frame) and
within :data:`CONFINED_TURN` of its angle for :data:`CONFINED_HOLD` are at rest, whatever their speeds."""
CONFINED_TURN = 5e-3
"""rad (see :data:`CONFINED_MOVE`)."""
CONFINED_HOLD = 1.0
"""s (see :data:`CONFINED_MOVE`). Why: two parts leaning on each other and on a frictionless wall can keep rocking
in Chipmunk (measured: a triangle against the wall turning ±1 mrad at ~0.1 rad/s, its CM within 0.2 mm, for the
whole 10 s limit) — a limit cycle of the solver, not of the physics (zero restitution); such runs timed out and
were refused. One part is unchanged (it settles by the speeds)."""
BLOWUP_RISE = 0.1
"""m. Without the half-step rerun (``verify`` off), a run whose parts gained more mechanical energy after the arm
stopped than g × this (J/kg: rising 10 cm from nothing) blew up — a Chipmunk contact solve that threw a part away
(seen: two parts, 2 × 10⁵ J/kg, a part 1.8 km away at the 10 s limit, reported as a timeout). It is rerun at half
the step; where that gains as much it is refused (``unconverged``), else the rerun stands (its message says so)."""
"""A part in contact within this angle of a resting orientation lies on that side (rad; flip counting)."""


def simulate(scene: Scene, realisation=None, settings: EngineSettings | None = None, *, record: bool = False,
             progress=None, run_for: float | None = None) -> EngineRun:
    """Simulate one throw (or arm motion) of every part in ``scene`` until all settle.

    ``realisation``: :class:`~throwmap.engine.ImpulseThrow` (default ω = 0: just
    settle), :class:`~throwmap.engine.FiniteThrow`, :class:`~throwmap.engine.RecoilThrow`
    or :class:`~throwmap.engine.TiltTo`. With ``record=True`` the run's
    :class:`~throwmap.records.trajectory.Trajectory` is kept. ``progress(t, t_max)``
    is called every simulated 10 ms if given. ``run_for`` (s): simulate exactly
    this long instead of stopping once settled.

    A run that loses a contact (status ``penetration``) is repeated with half the
    step, up to ``settings.retries`` times; if it still fails, the failure is
    returned (with its message), never the result. With ``settings.verify`` a
    hard run (deep penetration, repeated side changes, an energy gain, a
    timeout; :mod:`.verify`) is rerun at half the step, and where the two
    disagree the run is refused with status ``unconverged`` (its message says
    how they differ); where they agree the first run is returned, ``verified``.
    Without it, a run that blew up (an energy gain over g × :data:`BLOWUP_RISE`) is
    rerun at half the step, and refused (``unconverged``) where that blows up too.

    An unbounded arm (``Arm.length`` None) is simulated as long as the throw
    needs (:mod:`throwmap.engine.reach`); a part that reaches the simulated end is
    rerun on a longer arm, and at the end of the longest it is refused as
    ``unresolved`` (message: the lengths tried), never ``off_end``.
    """
    settings = EngineSettings() if settings is None else settings
    if not isinstance(settings, EngineSettings):
        raise InvalidStateError(
            "settings", f"must be a throwmap.engine.EngineSettings (or None: the defaults), got {type(settings).__name__}")
    if not isinstance(scene, Scene):
        raise InvalidStateError("scene", f"must be a throwmap.engine.Scene, got {type(scene).__name__}")
    realisation = ImpulseThrow(0.0) if realisation is None else check_realisation(realisation)
    t_max = settings.t_max  # the run's length (run_for is checked by _simulate_once)
    if isinstance(run_for, (int, float)) and not isinstance(run_for, bool) and math.isfinite(run_for):
        t_max = max(t_max, float(run_for))
    # an unbounded arm is simulated long enough for the throw; a part reaching its end reruns on a longer one
    with deferred_interrupts():  # a Ctrl-C inside a pymunk callback would be dropped (see .interrupt)
        return _simulate(scene, realisation, settings, record, progress, run_for, t_max)


def _simulate(scene, realisation, settings, record, progress, run_for, t_max) -> EngineRun:
    tried = lengths(scene, realisation, settings.default_length, t_max)
    for n, L in enumerate(tried):
        run = _with_retries(scene, realisation, settings, record, progress, run_for, L)
        if scene.arm.length is None and Status.OFF_END in run.statuses:
            if n + 1 < len(tried):
                continue
            return _refuse_unbounded(run, L, tried)
        break
    if not settings.verify and run_for is None and run.status != Status.PENETRATION \
            and run.energy_gain > scene.arm.g * BLOWUP_RISE:
        return _rerun_blowup(run, scene, realisation, settings, record, progress, L)
    if settings.verify and run_for is None and run.status != Status.PENETRATION:
        why = flags(run, settings)
        if why:
            half = replace(settings, dt=run.dt / 2, coarse_dt=max(settings.coarse_dt / 2, run.dt / 2))
            again = _simulate_once(scene, realisation, half, False, None, None, length=L)
            diff = disagreement(run, again, settings)
            finer = again
            for _ in range(int(settings.refine) if diff else 0):  # halve on until two steps agree
                step = replace(half, dt=finer.dt / 2, coarse_dt=max(half.coarse_dt / 2, finer.dt / 2))
                nxt = _simulate_once(scene, realisation, step, False, None, None, length=L)
                if not disagreement(finer, nxt, settings):
                    kept = nxt if not record else _simulate_once(scene, realisation, step, record, progress, None,
                                                                 length=L)
                    return replace(kept, verified=True, message=(kept.message + "; " if kept.message else "")
                                   + f"converged at dt = {nxt.dt:g} s (the half-step rerun disagreed: {diff})")
                finer, half = nxt, step
            if diff:
                n = len(run.statuses)
                run = replace(run, status=UNCONVERGED, statuses=(UNCONVERGED,) * n,
                              message=(run.message + "; " if run.message else "")
                              + f"half-step rerun ({', '.join(why)}) disagrees: {diff}; result refused")
            else:
                run = replace(run, verified=True)
    return run


def _moved(ref, now) -> bool:
    """Whether a part moved out of the confinement window (:data:`CONFINED_MOVE`) since ``ref`` (body states;
    None: the part has left the arm)."""
    for a, b in zip(ref, now):
        if (a is None) != (b is None):
            return True
        if a is not None and (math.hypot(b[0] - a[0], b[1] - a[1]) > CONFINED_MOVE or abs(b[2] - a[2]) > CONFINED_TURN):
            return True
    return False


def _rerun_blowup(run, scene, realisation, settings, record, progress, L) -> EngineRun:
    """``run`` blew up (:data:`BLOWUP_RISE`): its rerun at half the step, or the refusal where that blows up too."""
    half = replace(settings, dt=run.dt / 2, coarse_dt=max(settings.coarse_dt / 2, run.dt / 2))
    again = _with_retries(scene, realisation, half, record, progress, None, L)
    limit = scene.arm.g * BLOWUP_RISE
    why = f"gained {run.energy_gain:.3g} J/kg at dt = {run.dt:g} s (a blow-up)"
    if again.energy_gain > limit:
        n = len(run.statuses)
        return replace(run, status=UNCONVERGED, statuses=(UNCONVERGED,) * n,
                       message=f"{why}, {again.energy_gain:.3g} J/kg at {again.dt:g} s; result refused")
    return replace(again, message=(again.message + "; " if again.message else "") + f"rerun: {why}")


def _with_retries(scene, realisation, settings, record, progress, run_for, L) -> EngineRun:
    """One run on an arm of length ``L`` (m), repeated at half the step after a lost contact (``settings.retries``)."""
    run = _simulate_once(scene, realisation, settings, record, progress, run_for, length=L)
    tries = 0
    while run.status == Status.PENETRATION and tries < settings.retries:
        tries += 1
        finer = replace(settings, dt=settings.dt / 2**tries, settle_hold=max(settings.settle_hold, 4 * settings.dt))
        first = run.message
        run = _simulate_once(scene, realisation, finer, record, progress, run_for, length=L)
        run = replace(run, message=(run.message + "; " if run.message else "")
                      + f"retried at dt = {finer.dt:g} s after: {first}", retries=tries)
    return run


def _refuse_unbounded(run: EngineRun, L: float, tried: list) -> EngineRun:
    """``run`` on an unbounded arm with a part at the simulated end ``L`` (m): that part ``unresolved``, with the reason."""
    why = unbounded_message(L, tried)
    statuses = tuple(Status.UNRESOLVED if st == Status.OFF_END else st for st in run.statuses)
    status = Status.UNRESOLVED if run.status == Status.OFF_END else run.status
    return replace(run, status=status, statuses=statuses, message=(run.message + "; " if run.message else "") + why)


def _simulate_once(scene, realisation, settings, record, progress, run_for, *, raw: bool = True,
                   length: float | None = None) -> EngineRun:
    """One attempt of :func:`simulate` (no retries) on an arm ``length`` m long (None: :meth:`Scene.length`);
    ``raw=False`` calls pymunk's public API only."""
    if not isinstance(scene, Scene):
        raise InvalidStateError("scene", f"must be a throwmap.engine.Scene, got {type(scene).__name__}")
    realisation = ImpulseThrow(0.0) if realisation is None else check_realisation(realisation)
    t_max = settings.t_max
    if run_for is not None:
        if isinstance(run_for, bool) or not isinstance(run_for, (int, float)) or not run_for > 0 \
                or not math.isfinite(run_for):
            raise InvalidStateError("run_for", f"must be a positive number of seconds, got {shown(run_for)}")
        t_max = float(run_for)
    w = build_world(scene, realisation, settings, raw=raw, length=length)
    try:
        return _run_world(w, scene, realisation, settings, record, progress, run_for, t_max)
    finally:
        if w.native is not None:  # the space gets its own callbacks back: it may outlive the run's C state
            w.native.detach()


def _run_world(w, scene, realisation, settings, record, progress, run_for, t_max) -> EngineRun:
    """The loop of :func:`_simulate_once` on world ``w`` (built for ``scene``), until every part settles or ``t_max``."""
    contacts = Contacts(w)
    tracks, events = contacts.tracks, contacts.events
    recorder = Recorder(w) if record else None
    dt, coarse_dt, margin = settings.dt, settings.coarse_dt, settings.flight_margin
    use_coarse = coarse_dt > dt
    alpha = scene.alpha
    end_alpha = alpha + (realisation.delta if hasattr(realisation, "delta") else 0.0)
    arm_stop = realisation.duration
    angle = angle_function(realisation)
    omega_arm_bound = abs(getattr(realisation, "omega", 0.0)) + abs(getattr(realisation, "peak_rate", 0.0)) \
        + abs(getattr(realisation, "rate_", 0.0))
    n_parts = w.n
    pen_tol, impact_window = settings.penetration_tol, settings.impact_window
    settle_hold = settings.settle_hold
    exact_flight = settings.exact_flight
    horizon = 2.0 * 4.0 * coarse_dt if use_coarse else 0.0  # twice the longest stretch between two checks, s
    n_steps = n_coarse = n_leaps = n_checks = n_clearance = 0
    native = w.native
    if native is not None:  # (bound once: the C helper's calls, else the same checks in Python)
        look, clear, parked_steps = native.probe, native.clearance, native.steps
    else:
        look, clear, parked_steps = partial(probe, w), partial(clearance, w), None

    t = 0.0
    next_check = next_flight_check = next_sample = next_progress = 0.0
    still_since = None
    confined_ref, confined_since = None, 0.0  # several parts: poses and time the confinement window began
    landing_near = False  # a vertex not in contact may touch before the next check: no coarse steps
    e_low = [math.inf] * n_parts  # lowest energy of each part since the arm stopped, J/kg
    e_gain = 0.0  # largest energy gain over that, J/kg
    masses = [float(p.mass) for p in w.parts]  # several parts: the gain is of their total energy per unit total mass
    m_total = sum(masses)
    status = Status.OK
    message = ""
    pen_max = 0.0
    pen_part = [float(tr.rec[C.PENETRATION_MAX]) for tr in tracks]  # each part's deepest, written back at the end
    done = False
    while not done:
        if record and t >= next_sample - 1e-12:
            recorder.sample(t)
            next_sample += settings.record_dt
        if progress is not None and t >= next_progress:
            progress(t, t_max)
            next_progress += 0.01
        if t >= t_max - 1e-12:
            if run_for is not None:
                break
            status = Status.TIMEOUT
            message = f"not settled after {t_max:g} s"
            flying = [str(i) for i, tr in enumerate(tracks) if tr.fell is None and not tr.ever and tr.n_contacts == 0]
            if flying:
                message += f" (part {', '.join(flying)} still in its first flight: raise EngineSettings.t_max)"
            for tr in tracks:
                if tr.fell is None:
                    tr.status = Status.TIMEOUT
            break
        arm_moving = t < arm_stop
        # -------------------------------------------- exact free flight when every part is clear
        if exact_flight and t >= next_flight_check and contacts.n_touching == 0:  # all free
            next_flight_check = t + CHECK_EVERY
            n_clearance += n_parts
            # (clearance may stop at a pair within margin: only gap > margin and, then, its exact value matter)
            gap = min(clear(i, margin) if tracks[i].fell is None else math.inf for i in range(n_parts)) \
                if n_parts > 1 else clear(0, margin) if tracks[0].fell is None else math.inf
            if gap > margin:
                vmax = vertex_speed_bound(w, tracks)
                if n_parts > 1:  # two parts in flight close on each other at up to the sum of their speeds
                    vmax *= 2.0
                vmax += 2.0 * omega_arm_bound * w.reach if arm_moving else 0.0
                tau = min(leap_length(w, gap, vmax, margin), 0.05, t_max - t)
                if record:
                    tau = min(tau, max(next_sample - t, dt))
                if tau > 4 * dt:
                    t += tau
                    contacts.now = t
                    leap(w, tau, alpha + angle(t))
                    n_leaps += 1
                    # a part falling past an edge of the arm has left it: say so now, not at t_max
                    for i in range(n_parts):
                        if tracks[i].fell is None:
                            gone = look(i)[16]
                            if gone:
                                contacts.fell(i, t, GONE[int(gone)])
                    if contacts.n_fell == n_parts:
                        break
                    continue
        # -------------------------------------------- fixed steps up to the next check
        coarse = (use_coarse and not arm_moving and not landing_near and t - contacts.last_begin >= impact_window
                  and contacts.n_touching - contacts.n_fell_touching == n_parts - contacts.n_fell)  # all touching
        h_step = coarse_dt if coarse else dt
        n_inner = max(1, int(math.ceil((min(next_check, t_max) - t) / h_step - 1e-9)))
        if native is None:
            t = fixed_steps(w, contacts, t, n_inner, h_step, angle, alpha, arm_stop, end_alpha)
        else:  # (fixed_steps in C: the arm parked, or moving)
            if not arm_moving and w.arm_w == 0.0:
                t = parked_steps(contacts, t, n_inner, h_step)
            else:
                t = native.arm_steps(w, contacts, t, n_inner, h_step, angle, alpha, arm_stop, end_alpha)
            check_interrupt()
        n_steps += n_inner
        if coarse:
            n_coarse += n_inner
        if contacts.n_touching < n_parts:
            contacts.after_steps(t)
        # -------------------------------------------- periodic checks
        if t >= next_check:
            n_checks += 1
            next_check = t + (CHECK_EVERY if h_step == dt else 4.0 * h_step)
            landing_near = False
            states = [None] * n_parts  # several parts: each one's state at this instant (confinement)
            slow = True  # every part still on the arm below the settling speeds
            e_sum = 0.0  # Σ m_i e_i of the parts still on the arm (several parts), J
            for i in range(n_parts):
                tr = tracks[i]
                if tr.fell is not None:
                    continue
                flips = tr.n_contacts > 0 and tr.ever
                # one part touching nothing: its `near` is not looked for (horizon 0), since it cannot matter:
                # coarse steps need it touching, and the contact that begins first sets last_begin later
                # than this check would (with more parts, one leaving the arm here could still matter)
                px, py, pa, vx, vy, om, pen, _, _, _, _, near, e, slow_i, k, tilt, gone = look(
                    i, 0.0 if n_parts == 1 and tr.n_contacts == 0 else horizon, flips)
                if n_parts > 1:
                    states[i] = (px, py, pa, vx, vy, om)
                if near:  # a landing is coming: fine steps until impact_window after it (pymunk's warm
                    landing_near = True  # start would scale the landing impulse by coarse_dt / dt)
                    contacts.last_begin = t
                if gone:  # left the arm: its depth "into" the arm's far side is no penetration
                    contacts.fell(i, t, GONE[int(gone)])
                    continue
                if not slow_i:
                    slow = False
                if t >= arm_stop:
                    if n_parts > 1:  # parts push each other: only their total energy may not rise
                        e_sum += masses[i] * e
                    else:
                        if e < e_low[i]:  # min and max as ifs
                            e_low[i] = e
                        if e - e_low[i] > e_gain:
                            e_gain = e - e_low[i]
                if pen > pen_part[i]:
                    pen_part[i] = pen
                if pen > pen_max:
                    pen_max = pen
                if pen > pen_tol:
                    tr.status = Status.PENETRATION
                    status = Status.PENETRATION
                    message = (f"part {i}: a vertex sank {pen * 1e3:.2f} mm into {sunk_into(w, i)} "
                               f"at t = {t:.4f} s "
                               f"(> penetration_tol {pen_tol * 1e3:g} mm); result refused")
                    done = True
                    break
                # flips: the side the part lies on whenever it is in contact and nearly flat
                if flips:
                    k = int(k)
                    if abs(tilt) < FLIP_TILT:
                        if k != tr.last_side:
                            tr.rec[C.N_FLIPS] += 1.0
                            events.append((t, f"flip {tr.last_side}→{k}"))
                        tr.last_side = k
            if done:
                break
            if n_parts > 1 and t >= arm_stop:  # the parts' total energy per unit total mass, J/kg (a part
                e = e_sum / m_total  # leaving the arm only lowers it)
                if e < e_low[0]:
                    e_low[0] = e
                if e - e_low[0] > e_gain:
                    e_gain = e - e_low[0]
            if contacts.n_fell == n_parts:
                break
            # settling
            if t >= arm_stop:
                if slow:
                    if still_since is None:
                        still_since = t
                    elif t - still_since >= settle_hold and run_for is None:
                        done = True
                else:
                    still_since = None
                    if n_parts > 1 and run_for is None:  # at rest up to Chipmunk's jitter (CONFINED)?
                        now = [states[i] if tracks[i].fell is None else None for i in range(n_parts)]
                        if confined_ref is None or _moved(confined_ref, now):
                            confined_ref, confined_since = now, t
                        elif t - confined_since >= CONFINED_HOLD:
                            still_since, done = confined_since, True
                            message = (message + "; " if message else "") + (
                                f"at rest from t = {confined_since:.3f} s by confinement (every part within "
                                f"{CONFINED_MOVE * 1e3:g} mm and {CONFINED_TURN:g} rad for {CONFINED_HOLD:g} s, "
                                "never below the settling speeds)")
    for tr, pen in zip(tracks, pen_part):
        if pen > tr.rec[C.PENETRATION_MAX]:
            tr.rec[C.PENETRATION_MAX] = pen
    if status == Status.OK and still_since is not None:
        events.append((still_since, "rest"))
    if record:
        recorder.sample(t)
    contacts.finished = True
    counts = {"steps": n_steps, "coarse": n_coarse, "leaps": n_leaps, "checks": n_checks, "clearance": n_clearance,
              "capped": contacts.friction_cap.n_capped if contacts.friction_cap is not None else 0, "energy_gain": e_gain, "dt": dt}
    return finish(scene, w, contacts, status, message, t, still_since, counts, pen_max, recorder)
