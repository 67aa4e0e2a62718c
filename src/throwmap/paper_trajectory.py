"""Dense time histories of the "paper" model's throws, for animation and inspection.

The throw map of :mod:`throwmap.kernels.paper` only resolves *where* a part comes
to rest. :func:`paper_trajectory` re-plays the same guard/reset sequence
(paper Sec. III-B–C, Eqs. 1–4; :mod:`throwmap.kernels.roll`) and adds *when*:

* **release** (t = 0): the part leaves the arm moving rigidly with it, CM velocity
  ω × r and spin ω (Eq. 1). The arm's displacement is negligible (an impulsive
  throw), so the arm stays horizontal (``arm_angle = 0``) throughout.
* **flight**: the closed form of Eq. (1), sampled every ``dt`` up to the first
  contact time the kernel reports (Eq. 3).
* **first impact**: plastic, no slip (Eq. 4), about the touching vertex.
* **pivot swings**: about vertex w_j the part is a compound pendulum,
  ``I_j θ̈ = −g ℓ_j cos θ`` with θ the angle of pivot → CM and I_j = ρ² + ℓ_j²
  (per unit mass). The kernel decides which end the swing reaches (over the
  peak, downhill, or turning back); the time along it comes from the energy
  quadrature ``t(θ) = ∫ dθ / |θ̇(θ)|``, ``θ̇² = 2 (E − g ℓ_j sin θ) / I_j``,
  evaluated with the substitution ``θ = θ_a + (θ_b − θ_a)(1 − cos πu)/2``, which
  removes the inverse-square-root singularity at a turning point or a start from
  rest (a midpoint rule in u, :data:`QUADRATURE_NODES` nodes per monotone piece).
* **side landings**: the plastic impact about the side's other vertex of
  :mod:`~throwmap.kernels.roll` (pivot on it, rest, or tip over an unstable side),
  and rocking to rest decided as the kernel does (energy below both barriers).

Poses are continuous through every impact (only velocities jump); the body angle
φ is kept unwrapped. The last pose is the kernel's resting configuration exactly:
``state_from_pose`` of it gives the ``(x, side)`` of
``throw(part, arm, x, side, omega, model="paper")`` (tested).

Events (``(t, label)``): ``"release"``, ``"impact v<j>"`` (first contact; j is the
user's vertex index, as :attr:`ThrowOutcome.contact_vertex`), ``"land side <k>"``
at every side landing, ``"flip <a>→<b>"`` at a landing on a side other than the
previous one, ``"rest"``, or ``"escape: <status>"`` where the part leaves the arm.

Contacts per sample (world (K, 2) arrays): both support vertices at rest and at a
landing, the pivot while swinging, none in flight.

:func:`orbit_trajectory` strings successive throws together with a short still
pause between them (any model that provides a trajectory function).
"""

from __future__ import annotations

import math

import numpy as np

from .system.arm import Arm
from .errors import InvalidStateError
from .kernels import codes as C
from .throws.outcome import Status, ThrowOutcome
from .system.part import Part
from .kernels.paper import throw_one
from .throws.throw import DEFAULT_MAX_IMPACTS, DEFAULT_MAX_ITER, DEFAULT_N_SAMPLES, DEFAULT_TOL, check_start, throw
from .throws.trajectory import Trajectory

__all__ = ["paper_trajectory", "orbit_trajectory", "QUADRATURE_NODES", "DEFAULT_DT"]

DEFAULT_DT = 1.0 / 240.0
"""Default sample interval, s."""
QUADRATURE_NODES = 400
"""Nodes of the time quadrature per monotone piece of a pivot swing."""
ESCAPE_FALL_TIME = 0.3
"""After a first contact off the arm, the free fall is drawn for this long, s."""
TRAJECTORY_MODELS = ("paper", "rigid_body", "engine")
"""Models :func:`orbit_trajectory` can render."""

_NO_CONTACT = np.zeros((0, 2))


def _contact(*points) -> np.ndarray:
    a = np.array(points, dtype=float).reshape(-1, 2)
    a.setflags(write=False)
    return a


class _Recorder:
    """Collects samples (t, pose, contacts) and events, keeping φ continuous."""

    def __init__(self):
        self.t: list[float] = []
        self.poses: list[tuple[float, float, float]] = []
        self.contacts: list[np.ndarray] = []
        self.events: list[tuple[float, str]] = []

    @property
    def now(self) -> float:
        return self.t[-1] if self.t else 0.0

    def continuous(self, phi):
        """φ (array or float) shifted by a multiple of 2π to continue the last sample's φ."""
        if not self.poses:
            return phi
        first = float(np.atleast_1d(phi)[0])
        k = round((self.poses[-1][2] - first) / (2.0 * math.pi))
        return phi + 2.0 * math.pi * k

    def add(self, times, xs, ys, phis, contacts, skip_first: bool = False):
        times = np.atleast_1d(np.asarray(times, dtype=float))
        xs = np.broadcast_to(np.asarray(xs, dtype=float), times.shape)
        ys = np.broadcast_to(np.asarray(ys, dtype=float), times.shape)
        phis = self.continuous(np.broadcast_to(np.asarray(phis, dtype=float), times.shape))
        start = 1 if skip_first else 0
        for i in range(start, times.size):
            self.t.append(float(times[i]))
            self.poses.append((float(xs[i]), float(ys[i]), float(phis[i])))
            self.contacts.append(contacts(i) if callable(contacts) else contacts)

    def event(self, label: str, t: float | None = None):
        self.events.append((self.now if t is None else float(t), label))


def _grid(t0: float, t1: float, dt: float) -> np.ndarray:
    """Times t0, t0 + dt, … and exactly t1 (at least the two ends)."""
    if t1 <= t0:
        return np.array([t0, t0])
    n = max(1, int(math.ceil((t1 - t0) / dt - 1e-9)))
    g = t0 + dt * np.arange(n + 1)
    g[-1] = t1
    return g


def _swing_piece(th0: float, th1: float, E: float, lj: float, I: float, g: float, nodes: int):
    """Time table ``(t, θ)`` of a monotone swing from θ0 to θ1 at energy E (per unit mass).

    ``t(θ) = ∫ dθ / |θ̇|`` with ``θ = θ0 + (θ1 − θ0)(1 − cos πu)/2`` and a midpoint
    rule in u; |θ̇| is floored at a tiny value so a swing that creeps over a peak
    with (numerically) zero margin still takes a finite time.
    """
    u_nodes = np.linspace(0.0, 1.0, nodes + 1)
    th_nodes = th0 + (th1 - th0) * 0.5 * (1.0 - np.cos(math.pi * u_nodes))
    th_nodes[-1] = th1
    if th1 == th0:
        return np.zeros(nodes + 1), th_nodes
    um = 0.5 * (u_nodes[:-1] + u_nodes[1:])
    thm = th0 + (th1 - th0) * 0.5 * (1.0 - np.cos(math.pi * um))
    dth_du = abs(th1 - th0) * 0.5 * math.pi * np.sin(math.pi * um)
    w2 = 2.0 * (E - g * lj * np.sin(thm)) / I
    floor = 1e-6 * math.sqrt(g / lj)
    speed = np.sqrt(np.maximum(w2, floor * floor))
    t_nodes = np.concatenate(([0.0], np.cumsum(dth_du / speed) / nodes))
    return t_nodes, th_nodes


def _theta_a(j, n, d, uL):
    k = (j - 1) % n
    return math.atan2(d[k], -uL[k])


def _theta_b(j, d, uR):
    return math.atan2(d[j], -uR[j])


def _paper_run(part: Part, arm: Arm, x0: float, side: int, omega: float, dt: float, max_impacts: int,
               nodes: int) -> tuple[_Recorder, float, int, Status]:
    """Replay the paper kernel's guard/reset sequence with time; returns (recorder, x, side, status)."""
    h, g = arm.h, arm.g
    length = arm.length_or_inf
    rho2 = part.radius_of_gyration ** 2
    w, beta, d, uL, uR, ell, stable = part.w, part.beta, part.d, part.uL, part.uR, part.ell, part.stable
    n = part.n_sides
    alpha = np.arctan2(w[:, 1], w[:, 0])  # body angle of CM → w_j
    rec = _Recorder()
    dk = float(d[side])
    phi0 = float(beta[side])
    rest_contacts = _contact((x0 + uR[side], h), (x0 + uL[side], h))
    rec.add([0.0], x0, h + dk, phi0, rest_contacts)
    rec.event("release")
    if omega == 0.0:
        rec.event("rest")
        return rec, x0, side, Status.OK

    # ------------------------------------------------------------ flight (Eq. 1) to first contact (Eq. 3)
    krec = np.empty(C.NREC)
    throw_one(x0, side, omega, h, g, length, rho2, w, beta, d, uL, uR, ell, stable, DEFAULT_TOL, DEFAULT_MAX_ITER,
              max_impacts, DEFAULT_N_SAMPLES, krec)
    t_f = float(krec[C.T_FLIGHT])
    jc = int(krec[C.CONTACT_VERTEX])

    def flight(ts):
        return x0 - (h + dk) * omega * ts, h + dk + x0 * omega * ts - 0.5 * g * ts * ts, phi0 + omega * ts

    if jc < 0:  # the contact search gave up (should not happen): draw a short flight and stop
        ts = _grid(0.0, ESCAPE_FALL_TIME, dt)
        rec.add(ts, *flight(ts), _NO_CONTACT, skip_first=True)
        rec.event(f"escape: {Status.NO_CONTACT.label}")
        return rec, x0, side, Status.NO_CONTACT
    ts = _grid(0.0, t_f, dt)
    xs, ys, phis = flight(ts)
    cp, sp = math.cos(omega * t_f), math.sin(omega * t_f)
    pu = math.cos(phi0) * w[jc, 0] - math.sin(phi0) * w[jc, 1]
    pv = math.sin(phi0) * w[jc, 0] + math.cos(phi0) * w[jc, 1]
    rx, ry = cp * pu - sp * pv, sp * pu + cp * pv
    xc_f = float(xs[-1])
    px = xc_f + rx
    last = len(ts) - 1
    rec.add(ts, xs, ys, phis, lambda i: _contact((px, h)) if i == last else _NO_CONTACT, skip_first=True)
    rec.event(f"impact v{part.user_vertex(jc)}")
    if px <= 0.0 or px > length:
        status = Status.BEHIND_JOINT if px <= 0.0 else Status.OFF_END
        rec.event(f"escape: {status.label}")
        # nothing to land on there: the part falls on past the arm line
        ts2 = _grid(t_f, t_f + ESCAPE_FALL_TIME, dt)
        vx, vy = -(h + dk) * omega, x0 * omega - g * t_f
        s2 = ts2 - t_f
        rec.add(ts2, xc_f + vx * s2, float(ys[-1]) + vy * s2 - 0.5 * g * s2 * s2, float(phis[-1]) + omega * s2,
                _NO_CONTACT, skip_first=True)
        return rec, xc_f, side, status

    # plastic impact about the contact vertex (Eq. 4): the pivot's spin
    H = rho2 * omega + ry * (-(h + dk) * omega) - rx * (x0 * omega - g * t_f)
    thdot = H / (rho2 + rx * rx + ry * ry)
    theta = math.atan2(-ry, -rx)
    j = jc

    # ------------------------------------------------------------ pivot swings and landings (roll.py)
    last_side = side
    n_impacts = 1
    while True:
        lj = float(ell[j])
        I = rho2 + lj * lj
        ta = _theta_a(j, n, d, uL)
        tb = _theta_b(j, d, uR)
        theta = min(max(theta, ta), tb)
        E = 0.5 * I * thdot * thdot + g * lj * math.sin(theta)
        if thdot > 0.0:
            dirn = 1
        elif thdot < 0.0:
            dirn = -1
        else:
            dirn = 1 if math.cos(theta) < 0.0 else -1
        if dirn > 0:
            end = tb
            peak_ahead = theta < 0.5 * math.pi < tb
        else:
            end = ta
            peak_ahead = ta < 0.5 * math.pi < theta
        if peak_ahead:
            barrier = g * lj
        elif math.sin(end) > math.sin(theta):
            barrier = g * lj * math.sin(end)
        else:
            barrier = -math.inf
        if E > barrier:
            pieces = [(theta, end)]
            land_dir = dirn
        else:
            s_turn = min(E / (g * lj), 1.0)
            th_turn = math.asin(s_turn) if dirn > 0 else math.pi - math.asin(s_turn)
            end = ta if dirn > 0 else tb
            pieces = [(theta, th_turn), (th_turn, end)]
            land_dir = -dirn
        # time along the swing
        t_tab, th_tab = [np.array([0.0])], [np.array([theta])]
        for a, b in pieces:
            tt, th = _swing_piece(a, b, E, lj, I, g, nodes)
            t_tab.append(tt[1:] + t_tab[-1][-1])
            th_tab.append(th[1:])
        t_tab = np.concatenate(t_tab)
        th_tab = np.concatenate(th_tab)
        t0 = rec.now
        ts = _grid(t0, t0 + float(t_tab[-1]), dt)
        ths = np.interp(ts - t0, t_tab, th_tab)
        ths[-1] = end
        pxj = px
        rec.add(ts, pxj + lj * np.cos(ths), h + lj * np.sin(ths), ths + math.pi - alpha[j],
                _contact((pxj, h)), skip_first=True)
        w2 = 2.0 * (E - g * lj * math.sin(end)) / I
        speed = math.sqrt(w2) if w2 > 0.0 else 0.0
        thdot = speed if land_dir > 0 else -speed
        # ---------------------------------------------------------- reset land_side
        if land_dir > 0:
            k = j
            uA, uB = float(uR[k]), float(uL[k])
            jB = (j + 1) % n
        else:
            k = (j - 1) % n
            uA, uB = float(uL[k]), float(uR[k])
            jB = k
        dk_ = float(d[k])
        x_cm = px - uA
        pxB = x_cm + uB
        # the landing pose exactly (flat on side k, CM at x_cm)
        rec.poses[-1] = (x_cm, h + dk_, float(rec.continuous(float(beta[k]))))
        rec.contacts[-1] = _contact((px, h), (pxB, h))
        rec.event(f"land side {k}")
        if k != last_side:
            rec.event(f"flip {last_side}→{k}")
            last_side = k
        n_impacts += 1
        if n_impacts > max_impacts:
            rec.event(f"escape: {Status.NO_REST.label}")
            return rec, x_cm, k, Status.NO_REST
        w_new = thdot * (rho2 + uA * uB + dk_ * dk_) / (rho2 + uB * uB + dk_ * dk_)
        lifts = (w_new > 0.0) if land_dir > 0 else (w_new < 0.0)
        IB = rho2 + uB * uB + dk_ * dk_
        k_after = 0.5 * IB * w_new * w_new if lifts else 0.0
        if pxB <= 0.0 or pxB > length:
            status = Status.BEHIND_JOINT if pxB <= 0.0 else Status.OFF_END
            rec.event(f"escape: {status.label}")
            return rec, x_cm, k, status
        if lifts:
            if stable[k] and k_after < min(g * (ell[j] - dk_), g * (ell[jB] - dk_)):
                rec.event("rest")  # rocks to rest (Zeno), energy below both barriers
                return rec, x_cm, k, Status.OK
            j = jB
            px = pxB
            thdot = w_new
            theta = _theta_a(j, n, d, uL) if land_dir > 0 else _theta_b(j, d, uR)
        elif stable[k]:
            rec.event("rest")
            return rec, x_cm, k, Status.OK
        else:
            thdot = 0.0
            if uL[k] >= 0.0:
                j = (k + 1) % n
                px = x_cm + float(uL[k])
                theta = _theta_a(j, n, d, uL)
            else:
                j = k
                px = x_cm + float(uR[k])
                theta = _theta_b(j, d, uR)
        if px <= 0.0 or px > length:
            status = Status.BEHIND_JOINT if px <= 0.0 else Status.OFF_END
            rec.event(f"escape: {status.label}")
            return rec, x_cm, k, status


def _drawn_length(arm: Arm, poses: np.ndarray, parts) -> float:
    """The arm's length, or for an unbounded arm one reaching a little past every vertex."""
    if arm.length is not None:
        return float(arm.length)
    reach = 0.0
    for p, part in enumerate(parts):
        r = float(np.max(part.ell))
        reach = max(reach, float(np.max(poses[:, p, 0])) + r)
    return max(1.15 * reach, reach + 0.03)


def _check_dt(dt) -> float:
    if isinstance(dt, bool):
        raise InvalidStateError("dt", f"must be a number, got {dt!r}")
    try:
        v = float(dt)
    except (TypeError, ValueError):
        raise InvalidStateError("dt", f"must be a number, got {dt!r}") from None
    if not (math.isfinite(v) and v > 0):
        raise InvalidStateError("dt", f"must be a positive finite time step (s), got {dt!r}")
    return v


def paper_throw_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, *, dt: float = DEFAULT_DT,
                           max_impacts: int = DEFAULT_MAX_IMPACTS,
                           nodes: int = QUADRATURE_NODES) -> tuple[ThrowOutcome, Trajectory]:
    """Like :func:`paper_trajectory`, also returning the kernel's :class:`ThrowOutcome`.

    Same signature shape as ``engine_trajectory``/``rigid_trajectory``.
    """
    dt = _check_dt(dt)
    x0, k0, om = check_start(part, arm, x, side, omega)
    outcome = throw(part, arm, x0, k0, om, model="paper", max_impacts=max_impacts)
    rec, xf, kf, status = _paper_run(part, arm, x0, k0, om, dt, max_impacts, nodes)
    if status != outcome.status or kf != outcome.side or not math.isclose(xf, outcome.x, rel_tol=1e-9,
                                                                          abs_tol=1e-12):
        # the replay must follow the kernel; anything else is a bug here, not bad input
        raise RuntimeError(f"paper_trajectory: replay ended at ({xf!r}, {kf}, {status.label}) but the kernel "
                           f"at ({outcome.x!r}, {outcome.side}, {outcome.status.label})")
    poses = np.array(rec.poses, dtype=float)[:, None, :]
    t = np.array(rec.t)
    traj = Trajectory(
        t=t,
        arm_angle=np.zeros_like(t),
        poses=poses,
        parts=(part,),
        h=arm.h,
        length=_drawn_length(arm, poses, (part,)),
        fixtures=(),
        contacts=tuple(rec.contacts),
        events=tuple(rec.events),
        source="paper",
        meta={"outcomes": (outcome,), "arm": arm, "arm_unbounded": arm.length is None},
    )
    return outcome, traj


def paper_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, *, dt: float = DEFAULT_DT,
                     max_impacts: int = DEFAULT_MAX_IMPACTS) -> Trajectory:
    """Time history of one "paper"-model throw from rest at ``(x, side)`` with release rate ``omega``.

    Parameters
    ----------
    part, arm : Part, Arm
        The arm stays horizontal (an impulsive throw); ``arm.length=None`` is drawn
        a little longer than the part's reach.
    x : float, m
        Resting CM position along the arm; ``side`` the stable side it rests on.
    omega : float, rad/s
        Release angular velocity (≥ 0).
    dt : float, s
        Sample interval (phase changes are sampled exactly in addition).
    max_impacts : int
        Impact cap, as in :func:`throwmap.throws.throw`.

    Returns
    -------
    Trajectory
        One part, ``source="paper"``; the first sample is the resting start at t = 0
        (the release), the last the kernel's resting configuration (or the escape).
        ``meta["outcomes"]`` holds the :class:`ThrowOutcome` of
        ``throw(..., model="paper")``. Events and contacts as in the module docstring.
    """
    return paper_throw_trajectory(part, arm, x, side, omega, dt=dt, max_impacts=max_impacts)[1]


# ------------------------------------------------------------------ orbits
def trajectory_function(model: str):
    """``f(part, arm, x, side, omega) -> (ThrowOutcome, Trajectory)`` for a model name.

    ``"paper"`` is always available; ``"engine"`` (:func:`throwmap.engine.engine_trajectory`)
    and ``"rigid_body"`` (:func:`throwmap.rigid_trajectory`) are imported on demand and
    raise :class:`ImportError` where they are not installed.
    """
    if model == "paper":
        return paper_throw_trajectory
    if model == "engine":
        from .engine import engine_trajectory

        return engine_trajectory
    if model == "rigid_body":
        from .rigid_trajectory import rigid_trajectory

        return rigid_trajectory
    raise InvalidStateError("model", f"cannot animate model {model!r} (choose from {', '.join(TRAJECTORY_MODELS)})")


def _pause(traj: Trajectory, seconds: float, dt: float) -> Trajectory:
    """The last sample of ``traj`` held still for ``seconds`` (starting at t = 0)."""
    ts = _grid(0.0, seconds, dt)
    m = ts.size
    return Trajectory(
        t=ts,
        arm_angle=np.full(m, traj.arm_angle[-1]),
        poses=np.repeat(traj.poses[-1:], m, axis=0),
        parts=traj.parts, h=traj.h, length=traj.length, fixtures=traj.fixtures,
        contacts=(traj.contacts[-1],) * m if traj.contacts else (),
        events=(), source=traj.source,
    )


def _dedupe(traj: Trajectory) -> Trajectory:
    """Drop samples whose time repeats the previous one (the joints :meth:`Trajectory.concat` makes)."""
    keep = np.ones(traj.n_samples, dtype=bool)
    keep[1:] = np.diff(traj.t) > 0.0
    if keep.all():
        return traj
    # keep the later of two samples at one time (the start of the next piece)
    keep = np.ones(traj.n_samples, dtype=bool)
    keep[:-1] = np.diff(traj.t) > 0.0
    idx = np.flatnonzero(keep)
    contacts = tuple(traj.contacts[i] for i in idx) if len(traj.contacts) == traj.n_samples else traj.contacts
    return Trajectory(traj.t[idx], traj.arm_angle[idx], traj.poses[idx], traj.parts, traj.h, traj.length,
                      traj.fixtures, contacts, traj.events, traj.source, dict(traj.meta))


def orbit_trajectory(part: Part, arm: Arm, x: float, side: int, omegas, n: int | None = None, model: str = "paper",
                     pause: float = 0.3, *, dt: float = DEFAULT_DT, progress=None) -> Trajectory:
    """Successive throws from ``(x, side)`` as one trajectory, with a still ``pause`` (s) between throws.

    ``omegas`` is one release rate (then ``n`` throws) or one per throw (as
    :func:`throwmap.iterate`). Stops after a throw that escapes (leaves the arm or
    does not come to rest); that throw is drawn. ``model`` is ``"paper"``
    (:func:`paper_trajectory`), ``"rigid_body"`` or ``"engine"`` (see
    :func:`trajectory_function`). ``progress``, if given, is called with the number
    of throws done after each. ``meta["outcomes"]`` holds each throw's
    :class:`ThrowOutcome`; ``meta["throw_starts"]`` each release time (s).
    """
    from .throws.orbit import throw_rates

    om = throw_rates(omegas, n, min_n=1)
    pause = float(pause)
    if not (math.isfinite(pause) and pause >= 0):
        raise InvalidStateError("pause", f"must be a finite time ≥ 0 (s), got {pause!r}")
    dt = _check_dt(dt)
    fn = trajectory_function(model)
    kwargs = {"dt": dt} if model == "paper" else {}
    traj = None
    outcomes = []
    starts = []
    xs, ss = float(x), side
    for w in om:
        out, piece = fn(part, arm, xs, ss, float(w), **kwargs)
        outcomes.append(out)
        if traj is None:
            starts.append(0.0)
            traj = piece
        else:
            if pause > 0:
                traj = traj.concat(_pause(traj, pause, dt))
            starts.append(float(traj.t[-1]))
            traj = traj.concat(piece)
        if progress is not None:
            progress(len(outcomes))
        if out.status != Status.OK:
            break
        xs, ss = out.x, out.side
    traj = _dedupe(traj)
    length = traj.length
    if arm.length is None and not traj.fixtures:  # an unbounded arm: draw it just past the part's reach
        length = _drawn_length(arm, traj.poses, traj.parts)
    meta = dict(traj.meta)
    meta.update(outcomes=tuple(outcomes), throw_starts=tuple(starts), arm=arm, arm_unbounded=arm.length is None)
    return Trajectory(traj.t, traj.arm_angle, traj.poses, traj.parts, traj.h, length, traj.fixtures, traj.contacts,
                      traj.events, traj.source if len(om) == 1 else f"{traj.source} orbit", meta)
