"""Trajectory files: a :class:`~throwmap.records.trajectory.Trajectory` saved to one ``.npz`` and read back.

:func:`save_trajectory` writes, :func:`load_trajectory` reads (``throwmap view FILE.npz`` plays one; ``throwmap
view … --save-trajectory FILE.npz`` writes one). The file is a NumPy ``.npz`` archive (compressed, read with
``allow_pickle=False``: loading runs no code) holding, all in SI units (m, rad, s):

==================  =========  =========================================================================
array               shape      meaning
==================  =========  =========================================================================
``t``               (T,)       sample times, s
``arm_angle``       (T,)       arm rotation about the joint, rad (CCW +)
``poses``           (T, P, 3)  pose ``(x, y, φ)`` of each part (m, m, rad; world frame)
``contact_counts``  (T,)       number of contact points at each sample
``contacts``        (K, 2)     the contact points of all samples, one after the other, m
``event_t``         (E,)       event times, s
``header``          ()         one JSON string: everything else (below)
==================  =========  =========================================================================

The header: ``{"format": "throwmap-trajectory", "version": 1, "parts": [{"vertices", "mass", "com",
"radius_of_gyration", "point_masses", "name"}, …], "h", "length", "fixtures": [fixture_to_dict, …],
"event_labels": [...], "source", "meta": {...}}``. ``meta`` keeps every JSON-ready value (numbers, strings,
lists, dicts, arrays as lists; tuples come back as lists) and two objects by name: ``outcomes`` (a tuple of
:class:`~throwmap.records.outcome.ThrowOutcome`, stored with ``to_dict``) and ``arm`` (an
:class:`~throwmap.system.arm.Arm`, stored as its fields); a dataclass value is stored as its fields (read back
as a dict). Any other object is refused (:class:`~throwmap.errors.InvalidStateError` naming ``meta[key]``):
nothing is dropped silently.
"""

from __future__ import annotations

import dataclasses
import io
import json
import math
from pathlib import Path

import numpy as np

from ..errors import InvalidStateError, shown
from ..records.trajectory import Trajectory
from .files import atomic_write_bytes
from ..serial import json_ready

__all__ = ["FORMAT", "VERSION", "save_trajectory", "load_trajectory", "trajectory_to_arrays",
           "trajectory_from_arrays"]

FORMAT = "throwmap-trajectory"
"""The header's ``format`` tag."""
VERSION = 1
"""The header's ``version``; a file of a later version is refused."""


# ------------------------------------------------------------------ parts, fixtures, meta
def _part_record(part) -> dict:
    return {"vertices": [list(v) for v in part.vertices], "mass": part.mass, "com": list(part.com),
            "radius_of_gyration": part.radius_of_gyration,
            "point_masses": [[m, list(at)] for m, at in part.point_masses], "name": part.name}


def _part_from_record(d: dict, k: int):
    from ..system.part import Part

    try:
        return Part(tuple(tuple(float(c) for c in v) for v in d["vertices"]), float(d["mass"]),
                    tuple(float(c) for c in d["com"]), float(d["radius_of_gyration"]),
                    tuple((float(m), (float(at[0]), float(at[1]))) for m, at in d.get("point_masses", ())),
                    str(d.get("name", "")))
    except (KeyError, TypeError, ValueError, IndexError) as err:
        raise InvalidStateError(f"parts[{k}]", f"not a part record ({type(err).__name__}: {err})") from None


def _meta_record(meta: dict) -> dict:
    out = {}
    for key, value in dict(meta or {}).items():
        field = f"meta[{key!r}]"
        if key == "outcomes":
            out[key] = {"__type__": "ThrowOutcome", "items": [o.to_dict() if hasattr(o, "to_dict") else json_ready(o)
                                                             for o in value]}
            continue
        if key == "arm" and dataclasses.is_dataclass(value) and type(value).__name__ == "Arm":
            out[key] = {"__type__": "Arm", "fields": json_ready(dataclasses.asdict(value))}
            continue
        if dataclasses.is_dataclass(value) and not isinstance(value, type):
            value = dataclasses.asdict(value)
        ready = json_ready(value)
        try:
            json.dumps(ready, allow_nan=False)
        except (TypeError, ValueError):
            raise InvalidStateError(field, f"cannot be stored in a trajectory file: {shown(value)} "
                                           f"(JSON-ready values, ThrowOutcome tuples and Arm only)") from None
        out[str(key)] = ready
    return out


def _meta_from_record(rec: dict) -> dict:
    out = {}
    for key, value in rec.items():
        if isinstance(value, dict) and value.get("__type__") == "ThrowOutcome":
            from ..records.outcome import ThrowOutcome

            out[key] = tuple(ThrowOutcome.from_dict(d) for d in value["items"])
        elif isinstance(value, dict) and value.get("__type__") == "Arm":
            from ..system.arm import Arm

            f = {k: (math.inf if k == "mu" and v is None else v) for k, v in value["fields"].items()}
            out[key] = Arm(**f)
        else:
            out[key] = value
    return out


# ------------------------------------------------------------------ arrays
def trajectory_to_arrays(traj: Trajectory) -> dict:
    """The arrays of a trajectory file (see the module docstring), ``header`` as a 0-d string array."""
    from ..system.fixtures import fixture_to_dict

    if not isinstance(traj, Trajectory):
        raise InvalidStateError("trajectory", f"must be a Trajectory, got {shown(traj)}")
    T = traj.n_samples
    contacts = list(traj.contacts) if traj.contacts else [np.zeros((0, 2))] * T
    if len(contacts) != T:
        raise InvalidStateError("trajectory.contacts", f"{len(contacts)} contact sets for {T} samples")
    pts = [np.asarray(c, dtype=float).reshape(-1, 2) for c in contacts]
    header = {"format": FORMAT, "version": VERSION, "parts": [_part_record(p) for p in traj.parts],
              "h": float(traj.h), "length": float(traj.length),
              "fixtures": [fixture_to_dict(f) for f in traj.fixtures],
              "event_labels": [str(lab) for _, lab in traj.events], "source": str(traj.source),
              "meta": _meta_record(traj.meta)}
    return {"t": traj.t, "arm_angle": traj.arm_angle, "poses": traj.poses,
            "contact_counts": np.array([len(p) for p in pts], dtype=np.int64),
            "contacts": np.vstack(pts) if pts else np.zeros((0, 2)),
            "event_t": np.array([float(te) for te, _ in traj.events], dtype=float),
            "header": np.array(json.dumps(header, allow_nan=False))}


def trajectory_from_arrays(arrays) -> Trajectory:
    """Inverse of :func:`trajectory_to_arrays` (``arrays``: a mapping such as an opened ``.npz``)."""
    from ..system.fixtures import fixture_from_dict

    try:
        header = json.loads(str(arrays["header"][()]))
    except (KeyError, ValueError) as err:
        raise InvalidStateError("header", f"not a throwmap trajectory file ({err})") from None
    if not isinstance(header, dict) or header.get("format") != FORMAT:
        raise InvalidStateError("header.format", f"must be {FORMAT!r}, got {shown(header.get('format') if isinstance(header, dict) else header)}")
    if not isinstance(header.get("version"), int) or header["version"] > VERSION:
        raise InvalidStateError("header.version", f"this throwmap reads versions ≤ {VERSION}, got {shown(header.get('version'))}")
    try:
        counts = np.asarray(arrays["contact_counts"], dtype=np.int64)
        flat = np.asarray(arrays["contacts"], dtype=float).reshape(-1, 2)
        t, arm, poses = (np.asarray(arrays[k], dtype=float) for k in ("t", "arm_angle", "poses"))
        event_t = np.asarray(arrays["event_t"], dtype=float)
    except KeyError as err:
        raise InvalidStateError(f"arrays[{err.args[0]!r}]", "missing from the trajectory file") from None
    if counts.shape != t.shape or int(counts.sum()) != flat.shape[0] or np.any(counts < 0):
        raise InvalidStateError("contact_counts", f"{int(counts.sum())} contacts counted for {flat.shape[0]} stored")
    ends = np.cumsum(counts)
    contacts = tuple(flat[e - c:e] for c, e in zip(counts, ends))
    labels = header.get("event_labels", [])
    if len(labels) != event_t.shape[0]:
        raise InvalidStateError("event_labels", f"{len(labels)} labels for {event_t.shape[0]} event times")
    parts = tuple(_part_from_record(d, k) for k, d in enumerate(header["parts"]))
    fixtures = tuple(fixture_from_dict(d) for d in header.get("fixtures", ()))
    try:
        return Trajectory(t, arm, poses, parts, float(header["h"]), float(header["length"]), fixtures, contacts,
                          tuple((float(te), str(lab)) for te, lab in zip(event_t, labels)),
                          str(header.get("source", "")), _meta_from_record(header.get("meta", {})))
    except ValueError as err:
        raise InvalidStateError("poses", str(err)) from None


# ------------------------------------------------------------------ files
def save_trajectory(traj: Trajectory, path) -> Path:
    """Write ``traj`` to ``path`` (a ``.npz``; written atomically); returns the path."""
    path = Path(path)
    if path.suffix.lower() != ".npz":
        raise InvalidStateError("path", f"a trajectory file ends in .npz, got {shown(str(path))}")
    buf = io.BytesIO()
    np.savez_compressed(buf, **trajectory_to_arrays(traj))
    return atomic_write_bytes(path, buf.getvalue())


def load_trajectory(path) -> Trajectory:
    """Read a trajectory written by :func:`save_trajectory`."""
    path = Path(path)
    try:
        with np.load(path, allow_pickle=False) as data:
            return trajectory_from_arrays(data)
    except FileNotFoundError:
        raise InvalidStateError("path", f"no such file: {path}") from None
    except (OSError, ValueError) as err:
        if isinstance(err, InvalidStateError):
            raise
        raise InvalidStateError("path", f"{path} is not a trajectory file (.npz): {err}") from None
