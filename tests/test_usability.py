"""Usability: part files stay editable, defaults, names, paths, JSON, suggestions."""

from __future__ import annotations

import inspect
import json
import math
import re

import pytest

import throwmap as tm
from throwmap.io.config import load_config, part_document, save_part
from throwmap.viz.style import describe_setting

BRACKET = [[0.0, 0.0], [0.11, 0.0], [0.13, 0.035], [0.02, 0.05]]


def _bracket(**kw) -> tm.Part:
    return tm.Part.from_vertices(BRACKET, mass=0.07, point_masses=[(0.012, (0.09, 0.01))], name="bracket", **kw)


# ------------------------------------------------------------ 1. editable part files
@pytest.mark.parametrize("suffix", [".toml", ".json"])
def test_edited_point_mass_moves_cm_and_rho(tmp_path, suffix):
    """Raising the lead weight in a saved file moves the CM toward it and changes ρ, exactly as
    building the edited part directly does (the file holds no stale com/ρ)."""
    path = save_part(_bracket(), None, tmp_path / f"bracket{suffix}")
    text = path.read_text()
    edited = re.sub(r"(\bmass\"?\s*[=:]\s*)0\.012\b", r"\g<1>0.5", text)
    assert edited != text
    path.write_text(edited)
    loaded = load_config(path).part
    heavy = tm.Part.from_vertices(BRACKET, mass=0.07, point_masses=[(0.5, (0.09, 0.01))], name="bracket")
    assert loaded == heavy
    before = _bracket()
    assert loaded.com != before.com and loaded.radius_of_gyration != before.radius_of_gyration
    # the CM moved toward the lead weight at (0.09, 0.01)
    assert math.dist(loaded.com, (0.09, 0.01)) < math.dist(before.com, (0.09, 0.01))


def test_only_overrides_are_written():
    assert "com" not in part_document(_bracket())["part"]
    assert "radius_of_gyration" not in part_document(_bracket())["part"]
    doc = part_document(_bracket(com=(0.061, 0.024)))["part"]
    assert doc["com"] == [0.061, 0.024] and "radius_of_gyration" not in doc  # ρ follows the given CM
    doc = part_document(_bracket(radius_of_gyration=0.0375))["part"]
    assert doc["radius_of_gyration"] == 0.0375 and "com" not in doc


@pytest.mark.parametrize("kw", [{}, {"com": (0.061, 0.024)}, {"radius_of_gyration": 0.0375},
                                {"com": (0.061, 0.024), "radius_of_gyration": 0.0375}])
@pytest.mark.parametrize("suffix", [".toml", ".json"])
def test_round_trip_exact_with_and_without_overrides(tmp_path, kw, suffix):
    part = _bracket(**kw)
    assert load_config(save_part(part, None, tmp_path / f"p{suffix}")).part == part


def test_given_override_survives_an_edit(tmp_path):
    """A com that was given stays given after the point mass is edited (the file keeps it)."""
    path = save_part(_bracket(com=(0.061, 0.024)), None, tmp_path / "b.toml")
    path.write_text(path.read_text().replace("mass = 0.012", "mass = 0.5"))
    assert load_config(path).part.com == (0.061, 0.024)


# ------------------------------------------------------------ 3. default model
def test_throw_map_defaults_are_rigid_body():
    from throwmap.throws.samples import throw_map_samples

    for fn in (tm.plot_throw_map, throw_map_samples):
        assert inspect.signature(fn).parameters["model"].default == tm.DEFAULT_MODEL == "rigid_body", fn.__name__


def test_no_public_plot_or_sample_function_defaults_to_paper():
    import throwmap.throws.samples as samples
    import throwmap.viz as viz

    mods = [tm, samples, viz] + [getattr(viz, m) for m in ("throw_map", "orbit", "limit_set", "basins", "funnels",
                                                            "comparison", "animation", "frames", "style")
                                 if hasattr(viz, m)]
    for mod in mods:
        for name, fn in vars(mod).items():
            if callable(fn) and not name.startswith("_"):
                try:
                    params = inspect.signature(fn).parameters
                except (TypeError, ValueError):
                    continue
                if "model" in params:
                    assert params["model"].default != "paper", f"{mod.__name__}.{name}"


# ------------------------------------------------------------ 4. names of unnamed parts
def test_unnamed_part_gets_a_descriptive_name():
    plain = tm.Part.from_vertices(BRACKET, mass=0.05)
    assert plain.name == "polygon(4 vertices, 50 g)"
    lead = tm.Part.from_vertices(BRACKET, mass=0.07, point_masses=[(0.012, (0.09, 0.01))])
    assert lead.name == "polygon(4 vertices, 70 g)+lead(12 g at (9, 1) cm)"
    assert "part ?" not in describe_setting(lead, -0.01, 4.0, "rigid_body")
    # an explicit empty name stays empty, and a title still describes the part
    empty = tm.Part.from_vertices(BRACKET, mass=0.05, name="")
    assert empty.name == "" and describe_setting(empty, -0.01, 4.0, "rigid_body").startswith("polygon(4 vertices")


def test_nameless_part_file_is_named_by_stem_and_lead(tmp_path):
    path = tmp_path / "bracket.toml"
    path.write_text('[part]\nvertices = [[0, 0], [0.11, 0], [0.13, 0.035], [0.02, 0.05]]\nmass = 0.07\n'
                    '[[part.point_masses]]\nmass = 0.012\nat = [0.09, 0.01]\n')
    assert load_config(path).part.name == "bracket+lead(12 g at (9, 1) cm)"
    path.write_text('[part]\nvertices = [[0, 0], [0.11, 0], [0.13, 0.035], [0.02, 0.05]]\nmass = 0.07\n')
    assert load_config(path).part.name == "bracket"


# ------------------------------------------------------------ 6. μ = ∞ in JSON
@pytest.mark.parametrize("arm", [tm.Arm(h=-0.01), tm.Arm(h=-0.02, mu=0.3, length=0.5, back=0.01, g=9.7)])
def test_json_arm_reads_back(arm):
    """The ``"arm"`` object of ``--json`` output (null = ∞ for μ, null = unbounded for length) reads back equal."""
    from throwmap.cli.options import arm_dict, to_json
    from throwmap.io.config import arm_from_spec

    doc = json.loads(to_json({"arm": arm_dict(arm)}))["arm"]
    assert arm_from_spec(doc) == arm
    if math.isinf(arm.mu):
        assert doc["mu"] is None and "null" in arm_dict.__doc__
        assert arm_from_spec({**doc, "mu": "inf"}) == arm  # the text "inf" is ∞ too (JSON part files)


def test_json_part_file_takes_mu_inf_text(tmp_path):
    path = tmp_path / "p.json"
    path.write_text(json.dumps({"part": {"vertices": BRACKET, "mass": 0.05}, "arm": {"h": -0.01, "mu": "inf"}}))
    assert math.isinf(load_config(path).arm.mu)
    path.write_text(json.dumps({"part": {"vertices": BRACKET, "mass": 0.05}, "arm": {"h": -0.01, "mu": "lots"}}))
    with pytest.raises(tm.ConfigError) as err:
        load_config(path)
    assert err.value.field == "arm.mu"


# ------------------------------------------------------------ 7. suggestions for unknown options
def test_unknown_option_suggests_only_close_names():
    from typer.testing import CliRunner

    from throwmap.cli.app import app

    base = ["throw", "--part", "triangle", "--h", "-0.01", "--x", "0.2", "--side", "0", "--omega", "4"]
    res = CliRunner().invoke(app, [*base, "--bogus", "1"])
    assert res.exit_code == 2 and "did you mean" not in res.stderr and "'--bogus'" in res.stderr
    res = CliRunner().invoke(app, [*base[:-2], "--omeg", "4"])
    assert res.exit_code == 2 and "did you mean --omega?" in res.stderr, res.stderr


# ------------------------------------------------------------ 5. figure titles: whole, with their x range
def test_basins_title_is_whole_and_states_the_range():
    import matplotlib

    matplotlib.use("Agg")
    from throwmap.viz.basins import plot_basins

    part, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01)
    bas = tm.basins(part, arm, 4.0, grid=40, x_max=0.6, rng=1)
    title = plot_basins(bas).axes[0].get_title()
    lines = title.splitlines()
    assert len(lines) == 2 and "…" not in title and "120 starts, x ≤ 60 cm: " in lines[1]
    assert "h = -0.01 m" in lines[0] and " m" not in lines[1]  # the setting as every figure's; then the axis' unit
    c = bas.certificate
    assert (f"all reach #{c.attractor} within {c.max_throws_to_reach} throws" in lines[1]) is (c.attractor is not None)
    title_m = plot_basins(bas, unit="m").axes[0].get_title()
    assert "x ≤ 0.6 m" in title_m and " cm" not in title_m


def test_throw_map_title_states_the_sampled_range():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    part = tm.triangle_30_60_90(0.17)
    fig = tm.plot_throw_map(part, tm.Arm(h=-0.01), 4.0, n=30)
    assert "x ≤ 50 cm" in fig._suptitle.get_text() and "rigid_body" in fig._suptitle.get_text()
    fig = tm.plot_throw_map(part, tm.Arm(h=-0.01, length=0.4), 4.0, n=30, unit="m")
    assert "x ≤ 0.4 m" in fig._suptitle.get_text()
    plt.close("all")
