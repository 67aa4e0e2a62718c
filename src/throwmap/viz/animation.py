"""Animations of a :class:`~throwmap.records.trajectory.Trajectory`: GIF (Pillow) or MP4 (ffmpeg).

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
* a scale bar of a round length (1–2–5 × 10ⁿ m, about a fifth of the view, e.g. 5 cm);
* a text box with the time, the throw number (from ``meta["throw_starts"]`` or the
  ``"release"`` events, shown when there are several) and the phase
  (:func:`frame_label`: an event on the frame it happens — ``"release"``,
  ``"impact v2"``, ``"flip 0→1"``, ``"rest (jog)"`` — then the phase it started,
  ``"flight"``, ``"contact on v2 (since impact)"`` …);
* a title naming the part(s), h, ω and the model.

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
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ThrowmapError
from ..io.files import atomic_output
from ..records.trajectory import Trajectory
from .frames import Scene, frame_label, sample_frames, scale_bar_length

__all__ = [
    "ANIMATION_FORMATS",
    "MAX_FRAMES",
    "Animation",
    "animate",
    "check_animation_path",
    "frame_label",
    "frame_times",
    "sample_frames",
    "scale_bar_length",
    "still",
]

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


def still(traj: Trajectory, t: float, *, step: float = 1 / 30, title: str | None = None, dpi: int = 100,
          figsize: tuple[float, float] = (7.0, 4.0)):
    """One frame of :func:`animate` at trajectory time ``t`` (s), as a matplotlib Figure.

    ``step`` (s of trajectory time between frames, ``speed / fps`` in :func:`animate`)
    decides how long an event stays named before its phase is shown (:func:`frame_label`).
    """
    if traj.n_samples == 0:
        raise ThrowmapError("trajectory", "has no samples to draw")
    scene = Scene(traj, [float(t)], step=float(step), title=title, dpi=int(dpi), figsize=figsize)
    scene.draw(0)
    return scene.fig


@dataclass(frozen=True, slots=True)
class Animation:
    """What :func:`animate` wrote: the file, the number of frames in it, its frame rate and playback length.

    ``n_frames`` is read back from the file (a GIF stores a held final state as one
    frame shown longer, so it can be fewer than the frames drawn); ``duration_s`` is
    the playback time, s. Usable as a path (``os.fspath``, ``open``).
    """

    path: Path
    n_frames: int
    fps: int
    duration_s: float
    frames_drawn: int

    def __fspath__(self) -> str:
        return str(self.path)


def _frames_in(path: Path, suffix: str, drawn: int) -> int:
    """Frames stored in the written file (a GIF is read back; an MP4 holds every frame drawn at a constant rate)."""
    if suffix == ".gif":
        from PIL import Image

        with Image.open(path) as im:
            return int(getattr(im, "n_frames", 1))
    return drawn


def animate(traj: Trajectory, path, *, fps: int = 30, speed: float = 1.0, dpi: int = 100, title: str | None = None,
            progress=None, hold: float = 0.5, max_frames: int = MAX_FRAMES,
            figsize: tuple[float, float] = (7.0, 4.0)) -> Animation:
    """Write an animation of ``traj`` to ``path`` (``.gif`` or ``.mp4``); returns an :class:`Animation`.

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
        Figure title; default names the part(s), h, ω and the model (:func:`_default_title`).
    progress : callable, optional
        Called as ``progress(done, total)`` after each frame is drawn.
    hold : float
        Seconds of playback the final state is held (≥ 0).
    max_frames : int
        Refuse (``ThrowmapError("out", …)``) to draw more frames than this.

    Returns
    -------
    Animation
        Every frame has a scale bar (a round length, e.g. 5 cm) and names the phase
        (:func:`frame_label`). The returned :attr:`Animation.n_frames` is the number of
        frames in the file, which is what should be reported.

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

    scene = Scene(traj, times, step=speed / fps, title=title, dpi=dpi, figsize=figsize)
    if suffix == ".gif":
        writer = mpl_animation.PillowWriter(fps=fps)
    else:
        writer = mpl_animation.FFMpegWriter(fps=fps, codec="h264", extra_args=["-pix_fmt", "yuv420p"])
    total = times.size
    with atomic_output(path, suffix=suffix) as tmp, writer.saving(scene.fig, str(tmp), dpi):
        for f in range(total):
            scene.draw(f)
            writer.grab_frame()
            if progress is not None:
                progress(f + 1, total)
    return Animation(path=path, n_frames=_frames_in(path, suffix, total), fps=fps, duration_s=total / fps,
                     frames_drawn=total)
