"""Compiling ahead (:mod:`throwmap.warmup`): a cold cache is seen as cold, compiling fills it, and the commands say so.

Run against a private, empty Numba cache (``NUMBA_CACHE_DIR`` in a subprocess): the project's own cache is not
touched. The compile itself is the slow part (≈ a minute a model): only the small-angle kernels are compiled here.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

CHECK = """
import json, sys
from throwmap import warmup
before = {m: warmup.cold(m) for m in ("small_angle", "engine", "no-such-model")}
import numpy as np
import throwmap as tm
part, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01)
tm.throw_batch(part, arm, np.linspace(0.1, 0.3, 4), 0, 4.0, "small_angle")
after = warmup.cold("small_angle")
print(json.dumps({"before": before, "after": after}))
"""


def _env(tmp_path):
    return {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}


@pytest.mark.slow
def test_a_cold_kernel_is_cold_until_its_first_call_compiles_it(tmp_path):
    out = subprocess.run([sys.executable, "-c", CHECK], env=_env(tmp_path), capture_output=True, text=True,
                         timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    doc = json.loads(out.stdout.splitlines()[-1])
    # the engines and unknown names claim nothing; the small-angle kernel is cold, then cached
    assert doc["before"] == {"small_angle": True, "engine": False, "no-such-model": False} and doc["after"] is False


def test_the_groups_compile_through_the_public_api_and_cover_every_exact_model():
    from throwmap import warmup

    # every group that waits, waits for a group that exists and does not wait itself; the order keeps every group
    assert set(warmup.AFTER) <= set(warmup.GROUPS) and set(warmup.AFTER.values()) <= set(warmup.GROUPS) - set(warmup.AFTER)
    order = warmup._order()
    assert sorted(order) == sorted(warmup.GROUPS)
    assert all(order.index(warmup.AFTER[g]) < order.index(g) for g in warmup.AFTER)
    assert set(warmup._KERNELS) == {"paper", "small_angle", "small_angle2", "rigid_body"}


def test_the_throw_command_says_when_it_compiles(monkeypatch):
    from typer.testing import CliRunner

    import throwmap.warmup as warmup
    from throwmap.cli.app import app

    for cold, said in ((True, True), (False, False)):
        monkeypatch.setattr(warmup, "cold", lambda model, c=cold: c)
        res = CliRunner().invoke(app, ["throw", "--part", "triangle", "--h", "-0.01", "--omega", "4", "--x", "0.2",
                                       "--side", "0", "--model", "paper", "--json"])
        assert res.exit_code == 0, res.output
        assert ("compiling the paper kernels, once" in res.stderr) is said
        assert json.loads(res.stdout)["side"] == 0
