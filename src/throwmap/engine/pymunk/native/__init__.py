"""The engine's C helper: the friction hook, the exact contact solve, blocks of steps and the per-part checks.

The run loop's hot paths, called once per contact per step (the friction hook, :mod:`..friction`; the exact
solve, :mod:`..exact`) or once per step or check (:mod:`..stepping`, :mod:`..checks`), written in C with the same
arithmetic as their Python versions, so that a run is the same bit for bit with or without it
(``tests/engine/test_native.py``). It calls Chipmunk through pointers taken from pymunk's own compiled module and
reads Chipmunk's structs with the layout pymunk's cffi declarations give (checked on load).

It is built on first use (:mod:`.build`); where it cannot be built (no C compiler), loaded or bound to this
pymunk, or where ``THROWMAP_NATIVE=0`` is set, the engine runs its Python versions (:func:`available` says why
not). :func:`disabled` turns it off for a block (tests compare both).
"""

from __future__ import annotations

import contextlib
import math
import os

__all__ = ["NativeRun", "available", "disabled", "load", "reason"]

_STATE = {"module": None, "reason": None, "tried": False, "off": 0}


def _bind(module) -> None:
    """Bind Chipmunk's functions and check the mirrored struct layouts against pymunk's (raises ImportError)."""
    from pymunk._chipmunk import ffi as pffi
    from pymunk._chipmunk import lib as plib

    ffi, lib = module.ffi, module.lib
    names = ("cpArbiterGetNormal", "cpArbiterGetCount", "cpArbiterGetPointA", "cpArbiterGetPointB",
             "cpArbiterGetContactPointSet", "cpArbiterSetFriction", "cpArbiterGetFriction", "cpArbiterGetBodies",
             "cpArbiterGetShapes", "cpShapeGetCollisionType", "cpShapeGetBody", "cpBodyGetPosition", "cpBodyGetVelocity",
             "cpBodyGetAngularVelocity", "cpBodyGetAngle", "cpBodySetPosition", "cpBodySetVelocity", "cpBodySetAngle",
             "cpBodySetAngularVelocity", "cpBodySetVelocityUpdateFunc", "cpBodyUpdateVelocity", "cpBodyEachArbiter",
             "cpBodyGetSpace", "cpBodyLocalToWorld", "cpShapePointQuery", "cpSpaceStep", "cpSpaceGetUserData",
             "cpSpaceSetUserData", "cpSpaceReindexShapesForBody", "cpArbiterIsRemoval")
    missing = None
    for name in names:
        try:
            fn = pffi.addressof(plib, name)
        except (AttributeError, TypeError) as exc:
            raise ImportError(f"pymunk lacks {name}") from exc
        missing = lib.tm_bind(name.encode(), ffi.cast("void *", int(pffi.cast("uintptr_t", fn))))
    if missing != 0:
        raise ImportError(f"{missing} Chipmunk functions left unbound")
    point = pffi.typeof("cpContactPointSet").fields[2][1].type.item
    arb, con, cps, handler = "struct cpArbiter", "struct cpContact", "cpContactPointSet", "struct cpCollisionHandler"
    expected = [pffi.sizeof(arb)] + [pffi.offsetof(arb, f) for f in ("u", "surface_vr", "a", "b", "body_a", "body_b",
                                                                     "count", "contacts", "n", "state")]
    expected += [pffi.sizeof(con)] + [pffi.offsetof(con, f) for f in ("r1", "r2", "tMass", "bounce", "jnAcc", "jtAcc",
                                                                      "hash")]
    expected += [pffi.sizeof(cps), pffi.offsetof(cps, "normal"), pffi.offsetof(cps, "points"), pffi.sizeof(point)]
    expected += [pffi.sizeof(handler)] + [pffi.offsetof(handler, f) for f in ("beginFunc", "preSolveFunc",
                                                                              "separateFunc", "userData")]
    out = ffi.new("long[]", 64)
    got = list(out[0:lib.tm_layout(out, 64)])
    if got != expected:
        raise ImportError(f"Chipmunk's struct layouts differ from the helper's ({got} != {expected})")
    module.state_first = int(plib.CP_ARBITER_STATE_FIRST_COLLISION)

    from_handle = ffi.from_handle

    @ffi.def_extern(name="tm_enumerate")
    def _enumerate(py, k, rows, u0, m_inv, i_inv, scale, out):
        enumerate_modes = from_handle(py)[2]  # (exact.enumerate_modes, given by NativeRun.solve_exactly)
        cons = []
        for i in range(k):
            r = ffi.unpack(rows + 11 * i, 11)
            cons.append([None, tuple(r[0:3]), tuple(r[3:6]), None, None, None, r[6], r[7], r[8], r[9], r[10]])
        x = enumerate_modes(cons, tuple(ffi.unpack(u0, 3)), m_inv, i_inv, scale)
        if x is None:
            return 0
        for i, (jn, jt) in enumerate(x):
            out[2 * i], out[2 * i + 1] = jn, jt
        return 1

    @ffi.def_extern(name="tm_py_begin")
    def _begin(py, arb, ia, ib):
        from_handle(py)[0](ia, ib, arb)

    @ffi.def_extern(name="tm_py_separate")
    def _separate(py, ia, ib):
        from_handle(py)[1](ia, ib)


def load():
    """The helper module (``.ffi``, ``.lib``), or None where it is off or unavailable (:func:`reason` says why)."""
    if _STATE["off"] or os.environ.get("THROWMAP_NATIVE", "1") == "0":
        return None
    if not _STATE["tried"]:
        _STATE["tried"] = True
        try:
            from . import build

            module = build.build()
            _bind(module)
            _STATE["module"] = module
        except (OSError, ImportError, AttributeError, TypeError) as exc:  # no compiler, no cffi, another pymunk
            _STATE["reason"] = f"{type(exc).__name__}: {exc}"
    return _STATE["module"]


def available() -> bool:
    """Whether runs use the C helper."""
    return load() is not None


def reason() -> str | None:
    """Why the C helper is not used (None where it is)."""
    if _STATE["off"] or os.environ.get("THROWMAP_NATIVE", "1") == "0":
        return "turned off (THROWMAP_NATIVE=0 or native.disabled())"
    load()
    return _STATE["reason"]


@contextlib.contextmanager
def disabled():
    """Runs started inside the block use the engine's Python code only."""
    _STATE["off"] += 1
    try:
        yield
    finally:
        _STATE["off"] -= 1


def _ptr(ffi, ctype: str, handle):
    """A pymunk cffi pointer as a pointer of the helper's ffi."""
    from pymunk._chipmunk import ffi as pffi

    return ffi.cast(ctype, int(pffi.cast("uintptr_t", handle)))


class NativeRun:
    """One run's C state (``tm_run``) for world ``w`` (raw Chipmunk handles), and the loop's calls on it.

    ``ptr`` doubles as the run's clock: the collision callbacks read ``ptr.now`` (s) and set ``ptr.stop`` to make
    :meth:`steps` return after the current step. The friction hook is configured by :meth:`set_hook`."""

    __slots__ = ("_probe", "_steps", "enumerate", "ffi", "keep", "lib", "module", "out", "ptr", "rate", "tbuf", "unpack")

    def __init__(self, module, w, settings, box_tol: float):
        """``box_tol``: the margin of the checks' bounding boxes (:data:`..world.BOX_TOL`, m)."""
        from ...rest import EDGE_EPS

        ffi, lib = module.ffi, module.lib
        self.module, self.ffi, self.lib = module, ffi, lib
        r = self.ptr = ffi.gc(lib.tm_new(), lib.tm_free)
        n = len(w.bodies)
        keep = self.keep = []

        def arr(ctype, values):
            a = ffi.new(ctype + "[]", values if len(values) else 1)
            keep.append(a)
            return a

        r.space = _ptr(ffi, "cpSpace *", w.space_h)
        r.arm = _ptr(ffi, "cpBody *", w.arm_h)
        r.n = n
        r.body = arr("cpBody *", [_ptr(ffi, "cpBody *", b) for b in w.bodies_h])
        r.shape = arr("cpShape *", [_ptr(ffi, "cpShape *", s) for s in w.shapes_h])
        r.fell = arr("int", [0] * n)
        verts, vstart, vcount, betas, bstart, bcount = [], [], [], [], [], []
        for i in range(n):
            vstart.append(len(verts) // 2)
            vcount.append(len(w.wlists[i]))
            verts.extend(c for v in w.wlists[i] for c in v)
            bstart.append(len(betas))
            bcount.append(len(w.betas[i]))
            betas.extend(w.betas[i])
        r.verts, r.vstart, r.vcount = arr("double", verts), arr("int", vstart), arr("int", vcount)
        r.betas, r.bstart, r.bcount = arr("double", betas), arr("int", bstart), arr("int", bcount)
        r.R, r.rho2 = arr("double", w.R), arr("double", w.rho2)
        others, ostart, ocount, hasbox, boxes, boxes_tol = [], [], [], [], [], []
        for i in range(n):
            ostart.append(len(others))
            ocount.append(len(w.others_h[i]))
            for s, bx, bt in zip(w.others_h[i], w.boxes[i], w.boxes_tol[i]):
                others.append(_ptr(ffi, "cpShape *", s))
                hasbox.append(bx is not None)
                boxes.extend(bx if bx is not None else (0.0,) * 4)
                boxes_tol.extend(bt if bt is not None else (0.0,) * 4)
        r.others, r.ostart, r.ocount = arr("cpShape *", others), arr("int", ostart), arr("int", ocount)
        r.hasbox, r.boxes, r.boxes_tol = arr("int", [int(b) for b in hasbox]), arr("double", boxes), arr("double", boxes_tol)
        r.corners = arr("double", [c for v in w.corners for c in v])
        r.ncorners = len(w.corners)
        r.hint = arr("int", [-1, 0, 0] * n)
        r.L, r.h, r.back, r.thick, r.margin, r.g = w.L, w.h, w.back, w.thickness, w.margin, w.g
        r.edge_eps, r.box_tol = EDGE_EPS, box_tol
        r.settle_speed, r.settle_spin = settings.settle_speed, settings.settle_spin
        r.plain_arm, r.end_wall, r.arm_thickness = bool(w.plain_arm), bool(w.end_wall), settings.arm_thickness
        r.inv_m = arr("double", [1.0 / b.mass for b in w.bodies])
        r.inv_i = arr("double", [1.0 / b.moment for b in w.bodies])
        r.hook = 0
        self.enumerate = None
        self.out = ffi.new("double[17]")
        self.tbuf = ffi.new("double[1]")
        self.rate = ffi.new("double[1]")
        self.unpack = ffi.unpack
        self._probe, self._steps = lib.tm_probe, lib.tm_steps

    # ------------------------------------------------------------------------------------------------ friction hook
    def set_hook(self, kind: int, cap: float, mu_arm: float, mu_fix: float, fix: int, by_u: bool, u_arm: float,
                 u_fix: float, mu_pp: float = 0.0) -> None:
        """Configure the C friction hook: ``kind`` 1 one part on a bare arm, 2 one part with fixtures, 3 several parts
        (:mod:`..friction`); ``cap`` its CAP; μ of arm, fixture and part pairs (``inf`` allowed); ``fix`` the fixtures'
        collision type; ``by_u``: the arbiter's friction (``u_arm``/``u_fix``) names the pair."""
        r = self.ptr
        r.hook, r.cap, r.mu, r.mu_fix, r.fix, r.by_u = kind, cap, mu_arm, mu_fix, fix, bool(by_u)
        r.u_arm, r.u_fix = u_arm, u_fix
        r.unc_arm = mu_arm if math.isfinite(mu_arm) else 1.0e30
        r.unc_fix = mu_fix if math.isfinite(mu_fix) else 1.0e30
        r.mu_pp, r.unc_pp = mu_pp, (mu_pp if math.isfinite(mu_pp) else 1.0e30)
        r.exact = 0

    def solve_exactly(self, trigger: float, max_sweeps: int, tol: float, same_point: float, mu_skid: float,
                      enumerate_modes) -> None:
        """One part: solve its capped steps exactly (:mod:`..exact`, whose constants these are; ``enumerate_modes``
        is called back for the steps whose sweeps cycle)."""
        r = self.ptr
        r.exact = 1
        r.trigger, r.max_sweeps, r.tol, r.same_point, r.mu_skid = trigger, max_sweeps, tol, same_point, mu_skid
        r.state_first = self.module.state_first
        self.enumerate = enumerate_modes

    def attach(self, space, contacts) -> None:
        """Make the run ``space``'s user data, the C hook its wildcard pre-solve (where :meth:`set_hook` set one) and
        the C begin/separate, which hand the part indices to ``contacts.begin_parts``/``separate_parts``, its
        callbacks; until :meth:`detach`."""
        from pymunk._chipmunk import ffi as pffi

        handler = space._handlers[(None, None)]._handler
        handle = self.ffi.new_handle((contacts.begin_parts, contacts.separate_parts, self.enumerate))
        self.keep.append(handle)
        self.ptr.py = handle
        if self.lib.tm_attach(self.ptr, self.ffi.cast("void *", int(pffi.cast("uintptr_t", handler)))) != 0:
            raise RuntimeError("the engine's C helper could not attach to the space")

    def detach(self) -> None:
        """Give the space its own callbacks back and forget the run (the space may outlive it)."""
        self.lib.tm_detach(self.ptr)

    def contact_point(self, arb, i: int):
        """The first contact point ``(x, y)`` (m, world frame) of raw arbiter ``arb`` on part ``i``, or None."""
        out = self.out
        return (out[0], out[1]) if self.lib.tm_contact_point(self.ptr, arb, i, out) else None

    # ------------------------------------------------------------------------------------------------ the loop
    def steps(self, contacts, t: float, n: int, step: float) -> float:
        """``n`` steps of ``step`` (s) from ``t`` (s) with the arm parked; first impacts recorded after their step."""
        tbuf, run, r = self.tbuf, self._steps, self.ptr
        tbuf[0] = t
        while n > 0:
            n -= run(r, n, step, tbuf)
            if contacts.need_post:
                contacts.record_post(step)
        return tbuf[0]

    def arm_steps(self, w, contacts, t: float, n: int, step: float, angle, alpha: float, arm_stop: float,
                  end_alpha: float) -> float:
        """``n`` steps of ``step`` (s) from ``t`` (s) while the arm moves (α + θ(t), ``angle`` θ) or stops (parked at
        ``end_alpha`` once t ≥ ``arm_stop``), as :func:`..stepping.fixed_steps`; θ is evaluated here, at the same
        times as there, and the steps taken in C. Keeps ``w.arm_w``."""
        ffi, run, r = self.ffi, self.lib.tm_steps_arm, self.ptr
        tbuf, rate = self.tbuf, self.rate
        rate[0] = w.arm_w
        while n > 0:
            angles, tk = [], t
            if tk < arm_stop:  # the block's step times while the arm moves (as the loop of fixed_steps takes them)
                angles.append(alpha + angle(tk))
                for _ in range(n):
                    tk += step
                    angles.append(alpha + angle(tk))
                    if not tk < arm_stop:
                        break
            tbuf[0] = t
            n -= run(r, n, step, tbuf, ffi.new("double[]", angles) if angles else ffi.NULL, arm_stop, end_alpha, rate)
            t = tbuf[0]
            if contacts.need_post:
                contacts.record_post(step)
        w.arm_w = rate[0]
        return t

    def probe(self, i: int, horizon: float = 0.0, flips: bool = False) -> list:
        """Part i's state and checks (:func:`..checks.probe`)."""
        out = self.out
        self._probe(self.ptr, i, horizon, flips, out)
        return self.unpack(out, 17)

    def clearance(self, i: int, enough: float) -> float:
        return self.lib.tm_clearance(self.ptr, i, enough)

    def vertex_speed_bound(self) -> float:
        return self.lib.tm_vertex_speed_bound(self.ptr)

    def leap(self, tau: float, arm_angle: float) -> None:
        self.lib.tm_leap(self.ptr, tau, arm_angle)

    def fell(self, i: int) -> None:
        self.ptr.fell[i] = 1

    @property
    def n_capped(self) -> int:
        return int(self.ptr.n_capped)
