"""Design parameters p and how a value of p becomes a throw map (paper Sec. V).

A :class:`DesignSpace` names the parameters that vary (a subset of :data:`PARAMETERS`), their
bounds, their scales, their finite-difference steps and everything that stays fixed: the
bare plate, the arm, the lead weight's mass and place, ω and α. :meth:`DesignSpace.setup`
turns a parameter vector into a :class:`Setup` — the part (plate + weight, built with
``Part.from_vertices(point_masses=…)`` so that CM and inertia follow from one mass
distribution: the reviewer's remark in Sec. V), the arm, ω and the throw options.

=============  =====  ==============================================================
name           unit   meaning
=============  =====  ==============================================================
weight_x       m      lead weight's x in the frame of the plate's vertices
weight_y       m      lead weight's y in that frame
weight_mass    kg     lead weight's mass (0: no weight)
omega          rad/s  release rate ω
h              m      arm surface height h at rest
alpha          rad    arm rest angle α (passed to the model as ``alpha=``)
com_x, com_y   m      the draft's parameters: the CM placed directly with the plate's ρ
                      kept (not a physical part in general; :func:`draft_example` only)
=============  =====  ==============================================================

Bounds: the weight's centre stays in the plate shrunk by ``margin`` (default 8 mm, a lead disc
of that radius stays on the plate; :mod:`throwmap.design.plate`), ``weight_mass`` in
[0, 0.5] kg, ω in [1, 15] rad/s, h in [−0.05, 0] m, α in [−15°, 15°]; every bound can be set.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidPartError, InvalidStateError, shown
from ..system.starts import check_omega
from ..system.arm import Arm
from ..system.part import Part
from .plate import InsetPolygon, inset_polygon

__all__ = ["PARAMETERS", "DEFAULT_BOUNDS", "DEFAULT_SCALES", "DEFAULT_STEPS", "DesignSpace", "Setup"]

PARAMETERS = ("weight_x", "weight_y", "weight_mass", "omega", "h", "alpha", "com_x", "com_y")

DEFAULT_BOUNDS = {"weight_mass": (0.0, 0.5), "omega": (1.0, 15.0), "h": (-0.05, 0.0),
                  "alpha": (-math.radians(15.0), math.radians(15.0))}
"""Box bounds per parameter (SI); the weight's and the CM's place are bounded by the inset plate."""

DEFAULT_SCALES = {"weight_x": 0.01, "weight_y": 0.01, "weight_mass": 0.01, "omega": 1.0, "h": 0.01,
                  "alpha": math.radians(1.0), "com_x": 0.01, "com_y": 0.01}
"""Typical size of each parameter (1 cm, 10 g, 1 rad/s, 1°): the solver works in p / scale and the
Jacobian's rank and condition number are reported in these units."""

DEFAULT_STEPS = {"weight_x": 5e-4, "weight_y": 5e-4, "weight_mass": 1e-3, "omega": 5e-3, "h": 2e-4,
                 "alpha": math.radians(0.05), "com_x": 5e-4, "com_y": 5e-4}
"""Central-difference half-steps (0.5 mm, 1 g, 0.005 rad/s, 0.2 mm, 0.05°). r_i moves by
O(1)–O(10) × the step in the canonical cases (≥ 0.2 mm), far above the 0.1 µm to which r_i is found:
the noise in a derivative is ≤ xtol / step ≈ 2·10⁻⁴ of it, the truncation error O(step²)."""


@dataclass(frozen=True, slots=True)
class Setup:
    """One design point: the part (plate + weight), arm, ω and throw options it gives."""

    part: Part
    arm: Arm
    omega: float
    throw_options: dict
    values: dict


@dataclass(frozen=True, slots=True, eq=False)
class DesignSpace:
    """What varies (``vary``), from where (``start``), within which bounds; everything else fixed.

    Attributes
    ----------
    plate : Part
        The bare plate (its vertices, mass, CM and ρ); a part given with lead weights keeps them
        as fixed mass and the designed weight is added.
    arm : Arm
    start : dict
        Every parameter's starting (or fixed) value, SI; ``weight_x``/``weight_y``/``weight_mass``
        /``omega``/``h`` always present, ``alpha`` None when the model is not asked for tilt.
    vary : tuple of str
        The varied parameters, in the order of p.
    bounds : dict
        name → (lo, hi) for the box-bounded ones.
    margin : float
        The weight's centre stays this far inside every edge of the plate, m.
    scales, steps : dict
        See :data:`DEFAULT_SCALES`, :data:`DEFAULT_STEPS`.
    """

    plate: Part
    arm: Arm
    start: dict
    vary: tuple
    bounds: dict
    margin: float
    scales: dict
    steps: dict
    region: InsetPolygon = field(init=False, repr=False)

    def __post_init__(self):
        if not isinstance(self.plate, Part):
            raise InvalidStateError("part", f"must be a Part, got {type(self.plate).__name__}")
        if not isinstance(self.arm, Arm):
            raise InvalidStateError("arm", f"must be an Arm, got {type(self.arm).__name__}")
        vary = self.vary
        if isinstance(vary, str):
            vary = (vary,)
        vary = tuple(vary)
        if not vary:
            raise InvalidStateError("vary", "name at least one parameter to vary")
        for v in vary:
            if v not in PARAMETERS:
                raise InvalidStateError("vary", f"unknown parameter {shown(v)} (choose from {', '.join(PARAMETERS)})")
        if len(set(vary)) != len(vary):
            raise InvalidStateError("vary", f"a parameter is named twice: {list(vary)}")
        if ({"com_x", "com_y"} & set(vary)) and ({"weight_x", "weight_y", "weight_mass"} & set(vary)):
            raise InvalidStateError("vary", "com_x/com_y (the CM placed directly) and the weight's parameters exclude "
                                            "each other")
        object.__setattr__(self, "vary", vary)
        try:
            region = inset_polygon(self.plate.vertices, self.margin)
        except InvalidPartError as err:
            raise InvalidStateError("margin", err.reason) from None
        object.__setattr__(self, "region", region)
        b = dict(DEFAULT_BOUNDS)
        b.update(self.bounds or {})
        for k, (lo, hi) in b.items():
            if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
                raise InvalidStateError(f"bounds.{k}", f"need finite lo ≤ hi, got ({lo}, {hi})")
        object.__setattr__(self, "bounds", b)
        st = dict(self.start)
        for k in ("weight_x", "weight_y", "weight_mass", "omega"):
            v = st.get(k)
            if v is None or not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
                raise InvalidStateError(k if k != "weight_x" and k != "weight_y" else "weight_at",
                                        f"must be a finite number, got {shown(v)}")
        if st["weight_mass"] < 0:
            raise InvalidStateError("weight_mass", f"must be ≥ 0 kg, got {st['weight_mass']}")
        check_omega(st["omega"])
        st.setdefault("h", self.arm.h)
        st.setdefault("alpha", None)
        if "alpha" in vary and st["alpha"] is None:
            st["alpha"] = 0.0
        if not region.contains((st["weight_x"], st["weight_y"])):
            raise InvalidStateError("weight_at", f"({st['weight_x']:.6g}, {st['weight_y']:.6g}) m is not inside the "
                                                 f"plate with a margin of {self.margin:g} m")
        for k in vary:
            if k in b:
                lo, hi = b[k]
                if not lo <= st[k] <= hi:
                    raise InvalidStateError(k, f"start {st[k]:.6g} is outside its bounds [{lo:.6g}, {hi:.6g}]")
        if "com_x" in vary or "com_y" in vary:
            st.setdefault("com_x", self.plate.com[0])
            st.setdefault("com_y", self.plate.com[1])
        object.__setattr__(self, "start", st)
        sc = dict(DEFAULT_SCALES)
        sc.update(self.scales or {})
        object.__setattr__(self, "scales", sc)
        sp = dict(DEFAULT_STEPS)
        sp.update(self.steps or {})
        for k in vary:
            if not (math.isfinite(sp[k]) and sp[k] > 0):
                raise InvalidStateError(f"steps.{k}", f"must be a positive number, got {sp[k]}")
        object.__setattr__(self, "steps", sp)

    # ----------------------------------------------------------------- vectors
    @property
    def p0(self) -> np.ndarray:
        return np.array([self.start[k] for k in self.vary], dtype=float)

    @property
    def scale(self) -> np.ndarray:
        return np.array([self.scales[k] for k in self.vary], dtype=float)

    @property
    def step(self) -> np.ndarray:
        return np.array([self.steps[k] for k in self.vary], dtype=float)

    def values(self, p) -> dict:
        """Every parameter's value at p (varied ones from p, the rest from ``start``)."""
        v = dict(self.start)
        v.update({k: float(x) for k, x in zip(self.vary, np.asarray(p, dtype=float))})
        return v

    def project(self, p) -> tuple[np.ndarray, tuple]:
        """p moved into the bounds; returns (p', names of the bounds that were active)."""
        p = np.array(p, dtype=float)
        hit = []
        for j, k in enumerate(self.vary):
            if k in self.bounds:
                lo, hi = self.bounds[k]
                q = min(hi, max(lo, p[j]))
                if q != p[j]:
                    hit.append(f"{k} {'≥' if q == lo else '≤'} {q:.6g}")
                p[j] = q
        for a, b, label in (("weight_x", "weight_y", "the weight"), ("com_x", "com_y", "the CM")):
            if a in self.vary or b in self.vary:
                v = self.values(p)
                pt = (v[a], v[b])
                q = self.region.project(pt, (a in self.vary, b in self.vary))
                if np.hypot(q[0] - pt[0], q[1] - pt[1]) > 0:
                    hit.append(f"{label} on the plate's edge less {self.margin * 1000:g} mm")
                for j, k in enumerate(self.vary):
                    if k == a:
                        p[j] = q[0]
                    elif k == b:
                        p[j] = q[1]
        return p, tuple(hit)

    def setup(self, p) -> Setup:
        """The part, arm, ω and throw options at p."""
        v = self.values(p)
        plate = self.plate
        if "com_x" in self.vary or "com_y" in self.vary:
            part = Part.from_vertices(plate.vertices, mass=plate.mass, com=(v["com_x"], v["com_y"]),
                                      radius_of_gyration=plate.radius_of_gyration, point_masses=plate.point_masses,
                                      name=f"{plate.name or 'plate'} with its CM moved to ({100 * v['com_x']:.3g}, "
                                           f"{100 * v['com_y']:.3g}) cm, ρ kept")
        else:
            pms = tuple(plate.point_masses)
            base_mass = plate.mass - sum(m for m, _ in pms)
            if v["weight_mass"] > 0:
                pms = pms + ((v["weight_mass"], (v["weight_x"], v["weight_y"])),)
            part = Part.from_vertices(plate.vertices, mass=base_mass, point_masses=pms,
                                      name=_weighted_name(plate.name, v) if v["weight_mass"] > 0 else plate.name)
        arm = self.arm if v["h"] == self.arm.h else dataclasses.replace(self.arm, h=v["h"])
        opts = {} if v.get("alpha") is None else {"alpha": float(v["alpha"])}
        return Setup(part=part, arm=arm, omega=float(v["omega"]), throw_options=opts, values=v)


def _weighted_name(name: str, v: dict) -> str:
    base = (name or "plate").split("+lead(")[0]
    return (f"{base}+lead({1000 * v['weight_mass']:.4g} g at ({100 * v['weight_x']:.4g}, "
            f"{100 * v['weight_y']:.4g}) cm)")
