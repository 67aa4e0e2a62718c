"""The oracle's rules, without running the engine: the finer reruns halve the coarse step with the fine one, and a
batch throw is compared only where both the engine and the exact model ended (ok, off_end, behind_joint)."""

from types import SimpleNamespace

import numpy as np

from throwmap.engine import EngineSettings
from throwmap.kernels import codes as C
from throwmap.models.base import BatchArrays
from throwmap.models.engine import EngineModel, EngineOptions
from throwmap.models.engine_oracle import settle_disagreement


def test_the_reruns_halve_and_quarter_both_steps():
    s = EngineSettings()
    assert s.coarse_dt > s.dt  # the defaults: the coarse step is the larger one
    asked = []

    def rerun(dt, coarse_dt):
        asked.append((dt, coarse_dt))
        return (0.2 + 0.1 * len(asked), 1, C.OK, None)  # every step disagrees with the next: 1/2, 1/4, 1/8 run

    settle_disagreement((0.2, 1, C.OK, None), rerun, s)
    assert asked == [(s.dt / 2, s.coarse_dt / 2), (s.dt / 4, s.coarse_dt / 4), (s.dt / 8, s.coarse_dt / 8)]


def _batch_check(monkeypatch, exact_status):
    """One engine throw (ok at 0.2 m, side 1) checked against an exact model that ends with ``exact_status`` at
    0.35 m; every rerun of the engine says ok at 0.3 m, side 2. Returns the checked arrays and the reruns asked."""
    reruns = []

    def fake_rerun(self, part, system, x, side, omega, o):
        def rerun(dt, coarse_dt):
            reruns.append(dt)
            return 0.3, 2, C.OK, SimpleNamespace(records=np.full((1, 3), 7.0))

        return rerun

    monkeypatch.setattr(EngineModel, "_rerun", fake_rerun)
    exact = SimpleNamespace(throw_batch=lambda *a: BatchArrays(np.array([0.35]), np.array([1]),
                                                                np.array([exact_status]), np.zeros((1, 3))))
    out = BatchArrays(np.array([0.2]), np.array([1]), np.array([C.OK]), np.zeros((1, 3)))
    EngineModel()._check_batch(None, None, np.array([0.4]), np.array([0]), np.array([4.0]), np.array([True]),
                               EngineOptions(), (exact, None), out)
    return out, reruns


def test_a_batch_throw_the_exact_model_ended_elsewhere_is_rerun(monkeypatch):
    out, reruns = _batch_check(monkeypatch, C.OK)
    assert reruns and (float(out.x[0]), int(out.side[0])) == (0.3, 2)


def test_a_batch_throw_the_exact_model_did_not_end_is_not_compared(monkeypatch):
    out, reruns = _batch_check(monkeypatch, C.UNRESOLVED)
    assert reruns == [] and (float(out.x[0]), int(out.side[0]), int(out.status[0])) == (0.2, 1, C.OK)
