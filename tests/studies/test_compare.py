"""Model comparison (throwmap.studies.compare): its result round-trips and its table reads back."""

import json

import throwmap as tm
from throwmap.studies.compare import ModelComparison, compare_models


def test_model_comparison_round_trip_and_table():
    comp = compare_models(tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01), omegas=(1.0, 4.0), n_x=30)
    d = json.loads(json.dumps(comp.to_dict()).replace("NaN", "null"))
    back = ModelComparison.from_dict(d)
    assert back.models == comp.models and back.reference == "paper" and len(back.rows) == len(comp.rows) == 4
    assert back.table() == comp.table()
    assert {r["model"] for r in comp.rows} == {"small_angle", "small_angle2"}


def test_compare_states_its_range_and_settings_and_honours_x_range():
    """The table says which starts, ω, μ, g and models it covers; x_min/x_max bound the grid it throws."""
    part = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=-0.01, mu=1.5)
    comp = compare_models(part, arm, omegas=(2.0,), n_x=5, x_min=0.1, x_max=0.2, models=("small_angle",))
    text = comp.table()
    assert "x ∈ (max(0.1 m, the side's x_min), 0.2 m]" in text
    assert "ω ∈ {2} rad/s" in text and "μ = 1.5" in text and "small_angle against 'paper'" in text
    assert comp.settings["x_max"] == 0.2 and comp.settings["n_x"] == 5
    # every stable side thrown from 5 starts inside (0.1, 0.2]: the switch x's lie there too
    for r in comp.switches:
        for m in ("paper", "small_angle"):
            assert r[m] != r[m] or 0.1 < r[m] <= 0.2
    d = json.loads(json.dumps(comp.to_dict()).replace("NaN", "null"))
    assert ModelComparison.from_dict(d).table() == text


def test_compare_refuses_an_empty_range():
    import pytest

    from throwmap.errors import ThrowmapError

    with pytest.raises(ThrowmapError, match="x_max"):
        compare_models(tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01), omegas=(2.0,), n_x=5, x_max=0.0)
