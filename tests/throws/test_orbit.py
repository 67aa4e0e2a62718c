"""Orbits of repeated throws and the first look at them (Figs. 2, 5, 7)."""

import subprocess
import sys

import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError


def test_iterate_constant_and_sequence(triangle, arm):
    orb = tm.iterate(triangle, arm, (0.12, 0), 4.0, n=50, model="paper")
    assert orb.n_throws == 50 and len(orb.x) == 51 and orb.status == tm.Status.OK
    for k, o in enumerate(orb.outcomes):
        assert o.x0 == orb.x[k] and o.x == orb.x[k + 1] and o.side == orb.side[k + 1]
    seq = tm.iterate(triangle, arm, (0.12, 0), [4.0, 2.0, 3.0], model="paper")
    assert list(seq.omegas) == [4.0, 2.0, 3.0]
    assert seq.x[1] == tm.throw(triangle, arm, 0.12, 0, 4.0, model="paper").x


def test_orbit_visits_every_side_and_stays_in_bands(triangle, arm):
    """Lemma 4.1: the part jogs out until it flips and eventually rests on every stable side."""
    orb = tm.iterate(triangle, arm, (0.12, 0), 4.0, n=400, model="paper")
    assert set(orb.side[100:]) == {0, 1, 2}
    assert 0.1 < orb.x[100:].min() and orb.x[100:].max() < 0.6
    assert "flip" in orb.kinds and "jog" in orb.kinds


def test_iterate_bad_input(triangle, arm):
    with pytest.raises(InvalidStateError, match="n:"):
        tm.iterate(triangle, arm, (0.12, 0), 4.0, model="paper")
    with pytest.raises(InvalidStateError, match="state"):
        tm.iterate(triangle, arm, 0.12, 4.0, n=3, model="paper")
    with pytest.raises(InvalidStateError, match="n:"):
        tm.iterate(triangle, arm, (0.12, 0), [1.0, 2.0], n=3, model="paper")


def test_plots_render(triangle, arm, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    from throwmap.viz.style import save_figure

    orb = tm.iterate(triangle, arm, (0.12, 0), 4.0, n=40, model="paper")
    fig = orb.plot()
    assert save_figure(fig, tmp_path / "orbit.png").stat().st_size > 1000
    fig = tm.plot_throw_map(triangle, arm, 4.0, n=200)
    assert len(fig.axes) == 3
    save_figure(fig, tmp_path / "map.png")
    esc = tm.iterate(triangle, arm, (0.12, 0), 5.6, n=100, model="paper")
    esc.plot()


def test_import_loads_neither_matplotlib_nor_mujoco():
    code = "import sys, throwmap; print('matplotlib' in sys.modules, 'mujoco' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["False", "False"]
