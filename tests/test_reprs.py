"""The records a user prints at the prompt say what they hold in one informative line (no raw array dumps)."""

import math

import matplotlib
import pytest

import throwmap as tm
from throwmap.control.inverse import inverse_jog
from throwmap.control.planner import plan_throws
from throwmap.io.config import load_config
from throwmap.statics import Body, analyse_rest, find_contacts

matplotlib.use("Agg")

TRI = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01)


def _one_line(text: str, *must: str) -> None:
    assert "\n" not in text and len(text) <= 300, text
    assert "np.float64" not in text and "array(" not in text, text
    for m in must:
        assert m in text, (m, text)


def test_part_repr_names_the_part_its_mass_cm_and_stable_sides():
    _one_line(repr(TRI), "triangle_30_60_90", "3 vertices", "0.05 kg", "stable sides 0, 1, 2")
    weighted = tm.Part.from_vertices([(0, 0), (0.1, 0), (0, 0.08)], mass=0.03, point_masses=[(0.02, (0.02, 0.02))])
    _one_line(repr(weighted), "1 lead weight", "0.05 kg")


def test_plan_repr_is_its_summary():
    plan = plan_throws(TRI, ARM, 0.2, 0, 0.25, 0, model="paper")
    _one_line(repr(plan), "plan (paper)", "0.2000 m, side 0")


def test_inverse_jog_repr_gives_the_rate_and_residual():
    jog = inverse_jog(TRI, ARM, 0.2, 0, 0.22, "paper")
    assert math.isfinite(jog.omega)
    _one_line(repr(jog), "InverseJog(ω =", "residual", "model paper")


def test_rest_analysis_repr_gives_the_verdict_and_friction():
    body = Body(tm.rectangle(0.06, 0.06), 0.2, 0.03, 0.0)
    r = analyse_rest((body,), find_contacts((body,), h=0.0, mu_arm=1.0), alpha=0.2)
    _one_line(repr(r), "rests", "μ needed 0.2027")


def test_loaded_config_repr_names_the_file_and_part(tmp_path):
    f = tmp_path / "part.toml"
    f.write_text('[part]\nvertices = [[0, 0], [0.1, 0], [0, 0.08]]\nmass = 0.05\n\n[arm]\nh = -0.01\n')
    _one_line(repr(load_config(f)), "part.toml", "Part(", "3 vertices", "h=-0.01")


def test_orbit_plot_title_names_the_part_and_h():
    orbit = tm.iterate(TRI, ARM, (0.2, 0), 4.0, 3, "paper")
    title = orbit.plot().axes[0].get_title()
    assert "part ?" not in title and "h = ?" not in title
    assert "triangle_30_60_90" in title and "h = -0.01 m" in title


@pytest.mark.parametrize("n_weights", [0, 2])
def test_part_repr_counts_weights(n_weights):
    pm = [(0.01, (0.02, 0.02))] * n_weights
    p = tm.Part.from_vertices([(0, 0), (0.1, 0), (0, 0.08)], mass=0.05, point_masses=pm)
    assert ("lead weight" in repr(p)) == bool(n_weights)
