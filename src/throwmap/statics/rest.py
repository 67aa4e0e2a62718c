"""Can planar parts rest as placed? Coulomb statics as a linear program (paper Sec. VI, Figs. 13, 14).

Parts touch the arm, the end wall and each other at point contacts (:class:`Contact`). At contact c
the force on body ``a`` is f_n n + f_t t (n the unit normal pushing into ``a``, t = n rotated by −90°),
and body ``b`` (another part) receives the opposite force. A configuration can rest iff forces exist
with, per contact,

    f_n ≥ 0,    |f_t| ≤ μ_c f_n    (μ_c = 0: f_t = 0;  μ_c = ∞: f_t free),

and, per body, Newton–Euler statics under gravity g(−sin α, −cos α) in the arm frame (α the arm's
rest angle, CCW +): Σ F + m g = 0 and Σ (p − c) × F = 0 about its CM c. In the plane the cone
|f_t| ≤ μ f_n is exactly two linear inequalities (f_t = f⁺ − f⁻, f⁺ + f⁻ ≤ μ f_n, f± ≥ 0), so
feasibility is a linear program (SciPy's HiGHS) — no linearisation of the cone.

Reported (:class:`RestAnalysis`): ``can_rest``; ``mu_needed``, the least friction coefficient that,
given to every contact with friction (frictionless ones stay frictionless), lets the configuration
rest (bisection on LP feasibility: the friction a configuration *needs*, Fig. 14's question);
the contact forces of one solution; per force its range over all admissible solutions (min/max LPs)
and whether it is unique (range below ``tol_unique`` of the weight) — statically indeterminate
contacts (e.g. a part flat on the arm, two supports, friction) have ranges, not values.

Units: N, m, kg, rad; arm frame (x along the arm from the joint, y up from it, surface y = h).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..conventions import G
from ..errors import InvalidStateError, ThrowmapError, shown
from ..models._checks import positive_float
from ..system.system import check_alpha

__all__ = ["Body", "Contact", "RestAnalysis", "analyse_rest", "gravity_arm_frame", "least_mu"]


def gravity_arm_frame(alpha: float, g: float = G) -> np.ndarray:
    """Gravity (m/s²) in the frame of an arm at rest angle ``alpha`` (rad, CCW +): g(−sin α, −cos α)."""
    return np.array([-g * math.sin(alpha), -g * math.cos(alpha)])


@dataclass(frozen=True)
class Body:
    """A part placed in the arm frame: CM at ``(x, y)`` (m), turned by ``phi`` (rad, CCW) from the part's
    centred body frame (``part.w``: vertices relative to the CM)."""

    part: object
    x: float
    y: float
    phi: float = 0.0

    def __post_init__(self):
        if not hasattr(self.part, "w"):
            raise InvalidStateError("body.part", f"must be a Part, got {type(self.part).__name__}")
        for name in ("x", "y", "phi"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.floating)) or not math.isfinite(v):
                raise InvalidStateError(f"body.{name}", f"must be a finite number (m, m, rad), got {shown(v)}")
            object.__setattr__(self, name, float(v))

    def vertices(self) -> np.ndarray:
        """World (arm-frame) vertices, m, in the part's centred order."""
        c, s = math.cos(self.phi), math.sin(self.phi)
        w = np.asarray(self.part.w, dtype=float)
        return np.column_stack([self.x + c * w[:, 0] - s * w[:, 1], self.y + s * w[:, 0] + c * w[:, 1]])

    @property
    def com(self) -> np.ndarray:
        return np.array([self.x, self.y])


@dataclass(frozen=True)
class Contact:
    """A point contact: force on body ``a`` = f_n ``normal`` + f_t t at ``point`` (m); ``b`` the other body's
    index, or None for the environment (arm, wall); ``mu`` its Coulomb coefficient (0, finite or ∞);
    ``label`` says what touches (``"arm"``, ``"wall"``, ``"corner"``, ``"part"``)."""

    a: int
    b: int | None
    point: tuple
    normal: tuple
    mu: float
    label: str = ""

    def __post_init__(self):
        n = np.asarray(self.normal, dtype=float)
        norm = float(np.hypot(*n))
        if not (norm > 0 and math.isfinite(norm)):
            raise InvalidStateError("contact.normal", f"must be a nonzero finite vector, got {shown(self.normal)}")
        object.__setattr__(self, "normal", (float(n[0] / norm), float(n[1] / norm)))
        try:
            px, py = (float(self.point[0]), float(self.point[1]))
        except (TypeError, ValueError, IndexError):
            raise InvalidStateError("contact.point", f"must be a point (x, y) in m, got {shown(self.point)}") from None
        if not (math.isfinite(px) and math.isfinite(py)):
            raise InvalidStateError("contact.point", f"must be finite, got {shown(self.point)}")
        object.__setattr__(self, "point", (px, py))
        if self.b is not None and self.b == self.a:
            raise InvalidStateError("contact.b", f"a contact is between two bodies: body {self.a} with itself")
        mu = self.mu
        if isinstance(mu, bool) or not isinstance(mu, (int, float)) or math.isnan(mu) or mu < 0:
            raise InvalidStateError("contact.mu", f"must be a number ≥ 0 (inf: no slip), got {shown(mu)}")
        object.__setattr__(self, "mu", float(mu))

    @property
    def tangent(self) -> tuple:
        nx, ny = self.normal
        return (ny, -nx)


@dataclass(frozen=True, slots=True)
class RestAnalysis:
    """The answer of :func:`analyse_rest` (see the module docstring). ``forces`` and ``ranges`` per contact:
    ``(f_n, f_t)`` in N and ``((f_n min, max), (f_t min, max))``; ``unique`` per contact; ``weight`` the
    parts' total weight (N); ``mu_needed`` dimensionless (0 when frictionless contacts suffice, inf when
    no friction does)."""

    can_rest: bool
    mu_needed: float
    contacts: tuple
    forces: tuple
    ranges: tuple
    unique: tuple
    weight: float
    message: str = ""

    def __repr__(self) -> str:
        """One line: whether it rests, the friction it needs, the contacts and the weight (:meth:`table`: the forces)."""
        verdict = "rests" if self.can_rest else "cannot rest"
        msg = f"; {self.message}" if self.message else ""
        return (f"RestAnalysis({verdict}, μ needed {self.mu_needed:.4g}, {len(self.contacts)} contacts, "
                f"weight {self.weight:.4g} N{msg})")

    def table(self) -> str:
        rows = ["| contact | on body | with | point (m) | μ | f_n (N) | f_t (N) | f_n range (N) | f_t range (N) |",
                "|---|---|---|---|---|---|---|---|---|"]
        for i, c in enumerate(self.contacts):
            f = self.forces[i] if self.forces else (math.nan, math.nan)
            r = self.ranges[i] if self.ranges else ((math.nan,) * 2,) * 2
            rows.append(f"| {i} {c.label} | {c.a} | {'env' if c.b is None else c.b} | ({c.point[0]:.4f}, "
                        f"{c.point[1]:.4f}) | {c.mu:g} | {f[0]:.4g} | {f[1]:.4g} | [{r[0][0]:.4g}, {r[0][1]:.4g}] | "
                        f"[{r[1][0]:.4g}, {r[1][1]:.4g}] |")
        return "\n".join(rows)

    def to_dict(self) -> dict:
        """JSON-ready (:func:`throwmap.serial.json_ready`: inf and nan as null): ``can_rest``, ``mu_needed``,
        ``weight_n``, ``message`` and per contact its ``a``, ``b``, ``point_m``, ``normal``, ``mu``, ``label``,
        ``force_n`` (f_n, f_t), ``range_n`` ((f_n min, max), (f_t min, max)) and ``unique``."""
        from ..serial import json_ready

        contacts = []
        for i, c in enumerate(self.contacts):
            contacts.append({"a": c.a, "b": c.b, "point_m": c.point, "normal": c.normal, "mu": c.mu, "label": c.label,
                             "force_n": self.forces[i] if self.forces else None,
                             "range_n": self.ranges[i] if self.ranges else None,
                             "unique": self.unique[i] if self.unique else None})
        return json_ready({"can_rest": bool(self.can_rest), "mu_needed": self.mu_needed, "weight_n": self.weight,
                           "message": self.message, "contacts": contacts})

    def plot(self, ax=None):
        """The contact forces (f_n, f_t per contact, in units of the weight) with their admissible ranges
        (:func:`throwmap.viz.statics.plot_rest_forces`)."""
        from ..viz.statics import plot_rest_forces

        return plot_rest_forces(self, ax=ax)


def _system(bodies, contacts, gvec):
    """Equality rows A x = b of the statics (3 per body) over x = (f_n, f⁺, f⁻) per contact."""
    nb, nc = len(bodies), len(contacts)
    A = np.zeros((3 * nb, 3 * nc))
    b = np.zeros(3 * nb)
    for i, body in enumerate(bodies):
        m = float(body.part.mass)
        b[3 * i:3 * i + 2] = -m * gvec  # Σ F = −m g
    for j, c in enumerate(contacts):
        n = np.array(c.normal)
        t = np.array(c.tangent)
        for body_i, sign in ((c.a, 1.0), (c.b, -1.0)):
            if body_i is None:
                continue
            r = np.array(c.point) - bodies[body_i].com
            for col, d in ((3 * j, n), (3 * j + 1, t), (3 * j + 2, -t)):
                A[3 * body_i, col] += sign * d[0]
                A[3 * body_i + 1, col] += sign * d[1]
                A[3 * body_i + 2, col] += sign * (r[0] * d[1] - r[1] * d[0])
    return A, b


def _cones(contacts, scale):
    """Inequality rows G x ≤ 0: f⁺ + f⁻ − μ f_n ≤ 0 (μ ← ``scale`` for every contact with friction, or
    each contact's own μ when ``scale`` is None), and the bounds (μ = 0: f± = 0)."""
    rows, bounds = [], []
    nc = len(contacts)
    for j, c in enumerate(contacts):
        mu = c.mu if scale is None else (scale if c.mu > 0 else 0.0)
        bounds += [(0, None), (0, None) if mu > 0 else (0, 0), (0, None) if mu > 0 else (0, 0)]
        if 0 < mu < math.inf:
            row = np.zeros(3 * nc)
            row[3 * j], row[3 * j + 1], row[3 * j + 2] = -mu, 1.0, 1.0
            rows.append(row)
    G_ = np.array(rows) if rows else np.zeros((0, 3 * nc))
    return G_, bounds


def _lp(c, A, b, G_, bounds):
    from scipy.optimize import linprog

    res = linprog(c, A_ub=G_ if len(G_) else None, b_ub=np.zeros(len(G_)) if len(G_) else None, A_eq=A, b_eq=b,
                  bounds=bounds, method="highs")
    return res


def _feasible(A, b, contacts, scale) -> bool:
    G_, bounds = _cones(contacts, scale)
    return _lp(np.zeros(A.shape[1]), A, b, G_, bounds).status == 0


def analyse_rest(bodies, contacts, *, alpha: float = 0.0, g: float = G, tol_unique: float = 1e-7,
                 detail: bool = True) -> RestAnalysis:
    """Whether ``bodies`` (a sequence of :class:`Body`) can rest with ``contacts`` on an arm at rest angle
    ``alpha`` (rad), and with which forces (see the module docstring). ``tol_unique``: a force whose
    range is below this share of the total weight is unique. ``detail=False`` answers ``can_rest`` alone
    (one LP; ``mu_needed`` nan, no forces)."""
    bodies = tuple(bodies)
    contacts = tuple(contacts)
    alpha = check_alpha(alpha, "alpha")
    g = positive_float(g, "g")
    if not bodies:
        raise InvalidStateError("bodies", "give at least one Body")
    for c in contacts:
        for idx in (c.a, c.b):
            if idx is not None and not (0 <= idx < len(bodies)):
                raise InvalidStateError("contact", f"body index {idx} is not one of the {len(bodies)} bodies")
    gvec = gravity_arm_frame(float(alpha), float(g))
    weight = float(sum(bd.part.mass for bd in bodies)) * float(g)
    A, b = _system(bodies, contacts, gvec)
    if not contacts:
        return RestAnalysis(False, math.inf, (), (), (), (), weight, "no contact: the parts fall")
    can = _feasible(A, b, contacts, None)
    if not detail:
        return RestAnalysis(can, math.nan, contacts, (), (), (), weight)
    need = _mu_needed(A, b, contacts)
    if not can:
        why = (f"no admissible contact forces: it needs μ ≥ {need:.4g} at every contact with friction"
               if math.isfinite(need) else "no contact forces hold it, whatever the friction of the contacts that have "
                                            "friction (frictionless ones stay frictionless)")
        return RestAnalysis(False, need, contacts, (), (), (), weight, why)
    G_, bounds = _cones(contacts, None)
    sol = _lp(np.zeros(A.shape[1]), A, b, G_, bounds).x
    forces = tuple((float(sol[3 * j]), float(sol[3 * j + 1] - sol[3 * j + 2])) for j in range(len(contacts)))
    ranges, unique = [], []
    for j in range(len(contacts)):
        rng = []
        for vec in (_unit(A.shape[1], 3 * j), _unit(A.shape[1], 3 * j + 1) - _unit(A.shape[1], 3 * j + 2)):
            lo = _lp(vec, A, b, G_, bounds)
            hi = _lp(-vec, A, b, G_, bounds)
            rng.append((float(lo.fun) if lo.status == 0 else -math.inf, float(-hi.fun) if hi.status == 0 else math.inf))
        ranges.append(tuple(rng))
        unique.append(all(r[1] - r[0] <= tol_unique * weight for r in rng))
    return RestAnalysis(True, need, contacts, forces, tuple(ranges), tuple(unique), weight)


def _unit(n: int, i: int) -> np.ndarray:
    e = np.zeros(n)
    e[i] = 1.0
    return e


MAX_BISECTIONS = 200
"""Cap on :func:`least_mu`'s bisection steps: a monotone predicate needs ≈ 34 for ``rel`` = 1e-10 from μ* ≥ 1/2,
and one more per halving below (μ* down to ≈ 1e-50 fits)."""


def least_mu(ok, *, rel: float = 1e-10, cap: float = 1e9) -> float:
    """The least μ ≥ 0 with ``ok(μ)`` for a predicate that holds above some μ* (0 if ``ok(0)``, inf if not even
    ``ok(inf)``): doubling from 1 (up to ``cap``: inf beyond), then bisection to ``rel`` (relative). At most :data:`MAX_BISECTIONS` steps: a predicate that does not settle by then
    (not monotone in μ) is refused with :class:`~throwmap.errors.ThrowmapError`, never looped on."""
    if ok(0.0):
        return 0.0
    if not ok(math.inf):
        return math.inf
    lo, hi = 0.0, 1.0
    while not ok(hi):
        lo, hi = hi, 2 * hi
        if hi > cap:
            return math.inf
    steps = 0
    while hi - lo > rel * hi:
        steps += 1
        if steps > MAX_BISECTIONS:
            raise ThrowmapError("least_mu", f"no μ* found in {MAX_BISECTIONS} bisections (between {lo:.6g} and "
                                            f"{hi:.6g}): the rest test is not monotone in μ")
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    return hi


def _mu_needed(A, b, contacts) -> float:
    """The least μ that, given to every contact with friction, admits rest (:func:`least_mu`; inf if none does)."""
    if not any(c.mu > 0 for c in contacts):
        return 0.0 if _feasible(A, b, contacts, 0.0) else math.inf
    return least_mu(lambda mu: _feasible(A, b, contacts, mu))
