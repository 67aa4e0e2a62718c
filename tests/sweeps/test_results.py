"""A sweep's status and a design point's summary are results: ``table()``, ``to_dict()`` (the stored row) and
``.plot()``."""

from __future__ import annotations

import json

import matplotlib

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

from throwmap.experiments.base import Trial, trial_seed  # noqa: E402
from throwmap.sweeps.run import SweepStatus  # noqa: E402
from throwmap.sweeps.targets import PointSummary, summarise_trials  # noqa: E402


def test_sweep_status_is_a_result():
    st = SweepStatus("out", "abcdef0123456789", 10, 3, 4, 6, 2)
    assert st.to_dict() == {"out": "out", "sweep_sha256": "abcdef0123456789", "n_points": 10, "n_chunks": 3,
                            "rows": 4, "missing": 6, "chunks_missing": 2}
    assert st.table() == "sweep abcdef012345 in out: 10 points in 3 parts; rows stored 4, missing 6 (2 parts)"
    assert isinstance(st.plot(), Figure)


def test_point_summary_is_the_points_row():
    trials = [Trial(i, trial_seed(0, i), i != 1, None if i != 1 else "ejected", {"throws": i}).to_json()
              for i in range(3)]
    p = summarise_trials("settle", {}, 0, 3, [(trials[:2], 0.5, "v1", None), (trials[2:], 0.25, "v1", None)])
    assert isinstance(p, PointSummary) and (p.n, p.successes) == (3, 2)
    row = p.to_dict()
    assert list(row) == ["n", "successes", "success_rate", "ci95_low", "ci95_high", "failures", "values", "error",
                         "elapsed_s", "version"]
    assert json.loads(row["failures"]) == {"ejected": 1} and row["elapsed_s"] == 0.75
    assert p.table().startswith("2/3 succeeded = 66.7 %, Wilson 95 % [") and "ejected 1" in p.table()
    assert isinstance(p.plot(), Figure)
    refused = summarise_trials("settle", {}, 0, 3, [([], 0.1, "v1", "config.n: too big")])
    assert refused.to_dict() == {"error": "config.n: too big", "elapsed_s": 0.1, "version": "v1"}
    assert refused.table() == "refused: config.n: too big" and isinstance(refused.plot(), Figure)
