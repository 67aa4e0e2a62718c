"""The guards of a Coulomb contact, shared by every integrated contact mode of model "rigid_body".

A contact pressed with normal force N ≥ 0 and friction F (per unit mass, m/s²) leaves its mode
when one of three guards reaches 0 (Stronge 2000 ch. 2; the single-contact Coulomb law of
:func:`~.slide.select_contact_mode`):

``lift_off``  N / scale                    the normal force vanishes (any mode);
``slip``      (μ N − |F|) / scale           sticking: the friction reaches the cone's edge (finite μ);
``stick``     σ v                          sliding with slip sense σ: the slip velocity v reaches 0.

``scale`` (m/s², gravity's magnitude) makes the force guards comparable with the geometric ones
they are minimised with. Used by PIVOT_SLIDE (:mod:`.slide`), WALL_CONTACT (:mod:`.wall_slide`),
CORNER (:mod:`.wall_corner`) and LADDER (:mod:`.wall_lean`); located inside an integration step by
:func:`~.bracket.locate_guard`.
"""

import math

from numba import njit

from .modes import EV_LIFT_OFF, EV_SLIP, EV_STICK


@njit(cache=True, inline="always")
def cone_guard(N, F, v, stick, sig, mu, scale, watch_stick):
    """The least guard of a Coulomb contact (module docstring) and which it is: ``(value, event)``.

    ``stick``: the contact sticks (guards ``lift_off`` and, for finite ``mu``, ``slip``); else it slides
    with sense ``sig`` at slip velocity ``v`` (m/s; guards ``lift_off`` and, where ``watch_stick``,
    ``stick``: a frictionless face lets its contact slide through v = 0 unwatched). Events
    EV_LIFT_OFF, EV_SLIP, EV_STICK of :mod:`.modes`.
    """
    gmin = N / scale
    which = EV_LIFT_OFF
    if stick:
        if math.isfinite(mu):
            gs = (mu * N - abs(F)) / scale
            if gs < gmin:
                gmin = gs
                which = EV_SLIP
    elif watch_stick and sig * v < gmin:
        gmin = sig * v
        which = EV_STICK
    return gmin, which


@njit(cache=True, inline="always")
def cone_guard_value(which, N, F, v, sig, mu, scale):
    """The value of one guard of :func:`cone_guard` (``which``: EV_LIFT_OFF, EV_SLIP or EV_STICK); nan for another."""
    if which == EV_STICK:
        return sig * v
    if which == EV_LIFT_OFF:
        return N / scale
    if which == EV_SLIP:
        return (mu * N - abs(F)) / scale
    return math.nan
