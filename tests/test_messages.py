"""Error messages show values as a user wrote them: never ``np.float64(…)``, ``array(…)`` or ``numpy``.

NumPy scalars are what a user passes after any arithmetic on arrays; each entry point
(Part, Arm, throw, throw_batch, iterate) is fed bad ones and its one-line message checked.
"""

from __future__ import annotations

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import ThrowmapError, shown
from throwmap.io.config import resolve_part

NUMPY_WORDS = ("np.", "numpy", "array(", "float64", "int64")

TRIANGLE = [[0.0, 0.0], [0.1, 0.0], [0.0, 0.05]]


def _part():
    return resolve_part("triangle").part


BAD_CALLS = {
    "Arm h nan": lambda: tm.Arm(h=np.float64("nan")),
    "Arm g negative": lambda: tm.Arm(h=-0.01, g=np.float64(-9.81)),
    "Arm length negative": lambda: tm.Arm(h=-0.01, length=np.float64(-1.0)),
    "Arm length float32": lambda: tm.Arm(h=-0.01, length=np.float32(-1.0)),
    "Arm mu negative": lambda: tm.Arm(h=-0.01, mu=np.float64(-1.0)),
    "Arm back negative": lambda: tm.Arm(h=-0.01, back=np.float64(-0.5)),
    "Part mass negative": lambda: tm.Part.from_vertices(TRIANGLE, mass=np.float64(-1.0)),
    "Part vertex nan": lambda: tm.Part.from_vertices(np.array([[0.0, 0.0], [0.1, np.nan], [0.0, 0.05]]), mass=1.0),
    "Part rho negative": lambda: tm.Part.from_vertices(TRIANGLE, mass=1.0, radius_of_gyration=np.float64(-0.1)),
    "Part com outside": lambda: tm.Part.from_vertices(TRIANGLE, mass=1.0, com=np.array([0.5, 0.5])),
    "Part point mass": lambda: tm.Part.from_vertices(TRIANGLE, mass=1.0, point_masses=[(np.float64(-1), (0.01, 0.01))]),
    "throw side float": lambda: tm.throw(_part(), tm.Arm(h=-0.01), 0.2, np.float64(0.0), 4.0, model="paper"),
    "throw side too big": lambda: tm.throw(_part(), tm.Arm(h=-0.01), 0.2, np.int64(9), 4.0, model="paper"),
    "throw x behind joint": lambda: tm.throw(_part(), tm.Arm(h=-0.01), np.float64(-5.0), 0, 4.0, model="paper"),
    "throw x nan": lambda: tm.throw(_part(), tm.Arm(h=-0.01), np.float64("nan"), 0, 4.0, model="paper"),
    "throw omega negative": lambda: tm.throw(_part(), tm.Arm(h=-0.01), 0.2, 0, np.float64(-4.0), model="paper"),
    "throw_batch side": lambda: tm.throw_batch(_part(), tm.Arm(h=-0.01), np.array([0.2]), np.array([0.5]), 4.0,
                                               model="paper"),
    "throw_batch x": lambda: tm.throw_batch(_part(), tm.Arm(h=-0.01), np.array([0.2, -1.0]), 0, np.float64(4.0),
                                            model="paper"),
    "throw_batch omega": lambda: tm.throw_batch(_part(), tm.Arm(h=-0.01), 0.2, 0, np.array([4.0, -1.0]),
                                                model="paper"),
    "iterate n float": lambda: tm.iterate(_part(), tm.Arm(h=-0.01), (0.2, 0), 4.0, n=np.float64(3), model="paper"),
    "iterate state": lambda: tm.iterate(_part(), tm.Arm(h=-0.01), np.float64(0.2), 4.0, n=2, model="paper"),
}


@pytest.mark.parametrize("case", sorted(BAD_CALLS))
def test_messages_show_no_numpy_reprs(case):
    with pytest.raises(ThrowmapError) as err:
        BAD_CALLS[case]()
    text = str(err.value)
    assert "\n" not in text
    for word in NUMPY_WORDS:
        assert word not in text, text


def test_the_error_class_writes_numpy_values_plainly():
    """The safety net under every message: reasons built with ``{value!r}`` on NumPy values."""
    v = np.float64(1.5)
    err = ThrowmapError("x", f"got {v!r}, {np.int64(3)!r}, {np.True_!r}, {np.str_('a(b)')!r}, "
                             f"{np.array([1.0, 2.0])!r}, {(np.float32(0.5), np.float64('nan'))!r}")
    assert str(err) == "x: got 1.5, 3, True, 'a(b)', [1., 2.], (0.5, nan)"
    assert err.reason == "got 1.5, 3, True, 'a(b)', [1., 2.], (0.5, nan)"


@pytest.mark.parametrize("value, text", [
    (np.float64(2.5), "2.5"), (np.float32(0.1), "0.1"), (np.int64(3), "3"), (np.True_, "True"),
    (np.array([1, 2]), "[1, 2]"), (np.array(3.0), "3.0"), ("abc", "'abc'"), (np.str_("y"), "'y'"),
    ((np.float64(1.0), 2), "(1.0, 2)"), (None, "None"), (float("inf"), "inf"),
])
def test_shown(value, text):
    assert shown(value) == text


def test_shown_is_short():
    assert len(shown(list(range(10_000)))) <= 80


def test_errors_survive_pickling_across_processes():
    """An error raised in a worker comes back to the parent as itself (issue 11: a bad feed setting with
    --workers 2 crashed the pool with a TypeError instead of the one-line error)."""
    import pickle

    from throwmap.errors import ConfigError, InvalidArmError, InvalidPartError, InvalidStateError, ThrowmapError

    for cls in (ThrowmapError, InvalidStateError, InvalidPartError, InvalidArmError, ConfigError):
        err = cls("config.settings.foo", "unknown EngineSettings field")
        back = pickle.loads(pickle.dumps(err))
        assert type(back) is cls and back.field == err.field and back.reason == err.reason
        assert str(back) == str(err)
