"""Noise models: the draws have the stated distributions, use the trial's stream, and build the stated arm motion."""

import math

import numpy as np
import pytest

from throwmap import Arm
from throwmap.engine import ImpulseThrow, RecoilThrow
from throwmap.errors import InvalidStateError
from throwmap.system.noise import Noise
from throwmap.io.spec import NoiseSpec


def test_omega_jitter_is_relative_gaussian():
    noise = Noise(omega_rel=0.03)
    rng = np.random.default_rng(0)
    w = np.array([noise.omega(4.0, rng) for _ in range(20000)])
    se = 0.03 * 4.0 / math.sqrt(w.size)
    assert abs(w.mean() - 4.0) < 5 * se
    assert w.std() == pytest.approx(0.12, rel=0.03)


def test_quiet_noise_is_exact_but_uses_the_stream_the_same_way():
    a, b = np.random.default_rng(5), np.random.default_rng(5)
    assert Noise().omega(4.0, a) == 4.0 and Noise().mu(0.8, a) == 0.8
    Noise(omega_rel=0.1).omega(4.0, b)
    Noise(mu_rel=0.1).mu(0.8, b)
    assert a.random() == b.random()  # same number of draws whatever σ


def test_mu_spread():
    rng = np.random.default_rng(1)
    lo_hi = Noise(mu_range=(0.3, 1.2))
    mus = [lo_hi.mu(0.8, rng) for _ in range(2000)]
    assert 0.3 <= min(mus) and max(mus) <= 1.2 and np.mean(mus) == pytest.approx(0.75, abs=0.03)
    rel = Noise(mu_rel=0.5)
    assert min(rel.mu(0.8, rng) for _ in range(2000)) >= 0.0
    assert rel.mu(math.inf, rng) == math.inf
    arm = rel.arm(Arm(h=-0.01, length=0.4, mu=0.8), rng)
    assert arm.h == -0.01 and arm.length == 0.4 and arm.mu != 0.8


def test_realisations():
    assert Noise().realisation_for(4.0) == ImpulseThrow(4.0)
    r = Noise(realisation="recoil").realisation_for(4.0)
    assert isinstance(r, RecoilThrow) and r.recoil == pytest.approx(math.radians(3.0))
    # independent check of the profile: its largest arm rate, sampled, is the release rate ω
    t = np.linspace(0.0, r.duration, 200001)
    assert max(r.rate(s) for s in t) == pytest.approx(4.0, rel=1e-4)
    w, real = Noise(omega_rel=0.03, realisation="recoil").throw(4.0, np.random.default_rng(2))
    assert real.peak_rate == pytest.approx(w, rel=1e-12) and w != 4.0


@pytest.mark.parametrize("kw,field", [({"omega_rel": -0.1}, "noise.omega_rel"), ({"mu_range": (1.0, 0.5)}, "noise.mu_range"),
                                      ({"realisation": "finite"}, "noise.realisation"), ({"zeta": 1.0}, "noise.zeta"),
                                      ({"mu_rel": math.nan}, "noise.mu_rel")])
def test_bad_noise_is_refused(kw, field):
    with pytest.raises(InvalidStateError, match=rf"^{field}:"):
        Noise(**kw)


def test_config_builds_the_noise():
    cfg = NoiseSpec(omega_rel=0.03, realisation="recoil", mu_range=(0.5, 1.0))
    assert cfg.noise() == Noise(0.03, 0.0, (0.5, 1.0), "recoil")
    assert cfg.noise().to_dict()["omega_rel"] == 0.03
