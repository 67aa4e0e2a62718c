"""Seeing a throw: the paper model's time history (throwmap.throws.orbit_trajectory), the
animation writer (throwmap.viz.animation) and ``throwmap animate`` (throwmap.cli.animate)."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
import typer
from typer.testing import CliRunner

import throwmap as tm
from throwmap.viz.animation import animate, frame_times, sample_frames
from throwmap.cli.animate import register
from throwmap.errors import ThrowmapError
from throwmap.throws.orbit_trajectory import orbit_trajectory, paper_throw_trajectory, paper_trajectory
from throwmap.system.catalogue import builtin_part
from throwmap.system.pose import state_from_pose

PImage = pytest.importorskip("PIL.Image")

H = -0.01
ARM = tm.Arm(h=H)


def _parts():
    return {"triangle": tm.triangle_30_60_90(), "square": builtin_part("square"), "pentagon": builtin_part("pentagon")}


PARTS = _parts()


def _starts(part, omegas=(2.0, 3.0, 4.0, 5.0, 6.0), n_x=7):
    for s in part.stable_sides:
        for x in np.linspace(part.x_min(s) + 0.002, 0.4, n_x):
            for om in omegas:
                yield float(x), s, om


def _between(traj, t_lo, t_hi):
    return np.flatnonzero((traj.t > t_lo) & (traj.t < t_hi))


# ---------------------------------------------------------------- paper_trajectory: physics
@pytest.mark.parametrize("name", sorted(PARTS))
def test_paper_trajectory_ends_where_the_kernel_rests(name):
    """The last pose is throw(..., model="paper")'s (x, side), flat; no vertex sinks below the arm line."""
    part = PARTS[name]
    kinds = set()
    for x, s, om in _starts(part, omegas=(2.0, 3.0, 4.0, 5.0, 6.0, 10.0)):
        out = tm.throw(part, ARM, x, s, om, model="paper")
        traj = paper_trajectory(part, ARM, x, s, om)
        kept = traj.meta["outcomes"][0]
        assert traj.source == "paper" and (kept.x, kept.side, kept.status) == (out.x, out.side, out.status)
        if not out.ok:
            assert traj.events[-1][1] == f"escape: {out.status.label}"
            continue
        kinds.add((out.kind, out.n_impacts > 2))
        xf, kf, tilt = state_from_pose(part, traj.poses[-1, 0])
        assert kf == out.side
        assert xf == pytest.approx(out.x, abs=1e-12)
        assert abs(tilt) < 1e-12
        assert traj.poses[-1, 0, 1] == pytest.approx(H + part.d[kf], abs=1e-12)
        lowest = min(traj.vertices(i)[:, 1].min() for i in range(traj.n_samples))
        assert lowest >= H - 1e-6
        labels = [lab for _, lab in traj.events]
        assert labels[0] == "release" and labels[1].startswith("impact v") and labels[-1] == "rest"
        if out.kind == "flip":
            assert any(lab.startswith("flip ") for lab in labels)
    # the sample covers jogs, flips and rocking (more than the first impact and one landing)
    assert ("jog", False) in kinds and ("flip", False) in kinds
    if name != "square":
        assert any(rocking for _, rocking in kinds)


def test_paper_trajectory_tips_over_unstable_sides():
    """A slanted parallelogram (sides 1 and 3 unstable): landings there tip over from rest, as the kernel says."""
    quad = tm.Part.from_vertices([[0.0, 0.0], [0.1, 0.0], [0.13, 0.02], [0.03, 0.02]], mass=0.05)
    arm = tm.Arm(h=-0.005)
    unstable_landings = 0
    for x, s, om in _starts(quad, omegas=(4.0, 8.0, 14.0), n_x=8):
        out = tm.throw(quad, arm, x, s, om, model="paper")
        traj = paper_trajectory(quad, arm, x, s, om)
        landed = [int(lab.split()[-1]) for _, lab in traj.events if lab.startswith("land side")]
        unstable_landings += sum(not quad.stable[k] for k in landed)
        if out.ok:
            xf, kf, tilt = state_from_pose(quad, traj.poses[-1, 0])
            assert (kf, abs(tilt) < 1e-12) == (out.side, True)
            assert xf == pytest.approx(out.x, abs=1e-12)
    assert unstable_landings > 0


def test_paper_trajectory_flips_and_rocks_on_the_triangle():
    """Named cases on the paper's triangle at ω = 4 (jog, flip 1→2) and a rocking throw at ω = 10."""
    tri = PARTS["triangle"]
    jog = paper_trajectory(tri, ARM, 0.2, 0, 4.0)
    v = tm.throw(tri, ARM, 0.2, 0, 4.0, model="paper").contact_vertex  # the user's vertex index
    assert [lab for _, lab in jog.events] == ["release", f"impact v{v}", "land side 0", "rest"]
    flip = paper_trajectory(tri, ARM, 0.34, 1, 4.0)
    assert [lab for _, lab in flip.events][-2:] == ["flip 1→2", "rest"]
    rock = tm.throw(tri, ARM, 0.4, 1, 10.0, model="paper")
    assert rock.ok and rock.n_impacts >= 3
    traj = paper_trajectory(tri, ARM, 0.4, 1, 10.0)
    assert sum(lab.startswith("land side") for _, lab in traj.events) == rock.n_impacts - 1


def test_flight_conserves_energy():
    """Between release and first impact: ½|v|² + ½ρ²φ̇² + g(y − h) is the release energy (Eq. 1)."""
    tri = PARTS["triangle"]
    dt = 1.0 / 1000.0
    for x, s, om in [(0.2, 0, 4.0), (0.34, 1, 4.0), (0.15, 2, 6.0)]:
        out, traj = paper_throw_trajectory(tri, ARM, x, s, om, dt=dt)
        t_impact = next(te for te, lab in traj.events if lab.startswith("impact"))
        i = _between(traj, 0.0, t_impact - dt)  # interior samples on the uniform grid
        assert i.size > 20
        p = traj.poses[:, 0, :]
        v = (p[i + 1] - p[i - 1]) / (2 * dt)  # exact for the quadratic/linear flight
        E = 0.5 * (v[:, 0] ** 2 + v[:, 1] ** 2 + tri.radius_of_gyration**2 * v[:, 2] ** 2) + ARM.g * (p[i, 1] - H)
        np.testing.assert_allclose(E * tri.mass, out.energy_release, rtol=1e-9)
        assert t_impact == pytest.approx(out.t_flight, rel=1e-12)


def _kernel_swing(th0, th1, E, lj, I, g, nodes=400):
    """The kernel's time table of a monotone swing θ0 → θ1 (kernels.record.swing_table)."""
    from throwmap.kernels.record import swing_table

    t, th = np.empty(nodes + 1), np.empty(nodes + 1)
    swing_table(th0, th1, E, lj, I, g, nodes, t, th, 0, 0.0)
    return t, th


def test_pivot_swing_time_matches_the_pendulum_ode():
    """The kernel's energy quadrature of a swing (over the top, and turning back) agrees with I θ̈ = −g ℓ cos θ."""
    from scipy.integrate import solve_ivp

    g, lj = 9.81, 0.05
    I = 0.0025 + lj * lj
    f = lambda t, y: [y[1], -g * lj / I * math.cos(y[0])]  # noqa: E731
    # turning back: up from 0.3 rad at 8 rad/s and down to 0.3 again
    th0, w0 = 0.3, 8.0
    E = 0.5 * I * w0**2 + g * lj * math.sin(th0)
    th_turn = math.asin(E / (g * lj))
    t1, th1 = _kernel_swing(th0, th_turn, E, lj, I, g)
    t2, _ = _kernel_swing(th_turn, th0, E, lj, I, g)
    back = lambda t, y: y[0] - th0  # noqa: E731
    back.terminal, back.direction = True, -1
    sol = solve_ivp(f, [1e-9, 5.0], [th0 + w0 * 1e-9, w0], events=back, rtol=1e-11, atol=1e-13, dense_output=True)
    assert t1[-1] + t2[-1] == pytest.approx(sol.t_events[0][0], abs=1e-5)
    ts = np.linspace(0, t1[-1], 9)
    np.testing.assert_allclose(np.interp(ts, t1, th1), sol.sol(ts)[0], atol=1e-5)
    # from rest near the top, down to the end
    th0, end = 2.0, math.pi - 0.3
    t3, _ = _kernel_swing(th0, end, g * lj * math.sin(th0), lj, I, g)
    hit = lambda t, y: y[0] - end  # noqa: E731
    hit.terminal = True
    sol = solve_ivp(f, [0.0, 5.0], [th0, 0.0], events=hit, rtol=1e-11, atol=1e-13)
    assert t3[-1] == pytest.approx(sol.t_events[0][0], abs=1e-5)


def test_recorded_swing_ends_at_the_quadrature_time():
    """The kernel's recorded landing time after the first impact = t_flight + ∫ dθ/|θ̇| (SciPy quad, independent)."""
    from scipy.integrate import quad

    tri = PARTS["triangle"]
    for x, s, om in [(0.2, 0, 4.0), (0.34, 1, 4.0)]:
        out, traj = paper_throw_trajectory(tri, ARM, x, s, om, dt=1.0 / 240.0)
        t_land = next(te for te, lab in traj.events if lab.startswith("land side"))
        i = int(np.flatnonzero(traj.t == out.t_flight)[0])
        # the swing about the touching vertex, from the impact angle, at the post-impact energy
        j = [tri.user_vertex(q) for q in range(tri.n_sides)].index(out.contact_vertex)
        px = out.contact_x
        x_cm, y_cm = traj.poses[i, 0, :2]
        lj = float(tri.ell[j])
        I = tri.radius_of_gyration**2 + lj * lj
        th0 = math.atan2(y_cm - H, x_cm - px)
        wp = out.v_post[2]
        E = 0.5 * I * wp * wp + ARM.g * lj * math.sin(th0)
        k_land = int(next(lab for _, lab in traj.events if lab.startswith("land side")).split()[-1])
        n = tri.n_sides
        qa = (k_land == (j - 1) % n)
        end = math.atan2(tri.d[k_land], -(tri.uL[k_land] if qa else tri.uR[k_land]))
        speed = lambda th: math.sqrt(max(2.0 * (E - ARM.g * lj * math.sin(th)) / I, 0.0))  # noqa: E731
        moving_up = (wp > 0) == (th0 < math.pi / 2)
        if E < ARM.g * lj and moving_up:  # turns back at sin θ = E/(g ℓ)
            th_turn = math.asin(E / (ARM.g * lj)) if wp > 0 else math.pi - math.asin(E / (ARM.g * lj))
            legs = [(th0, th_turn), (th_turn, end)]
        else:
            legs = [(th0, end)]
        t_swing = sum(quad(lambda th: 1.0 / speed(th), min(a, b), max(a, b), limit=200)[0] for a, b in legs)
        assert t_land - out.t_flight == pytest.approx(t_swing, rel=1e-5)


def test_poses_continuous_and_contacts_per_sample():
    tri = PARTS["triangle"]
    out, traj = paper_throw_trajectory(tri, ARM, 0.34, 1, 4.0)
    assert len(traj.contacts) == traj.n_samples
    assert np.all(np.diff(traj.t) > 0)
    step = np.abs(np.diff(traj.poses[:, 0, :], axis=0))
    assert step[:, :2].max() < 0.02 and step[:, 2].max() < 0.1  # no jumps (φ unwrapped)
    t_impact = next(te for te, lab in traj.events if lab.startswith("impact"))
    flight = _between(traj, 0.0, t_impact)
    assert len(flight) > 0 and all(traj.contacts[i].shape == (0, 2) for i in flight)
    for i in (0, -1):  # at rest: both support vertices, on the arm line
        c = traj.contacts[i]
        assert c.shape == (2, 2)
        np.testing.assert_allclose(c[:, 1], H)
    np.testing.assert_allclose(np.sort(traj.contacts[-1][:, 0]),
                               np.sort(out.x + np.array([tri.uL[out.side], tri.uR[out.side]])), atol=1e-12)
    np.testing.assert_array_equal(traj.arm_angle, 0.0)  # impulsive throw: the arm does not move


def test_escape_is_drawn_and_labelled():
    tri = PARTS["triangle"]
    out = tm.throw(tri, ARM, 0.1225, 0, 10.0, model="paper")
    assert out.status == tm.Status.BEHIND_JOINT
    traj = paper_trajectory(tri, ARM, 0.1225, 0, 10.0)
    assert traj.events[-1][1] == "escape: behind_joint"


def test_paper_trajectory_refuses_bad_input():
    tri = PARTS["triangle"]
    with pytest.raises(tm.InvalidStateError, match="^x:"):
        paper_trajectory(tri, ARM, 0.0, 0, 4.0)
    with pytest.raises(tm.InvalidStateError, match="^dt:"):
        paper_trajectory(tri, ARM, 0.2, 0, 4.0, dt=0.0)


# ---------------------------------------------------------------- orbits
def test_orbit_trajectory_of_three_throws():
    tri = PARTS["triangle"]
    traj = orbit_trajectory(tri, ARM, 0.3, 1, 4.0, 3, model="paper", pause=0.2)
    orbit = tm.iterate(tri, ARM, (0.3, 1), 4.0, n=3, model="paper")
    outs = traj.meta["outcomes"]
    assert len(outs) == 3
    assert [(o.x, o.side, o.status) for o in outs] == [(o.x, o.side, o.status) for o in orbit.outcomes]
    releases = [te for te, lab in traj.events if lab == "release"]
    rests = [te for te, lab in traj.events if lab == "rest"]
    assert len(releases) == 3 and len(rests) == 3
    assert releases == list(traj.meta["throw_starts"])
    for r, nxt in zip(rests[:-1], releases[1:]):
        assert nxt - r == pytest.approx(0.2)  # the still pause
    assert np.all(np.diff(traj.t) > 0)
    xf, kf, _ = state_from_pose(tri, traj.poses[-1, 0])
    assert (kf, xf) == (orbit.side[-1], pytest.approx(orbit.x[-1], abs=1e-12))
    assert len(traj.contacts) == traj.n_samples


def test_orbit_trajectory_stops_at_an_escape():
    tri = PARTS["triangle"]
    traj = orbit_trajectory(tri, tm.Arm(h=H, length=0.3), 0.2, 0, 4.0, 10, model="paper")  # a start at rest
    outs = traj.meta["outcomes"]
    assert outs[-1].status == tm.Status.OFF_END and len(outs) < 10
    assert traj.events[-1][1] == "escape: off_end"


def test_orbit_trajectory_refuses_bad_input():
    tri = PARTS["triangle"]
    with pytest.raises(tm.InvalidStateError, match="^n:"):
        orbit_trajectory(tri, ARM, 0.3, 1, 4.0, None)
    with pytest.raises(tm.InvalidStateError, match="^model:"):
        orbit_trajectory(tri, ARM, 0.3, 1, 4.0, 2, model="small_angle")


# ---------------------------------------------------------------- animation
def test_gif_has_the_expected_frames(tmp_path):
    tri = PARTS["triangle"]
    traj = paper_trajectory(tri, ARM, 0.34, 1, 4.0)
    fps, speed = 12, 0.5
    times = frame_times(traj, fps, speed)
    n = int(math.floor(traj.t[-1] * fps / speed + 1e-9)) + 1
    assert len(times) in (n, n + 1) and times[-1] == traj.t[-1] and times[0] == 0.0
    calls = []
    res = animate(traj, tmp_path / "throw.gif", fps=fps, speed=speed, dpi=40, hold=0.0,
                  progress=lambda done, total: calls.append((done, total)))
    path = res.path
    assert path == tmp_path / "throw.gif" and res.n_frames == len(times)
    with PImage.open(path) as im:
        assert im.format == "GIF"
        assert im.n_frames == len(times)
    assert calls[-1] == (len(times), len(times))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["throw.gif"]  # no temporary file left


def test_sample_frames_interpolates_unwrapped_angles():
    tri = PARTS["triangle"]
    traj = paper_trajectory(tri, ARM, 0.34, 1, 4.0)
    poses, arm, idx = sample_frames(traj, traj.t)
    np.testing.assert_allclose(poses, traj.poses, atol=1e-12)
    np.testing.assert_array_equal(idx, np.arange(traj.n_samples))
    mid = 0.5 * (traj.t[:-1] + traj.t[1:])
    pm, _, _ = sample_frames(traj, mid)
    np.testing.assert_allclose(pm[:, 0, 2], 0.5 * (traj.poses[:-1, 0, 2] + traj.poses[1:, 0, 2]), atol=1e-12)


def test_mp4_without_ffmpeg_says_so(tmp_path, monkeypatch):
    import matplotlib

    monkeypatch.setenv("PATH", str(tmp_path / "empty"))
    monkeypatch.setitem(matplotlib.rcParams, "animation.ffmpeg_path", "no-such-ffmpeg")
    traj = paper_trajectory(PARTS["triangle"], ARM, 0.2, 0, 4.0)
    with pytest.raises(ThrowmapError) as err:
        animate(traj, tmp_path / "throw.mp4", dpi=30)
    assert str(err.value) == "out: writing .mp4 needs ffmpeg on PATH; write a .gif instead"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("target, reason", [("throw.avi", "cannot write '.avi'"), ("throw", "without extension"),
                                            ("missing/throw.gif", "does not exist")])
def test_animate_refuses_bad_targets(tmp_path, target, reason):
    traj = paper_trajectory(PARTS["triangle"], ARM, 0.2, 0, 4.0)
    with pytest.raises(ThrowmapError, match=reason) as err:
        animate(traj, tmp_path / target)
    assert err.value.field == "out"


def test_animate_refuses_too_many_frames(tmp_path):
    traj = paper_trajectory(PARTS["triangle"], ARM, 0.2, 0, 4.0)
    with pytest.raises(ThrowmapError, match="max_frames"):
        animate(traj, tmp_path / "a.gif", fps=30, speed=0.01, max_frames=100)
    with pytest.raises(ThrowmapError, match="^fps:"):
        animate(traj, tmp_path / "a.gif", fps=0)


def test_fixtures_with_an_outline_are_drawn(tmp_path):
    """The fixture protocol: ``outline(h, length) -> (N, 2)`` arm-frame points; others are skipped."""
    import dataclasses

    seen = []

    class Block:
        def outline(self, h, length):
            seen.append((h, length))
            return np.array([[length - 0.02, h], [length, h], [length, h + 0.05], [length - 0.02, h + 0.05]])

    traj = paper_trajectory(PARTS["triangle"], ARM, 0.2, 0, 4.0)
    traj = dataclasses.replace(traj, fixtures=(Block(), object()))
    animate(traj, tmp_path / "f.gif", fps=5, dpi=30, hold=0.0)
    assert seen == [(traj.h, traj.length)]


def test_import_throwmap_loads_no_matplotlib():
    code = ("import sys, throwmap, throwmap.throws.orbit_trajectory, throwmap.viz.animation, throwmap.cli.animate; "
            "assert 'matplotlib' not in sys.modules, 'matplotlib imported'")
    subprocess.run([sys.executable, "-c", code], check=True)


# ---------------------------------------------------------------- CLI
def _app():
    app = typer.Typer()
    register(app)

    @app.command("other")
    def _other() -> None:  # a second command keeps "animate" a subcommand
        """Placeholder."""

    return app


runner = CliRunner()
BASE = ["animate", "--part", "triangle", "--h", "-0.01", "--x", "0.3", "--side", "1", "--omega", "4",
        "--model", "paper", "--fps", "8", "--speed", "1"]


def test_cli_animate_writes_a_gif(tmp_path):
    out = tmp_path / "throw.gif"
    result = runner.invoke(_app(), BASE + ["--n", "2", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert out.is_file()
    lines = result.stdout.splitlines()
    assert lines[0].startswith(f"wrote {out}")
    assert "2 throws" in lines[1] and "rests at x =" in lines[1]
    with PImage.open(out) as im:
        assert im.n_frames > 3


@pytest.mark.parametrize("change, field", [
    (["--model", "nope"], "model"),
    (["--out", "throw.avi"], "out"),
    (["--x", "0.01"], "x"),
    (["--side", "7"], "side"),
    (["--n", "0"], "n"),
    (["--fps", "0"], "fps"),
    (["--speed", "-1"], "speed"),
    (["--mu", "-1"], "arm.mu"),
])
def test_cli_animate_bad_input_is_one_line(tmp_path, change, field):
    args = list(BASE) + ["--out", str(tmp_path / "throw.gif")]
    for opt, val in zip(change[::2], change[1::2]):
        if opt in args:
            args[args.index(opt) + 1] = val
        else:
            args += [opt, val]
    if change[0] == "--out":
        args[args.index("--out", len(BASE)) + 1] = str(tmp_path / change[1])
    result = runner.invoke(_app(), args)
    assert result.exit_code == 2, result.output
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}:"), result.stderr
    assert result.stdout == ""
    assert list(tmp_path.iterdir()) == []
