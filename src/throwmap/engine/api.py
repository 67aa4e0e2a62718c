"""The engine as a throw map: one part, one throw, results in the analytic models' types.

``throw(..., model="engine")`` and ``throw_batch(..., model="engine")`` call these.
"""

from __future__ import annotations

import os
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from ..system.arm import Arm
from ..errors import InvalidStateError
from ..kernels import codes as C
from ..records.outcome import BatchOutcome, Status, ThrowOutcome
from ..system.part import Part
from .pymunk import EngineRun, simulate
from ..system.motion import ImpulseThrow
from .scene import Placement, Scene
from .settings import EngineSettings, Friction

__all__ = ["engine_throw", "engine_trajectory", "engine_batch", "engine_run"]


def engine_run(part: Part, arm: Arm, x: float, side: int, omega: float, *, fixtures=(), alpha: float = 0.0,
               realisation=None, settings: EngineSettings | None = None, friction: Friction | None = None,
               record: bool = False) -> EngineRun:
    """Simulate one part thrown from rest at ``(x, side)``; see :func:`throwmap.engine.simulate`."""
    scene = Scene(arm, (Placement(part, x=x, side=side),), tuple(fixtures), alpha,
                  Friction() if friction is None else friction)
    real = ImpulseThrow(omega) if realisation is None else realisation
    return simulate(scene, real, settings, record=record)


def engine_throw(part: Part, arm: Arm, x: float, side: int, omega: float, **kw) -> ThrowOutcome:
    """One throw in pymunk as a :class:`~throwmap.ThrowOutcome` (model ``"engine"``).

    Keywords as :func:`engine_run` (``fixtures``, ``alpha``, ``realisation``,
    ``settings``, ``friction``). With ``realisation=None`` the throw is the
    paper's impulse at rate ``omega``.
    """
    kw.pop("record", None)
    run = engine_run(part, arm, x, side, omega, **kw)
    return run.outcome(0, x0=x, side0=side, omega=omega)


def engine_trajectory(part: Part, arm: Arm, x: float, side: int, omega: float, **kw):
    """One engine throw with its sampled motion: ``(ThrowOutcome, Trajectory)``."""
    kw["record"] = True
    run = engine_run(part, arm, x, side, omega, **kw)
    return run.outcome(0, x0=x, side0=side, omega=omega), run.trajectory


def _check_keywords(kw: dict) -> None:
    """Raise :class:`InvalidStateError` naming ``settings``/``friction`` when they have the wrong type."""
    for name, kind in (("settings", EngineSettings), ("friction", Friction)):
        v = kw.get(name)
        if v is not None and not isinstance(v, kind):
            raise InvalidStateError(
                name, f"must be a throwmap.engine.{kind.__name__} (or None: the defaults), got {type(v).__name__}")


def _one(args):
    part, arm, x, side, omega, kw = args
    try:
        o = engine_run(part, arm, x, side, omega, **kw)
        return o.states[0][0], o.states[0][1], int(o.statuses[0]), o.records[0]
    except InvalidStateError:
        rec = np.full(C.NREC, np.nan)
        return x, side, int(Status.INVALID_START), rec


def engine_batch(part: Part, arm: Arm, x, side, omega, *, valid=None, workers: int | None = 1, progress=None,
                 **kw) -> BatchOutcome:
    """Many independent engine throws (flat arrays); ``workers`` > 1 uses processes.

    ``valid`` marks admissible starts (others get ``INVALID_START``);
    ``progress(done, total)`` is called after each throw.
    """
    _check_keywords(kw)  # a bad setting is the caller's error, not an invalid start of every throw
    x = np.asarray(x, dtype=float).ravel()
    side = np.asarray(side).ravel().astype(np.int64)
    omega = np.asarray(omega, dtype=float).ravel()
    n = x.size
    valid = np.ones(n, dtype=bool) if valid is None else np.asarray(valid, dtype=bool).ravel()
    x_out = x.copy()
    side_out = side.copy()
    status_out = np.full(n, int(Status.INVALID_START), dtype=np.int64)
    rec_out = np.full((n, C.NREC), np.nan)
    idx = np.flatnonzero(valid)
    jobs = [(part, arm, float(x[i]), int(side[i]), float(omega[i]), kw) for i in idx]
    workers = 1 if workers is None else int(workers)
    if workers <= 0:
        workers = os.cpu_count() or 1
    if workers == 1 or len(jobs) < 2:
        results = []
        for k, job in enumerate(jobs):
            results.append(_one(job))
            if progress is not None:
                progress(k + 1, len(jobs))
    else:
        with ProcessPoolExecutor(max_workers=workers) as ex:
            results = []
            for k, r in enumerate(ex.map(_one, jobs, chunksize=max(1, len(jobs) // (8 * workers)))):
                results.append(r)
                if progress is not None:
                    progress(k + 1, len(jobs))
    for i, (xn, kn, st, rec) in zip(idx, results):
        x_out[i], side_out[i], status_out[i], rec_out[i] = xn, kn, st, rec
    return BatchOutcome(x=x_out, side=side_out, status=status_out, records=rec_out, model="engine")
