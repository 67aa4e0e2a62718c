"""Bad input to the feeding commands: ``experiment --workers``, the feed config's ``settings``
overrides and the keys of a ``--cavity`` file. Each refusal is one ``error: <field>: …`` line on
stderr, exit 2, no traceback, nothing on stdout.

The feed configs use the impulse arm (its cavity design uses the exact model: about a second) and
``--workers 1``: a config error must surface before any trial's physics.
"""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.cli.options import _cavity_profile
from throwmap.errors import ConfigError, InvalidStateError
from throwmap.experiments.feed import FeedConfig, _settings

runner = CliRunner()
PROFILE = "[[0.06, 0.0], [0.06, -0.02], [0.0, -0.02]]"
THROW = ["throw", "--part", "triangle", "--h", "-0.01", "--length", "0.3", "--mu", "1", "--x", "0.15",
         "--side", "0", "--omega", "5", "--model", "engine"]
FEED = 'max_throws = 1\nhold_throws = 0\n[noise]\nomega_rel = 0.03\nmu_rel = 0.1\nrealisation = "impulse"\n'


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def one_error(result, field):
    """Exit 2, exactly one stderr line ``error: <field>: …``, nothing on stdout, no traceback."""
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}: "), result.stderr
    assert result.stdout == "" and "Traceback" not in result.output
    return lines[0]


# ---------------------------------------------------------------- 1. --workers
def test_workers_below_zero_are_refused_and_zero_is_documented_as_all_cores():
    # 0 is the documented default ("all cores", as in run_experiment and the engine options): kept
    line = one_error(invoke("experiment", "feed", "--workers", -1, "--n", 2), "workers")
    assert "got -1" in line and "0: all cores" in line
    one_error(invoke("experiment", "feed", "--workers", "1.5", "--n", 2), "workers")
    assert "0: all cores" in invoke("experiment", "--help").stdout


# ---------------------------------------------------------------- 2. feed settings
def test_an_unknown_settings_key_is_named_with_its_path_and_the_allowed_fields(tmp_path):
    cfg = tmp_path / "feed.toml"
    cfg.write_text("settings = { foo = 1 }\n" + FEED, encoding="utf-8")
    line = one_error(invoke("experiment", "feed", cfg, "--n", 1, "--workers", 1), "config.settings.foo")
    assert "unknown EngineSettings field" in line and "allowed: dt, " in line and "t_max" in line


def test_a_settings_value_of_the_wrong_type_is_named_with_its_path(tmp_path):
    cfg = tmp_path / "feed.toml"
    cfg.write_text('settings = { dt = "x" }\n' + FEED, encoding="utf-8")
    line = one_error(invoke("experiment", "feed", cfg, "--n", 1, "--workers", 1), "config.settings.dt")
    assert "'x'" in line


@pytest.mark.parametrize("settings, field, text", [
    ({"t_mx": 5.0}, "config.settings.t_mx", "did you mean 't_max'?"),
    ({"dt": "x"}, "config.settings.dt", "must be a finite number"),
    ({"coarse_dt": 1e-5}, "config.settings.coarse_dt", "must be ≥ dt"),
])
def test_settings_errors_name_the_key_path(settings, field, text):
    with pytest.raises(InvalidStateError) as err:
        _settings(FeedConfig(settings=settings))
    assert err.value.field == field and text in err.value.reason
    assert _settings(FeedConfig(settings={"t_max": 5.0})).t_max == 5.0
    assert _settings(FeedConfig()) is None


# ---------------------------------------------------------------- 3. --cavity keys
@pytest.mark.parametrize("name, content, text", [
    ("cav.toml", f"[cavity]\nprofle = {PROFILE}\n", "unknown key 'profle' in [cavity] (did you mean 'profile'? "
                                                    "allowed: profile, kind)"),
    ("cav.toml", f"profle = {PROFILE}\n", "unknown key 'profle' (did you mean 'profile'? allowed: profile, kind, "
                                          "cavity)"),
    ("cav.toml", f"[cavty]\nprofile = {PROFILE}\n", "unknown key 'cavty' (did you mean 'cavity'?"),
    ("cav.json", f'{{"profile": {PROFILE}, "mu": 0.3}}', "unknown key 'mu' (allowed: profile, kind, cavity)"),
    ("cav.toml", f"profile = {PROFILE}\n[cavity]\nprofile = {PROFILE}\n", "not both"),
    ("cav.json", f'{{"kind": "wall", "profile": {PROFILE}}}', "kind must be 'cavity', got 'wall'"),
])
def test_an_unknown_cavity_file_key_is_named_with_the_allowed_keys(tmp_path, name, content, text):
    f = tmp_path / name
    f.write_text(content, encoding="utf-8")
    line = one_error(invoke(*THROW, "--cavity", f), "cavity")
    assert text in line and str(f) in line


@pytest.mark.parametrize("name, content", [
    ("cav.toml", f"profile = {PROFILE}\n"),
    ("cav.toml", f"[cavity]\nprofile = {PROFILE}\n"),
    ("cav.json", f'{{"kind": "cavity", "profile": {PROFILE}}}'),  # a fixture record of Outcome JSON
])
def test_the_documented_cavity_file_forms_still_read(tmp_path, name, content):
    f = tmp_path / name
    f.write_text(content, encoding="utf-8")
    assert _cavity_profile(f) == ((0.06, 0.0), (0.06, -0.02), (0.0, -0.02))


def test_a_cavity_file_without_a_profile_is_still_refused(tmp_path):
    f = tmp_path / "cav.json"
    f.write_text("{}", encoding="utf-8")
    with pytest.raises(ConfigError, match="needs profile"):
        _cavity_profile(f)
