"""What one frame of an animation draws: the scene (arm, fixtures, parts, contacts, scale bar, phase text).

:class:`Scene` builds the figure once and poses it per frame; :func:`frame_label`
names the phase a frame shows; :func:`scale_bar_length` picks the scale bar's
round length. Used by :mod:`throwmap.viz.animation` (files and stills); matplotlib
is imported when a scene is built.
"""

from __future__ import annotations

import math

import numpy as np

from ..records.trajectory import Trajectory
from ..system.pose import world_vertices
from .style import part_label

__all__ = ["Scene", "frame_label", "sample_frames", "scale_bar_length"]


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


def _rot(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


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


def _phase_after(label: str) -> str:
    """The phase a part is in after an event, until the next one (paper Sec. III: flight, pivot, landing, rest)."""
    if label in ("release", "lift-off"):
        return "flight"
    if label.startswith("impact"):
        vertex = label[len("impact"):].strip()
        return f"contact{' on ' + vertex if vertex else ''} (since impact)"
    if label.startswith("land side "):
        return f"on side {label[len('land side '):]} (landing)"
    if label.startswith("flip "):
        return f"on side {label.split('→')[-1]} (after flip {label[5:]})"
    return label


def frame_label(events, t: float, step: float) -> str:
    """The phase shown on the frame at time ``t`` (s); ``step`` is the time between frames (s).

    ``events`` are ``(t, label)`` sorted by time. An event at most one step before ``t``
    is named (``"release"``, ``"impact v2"``, ``"rest (jog)"`` …); later frames name the
    phase it started: ``"flight"`` after a release or a lift-off, ``"contact on vK
    (since impact)"`` after an impact, ``"on side k …"`` after a landing or a flip; rest
    and escapes stay shown. So no frame in mid-flight is labelled ``release``.
    """
    eps = 1e-9
    times = np.array([te for te, _ in events], dtype=float)
    n = int(np.searchsorted(times, t + eps, side="right"))
    if n == 0:
        return ""
    latest = _event_text(events, n)
    if t - times[n - 1] < step - eps or latest.startswith(("rest", "escape")):
        return latest
    return _phase_after(events[n - 1][1])


def _default_title(traj: Trajectory) -> str:
    """Part(s), h, ω and the model (or source) of a trajectory: what every figure's title names."""
    from .style import describe_setting

    names = " + ".join(dict.fromkeys(part_label(p) or "part" for p in traj.parts))
    outs = traj.meta.get("outcomes", ()) if isinstance(traj.meta, dict) else ()
    omegas = list(dict.fromkeys(float(o.omega) for o in outs if hasattr(o, "omega")))
    models = list(dict.fromkeys(str(o.model) for o in outs if getattr(o, "model", None)))
    model = ", ".join(models) or traj.source or None
    arm = traj.meta.get("arm") if isinstance(traj.meta, dict) else None
    mu = getattr(arm, "mu", None)
    text = describe_setting(names, traj.h, omegas if len(omegas) <= 4 else (), model, mu)
    if len(omegas) > 4:
        text = text.replace("ω = ?", f"{len(omegas)} release rates")
    angles = np.unique(np.round(np.asarray(traj.arm_angle, dtype=float), 12)) if traj.n_samples else np.zeros(0)
    if angles.size == 1 and angles[0] != 0.0:  # an arm resting tilted throughout (an impulsive throw)
        text += f", α = {math.degrees(float(angles[0])):.3g}°"
    for f in traj.fixtures:
        kind = type(f).__name__.lower()
        if kind == "wall":
            mu = getattr(f, "mu", None)
            text += f", wall {100 * f.height:.3g} cm ({'arm μ' if mu is None else f'μ {mu:g}'})"
        elif kind == "cavity":
            text += ", cavity"
    return text


def scale_bar_length(width: float) -> float:
    """A round length (m) for the scale bar of a view ``width`` m wide: the largest 1–2–5 value ≤ width / 5."""
    target = max(width, 1e-6) / 5.0
    exp = math.floor(math.log10(target))
    best = 10.0 ** exp
    for m in (1.0, 2.0, 5.0):
        if m * 10.0 ** exp <= target * (1 + 1e-12):
            best = m * 10.0 ** exp
    return best


def _length_text(metres: float) -> str:
    if metres >= 1.0:
        return f"{metres:g} m"
    if metres >= 0.01:
        return f"{100 * metres:g} cm"
    return f"{1000 * metres:g} mm"


def _bounds(traj: Trajectory, fixtures_outlines) -> tuple[float, float, float, float]:
    """Axis limits holding every sample's parts, the arm at every angle drawn and the fixtures; a trajectory whose
    ``meta["view"]`` is ``(x0, x1, y0, y1)`` (m, world) is drawn in that window instead (e.g. a tall wall cut)."""
    view = traj.meta.get("view") if isinstance(traj.meta, dict) else None
    if view is not None and len(view) == 4 and view[0] < view[1] and view[2] < view[3]:
        return tuple(float(v) for v in view)
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


class Scene:
    """The figure of an animation and how to draw frame ``f`` into it (shared by :func:`animate` and :func:`still`)."""

    def __init__(self, traj: Trajectory, times, *, step: float, title, dpi: int, figsize):
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
        from matplotlib.patches import Circle, Polygon

        from .style import side_colors

        self.traj, self.times, self.step = traj, np.asarray(times, dtype=float), float(step)
        self.poses, self.arm_angles, self.idx = sample_frames(traj, self.times)
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
        fig.suptitle(_default_title(traj) if title is None else title, fontsize=8)
        ax.axhline(0.0, color="0.92", lw=0.6, zorder=0)  # the joint's height, for reference

        # length scale: a round length, bottom right (the axes have equal scales)
        bar = scale_bar_length(x1 - x0)
        bx1 = x1 - 0.04 * (x1 - x0)
        by = y0 + 0.05 * (y1 - y0)
        ax.plot([bx1 - bar, bx1], [by, by], color="k", lw=2.5, solid_capstyle="butt", zorder=7, gid="scale-bar")
        ax.text(bx1 - bar / 2, by + 0.012 * (y1 - y0), _length_text(bar), ha="center", va="bottom", fontsize=7,
                zorder=7, gid="scale-bar-label")

        L, h = traj.length, traj.h
        thick = 0.012 * max(x1 - x0, y1 - y0)
        self.arm_body = np.array([[0.0, h], [L, h], [L, h - thick], [0.0, h - thick]])
        self.arm_patch = Polygon(self.arm_body, closed=True, facecolor="0.75", edgecolor="0.35", lw=0.8, zorder=1)
        ax.add_patch(self.arm_patch)
        self.stem, = ax.plot([0, 0], [0, h], color="0.35", lw=1.5, zorder=1)
        ax.add_patch(Circle((0.0, 0.0), 0.6 * thick + 0.002, facecolor="white", edgecolor="k", lw=1.0, zorder=4))
        self.fixture_patches = []
        for o in outlines:
            fp = Polygon(o, closed=True, facecolor="0.85", edgecolor="0.3", hatch="///", lw=0.8, zorder=1)
            ax.add_patch(fp)
            self.fixture_patches.append((fp, o))

        self.part_artists = []
        fill_colors = ["#dde6f0", "#f0e4d8", "#e0eedc", "#eddcee"]
        for p, part in enumerate(traj.parts):
            n = part.n_sides
            colors = side_colors(n)
            body = Polygon(part.w, closed=True, facecolor=fill_colors[p % len(fill_colors)], edgecolor="none",
                           zorder=2)
            ax.add_patch(body)
            edges = [ax.plot([], [], color=colors[k], lw=2.2, solid_capstyle="round", zorder=3)[0] for k in range(n)]
            labels = [ax.text(0, 0, str(k), color=colors[k], fontsize=8, fontweight="bold", ha="center",
                              va="center", zorder=5) for k in range(n)]
            cm, = ax.plot([], [], "o", color="k", ms=3.5, zorder=5)
            self.part_artists.append((part, body, edges, labels, cm))
        self.contacts_line, = ax.plot([], [], "o", color="red", ms=4.5, mec="darkred", zorder=6)
        self.text = ax.text(0.01, 0.98, "", transform=ax.transAxes, ha="left", va="top", fontsize=8,
                            family="monospace", bbox=dict(boxstyle="round", facecolor="white", edgecolor="0.6",
                                                          alpha=0.9), zorder=7, gid="phase")

        ev_times = np.array([te for te, _ in traj.events], dtype=float)
        order = np.argsort(ev_times, kind="stable")
        self.events = [traj.events[i] for i in order]
        starts = traj.meta.get("throw_starts") if isinstance(traj.meta, dict) else None
        self.release_times = np.sort(np.asarray(
            starts if starts else [te for te, lab in self.events if lab == "release"], dtype=float))
        self.has_contacts = len(traj.contacts) == traj.n_samples
        self.fig, self.ax = fig, ax

    def draw(self, f: int) -> None:
        """Pose every artist for frame ``f``."""
        traj, h = self.traj, self.traj.h
        R = _rot(float(self.arm_angles[f]))
        self.arm_patch.set_xy(self.arm_body @ R.T)
        js = R @ np.array([0.0, h])
        self.stem.set_data([0.0, js[0]], [0.0, js[1]])
        for fp, o in self.fixture_patches:
            fp.set_xy(o @ R.T)
        for p, (part, body, edges, labels, cm) in enumerate(self.part_artists):
            v = world_vertices(part, self.poses[f, p])
            body.set_xy(v)
            c = self.poses[f, p, :2]
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
        if self.has_contacts:
            pts = np.asarray(traj.contacts[self.idx[f]], dtype=float).reshape(-1, 2)
            self.contacts_line.set_data(pts[:, 0], pts[:, 1])
        tf = float(self.times[f])
        n_throw = int(np.searchsorted(self.release_times, tf + 1e-9, side="right"))
        head = f"t = {tf - float(traj.t[0]):6.3f} s"
        if self.release_times.size > 1:
            head += f"   throw {max(n_throw, 1)}/{self.release_times.size}"
        latest = frame_label(self.events, tf, self.step)
        self.text.set_text(head + ("\n" + latest if latest else ""))
