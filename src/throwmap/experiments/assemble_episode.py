"""One self-assembly trial recorded throw by throw (paper Sec. VI, Figs. 15 and 16).

:func:`assembly_episode` reruns trial ``index`` of a run of the ``assemble`` experiment seeded ``seed`` — the
same random stream, so the same trial as in the Monte Carlo table (:func:`~throwmap.experiments.base.trial_generator`)
— and keeps, after every engine run (the drop, each randomising throw, the tilt, each assembling throw and each
retention throw), both parts' arm-frame poses, their ``(x, side, tilt)`` states, the phase, the nominal release rate
and, when asked, the run's sampled motion (for the animation). :func:`first_success` finds the first successful
trial of a seed. The result, :class:`AssemblyEpisode`, draws the Fig. 16 analogue (x of both parts against throw
number, the switch marked) and the Fig. 15 analogue (snapshots: ready, partial, assembled).

Throw numbering: throw 0 is the dropped state; throw k ≥ 1 the state after the k-th arm motion that throws (the
tilt is not a throw: it shares the number of the throw before it, as in the draft's Fig. 16, where the switch
happens between throws 33 and 34).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown
from .base import Trial, config_of, trial_generator
from .registry import get_experiment

__all__ = ["AssemblyEpisode", "assembly_episode", "first_success"]

PHASES = ("drop", "high", "slide", "escape", "tilt", "low", "reset", "hold")
"""The ``assemble`` trial's engine runs (its observer's phases): the drop, randomising throws, the arm tilted to slide
the parts from the joint to the wall and back, tilted up and back around an escape throw, the switch's tilt to α,
assembling throws, a stalled low phase's tilt back, retention throws."""

MOTIONS = frozenset({"drop", "slide", "escape", "tilt", "reset"})
"""Phases that move the arm without throwing (they keep the throw number before them)."""


@dataclass(frozen=True, slots=True)
class AssemblyEpisode:
    """A recorded ``assemble`` trial (SI units, arm frame).

    Attributes
    ----------
    trial : Trial
        The trial's result, as the Monte Carlo run records it (success, failure kind, values).
    seed, index : int
        The run's seed and the trial's index (trial_generator(seed, index) re-creates it).
    part : Part
        The triangle (both parts are copies).
    length, h, wall_height : float
        Arm length = wall face (m), arm surface height (m), wall height (m).
    phases : tuple of str
        Per engine run, one of :data:`PHASES`.
    omegas : (R,) array, rad/s
        Nominal release rate of each run (0 for the drop and the tilt).
    throw_no : (R,) int array
        Throw number after each run (the drop 0; an arm motion without a throw keeps the number before it).
    poses : (R, 2, 3) array
        Both parts' arm-frame poses ``(x, y, φ)`` at the end of each run (m, m, rad).
    states : (R, 2, 3) array
        ``(x, side, tilt)`` of both parts at the end of each run.
    alphas : (R,) array, rad
        The arm's rest angle at the end of each run.
    statuses : tuple of str
        The run's status label (``"ok"`` or why it was refused / where a part went).
    trajectories : tuple
        The runs' :class:`~throwmap.records.trajectory.Trajectory` (empty unless recorded with ``motion=True``).
    """

    trial: Trial
    seed: int
    index: int
    part: object
    length: float
    h: float
    wall_height: float
    phases: tuple
    omegas: np.ndarray
    throw_no: np.ndarray
    poses: np.ndarray
    states: np.ndarray
    alphas: np.ndarray
    statuses: tuple
    trajectories: tuple = ()

    @property
    def success(self) -> bool:
        return self.trial.success

    @property
    def n_runs(self) -> int:
        return len(self.phases)

    @property
    def switch_runs(self) -> tuple:
        """Indices of every switch's tilt run (a stalled low phase tilts back and randomises again)."""
        return tuple(i for i, p in enumerate(self.phases) if p == "tilt")

    @property
    def switch_run(self) -> int | None:
        """Index of the last switch's tilt run (the sensor fired just before it), None when it never fired."""
        runs = self.switch_runs
        return runs[-1] if runs else None

    @property
    def switch_throw(self) -> int | None:
        """The throw number after which the sensor fired (the draft's "33rd throw"), None when it never did."""
        k = self.switch_run
        return None if k is None else int(self.throw_no[k])

    @property
    def assembled_run(self) -> int | None:
        """Index of the first run after the last switch with the pair assembled (a success), else None."""
        from ..control.pair_sensors import is_assembled

        k = self.switch_run
        if not self.success or k is None:
            return None
        for i in range(k, self.n_runs):
            if is_assembled(self.part, self.poses[i], length=self.length, h=self.h):
                return i
        return None

    def roles(self) -> tuple:
        """``((name, side), …)`` per part: at the switch the part on its longer leg is *a* (side 1) and the one on
        its hypotenuse *b* (side 0), as the pair sensor saw them; without a switch ``("part i", −1)``."""
        from ..control.pair_sensors import HYPOTENUSE, LONG_LEG

        k = self.switch_run
        if k is not None and k > 0:
            sides = [int(s) for s in self.states[k - 1, :, 1]]
            if sorted(sides) == sorted((LONG_LEG, HYPOTENUSE)):
                return tuple(("a" if s == LONG_LEG else "b", s) for s in sides)
        return tuple((f"part {i}", -1) for i in range(self.states.shape[1]))

    def snapshot_runs(self) -> tuple:
        """Runs for the Fig. 15 analogue: ready (the tilt's end), partial (the low-phase state whose parts overlap
        most in x while not assembled: *b* propped on *a*), assembled. Missing ones are left out."""
        out = []
        k = self.switch_run
        if k is not None:
            out.append(("ready (switch)", k))
            end = self.assembled_run if self.assembled_run is not None else self.n_runs - 1
            lows = [i for i in range(k + 1, end) if self.phases[i] == "low"]
            if lows:
                gap = [abs(self.states[i, 0, 0] - self.states[i, 1, 0]) for i in lows]
                out.append(("partial", lows[int(np.argmin(gap))]))
            if self.assembled_run is not None and self.assembled_run != k:
                out.append(("assembled", self.assembled_run))
        return tuple(out)

    def summary(self) -> dict:
        t = self.trial
        return {"seed": self.seed, "index": self.index, "success": t.success, "failure": t.failure,
                "runs": self.n_runs, "throws": int(self.throw_no[-1]) if self.n_runs else 0,
                "switch_throw": self.switch_throw,
                "assembled_throw": None if self.assembled_run is None else int(self.throw_no[self.assembled_run]),
                "values": dict(t.values)}

    def to_dict(self) -> dict:
        """The episode as one JSON-ready dict (a line of ``throwmap chain assemble``'s episode file): the trial
        (``index``, ``seed``, ``success``, ``failure``, ``values``; non-finite values as null), and per run its
        ``phases``, ``omegas``, ``throw_no``, ``poses``, ``states`` and ``statuses``."""
        import math

        tr = self.trial
        values = {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in tr.values.items()}
        return {"index": self.index, "seed": self.seed, "success": tr.success, "failure": tr.failure, "values": values,
                "phases": list(self.phases), "omegas": self.omegas.tolist(), "throw_no": self.throw_no.tolist(),
                "poses": self.poses.tolist(), "states": self.states.tolist(), "statuses": list(self.statuses)}

    def table(self) -> str:
        """One line per run: throw, phase, ω (rad/s), both parts' (x cm, side), status."""
        lines = [repr(self), "| run | throw | phase | ω (rad/s) | parts (x cm, side) | status |",
                 "|---|---|---|---|---|---|"]
        for r in self.rows():
            parts = "; ".join(f"{100 * p['x_m']:.2f}, {p['side']}" for p in r["parts"])
            lines.append(f"| {r['run']} | {r['throw']} | {r['phase']} | {r['omega_rad_s']:g} | {parts} | {r['status']} |")
        return "\n".join(lines)

    def rows(self) -> list[dict]:
        """One dict per run: throw, phase, ω, both parts' (x, side, tilt) and poses, α, status."""
        return [{"run": i, "throw": int(self.throw_no[i]), "phase": self.phases[i], "omega_rad_s": float(self.omegas[i]),
                 "alpha_rad": float(self.alphas[i]), "status": self.statuses[i],
                 "parts": [{"x_m": float(self.states[i, p, 0]), "side": int(self.states[i, p, 1]),
                            "tilt_rad": float(self.states[i, p, 2]), "pose": [float(v) for v in self.poses[i, p]]}
                           for p in range(self.poses.shape[1])]} for i in range(self.n_runs)]

    def motion(self, *, start: str = "switch", throws_before: int = 2):
        """The recorded runs joined into one :class:`~throwmap.records.trajectory.Trajectory` for the animation:
        from ``throws_before`` randomising throws before the switch (``start="switch"``) or from the drop
        (``start="drop"``) to the end. Needs an episode recorded with ``motion=True``."""
        if not self.trajectories or any(tr is None for tr in self.trajectories):
            raise InvalidStateError("motion", "this episode was recorded without its motion (motion=True)")
        if start not in ("switch", "drop"):
            raise InvalidStateError("start", f"must be 'switch' or 'drop', got {shown(start)}")
        first = 0
        if start == "switch" and self.switch_run is not None:
            first = max(0, self.switch_run - throws_before)
        traj = self.trajectories[first]
        for tr in self.trajectories[first + 1:]:
            traj = traj.concat(tr)
        # the window: the arm and the parts' flights, not the whole (tall) wall
        wx, wy = traj.poses[..., 0], traj.poses[..., 1]  # world poses
        r = float(np.max(self.part.ell))
        x0, x1 = min(-0.03, float(wx.min()) - r), max(self.length + 0.05, float(wx.max()) + r)
        y0 = min(float(wy.min()) - r, self.length * min(0.0, float(np.sin(traj.arm_angle).min())) + self.h - 0.03)
        y1 = max(float(wy.max()) + r, 0.1)
        meta = dict(traj.meta or {})
        meta["view"] = (x0, x1, y0, y1 + 0.02)
        return dataclasses.replace(traj, meta=meta)

    def plot(self, *, unit: str = "cm", title: str | None = None):
        """The Fig. 16 analogue (:func:`throwmap.viz.assembly.plot_assembly_episode`)."""
        from ..viz.assembly import plot_assembly_episode

        return plot_assembly_episode(self, unit=unit, title=title)

    def plot_snapshots(self, *, title: str | None = None):
        """The Fig. 15 analogue (:func:`throwmap.viz.assembly.plot_assembly_snapshots`)."""
        from ..viz.assembly import plot_assembly_snapshots

        return plot_assembly_snapshots(self, title=title)

    def __repr__(self) -> str:
        s = self.summary()
        end = "assembled" if s["success"] else f"failed ({s['failure']})"
        sw = "never switched" if s["switch_throw"] is None else f"switch after throw {s['switch_throw']}"
        return f"AssemblyEpisode(seed {self.seed}, trial {self.index}: {end}, {sw}, {s['throws']} throws)"


def assembly_episode(config=None, index: int = 0, seed: int = 0, *, motion: bool = False,
                     experiment: str = "assemble") -> AssemblyEpisode:
    """Rerun trial ``index`` of seed ``seed`` of ``experiment`` (an ``assemble``-like experiment whose ``trial`` takes
    an ``observer``) with ``config`` (its config type, a dict, or None: the built-in example) and record it;
    ``motion=True`` also keeps every run's sampled motion (for :meth:`AssemblyEpisode.motion`)."""
    from ..system.pose import state_from_pose
    from .assemble import _setup

    if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or index < 0:
        raise InvalidStateError("index", f"must be a non-negative integer, got {shown(index)}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise InvalidStateError("seed", f"must be a non-negative integer, got {shown(seed)}")
    exp = get_experiment(experiment)
    cfg = config_of(exp, config)
    part, arm, wall = _setup(cfg)
    rec = {"phase": [], "omega": [], "poses": [], "states": [], "alpha": [], "status": [], "traj": []}

    def observer(phase, run, omega):
        rec["phase"].append(str(phase))
        rec["omega"].append(float(omega))
        poses = np.asarray(run.poses, dtype=float).reshape(-1, 3)
        rec["poses"].append(poses)
        rec["states"].append(np.array([state_from_pose(part, q) for q in poses], dtype=float))
        rec["alpha"].append(float(run.alpha))
        rec["status"].append(str(run.status.label))
        rec["traj"].append(run.trajectory if motion else None)

    trial = exp.trial(cfg, int(index), trial_generator(int(seed), int(index)), observer=observer)
    throws, k = [], 0
    for p in rec["phase"]:
        if p not in MOTIONS:
            k += 1
        throws.append(k)
    n = len(rec["phase"])
    return AssemblyEpisode(trial, int(seed), int(index), part, float(arm.length), float(arm.h), float(wall.height),
                           tuple(rec["phase"]), np.asarray(rec["omega"]), np.asarray(throws, dtype=int),
                           np.asarray(rec["poses"]).reshape(n, -1, 3), np.asarray(rec["states"]).reshape(n, -1, 3),
                           np.asarray(rec["alpha"]), tuple(rec["status"]),
                           tuple(rec["traj"]) if motion else ())


def first_success(config=None, seed: int = 0, *, start: int = 0, max_tries: int = 20, motion: bool = False,
                  experiment: str = "assemble") -> AssemblyEpisode:
    """The first successful trial of seed ``seed`` from index ``start`` on, recorded (at most ``max_tries`` trials,
    each a full trial: seconds); an :class:`InvalidStateError` when none of them succeeds."""
    if isinstance(max_tries, bool) or not isinstance(max_tries, int) or not 1 <= max_tries <= 1000:
        raise InvalidStateError("max_tries", f"must be an integer in [1, 1000], got {shown(max_tries)}")
    kinds = []
    for i in range(int(start), int(start) + max_tries):
        ep = assembly_episode(config, i, seed, motion=motion, experiment=experiment)
        if ep.success:
            return ep
        kinds.append(ep.trial.failure)
    raise InvalidStateError("index", f"no successful trial among indices {start}…{start + max_tries - 1} of seed "
                                     f"{seed} (failures: {', '.join(kinds)})")

