"""The design sheet's drifts: removing the last weight undoes adding it, and each drifted config changes only the
quantity it names."""

from __future__ import annotations

import numpy as np
import pytest

import throwmap as tm
from throwmap.experiments.base import read_config
from throwmap.experiments.feed import Feed
from throwmap.feeder import Weight, with_weight
from throwmap.feeder.family import without_last_weight
from throwmap.feeder.sheet import drifted
from throwmap.io.config import resolve_part, save_part_toml


def test_removing_the_last_weight_undoes_adding_it():
    tri = tm.triangle_30_60_90(0.17)
    for m, at in ((0.05, (0.03, 0.04)), (0.2, (0.01, 0.07)), (0.001, (0.1, 0.01))):
        back = without_last_weight(with_weight(tri, Weight(m, at)))
        assert back.mass == pytest.approx(tri.mass, rel=1e-12) and back.com == pytest.approx(tri.com, abs=1e-12)
        assert back.radius_of_gyration == pytest.approx(tri.radius_of_gyration, rel=1e-9)


def test_each_drift_changes_only_its_quantity(tmp_path):
    cfg = read_config(Feed(), "examples/feed_recoil.toml")
    w = drifted(cfg, "omega", -0.06, tmp_path / "w")
    assert w.omega == pytest.approx(cfg.omega * 0.94) and w.model_copy(update={"omega": cfg.omega}) == cfg
    m = drifted(cfg, "mu", 1.5, tmp_path / "m")
    assert m.arm.mu == pytest.approx(1.5 * cfg.arm.mu) and m.arm.h == cfg.arm.h and m.noise == cfg.noise
    j = drifted(cfg, "jitter", 0.08, tmp_path / "j")
    assert j.noise.omega_rel == 0.08 and j.noise.mu_rel == cfg.noise.mu_rel
    x = drifted(cfg, "weight_y", 0.003, tmp_path / "y")
    before, after = resolve_part(cfg.part).part, resolve_part(x.part).part
    (m0, p0), (m1, p1) = before.point_masses[-1], after.point_masses[-1]
    assert m1 == pytest.approx(m0) and np.subtract(p1, p0) == pytest.approx((0.0, 0.003), abs=1e-12)
    assert after.vertices == before.vertices and after.mass == pytest.approx(before.mass)
    assert drifted(cfg, "weight_x", 1.0, tmp_path / "far") is None  # off the plate: not a drift


def test_no_margin_step_starts_after_the_budget(tmp_path, monkeypatch):
    import throwmap.experiments.runner as runner
    from throwmap.feeder.sheet import MARGIN_STEPS, _margin_text, margins

    monkeypatch.setattr(runner, "run_experiment", lambda *a, **k: pytest.fail("a margin step ran"))
    cfg = read_config(Feed(), "examples/feed_recoil.toml")
    out = margins(cfg, tmp_path, budget_s=-1.0)
    assert set(out) == set(MARGIN_STEPS) and all(r["not measured"] == "budget" for rows in out.values() for r in rows)
    assert "not measured" in _margin_text("omega", out["omega"])[1]


def test_a_weight_step_that_fails_is_followed_by_half_of_it(tmp_path, monkeypatch):
    """The weight's place: 3 mm failing is followed by 1.5 mm (holds or not); other quantities stop at a failure."""
    from types import SimpleNamespace

    import throwmap.experiments.runner as runner
    from throwmap.experiments.stats import wilson_interval
    from throwmap.feeder import sheet

    cfg = read_config(Feed(), "examples/feed_recoil.toml")
    base = resolve_part(cfg.part).part.point_masses[-1][1]
    holds = {"weight_x": 0.002, "weight_y": 0.001}  # the drift each quantity takes before failing, m
    ran = []

    def fake(name, c, *, n, **kw):
        part = resolve_part(c.part).part
        at = part.point_masses[-1][1]
        what = "weight_x" if abs(at[0] - base[0]) > 1e-12 else "weight_y"
        drift = abs(at[0] - base[0]) + abs(at[1] - base[1])
        if abs(c.arm.mu - cfg.arm.mu) > 1e-12:  # μ: every step holds
            what, drift = "mu", 0.0
        elif drift < 1e-12:  # ω or jitter: every step fails
            what, drift = "other", 1.0
        ran.append((what, round(drift, 6)))
        k = n if drift <= holds.get(what, 0.0) + 1e-12 else n // 2
        return SimpleNamespace(n=n, successes=k, success_rate=k / n, ci95=wilson_interval(k, n))

    monkeypatch.setattr(runner, "run_experiment", fake)
    out = sheet.margins(cfg, tmp_path, trials=30)
    assert [r for r in ran if r[0] == "other"] == [("other", 1.0)] * 3  # ω ±: one failing step each; jitter
    assert sorted(r for r in ran if r[0] == "weight_x") == [("weight_x", 0.0015)] * 2 + [("weight_x", 0.003)] * 2
    assert [(r["passed"], r["failed"]) for r in out["weight_x"]] == [(-0.0015, -0.003), (0.0015, 0.003)]
    assert [(r["passed"], r["failed"]) for r in out["weight_y"]] == [(None, -0.0015), (None, 0.0015)]
    assert [x["step"] for x in out["weight_x"][1]["runs"]] == [0.0015, 0.003]  # sorted by size
    assert [x["step"] for x in out["mu"][0]["runs"]] == [0.8, 0.6]  # μ's steps keep their order (× 0.8 first)
    assert [x["step"] for x in out["mu"][1]["runs"]] == [1.25, 1.5]
    text = sheet._margin_text("weight_x", out["weight_x"])[1]
    assert "holds to -1.5 mm, not to -3 mm" in text, text


def test_a_margin_step_fails_only_when_clearly_below_the_goal(tmp_path, monkeypatch):
    """27/30 (Wilson [74, 96.5] %) cannot tell the feeder from its goal: the step holds; 20/30 (upper end 80 %) fails.
    The same test as the search's ω and weight checks, so the sheet and the search agree on the same trials."""
    from types import SimpleNamespace

    import throwmap.experiments.runner as runner
    from throwmap.experiments.stats import wilson_interval
    from throwmap.feeder import sheet

    cfg = read_config(Feed(), "examples/feed_recoil.toml")

    def fake(name, c, *, n, **kw):
        k = 27 if c.omega < cfg.omega else 20  # ω down: 27/30; anything else: 20/30
        return SimpleNamespace(n=n, successes=k, success_rate=k / n, ci95=wilson_interval(k, n))

    monkeypatch.setattr(runner, "run_experiment", fake)
    monkeypatch.setattr(sheet, "MARGIN_STEPS", {"omega": ((-0.03, -0.06), (0.03,))})
    out = sheet.margins(cfg, tmp_path, trials=30)
    assert [(r["passed"], r["failed"]) for r in out["omega"]] == [(-0.06, None), (None, 0.03)]
    assert "falls clearly below the goal at +3 %" in sheet._margin_text("omega", out["omega"])[1]


def test_a_feeder_is_refused_only_when_a_three_percent_drift_is_clearly_below_the_goal():
    from throwmap.experiments.stats import wilson_interval
    from throwmap.feeder.sheet import margin_refusal

    def row(step, s, n=30):
        return {"passed": None, "failed": step, "runs": [{"step": step, "n": n, "successes": s,
                                                          "ci95": list(wilson_interval(s, n))}]}

    assert margin_refusal({"omega": [row(-0.03, 27), row(0.03, 30)]}, 0.95) == ""  # 90 %: not clearly below 95 %
    why = margin_refusal({"omega": [row(-0.03, 30), row(0.03, 20)]}, 0.95)
    assert why.startswith("verified, but within 3 % of ω of losing its feed: at ω +3 % 20/30 fed")
    assert margin_refusal({"omega": [row(-0.06, 0)]}, 0.95) == "" and margin_refusal({}, 0.95) == ""


def test_the_sheet_says_when_a_design_sits_at_an_edge():
    from types import SimpleNamespace

    from throwmap.feeder.sheet import _edge_rows, _tail_note

    grid = {"omegas_rad_s": [3.5, 4.0, 4.5], "hs_m": [-0.03, -0.02, 0.0]}
    rows = dict(_edge_rows(SimpleNamespace(omega=3.5, h=-0.02), grid))
    assert list(rows) == ["ω at the grid's edge"] and "3.5 to 4.5 rad/s" in rows["ω at the grid's edge"]
    rows = dict(_edge_rows(SimpleNamespace(omega=4.2, h=0.0), grid))  # a shifted ω inside the grid: no row for ω
    assert list(rows) == ["h at the grid's edge"] and "-3 to 0 cm" in rows["h at the grid's edge"]
    assert _edge_rows(SimpleNamespace(omega=4.0, h=-0.02), grid) == []
    assert "85 of the 100" in _tail_note({"max": 85}, 100) and _tail_note({"max": 80}, 100) == ""


def test_margin_steps_go_breadth_first(tmp_path, monkeypatch):
    """Every quantity's first step in each direction runs before any second step (a short budget then measures the
    smallest drift of each, not ω's largest): here every step holds, and the runs come in rounds."""
    from types import SimpleNamespace

    import throwmap.experiments.runner as runner
    from throwmap.experiments.stats import wilson_interval
    from throwmap.feeder import sheet

    cfg = read_config(Feed(), "examples/feed_recoil.toml")
    ran = []

    def fake(name, c, *, n, out, **kw):
        ran.append(out.parent.name)  # "<what>_<step>"
        return SimpleNamespace(n=n, successes=n, success_rate=1.0, ci95=wilson_interval(n, n))

    monkeypatch.setattr(runner, "run_experiment", fake)
    out = sheet.margins(cfg, tmp_path, trials=30)
    firsts = [f"{what}_{d[0]:+g}" for what, dirs in sheet.MARGIN_STEPS.items() for d in dirs]
    assert ran[:len(firsts)] == firsts
    assert ran[len(firsts)] == f"omega_{sheet.MARGIN_STEPS['omega'][0][1]:+g}"  # then the second round
    assert sorted(ran) == sorted(f"{w}_{x:+g}" for w, dirs in sheet.MARGIN_STEPS.items() for d in dirs for x in d)
    assert all(r["failed"] is None and r["passed"] == d[-1] for w, dirs in sheet.MARGIN_STEPS.items()
               for r, d in zip(out[w], dirs))


def test_a_part_without_a_weight_has_no_weight_margins(tmp_path, monkeypatch):
    from types import SimpleNamespace

    import throwmap.experiments.runner as runner
    from throwmap.experiments.stats import wilson_interval
    from throwmap.feeder import sheet

    cfg = read_config(Feed(), "examples/feed_recoil.toml")
    bare = save_part_toml(tm.triangle_30_60_90(0.17), None, tmp_path / "bare.toml")  # no lead weight on it
    cfg = cfg.model_copy(update={"part": str(bare)})
    monkeypatch.setattr(runner, "run_experiment", lambda name, c, *, n, **kw: SimpleNamespace(
        n=n, successes=n, success_rate=1.0, ci95=wilson_interval(n, n)))
    out = sheet.margins(cfg, tmp_path / "m", trials=30)
    assert set(out) == {"omega", "mu", "jitter"}


@pytest.mark.parametrize("seed", [3, 11, 27, 40])
def test_the_drawings_labels_keep_clear_of_each_other_and_the_marks(seed):
    """On random plates with the heaviest lead weight allowed near the fed side (the case where the weight, the CM
    and the side's number crowd together): in both panels the "lead" and "CM" labels overlap neither each other, nor
    any side number or text, nor the weight's mark; the part panel's axis labels stay clear of the arm panel; both
    panels give the weight's mass alike (one decimal)."""
    import matplotlib.pyplot as plt
    from types import SimpleNamespace

    from throwmap.design.cavity import Pocket, design_cavity
    from throwmap.feeder import random_plate
    from throwmap.feeder.family import weight_variants
    from throwmap.feeder.sheet import _gap, _texts, drawing

    part = random_plate(np.random.default_rng(seed))
    side = part.stable_sides[0]
    variants = [v for v in weight_variants(part, side, max_kg=1.7 * part.mass) if side in v.part.stable_sides]
    v = max(variants, key=lambda v: v.weight.mass)
    L = 0.45
    design = design_cavity(v.part, tm.Arm(h=-0.02, mu=1.0), 4.0, side, verify=False,
                           pocket=Pocket(depth=0.01, wall_mu=0.2, lined=True, length=L, window=False))
    res = SimpleNamespace(feeder=SimpleNamespace(variant=v, side=side, X=L))
    fig = drawing(res, design)
    try:
        ax, bx = fig.axes[:2]
        for panel in (ax, bx):
            texts = panel.texts
            ours = [t for t in texts if t.get_text() == "CM" or t.get_text().startswith("lead")]
            assert len(ours) == 2, [t.get_text() for t in texts]
            boxes = _texts(panel)
            for t in ours:
                mine = tuple(t.get_window_extent().extents)
                others = [b for u, b in zip(texts, boxes) if u is not t]
                assert all(_gap(mine, b) >= 0 for b in others), (t.get_text(), mine, others)
            mark = [ln for ln in panel.lines if ln.get_marker() == "o" and ln.get_markersize() > 5]
            assert len(mark) == 1
            x, y = panel.transData.transform(np.column_stack(mark[0].get_data())[0])
            r = mark[0].get_markersize() / 2 * fig.dpi / 72
            assert all(_gap(tuple(t.get_window_extent().extents), (x - r, y - r, x + r, y + r)) >= 0 for t in ours)
        r = fig.canvas.get_renderer()
        assert bx.yaxis.get_tightbbox(r).x0 > ax.get_window_extent().x1  # no tick label over the arm panel
        grams = f"{1000 * v.weight.mass:.1f} g"
        assert any(t.get_text() == f"lead {grams}" for t in ax.texts) and grams in bx.get_xlabel()
    finally:
        plt.close(fig)


def test_a_margin_step_cut_short_by_the_budget_shows_how_far_it_got():
    from throwmap.feeder.sheet import _margin_text

    cut = {"step": 0.003, "n": 26, "successes": 26, "planned": 30}
    name, text = _margin_text("weight_y", [{"passed": None, "failed": None, "runs": [], "not measured": "budget",
                                            "cut_short": cut}])
    assert name == "weight y" and text == ("not measured (the search's time budget was spent; +3 mm cut short by the "
                                           "budget at 26/26 of 30 trials, no verdict)")
    row = {"passed": 0.0015, "failed": None, "runs": [{"step": 0.0015, "n": 30, "successes": 30}], "cut_short": cut}
    assert _margin_text("weight_y", [row])[1].endswith("(+1.5 mm: 30/30; +3 mm cut short by the budget at 26/26 of "
                                                       "30 trials, no verdict)")
