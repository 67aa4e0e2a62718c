"""The recoil-feeder search (throwmap.design.feed_search): candidates inside their bounds, seeded,
windows as their passages say."""

import numpy as np
import pytest

from throwmap.design.examples import plexiglas_triangle
from throwmap.design.feed_search import FeederSpace, search_feeders
from throwmap.design.plate import inset_polygon
from throwmap.errors import InvalidStateError


@pytest.mark.slow
def test_candidates_are_in_bounds_seeded_and_consistent():
    plate = plexiglas_triangle()
    kw = dict(n=2, seed=4, chains=200, throws=20, step=0.05, workers=1,
              space=FeederSpace(omega_range=(4.0, 5.0), h_range=(-0.03, -0.01)))
    a = list(search_feeders(plate, **kw))
    b = list(search_feeders(plate, **kw))
    inset = inset_polygon(plate.vertices, 0.008)
    for c, d in zip(a, b):
        assert c.weight_at == d.weight_at and c.omega == d.omega and c.h == d.h and c.weight_mass == d.weight_mass
        assert inset.contains(c.weight_at)
        assert 4.0 <= c.omega <= 5.0 and -0.03 <= c.h <= -0.01 and c.weight_mass in (0.03, 0.05, 0.08)
        assert np.allclose(c.part.mass, plate.mass + c.weight_mass)
        for k, p in c.passages.items():
            win = p.window(0.99)
            assert (c.windows[k] is None) == (not win)
        assert c.to_dict()["best_side"] == c.best


def test_bad_ranges_are_refused():
    with pytest.raises(InvalidStateError, match="n"):
        next(search_feeders(plexiglas_triangle(), n=0))
    with pytest.raises(InvalidStateError, match="omega_range"):
        next(search_feeders(plexiglas_triangle(), space=FeederSpace(omega_range=(5.0, 4.0))))
