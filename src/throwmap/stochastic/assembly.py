"""A chain of the self-assembly experiment's low phase on a reduced pair state, from recorded episodes.

The ``assemble`` experiment runs two parts in the engine; its controller has memory (a stall counter, resets,
the randomiser's planner), so no chain on one part's rest is exact. What is chained here is the **first low
phase** — from the tilt to α until the pair is assembled or the phase ends (the stall rule, ``max_low``, a part
lost) — on a **reduced state** of the pair after each low throw:

* ``ready x∈(x₀, x₁]``: *a* flat on its longer leg wholly left of *b* flat on its hypotenuse
  (:func:`throwmap.control.pair_sensors.pair_ready`, arm frame), binned by *a*'s CM abscissa (``bin`` m);
* ``a flat, b not x∈(x₀, x₁]``: a part flat on its longer leg (*a*, the leftmost such one, binned by its CM)
  while the pair is not ready (*b* leaning on the wall or on *a*, *a* sliding under *b*);
* ``other``: any other arrangement on the arm;
* absorbing: ``assembled`` (:func:`~throwmap.control.pair_sensors.is_assembled`, the goal) and ``ended`` (the
  phase ended without assembly: the stall rule or ``max_low``, a lost part, a refused run).

The transition matrix is counted from the recorded throws (:func:`throwmap.experiments.assemble_episode.assembly_episode`
rows: phases and poses), a row with no data is sent to ``ended``. The "ended" rate of a state stands in for the
stall counter (memory) and is an approximation; the comparison says by how much it matters. The chain is
estimated on one set of episodes and checked against the hitting throws of another.
"""

from __future__ import annotations

import numpy as np

from ..errors import InvalidStateError
from .chain import MarkovChain

__all__ = ["low_phase_sequences", "low_phase_chain", "low_phase_hits", "read_episodes", "record_episodes"]


def _first_low(phases) -> list[int]:
    """Run indices of the first low phase (after the first tilt, up to the next non-low run)."""
    if "tilt" not in phases:
        return []
    i = phases.index("tilt") + 1
    out = []
    while i < len(phases) and phases[i] == "low":
        out.append(i)
        i += 1
    return out


def low_phase_sequences(episodes, part, *, length: float, h: float, bin: float = 0.02) -> list[list]:
    """Per episode with a tilt: the reduced states (labels) after the tilt and after each throw of its first low
    phase, ending in ``assembled`` or ``ended``. ``episodes``: dicts with ``phases``, ``poses``, ``statuses``."""
    from ..control.pair_sensors import LONG_LEG, READY_TILT, is_assembled, pair_ready
    from ..system.pose import state_from_pose

    def label(poses, status) -> str:
        if status != "ok":
            return "ended"
        if is_assembled(part, poses, length=length, h=h):
            return "assembled"
        r = pair_ready(part, poses)
        if r is not None:
            return "ready " + cell(float(poses[r[0]][0]))
        st = [state_from_pose(part, q) for q in poses]
        legs = [i for i in (0, 1) if int(st[i][1]) == LONG_LEG and abs(st[i][2]) < READY_TILT]
        if legs:
            return "a flat, b not " + cell(float(min(poses[i][0] for i in legs)))
        return "other"

    def cell(x: float) -> str:
        lo = bin * np.floor(x / bin)
        return f"x∈({100 * lo:.0f}, {100 * (lo + bin):.0f}] cm"

    out = []
    for ep in episodes:
        phases = list(ep["phases"])
        runs = _first_low(phases)
        if "tilt" not in phases:
            continue
        t = phases.index("tilt")
        seq = [label(ep["poses"][t], ep["statuses"][t])]
        for i in runs:
            if seq[-1] in ("assembled", "ended"):
                break
            seq.append(label(ep["poses"][i], ep["statuses"][i]))
        if seq[-1] not in ("assembled", "ended"):
            seq.append("ended")  # the phase ended here without assembly (stall, max_low, reset)
        out.append(seq)
    return out


def low_phase_hits(sequences) -> np.ndarray:
    """The low throw at which each sequence reached ``assembled`` (0: already at the tilt), −1 never."""
    return np.array([s.index("assembled") if "assembled" in s else -1 for s in sequences], dtype=np.int64)


def low_phase_chain(sequences) -> MarkovChain:
    """The chain counted from ``sequences`` (module docstring); its ``initial`` is the sequences' first states.
    The "ended" step after the last low throw is not a throw: ``ended`` entered from a live state after the
    phase's last throw is counted as a transition (the stall rule's rate)."""
    if not sequences:
        raise InvalidStateError("episodes", "no episode reached the low phase")
    absorbing = ("assembled", "ended")
    live = sorted({s for seq in sequences for s in seq if s not in absorbing},
                  key=lambda s: (s == "other", s))
    labels = tuple(live) + absorbing
    ix = {s: i for i, s in enumerate(labels)}
    n = len(labels)
    C = np.zeros((n, n))
    init = np.zeros(n)
    for seq in sequences:
        init[ix[seq[0]]] += 1
        for a, b in zip(seq, seq[1:]):
            if a not in absorbing:
                C[ix[a], ix[b]] += 1
    P = np.zeros((n, n))
    for i in range(len(live)):
        s = C[i].sum()
        if s > 0:
            P[i] = C[i] / s
        else:
            P[i, ix["ended"]] = 1.0
    for a in absorbing:
        P[ix[a], ix[a]] = 1.0
    return MarkovChain(P, labels, len(live), init / init.sum(),
                       meta={"kind": "assemble low phase", "transitions": int(C.sum()), "episodes": len(sequences)})


def read_episodes(path, *, cut: bool = False) -> list[dict]:
    """The episode rows of the JSON-lines file ``path`` (:func:`record_episodes`). A torn last line (a recording
    interrupted while writing it: no newline, or not JSON) is skipped with a warning, and cut off the file when
    ``cut`` (before appending); any other line that is not an episode row is refused (field ``episodes``)."""
    import json
    import warnings
    from pathlib import Path

    from ..errors import ThrowmapWarning

    p = Path(path)
    try:
        raw = p.read_bytes()
    except OSError as err:
        raise InvalidStateError("episodes", f"cannot read {str(p)!r}: {err.strerror or err}") from None
    lines = raw.splitlines(keepends=True)
    rows, good = [], 0
    for i, line in enumerate(lines):
        last = i == len(lines) - 1
        try:
            row = json.loads(line.decode("utf-8")) if line.strip() else None
        except (UnicodeDecodeError, ValueError):
            row = ...
        ok = row is None or (isinstance(row, dict) and isinstance(row.get("index"), int)
                             and isinstance(row.get("seed"), int)
                             and all(isinstance(row.get(k), list) for k in ("phases", "poses", "statuses")))
        if last and (i > 0 or cut) and (not ok or (cut and not line.endswith(b"\n"))):
            warnings.warn(f"episodes: skipped the torn last line {i + 1} of {str(p)!r} (an interrupted recording)"
                          + ("; cut off the file" if cut else ""), ThrowmapWarning, stacklevel=2)
            if cut:
                with open(p, "r+b") as fh:
                    fh.truncate(good)
            break
        if not ok:
            raise InvalidStateError("episodes", f"{str(p)!r} line {i + 1} is not an episode row (JSON lines of "
                                                f"'throwmap chain assemble FILE --record N')")
        if row is not None:
            rows.append(row)
        good += len(line)
    return rows


def record_episodes(path, seed: int, n: int, config=None, progress=None) -> list[dict]:
    """Episodes ``0 … n−1`` of seed ``seed`` recorded into the JSON-lines file ``path`` (those already there are
    kept and not rerun: an interrupted recording resumes); returns all rows of the file."""
    import json
    from pathlib import Path

    from ..experiments.assemble_episode import assembly_episode

    p = Path(path)
    rows = read_episodes(p, cut=True) if p.exists() else []
    stored = sorted({r["seed"] for r in rows})
    if stored and stored != [int(seed)]:
        raise InvalidStateError("seed", f"differs from the episodes stored in {str(p)!r} (stored "
                                        f"{', '.join(map(str, stored))}, given {int(seed)}): use another file")
    have = {(r["seed"], r["index"]) for r in rows}
    for i in range(int(n)):
        if (int(seed), i) in have:
            continue
        row = assembly_episode(config, i, int(seed)).to_dict()
        with p.open("a", encoding="utf-8") as f:
            f.write(json.dumps(row) + "\n")
        rows.append(row)
        if progress is not None:
            progress(i + 1, int(n))
    return rows
