"""More checks of the "paper" pivot cascade (kernels/roll.py) added by the mutation pass (tools/mutants.py).

Each test names the mutant(s) it kills. The expected values come from an independent
computation (the rest pose rebuilt from the vertices by turning the side's outward
normal straight down, angular momentum about the landing vertex written with 2-D
cross products) or from an invariant (mirror symmetry, the CM does not move when a
part starts to tip from rest), never from copied outputs.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import throwmap as tm
from throwmap.kernels import codes as C
from throwmap.kernels.roll import land_side, roll_to_rest, tip_over

G = 9.81


def _record():
    rec = np.zeros(C.NREC)
    rec[C.N_MIN] = math.inf
    rec[C.K_MAX_IMPACT_GAIN] = -math.inf
    return rec


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _random_parts(seed, count):
    """Uniform plates: convex hulls of 3–6 random points (obtuse triangles and irregular polygons included)."""
    rng = np.random.default_rng(seed)
    parts = []
    while len(parts) < count:
        m = int(rng.integers(3, 7))
        pts = rng.uniform(-0.1, 0.1, size=(m, 2)) * rng.uniform(0.3, 1.0, size=2)  # some long, flat ones
        hull = ConvexHull(pts)  # a fixed seed: no degenerate draw
        v = pts[hull.vertices]
        if len(v) < 3 or hull.volume < 1e-5:
            continue
        # drop nearly collinear corners (the part would be ill-conditioned, not wrong)
        e = np.roll(v, -1, axis=0) - v
        f = np.roll(e, -1, axis=0)
        turn = np.abs(e[:, 0] * f[:, 1] - e[:, 1] * f[:, 0]) / (np.hypot(*e.T) * np.hypot(*f.T))
        if np.min(turn) < 0.05:
            continue
        parts.append(tm.Part.from_vertices(v, mass=1.0))
    return parts


PARTS = _random_parts(20261123, 60)


def _rest_pose(part, k):
    """Body→world rotation (2×2) putting side k (edge w_k → w_{k+1}) flat at the bottom, found independently:
    the side's outward normal (the perpendicular pointing away from the CM) is turned to (0, −1)."""
    w = part.w
    a, b = w[k], w[(k + 1) % len(w)]
    e = b - a
    nrm = np.array([e[1], -e[0]])
    if nrm @ a < 0.0:
        nrm = -nrm
    phi = -0.5 * math.pi - math.atan2(nrm[1], nrm[0])
    c, s = math.cos(phi), math.sin(phi)
    rot = np.array([[c, -s], [s, c]])
    r = w @ rot.T
    # sanity of the pose itself: the side is the bottom, horizontal, with every other vertex above it
    assert abs(r[k, 1] - r[(k + 1) % len(w), 1]) <= 1e-12
    assert np.all(r[:, 1] >= r[k, 1] - 1e-12)
    return rot


def _unstable_sides(which):
    """(part, k) for the unstable sides whose CM lies left (``"left"``: both support vertices right of the CM,
    the part tips over its left vertex) or right (``"right"``) of the side."""
    out = []
    for p in PARTS:
        for k in range(p.n_sides):
            if p.stable[k]:
                continue
            r = p.w @ _rest_pose(p, k).T
            xs = (r[k, 0], r[(k + 1) % p.n_sides, 0])
            if (which == "left" and min(xs) > 1e-9) or (which == "right" and max(xs) < -1e-9):
                out.append((p, k))
    return out


LEFT = _unstable_sides("left")
RIGHT = _unstable_sides("right")


def test_the_random_parts_have_unstable_sides_of_both_kinds():
    assert len(LEFT) >= 10 and len(RIGHT) >= 10


# ---------------------------------------------------------------------------------------- reset tip_over (K28)
@pytest.mark.parametrize("which", ["left", "right"])
def test_tip_over_pivots_on_the_overhung_vertex_where_it_lies(which):
    """K28: flat at rest on an unstable side at CM abscissa x, the part tips over the support vertex nearer the
    CM's vertical; the returned pivot x is that vertex's world x (rest pose rebuilt from the vertices), and the
    CM rebuilt from (pivot x, θ, ℓ_j) is where it was — tipping from rest moves nothing."""
    cases = LEFT if which == "left" else RIGHT
    for i, (p, k) in enumerate(cases):
        n = p.n_sides
        x_cm = -0.3 + 0.05 * i
        r = p.w @ _rest_pose(p, k).T
        d = -r[k, 1]
        cand = (k, (k + 1) % n)
        jv = min(cand, key=lambda q: abs(r[q, 0]))  # the vertex the CM overhangs
        j, px, theta = tip_over(k, x_cm, n, p.d, p.uL, p.uR)
        assert j == jv
        assert px == pytest.approx(x_cm + r[jv, 0], abs=1e-12)
        assert theta == pytest.approx(math.atan2(d, -r[jv, 0]), abs=1e-12)
        ell = math.hypot(*p.w[j])
        assert px + ell * math.cos(theta) == pytest.approx(x_cm, abs=1e-12)
        assert ell * math.sin(theta) == pytest.approx(d, abs=1e-12)


@pytest.mark.parametrize("which", ["left", "right"])
def test_release_at_rest_on_an_unstable_side_does_not_depend_on_the_nominal_pivot(which):
    """K28 through the cascade: a part at rest flat on an unstable side k is the same state whether the cascade
    is started pivoting on w_k (θ = θb) or on w_{k+1} (θ = θa); the pivot never slips, so both end at the
    same x on the same side."""
    cases = LEFT if which == "left" else RIGHT
    for p, k in cases[:12]:
        n = p.n_sides
        x_cm = 0.5
        rho2 = p.radius_of_gyration ** 2
        r = p.w @ _rest_pose(p, k).T
        d = -r[k, 1]
        ends = []
        for j in (k, (k + 1) % n):
            px = x_cm + r[j, 0]
            theta = math.atan2(d, x_cm - px)
            x, side, status = roll_to_rest(j, theta, 0.0, px, -1, rho2, p.d, p.uL, p.uR, p.ell, p.stable, G,
                                           math.inf, 1000, 16, _record(), math.inf)
            assert status == C.OK
            ends.append((x, side))
        assert ends[0][1] == ends[1][1]
        assert ends[0][0] == pytest.approx(ends[1][0], abs=1e-12)


# ---------------------------------------------------------------------------------------- reset land_side (K26)
def _landing_expected(p, j, land_dir, thdot):
    """Independent landing about B: rest pose of the side landed on, angular momentum about B conserved (plastic
    impact), then the edge lifts iff the old pivot A moves up after the impact."""
    n = p.n_sides
    if land_dir > 0:
        k, jb = j, (j + 1) % n
    else:
        k, jb = (j - 1) % n, (j - 1) % n
    r = p.w @ _rest_pose(p, k).T
    A, B = r[j], r[jb]
    c = np.zeros(2)
    rho2 = p.radius_of_gyration ** 2
    v_c = thdot * np.array([-(c - A)[1], (c - A)[0]])  # ω × (c − A)
    L_B = rho2 * thdot + _cross(c - B, v_c)
    w_post = L_B / (rho2 + float((c - B) @ (c - B)))
    v_A_up = w_post * (A - B)[0]  # y-velocity of A for a rotation about B: ω × (A − B)
    return k, jb, w_post, v_A_up > 0.0


@pytest.mark.parametrize("land_dir", [-1, 1])
def test_side_landing_lifts_iff_the_old_pivot_rises(land_dir):
    """K26: after the plastic landing about B the part pivots on B exactly when its old pivot A rises
    (both senses of landing; long flat parts, whose spin reverses and which stay down, included)."""
    seen = set()
    for i, p in enumerate(PARTS):
        n = p.n_sides
        for j in range(n):
            thdot = land_dir * (0.5 + 0.1 * ((i + j) % 7))
            k, jb, w_post, lifts_exp = _landing_expected(p, j, land_dir, thdot)
            rec = _record()
            got = land_side(j, land_dir, thdot, p.radius_of_gyration ** 2, n, p.d, p.uL, p.uR, rec)
            assert got[0] == k and got[3] == jb
            assert got[4] == pytest.approx(w_post, rel=1e-10, abs=1e-12)
            assert got[5] == lifts_exp
            assert rec[C.K_MAX_IMPACT_GAIN] <= 1e-12  # a plastic impact never gains energy
            seen.add(lifts_exp)
    assert seen == {True, False}


def _mirror(p):
    """The mirror image x → −x of part p and the map of its clockwise vertex indices onto the image's."""
    q = tm.Part.from_vertices(np.asarray(p.vertices) * [-1.0, 1.0], mass=p.mass)
    vmap = [int(np.argmin(np.hypot(*(q.w - p.w[j] * [-1.0, 1.0]).T))) for j in range(p.n_sides)]
    assert np.allclose(q.w[vmap], p.w * [-1.0, 1.0], atol=1e-12)
    return q, vmap


def test_pivot_cascade_is_mirror_symmetric():
    """K26 through the cascade: the mirror image of a pivot start (vertex j → its image, θ → π − θ, θ̇ → −θ̇,
    pivot x → −x) ends at the mirror image of the rest state, after as many landings and flips. Each landing
    of one run is a landing in the other sense in the image, so every negative-sense landing (rocking back)
    is checked against its positive-sense image."""
    rng = np.random.default_rng(7)
    n_rocking = 0
    for p in PARTS[:30]:
        q, vmap = _mirror(p)
        n = p.n_sides
        side_map = [vmap[(k + 1) % n] for k in range(n)]  # edge w_k → w_{k+1} becomes w'_{m(k+1)} → w'_{m(k)}
        assert np.allclose(q.uL[side_map], -p.uR) and np.allclose(q.uR[side_map], -p.uL)
        rho2 = p.radius_of_gyration ** 2
        for _ in range(4):
            j = int(rng.integers(n))
            theta = float(rng.uniform(0.3, math.pi - 0.3))
            thdot = float(rng.uniform(-12.0, 12.0))
            px = float(rng.uniform(-0.5, 0.5))
            rec_p, rec_q = _record(), _record()
            x1, k1, s1 = roll_to_rest(j, theta, thdot, px, -1, rho2, p.d, p.uL, p.uR, p.ell, p.stable, G,
                                      math.inf, 1000, 16, rec_p, math.inf)
            x2, k2, s2 = roll_to_rest(vmap[j], math.pi - theta, -thdot, -px, -1, rho2, q.d, q.uL, q.uR, q.ell,
                                      q.stable, G, math.inf, 1000, 16, rec_q, math.inf)
            assert s1 == s2 == C.OK
            assert k2 == side_map[k1]
            assert x2 == pytest.approx(-x1, abs=1e-9)
            assert rec_q[C.N_IMPACTS] == rec_p[C.N_IMPACTS] and rec_q[C.N_FLIPS] == rec_p[C.N_FLIPS]
            n_rocking += rec_p[C.N_IMPACTS] >= 2  # a landing that lifted, then another
    assert n_rocking >= 20
