"""The one throw-map plotter (paper Fig. 2): it draws exactly the samples it is given, in both looks."""

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

import throwmap as tm  # noqa: E402
from throwmap.analysis import FunctionMap  # noqa: E402
from throwmap.errors import InvalidStateError  # noqa: E402
from throwmap.throws.samples import MapSamples, sample_map, throw_map_samples  # noqa: E402
from throwmap.viz.throw_map import plot_map  # noqa: E402

OMEGA = 4.0


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def samples(triangle, arm):
    return throw_map_samples(triangle, arm, OMEGA, x_max=0.6, n=120)


@pytest.fixture(scope="module")
def escaping():
    """Side 0 doubles x and leaves the arm beyond 0.3 m; side 1 flips to side 0."""
    f = FunctionMap(lambda x, s: (np.where(s == 0, 2 * x, x), np.zeros_like(s), np.where((s == 0) & (x > 0.3), 2, 0)),
                    {0: (0.0, 0.5), 1: (0.1, 0.5)}, name="doubling")
    return sample_map(f, 50)


def _branches(ax):
    return {c.get_gid(): c for c in ax.collections if (c.get_gid() or "").startswith("branch-")}


@pytest.mark.parametrize("compact", [False, True])
def test_draws_exactly_the_samples(samples, compact):
    """Every resting image is one dot at (x, T(x)) in cm, in the panel of its start side and its landing colour."""
    fig = plot_map(samples, compact=compact)
    assert len(fig.axes) >= len(samples.sides)
    for ax, s in zip(fig.axes, samples.sides):
        sl = samples.panel(s)
        ok = samples.ok[sl]
        got = _branches(ax)
        tumble = samples.kinds()[sl] == "tumble"  # drawn hollow, in their own collection
        assert set(got) == {f"branch-{d}" for d in np.unique(samples.side_next[sl][ok & ~tumble])}
        tumbles = {c.get_gid(): c for c in ax.collections if str(c.get_gid()).startswith("tumble-")}
        assert set(tumbles) == {f"tumble-{d}" for d in np.unique(samples.side_next[sl][tumble])}
        for gid, coll in [*got.items(), *tumbles.items()]:
            d = int(gid.split("-")[1])
            m = ok & (samples.side_next[sl] == d) & (tumble if gid.startswith("tumble") else ~tumble)
            np.testing.assert_allclose(coll.get_offsets(), 100 * np.column_stack([samples.x[sl][m],
                                                                                 samples.x_next[sl][m]]))
        assert ax.get_title() == f"side {s}" and ax.get_xlabel() == f"x on side {s} (cm)"


def test_compact_look_is_fig2(samples):
    fig = plot_map(samples, compact=True)
    assert type(fig.get_layout_engine()).__name__ != "ConstrainedLayoutEngine"
    assert tuple(fig.get_size_inches()) == pytest.approx((4.2 * 3, 4))
    assert fig._suptitle.get_text() == ("throw map T(x): triangle_30_60_90(hypotenuse=0.17), h = -0.01 m, "
                                        "ω = 4 rad/s, model 'rigid_body', sampled for x ≤ 60 cm")
    for ax, s in zip(fig.axes, samples.sides):
        top = max(60.0, 100 * float(samples.x_next[samples.ok].max()))
        assert ax.get_xlim() == pytest.approx((0.0, top)) == ax.get_ylim()  # the sampled domain and every image
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert f"→ side {s} (jog)" in labels and "T(x) = x" in labels
        assert any(t.endswith("(flip)") for t in labels)
    assert not fig.legends


def test_full_look_spans_every_image(samples):
    fig = plot_map(samples, title="my map")
    assert type(fig.get_layout_engine()).__name__ == "ConstrainedLayoutEngine"
    assert fig._suptitle.get_text() == "my map"
    hi = 100 * samples.x_next[samples.ok].max()
    assert hi > 60 and fig.axes[0].get_xlim()[1] == pytest.approx(hi)
    assert len(fig.legends) == 1 and all(ax.get_legend() is None for ax in fig.axes)


@pytest.mark.parametrize("compact", [False, True])
def test_escapes_on_the_axis(escaping, compact):
    fig = plot_map(escaping, compact=compact, unit="m")
    esc = [c for c in fig.axes[0].collections if c.get_gid() == "escapes"]
    assert len(esc) == 1 and len(esc[0].get_offsets()) == 20  # x in (0.3, 0.5] on side 0, 50 steps of 1 cm
    np.testing.assert_allclose(esc[0].get_offsets()[:, 1], fig.axes[0].get_ylim()[0])
    assert not [c for c in fig.axes[1].collections if c.get_gid() == "escapes"]
    assert fig.axes[1].get_xlabel() == "x on side 1 (m)"


def test_plot_method_and_given_axes(escaping):
    fig, axes = plt.subplots(1, 3)
    assert escaping.plot(axes=axes[1:]) is fig
    assert not axes[0].has_data() and axes[1].has_data() and axes[2].has_data()
    with pytest.raises(InvalidStateError, match="axes"):
        escaping.plot(axes=axes[:1])
    with pytest.raises(InvalidStateError, match="unit"):
        escaping.plot(unit="inch")


def test_plot_throw_map_is_the_compact_plot_of_its_samples(triangle, arm):
    fig = tm.plot_throw_map(triangle, arm, OMEGA, sides=[0, 2], n=60, x_max=0.6)
    assert isinstance(fig, Figure) and len(fig.axes) == 2
    ref = throw_map_samples(triangle, arm, OMEGA, sides=[0, 2], n=60, x_max=0.6)
    for ax, s in zip(fig.axes, ref.sides):
        sl = ref.panel(s)
        m = ref.ok[sl]
        got = np.concatenate([c.get_offsets() for c in _branches(ax).values()])
        assert len(got) == int(m.sum())
        assert ax.get_legend() is not None and ax.get_xlim() == pytest.approx((0.0, 60.0))


def test_samples_from_json_draw_the_same(escaping):
    back = MapSamples.from_dict(escaping.to_dict())
    a, b = plot_map(escaping).axes[0], plot_map(back).axes[0]
    for ca, cb in zip(a.collections, b.collections):
        np.testing.assert_array_equal(ca.get_offsets(), cb.get_offsets())
