"""Chains estimated from throws: invariants, the noiseless map, and the Monte Carlo of the same model."""

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.system.noise import Noise
from throwmap.stochastic import (Cells, GoalSet, ThrowStep, build_chain, build_mixture, compare_curve, mu_nodes,
                                 open_loop_trials)


@pytest.fixture(scope="module")
def setup():
    part = tm.triangle_30_60_90()
    arm = tm.Arm(h=-0.01, length=0.60, mu=1.0)
    return part, arm


def test_cells_cover_the_admissible_starts_and_are_cut_at_breaks(setup):
    part, arm = setup
    cells = Cells.on_arm(part, arm, 0.01, breaks=(0.47, 0.49))
    left, right, side = cells.bounds()
    assert np.all(right > left) and np.all(right - left <= 0.01 + 1e-12)
    for k in part.stable_sides:
        e = cells.edges[cells.sides.index(k)]
        lo, hi = tm.system.starts.start_interval(part, arm, k)
        assert e[0] == lo and e[-1] == hi
        assert 0.47 in e and 0.49 in e
    x, s = cells.centres()
    assert np.array_equal(cells.index(x, s), np.arange(cells.n))
    assert cells.index(-1.0, 0) == -1
    with pytest.raises(InvalidStateError, match="cell"):
        Cells.on_arm(part, arm, 0.0)


@pytest.mark.parametrize("model", ["rigid_body", "paper"])
def test_noiseless_chain_at_cell_centres_is_the_map_of_centres(setup, model):
    part, arm = setup
    cells = Cells.on_arm(part, arm, 0.01)
    b = build_chain(cells, ThrowStep(part, arm, 3.0, model), samples=4, rng=0, within="centre")
    P = b.chain.P
    assert np.allclose(P.sum(axis=1), 1.0)
    assert np.all(np.isin(P, (0.0, 1.0)))              # one unit entry per row: a map on states
    assert b.check["tv_max"] == 0.0                     # halves agree exactly without noise
    x, s = cells.centres()
    for i in range(0, cells.n, 7):                      # the chain's successor = iterate's first throw
        o = tm.iterate(part, arm, (float(x[i]), int(s[i])), 3.0, 1, model=model)
        j = int(np.argmax(P[i]))
        if str(o.status) == "ok":
            assert j == cells.index(o.x[-1], o.side[-1])
        else:
            assert b.chain.labels[j] == str(o.status)


def test_rows_sum_to_one_and_absorption_plus_escape_is_one(setup):
    part, arm = setup
    cells = Cells.on_arm(part, arm, 0.01)
    b = build_chain(cells, ThrowStep(part, arm, 4.5, "rigid_body", Noise(omega_rel=0.03)), samples=8, rng=1)
    assert np.allclose(b.chain.P.sum(axis=1), 1.0, atol=1e-12)
    ab = b.chain.absorption()
    assert np.allclose(ab.B.sum(axis=1) + ab.escape, 1.0, atol=1e-9)
    st = b.chain.stationary()
    assert st.pi.sum() == pytest.approx(1.0)
    assert 0 <= b.check["tv_mean"] <= b.check["tv_max"] <= 1


def test_mu_nodes_are_quantile_midpoints():
    mus, w = mu_nodes(Noise(mu_rel=0.1), 1.0, 4)
    assert w == pytest.approx([0.25] * 4) and np.all(np.diff(mus) > 0) and np.mean(mus) == pytest.approx(1.0)
    assert mu_nodes(Noise(mu_range=(0.5, 1.5)), 1.0, 2)[0] == pytest.approx([0.75, 1.25])
    assert mu_nodes(Noise(), 1.0, 5)[0] == pytest.approx([1.0])


def test_open_loop_chain_lies_in_the_monte_carlo_band(setup):
    """ω = 3 rad/s on rigid_body, 3 % jitter, μ ± 10 % per trial: P(off the end by k) of the chain against
    300 simulated trials (seeded; ≈ 3 s)."""
    part, arm = setup
    goal = GoalSet(label="off_end")
    cells = Cells.on_arm(part, arm, 0.005)
    step = ThrowStep(part, arm, 3.0, "rigid_body", Noise(omega_rel=0.03, mu_rel=0.1))
    init = np.ones(cells.n)
    mix, _ = build_mixture(cells, step, samples=16, rng=0, n_mu=3, initial=init)
    curve = mix.p_goal_by(40, goal.mask(mix.chains[0]), init)
    hits = open_loop_trials(step, cells, init, goal, n=300, k_max=40, rng=1)
    cmp = compare_curve(curve, hits, 40)
    assert cmp.fraction_inside >= 0.8, cmp.summary()
    assert cmp.max_outside < 0.03


def test_the_noise_realisation_reaches_models_that_take_one(setup, monkeypatch):
    """rigid_body rides the noise's recoil arm (a callable ω → realisation, as closed_loop does); 'paper' never
    gets one; the impulse is passed as no realisation (the batched kernel)."""
    import throwmap.throws.session as S

    part, arm = setup
    seen = []
    real = S.MapEnsemble.throw

    def spy(self, omega, motion=None, **kw):  # the motion the step was given; thrown as the impulse (quicker)
        seen.append((self.model.name, motion))
        return real(self, omega, None, **kw)

    monkeypatch.setattr(S.MapEnsemble, "throw", spy)
    x, s = np.array([0.3]), np.array([1])
    rng = np.random.default_rng(0)
    recoil = Noise(realisation="recoil")
    ThrowStep(part, arm, 3.0, "rigid_body", recoil)(x, s, rng)
    ThrowStep(part, arm, 3.0, "paper", recoil)(x, s, rng)
    ThrowStep(part, arm, 3.0, "rigid_body", Noise())(x, s, rng)
    assert seen[0][1] is not None and callable(seen[0][1])
    assert seen[1][1] is None and seen[2][1] is None
