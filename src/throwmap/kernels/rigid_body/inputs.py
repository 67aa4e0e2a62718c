"""The records the "rigid_body" kernels take: the part, the arm and the run's limits, each built once.

Numba accepts a named tuple of scalars and arrays as one argument (a heterogeneous ``NamedTuple`` type); a field
read compiles to the plain value. The model layer (:mod:`throwmap.models.rigid_body`) builds the three records from
its :class:`~throwmap.system.part.Part`, :class:`~throwmap.system.arm.Arm`, rest angle, fixtures and options; the
kernels read them and pass them on instead of a long list of positional arguments.

``PartArrays``  ρ² (m², radius of gyration squared), the vertices ``w`` (n, 2) about the CM (m), the sides' angles
                ``beta`` (rad), heights ``d`` (m), support offsets ``uL``, ``uR`` (m), vertex distances ``ell``
                (m) and the stable-side table ``stable`` at the arm's rest angle (:func:`~.tilt.tilted_stable`).
``ArmArrays``   the arm line's height ``h`` (m), gravity's magnitude ``g`` (m/s²), the rest angle ``alpha`` (rad),
                ``length`` (m; inf: unbounded), ``back`` (m), Coulomb ``mu`` (inf: no slip), the impact law's
                code ``law`` (:data:`~.impact.LAW_ROUTH`, :data:`~.impact.LAW_VELOCITY`), the end wall's height
                ``wall_h`` (m; 0: no wall) and its ``wall_mu``.
``RunLimits``   the contact search's relative tolerance ``tol``, ``max_iter`` steps per mode, ``max_events`` mode
                changes per throw.
"""

from collections import namedtuple

import numpy as np

PartArrays = namedtuple("PartArrays", ("rho2", "w", "beta", "d", "uL", "uR", "ell", "stable"))
ArmArrays = namedtuple("ArmArrays", ("h", "g", "alpha", "length", "back", "mu", "law", "wall_h", "wall_mu"))
RunLimits = namedtuple("RunLimits", ("tol", "max_iter", "max_events"))


def part_arrays(part, stable=None) -> PartArrays:
    """The kernels' record of ``part`` (:class:`~throwmap.system.part.Part`) with the stable-side table ``stable``
    (``part.stable`` where None: the arm at α = 0)."""
    return PartArrays(float(part.radius_of_gyration ** 2), part.w, part.beta, part.d, part.uL, part.uR, part.ell,
                      part.stable if stable is None else stable)


def arm_arrays(h, g, alpha, length, back, mu, law, wall_h=0.0, wall_mu=0.0) -> ArmArrays:
    """The kernels' record of the arm (SI units; ``law`` an int code): every scalar as the kernels type it."""
    return ArmArrays(float(h), float(g), float(alpha), float(length), float(back), float(mu), int(law), float(wall_h),
                     float(wall_mu))


def arm_record(arm, alpha, law, wall_h=0.0, wall_mu=0.0) -> ArmArrays:
    """:func:`arm_arrays` of an :class:`~throwmap.system.arm.Arm` at rest angle ``alpha`` (rad)."""
    return arm_arrays(arm.h, arm.g, alpha, arm.length_or_inf, arm.back, arm.mu, law, wall_h, wall_mu)


def run_limits(tol, max_iter, max_events) -> RunLimits:
    """The kernels' record of the run's limits (``tol`` relative; the caps as ints)."""
    return RunLimits(float(tol), int(max_iter), int(max_events))


def no_traj():
    """The empty trajectory buffer of a throw that records none."""
    return np.empty((0, 4))
