"""The per-throw record row every kernel fills (layout: :mod:`throwmap.kernels.codes`).

:func:`start_record` sets a row to its state before release (counters 0, extrema at
their identities, no contact yet); :func:`mark_invalid` writes the row of a batch
entry whose start was refused (status INVALID_START, the start kept, the record nan).
"""

import math

from numba import njit

from . import codes as C


@njit(cache=True, inline="always")
def start_record(rec):
    """A record before release: every entry 0, smallest normal force +inf, largest impact
    energy gain −inf, T_REST nan (not yet at rest), contact vertex −1 (none yet)."""
    for i in range(C.NREC):
        rec[i] = 0.0
    rec[C.N_MIN] = math.inf
    rec[C.T_REST] = math.nan
    rec[C.K_MAX_IMPACT_GAIN] = -math.inf
    rec[C.CONTACT_VERTEX] = -1.0


@njit(cache=True, inline="always")
def mark_invalid(i, x0, side, x_out, side_out, status_out, rec_out):
    """Batch entry ``i`` was not thrown: its start stays, status INVALID_START, record nan."""
    x_out[i] = x0[i]
    side_out[i] = side[i]
    status_out[i] = C.INVALID_START
    for q in range(C.NREC):
        rec_out[i, q] = math.nan
