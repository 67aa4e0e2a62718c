"""Rigid planar parts: a convex polygon with mass properties (paper Sec. III-A, Sec. V).

A :class:`Part` is immutable. Its per-side geometry (d, u_L, v_L, u_R, v_R and
stability, paper Sec. III-A) is computed once at construction, in the body
frame re-ordered and centred as :mod:`throwmap.conventions` states.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidPartError, InvalidStateError, shown, warn_scale
from .geometry import (
    as_finite_array,
    check_convex_polygon,
    clockwise_order,
    point_in_convex_polygon,
    polygon_mass_properties,
    side_table,
)

__all__ = ["Part", "Side", "default_name"]


def default_name(n_vertices: int, plate_mass: float, point_masses=()) -> str:
    """The name of a part built without one: ``"polygon(5 vertices, 50 g)"`` (the plate's
    vertex count and mass, kg shown in g), with its lead weights appended as
    :func:`throwmap.system.catalogue.lead_name` does (``"…+lead(12 g at (9, 1) cm)"``),
    so a figure's title always says which part it shows."""
    name = f"polygon({n_vertices} vertices, {1000 * plate_mass:.4g} g)"
    if not point_masses:
        return name
    items = "; ".join(f"{1000 * m:.4g} g at ({100 * x:.4g}, {100 * y:.4g}) cm" for m, (x, y) in point_masses)
    return f"{name}+lead({items})"


@dataclass(frozen=True, slots=True)
class Side:
    """Rest geometry of one side (paper Sec. III-A), lengths in metres.

    ``d`` is the CM height above the surface, ``(u_L, v_L)`` and ``(u_R, v_R)``
    the vectors from the CM to the left and right support vertices, ``stable``
    whether ``u_L < 0 < u_R``; ``length`` the edge length; ``x_min`` the smallest
    resting x at which the left support vertex is still in front of the joint.
    """

    index: int
    stable: bool
    d: float
    u_L: float
    v_L: float
    u_R: float
    v_R: float
    length: float

    @property
    def x_min(self) -> float:
        return -self.u_L


def _readonly(a) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, slots=True)
class Part:
    """A convex polygonal part (SI units).

    Build with :meth:`from_vertices`; fields are plain tuples so parts compare and hash.

    Attributes
    ----------
    vertices : tuple of (x, y)
        Polygon vertices as given (body frame, either orientation), m.
    mass : float
        Total mass, kg (plate plus point masses).
    com : (x, y)
        Centre of mass in the body frame, m.
    radius_of_gyration : float
        ρ about the CM, m (moment of inertia ``mass * ρ²``).
    point_masses : tuple of (m, (x, y))
        Lead weights included in ``mass``, ``com`` and ρ.
    name : str
        Free label.
    """

    vertices: tuple
    mass: float
    com: tuple
    radius_of_gyration: float
    point_masses: tuple = ()
    name: str = ""
    # derived, computed once (not part of equality)
    w: np.ndarray = field(init=False, repr=False, compare=False)
    beta: np.ndarray = field(init=False, repr=False, compare=False)
    d: np.ndarray = field(init=False, repr=False, compare=False)
    uL: np.ndarray = field(init=False, repr=False, compare=False)
    uR: np.ndarray = field(init=False, repr=False, compare=False)
    length: np.ndarray = field(init=False, repr=False, compare=False)
    ell: np.ndarray = field(init=False, repr=False, compare=False)
    stable: np.ndarray = field(init=False, repr=False, compare=False)
    min_d: float = field(init=False, repr=False, compare=False)
    """min_i d_i over the stable sides, m (bounds the paper's regime of h)."""
    user_index: tuple = field(init=False, repr=False, compare=False)
    """``user_index[j]``: the user's index of clockwise vertex w_j."""

    def __post_init__(self):
        v = as_finite_array(self.vertices, "part.vertices", (None, 2))
        check_convex_polygon(v)
        c = as_finite_array(self.com, "part.com", (2,))
        if not point_in_convex_polygon(v, c, strict=True):
            raise InvalidPartError("part.com", f"centre of mass {tuple(c)} is not strictly inside the polygon")
        if not (math.isfinite(self.mass) and self.mass > 0):
            raise InvalidPartError("part.mass", f"must be a positive finite number, got {self.mass}")
        rho = self.radius_of_gyration
        if not (math.isfinite(rho) and rho > 0):
            raise InvalidPartError("part.radius_of_gyration", f"must be a positive finite number, got {rho}")
        warn_scale("part.vertices", float(np.max(np.abs(v))), "length")
        warn_scale("part.mass", self.mass, "mass")
        idx = clockwise_order(v)
        w = v[idx] - c[None, :]
        tab = side_table(w)
        if not np.any(tab["stable"]):
            raise InvalidPartError("part.com", "the part has no stable side (the CM projects outside every edge)")
        set_ = object.__setattr__
        set_(self, "w", _readonly(w))
        for key in ("beta", "d", "uL", "uR", "length", "ell"):
            set_(self, key, _readonly(tab[key]))
        st = np.array(tab["stable"], dtype=np.bool_)
        st.setflags(write=False)
        set_(self, "stable", st)
        set_(self, "min_d", float(np.min(tab["d"][tab["stable"]])))
        set_(self, "user_index", tuple(int(i) for i in idx))

    def __repr__(self) -> str:
        """One line: name, vertex count, mass (kg), CM (m), ρ (m), lead weights and stable sides."""
        name = f"{self.name!r}, " if self.name else ""
        n_w = len(self.point_masses)
        weights = f", {n_w} lead weight{'s' if n_w != 1 else ''}" if n_w else ""
        stable = ", ".join(str(i) for i in np.flatnonzero(self.stable))
        return (f"Part({name}{len(self.vertices)} vertices, mass {self.mass:.4g} kg, CM ({self.com[0]:.4g}, "
                f"{self.com[1]:.4g}) m, ρ {self.radius_of_gyration:.4g} m{weights}, stable sides {stable})")

    # ------------------------------------------------------------------ build
    @classmethod
    def from_vertices(
        cls,
        vertices,
        mass: float,
        com=None,
        radius_of_gyration: float | None = None,
        point_masses=(),
        name: str | None = None,
    ) -> "Part":
        """Build a part from a convex polygon and its mass properties.

        Explicit ``com``/``radius_of_gyration`` override the computed values.

        Parameters
        ----------
        vertices : (n, 2) array-like, m
            Convex polygon in either orientation. Side 0 is the edge joining the
            first two vertices; sides are numbered clockwise (see conventions).
        mass : float, kg
            Mass of the uniform plate.
        com : (x, y), m, optional
            Centre of mass. Default: that of the uniform plate plus point masses.
        radius_of_gyration : float, m, optional
            ρ about the CM. Default: from the uniform plate plus point masses,
            taken about ``com`` (parallel-axis theorem).
        point_masses : sequence of (m, (x, y))
            Lead weights (kg, m) inside or on the polygon. They add to the total
            mass and move the CM and inertia consistently (the reviewer's question
            in paper Sec. V): no separate CM and inertia can be incompatible.
        name : str, optional
            Free label. Default (None): :func:`default_name`, e.g. ``"polygon(4 vertices, 70 g)"``
            plus the lead weights; an explicit ``""`` stays empty.
        """
        v = as_finite_array(vertices, "part.vertices", (None, 2))
        check_convex_polygon(v)
        try:
            m_plate = float(mass)
        except (TypeError, ValueError):
            raise InvalidPartError("part.mass", f"must be a number, got {shown(mass)}") from None
        if not (math.isfinite(m_plate) and m_plate > 0):
            raise InvalidPartError("part.mass", f"must be a positive finite number, got {mass}")
        area, centroid, j_area = polygon_mass_properties(v)
        pms = []
        for i, pm in enumerate(point_masses):
            fld = f"part.point_masses[{i}]"
            try:
                mi, at = pm
            except (TypeError, ValueError):
                raise InvalidPartError(fld, "must be a pair (mass, (x, y))") from None
            try:
                mi = float(mi)
            except (TypeError, ValueError):
                raise InvalidPartError(fld + ".mass", f"must be a number, got {shown(mi)}") from None
            if not (math.isfinite(mi) and mi > 0):
                raise InvalidPartError(fld + ".mass", f"must be a positive finite number, got {mi}")
            p = as_finite_array(at, fld + ".at", (2,))
            if not point_in_convex_polygon(v, p):
                raise InvalidPartError(fld + ".at", f"point {tuple(p)} is outside the part")
            pms.append((mi, (float(p[0]), float(p[1]))))
        m_tot = m_plate + sum(mi for mi, _ in pms)
        if com is None:
            c = (m_plate * centroid + sum(mi * np.asarray(p) for mi, p in pms)) / m_tot
        else:
            c = as_finite_array(com, "part.com", (2,))
        if radius_of_gyration is None:
            inertia = m_plate / area * j_area + m_plate * float(np.sum((centroid - c) ** 2))
            inertia += sum(mi * float(np.sum((np.asarray(p) - c) ** 2)) for mi, p in pms)
            rho = math.sqrt(inertia / m_tot)
        else:
            try:
                rho = float(radius_of_gyration)
            except (TypeError, ValueError):
                raise InvalidPartError("part.radius_of_gyration", f"must be a number, got {shown(radius_of_gyration)}") from None
        return cls(
            vertices=tuple((float(a), float(b)) for a, b in v),
            mass=m_tot,
            com=(float(c[0]), float(c[1])),
            radius_of_gyration=rho,
            point_masses=tuple(pms),
            name=default_name(len(v), m_plate, pms) if name is None else name,
        )

    # -------------------------------------------------------------- queries
    @property
    def n_sides(self) -> int:
        return len(self.vertices)

    @property
    def stable_sides(self) -> tuple[int, ...]:
        """Indices of the stable sides, ascending."""
        return tuple(int(k) for k in np.flatnonzero(self.stable))

    @property
    def moment_of_inertia(self) -> float:
        """About the CM, kg·m²."""
        return self.mass * self.radius_of_gyration**2

    def side(self, k: int) -> Side:
        """Rest geometry of side ``k``."""
        k = self.check_side(k, require_stable=False)
        d = float(self.d[k])
        return Side(k, bool(self.stable[k]), d, float(self.uL[k]), -d, float(self.uR[k]), -d, float(self.length[k]))

    def check_side(self, side, require_stable: bool = True, field: str = "side") -> int:
        """Validate a side index, returning it as ``int``."""
        if isinstance(side, bool) or not isinstance(side, (int, np.integer)):
            raise InvalidStateError(field, f"must be an integer side index, got {shown(side)}")
        k = int(side)
        if not 0 <= k < self.n_sides:
            raise InvalidStateError(field, f"side {k} does not exist (the part has sides 0..{self.n_sides - 1})")
        if require_stable and not self.stable[k]:
            raise InvalidStateError(
                field, f"side {k} is unstable (the part cannot rest on it); stable sides: {list(self.stable_sides)}"
            )
        return k

    def x_min(self, side: int) -> float:
        """Smallest resting x on ``side`` with the left support vertex in front of the joint, m."""
        return float(-self.uL[self.check_side(side)])

    def vertices_at_rest(self, x: float, side: int, h: float) -> np.ndarray:
        """World coordinates of the vertices (clockwise order) resting at ``(x, side)`` on y = h."""
        k = self.check_side(side, require_stable=False)
        b = float(self.beta[k])
        c, s = math.cos(b), math.sin(b)
        rot = np.array([[c, -s], [s, c]])
        return (self.w @ rot.T) + np.array([x, h + float(self.d[k])])

    def user_vertex(self, j: int) -> int:
        """Index in the user's vertex list of clockwise vertex ``w_j``."""
        return self.user_index[j % self.n_sides]
