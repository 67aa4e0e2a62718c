"""Model "mujoco": the impulse throw in MuJoCo, the engine cross-check (optional extra ``throwmap[mujoco]``).

One part on the plain arm, with the tuned contact settings of
:class:`throwmap.engine.mujoco.MujocoSettings` (docs/explanation/models.md, the engine). The mujoco
package is imported only when a throw runs; without it the call fails with one
line saying what to install.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError
from ..kernels import codes as C
from .base import BatchArrays, Features
from .engine import engine_failures
from .registry import register

__all__ = ["MujocoOptions", "MujocoModel", "MODEL"]


def _backend():
    from ..engine import mujoco as mujoco_backend

    return mujoco_backend


@dataclass(frozen=True, slots=True)
class MujocoOptions:
    """``settings``: a :class:`~throwmap.engine.mujoco.MujocoSettings` (None: the tuned defaults)."""

    settings: object = None

    def resolved(self):
        b = _backend()
        s = b.MujocoSettings() if self.settings is None else self.settings
        if not isinstance(s, b.MujocoSettings):
            raise InvalidStateError("settings", f"must be MujocoSettings, got {type(s).__name__}")
        return s


class MujocoModel:
    name = "mujoco"
    summary = "MuJoCo (optional extra) with tuned solref/solimp, elliptic cones: the engine cross-check"
    options_type = MujocoOptions
    features = Features(trajectory=True, friction=True, parallel=False)

    def outcome(self, part, system, x, side, omega, o: MujocoOptions):
        out = _backend().mujoco_throw(part, system.arm, x, side, omega, o.resolved())
        return out.replace(model=self.name)

    def throw_one(self, part, system, x, side, omega, o: MujocoOptions):
        out = self.outcome(part, system, x, side, omega, o)
        return out.x, out.side, int(out.status), out.to_record(part)

    def throw_batch(self, part, system, x, side, omega, valid, o: MujocoOptions, progress=None):
        m = x.size
        out = BatchArrays(x.copy(), side.copy(), np.full(m, C.INVALID_START, dtype=np.int64), np.full((m, C.NREC), np.nan))
        idx = np.flatnonzero(valid)
        for done, i in enumerate(idx, 1):
            out.x[i], out.side[i], out.status[i], out.records[i] = self.throw_one(
                part, system, float(x[i]), int(side[i]), float(omega[i]), o)
            if progress is not None:
                progress(done, idx.size)
        return out

    def assumptions(self, records, mu, status) -> str:
        """Runs that did not finish: timeouts and refused penetrations (validation table)."""
        return engine_failures(status)

    def trajectory(self, part, system, x, side, omega, o: MujocoOptions, dt):
        out, traj = _backend().mujoco_throw(part, system.arm, x, side, omega, o.resolved(), record=True)
        return out.replace(model=self.name), traj


MODEL = register(MujocoModel())
