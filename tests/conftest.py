"""Shared fixtures: the canonical parts and arms, in one place."""

import os

os.environ.setdefault("MPLBACKEND", "Agg")

import pytest  # noqa: E402
from hypothesis import settings  # noqa: E402

import throwmap as tm  # noqa: E402

# CI runs are reproducible (fixed Hypothesis examples); local runs keep exploring.
settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")


def pytest_configure(config):
    """With pytest-xdist workers on the whole suite (``make test``, CI: no test paths named), compile the Numba
    kernels once, in parallel, before the workers start (``tests/warmup.py``): on a fresh clone each worker would
    otherwise compile them all itself. A run of chosen files leaves it to the tests it runs;
    ``THROWMAP_NO_WARMUP=1`` leaves it out, ``THROWMAP_WARMUP=1`` asks for it anyway."""
    workers = getattr(config.option, "numprocesses", None)
    if hasattr(config, "workerinput") or not workers or os.environ.get("THROWMAP_NO_WARMUP"):
        return
    named = [a for a in config.invocation_params.args if not str(a).startswith("-") and os.path.exists(str(a))]
    if named and not os.environ.get("THROWMAP_WARMUP"):
        return
    import sys

    sys.path.insert(0, os.path.dirname(__file__))
    import warmup

    n = (os.cpu_count() or 1) if workers in ("auto", "logical") else int(workers)
    seconds = warmup.warm(workers=n)
    config._throwmap_warmup_s = seconds


def pytest_terminal_summary(terminalreporter, config):
    seconds = getattr(config, "_throwmap_warmup_s", None)
    if seconds is not None:
        terminalreporter.write_line(f"kernels compiled or loaded before the workers started: {seconds:.1f} s")


@pytest.fixture(scope="session")
def triangle():
    """The paper's part: uniform 30-60-90 triangle, hypotenuse 0.17 m."""
    return tm.triangle_30_60_90(0.17)


@pytest.fixture(scope="session")
def offset_triangle():
    """The same triangle with a lead weight near its 30° corner (offset CM, Sec. V-C)."""
    return tm.triangle_30_60_90(0.17, point_masses=[(0.03, (0.10, 0.01))])


@pytest.fixture(scope="session")
def arm():
    """The paper's arm geometry, h = −1 cm, unbounded."""
    return tm.Arm(h=-0.01)


CANONICAL = {
    "triangle": lambda: tm.triangle_30_60_90(0.17),
    "offset_triangle": lambda: tm.triangle_30_60_90(0.17, point_masses=[(0.03, (0.10, 0.01))]),
    "pentagon": lambda: tm.regular_polygon(5, 0.05),
    "rectangle": lambda: tm.rectangle(0.08, 0.04),
}


@pytest.fixture(scope="session", params=sorted(CANONICAL))
def canonical_part(request):
    return CANONICAL[request.param]()
