"""A lead-weighted part never carries the plain part's name (figures and tables label parts by name)."""

import throwmap as tm
from throwmap.analysis.maps import ThrowMap
from throwmap.system.catalogue import lead_name

LEAD = [(0.03, (0.10, 0.01))]


def test_weighted_triangle_is_named_apart_from_the_plain_one():
    plain = tm.triangle_30_60_90(0.17)
    heavy = tm.triangle_30_60_90(0.17, point_masses=LEAD)
    assert heavy.name != plain.name
    assert heavy.name.startswith(plain.name) and "lead" in heavy.name and "30 g" in heavy.name
    other = tm.triangle_30_60_90(0.17, point_masses=[(0.03, (0.05, 0.01))])
    assert len({plain.name, heavy.name, other.name}) == 3  # different weights, different names
    mirrored = tm.triangle_30_60_90(0.17, mirror=True, point_masses=[(0.03, (-0.10, 0.01))])
    assert "mirror" in mirrored.name and "lead" in mirrored.name


def test_the_labels_figures_use_differ():
    arm = tm.Arm(h=-0.01)
    plain = ThrowMap(tm.triangle_30_60_90(0.17), arm, 4.0, "paper").label
    heavy = ThrowMap(tm.triangle_30_60_90(0.17, point_masses=LEAD), arm, 4.0, "paper").label
    assert plain != heavy and "lead" in heavy


def test_lead_name_without_weights_is_the_name():
    assert lead_name("square", ()) == "square"
    assert lead_name("p", ((0.002, (0.01, -0.005)),)) == "p+lead(2 g at (1, -0.5) cm)"
