"""Animations of a :class:`~throwmap.throws.trajectory.Trajectory`: GIF (Pillow) or MP4 (ffmpeg).

matplotlib is imported on first use; ``import throwmap`` does not load it.

What is drawn, per frame
------------------------
* the arm, turned by ``arm_angle`` about the joint: a bar from the joint to
  ``traj.length`` with its surface on the arm-frame line y = ``traj.h``, and the
  joint marked;
* fixtures: every object in ``traj.fixtures`` that has a method
  ``outline(h, length) -> (N, 2) array`` giving a closed polygon in the *arm frame*
  (m; joint at the origin, x along the arm), turned with the arm. Objects without
  it are skipped. (This is the whole fixture protocol the animation relies on.)
* each part: its polygon filled, each side drawn in its colour
  (:func:`throwmap.viz.style.side_colors`) with its number at mid-edge (side k is
  the edge w_k → w_{k+1}, see :mod:`throwmap.conventions`), and the CM as a dot;
* the contact points of the sample as red markers;
* a text box with the time, the throw number (from ``meta["throw_starts"]`` or the
  ``"release"`` events, shown when there are several) and the latest event
  (``"flip 0→1"``, ``"rest (jog)"`` …).

Time
----
The trajectory is resampled to frames at ``t_k = t_0 + k · speed / fps``,
``k = 0 … floor((t_end − t_0) · fps / speed)``, ending exactly at the end time,
plus ``hold`` seconds of the final state (:func:`frame_times`): ``speed = 0.25``
plays four times slower than real time. Poses are interpolated linearly (angles
unwrapped first); contacts and events are taken from the latest sample at or
before ``t_k``. (Pillow merges identical consecutive GIF frames, so a hold is
stored as one long frame.)
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np

from ..errors import ThrowmapError
from ..io.files import atomic_output
from ..throws.trajectory import Trajectory, world_vertices

__all__ = ["animate", "check_animation_path", "frame_times", "sample_frames", "ANIMATION_FORMATS", "MAX_FRAMES"]

ANIMATION_FORMATS = (".gif", ".mp4")
"""File types :func:`animate` writes."""
MAX_FRAMES = 5000
"""Default cap on the number of frames (safety: a long orbit at a high fps)."""


def frame_times(traj: Trajectory, fps: float, speed: float = 1.0, hold: float = 0.0) -> np.ndarray:
    """The frame times (s of trajectory time) of an animation at ``fps`` played at ``speed``.

    ``t_k = t_0 + k · speed / fps`` up to the end; the last state is always shown:
    the end time replaces the last grid time if it is less than half a step after it,
    else it is added as one more frame. Then ``round(hold · fps)``
    more frames of the end (a still of ``hold`` seconds of playback).
    """
    if traj.n_samples == 0:
        return np.zeros(0)
    t0, t1 = float(traj.t[0]), float(traj.t[-1])
    step = speed / fps
    n = int(math.floor((t1 - t0) / step + 1e-9)) + 1
    times = t0 + step * np.arange(n)
    if t1 - times[-1] >= 0.5 * step:
        times = np.append(times, t1)
    else:
        times[-1] = t1  # the end replaces a grid time less than half a step before it
    n_hold = int(round(hold * fps))
    if n_hold > 0:
        times = np.concatenate((times, np.full(n_hold, t1)))
    return times


def sample_frames(traj: Trajectory, times) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Poses ``(F, P, 3)``, arm angles ``(F,)`` and sample indices ``(F,)`` at ``times``.

    Positions and angles are interpolated linearly in time (φ and the arm angle
    unwrapped first); the index is that of the latest sample at or before each time
    (for contacts and events).
    """
    times = np.asarray(times, dtype=float)
    t = traj.t
    idx = np.clip(np.searchsorted(t, times, side="right") - 1, 0, traj.n_samples - 1)
    arm = np.interp(times, t, np.unwrap(traj.arm_angle))
    P = traj.poses.shape[1]
    poses = np.empty((times.size, P, 3))
    for p in range(P):
        for q in range(3):
            col = traj.poses[:, p, q]
            if q == 2:
                col = np.unwrap(col)
            poses[:, p, q] = np.interp(times, t, col)
    return poses, arm, idx


def _check_positive(value, field: str, integer: bool = False) -> float:
    if isinstance(value, bool):
        raise ThrowmapError(field, f"must be a positive number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ThrowmapError(field, f"must be a positive number, got {value!r}") from None
    if not (math.isfinite(v) and v > 0) or (integer and v != int(v)):
        kind = "integer" if integer else "finite number"
        raise ThrowmapError(field, f"must be a positive {kind}, got {value!r}")
    return v


def _rot(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


def _ffmpeg_available() -> bool:
    from matplotlib import animation as mpl_animation

    try:
        return bool(mpl_animation.FFMpegWriter.isAvailable()) or shutil.which("ffmpeg") is not None
    except Exception:  # pragma: no cover - defensive
        return shutil.which("ffmpeg") is not None


def check_animation_path(path, *, need_directory: bool = True) -> Path:
    """Refuse, before any work, a target :func:`animate` cannot write (``ThrowmapError("out", …)``).

    Checks the suffix (``.gif``/``.mp4``), that ffmpeg is on PATH for ``.mp4``, that
    the target is not a directory and (``need_directory``) that its directory exists.
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in ANIMATION_FORMATS:
        raise ThrowmapError("out", f"cannot write {suffix or 'a file without extension'!r} animations "
                                   f"(use {' or '.join(ANIMATION_FORMATS)})")
    if suffix == ".mp4" and not _ffmpeg_available():
        raise ThrowmapError("out", "writing .mp4 needs ffmpeg on PATH; write a .gif instead")
    if path.is_dir():
        raise ThrowmapError("out", f"cannot write {path}: it is a directory")
    directory = path.parent if str(path.parent) else Path(".")
    if need_directory and not directory.is_dir():
        raise ThrowmapError("out", f"cannot write {path}: directory {directory} does not exist")
    return path


def _event_text(events, n_events: int) -> str:
    """The latest event among the first ``n_events``; ``rest`` says whether the throw jogged or flipped."""
    if n_events == 0:
        return ""
    label = events[n_events - 1][1]
    if label == "rest":
        flips = []
        for _, lab in reversed(events[:n_events]):
            if lab == "release":
                break
            if lab.startswith("flip "):
                flips.append(lab[5:])
        if flips:
            a = flips[-1].split("→")[0]
            b = flips[0].split("→")[-1]
            if a != b:
                return f"rest (flip {a}→{b})"
        return "rest (jog)"
    return label


def _bounds(traj: Trajectory, fixtures_outlines) -> tuple[float, float, float, float]:
    """Axis limits holding every sample's parts, the arm at every angle drawn and the fixtures."""
    pts = [np.zeros((1, 2))]
    L, h = traj.length, traj.h
    arm_pts = np.array([[0.0, h], [L, h], [L, h - 0.01], [0.0, h - 0.01], [0.0, 0.0]])
    angles = np.unique(np.round(traj.arm_angle, 4))
    if angles.size > 200:
        angles = np.linspace(angles.min(), angles.max(), 200)
    for a in angles:
        R = _rot(float(a))
        pts.append(arm_pts @ R.T)
        for o in fixtures_outlines:
            pts.append(o @ R.T)
    for p, part in enumerate(traj.parts):
        c = traj.poses[:, p, :2]
        r = float(np.max(part.ell))
        pts.append(np.column_stack((c[:, 0] - r, c[:, 1] - r)))
        pts.append(np.column_stack((c[:, 0] + r, c[:, 1] + r)))
    allp = np.vstack(pts)
    lo = allp.min(axis=0)
    hi = allp.max(axis=0)
    span = max(hi[0] - lo[0], hi[1] - lo[1], 0.05)
    pad = 0.05 * span
    return lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + 2.5 * pad


def animate(traj: Trajectory, path, *, fps: int = 30, speed: float = 1.0, dpi: int = 100, title: str | None = None,
            progress=None, hold: float = 0.5, max_frames: int = MAX_FRAMES,
            figsize: tuple[float, float] = (7.0, 4.0)) -> Path:
    """Write an animation of ``traj`` to ``path`` (``.gif`` or ``.mp4``); returns the path.

    Parameters
    ----------
    traj : Trajectory
        What to draw (see the module docstring for what each frame shows).
    path : str or Path
        Target file; its directory must exist. ``.gif`` is written with Pillow,
        ``.mp4`` with ffmpeg (which must be on PATH). The file is written to a
        temporary name beside it and renamed into place, so ``path`` is never half
        written.
    fps : int
        Frames per second of the file.
    speed : float
        Playback speed relative to real time (0.25: four times slower).
    dpi : int
        Resolution (the frame is ``figsize × dpi`` pixels).
    title : str, optional
        Figure title; default names the part(s) and the trajectory's source.
    progress : callable, optional
        Called as ``progress(done, total)`` after each frame is drawn.
    hold : float
        Seconds of playback the final state is held (≥ 0).
    max_frames : int
        Refuse (``ThrowmapError("out", …)``) to draw more frames than this.

    Raises
    ------
    ThrowmapError
        ``field="out"`` for an unsupported suffix, a missing directory, an
        unavailable ffmpeg or too many frames; ``"fps"``/``"speed"``/``"dpi"`` for
        bad values.
    """
    path = check_animation_path(path)
    suffix = path.suffix.lower()
    fps = int(_check_positive(fps, "fps", integer=True))
    speed = _check_positive(speed, "speed")
    dpi = int(_check_positive(dpi, "dpi", integer=True))
    if traj.n_samples == 0:
        raise ThrowmapError("trajectory", "has no samples to draw")
    hold = float(hold)
    if not (math.isfinite(hold) and hold >= 0):
        raise ThrowmapError("hold", f"must be a finite time ≥ 0 (s), got {hold!r}")
    times = frame_times(traj, fps, speed, hold)
    if times.size > max_frames:
        raise ThrowmapError("out", f"the animation would have {times.size} frames (more than max_frames = "
                                   f"{max_frames}); lower the fps, raise the speed or draw a shorter trajectory")

    from matplotlib import animation as mpl_animation
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle, Polygon

    from .style import side_colors

    poses, arm_angles, idx = sample_frames(traj, times)
    outlines = []
    for f in traj.fixtures:
        outline = getattr(f, "outline", None)
        if callable(outline):
            o = np.asarray(outline(traj.h, traj.length), dtype=float)
            if o.ndim == 2 and o.shape[1] == 2 and o.shape[0] >= 2:
                outlines.append(o)

    # even pixel sizes (H.264 in yuv420p needs them)
    figsize = tuple(2 * max(1, round(float(v) * dpi / 2)) / dpi for v in figsize)
    fig = Figure(figsize=figsize, dpi=dpi)  # no pyplot: no window, no global state
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.88))
    x0, x1, y0, y1 = _bounds(traj, outlines)
    box_aspect = (0.88 * figsize[1]) / (0.96 * figsize[0])  # height / width of the axes
    if (y1 - y0) / (x1 - x0) < box_aspect:  # widen the narrower extent so both scales are equal
        grow = 0.5 * ((x1 - x0) * box_aspect - (y1 - y0))
        y0, y1 = y0 - grow, y1 + grow
    else:
        grow = 0.5 * ((y1 - y0) / box_aspect - (x1 - x0))
        x0, x1 = x0 - grow, x1 + grow
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xticks([])
    ax.set_yticks([])
    for s in ax.spines.values():
        s.set_visible(False)
    if title is None:
        names = ", ".join(dict.fromkeys(p.name or "part" for p in traj.parts))
        title = f"{names} — {traj.source}" if traj.source else names
    fig.suptitle(title, fontsize=9)
    ax.axhline(0.0, color="0.92", lw=0.6, zorder=0)  # the joint's height, for reference

    L, h = traj.length, traj.h
    thick = 0.012 * max(x1 - x0, y1 - y0)
    arm_body = np.array([[0.0, h], [L, h], [L, h - thick], [0.0, h - thick]])
    arm_patch = Polygon(arm_body, closed=True, facecolor="0.75", edgecolor="0.35", lw=0.8, zorder=1)
    ax.add_patch(arm_patch)
    stem, = ax.plot([0, 0], [0, h], color="0.35", lw=1.5, zorder=1)
    ax.add_patch(Circle((0.0, 0.0), 0.6 * thick + 0.002, facecolor="white", edgecolor="k", lw=1.0, zorder=4))
    fixture_patches = []
    for o in outlines:
        fp = Polygon(o, closed=True, facecolor="0.85", edgecolor="0.3", hatch="///", lw=0.8, zorder=1)
        ax.add_patch(fp)
        fixture_patches.append((fp, o))

    part_artists = []
    fill_colors = ["#dde6f0", "#f0e4d8", "#e0eedc", "#eddcee"]
    for p, part in enumerate(traj.parts):
        n = part.n_sides
        colors = side_colors(n)
        body = Polygon(part.w, closed=True, facecolor=fill_colors[p % len(fill_colors)], edgecolor="none", zorder=2)
        ax.add_patch(body)
        edges = [ax.plot([], [], color=colors[k], lw=2.2, solid_capstyle="round", zorder=3)[0] for k in range(n)]
        labels = [ax.text(0, 0, str(k), color=colors[k], fontsize=8, fontweight="bold", ha="center", va="center",
                          zorder=5) for k in range(n)]
        cm, = ax.plot([], [], "o", color="k", ms=3.5, zorder=5)
        part_artists.append((part, body, edges, labels, cm))
    contacts_line, = ax.plot([], [], "o", color="red", ms=4.5, mec="darkred", zorder=6)
    text = ax.text(0.01, 0.98, "", transform=ax.transAxes, ha="left", va="top", fontsize=8, family="monospace",
                   bbox=dict(boxstyle="round", facecolor="white", edgecolor="0.6", alpha=0.9), zorder=7)

    ev_times = np.array([te for te, _ in traj.events], dtype=float)
    order = np.argsort(ev_times, kind="stable")
    events = [traj.events[i] for i in order]
    ev_times = ev_times[order]
    starts = traj.meta.get("throw_starts") if isinstance(traj.meta, dict) else None
    release_times = np.sort(np.asarray(starts if starts else [te for te, lab in events if lab == "release"],
                                       dtype=float))
    has_contacts = len(traj.contacts) == traj.n_samples
    eps = 1e-9

    def draw(f: int) -> None:
        R = _rot(float(arm_angles[f]))
        arm_patch.set_xy(arm_body @ R.T)
        js = R @ np.array([0.0, h])
        stem.set_data([0.0, js[0]], [0.0, js[1]])
        for fp, o in fixture_patches:
            fp.set_xy(o @ R.T)
        for p, (part, body, edges, labels, cm) in enumerate(part_artists):
            v = world_vertices(part, poses[f, p])
            body.set_xy(v)
            c = poses[f, p, :2]
            n = part.n_sides
            for k in range(n):
                a, b = v[k], v[(k + 1) % n]
                edges[k].set_data([a[0], b[0]], [a[1], b[1]])
                mid = 0.5 * (a + b)
                inward = c - mid
                norm = float(np.hypot(*inward))
                off = min(0.35 * norm, 0.008)
                labels[k].set_position(tuple(mid + (inward / norm * off if norm > 0 else 0.0)))
            cm.set_data([c[0]], [c[1]])
        if has_contacts:
            pts = np.asarray(traj.contacts[idx[f]], dtype=float).reshape(-1, 2)
            contacts_line.set_data(pts[:, 0], pts[:, 1])
        tf = float(times[f])
        n_ev = int(np.searchsorted(ev_times, tf + eps, side="right"))
        n_throw = int(np.searchsorted(release_times, tf + eps, side="right"))
        head = f"t = {tf - float(traj.t[0]):6.3f} s"
        if release_times.size > 1:
            head += f"   throw {max(n_throw, 1)}/{release_times.size}"
        latest = _event_text(events, n_ev)
        text.set_text(head + ("\n" + latest if latest else ""))

    if suffix == ".gif":
        writer = mpl_animation.PillowWriter(fps=fps)
    else:
        writer = mpl_animation.FFMpegWriter(fps=fps, codec="h264", extra_args=["-pix_fmt", "yuv420p"])
    with atomic_output(path, suffix=suffix) as tmp, writer.saving(fig, str(tmp), dpi):
        total = times.size
        for f in range(total):
            draw(f)
            writer.grab_frame()
            if progress is not None:
                progress(f + 1, total)
    return path
