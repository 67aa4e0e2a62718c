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
