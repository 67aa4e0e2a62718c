"""The browser viewer: one self-contained HTML file that plays a recorded motion beside its orbit plot.

``throwmap view`` (:mod:`throwmap.cli.view`) computes or loads what is shown; this module only renders data it is
given — a :class:`~throwmap.records.trajectory.Trajectory` and plain dicts — into HTML. Nothing is fetched when the
page is viewed: the script and the style (:file:`viewer_assets/viewer.js`, :file:`viewer.css`, package data) and
the data (one ``<script type="application/json">`` block) are inlined.

What the page shows
-------------------
* **the scene** (a canvas): the arm turned by its angle about the joint (its solid pieces and the fixtures' —
  walls, a cavity's floor — from :func:`throwmap.system.fixtures.arm_solids`, in the arm frame, turned with it),
  each part's polygon filled in its colour (:data:`PART_COLORS`) with its CM, the contact points (red), a scale
  bar, and the time, throw number and phase (:func:`throwmap.viz.frames.frame_label`);
* **the orbit plot** (a canvas beside it): x of each part (arm frame, cm) against throw number, the throw being
  played highlighted (a vertical bar and ringed points), the sensor's switch marked for an assembly episode;
  clicking a throw jumps to it;
* **controls**: play/pause, step one frame back/forward, previous/next throw, speed (¼× … 8× real time), a time
  slider (every frame) and a throw slider (the start of each throw); keys: space, ←/→;
* **tables** below (an experiment's outcomes and trials, an episode's summary), rendered here from dicts.

Data, in the page
-----------------
The motion is resampled to ``fps`` frames per simulated second (:func:`~throwmap.viz.frames.sample_frames`:
poses interpolated, contacts and labels from the latest sample); at most ``max_frames`` frames (a longer motion
gets a lower rate). Lengths are stored as integers in units of 0.1 mm and angles in 0.1 mrad (:data:`QUANTUM`),
so an assembly episode of about 19 s at 60 frames/s is about 100 kB.

The orbit (what the plot shows) comes from the trajectory's ``meta``: ``meta["orbit"]`` — a dict of lists, one
entry per step: ``throw`` (int), ``x`` (m, one per part, arm frame), ``side`` (one per part), ``phase`` (str)
and ``t`` (s: when the step's motion starts in the trajectory; None for steps before it starts) — or else, for an
orbit of throws (:func:`throwmap.throws.orbit_trajectory.orbit_trajectory`), ``meta["outcomes"]`` with
``meta["throw_starts"]`` (step 0: the start ``x0``; step k: where throw k left the part). ``meta["view"]``
``(x0, x1, y0, y1)`` (m, world), when given, is the scene's window.
"""

from __future__ import annotations

import html
import json
import math
import re
from importlib import resources
from pathlib import Path

import numpy as np

from ..errors import InvalidStateError, shown
from ..io.files import atomic_write_text
from ..serial import json_ready
from ..system.fixtures import arm_solids
from ..records.trajectory import Trajectory
from .frames import frame_label, sample_frames

__all__ = ["DEFAULT_FPS", "MAX_FRAMES", "MAX_TABLE_ROWS", "PART_COLORS", "QUANTUM", "orbit_steps", "player_data",
           "table_html", "viewer_html", "write_viewer"]

DEFAULT_FPS = 60.0
"""Frames per simulated second stored in the page."""
MAX_FRAMES = 6000
"""Cap on the frames stored (a longer motion is stored at a lower rate)."""
MAX_TABLE_ROWS = 2000
"""Rows of a table shown at most (the rest counted in its caption)."""
QUANTUM = 1e-4
"""Stored resolution: lengths in units of 0.1 mm (1e-4 m), angles in 0.1 mrad (1e-4 rad)."""
PART_COLORS = ("#d1495b", "#2e86ab", "#66a182", "#edae49", "#8d6a9f", "#00798c")
"""Fill colour of part p (cycled)."""
ARM_THICKNESS = 0.01
"""Drawn thickness of the arm below its surface, m."""


def _q(a) -> list:
    """Quantised integers (units of :data:`QUANTUM`) of an array, as a flat list."""
    return np.rint(np.asarray(a, dtype=float) / QUANTUM).astype(np.int64).ravel().tolist()


def orbit_steps(traj: Trajectory) -> dict | None:
    """The orbit drawn beside the scene (see the module docstring), or None when the trajectory carries none."""
    meta = traj.meta if isinstance(traj.meta, dict) else {}
    P = len(traj.parts)
    if isinstance(meta.get("orbit"), dict):
        o = meta["orbit"]
        n = len(o.get("throw", ()))
        for key in ("x", "side", "phase", "t"):
            if key in o and len(o[key]) != n:
                raise InvalidStateError(f"meta['orbit'][{key!r}]", f"{len(o[key])} entries for {n} steps")
        xs = np.asarray(o.get("x", ()), dtype=float).reshape(n, -1)
        if n and xs.shape[1] != P:
            raise InvalidStateError("meta['orbit']['x']", f"{xs.shape[1]} values per step for {P} parts")
        return {"throw": [int(k) for k in o["throw"]], "x": xs.tolist(),
                "side": [[int(s) for s in row] for row in o.get("side", [[-1] * P] * n)],
                "phase": [str(p) for p in o.get("phase", [""] * n)],
                "t": [None if v is None else float(v) for v in o.get("t", [None] * n)]}
    outs, starts = meta.get("outcomes"), meta.get("throw_starts")
    if outs and starts is not None and len(starts) == len(outs) and P == 1:
        get = (lambda o, k: o[k]) if isinstance(outs[0], dict) else getattr
        steps = {"throw": [0], "x": [[float(get(outs[0], "x0"))]], "side": [[int(get(outs[0], "side0"))]],
                 "phase": ["start"], "t": [None]}
        for k, (o, ts) in enumerate(zip(outs, starts), start=1):
            status = get(o, "status")
            label = status if isinstance(status, str) else getattr(status, "label", str(status))
            steps["throw"].append(k)
            steps["x"].append([float(get(o, "x"))])
            steps["side"].append([int(get(o, "side"))])
            steps["phase"].append("" if label == "ok" else str(label))
            steps["t"].append(float(ts))
        return steps
    return None


def _view(traj: Trajectory, pieces) -> list:
    """The scene's window ``[x0, x1, y0, y1]`` (m, world): ``meta["view"]`` or one holding everything drawn."""
    view = traj.meta.get("view") if isinstance(traj.meta, dict) else None
    if view is not None and len(view) == 4 and view[0] < view[1] and view[2] < view[3]:
        return [float(v) for v in view]
    pts = [np.zeros((1, 2))]
    angles = np.unique(np.round(traj.arm_angle, 3)) if traj.n_samples else np.zeros(1)
    if angles.size > 50:
        angles = np.linspace(angles.min(), angles.max(), 50)
    for a in angles:
        c, s = math.cos(a), math.sin(a)
        R = np.array([[c, -s], [s, c]])
        pts += [p @ R.T for p in pieces]
    for p, part in enumerate(traj.parts):
        r = float(np.max(part.ell))
        c = traj.poses[:, p, :2]
        pts += [c - r, c + r]
    allp = np.vstack(pts)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    pad = 0.05 * max(hi[0] - lo[0], hi[1] - lo[1], 0.05)
    return [float(lo[0] - pad), float(hi[0] + pad), float(lo[1] - pad), float(hi[1] + 2 * pad)]


def player_data(traj: Trajectory, *, fps: float = DEFAULT_FPS, max_frames: int = MAX_FRAMES) -> dict:
    """What the page's player needs (JSON-ready; lengths and angles quantised, see :data:`QUANTUM`).

    Keys: ``q`` (the quantum), ``fps``, ``t0`` (s), ``n`` (frames), ``arm`` (F angles), ``poses`` (per part, F·3
    values x, y, φ), ``cc``/``cp`` (contact count per frame; their points, flat), ``labels`` with ``label`` (per
    frame, an index into ``labels``), ``step`` (per frame, the orbit step being played, −1 before the first),
    ``parts`` (name, colour, body vertices ``w``), ``arm_pieces``/``fixture_pieces`` (polygons, arm frame),
    ``view`` (m), ``orbit`` (:func:`orbit_steps`, x quantised) and ``events`` (count)."""
    if not isinstance(traj, Trajectory):
        raise InvalidStateError("trajectory", f"must be a Trajectory, got {shown(traj)}")
    if traj.n_samples == 0:
        raise InvalidStateError("trajectory", "has no samples to show")
    if isinstance(fps, bool) or not (isinstance(fps, (int, float)) and math.isfinite(fps) and fps > 0):
        raise InvalidStateError("fps", f"must be a positive finite number of frames per second, got {shown(fps)}")
    if isinstance(max_frames, bool) or not isinstance(max_frames, int) or max_frames < 2:
        raise InvalidStateError("max_frames", f"must be an integer ≥ 2, got {shown(max_frames)}")
    t0, t1 = float(traj.t[0]), float(traj.t[-1])
    span = t1 - t0
    rate = float(fps)
    if span * rate + 1 > max_frames:
        rate = (max_frames - 1) / span
    n = int(math.floor(span * rate + 1e-9)) + 1
    times = t0 + np.arange(n) / rate
    poses, arm, idx = sample_frames(traj, times)
    # contacts and phase labels of the latest sample at or before each frame
    contacts = [np.asarray(traj.contacts[i], dtype=float).reshape(-1, 2) if traj.contacts else np.zeros((0, 2))
                for i in idx]
    seen: dict = {}
    label_idx = []
    events = sorted(traj.events, key=lambda e: e[0])
    for tk in times:
        text = frame_label(events, float(tk), 1.0 / rate) if events else ""
        label_idx.append(seen.setdefault(text, len(seen)))
    labels = list(seen)
    orbit = orbit_steps(traj)
    step = [-1] * n
    if orbit is not None:
        st = np.array([np.nan if v is None else v for v in orbit["t"]], dtype=float)
        playable = np.flatnonzero(np.isfinite(st))
        if playable.size:
            order = playable[np.argsort(st[playable], kind="stable")]
            k = np.searchsorted(st[order], times + 1e-9, side="right") - 1
            step = [int(order[j]) if j >= 0 else -1 for j in k]
        orbit = dict(orbit, x=[_q(row) for row in orbit["x"]])
    pieces, fixture_pieces = arm_solids(float(traj.h), float(traj.length), ARM_THICKNESS, traj.fixtures)
    return {
        "q": QUANTUM, "fps": rate, "t0": t0, "n": n,
        "arm": _q(arm), "poses": [_q(poses[:, p, :]) for p in range(len(traj.parts))],
        "cc": [len(c) for c in contacts], "cp": _q(np.vstack(contacts)) if contacts else [],
        "labels": labels, "label": label_idx, "step": step,
        "parts": [{"name": p.name or f"part {i}", "color": PART_COLORS[i % len(PART_COLORS)], "w": _q(p.w)}
                  for i, p in enumerate(traj.parts)],
        "arm_pieces": [_q(p) for p in pieces], "fixture_pieces": [_q(p) for p in fixture_pieces],
        "view": _view(traj, list(pieces) + list(fixture_pieces)), "orbit": orbit, "events": len(traj.events),
        "source": str(traj.source),
    }


def _cell(value) -> str:
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return "–" if not math.isfinite(value) else f"{value:.4g}"
    if value is None:
        return "–"
    return html.escape(str(value))


def table_html(columns, rows, *, caption: str = "", max_rows: int = MAX_TABLE_ROWS, highlight=None,
               table_id: str = "") -> str:
    """An HTML table of ``rows`` (sequences, one value per column; floats to 4 significant digits, None as –);
    row ``highlight`` (an index into ``rows``) marked; at most ``max_rows`` rows, the rest counted in the caption."""
    rows = list(rows)
    shown_rows = rows[:max_rows]
    more = f" (first {max_rows} of {len(rows)} shown)" if len(rows) > max_rows else ""
    head = "".join(f"<th>{html.escape(str(c))}</th>" for c in columns)
    body = []
    for i, r in enumerate(shown_rows):
        cls = ' class="hl"' if highlight is not None and i == highlight else ""
        body.append(f"<tr{cls}>" + "".join(f"<td>{_cell(v)}</td>" for v in r) + "</tr>")
    ident = f' id="{html.escape(table_id)}"' if table_id else ""
    cap = f"<caption>{html.escape(caption + more)}</caption>" if caption or more else ""
    return f"<table{ident}>{cap}<thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def _asset(name: str) -> str:
    return resources.files(__package__).joinpath("viewer_assets", name).read_text(encoding="utf-8")


def viewer_html(*, title: str, subtitle: str = "", player: dict | None = None, sections: str = "") -> str:
    """The whole page: ``title``, ``subtitle``, the player of ``player`` (:func:`player_data`; None: no player)
    and ``sections`` (HTML, e.g. :func:`table_html` tables) below it."""
    data = json.dumps(json_ready(player), separators=(",", ":"), allow_nan=False) if player is not None else "null"
    data = data.replace("</", "<\\/")  # never close the script block early
    page = _asset("template.html")
    subs = {"TITLE": html.escape(title), "SUBTITLE": html.escape(subtitle), "SECTIONS": sections,
            "PLAYER_HIDDEN": "" if player is not None else " hidden", "CSS": _asset("viewer.css"),
            "JS": _asset("viewer.js"), "DATA": data}
    return re.sub(r"\{\{([A-Z_]+)\}\}", lambda m: subs.get(m.group(1), m.group(0)), page)  # one pass


def write_viewer(path, page: str) -> Path:
    """Write the page (from :func:`viewer_html`) to ``path`` atomically; ``path`` must end in ``.html``/``.htm``."""
    path = Path(path)
    if path.suffix.lower() not in (".html", ".htm"):
        raise InvalidStateError("out", f"the viewer is an .html file, got {shown(str(path))}")
    return atomic_write_text(path, page)
