"""Model "paper": the kernel's own trajectory rows (kernels.record, paper.throw_one_traj)."""

import numpy as np
import pytest

import throwmap as tm
from throwmap.kernels import codes as C
from throwmap.kernels.paper import throw_one, throw_one_traj
from throwmap.models.paper import PaperOptions

O = PaperOptions()


def _args(part, arm):
    return (arm.h, arm.g, 0.0, arm.length_or_inf, arm.back, part.radius_of_gyration**2, part.w, part.beta, part.d, part.uL,
            part.uR, part.ell, part.stable, O.tol, O.max_iter, O.max_impacts, O.n_samples)


@pytest.mark.parametrize("x, side, omega", [(0.2, 0, 4.0), (0.34, 1, 4.0), (0.4, 1, 10.0), (0.1225, 0, 10.0)])
def test_recording_changes_nothing_and_overflow_is_counted(triangle, arm, x, side, omega):
    rec0 = np.empty(C.NREC)
    plain = throw_one(x, side, omega, *_args(triangle, arm), rec0)
    rec1 = np.empty(C.NREC)
    big = np.full((5000, 4), np.nan)
    tags = np.zeros(5000, dtype=np.int64)
    xr, kr, sr, rows, dropped = throw_one_traj(x, side, omega, *_args(triangle, arm), rec1, big, tags, 1 / 240)
    assert (xr, kr, sr) == plain and dropped == 0 and rows > 3
    np.testing.assert_array_equal(rec0, rec1)
    assert np.all(np.isnan(big[rows:])) and not np.any(np.isnan(big[:rows]))
    assert np.all(np.diff(big[:rows, 0]) > 0) and big[0, 0] == 0.0
    # a buffer too small: the rows that fit are the same, the rest are counted
    small = np.full((3, 4), np.nan)
    stags = np.zeros(3, dtype=np.int64)
    xs, ks, ss, rows_s, dropped_s = throw_one_traj(x, side, omega, *_args(triangle, arm), rec1, small, stags, 1 / 240)
    assert (xs, ks, ss) == plain
    assert rows_s == 3 and rows_s + dropped_s == rows
    np.testing.assert_array_equal(small, big[:3])
    np.testing.assert_array_equal(stags, tags[:3])


def test_tags_mark_flight_pivot_and_flat_rows(triangle, arm):
    n = triangle.n_sides
    rec = np.empty(C.NREC)
    traj = np.full((5000, 4), np.nan)
    tags = np.zeros(5000, dtype=np.int64)
    x, k, st, rows, _ = throw_one_traj(0.34, 1, 4.0, *_args(triangle, arm), rec, traj, tags, 1 / 240)
    tags = tags[:rows]
    assert tags[0] == n + 1 and tags[-1] == n + k  # flat at the start and at rest
    i_imp = int(np.flatnonzero(traj[:rows, 0] == rec[C.T_FLIGHT])[0])
    assert np.all(tags[1:i_imp] == -1)  # flight
    assert tags[i_imp] == int(rec[C.CONTACT_VERTEX])  # the touching vertex, then pivoting on it
    assert st == tm.Status.OK and traj[rows - 1, 1] == x
